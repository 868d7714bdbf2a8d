#!/bin/sh
# ldpaths.sh — pm-shoot --light-paths sobol against random: the variance of
# one pass's photon-map estimate, and the error of N-pass averages.
#
# Usage: bench/ldpaths.sh [BUILD_DIR]   (default build; needs bin/ and
# bench/errsplit: make bench-progs). Environment, with defaults:
#   NMAX=32 passes, PHOTONS=10000 per pass, K=50, SPP=4, EST=compensated,
#   SCENES="mirror caustic furnace cornell", REF_PASSES=4 REF_SPP=256 (the
#   Cornell reference, bench/passes.sh)
# Scenes: tests/scenes/mirror.pms, a point light over a mirror floor under
# a dark ceiling (the ceiling's photons come through the mirror: a caustic,
# placed by the emission direction alone); examples/caustic (the Cornell box
# with a glass and a mirror sphere; no reference: pass spread only);
# tests/scenes/furnace.pms (exact radiance 2); the Cornell box. All 64 x 48
# or 64 x 64.
#
# Each pass's map is rendered twice: with -s 1 in every pass (the view pass
# the same each time, so the spread between passes, passvar, is the photon
# map's alone: "one pass's estimate"), and with -P I/N (the usual pass pairs:
# RMSE of the average of passes 1..N against the reference, none for mirror).
# Writes bench/results/ldpaths.tsv (scene paths N rmse relmse passvar mean;
# passvar as bench/errsplit.c's, the mean per-pixel variance of one pass,
# mean the image's mean radiance, for scale) and ldpaths-SCENE.png (RMSE
# against N).
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
B=${1:-build}
case $B in /*) ;; *) B=$top/$B ;; esac
NMAX=${NMAX:-32} PHOTONS=${PHOTONS:-10000} K=${K:-50} SPP=${SPP:-4} EST=${EST:-compensated}
SCENES=${SCENES:-mirror caustic furnace cornell}
. "$top/bench/passes.sh"
out=$res/ldpaths.tsv
printf 'scene\tpaths\tN\trmse\trelmse\tpassvar\tmean\n' >"$out"

for name in $SCENES; do
	case $name in
	furnace) sc=$(scene "$name" 64 48) refopt="-v 2" ref= ;;
	mirror|caustic) sc=$(scene "$name" 64 64) refopt= ref= ;;
	*) sc=$(scene "$name" 64 64) refopt= ref=$(reference "$name" "$sc") ;;
	esac
	echo "ldpaths: $name, $NMAX pass pairs of $PHOTONS photons, $EST, k = $K" >&2
	for lp in random sobol; do
		for i in $(seq 1 "$NMAX"); do
			"$bin/pm-shoot" -q -j 1 -n "$PHOTONS" --light-paths $lp -P "$i/$NMAX" "$sc" |
				"$bin/pm-build" -q -j 1 -o "$tmp/map.pm"
			"$bin/pm-render" -q -j 1 -e "$EST" -k "$K" -p "$SPP" -s 1 -P "$i/$NMAX" "$sc" "$tmp/map.pm" \
				-o "$tmp/fix-$lp-$i.exr"
			"$bin/pm-render" -q -j 1 -e "$EST" -k "$K" -p "$SPP" -P "$i/$NMAX" "$sc" "$tmp/map.pm" \
				-o "$tmp/pass-$lp-$i.exr"
		done
		"$bin/pm-average" -q $(seq -f "$tmp/fix-$lp-%g.exr" 1 "$NMAX") -o "$tmp/fix.exr"
		# errsplit: pixels mse rmse relmse passvar relpassvar refvar relrefvar
		pv=$("$bb/errsplit" -v 0 "$tmp/fix.exr" | awk '{ print $5 }')
		pv="$pv	$("$bin/pm-diff" "$tmp/fix.exr" "$tmp/fix.exr" | sed -n 's/^mean_a: *//p')"
		n=1
		while [ $n -le "$NMAX" ]; do
			"$bin/pm-average" -q $(seq -f "$tmp/pass-$lp-%g.exr" 1 $n) -o "$tmp/avg.exr"
			if [ -n "$refopt$ref" ]; then
				# shellcheck disable=SC2086
				e=$("$bb/errsplit" $refopt "$tmp/avg.exr" $ref | awk -v OFS='\t' '{ print $3, $4 }')
			else
				e=$(printf 'NA\tNA')
			fi
			printf '%s\t%s\t%s\t%s\t%s\n' "$name" $lp $n "$e" "$pv" >>"$out"
			n=$((n * 2))
		done
		rm -f "$tmp"/fix-* "$tmp"/pass-*
	done
	if [ -n "$refopt$ref" ] && command -v gnuplot >/dev/null; then
		awk -F'\t' -v s="$name" 'NR > 1 && $1 == s' "$out" >"$tmp/plot.tsv"
		gnuplot <<PLOT
set terminal pngcairo size 640,420
set output "$res/ldpaths-$name.png"
set title "$name: RMSE of the average of passes 1..N\\n$PHOTONS photons a pass, $EST, k = $K"
set xlabel "passes N"
set ylabel "RMSE"
set logscale xy
plot for [p in "random sobol"] "< awk -F'\\t' '\$2 == \"".p."\"' $tmp/plot.tsv" using 3:4 with linespoints title p
PLOT
	fi
done
echo "ldpaths: wrote $out" >&2
