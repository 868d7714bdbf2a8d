# caustic_map.sh — pm-shoot --caustic: the caustic map holds exactly the
# photons whose path from the light went through mirrors, glass and strong
# glossy surfaces only before the diffuse hit (L S+ D), checked against
# geometry computed here, not by pm: traced back along its incoming
# direction, every caustic photon meets the glass sphere, and most of the
# caustic's power lies in the sphere's focused spot on the floor.
. "$PM_TOP/tests/lib.sh"

# The caustic scene without its mirror sphere: the glass sphere (centre
# 186 91 170, radius 90) is the only specular surface.
grep -v 'sphere chrome' "$PM_TOP/examples/caustic/caustic.pms" >glass.pms
pm-shoot -q -n 50000 -s 2 glass.pms --caustic c.pm -o g.pm
pm-dump --stats c.pm >c.txt
pm-dump --stats g.pm >g.txt
check "caustic file says map: caustic" test "$(kv c.txt map)" = caustic
check "global file says map: global" test "$(kv g.txt map)" = global
check "caustic file is version 2" test "$(kv c.txt version)" = 2
check "global file stays version 1" test "$(kv g.txt version)" = 1
check "same light paths: emitted equal" test "$(kv c.txt emitted)" = "$(kv g.txt emitted)"
nc=$(kv c.txt photons)
check "caustic photons found ($nc)" test "$nc" -gt 500

# Back along psi from each caustic photon: the ray must meet the sphere
# (radius 90.5: the tessellated sphere lies inside the true one).
# The spot: the floor (y < 1) within 90 of where the line from the light's
# centre (278 548.3 279.5) through the sphere's centre meets the floor.
pm-dump --tsv c.pm | awk 'NR > 1 {
	ox = $1 - 186; oy = $2 - 91; oz = $3 - 170
	b = ox * $4 + oy * $5 + oz * $6; c = ox * ox + oy * oy + oz * oz - 90.5 * 90.5
	d = b * b - c
	if (d < 0 || -b + sqrt(d) < 0) miss++
	P = $7 + $8 + $9; tot += P
	if ($2 < 1 && ($1 - 168) ^ 2 + ($3 - 148) ^ 2 < 90 * 90) spot += P
} END { printf "miss: %d\nspot: %.4f\n", miss, spot / tot }' >back.txt
check "every caustic photon came through the sphere" test "$(kv back.txt miss)" = 0
num_near "most caustic power in the spot under the sphere" "$(kv back.txt spot)" 0.95 0.15
# The same test on the global map does find photons that did not: the
# check above can fail.
pm-dump --tsv g.pm | awk 'NR > 1 {
	ox = $1 - 186; oy = $2 - 91; oz = $3 - 170
	b = ox * $4 + oy * $5 + oz * $6; c = ox * ox + oy * oy + oz * oz - 90.5 * 90.5
	d = b * b - c
	if (d < 0 || -b + sqrt(d) < 0) miss++
} END { printf "miss: %d\n", miss }' >gback.txt
check "global photons mostly did not come through it" test "$(kv gback.txt miss)" -gt 30000

# Every caustic photon is also in the global map (same record bytes).
pm-dump --tsv c.pm | tail -n +2 | sort >cs.tsv
pm-dump --tsv g.pm | tail -n +2 | sort >gs.tsv
check "caustic photons are a subset of the global ones" test "$(comm -23 cs.tsv gs.tsv | wc -l)" -eq 0

# No specular surface, no caustic: an empty caustic map.
pm-shoot -q -n 20000 -s 3 "$PM_TOP/examples/cornell/cornell.pms" --caustic e.pm -o e_g.pm
pm-dump --stats e.pm >e.txt
check "cornell box: empty caustic map" test "$(kv e.txt photons)" = 0

# Threads change nothing.
pm-shoot -q -j 1 -n 50000 -s 2 glass.pms --caustic c1.pm -o g1.pm
pm-shoot -q -j 3 -n 50000 -s 2 glass.pms --caustic c3.pm -o g3.pm
# (Records compared: the headers record the differing output names.)
for f in c1 c3 g1 g; do pm-dump --tsv $f.pm >$f.tsv; done
check "caustic map independent of -j" cmp -s c1.tsv c3.tsv
check "global map unchanged by --caustic" cmp -s g1.tsv g.tsv

# --caustic-photons: the caustic map goes on to N photons, counts its own
# paths, and begins with the photons it had without the option.
pm-shoot -q -n 50000 -s 2 glass.pms --caustic cn.pm --caustic-photons 5000 -o gn.pm
pm-dump --stats cn.pm >cn.txt
check "--caustic-photons 5000 stores 5000" test "$(kv cn.txt photons)" = 5000
check "--caustic-photons: more paths emitted" test "$(kv cn.txt emitted)" -gt "$(kv c.txt emitted)"
pm-dump --tsv c.pm | cut -f 1-6 >c6.tsv
pm-dump --tsv cn.pm | head -n "$(wc -l <c6.tsv)" | cut -f 1-6 >cn6.tsv
check "--caustic-photons: the same first photons" cmp -s c6.tsv cn6.tsv
pm-dump --tsv gn.pm >gn.tsv
check "--caustic-photons leaves the global map alone" cmp -s gn.tsv g.tsv
pm-shoot -q -n 20000 -s 3 "$PM_TOP/examples/cornell/cornell.pms" --caustic en.pm --caustic-photons 1000000 -o en_g.pm
pm-dump --stats en.pm >en.txt
check "no specular surface: --caustic-photons stops at once, empty" test "$(kv en.txt photons)" = 0
expect_fail "--caustic-photons needs --caustic" 2 "^pm-shoot: --caustic-photons needs --caustic CFILE$" pm-shoot --caustic-photons 10 glass.pms -o z.pm

# pm-build keeps the tag and refuses to mix the two kinds, even forced.
pm-build -q c.pm -o cm.pm
pm-dump --stats cm.pm >cm.txt
check "built caustic map keeps map: caustic" test "$(kv cm.txt map)" = caustic
check "built caustic map keeps its photons" test "$(kv cm.txt photons)" = "$nc"
expect_fail "global and caustic not merged" 1 "^pm-build: 'c.pm': a caustic map, 'g.pm' is a global map: they cannot be merged$" pm-build -f g.pm c.pm -o x.pm
check "refused merge wrote nothing" test ! -e x.pm
expect_fail "caustic output must differ from -o" 2 "^pm-shoot: --caustic: 'same.pm' must be a file other than the output" pm-shoot -n 10 glass.pms --caustic same.pm -o same.pm
expect_fail "caustic output not stdout" 2 "^pm-shoot: --caustic: '-' must be a file other than the output" pm-shoot -n 10 glass.pms --caustic - -o y.pm
sed 's/^map=caustic$/map=both/' c.pm >badmap.pm
expect_fail "bad map key refused" 1 "^pm-dump: 'badmap.pm': line .*: bad map 'both' (want global, caustic or guide)$" pm-dump --stats badmap.pm
