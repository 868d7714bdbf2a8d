#!/bin/sh
# slurm.sh — fan-out on a SLURM cluster: the N pass pairs as one array job
# (task I runs pass.sh I N), then their average as a second job that starts
# only once every task has succeeded (--dependency=afterok). It submits the
# two jobs, prints their ids and returns; the averaging job writes
# DIR/average.exr, byte-identical to serial.sh's, and DIR/average.png.
# Usage: slurm.sh SCENE DIR [N]   (N=8; pass settings as in pass.sh)
# SLURM settings from the environment: PARTITION (default: the cluster's
# default partition), TIME (a time limit per job in sbatch --time form, e.g.
# 30 or 2:00:00; default: the partition's), CPUS (cores per task, default 1;
# pass.sh runs the programs on one thread, so more only helps where a site
# hands out memory by the core).
#
# DIR and the scene must be at the same path on every node (a shared file
# system), and the pm programs too (PM_BIN, or PATH at submission, which
# sbatch passes on). The two job scripts are written to DIR as pass.sbatch
# and average.sbatch with every setting in them, so a failed task can be run
# again alone, from any shell, with the same settings (the message printed
# on submission says how).
set -eu
if [ $# -lt 2 ] || [ $# -gt 3 ]; then
	echo "usage: slurm.sh SCENE DIR [N]" >&2
	exit 2
fi
N=${3:-${N:-8}}
case $N in
'' | *[!0-9]* | 0*) echo "slurm.sh: N: '$N': not a whole number from 1" >&2; exit 2 ;;
esac
[ -r "$1" ] || { echo "slurm.sh: cannot read '$1'" >&2; exit 1; }
command -v sbatch >/dev/null ||
	{ echo "slurm.sh: cannot submit: 'sbatch' is not on PATH" >&2; exit 1; }
here=$(cd "$(dirname "$0")" && pwd)
scene=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
mkdir -p "$2"
dir=$(cd "$2" && pwd)
case $dir in *'"'*) echo "slurm.sh: '$dir': sbatch cannot take a '\"' in a path" >&2; exit 1 ;; esac

# q WORD: WORD quoted for sh.
q() { printf "'%s'" "$(printf '%s' "$1" | sed "s/'/'\\\\''/g")"; }

# preamble NAME OUTPUT: the #SBATCH lines both job scripts begin with.
preamble() {
	echo '#!/bin/sh'
	echo "#SBATCH --job-name=$1"
	echo "#SBATCH --chdir=\"$dir\""
	echo "#SBATCH --output=$2"
	[ -n "${PARTITION:-}" ] && echo "#SBATCH --partition=$PARTITION"
	[ -n "${TIME:-}" ] && echo "#SBATCH --time=$TIME"
	return 0
}

{
	preamble pm-pass 'slurm-%A_%a.out'
	echo "#SBATCH --cpus-per-task=${CPUS:-1}"
	echo "# Array task I runs pass I of $N (pass.sh writes pass-I.exr in $dir)."
	echo "export PM_BIN=$(q "${PM_BIN:-}")"
	echo "export PHOTONS=$(q "${PHOTONS:-20000}") SPP=$(q "${SPP:-16}") K=$(q "${K:-50}") EST=$(q "${EST:-compensated}")"
	echo "exec sh $(q "$here/pass.sh") \"\$SLURM_ARRAY_TASK_ID\" $N $(q "$scene")"
} >"$dir/pass.sbatch"

# The average with serial.sh's command, run in DIR, so its bytes are the same.
{
	preamble pm-average 'slurm-%j.out'
	echo '#SBATCH --kill-on-invalid-dep=yes'
	echo 'set -eu'
	echo "PM_BIN=$(q "${PM_BIN:-}")"
	echo 'bin=${PM_BIN:+$PM_BIN/}'
	echo "\"\${bin}pm-average\" -q \$(seq -f 'pass-%g.exr' 1 $N) -o average.exr"
	echo '"${bin}pm-tonemap" -o average.png average.exr'
} >"$dir/average.sbatch"

# --parsable prints "id" or "id;cluster".
passes=$(sbatch --parsable --array="1-$N" "$dir/pass.sbatch")
passes=${passes%%;*}
avg=$(sbatch --parsable --dependency="afterok:$passes" "$dir/average.sbatch") || {
	echo "slurm.sh: cannot submit '$dir/average.sbatch'; the passes are job $passes" >&2
	exit 1
}
avg=${avg%%;*}
cat <<EOF
passes:  job $passes, array 1-$N (logs $dir/slurm-${passes}_I.out)
average: job $avg, once all $N tasks succeed: $dir/average.exr, average.png
watch:   squeue -j $passes,$avg
         sacct -X -j $passes,$avg -o JobID,JobName,State,ExitCode,Elapsed
A failed task leaves its log and cancels the average. Run only the failed
indices again, e.g. 3 and 7, then the average after them (NEW is the job id
the first command prints):
         sbatch --array=3,7 $(q "$dir/pass.sbatch")
         sbatch --dependency=afterok:NEW $(q "$dir/average.sbatch")
EOF
