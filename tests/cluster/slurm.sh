# slurm.sh — examples/fanout/slurm.sh on a one-node SLURM cluster
# (tests/cluster.sh; make check-cluster): the array job writes the same 8
# pass images as serial.sh and the averaging job the same average, byte for
# byte; a failed task keeps the averaging job from running, and rerunning
# that index alone, then the average, with the commands slurm.sh prints,
# gives the same average again.
. "$PM_TOP/tests/lib.sh"
. "$PM_TOP/tests/cluster.sh"

ex=$PM_TOP/examples/fanout
scene=$ex/scene.pms
export PM_BIN PHOTONS=4000 SPP=2 N=8

expect_fail "slurm.sh N=0 refused" 2 "slurm.sh: N: '0'" sh "$ex/slurm.sh" "$scene" x 0
expect_fail "slurm.sh without a scene refused" 1 "slurm.sh: cannot read 'none.pms'" \
	sh "$ex/slurm.sh" none.pms x
expect_fail "slurm.sh without sbatch refused" 1 "slurm.sh: cannot submit: 'sbatch' is not on PATH" \
	env PATH=/nonexistent /bin/sh "$ex/slurm.sh" "$scene" x

if ! cluster_up 2>up.txt; then
	cat up.txt >&2
	notok "one-node SLURM cluster starts" "$(head -n 1 up.txt)"
	exit 1
fi
ok "one-node SLURM cluster starts"

sh "$ex/serial.sh" "$scene" serial >serial.log 2>&1
check "serial.sh runs" test $? -eq 0 -a -s serial/average.exr

# ids OUT: "PASSES AVERAGE", the job ids slurm.sh printed.
ids() {
	echo "$(sed -n 's/^passes: *job \([0-9]*\),.*/\1/p' "$1")" \
		"$(sed -n 's/^average: *job \([0-9]*\),.*/\1/p' "$1")"
}
# task_state JOB I: the state of task I of array job JOB.
task_state() {
	scontrol -o show job "$1" | sed -n "s/.* ArrayTaskId=$2 .* JobState=\([A-Z_]*\) .*/\1/p"
}

# All 8 tasks succeed: the average runs.
sh "$ex/slurm.sh" "$scene" good >good.out 2>good.err
check "slurm.sh submits" test $? -eq 0
set -- $(ids good.out)
p=${1:-} a=${2:-}
check "slurm.sh prints the two job ids" test -n "$p" -a -n "$a"
echo "# good run: passes job $p, average job $a"
sq=$(sed -n 's/^watch: *//p' good.out)
eval "$sq" >squeue.txt 2>&1
check "the squeue command it prints runs" test $? -eq 0 -a -s squeue.txt
job_wait "$p" "$a"
check "the jobs end within ${CLUSTER_WAIT:-300} s" test $? -eq 0
echo "# $(job_state "$p" | sort | uniq -c | tr -s ' \n' '  ')tasks; average $(job_state "$a")"
check "all 8 tasks COMPLETED" test "$(job_state "$p" | grep -c '^COMPLETED$')" -eq 8
check "the averaging job COMPLETED" test "$(job_state "$a")" = COMPLETED
check "SLURM average byte-identical to serial" cmp -s serial/average.exr good/average.exr
same=0
for i in 1 2 3 4 5 6 7 8; do cmp -s "serial/pass-$i.exr" "good/pass-$i.exr" && same=$((same + 1)); done
check "all 8 pass images byte-identical to serial" test "$same" -eq 8
check "the averaging job writes a PNG" sh -c 'head -c 4 good/average.png | grep -q PNG'

# Pass 3 cannot write its image (a directory is in the way): the average
# never runs. Then index 3 alone and the average, as slurm.sh says (in a
# directory with a blank in its name, which the job scripts must quote).
mkdir -p 'bad run'/pass-3.exr
sh "$ex/slurm.sh" "$scene" 'bad run' >bad.out 2>bad.err
set -- $(ids bad.out)
p=${1:-} a=${2:-}
echo "# broken run: passes job $p, average job $a"
job_wait "$p" "$a"
check "the broken run's jobs end" test $? -eq 0
check "task 3 FAILED" test "$(task_state "$p" 3)" = FAILED
check "its log says why" grep -q "pm-render: cannot write 'pass-3.exr': that names a directory" "bad run/slurm-${p}_3.out"
check "the other 7 tasks COMPLETED" test "$(job_state "$p" | grep -c '^COMPLETED$')" -eq 7
check "a failed task cancels the averaging job" test "$(job_state "$a")" = CANCELLED
check "the averaging job never ran" test ! -e "bad run/slurm-$a.out" -a ! -e 'bad run'/average.exr
rmdir 'bad run'/pass-3.exr
cmd=$(sed -n 's/^ *sbatch --array=3,7 /sbatch --array=3 /p' bad.out)
r=$(eval "$cmd" | sed -n 's/^Submitted batch job //p')
cmd=$(sed -n "s/^ *sbatch --dependency=afterok:NEW /sbatch --dependency=afterok:$r /p" bad.out)
a=$(eval "$cmd" | sed -n 's/^Submitted batch job //p')
echo "# rerun: index 3 job $r, average job $a"
check "the printed commands resubmit index 3 and the average" test -n "$r" -a -n "$a"
job_wait "$r" "$a"
check "index 3 alone COMPLETED, then the average" \
	test "$(job_state "$r")/$(job_state "$a")" = COMPLETED/COMPLETED
check "the repaired average byte-identical to serial" cmp -s serial/average.exr 'bad run'/average.exr
