#!/bin/sh
# run.sh — runs every unit test binary, fuzz regression replay and
# end-to-end script against one or more build trees (e.g. the plain build and
# its ASan+UBSan twin), counts the "ok - " and "not ok - " lines they print,
# and ends with one "N passed, N failed" for everything.
# Usage: tests/run.sh BUILD_DIR... [PATTERN]
# A test also fails if a sanitizer (ASan, UBSan, LSan) or valgrind (through
# the wrappers of tests/memcheck.sh) wrote a report while it ran: reports go
# to files in $PM_REPORT_DIR, which is checked after each test (run1.sh).
# Tests run PM_TEST_JOBS at a time (default: one per CPU), each in its own
# directory; lines come in the order tests end. The end-to-end scripts go
# first, the slowest tree's first, so that the long ones do not finish last
# alone. PM_TEST_JOBS=1 runs one at a time in list order.
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
export PM_WORK="$tmp" PM_LIST="$tmp/list" PM_RESULTS="$tmp/results"
export PM_ASAN_USER="${ASAN_OPTIONS:-}" PM_UBSAN_USER="${UBSAN_OPTIONS:-}"
export LSAN_OPTIONS="suppressions=$top/tests/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
mkdir "$PM_RESULTS"
jobs=${PM_TEST_JOBS:-$(nproc 2>/dev/null || echo 1)}
# PM_SUITE=DIR runs DIR/*.sh alone (make check-cluster: tests/cluster), one
# at a time: its tests share one cluster.
[ -n "${PM_SUITE:-}" ] && jobs=1
case "$jobs" in '' | *[!0-9]* | 0) echo "run.sh: PM_TEST_JOBS must be a positive number" >&2; exit 2 ;; esac
ndirs=$(echo $dirs | wc -w)
rev=
for B in $dirs; do rev="$B $rev"; done
# list KIND TREE: appends that tree's tests of one kind (scripts, binaries).
list() {
	B=$1
	tag=
	[ "$ndirs" -gt 1 ] && tag=" [$(basename "$B")]"
	if [ "$2" = scripts ]; then
		if [ -n "${PM_SUITE:-}" ]; then set -- "$top/$PM_SUITE"/*.sh
		else set -- "$top"/tests/e2e/*.sh; fi
	else
		[ -n "${PM_SUITE:-}" ] && return
		set -- "$B"/tests/test_* "$B"/fuzz/replay-*
	fi
	for t in "$@"; do
		case "$t" in *.o) continue ;; esac
		[ -e "$t" ] || continue
		[ -n "$pat" ] && case "$t" in *"$pat"*) ;; *) continue ;; esac
		printf '%s\t%s\t%s\n' "$B" "$t" "$(basename "$t")$tag"
	done >>"$PM_LIST"
}
: >"$PM_LIST"
if [ "$jobs" -eq 1 ]; then
	for B in $dirs; do list "$B" binaries; list "$B" scripts; done
else
	for B in $rev; do list "$B" scripts; done
	for B in $rev; do list "$B" binaries; done
fi
n=$(wc -l <"$PM_LIST")
[ "$n" -gt 0 ] && seq 1 "$n" | xargs -P "$jobs" -n 1 sh "$top/tests/run1.sh"
pass=0 fail=0 i=1
while [ "$i" -le "$n" ]; do
	# A test whose runner was killed left no result: it failed.
	if [ -s "$PM_RESULTS/$i" ]; then
		read -r p f <"$PM_RESULTS/$i"
	else
		p=0 f=1
		echo "not ok - $(sed -n "${i}p" "$PM_LIST" | cut -f3): no result"
	fi
	pass=$((pass + p)); fail=$((fail + f)); i=$((i + 1))
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
