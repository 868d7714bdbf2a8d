#!/bin/sh
# parallel.sh — fan-out way 3 of 4: the N pass pairs with GNU parallel, on
# this machine or on many, then their average.
# Usage: parallel.sh SCENE DIR   (N=8, P=cores per host; pass settings as in
#   pass.sh; HOSTS=: is this machine, no ssh)
#
# Many machines: HOSTS=host1,host2 (parallel's -S / --sshlogin list; ':' is
# this machine, '4/host1' caps host1 at 4 jobs). Each host needs the pm
# programs (PM_BIN or PATH) and this directory at the same path, e.g. on a
# shared file system: the command runs in DIR (--workdir) and writes
# pass-I.exr there. Without a shared file system, parallel can copy the
# scene (and pass.sh) to each host and the images back: see its options
# --transferfile, --return and --cleanup. The settings travel in the command
# line itself, since ssh does not carry the environment. Progress and a
# summary on stderr (progress.sh; passes on other hosts are counted when
# they share this file system).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
scene=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
N=${N:-8} P=${P:-$(nproc)} HOSTS=${HOSTS:-:}
bin=${PM_BIN:+$PM_BIN/}
. "$here/progress.sh"
mkdir -p "$2" && cd "$2"
progress_begin "$N" parallel.sh
env="PHOTONS=${PHOTONS:-20000} SPP=${SPP:-16} K=${K:-50} EST=${EST:-compensated} PM_BIN=${PM_BIN:-} PM_PROGRESS_LOG='$PM_PROGRESS_LOG'"
seq 1 "$N" | parallel --will-cite --halt now,fail=1 -j "$P" -S "$HOSTS" --workdir "$PWD" \
	"$env sh '$here/pass.sh' {} $N '$scene'"
progress_end
"${bin}pm-average" -q $(seq -f 'pass-%g.exr' 1 "$N") -o average.exr
progress_summary parallel.sh average.exr
