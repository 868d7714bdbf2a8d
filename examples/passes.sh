#!/bin/sh
# passes.sh — N pass pairs of a scene (light pass | pm-build | view pass), run
# in parallel with xargs -P, then averaged and tone-mapped.
# Usage: examples/passes.sh SCENE NAME   (settings from the environment:)
#   N=8 passes, PHOTONS=200000 per pass, SPP=4, K=50, EST=compensated,
#   P=cores in parallel, OUT=examples/out, PM_BIN=build/bin
# Pass i of N is -P i/N for both its light pass and its view pass (seed and
# shutter time derived from i and N; README, "Running at scale").
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
scene=$1 name=$2
bin=${PM_BIN:-$top/build/bin}
N=${N:-8} PHOTONS=${PHOTONS:-200000} SPP=${SPP:-4} K=${K:-50} EST=${EST:-compensated}
P=${P:-$(nproc)}
out=${OUT:-$top/examples/out}
mkdir -p "$out/$name"
export bin scene out name N PHOTONS SPP K EST
seq 1 "$N" | xargs -P "$P" -I{} sh -c '
	set -e
	"$bin/pm-shoot" -q -j 1 -n "$PHOTONS" -P {}/"$N" "$scene" | "$bin/pm-build" -q |
	"$bin/pm-render" -j 1 -e "$EST" -k "$K" -p "$SPP" -P {}/"$N" "$scene" - -o "$out/$name/pass-{}.exr"'
"$bin/pm-average" "$out/$name"/pass-*.exr -o "$out/$name.exr"
"$bin/pm-tonemap" "$out/$name.exr" -o "$out/$name.png"
echo "$name: $N pass pairs averaged into $out/$name.exr; preview $out/$name.png"
