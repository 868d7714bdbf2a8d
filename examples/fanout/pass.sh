#!/bin/sh
# pass.sh — one pass pair, pass I of N: light pass | pm-build | view pass,
# written to pass-I.exr in the current directory. Both halves take -P I/N,
# so they derive the same seed and shutter time from I and N (README.md,
# "Running at scale"), whoever runs them, wherever and in whatever order.
# Usage: pass.sh I N SCENE
# Settings from the environment: PHOTONS=20000 SPP=16 K=50 EST=compensated;
# PM_BIN, the directory of the pm programs (default: found on PATH);
# PM_PROGRESS_LOG, a file to append a line to when the pass is written
# (progress.sh counts them; unwritable, it is skipped).
set -eu
i=$1 n=$2 scene=$3
bin=${PM_BIN:+$PM_BIN/}
"${bin}pm-shoot" -q -j 1 -n "${PHOTONS:-20000}" -P "$i/$n" "$scene" |
	"${bin}pm-build" -q -j 1 |
	"${bin}pm-render" -q -j 1 -e "${EST:-compensated}" -k "${K:-50}" -p "${SPP:-16}" \
		-P "$i/$n" "$scene" - -o "pass-$i.exr"
if [ -n "${PM_PROGRESS_LOG:-}" ]; then
	{ echo "$i" >>"$PM_PROGRESS_LOG"; } 2>/dev/null || :
fi
