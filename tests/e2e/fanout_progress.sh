# fanout_progress.sh — the fan-out scripts (examples/fanout/progress.sh)
# show one overall progress line on stderr instead of the programs' own
# bars: rewritten in place at a terminal, a line per tenth elsewhere (not
# one per pass), and always a final summary line whose passes and relative
# standard error are pm-average --stats's; the watcher does not outlive a
# failed run.
. "$PM_TOP/tests/lib.sh"
ex=$PM_TOP/examples/fanout
scene=$ex/scene.pms
export PM_BIN PHOTONS=1000 SPP=1 P=2 TMPDIR="$PWD/tmp"
mkdir -p tmp

# summary_ok NAME ERRFILE LABEL IMAGE: the last stderr line is the summary
# of IMAGE.
summary_ok() {
	pm-average -q --stats "$4" >s.txt
	want=$(awk -v s="$(kv s.txt mean_stderr)" -v m="$(kv s.txt mean)" 'BEGIN { printf "%.4g", s / m }')
	last=$(tail -n 1 "$2" | tr -d '\r')
	check "$1" test "$last" = "$(echo "$last" | grep -x "$3: $(kv s.txt passes) passes, [0-9.]* s, relative standard error $want")"
}

N=8 sh "$ex/xargs.sh" "$scene" x8 2>x8.err
check "xargs.sh runs" test $? -eq 0 -a -s x8/average.exr
summary_ok "off a terminal: a summary line with passes and the relative standard error" x8.err xargs.sh x8/average.exr
check "... after a progress line of all passes done" grep -q '^xargs.sh: 8/8 passes, [0-9.e-]* s/pass, 0:00 left$' x8.err

N=30 sh "$ex/xargs.sh" "$scene" x30 2>x30.err
lines=$(grep -c "^xargs.sh: [0-9]*/30 passes" x30.err)
check "30 passes: at most 12 progress lines, not one per pass ($lines)" test "$lines" -ge 2 -a "$lines" -le 12
check "... the last says 30/30" grep -q "^xargs.sh: 30/30 passes" x30.err
summary_ok "... and the summary counts 30 passes" x30.err xargs.sh x30/average.exr

sh "$ex/make.sh" "$scene" x8 2>resume.err
check "make.sh resuming with nothing left: no progress lines" test "$(grep -c 'passes, .* left' resume.err)" -eq 0
summary_ok "... only the summary" resume.err make.sh x8/average.exr

N=2 OUT=$PWD/out sh "$PM_TOP/examples/passes.sh" "$scene" two >two.out 2>two.err
check "passes.sh runs" test $? -eq 0 -a -s out/two.exr
summary_ok "passes.sh ends with a summary line" two.err two out/two.exr

FIRST=2 ROUNDS=1 OUT=prog sh "$PM_TOP/examples/progressive.sh" "$scene" 1e-9 >prog.out 2>prog.err
check "progressive.sh shows the round's progress" grep -q '^round 1: 2/2 passes' prog.err
check "... and ends with a summary line before its verdict" \
	sh -c "tail -n 2 prog.err | head -n 1 | grep -q '^progressive.sh: 2 passes, [0-9.]* s, relative standard error '"

# A failing run: the watcher goes with it and leaves no log behind.
# (A watcher left behind would hold the pipe open: timeout ends the wait.)
start=$(date +%s)
timeout 30 sh -c '(N=4 sh "$0/xargs.sh" "$1/missing.pms" bad; echo "exit $?") 2>&1 | cat >bad.out' "$ex" "$PWD"
check "a failed run fails" grep -q '^exit [1-9]' bad.out
check "... its watcher ends with it (stderr closed within 10 s)" test $(($(date +%s) - start)) -le 10
check "... and leaves no progress log" test -z "$(ls tmp)"

if ! command -v script >/dev/null 2>&1; then
	ok "script(1) missing: terminal checks skipped"
	exit 0
fi
# At a terminal (a pty from script(1)): one line rewritten in place, none
# of the programs' bars, the summary on a line of its own.
script -qec "N=6 PHOTONS=20000 OUT='$PWD/out' sh '$PM_TOP/examples/passes.sh' '$scene' tty" /dev/null </dev/null >tty.out
check "terminal: the progress line is rewritten in place" grep -q "$(printf '\r')tty: 6/6 passes, .* left" tty.out
check "terminal: no pm-render or pm-average bars" sh -c "! grep -q 'pm-render: rows\|pm-average: images' tty.out"
check "terminal: the summary on its own line" grep -q "^tty: 6 passes, [0-9.]* s, relative standard error [0-9.e-]*$(printf '\r')\$" tty.out
