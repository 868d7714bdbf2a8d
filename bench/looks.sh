#!/bin/sh
# looks.sh — what textures and an environment light cost a view pass: the
# same open scene (a floor, a box and a sphere under a distant light) as it
# is, with its floor and box textured (a 1024 x 1024 image on the floor, a
# checkerboard on the box), and with a lat-long sky (512 x 256) added; each
# pm-render pass (compensated estimate, its own map of PHOTONS photons, one
# thread) timed RUNS times in rounds of the three, median seconds and the
# ratio to the plain scene.
#
# Usage: bench/looks.sh [BUILD_DIR]   (default build; needs bin/ and
# tests/tools/mkimg). Environment, with defaults: PHOTONS=100000, SPP=16,
# RUNS=7, SIZE="160 120". Writes bench/results/looks.tsv.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
B=${1:-build}
case $B in /*) ;; *) B=$top/$B ;; esac
PHOTONS=${PHOTONS:-100000} SPP=${SPP:-16} RUNS=${RUNS:-7} SIZE=${SIZE:-160 120}
bin=$B/bin res=$top/bench/results
mkimg=$B/tests/tools/mkimg
for p in "$bin/pm-shoot" "$bin/pm-build" "$bin/pm-render" "$mkimg"; do
	[ -x "$p" ] || { echo "$0: '$p' missing: make all-tests" >&2; exit 1; }
done
mkdir -p "$res"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
"$mkimg" -p ramp floor.exr 1024 1024
"$mkimg" -v 0.8,0.9,1.2 sky.exr 512 256
base() {
	cat <<SCENE
camera eye 0 2 6  look 0 0.6 0  up 0 1 0  fov 45  size $SIZE
$1
quad floor -4 0 -4  -4 0 4  4 0 4  4 0 -4
box box -1.6 0 -0.6  -0.4 1.2 0.6
sphere ball 1 0.6 0 0.6
distantlight dir 0.5 -1 -0.3  irradiance 3 3 3
$2
SCENE
}
plain="material floor diffuse albedo 0.6 0.6 0.6
material box diffuse albedo 0.5 0.4 0.3
material ball glossy kd 0.4 0.4 0.4 ks 0.2 0.2 0.2 exponent 20"
tex="texture wood image floor.exr scale 4 4
texture chk checker 0.2 0.2 0.2  0.7 0.6 0.5 scale 8 8
material floor diffuse albedo tex wood
material box diffuse albedo tex chk
material ball glossy kd 0.4 0.4 0.4 ks 0.2 0.2 0.2 exponent 20"
base "$plain" "" >plain.pms
base "$tex" "" >textured.pms
base "$plain" "envlight image sky.exr scale 0.3" >sky.pms
printf 'scene\truns\tmedian_seconds\tratio_to_plain\n' >"$res/looks.tsv"
median() { sort -g | awk '{ a[NR] = $1 } END { print a[int((NR + 1) / 2)] }'; }
for s in plain textured sky; do
	"$bin/pm-shoot" -q -n "$PHOTONS" $s.pms | "$bin/pm-build" -q -o $s.map
done
# Rounds of one pass of each scene, one thread: a change of the machine's
# load between rounds moves all three alike.
for r in $(seq "$RUNS"); do
	for s in plain textured sky; do
		t0=$(date +%s.%N)
		"$bin/pm-render" -q -j 1 -p "$SPP" $s.pms $s.map -o out-$s.exr
		t1=$(date +%s.%N)
		echo "$t1 $t0" | awk '{ print $1 - $2 }' >>$s.times
	done
done
base_t=$(median <plain.times)
for s in plain textured sky; do
	t=$(median <$s.times)
	printf '%s\t%s\t%s\t%.3f\n' $s "$RUNS" "$t" "$(awk -v a="$t" -v b="$base_t" 'BEGIN { print a / b }')" >>"$res/looks.tsv"
done
cat "$res/looks.tsv"
