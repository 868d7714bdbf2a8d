# image_tools.sh — pm-average, pm-diff and pm-tonemap on images made by
# mkimg, with answers computed by hand.
. "$PM_TOP/tests/lib.sh"
T="$PM_BIN/../tests/tools"
H=0123456789abcdef

# ---- pm-average: weights by pm.passes ----
# a: an average of 3 passes of value 1 whose M2 is 0.5; b: one pass of 4.
"$T/mkimg" -v 1,1,1 -a pm.passes=3 -a pm.scene_hash=$H -a pm.k=50 -a pm.estimator=compensated \
	-c m2.R=0.5 -c m2.G=0.5 -c m2.B=0.5 -c direct.R=2 a.exr 8 6
"$T/mkimg" -v 4,4,4 -a pm.scene_hash=$H -a pm.k=40 -a pm.estimator=compensated -c direct.R=6 b.exr 8 6
pm-average a.exr b.exr -o ab.exr --stats >stats.txt
check "average exits 0" test $? -eq 0
check "average passes" test "$(kv stats.txt passes)" = 4
# (3*1 + 4) / 4 = 1.75
num_near "average weighted mean" "$(kv stats.txt mean)" 1.75 1e-6
# M2 = 0.5 + 3^2 * 3*1/4 = 7.25; stderr = sqrt(7.25 / 3 / 4)
num_near "average mean_stderr" "$(kv stats.txt mean_stderr)" 0.777281 1e-5
"$T/mkimg" -v 1.75,1.75,1.75 -c direct.R=3 c175.exr 8 6
pm-diff ab.exr c175.exr >d.txt
num_near "average pixels match the weighted mean" "$(kv d.txt max_abs)" 0 1e-6
expect_fail "a layer needs all of .R .G .B" 1 "^pm-diff: 'ab.exr': no channel 'direct.G'$" \
	pm-diff --layer direct ab.exr c175.exr
check "average writes pm.passes" test "$("$T/exrattr" ab.exr pm.passes)" = 4
check "average keeps an agreeing pm.estimator" test "$("$T/exrattr" ab.exr pm.estimator)" = compensated
check "average keeps pm.scene_hash" test "$("$T/exrattr" ab.exr pm.scene_hash)" = $H
check "average drops a disagreeing pm.k" sh -c "! '$T/exrattr' ab.exr pm.k"
check "average records its command" test "$("$T/exrattr" ab.exr pm.command)" = "pm-average a.exr b.exr -o ab.exr --stats"
"$T/exrattr" ab.exr >attrs.txt
check "average writes m2 and stderr layers" grep -q '^channel stderr.G$' attrs.txt
check "average averages the shared direct.R" grep -q '^channel direct.R$' attrs.txt
"$T/mkimg" -v 3.5,3.5,3.5 -c direct.R=3 want.exr 8 6
pm-diff --layer direct.R ab.exr want.exr >d.txt
num_near "average weights other layers the same (direct.R = 3)" "$(kv d.txt max_abs)" 0 1e-6

# ---- averages of averages equal the average of all passes ----
for i in 1 2 3 4 5; do
	"$T/mkimg" -v "$i.5,$((i * i)),0.$i" -a pm.scene_hash=$H p$i.exr 4 3
done
pm-average p1.exr p2.exr p3.exr p4.exr p5.exr -o all.exr
pm-average p1.exr p2.exr -o h1.exr
pm-average p3.exr p4.exr -o h2.exr
pm-average h1.exr p5.exr -o h3.exr
pm-average h2.exr h3.exr -o tree.exr --stats >tree.txt
check "tree of averages counts 5 passes" test "$(kv tree.txt passes)" = 5
for layer in "" m2 stderr; do
	pm-diff ${layer:+--layer $layer} tree.exr all.exr >d.txt
	num_near "tree of averages equals flat average ${layer:-beauty}" "$(kv d.txt max_abs)" 0 2e-5
done
# stderr = sqrt(sample variance / n) per channel, computed here with awk
sd() { awk -v list="$1" 'BEGIN { n = split(list, v, " "); for (i = 1; i <= n; i++) m += v[i] / n
	for (i = 1; i <= n; i++) s += (v[i] - m) ^ 2; printf "%.9g", sqrt(s / (n - 1) / n) }'; }
"$T/mkimg" -c stderr.R="$(sd '1.5 2.5 3.5 4.5 5.5')" -c stderr.G="$(sd '1 4 9 16 25')" \
	-c stderr.B="$(sd '0.1 0.2 0.3 0.4 0.5')" se.exr 4 3
pm-diff --layer stderr all.exr se.exr >d.txt
num_near "stderr = sqrt(var / n) per channel" "$(kv d.txt max_abs)" 0 1e-5

