#!/bin/sh
# serial.sh — fan-out way 1 of 4: the N pass pairs one after another in a
# shell loop, then their average. The other ways (xargs.sh, parallel.sh,
# Makefile) write byte-identical pass images and average.
# Usage: serial.sh SCENE DIR   (N=8 passes; pass settings as in pass.sh)
# Everything is written in DIR and named relative to it, and the scene by its
# absolute path, so the command lines recorded in the images are the same
# whichever way ran them. Progress and a summary on stderr (progress.sh).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
scene=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
N=${N:-8}
bin=${PM_BIN:+$PM_BIN/}
. "$here/progress.sh"
mkdir -p "$2" && cd "$2"
progress_begin "$N" serial.sh
for i in $(seq 1 "$N"); do
	sh "$here/pass.sh" "$i" "$N" "$scene"
done
progress_end
"${bin}pm-average" -q $(seq -f 'pass-%g.exr' 1 "$N") -o average.exr
progress_summary serial.sh average.exr
