#!/bin/sh
# make.sh — runs the fan-out Makefile beside it in DIR with make -j P.
# Usage: make.sh SCENE DIR   (N=8, P=cores; pass settings as in pass.sh)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
scene=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
mkdir -p "$2"
exec make -s -C "$2" -f "$here/Makefile" -j "${P:-$(nproc)}" N="${N:-8}" SCENE="$scene"
