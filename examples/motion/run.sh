#!/bin/sh
# run.sh — the motion-blur example: N pass pairs of motion.pms, pass I at the
# shutter time that -P I/N derives (one jittered time per 1/N of the
# shutter), averaged; plus a still frame at t = 0 to compare.
# Usage: examples/motion/run.sh   (N=32 PHOTONS=50000 SPP=16, P=cores,
#   OUT=examples/out, PM_BIN=build/bin)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
top=$(cd "$here/../.." && pwd)
bin=${PM_BIN:-$top/build/bin}
N=${N:-32} P=${P:-$(nproc)} out=${OUT:-$top/examples/out}
mkdir -p "$out/motion"
export bin N out PHOTONS=${PHOTONS:-50000} SPP=${SPP:-16} scene="$here/motion.pms"
seq 1 "$N" | xargs -P "$P" -I{} sh -c '
	"$bin/pm-shoot" -q -j 1 -n "$PHOTONS" -P {}/"$N" "$scene" | "$bin/pm-build" -q -j 1 |
	"$bin/pm-render" -q -j 1 -p "$SPP" -P {}/"$N" "$scene" - -o "$out/motion/pass-{}.exr"'
"$bin/pm-average" $(seq -f "$out/motion/pass-%g.exr" 1 "$N") -o "$out/motion.exr"
"$bin/pm-tonemap" "$out/motion.exr" -o "$out/motion.png"
"$bin/pm-shoot" -q -n "$PHOTONS" -t 0 "$scene" | "$bin/pm-build" -q |
	"$bin/pm-render" -q -p "$((SPP * 4))" "$scene" - -o "$out/motion-still.exr"
"$bin/pm-tonemap" "$out/motion-still.exr" -o "$out/motion-still.png"
echo "motion: $N pass pairs averaged into $out/motion.png; still frame at t = 0: $out/motion-still.png"
