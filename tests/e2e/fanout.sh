# fanout.sh — the same 8 pass pairs run four ways (a shell loop, xargs -P,
# GNU parallel with -S :, make -j; examples/fanout/) give byte-identical pass
# images and averages; a subset in reverse order gives the same passes; both
# halves of a pair derive the same seed and time from -P I/N, and a pair
# whose halves disagree is refused.
. "$PM_TOP/tests/lib.sh"

ex=$PM_TOP/examples/fanout
export PM_BIN PHOTONS=4000 SPP=2 N=8 P=2
for way in serial xargs parallel make; do
	sh "$ex/$way.sh" "$ex/scene.pms" "$way" >"$way.log" 2>&1
	check "fan-out $way runs" test $? -eq 0 -a -s "$way/average.exr"
	check "fan-out $way ends with a summary line" grep -q "^$way.sh: 8 passes, [0-9.]* s, relative standard error " "$way.log"
done
for way in xargs parallel make; do
	check "fan-out $way average byte-identical to serial" cmp -s serial/average.exr "$way/average.exr"
	same=0
	for i in 1 2 3 4 5 6 7 8; do cmp -s "serial/pass-$i.exr" "$way/pass-$i.exr" && same=$((same + 1)); done
	check "fan-out $way: all 8 pass images byte-identical to serial" test "$same" -eq 8
done
check "passes differ from each other" sh -c '! cmp -s serial/pass-1.exr serial/pass-2.exr'
pm-average --stats serial/average.exr >stats.txt
check "the average stands for 8 passes" test "$(kv stats.txt passes)" = 8

# Any subset, any order: passes 7 and 2 alone, 7 first.
mkdir -p subset
(cd subset && for i in 7 2; do sh "$ex/pass.sh" $i 8 "$PM_TOP/examples/fanout/scene.pms"; done)
# The scene path differs in the recorded command when given another way, so
# compare pixels here, and bytes when the path is the same string.
scene=$(cd "$ex" && pwd)/scene.pms
(cd subset && sh "$ex/pass.sh" 5 8 "$scene")
check "pass 5 alone is byte-identical to pass 5 of the serial run" cmp -s subset/pass-5.exr serial/pass-5.exr
for i in 7 2; do
	pm-diff "subset/pass-$i.exr" "serial/pass-$i.exr" >d.txt
	check "pass $i run alone has the same pixels" test "$(kv d.txt max_abs)" = 0
done

# The derived time is recorded; the 8 times are one per eighth of [0, 1).
strat=0
for i in 1 2 3 4 5 6 7 8; do
	t=$("$PM_BIN/../tests/tools/exrattr" "serial/pass-$i.exr" | sed -n 's/^pm.time=//p')
	awk -v t="$t" -v i=$i 'BEGIN { exit !(t >= (i - 1) / 8 && t < i / 8) }' && strat=$((strat + 1))
done
check "pass i of 8 has its time in [(i-1)/8, i/8)" test "$strat" -eq 8

# -s and -t override what -P derives; a pair whose halves disagree is refused.
pm-shoot -q -n 2000 -P 3/8 "$scene" -o p3.pm
pm-shoot -q -n 2000 -P 3/8 -s 99 -t 0.5 "$scene" -o p3s.pm
pm-dump --header p3s.pm >h.txt
check "-s and -t override -P" sh -c 'grep -q "^seeds=99$" h.txt && grep -q "^time=0.5$" h.txt'
pm-build -q p3.pm -o m3.pm
expect_fail "halves of different passes refused" 1 "pm-render: 'm3.pm': photon map is of time" \
	pm-render -q -e classical -P 4/8 "$scene" m3.pm -o x.exr
pm-render -q -e classical -P 3/8 "$scene" m3.pm -o ok.exr
check "halves of the same pass agree" test -s ok.exr
for bad in 0/8 9/8 3 3/0 x/8; do
	expect_fail "pm-shoot -P $bad refused" 2 "pm-shoot: -P: '$bad'" pm-shoot -P $bad "$scene" -o x.pm
	expect_fail "pm-render -P $bad refused" 2 "pm-render: -P: '$bad'" pm-render -P $bad "$scene" m3.pm -o x.exr
done
