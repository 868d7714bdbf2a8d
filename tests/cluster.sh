# cluster.sh — a throwaway one-node SLURM cluster for the tests in
# tests/cluster/ (make check-cluster); sourced after tests/lib.sh. Runs as
# root: munged with its own key and socket, slurmctld and slurmd in the
# foreground as children of the test, on two free ports, with their
# configuration, state, spool, pid and log files in one temporary directory.
#   cluster_up     start it; exports SLURM_CONF for sbatch, squeue, scancel,
#                  scontrol; 0 when the node takes jobs, else 1 with the
#                  daemons' last log lines on stderr
#   cluster_down   cancel every job, stop the daemons, remove the directory
#                  (installed as the EXIT, INT and TERM trap by cluster_up)
#   job_state ID   the state of job ID ("COMPLETED", ...), one line per task
#                  for an array job, from slurmctld
#   job_wait ID... wait until no task of the jobs is pending or running;
#                  1 after CLUSTER_WAIT seconds (default 300)
cluster_pids= cluster_dir=

# port_free PORT: nothing listens on or talks through TCP port PORT.
port_free() {
	! grep -qi ":$(printf '%04X' "$1") " /proc/net/tcp /proc/net/tcp6 2>/dev/null
}

cluster_log() {
	for f in "$cluster_dir"/*.log "$cluster_dir"/*.err; do
		[ -s "$f" ] && tail -n 15 "$f" | sed "s|^|$(basename "$f"): |" >&2
	done
	return 0
}

cluster_up() {
	[ "$(id -u)" -eq 0 ] || { echo "cluster.sh: cannot start SLURM: needs root" >&2; return 1; }
	trap cluster_down EXIT
	trap 'exit 1' INT TERM
	cluster_dir=$(mktemp -d --suffix=.pm-slurm) || return 1
	# munged wants every directory up to its socket open to all.
	chmod 755 "$cluster_dir"
	c=$cluster_dir
	mkdir "$c/state" "$c/spool"
	mungekey -c -k "$c/munge.key" || return 1
	munged -F --socket="$c/munge.sock" --key-file="$c/munge.key" \
		--pid-file="$c/munged.pid" --seed-file="$c/munged.seed" \
		--log-file="$c/munged.log" 2>>"$c/munged.err" &
	m=$!
	cluster_pids=$m
	n=0
	until [ -S "$c/munge.sock" ]; do
		n=$((n + 1))
		[ $n -le 50 ] && kill -0 "$m" 2>/dev/null || {
			echo "cluster.sh: munged did not start" >&2; cluster_log; return 1; }
		sleep 0.1
	done
	port=$((20000 + $$ % 20000))
	until port_free $port && port_free $((port + 1)); do port=$((port + 2)); done
	host=$(hostname -s)
	# No cgroups (containers): processes are tracked by parent pid; no task
	# binding; cons_tres with CR_CPU lets every core run a task at once.
	cat >"$c/slurm.conf" <<EOF
ClusterName=pmtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$c/munge.sock
CredType=cred/munge
StateSaveLocation=$c/state
SlurmdSpoolDir=$c/spool
SlurmctldPidFile=$c/slurmctld.pid
SlurmdPidFile=$c/slurmd.pid
SlurmctldLogFile=$c/slurmctld.log
SlurmdLogFile=$c/slurmd.log
PlugStackConfig=$c/plugstack.conf
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
MinJobAge=3600
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$c/jobcomp.txt
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=pm Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
	: >"$c/plugstack.conf"
	export SLURM_CONF="$c/slurm.conf"
	slurmctld -D -f "$SLURM_CONF" 2>>"$c/slurmctld.err" &
	ctld=$!
	slurmd -D -f "$SLURM_CONF" 2>>"$c/slurmd.err" &
	d=$!
	cluster_pids="$cluster_pids $ctld $d"
	n=0
	until sinfo -h -N -o %T 2>/dev/null | grep -qx idle; do
		for x in "munged $m" "slurmctld $ctld" "slurmd $d"; do
			set -- $x
			kill -0 "$2" 2>/dev/null && continue
			echo "cluster.sh: $1 exited: $(tail -n 1 "$c/$1.err")" >&2
			cluster_log
			return 1
		done
		n=$((n + 1))
		[ $n -le 60 ] || {
			echo "cluster.sh: node $host not idle after 30 s" >&2; cluster_log; return 1; }
		sleep 0.5
	done
}

cluster_down() {
	trap - EXIT INT TERM
	if [ -n "$cluster_pids" ]; then
		ids=$(squeue -h -o %A 2>/dev/null)
		[ -n "$ids" ] && scancel $ids 2>/dev/null
		# Stop slurmd, slurmctld, then munged; give each 10 s.
		for p in $(echo $cluster_pids | awk '{ for (i = NF; i > 0; i--) print $i }'); do
			kill "$p" 2>/dev/null
			n=0
			while kill -0 "$p" 2>/dev/null && [ $n -lt 100 ]; do n=$((n + 1)); sleep 0.1; done
			kill -9 "$p" 2>/dev/null
		done
		wait 2>/dev/null
	fi
	[ -n "$cluster_dir" ] && rm -rf "$cluster_dir"
	cluster_pids= cluster_dir=
}

job_state() {
	scontrol -o show job "$1" | sed -n 's/.* JobState=\([A-Z_]*\) .*/\1/p'
}

job_wait() {
	n=0
	while for j in "$@"; do job_state "$j"; done |
		grep -q -E 'PENDING|CONFIGURING|RUNNING|COMPLETING|SUSPENDED|REQUEUE'; do
		n=$((n + 1))
		[ $n -le $((${CLUSTER_WAIT:-300} * 2)) ] || return 1
		sleep 0.5
	done
}
