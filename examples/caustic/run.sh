#!/bin/sh
# run.sh — the Cornell box with a glass and a mirror sphere (a caustic):
# N pass pairs in parallel (xargs -P), averaged. Settings as in
# examples/passes.sh (N, PHOTONS, SPP, K, EST, P, OUT).
here=$(cd "$(dirname "$0")" && pwd)
exec sh "$here/../passes.sh" "$here/caustic.pms" caustic
