#!/bin/sh
# run1.sh — one test of tests/run.sh's list: item N of $PM_LIST ("TREE<TAB>
# PATH<TAB>NAME" lines), run in a directory of its own with a sanitizer
# report directory of its own, so that tests of different trees can run at
# the same time. Prints the test's line (and what failed) in one write, and
# leaves "PASSED FAILED" in $PM_RESULTS/N.
# Usage: tests/run1.sh N
n=$1
line=$(sed -n "${n}p" "$PM_LIST")
tab=$(printf '\t')
B=${line%%"$tab"*}; rest=${line#*"$tab"}
t=${rest%%"$tab"*}; name=${rest#*"$tab"}
export PM_BIN="$B/bin"
w=$(mktemp -d "$PM_WORK/work.XXXXXX")
export PM_REPORT_DIR="$w.reports"
mkdir "$PM_REPORT_DIR"
# Reports to files, so one inside a pipeline is not lost; a distinct exit
# status. detect_leaks is LeakSanitizer's default on x86-64, made explicit.
# intercept_tls_get_addr=0: with OpenImageIO's module loaded (dlopen), the
# leak check at exit read a bad dynamic-TLS range of Debian 12's glibc and
# crashed ("Tracer caught signal 11", pm-import on a textured Mitsuba
# scene, every run); pm keeps no heap pointer in dynamic TLS.
export ASAN_OPTIONS="log_path=$PM_REPORT_DIR/asan:exitcode=99:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:intercept_tls_get_addr=0${PM_ASAN_USER:+:$PM_ASAN_USER}"
export UBSAN_OPTIONS="log_path=$PM_REPORT_DIR/ubsan:print_stacktrace=1:halt_on_error=1:exitcode=99${PM_UBSAN_USER:+:$PM_UBSAN_USER}"
out=$w.out err=$w.err blk=$w.block
start=$(date +%s)
case "$t" in
*.sh) (cd "$w" && sh "$t") >"$out" 2>"$err" ;;
*/replay-*)
	# every seed and every past crash of this target
	tgt=${t##*/replay-}
	set --
	for d in "$PM_TOP/tests/fuzz/corpus/$tgt" "$PM_TOP/tests/fuzz/regress/$tgt"; do
		[ -d "$d" ] && set -- "$@" "$d"
	done
	(cd "$w" && "$t" "$@") >"$out" 2>"$err" ;;
*) (cd "$w" && "$t") >"$out" 2>"$err" ;;
esac
rc=$?
p=$(grep -c '^ok - ' "$out")
f=$(grep -c '^not ok - ' "$out")
if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
	echo "not ok - $name: exited $rc without a failed check" >>"$out"
	f=1
fi
for r in "$PM_REPORT_DIR"/*; do
	[ -s "$r" ] || continue
	echo "not ok - $name: report in $(basename "$r"): $(grep -m1 -E 'ERROR|runtime error|definitely lost|Invalid|uninitialised|SUMMARY' "$r" | cut -c1-200)" >>"$out"
	sed -n '1,12p' "$r" | sed 's/^/  also /' >>"$out"
	f=$((f + 1))
done
echo "$p $f" >"$PM_RESULTS/$n"
{
	printf '%-36s %3d passed %3d failed  %3ds\n' "$name" "$p" "$f" $(( $(date +%s) - start ))
	if [ "$f" -ne 0 ]; then
		grep '^not ok - \|^  also' "$out" | sed 's/^/    /'
		tail -n 5 "$err" | sed 's/^/    stderr: /'
	fi
} >"$blk"
cat "$blk"
# Only what a failure needs to be read is kept until the run ends.
[ "$f" -ne 0 ] || rm -rf "$w" "$PM_REPORT_DIR" "$out" "$err" "$blk"
