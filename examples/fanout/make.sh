#!/bin/sh
# make.sh — runs the fan-out Makefile beside it in DIR with make -j P.
# Usage: make.sh SCENE DIR   (N=8, P=cores; pass settings as in pass.sh)
# Progress (of the passes still to make) and a summary on stderr
# (progress.sh).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
scene=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
N=${N:-8}
. "$here/progress.sh"
mkdir -p "$2"
todo=0
for i in $(seq 1 "$N"); do
	[ -e "$2/pass-$i.exr" ] || todo=$((todo + 1))
done
progress_begin "$todo" make.sh
make -s -C "$2" -f "$here/Makefile" -j "${P:-$(nproc)}" N="$N" SCENE="$scene"
progress_end
progress_summary make.sh "$2/average.exr"
