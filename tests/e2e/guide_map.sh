# guide_map.sh — importance sampling by the photon map where camera paths go
# on from a strong glossy surface: pm-shoot --guide keeps the photons that
# reach such surfaces (checked against the scene's geometry here), and
# pm-render --guide draws part of the continuations from their incoming
# directions without moving the mean (path tracer and photon estimate,
# against BSDF sampling alone, with an area light so the light samples'
# weights are exercised) while lowering the noise where the light comes from
# a small part of the hemisphere.
. "$PM_TOP/tests/lib.sh"
dump=$PM_BIN/../tests/tools/exrstat

# A dark room lit by a patch of ceiling; the camera looks at its strong
# glossy floor (tests/scenes/glossyroom.pms).
cp "$PM_TOP/tests/scenes/glossyroom.pms" gs.pms
pm-shoot -q -n 100000 -s 1 gs.pms --guide gd.pm -o g.pm
pm-dump --stats gd.pm >gd.txt
pm-dump --stats g.pm >g.txt
check "guide file says map: guide" test "$(kv gd.txt map)" = guide
check "guide file is version 2" test "$(kv gd.txt version)" = 2
check "same light paths: emitted equal" test "$(kv gd.txt emitted)" = "$(kv g.txt emitted)"
ng=$(kv gd.txt photons)
check "guide photons found ($ng)" test "$ng" -gt 2000
# Every guide photon lies on the glossy floor and arrived from above it;
# the global map, which stores none on strong glossy surfaces, has none there.
pm-dump --tsv gd.pm | awk 'NR > 1 {
	if ($2 < 0.0009 || $2 > 0.0011) off++
	if (!($5 > 0)) below++
} END { printf "off: %d\nbelow: %d\n", off, below }' >on.txt
check "every guide photon is on the glossy floor" test "$(kv on.txt off)" = 0
check "every guide photon came from above" test "$(kv on.txt below)" = 0
pm-dump --tsv g.pm | awk 'NR > 1 && $2 > 0.0009 && $2 < 0.0011 && $1 * $1 < 3.9 && $3 * $3 < 8.9 { n++ }
	END { print "floor: " n + 0 }' >gf.txt
check "the global map has no photon on the glossy floor" test "$(kv gf.txt floor)" = 0
# No strong glossy surface (mirror and glass do not count: their
# continuations are deltas), no guide photons.
pm-shoot -q -n 20000 -s 3 "$PM_TOP/examples/caustic/caustic.pms" --guide e.pm -o e_g.pm
pm-dump --stats e.pm >e.txt
check "caustic scene (mirror, glass): empty guide map" test "$(kv e.txt photons)" = 0

pm-build -q g.pm -o gm.pm
pm-build -q gd.pm -o gdm.pm
# The same mean, less noise: eight view seeds each (the means of eight
# differ by about 1 % from one set of seeds to another).
for s in 1 2 3 4 5 6 7 8; do
	pm-render -q -p 64 -s $s gs.pms gm.pm -o b$s.exr
	pm-render -q -p 64 --guide gdm.pm -s $s gs.pms gm.pm -o i$s.exr
done
mb=$(for s in 1 2 3 4 5 6 7 8; do "$dump" b$s.exr | kv /dev/stdin mean; done | awk '{ s += $1 } END { print s / NR }')
mi=$(for s in 1 2 3 4 5 6 7 8; do "$dump" i$s.exr | kv /dev/stdin mean; done | awk '{ s += $1 } END { print s / NR }')
num_near "guided and BSDF sampling: the same mean ($mi vs $mb)" "$(awk -v a="$mi" -v b="$mb" 'BEGIN { print a / b }')" 1 0.03
nb=$(pm-diff b1.exr b2.exr | kv /dev/stdin rmse)
ni=$(pm-diff i1.exr i2.exr | kv /dev/stdin rmse)
check "guided continuations: less noise ($ni vs $nb)" awk -v a="$ni" -v b="$nb" 'BEGIN { exit !(a < 0.8 * b) }'

