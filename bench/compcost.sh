#!/bin/sh
# compcost.sh — what the compensated estimate costs against the classical
# one (issue 21): the time of one view pass of each on the same photon map,
# per scene, and one estimate's time against the polygons meeting its cube.
#
# Usage: bench/compcost.sh [BUILD_DIR]   (default build; needs bin/ and
# bench/compcost, bench/meshroom, bench/peakrss: make bench-progs).
# Environment, with defaults:
#   SCENES="cornell room caustic meshroom"   scenes for the pass ratio
#   SIZE=128 PHOTONS=200000 THREADS=2 RUNS=3
#   CURVE_RES="0.5 1 2" CURVE_SIZE=64      meshroom resolutions for the curve
# Writes bench/results/compcost.tsv (per scene: triangles, median seconds of
# a view pass, classical and compensated, wall and CPU, and their ratios),
# compcost-curve.tsv (per bin of polygons in the cube: estimates, mean
# microseconds compensated and classical) and compcost-facets.png.
#
# Pass times: pm-render with its defaults, -j THREADS, on one map made
# once; each run times both estimators back to back, and the ratio is that
# of the medians. CPU seconds (user + system, bench/peakrss) are the better
# measure on a shared machine; wall seconds are what a user waits.
#
# To add a scene family: a line in make_scene that writes it (and prints the
# .pms path), and its name in SCENES.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
B=${1:-build}
case $B in /*) ;; *) B=$top/$B ;; esac
SCENES=${SCENES:-cornell room caustic meshroom}
SIZE=${SIZE:-128} PHOTONS=${PHOTONS:-200000} THREADS=${THREADS:-2} RUNS=${RUNS:-3}
CURVE_RES=${CURVE_RES:-0.5 1 2} CURVE_SIZE=${CURVE_SIZE:-64}
. "$top/bench/passes.sh"
for p in compcost meshroom peakrss; do
	[ -x "$bb/$p" ] || { echo "$0: '$bb/$p' missing: make bench-progs" >&2; exit 1; }
done
command -v gnuplot >/dev/null || { echo "$0: gnuplot missing: sh mk/deps.sh bench" >&2; exit 1; }

# make_scene NAME: writes the scene at SIZE x SIZE, prints its path.
make_scene() {
	case $1 in
	cornell|room|caustic) scene "$1" "$SIZE" "$SIZE" ;;
	meshroom) mkdir -p "$tmp/mr" && "$bb/meshroom" -s "$SIZE" "$tmp/mr" && echo "$tmp/mr/meshroom.pms" ;;
	*) echo "$0: unknown scene '$1'" >&2; exit 2 ;;
	esac
}

kv() { awk -F'\t' -v k="$2" '$1 == k { print $2; exit }' "$1"; }
med() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

out=$res/compcost.tsv
printf 'scene\ttriangles\tclassical_wall_s\tcompensated_wall_s\tratio_wall\tclassical_cpu_s\tcompensated_cpu_s\tratio_cpu\n' >"$out"
for name in $SCENES; do
	sc=$(make_scene "$name")
	echo "compcost: $name, $PHOTONS photons, $SIZE x $SIZE, -j $THREADS, $RUNS runs" >&2
	"$bin/pm-shoot" -q -n "$PHOTONS" -s 1 "$sc" | "$bin/pm-build" -q -o "$tmp/map.pm"
	: >"$tmp/t.tsv"
	for i in $(seq 1 "$RUNS"); do
		for est in classical compensated; do
			"$bb/peakrss" "$bin/pm-render" -q -j "$THREADS" -e "$est" -s 1 "$sc" "$tmp/map.pm" \
				-o "$tmp/$est.exr" >"$tmp/r.tsv"
			printf '%s\t%s\t%s\n' "$est" "$(kv "$tmp/r.tsv" wall_s)" "$(kv "$tmp/r.tsv" cpu_s)" >>"$tmp/t.tsv"
		done
	done
	tris=$("$bb/compcost" -t "$sc" | cut -f2)
	cw=$(awk -F'\t' '$1 == "classical" { print $2 }' "$tmp/t.tsv" | med)
	ow=$(awk -F'\t' '$1 == "compensated" { print $2 }' "$tmp/t.tsv" | med)
	cc=$(awk -F'\t' '$1 == "classical" { print $3 }' "$tmp/t.tsv" | med)
	oc=$(awk -F'\t' '$1 == "compensated" { print $3 }' "$tmp/t.tsv" | med)
	awk -v n="$name" -v t="$tris" -v cw="$cw" -v ow="$ow" -v cc="$cc" -v oc="$oc" 'BEGIN {
		printf "%s\t%s\t%.3f\t%.3f\t%.2f\t%.3f\t%.3f\t%.2f\n", n, t, cw, ow, ow / cw, cc, oc, oc / cc }' >>"$out"
done

# One estimate's time against the polygons in its cube: meshroom at several
# resolutions (finer meshes put more facets in a cube), every first hit.
curve=$res/compcost-curve.tsv
: >"$tmp/all.tsv"
for r in $CURVE_RES; do
	echo "compcost: per-estimate times, meshroom -r $r, $CURVE_SIZE x $CURVE_SIZE" >&2
	mkdir -p "$tmp/c$r"
	"$bb/meshroom" -r "$r" -s "$CURVE_SIZE" "$tmp/c$r"
	"$bb/compcost" -r 1 -n "$PHOTONS" -o "$tmp/c$r/est.tsv" "$tmp/c$r/meshroom.pms" >/dev/null 2>&1
	cat "$tmp/c$r/est.tsv" >>"$tmp/all.tsv"
done
# bins 1, 2, 3-4, 5-8, ...: estimates, mean polygons, mean and 90th
# percentile microseconds compensated, mean classical
printf 'polys_max\testimates\tmean_polys\tus_compensated\tus_compensated_p90\tus_classical\n' >"$curve"
awk -F'\t' '{ b = 1; while (b < $1) b *= 2; print b "\t" $1 "\t" $3 "\t" $4 }' "$tmp/all.tsv" | sort -n -k1,1 -k3,3g |
	awk -F'\t' '
	function flush() { if (n) printf "%d\t%d\t%.1f\t%.2f\t%.2f\t%.2f\n", cur, n, sp / n, sc / n, v[int(0.9 * (n - 1)) + 1], sl / n }
	$1 != cur { flush(); cur = $1; n = sp = sc = sl = 0 }
	{ n++; sp += $2; sc += $3; sl += $4; v[n] = $3 }
	END { flush() }' >>"$curve"
{
	echo "set terminal pngcairo size 900,600 noenhanced font ',10'"
	echo "set output '$res/compcost-facets.png'"
	echo "set logscale xy; set grid; set key top left"
	echo "set xlabel 'polygons meeting the cube (bin mean)'"
	echo "set ylabel 'microseconds per estimate (one thread, CPU time)'"
	echo "set title 'one estimate against the polygons in its cube (meshroom at $CURVE_RES)'"
	echo "plot '$curve' every ::1 using 3:4 with linespoints title 'compensated, mean', \\"
	echo "     '$curve' every ::1 using 3:5 with linespoints title 'compensated, 90th percentile', \\"
	echo "     '$curve' every ::1 using 3:6 with linespoints title 'classical, mean'"
} >"$tmp/p.gp"
gnuplot "$tmp/p.gp"
cat "$out" >&2
