#!/bin/sh
# density.sh — pm-build --density against plain maps: photons stored, bytes
# a pass, time, and the error of an N-pass average (whole image and edge
# band) at equal light passes (the same photons shot, then thinned) and at
# equal stored photons (a plain map of as many photons as the thinned ones).
#
# Usage: bench/density.sh [BUILD_DIR]   (default build; needs bin/ and
# bench/errsplit: make bench-progs). Environment, with defaults:
#   N=8 passes, PHOTONS=100000 per pass, K=50, SPP=4, EST=compensated,
#   PIXELS="2 4" (--density-pixels), SCENES="cornell room", both at 64 x 48
#   or 64 x 64; REF_PASSES=4 REF_SPP=256 (references, bench/passes.sh)
# Writes bench/results/density.tsv: scene, map (plain-P, density-C,
# plain-M with M the thinned maps' mean count), photons stored (mean over
# passes), bytes of the map (mean), seconds a pass (shoot + build + render,
# one thread, summed over the N passes), RMSE, relMSE, edge-band RMSE and
# relMSE of the N-pass average against the reference. The edge band is as
# bench/run.sh's: pixels whose compensated cube (k = 50) meets another
# surface's plane, from one plain pass. Plots: density-SCENE.png.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
B=${1:-build}
case $B in /*) ;; *) B=$top/$B ;; esac
N=${N:-8} PHOTONS=${PHOTONS:-100000} K=${K:-50} SPP=${SPP:-4} EST=${EST:-compensated}
PIXELS=${PIXELS:-2 4} SCENES=${SCENES:-cornell room}
. "$top/bench/passes.sh"
out=$res/density.tsv
printf 'scene\tmap\tphotons\tbytes\ttime_s\trmse\trelmse\tedge_rmse\tedge_relmse\n' >"$out"
now() { date +%s.%N; }

# series SCENE NAME REF MASK SHOOT_N [BUILD_ARGS...]: N pass pairs, one row
series() {
	sc=$1 label=$2 ref=$3 mask=$4 n=$5
	shift 5
	t=0 cnt=0 bytes=0
	for i in $(seq 1 "$N"); do
		a=$(now)
		"$bin/pm-shoot" -q -j 1 -n "$n" -P "$i/$N" "$sc" -o "$tmp/shot.pm"
		"$bin/pm-build" -q -j 1 "$@" "$tmp/shot.pm" -o "$tmp/map.pm"
		"$bin/pm-render" -q -j 1 -e "$EST" -k "$K" -p "$SPP" -P "$i/$N" "$sc" "$tmp/map.pm" -o "$tmp/pass-$i.exr"
		b=$(now)
		t=$(awk -v t="$t" -v a="$a" -v b="$b" 'BEGIN { printf "%.3f", t + b - a }')
		cnt=$((cnt + $("$bin/pm-dump" --stats "$tmp/map.pm" | sed -n 's/^photons: //p')))
		bytes=$((bytes + $(wc -c <"$tmp/map.pm")))
	done
	"$bin/pm-average" -q $(seq -f "$tmp/pass-%g.exr" 1 "$N") -o "$tmp/avg.exr"
	# errsplit: pixels mse rmse relmse passvar relpassvar refvar relrefvar
	all=$("$bb/errsplit" "$tmp/avg.exr" "$ref" | awk '{ print $3 "\t" $4 }')
	edge=$("$bb/errsplit" -m "$mask" -c edge "$tmp/avg.exr" "$ref" | awk '{ print $3 "\t" $4 }')
	printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$label" $((cnt / N)) $((bytes / N)) "$t" "$all" "$edge" >>"$out"
	echo $((cnt / N))
}

for name in $SCENES; do
	case $name in
	room) sc=$(scene room 64 48) ;;
	*) sc=$(scene "$name" 64 64) ;;
	esac
	ref=$(reference "$name" "$sc")
	mask=$tmp/mask-$name.exr
	"$bin/pm-shoot" -q -n "$PHOTONS" -s 999 "$sc" | "$bin/pm-build" -q |
		"$bin/pm-render" -q -k 50 -p "$SPP" -s 999 "$sc" - -o "$mask"
	echo "density: $name, $N pass pairs of $PHOTONS photons, $EST, k = $K" >&2
	series "$sc" "plain-$PHOTONS" "$ref" "$mask" "$PHOTONS" >/dev/null
	for c in $PIXELS; do
		m=$(series "$sc" "density-$c" "$ref" "$mask" "$PHOTONS" --density "$sc" --density-pixels "$c" --density-k "$K")
		series "$sc" "plain-$m" "$ref" "$mask" "$m" >/dev/null
	done
done
# density-SCENE.png: relMSE against photons stored, plain maps as a line,
# thinned ones as points
if command -v gnuplot >/dev/null; then
	for name in $SCENES; do
		awk -F'\t' -v s="$name" '$1 == s && $2 ~ /^plain/' "$out" | sort -n -k3 >"$tmp/plain.tsv"
		awk -F'\t' -v s="$name" '$1 == s && $2 ~ /^density/' "$out" >"$tmp/dens.tsv"
		gnuplot <<PLOT
set terminal pngcairo size 640,420
set output "$res/density-$name.png"
set title "$name: relMSE of $N passes against photons stored\\n$EST, k = $K; thinned from $PHOTONS photons"
set xlabel "photons stored a pass"
set ylabel "relMSE"
set logscale x
plot "$tmp/plain.tsv" using 3:7 with linespoints title "plain maps", \
	"$tmp/dens.tsv" using 3:7:2 with labels point pt 7 offset 1,1 notitle, \
	"$tmp/dens.tsv" using 3:7 with points pt 7 title "pm-build --density (C)"
PLOT
	done
fi
echo "density: wrote $out" >&2
