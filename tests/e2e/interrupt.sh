# interrupt.sh — nothing lost: programs killed (SIGINT, SIGTERM, SIGKILL)
# while computing or while writing leave the previous output intact and no
# temporary file behind, with O_TMPFILE and with the named-temporary
# fallback (PM_ATOMIC_NAMED=1, lib/base/atomic.h) whose names the tools' signal
# handler removes. SIGKILL cannot be caught: with the named fallback it may
# leave a hidden ".NAME.pm-tmp-XXXXXX" (documented), so it is tested with
# O_TMPFILE only.
. "$PM_TOP/tests/lib.sh"
mk="$PM_BIN/../tests/tools/mkphotons"
scene="$PM_TOP/examples/cornell/cornell.pms"

"$mk" -n 400000 -s 1 -o big.pm
mkdir w

# start SIG NAMED WHEN CMD...: runs CMD in w/ (SIGINT not ignored, as it
# would be for a background job of a script), kills it with SIG once WHEN
# holds ("computing": after a moment; "writing": once it has a file open in
# w/), and leaves the exit status in $rc.
start() {
	sig=$1 named=$2 when=$3; shift 3
	(cd w && PM_ATOMIC_NAMED=$named exec env --default-signal=INT "$@" 2>/dev/null) &
	pid=$!
	i=0
	if [ "$when" = writing ]; then
		while [ $i -lt 400 ]; do
			ls -l /proc/$pid/fd 2>/dev/null | grep -q "$PWD/w/" && break
			sleep 0.02; i=$((i + 1))
		done
	else
		sleep 0.5
	fi
	had=$(ls -A w | grep -c pm-tmp)
	kill -s "$sig" $pid 2>/dev/null
	wait $pid 2>/dev/null
	rc=$?
}

# after NAME OUT WANTRC: the old OUT is intact, w/ holds nothing else, and
# the program died of the signal (or, rarely, finished first: then OUT
# must be whole, which the reader checks).
after() {
	nm=$1 out=$2 want=$3
	if [ "$rc" -eq "$want" ]; then
		check "$nm: previous output intact" [ "$(cat "w/$out")" = old ]
	else
		check "$nm: finished before the signal, output whole (exit $rc)" [ "$rc" -eq 0 ]
	fi
	check "$nm: no temporary left" [ "$(ls -A w | tr '\n' ' ')" = "$out " ]
	rm -rf w; mkdir w
}

for named in 0 1; do
	for sig in INT TERM; do
		case $sig in INT) want=130 ;; TERM) want=143 ;; esac
		echo old >w/out.pm
		start $sig $named computing pm-shoot -q -n 100000000 -o out.pm "$scene"
		after "pm-shoot $sig while shooting (named=$named)" out.pm $want

		echo old >w/out.tsv
		start $sig $named writing pm-dump --tsv ../big.pm -o out.tsv
		[ "$named" = 1 ] && check "pm-dump $sig: a named temporary existed when killed" [ "$had" -eq 1 ]
		after "pm-dump $sig while writing (named=$named)" out.tsv $want
	done
done
echo old >w/out.tsv
start KILL 0 writing pm-dump --tsv ../big.pm -o out.tsv
after "pm-dump KILL while writing" out.tsv 137
echo old >w/out.pm
start KILL 0 computing pm-shoot -q -n 100000000 -o out.pm "$scene"
after "pm-shoot KILL while shooting" out.pm 137