# An area light and a strong glossy floor (the Cornell box's): the light
# samples at the floor are weighted against continuations drawn from the
# mixture, so a wrong density there would move the mean. Path tracer and
# compensated estimate, each guided against unguided, four seeds each.
sed -e 's/size 256 256/size 32 32/' \
    -e 's/^quad white  552.8 0 0 /quad floor  552.8 0 0 /' \
    -e 's/^material white .*/&\nmaterial floor glossy kd 0.4 0.4 0.4 ks 0.35 0.35 0.35 exponent 300/' \
    "$PM_TOP/examples/cornell/cornell.pms" >cb.pms
cp "$PM_TOP/examples/cornell/"*.obj .
pm-shoot -q -n 100000 -s 2 cb.pms --guide cgd.pm | pm-build -q -o cm.pm
pm-build -q cgd.pm -o cgdm.pm
pm-dump --stats cgdm.pm >cg.txt
check "cornell with a glossy floor: guide photons ($(kv cg.txt photons))" test "$(kv cg.txt photons)" -gt 5000
for e in path compensated; do
	for s in 1 2 3 4; do
		pm-render -q -e $e -p 64 -s $s cb.pms cm.pm -o cb$s.exr
		pm-render -q -e $e -p 64 --guide cgdm.pm -s $s cb.pms cm.pm -o ci$s.exr
	done
	mb=$(for s in 1 2 3 4; do "$dump" cb$s.exr | kv /dev/stdin mean; done | awk '{ s += $1 } END { print s / NR }')
	mi=$(for s in 1 2 3 4; do "$dump" ci$s.exr | kv /dev/stdin mean; done | awk '{ s += $1 } END { print s / NR }')
	num_near "cornell, glossy floor, -e $e: guided mean = BSDF mean ($mi vs $mb)" "$(awk -v a="$mi" -v b="$mb" 'BEGIN { print a / b }')" 1 0.015
done

# Threads change nothing; the image records the guide map.
mkdir -p j1 j3
(cd j1 && pm-render -q -j 1 -p 4 --guide ../gdm.pm -s 4 ../gs.pms ../gm.pm -o j.exr)
(cd j3 && pm-render -q -j 3 -p 4 --guide ../gdm.pm -s 4 ../gs.pms ../gm.pm -o j.exr)
check "guided continuations independent of -j" cmp -s j1/j.exr j3/j.exr
pm-dump --header j1/j.exr >hdr.txt
check "the image records the guide map's photons" grep -q "^pm.guide_photons=$ng\$" hdr.txt

# Maps in the wrong place, and maps that cannot be merged.
expect_fail "a global map is no guide map" 1 "^pm-render: 'gm.pm': a global map where the guide map belongs (pm-shoot --guide makes one)$" pm-render gs.pms gm.pm --guide gm.pm -o x.exr
expect_fail "a guide map is no global map" 1 "^pm-render: 'gdm.pm': a guide map where the global map belongs: give it as --guide$" pm-render gs.pms gdm.pm -o x.exr
expect_fail "a guide map is no caustic map" 1 "^pm-render: 'gdm.pm': a guide map where the caustic map belongs" pm-render -g 4 gs.pms gm.pm --caustic gdm.pm -o x.exr
expect_fail "a guide map of another scene" 1 "^pm-render: 'cgdm.pm': guide map of another scene or time than 'gs.pms'; --force to use it$" pm-render gs.pms gm.pm --guide cgdm.pm -o x.exr
expect_fail "a guide file is not built" 1 "^pm-render: 'gd.pm': a photon file, not a photon map" pm-render gs.pms gm.pm --guide gd.pm -o x.exr
check "refusals wrote nothing" test ! -e x.exr
expect_fail "guide and global maps do not merge" 1 "^pm-build: 'g.pm': a global map, 'gd.pm' is a guide map: they cannot be merged$" pm-build gd.pm g.pm -o x.pm
expect_fail "--guide is another file" 2 "^pm-shoot: --guide: 'o.pm' must be a file other than the other outputs$" pm-shoot -n 10 gs.pms --guide o.pm -o o.pm
check "no photon file written" test ! -e x.pm -a ! -e o.pm
