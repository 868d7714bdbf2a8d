#!/bin/sh
# passes.sh — N pass pairs of a scene (light pass | pm-build | view pass),
# run in parallel with xargs -P, then averaged and tone-mapped.
# Usage: examples/passes.sh SCENE NAME   (settings from the environment:)
#   N=8 passes, PHOTONS=200000 per pass, SPP=16, K=50, EST=compensated,
#   P=cores in parallel, OUT=examples/out, PM_BIN=build/bin
# Pass i of N is examples/fanout/pass.sh i N: -P i/N for both its light pass
# and its view pass (seed and shutter time derived from i and N; README,
# "Running at scale"). Progress on stderr, then a summary line
# (examples/fanout/progress.sh).
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
scene=$(cd "$(dirname "$1")" && pwd)/$(basename "$1") name=$2
export PM_BIN="${PM_BIN:-$top/build/bin}"
export N="${N:-8}" PHOTONS="${PHOTONS:-200000}" SPP="${SPP:-16}" K="${K:-50}" EST="${EST:-compensated}"
P=${P:-$(nproc)}
out=${OUT:-$top/examples/out}
mkdir -p "$out/$name"
out=$(cd "$out" && pwd)
. "$top/examples/fanout/progress.sh"
cd "$out/$name"
progress_begin "$N" "$name"
seq 1 "$N" | xargs -P "$P" -I{} sh "$top/examples/fanout/pass.sh" {} "$N" "$scene"
progress_end
"$PM_BIN/pm-average" -q $(seq -f 'pass-%g.exr' 1 "$N") -o "$out/$name.exr"
"$PM_BIN/pm-tonemap" "$out/$name.exr" -o "$out/$name.png"
progress_summary "$name" "$out/$name.exr"
echo "$name: $N pass pairs averaged into $out/$name.exr; preview $out/$name.png"
