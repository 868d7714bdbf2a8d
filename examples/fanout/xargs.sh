#!/bin/sh
# xargs.sh — fan-out way 2 of 4: the N pass pairs with xargs -P, P at a time
# (default: the number of cores), then their average.
# Usage: xargs.sh SCENE DIR   (N=8, P=cores; pass settings as in pass.sh)
# Progress and a summary on stderr (progress.sh).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
scene=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
N=${N:-8} P=${P:-$(nproc)}
bin=${PM_BIN:+$PM_BIN/}
. "$here/progress.sh"
mkdir -p "$2" && cd "$2"
progress_begin "$N" xargs.sh
seq 1 "$N" | xargs -P "$P" -I{} sh "$here/pass.sh" {} "$N" "$scene"
progress_end
"${bin}pm-average" -q $(seq -f 'pass-%g.exr' 1 "$N") -o average.exr
progress_summary xargs.sh average.exr
