#!/bin/sh
# run.sh — make check-peers: pm against an independent renderer on scenes
# the tests/peers/pbrt_*.sh scripts write (not part of make check). The
# peer is pbrt-v4, $PM_PBRT (default ../shared/peers/pbrt beside the
# checkout); without it the run is skipped. Each script runs in a directory
# of its own; its "ok - " / "not ok - " lines, which carry the measured
# numbers, are printed as they are. PM_PEERS_KEEP=DIR keeps the scenes and
# images there.
# Usage: tests/peers/run.sh BUILD_DIR [PATTERN]
top=$(cd "$(dirname "$0")/../.." && pwd)
B=$(cd "$1" && pwd) || exit 2
pat=${2:-}
PM_PBRT=${PM_PBRT:-$top/../shared/peers/pbrt}
if [ ! -x "$PM_PBRT" ]; then
	echo "check-peers: no pbrt-v4 at $PM_PBRT (set PM_PBRT to a pbrt-v4 binary), skipped"
	exit 0
fi
export PM_TOP="$top" PM_BIN="$B/bin" PM_PBRT
work=${PM_PEERS_KEEP:-$(mktemp -d)}
[ -n "${PM_PEERS_KEEP:-}" ] || trap 'rm -rf "$work"' EXIT
mkdir -p "$work"
pass=0 fail=0
for t in "$top"/tests/peers/pbrt_*.sh; do
	[ -e "$t" ] || continue
	[ -n "$pat" ] && case "$t" in *"$pat"*) ;; *) continue ;; esac
	name=$(basename "$t" .sh)
	mkdir -p "$work/$name"
	start=$(date +%s)
	(cd "$work/$name" && sh "$t") >"$work/$name.out" 2>"$work/$name.err"
	rc=$?
	grep '^ok - \|^not ok - ' "$work/$name.out"
	p=$(grep -c '^ok - ' "$work/$name.out")
	f=$(grep -c '^not ok - ' "$work/$name.out")
	if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
		echo "not ok - $name: exited $rc without a failed check"; f=1
		tail -n 5 "$work/$name.err" | sed 's/^/    stderr: /'
	fi
	echo "# $name: $p passed, $f failed, $(( $(date +%s) - start )) s"
	pass=$((pass + p)); fail=$((fail + f))
done
echo "check-peers: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