# ---- 1000 inputs, O(image) memory ----
set --
for i in $(seq 500); do set -- "$@" p1.exr p3.exr; done
pm-average --stats "$@" -o k.exr >k.txt
check "1000 inputs" test "$(kv k.txt passes)" = 1000
num_near "1000 inputs: mean of (1.5,1,0.1) and (3.5,9,0.3)" "$(kv k.txt mean)" 2.56666667 1e-6
# half the passes at each value: stderr = (difference / 2) / sqrt(999)
d=$(awk 'BEGIN { printf "%.9g", sqrt(999) }')
"$T/mkimg" -c stderr.R="$(awk "BEGIN { printf \"%.9g\", 1 / $d }")" \
	-c stderr.G="$(awk "BEGIN { printf \"%.9g\", 4 / $d }")" \
	-c stderr.B="$(awk "BEGIN { printf \"%.9g\", 0.1 / $d }")" kse.exr 4 3
pm-diff --layer stderr k.exr kse.exr >d.txt
num_near "1000 inputs: stderr" "$(kv d.txt max_abs)" 0 1e-6

# ---- refusals ----
"$T/mkimg" -a pm.scene_hash=$H small.exr 4 4
expect_fail "average refuses a different size" 1 "^pm-average: 'small.exr': size 4x4 differs from 'a.exr' (8x6)$" \
	pm-average a.exr small.exr -o x.exr
"$T/mkimg" -v 4,4,4 -a pm.scene_hash=fedcba9876543210 other.exr 8 6
expect_fail "average refuses a different scene hash" 1 \
	"^pm-average: 'other.exr': scene hash fedcba9876543210 differs from 'a.exr' ($H)$" \
	pm-average a.exr other.exr -o x.exr
check "refusal leaves no output" test ! -e x.exr
pm-average -q --force a.exr other.exr -o forced.exr 2>err.txt
check "--force averages anyway" test $? -eq 0 -a ! -s err.txt
check "--force output has no scene hash" sh -c "! '$T/exrattr' forced.exr pm.scene_hash"
pm-average --force a.exr other.exr -o forced.exr 2>err.txt
check "--force without -q warns" grep -q "differs from 'a.exr'.*averaging anyway" err.txt
"$T/mkimg" -n 2,1 -a pm.scene_hash=$H nan.exr 8 6
expect_fail "average refuses NaN naming file and pixel" 1 "^pm-average: 'nan.exr': channel 'G' pixel (2, 1) is nan$" \
	pm-average a.exr nan.exr -o x.exr
"$T/mkimg" -a pm.passes=two bad.exr 8 6
expect_fail "average refuses a bad pm.passes" 1 "'bad.exr': pm.passes 'two'" pm-average a.exr bad.exr -s
expect_fail "average: missing input named" 1 "^pm-average: cannot open 'nope.exr': No such file" \
	pm-average a.exr nope.exr -o x.exr
printf 'not an image\n' >junk.exr
expect_fail "average: non-EXR input" 1 "^pm-average: 'junk.exr': not an OpenEXR file$" pm-average junk.exr -s
cp a.exr keep.exr
pm-average a.exr nope.exr -o keep.exr 2>/dev/null
check "failed run leaves an existing output untouched" cmp -s a.exr keep.exr
expect_fail "average: output in a missing directory" 1 "'no/dir/x.exr'" pm-average a.exr -o no/dir/x.exr
check "nothing left behind" test ! -e no -a -z "$(ls -A | grep '^\.')"

