#!/bin/sh
# sidebyside.sh — one view pass's price, compensated ÷ classical, for two
# builds of pm measured in turn on one machine (a change to the estimate
# against main, say): each round runs OLD's and NEW's pm-render with both
# estimators on the same map, RUNS rounds, and prints the medians of user
# CPU seconds (one thread, so the machine's other load counts less) and
# the prices. Also says whether the two builds' compensated images agree
# pixel for pixel (pm-diff RMSE 0), as a change meant to leave the estimate
# alone must.
#
# Usage: sh bench/sidebyside.sh OLD_BUILD NEW_BUILD SCENE MAP [RUNS]
#   (RUNS default 5; the map from pm-shoot | pm-build on SCENE)
# Prints one line: scene, then for OLD and NEW the classical and the
# compensated medians and the price (each build's compensated over its own
# classical: a change to pm-render moves both).
set -eu
[ $# -ge 4 ] || { echo "usage: sh bench/sidebyside.sh OLD_BUILD NEW_BUILD SCENE MAP [RUNS]" >&2; exit 2; }
old=$1 new=$2 sc=$3 map=$4 runs=${5:-5}
for b in "$old" "$new"; do
	[ -x "$b/bin/pm-render" ] || { echo "$0: '$b/bin/pm-render' missing" >&2; exit 1; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for r in $(seq 1 "$runs"); do
	for v in old new; do
		eval b=\$$v
		for e in compensated classical; do
			/usr/bin/time -f %U -o "$tmp/t" "$b/bin/pm-render" -q -j 1 -e $e -s 1 "$sc" "$map" \
				-o "$tmp/$v-$e.exr"
			echo "$v-$e $(tail -n 1 "$tmp/t")"
		done
	done
done >"$tmp/runs"
med() { grep "^$1 " "$tmp/runs" | awk '{ print $2 }' | sort -g |
	awk '{ a[NR] = $1 } END { print NR % 2 ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
same=differ
pmdiff=$new/bin/pm-diff
[ -x "$pmdiff" ] || pmdiff=$(dirname "$0")/../build/bin/pm-diff
"$pmdiff" "$tmp/old-compensated.exr" "$tmp/new-compensated.exr" | grep -q '^rmse: 0$' && same=identical
awk -v n="$(basename "$sc" .pms)" -v oc="$(med old-compensated)" -v nc="$(med new-compensated)" \
	-v ok="$(med old-classical)" -v nk="$(med new-classical)" -v same=$same 'BEGIN {
	printf "%s\told %.2f s / %.2f s (%.2f)\tnew %.2f s / %.2f s (%.2f)\timages %s\n", n, oc, ok, oc / ok, nc, nk, nc / nk, same }'
