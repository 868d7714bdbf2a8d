#!/bin/sh
# run.sh — runs every unit test binary, fuzz regression replay and
# end-to-end script against one or more build trees (e.g. the plain build and
# its ASan+UBSan twin), counts the "ok - " and "not ok - " lines they print,
# and ends with one "N passed, N failed" for everything.
# Usage: tests/run.sh BUILD_DIR... [PATTERN]
# A test also fails if a sanitizer (ASan, UBSan, LSan) or valgrind (through
# the wrappers of tests/memcheck.sh) wrote a report while it ran: reports go
# to files in $PM_REPORT_DIR, which is checked after each test.
top=$(cd "$(dirname "$0")/.." && pwd)
dirs= pat=
for a in "$@"; do
	if [ -d "$top/$a/bin" ] || [ -d "$a/bin" ]; then
		d=$(cd "$top" && cd "$a" && pwd) || exit 2
		dirs="$dirs $d"
	else
		pat=$a
	fi
done
[ -n "$dirs" ] || dirs=$(cd "$top" && cd build && pwd) || exit 2
export PM_TOP="$top"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export PM_REPORT_DIR="$tmp/reports"
mkdir "$PM_REPORT_DIR"
# Sanitizer settings for the instrumented tree (ignored by a plain build):
# reports to files, so one inside a pipeline is not lost; a distinct exit
# status. detect_leaks is LeakSanitizer's default on x86-64, made explicit.
export ASAN_OPTIONS="log_path=$PM_REPORT_DIR/asan:exitcode=99:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="log_path=$PM_REPORT_DIR/ubsan:print_stacktrace=1:halt_on_error=1:exitcode=99${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
export LSAN_OPTIONS="suppressions=$top/tests/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
ndirs=$(echo $dirs | wc -w)
pass=0 fail=0
for B in $dirs; do
	export PM_BIN="$B/bin"
	tag=
	[ "$ndirs" -gt 1 ] && tag=" [$(basename "$B")]"
	# PM_SUITE=DIR runs DIR/*.sh alone (make check-cluster: tests/cluster).
	if [ -n "${PM_SUITE:-}" ]; then set -- "$top/$PM_SUITE"/*.sh
	else set -- "$B"/tests/test_* "$B"/fuzz/replay-* "$top"/tests/e2e/*.sh; fi
	for t in "$@"; do
		case "$t" in *.o) continue ;; esac
		[ -e "$t" ] || continue
		[ -n "$pat" ] && case "$t" in *"$pat"*) ;; *) continue ;; esac
		name=$(basename "$t")$tag
		start=$(date +%s)
		# Each test in a directory of its own: no test sees another's files.
		w=$(mktemp -d "$tmp/work.XXXXXX")
		case "$t" in
		*.sh) (cd "$w" && sh "$t") >"$tmp/out" 2>"$tmp/err" ;;
		*/replay-*)
			# every seed and every past crash of this target
			tgt=${t##*/replay-}
			set --
			for d in "$top/tests/fuzz/corpus/$tgt" "$top/tests/fuzz/regress/$tgt"; do
				[ -d "$d" ] && set -- "$@" "$d"
			done
			(cd "$w" && "$t" "$@") >"$tmp/out" 2>"$tmp/err" ;;
		*) (cd "$w" && "$t") >"$tmp/out" 2>"$tmp/err" ;;
		esac
		rc=$?
		p=$(grep -c '^ok - ' "$tmp/out")
		f=$(grep -c '^not ok - ' "$tmp/out")
		if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
			echo "not ok - $name: exited $rc without a failed check" >>"$tmp/out"
			f=1
		fi
		for r in "$PM_REPORT_DIR"/*; do
			[ -s "$r" ] || continue
			echo "not ok - $name: report in $(basename "$r"): $(grep -m1 -E 'ERROR|runtime error|definitely lost|Invalid|uninitialised|SUMMARY' "$r" | cut -c1-200)" >>"$tmp/out"
			sed -n '1,12p' "$r" | sed 's/^/  also /' >>"$tmp/out"
			f=$((f + 1))
		done
		rm -f "$PM_REPORT_DIR"/*
		pass=$((pass + p)); fail=$((fail + f))
		printf '%-36s %3d passed %3d failed  %3ds\n' "$name" "$p" "$f" $(( $(date +%s) - start ))
		if [ "$f" -ne 0 ]; then
			grep '^not ok - \|^  also' "$tmp/out" | sed 's/^/    /'
			tail -n 5 "$tmp/err" | sed 's/^/    stderr: /'
		fi
	done
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
