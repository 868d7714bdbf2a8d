# consistent.sh — pm-render --consistent: pass I of N shrinks the estimate's
# support with I alone, so the average of passes 1..N loses the fixed-K
# bias that no number of passes removes. On the furnace (exact radiance 2)
# with few photons a pass, the bias of a 48-pass average, measured as its
# squared error minus its own noise (pm-average's stderr layer), must be
# well below fixed K's. Also: pass 1 is the fixed mode's image, the mode is
# recorded, and pm-average refuses to mix the modes.
. "$PM_TOP/tests/lib.sh"
T=$PM_BIN/../tests/tools

sed 's/size 40 30/size 32 24/' "$PM_TOP/tests/scenes/furnace.pms" >f.pms
N=48
for i in $(seq 1 $N); do
	pm-shoot -q -j 1 -n 3000 -P $i/$N f.pms -o m.pm && pm-build -q m.pm -o map.pm &&
	pm-render -q -j 1 -e classical -k 40 -p 2 -P $i/$N f.pms map.pm -o fix-$i.exr &&
	pm-render -q -j 1 -e classical -k 40 -p 2 -P $i/$N --consistent 0.5 f.pms map.pm -o con-$i.exr ||
		notok "pass $i renders" "exit $?"
done
"$T/mkimg" -v 2,2,2 two.exr 32 24
"$T/mkimg" -v 0,0,0 -c stderr.R=0 -c stderr.G=0 -c stderr.B=0 zero.exr 32 24
for m in fix con; do
	pm-average -q $(seq -f "$m-%g.exr" 1 $N) -o $m.exr
	mse=$(pm-diff $m.exr two.exr | sed -n 's/^rmse: *//p')
	noise=$(pm-diff -l stderr $m.exr zero.exr | sed -n 's/^rmse: *//p')
	eval "bias_$m=\$(awk -v e=\"\$mse\" -v s=\"\$noise\" 'BEGIN { print e * e - s * s }')"
done
check "consistent bias^2 $bias_con < 0.5 * fixed $bias_fix (48 passes)" \
	awk -v a="$bias_con" -v b="$bias_fix" 'BEGIN { exit !(b > 0 && a < 0.5 * b) }'

check "pass 1 of the consistent mode is the fixed mode's image" \
	sh -c 'pm-diff fix-1.exr con-1.exr | grep -q "^max_abs: 0$"'
"$T/exrattr" con-3.exr pm.consistent >attr.txt 2>&1
check "pm.consistent records alpha" grep -qx 'alpha 0.5' attr.txt
"$T/exrattr" fix-3.exr pm.consistent >attr.txt 2>&1
check "pm.consistent is off in the fixed mode" grep -qx 'off' attr.txt
"$T/exrattr" con-8.exr pm.shrink >attr.txt 2>&1
num_near "pm.shrink of pass 8 is 8^-1/4" "$(cat attr.txt)" 0.594603558 1e-8
"$T/exrattr" con.exr pm.consistent >attr.txt 2>&1
check "the average keeps pm.consistent" grep -qx 'alpha 0.5' attr.txt

expect_fail "pm-average refuses fixed with consistent passes" 1 \
	"con-2.exr'*: consistent mode alpha 0.5 differs from .*fix-1.exr'* (off); --force" \
	pm-average fix-1.exr con-2.exr -o mix.exr
check "no half-written output" test ! -e mix.exr
pm-average -q --force fix-1.exr con-2.exr -o mix.exr
"$T/exrattr" mix.exr pm.consistent >attr.txt 2>&1
check "a forced mix is pm.consistent mixed" grep -qx 'mixed' attr.txt
expect_fail "--consistent needs -P" 2 "^pm-render: --consistent needs -P I/N" \
	pm-render --consistent 0.5 f.pms map.pm -o x.exr
expect_fail "--consistent 1 is refused" 2 "^pm-render: --consistent: ALPHA must be between 0 and 1" \
	pm-render --consistent 1 -P 1/2 f.pms map.pm -o x.exr
expect_fail "--consistent with -e path is refused" 2 "^pm-render: --consistent is for estimates" \
	pm-render --consistent 0.5 -P 1/2 -e path f.pms -o x.exr
