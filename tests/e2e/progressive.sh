# progressive.sh — examples/progressive.sh adds rounds of pass pairs until
# the relative standard error (mean_stderr / mean of pm-average --stats)
# falls below the target: it stops at the first round below it, not before
# and not after, writes a preview per round, gives up with exit 1 after
# ROUNDS, and its running average (average of averages) equals the flat
# average of every pass it ran.
. "$PM_TOP/tests/lib.sh"
prog=$PM_TOP/examples/progressive.sh
scene=$PM_TOP/examples/fanout/scene.pms
export PM_BIN PHOTONS=3000 SPP=2 FIRST=2 P=2

# Unreachable target, 3 rounds: exit 1, and the per-round errors to calibrate.
OUT=cap ROUNDS=3 sh "$prog" "$scene" 1e-9 >cap.txt 2>cap.err
check "an unreachable target stops after ROUNDS rounds with exit 1" test $? -eq 1 -a "$(grep -c '^round ' cap.txt)" -eq 3
check "... and says so" grep -q 'not reached after 3 rounds' cap.err
rel() { sed -n "s/^round $1: .* relative //p" cap.txt; }
r2=$(rel 2) r3=$(rel 3)
check "the error estimate falls from round 2 to round 3 ($r2 -> $r3)" awk -v a="$r2" -v b="$r3" 'BEGIN { exit !(b < a) }'

# A target between rounds 2 and 3: it must stop at round 3.
target=$(awk -v a="$r2" -v b="$r3" 'BEGIN { printf "%.9g", (a + b) / 2 }')
OUT=run ROUNDS=6 sh "$prog" "$scene" "$target" >run.txt 2>run.err
check "target $target reached: exit 0" test $? -eq 0
check "stopped at round 3" test "$(grep -c '^round ' run.txt)" -eq 3 -a ! -e run/round-4.exr
f=$(sed -n 's/^round 3: .* relative //p' run.txt)
check "final relative error $f below the target" awk -v a="$f" -v t="$target" 'BEGIN { exit !(a < t) }'
check "round 2 was not below the target" awk -v a="$(sed -n 's/^round 2: .* relative //p' run.txt)" -v t="$target" 'BEGIN { exit !(a >= t) }'
for r in 1 2 3; do
	check "preview of round $r" test -s run/round-$r.png
done
pm-average --stats run/image.exr >s.txt
check "the running average holds 2+4+8 passes" test "$(kv s.txt passes)" = 14
check "... 14 distinct ones, by their pass ids" \
	test "$("$PM_BIN/../tests/tools/exrattr" run/image.exr pm.pass_ids | tr ' ' '\n' | sort -u | wc -l)" -eq 14
pm-average -q run/round-1/pass-*.exr run/round-2/pass-*.exr run/round-3/pass-*.exr -o flat.exr
pm-diff run/image.exr flat.exr >d.txt
num_near "running average = flat average of all 14 passes" "$(kv d.txt max_abs)" 0 1e-5
pm-average --stats flat.exr >sf.txt
num_near "its mean_stderr agrees with the flat average's" "$(kv sf.txt mean_stderr)" "$(kv s.txt mean_stderr)" 1e-7
expect_fail "a target that is not a number is refused" 2 "TARGET 'x'" sh "$prog" "$scene" x
