#!/bin/sh
# consistent.sh — pm-render's consistent mode (--consistent ALPHA) against
# fixed k: the error of the average of passes 1..N as N grows, on the
# furnace of tests/scenes (exact radiance 2) and the Cornell box (a
# path-traced reference, bench/passes.sh),
# for the classical and compensated estimates. Each pass pair's map is
# rendered in both modes, so the two see the same photons.
#
# Usage: bench/consistent.sh [BUILD_DIR]   (default build; needs bin/ and
# bench/errsplit: make bench-progs). Environment, with defaults:
#   NMAX=64 passes, PHOTONS=10000 per pass, K=50, SPP=4, ALPHA=0.6667,
#   SCENES="furnace cornell", REF_PASSES=4 REF_SPP=256 (Cornell reference,
#   cached in BUILD_DIR/bench-cache), SIZE_furnace="64 48", SIZE_cornell="64 64"
# Writes bench/results/consistent.tsv (scene est mode N time_s rmse relmse
# bias2 noise2 ind_rmse ind_relmse; bias2 = mse - passvar/N - refvar,
# noise2 = passvar/N, as bench/errsplit.c splits them; ind_* are pm-diff's
# on the indirect layer, the photon estimate against the path tracer's
# light after the first bounce, NA for the furnace) and consistent-SCENE.png
# (RMSE against N; for the Cornell box, of the indirect layer).
# Every program runs on one thread; time is the sum of the renders' wall
# times (the light passes are shared by both modes and left out).
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
B=${1:-build}
case $B in /*) ;; *) B=$top/$B ;; esac
NMAX=${NMAX:-64} PHOTONS=${PHOTONS:-10000} K=${K:-50} SPP=${SPP:-4} ALPHA=${ALPHA:-0.6667}
SCENES=${SCENES:-furnace cornell}
SIZE_furnace=${SIZE_furnace:-64 48} SIZE_cornell=${SIZE_cornell:-64 64}
. "$top/bench/passes.sh"
out=$res/consistent.tsv
printf 'scene\test\tmode\tN\ttime_s\trmse\trelmse\tbias2\tnoise2\tind_rmse\tind_relmse\n' >"$out"
now() { date +%s.%N; }

for name in $SCENES; do
	eval "set -- \$SIZE_$name"
	sc=$(scene "$name" "$1" "$2")
	if [ "$name" = furnace ]; then
		refopt="-v 2" ref=
	else
		refopt= ref=$(reference "$name" "$sc")
	fi
	echo "consistent: $name, $NMAX pass pairs of $PHOTONS photons, k = $K, alpha = $ALPHA" >&2
	for i in $(seq 1 "$NMAX"); do
		"$bin/pm-shoot" -q -j 1 -n "$PHOTONS" -P "$i/$NMAX" "$sc" | "$bin/pm-build" -q -j 1 -o "$tmp/map.pm"
		for est in classical compensated; do
			for mode in fixed consistent; do
				c=
				[ $mode = consistent ] && c="--consistent $ALPHA"
				a=$(now)
				# shellcheck disable=SC2086
				"$bin/pm-render" -q -j 1 -e $est -k "$K" -p "$SPP" -P "$i/$NMAX" $c "$sc" "$tmp/map.pm" \
					-o "$tmp/$est-$mode-$i.exr"
				b=$(now)
				echo "$a $b" | awk '{ printf "%.3f\n", $2 - $1 }' >"$tmp/$est-$mode-$i.t"
			done
		done
	done
	for est in classical compensated; do
		for mode in fixed consistent; do
			n=1
			while [ $n -le "$NMAX" ]; do
				"$bin/pm-average" -q $(seq -f "$tmp/$est-$mode-%g.exr" 1 $n) -o "$tmp/avg.exr"
				t=$(seq -f "$tmp/$est-$mode-%g.t" 1 $n | xargs cat | awk '{ s += $1 } END { printf "%.2f", s }')
				ind="NA NA"
				[ -n "$ref" ] && ind=$("$bin/pm-diff" -l indirect "$tmp/avg.exr" "$ref" |
					awk '/^rmse:/ { r = $2 } /^relmse:/ { m = $2 } END { print r, m }')
				# errsplit: pixels mse rmse relmse passvar relpassvar refvar relrefvar
				# shellcheck disable=SC2086
				"$bb/errsplit" $refopt "$tmp/avg.exr" $ref | awk -v OFS='\t' -v s="$name" -v e="$est" -v m="$mode" \
					-v n="$n" -v t="$t" -v ind="$ind" '{ pv = (n > 1 ? $5 / n : 0); split(ind, x, " ")
					print s, e, m, n, t, $3, $4, $2 - pv - $7, pv, x[1], x[2] }' >>"$out"
				n=$((n * 2))
			done
		done
	done
	rm -f "$tmp"/*-fixed-* "$tmp"/*-consistent-*
	if command -v gnuplot >/dev/null; then
		awk -F'\t' -v s="$name" 'NR > 1 && $1 == s' "$out" >"$tmp/plot.tsv"
		col=6 what=RMSE
		[ -n "$ref" ] && col=10 what="RMSE of the indirect layer"
		gnuplot <<PLOT
set terminal pngcairo size 640,420
set output "$res/consistent-$name.png"
set title "$name: RMSE of the average of passes 1..N\\n$PHOTONS photons a pass, k = $K, alpha = $ALPHA"
set xlabel "passes N"
set ylabel "$what"
set logscale xy
set key top right
plot for [e in "classical compensated"] for [m in "fixed consistent"] \
	"< awk -F'\\t' '\$2 == \"".e."\" && \$3 == \"".m."\"' $tmp/plot.tsv" using 4:$col with linespoints title e." ".m
PLOT
	fi
done
echo "consistent: wrote $out" >&2
