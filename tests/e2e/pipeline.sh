# pipeline.sh — the programs end to end through pipes: help, usage errors,
# determinism for equal seeds and across thread counts, headers that say
# where a file came from, and a map from another scene refused.
. "$PM_TOP/tests/lib.sh"

cat >box.pms <<'SCENE'
camera eye 0 1 3.4  look 0 1 0  up 0 1 0  fov 45  size 48 36
material white diffuse albedo 0.7 0.7 0.7
material red diffuse albedo 0.6 0.1 0.1
material lamp diffuse albedo 0 0 0 emit 8 8 8
material shiny glossy kd 0.2 0.2 0.2 ks 0.6 0.6 0.6 exponent 400
material glass glass ior 1.5
quad white -1 0 -1  1 0 -1  1 0 1  -1 0 1
quad white -1 2 -1  -1 2 1  1 2 1  1 2 -1
quad white -1 0 -1  -1 2 -1  1 2 -1  1 0 -1
quad red -1 0 -1  -1 0 1  -1 2 1  -1 2 -1
quad shiny 1 0 -1  1 2 -1  1 2 1  1 0 1
quad lamp -0.3 1.99 -0.3  0.3 1.99 -0.3  0.3 1.99 0.3  -0.3 1.99 0.3
box white -0.5 0 -0.5  0 0.6 0
sphere glass 0.4 0.35 0.3 0.3 subdiv 3
pointlight 0.5 1.5 0.5 power 2 2 2
SCENE

for p in pm-shoot pm-build pm-render pm-average pm-dump pm-diff pm-tonemap; do
	$p -h >help.txt 2>&1
	rc=$?
	check "$p -h exits 0 with usage" test $rc -eq 0 -a -s help.txt
	grep -q '^usage: ' help.txt || notok "$p -h shows a usage line" "$(head -n 2 help.txt)"
	expect_fail "$p unknown option exits 2" 2 "$p: " $p --no-such-option
done

# The whole pipeline through pipes, twice with the same seed, and with 1 and
# 2 threads: identical bytes.
pm-shoot -n 20000 -s 1 box.pms | pm-build | pm-render -e classical -s 1 box.pms - -o a.exr
# Outputs record their command lines, so the runs being compared use the
# same file names, in two directories.
mkdir -p j1 j2
(cd j1 && pm-shoot -n 20000 -s 1 -j 1 ../box.pms -o shot.pm && pm-build -j 1 shot.pm -o map.pm)
(cd j2 && pm-shoot -n 20000 -s 1 -j 2 ../box.pms -o shot.pm && pm-build -j 2 shot.pm -o map.pm)
check "pm-shoot -j1 and -j2 give identical photon files" cmp -s j1/shot.pm j2/shot.pm
check "pm-build -j1 and -j2 give identical maps" cmp -s j1/map.pm j2/map.pm
cp j1/shot.pm shot1.pm
cp j1/map.pm map1.pm
for est in classical compensated path; do
	(cd j1 && pm-render -e $est -j 1 -s 9 ../box.pms map.pm -o $est.exr)
	(cd j2 && pm-render -e $est -j 2 -s 9 ../box.pms map.pm -o $est.exr)
	check "pm-render -e $est -j1 and -j2 identical" cmp -s j1/$est.exr j2/$est.exr
done
(cd j1 && pm-render -e classical -s 9 ../box.pms map.pm -o again.exr && pm-render -e classical -s 9 ../box.pms map.pm -o again2.exr)
pm-diff j1/again.exr j1/again2.exr >d0.txt
check "same seed twice gives the same pixels" test "$(kv d0.txt max_abs)" = 0
pm-render -e classical -s 1 box.pms map1.pm -o b.exr
pm-diff a.exr b.exr >d.txt
check "same seed through pipes and files gives the same pixels" test "$(kv d.txt max_abs)" = 0
pm-shoot -n 20000 -s 2 box.pms | pm-build -o map-s2.pm
check "another seed gives other photons" sh -c '! cmp -s map1.pm map-s2.pm'

pm-dump --stats map1.pm >stats.txt
check "photons stored as asked" test "$(kv stats.txt photons)" = 20000
check "bytes_per_photon <= 20" test "$(kv stats.txt bytes_per_photon)" -le 20
check "emitted >= photons / max bounces" test "$(kv stats.txt emitted)" -gt 1000
grep -q 'pm-shoot -n 20000 -s 1' stats.txt || notok "map history names pm-shoot" "$(cat stats.txt)"

# Power is conserved: the stored photons' total flux is what reached
# surfaces after at least one bounce, which is less than what the lights emit
# (8 * pi * 0.36 per channel from the lamp quad + 2 from the point light).
tp=$(kv stats.txt total_power | awk '{print $1}')
awk -v t="$tp" 'BEGIN { exit !(t > 0.5 && t < 8 * 3.14159265 * 0.36 + 2) }' &&
	ok "stored power below emitted power" || notok "stored power below emitted power" "$tp"

# A map of another scene is refused, with --force accepted.
sed 's/albedo 0.7 0.7 0.7/albedo 0.6 0.6 0.6/' box.pms >box2.pms
expect_fail "map of another scene refused" 1 "pm-render: 'map1.pm': photon map of another scene" \
	pm-render -e classical box2.pms map1.pm -o x.exr
check "no output after a refusal" test ! -e x.exr
pm-render -e classical --force box2.pms map1.pm -o x.exr 2>/dev/null
check "--force renders anyway" test -s x.exr
expect_fail "a photon file is not a map" 1 "run it through pm-build" \
	pm-render -e classical box.pms shot1.pm -o y.exr
expect_fail "a map where the scene belongs: the order is said" 1 \
	"^pm-render: 'map1.pm': a photon file where the scene belongs: the order is SCENE MAP$" \
	pm-render map1.pm box.pms -o y.exr
expect_fail "pm-shoot given a photon file as its scene says so" 1 \
	"^pm-shoot: 'map1.pm': a photon file, not a scene$" pm-shoot map1.pm -o z.pm
expect_fail "missing scene named" 1 "nonexistent.pms" pm-shoot nonexistent.pms -o z.pm
expect_fail "estimator needs a map" 2 "needs a photon map" pm-render -e classical box.pms -o y.exr

# Limits a typo cannot blow past, and the options that raise them.
expect_fail "pm-shoot -n above the limit refused" 2 "more than 100000000 photons" pm-shoot -n 200000000 box.pms -o big.pm
check "nothing written past the limit" test ! -e big.pm
expect_fail "--max-photons lowers the limit" 2 "more than 1000 photons" pm-shoot --max-photons 1000 -n 2000 box.pms -o big.pm
pm-shoot --max-photons 200000000 -n 100 box.pms -o small.pm
check "--max-photons raises the limit" test -s small.pm
expect_fail "pm-render -p above the limit refused" 2 "more than 65536 samples" pm-render -e path -p 100000 box.pms -o big.exr
pm-render -e path --max-samples 100 -p 70 box.pms -o ok.exr 2>/dev/null
check "--max-samples accepts up to the limit" test -s ok.exr