# ---- pm-diff ----
"$T/mkimg" -v 1,1,1 one.exr 5 4
"$T/mkimg" -v 1.5,1.5,1.5 onehalf.exr 5 4
pm-diff one.exr onehalf.exr >d.txt
num_near "diff rmse" "$(kv d.txt rmse)" 0.5 1e-7
num_near "diff mae" "$(kv d.txt mae)" 0.5 1e-7
num_near "diff max_abs" "$(kv d.txt max_abs)" 0.5 1e-7
# 0.25 / (1.5^2 + 0.01)
num_near "diff relmse" "$(kv d.txt relmse)" 0.110619469 1e-8
num_near "diff mean_a" "$(kv d.txt mean_a)" 1 1e-9
num_near "diff mean_b" "$(kv d.txt mean_b)" 1.5 1e-9
check "diff pixels" test "$(kv d.txt pixels)" = 20
# ramp mask: R = x, so R > 0.5 keeps columns 1..4 of 5
"$T/mkimg" -p ramp mask.exr 5 4
"$T/mkimg" -p ramp ramp.exr 5 4
pm-diff --mask mask.exr one.exr onehalf.exr >d.txt
check "diff --mask counts selected pixels" test "$(kv d.txt pixels)" = 16
# the ramp is R = x, G = y, B = x + 5y; the mask keeps x = 1..4
pm-diff -m mask.exr ramp.exr one.exr >d.txt
num_near "diff --mask mean_a over kept pixels" "$(kv d.txt mean_a)" "$(awk 'BEGIN { for (x = 1; x < 5; x++) for (y = 0; y < 4; y++) s += x + y + x + 5 * y; printf "%.9g", s / 48 }')" 1e-6
"$T/mkimg" -c direct.R=1 -c direct.G=2 -c direct.B=3 la.exr 5 4
"$T/mkimg" -c direct.R=1 -c direct.G=2 -c direct.B=5 lb.exr 5 4
pm-diff --layer direct la.exr lb.exr >d.txt
num_near "diff --layer compares that layer" "$(kv d.txt max_abs)" 2 1e-9
expect_fail "diff: size mismatch" 1 "^pm-diff: 'one.exr': size 5x4 differs from 'a.exr' (8x6)$" pm-diff one.exr a.exr
expect_fail "diff: missing layer" 1 "^pm-diff: 'one.exr': no channel 'direct.R'$" pm-diff -l direct one.exr onehalf.exr
"$T/mkimg" -n 4,3 nan5.exr 5 4
expect_fail "diff refuses NaN naming file and pixel" 1 "^pm-diff: 'nan5.exr': channel 'G' pixel (4, 3) is nan$" \
	pm-diff one.exr nan5.exr
"$T/mkimg" -v 0,0,0 zero.exr 5 4
expect_fail "diff: empty mask" 1 "mask selects no pixels" pm-diff -m zero.exr one.exr onehalf.exr
expect_fail "diff: missing input named" 1 "^pm-diff: cannot open 'nope.exr'" pm-diff one.exr nope.exr

# ---- pm-tonemap ----
"$T/mkimg" -v 0.5,0.25,0 half.exr 7 3
pm-tonemap -c clamp -e 0 half.exr -o t.png
check "tonemap PNG signature" test "$(od -An -tx1 -N8 t.png | tr -d ' \n')" = 89504e470d0a1a0a
# IHDR: width and height as big-endian 32-bit numbers at bytes 16..23
check "tonemap PNG size in IHDR" test "$(od -An -tx1 -j16 -N8 t.png | tr -d ' \n')" = 0000000700000003
check "tonemap pixel: 0.5 -> 188, 0.25 -> 137, 0 -> 0" test "$("$T/pngpix" t.png 6 2 | tail -n 1)" = "188 137 0"
pm-tonemap -c clamp --exposure -1 half.exr -o t.png
check "tonemap EV -1 halves: 0.25 -> 137" test "$("$T/pngpix" t.png 0 0 | tail -n 1)" = "137 99 0"
pm-tonemap -c clamp -e 1 -l direct la.exr -o t.png
check "tonemap --layer and EV +1: 1,2,3 -> 255" test "$("$T/pngpix" t.png 0 0 | tail -n 1)" = "255 255 255"
pm-tonemap -c clamp -e -2 -l direct la.exr -o t.png
check "tonemap --layer: 0.25,0.5,0.75" test "$("$T/pngpix" t.png 0 0 | tail -n 1)" = "137 188 225"
pm-tonemap half.exr -o - >stdout.png
check "tonemap to stdout" test "$("$T/pngpix" stdout.png | head -n 1)" = "7 3"
expect_fail "tonemap: missing input named" 1 "^pm-tonemap: cannot open 'nope.exr': No such file" pm-tonemap nope.exr -o t2.png
expect_fail "tonemap: missing layer" 1 "^pm-tonemap: 'half.exr': no channel 'x.R'$" pm-tonemap -l x half.exr -o t2.png
expect_fail "tonemap: output in a missing directory" 1 "'no/dir/t.png'" pm-tonemap half.exr -o no/dir/t.png
check "tonemap: no output after failures" test ! -e t2.png -a ! -e no

# ---- command lines ----
for p in pm-average pm-diff pm-tonemap; do
	$p -h >h.txt 2>&1
	check "$p -h exits 0" test $? -eq 0
	check "$p -h lists options with defaults" grep -q default h.txt
	$p --no-such-option a.exr >/dev/null 2>err.txt
	check "$p bad option exits 2" test $? -eq 2
	check "$p bad option says so" grep -q "^$p: unknown option '--no-such-option'" err.txt
done
pm-tonemap -e x a.exr -o t.png 2>/dev/null
check "tonemap: bad exposure exits 2" test $? -eq 2
pm-average a.exr 2>/dev/null
check "average: nothing to do exits 2" test $? -eq 2
pm-diff a.exr 2>/dev/null
check "diff: one image exits 2" test $? -eq 2
