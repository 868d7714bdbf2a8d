#!/bin/sh
# run.sh — runs every unit test binary and end-to-end script, counts the
# "ok - " and "not ok - " lines they print, and ends with "N passed, N failed".
# Usage: tests/run.sh BUILD_DIR [PATTERN]
B=${1:-build}
pat=${2:-}
top=$(cd "$(dirname "$0")/.." && pwd)
B=$(cd "$top" && cd "$B" && pwd) || exit 2
export PM_BIN="$B/bin" PM_TOP="$top"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
for t in "$B"/tests/test_* "$top"/tests/e2e/*.sh; do
	case "$t" in *.o) continue ;; esac
	[ -e "$t" ] || continue
	[ -n "$pat" ] && case "$t" in *"$pat"*) ;; *) continue ;; esac
	name=$(basename "$t")
	start=$(date +%s)
	case "$t" in
	*.sh) (cd "$tmp" && sh "$t") >"$tmp/out" 2>"$tmp/err" ;;
	*) (cd "$tmp" && "$t") >"$tmp/out" 2>"$tmp/err" ;;
	esac
	rc=$?
	p=$(grep -c '^ok - ' "$tmp/out")
	f=$(grep -c '^not ok - ' "$tmp/out")
	if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
		echo "not ok - $name: exited $rc without a failed check" >>"$tmp/out"
		f=1
	fi
	pass=$((pass + p)); fail=$((fail + f))
	printf '%-28s %3d passed %3d failed  %3ds\n' "$name" "$p" "$f" $(( $(date +%s) - start ))
	if [ "$f" -ne 0 ]; then
		grep '^not ok - \|^  also' "$tmp/out" | sed 's/^/    /'
		tail -n 5 "$tmp/err" | sed 's/^/    stderr: /'
	fi
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
