# ldpaths.sh — pm-shoot --light-paths sobol: the same light as pseudo-random
# paths, with less spread between passes where the sequence's pairs decide
# where photons land; independent of threads; recorded in the photon file
# and the image.
. "$PM_TOP/tests/lib.sh"
T=$PM_BIN/../tests/tools

# A point light above a mirror floor under a dark ceiling: the photons
# stored on the ceiling came down through the mirror, placed by the
# emission direction alone (one Sobol' pair). The view pass has one seed
# (-s 7) in every pass, so the spread between passes is the photon map's.
cp "$PM_TOP/tests/scenes/mirror.pms" mirror.pms
"$T/mkimg" -v 0,0,0 -c stderr.R=0 -c stderr.G=0 -c stderr.B=0 zero.exr 24 24
for lp in random sobol; do
	for i in 1 2 3 4 5 6 7 8 9 10 11 12; do
		pm-shoot -q -j 1 -n 2000 --light-paths $lp -P $i/12 mirror.pms |
			pm-build -q | pm-render -q -j 1 -e classical -k 30 -p 1 -s 7 -P $i/12 mirror.pms - -o $lp-$i.exr
	done
	pm-average -q $lp-*.exr -o $lp.exr
	eval "mean_$lp=\$(pm-diff $lp.exr zero.exr | sed -n 's/^mean_a: *//p')"
	eval "se_$lp=\$(pm-diff -l stderr $lp.exr zero.exr | sed -n 's/^rmse: *//p')"
done
check "sobol and random paths agree on the mean ($mean_sobol, $mean_random)" \
	awk -v a="$mean_sobol" -v b="$mean_random" 'BEGIN { d = a / b - 1; exit !(b > 0 && d < 0.02 && d > -0.02) }'
check "sobol passes spread less: standard error $se_sobol < 0.6 * random's $se_random" \
	awk -v a="$se_sobol" -v b="$se_random" 'BEGIN { exit !(b > 0 && a < 0.6 * b) }'
"$T/exrattr" sobol-3.exr pm.light_paths >attr.txt 2>&1
check "pm-render records pm.light_paths sobol" grep -qx sobol attr.txt
"$T/exrattr" sobol.exr pm.light_paths >attr.txt 2>&1
check "their average keeps it" grep -qx sobol attr.txt
"$T/exrattr" random-3.exr pm.light_paths >attr.txt 2>&1
check "pm-render records pm.light_paths random" grep -qx random attr.txt

# The furnace (exact radiance 2) with sobol paths, as tests/e2e/furnace.sh.
pm-shoot -q -n 200000 -s 5 --light-paths sobol "$PM_TOP/tests/scenes/furnace.pms" | pm-build -q |
	pm-render -q -e compensated -p 16 -s 5 "$PM_TOP/tests/scenes/furnace.pms" - -o furnace.exr
"$PM_BIN/../tests/tools/exrstat" --window 12,9,28,21 furnace.exr >furnace.txt
num_near "furnace with sobol paths: centre mean = 2" "$(kv furnace.txt mean)" 2 0.06

pm-shoot -q -n 3000 -s 9 --light-paths sobol -j 1 mirror.pms >j1.pm
pm-shoot -q -n 3000 -s 9 --light-paths sobol -j 2 mirror.pms >j2.pm
check "sobol photons are the same bytes for -j 1 and -j 2" cmp -s j1.pm j2.pm
check "the photon file says light_paths=sobol" grep -aqx 'light_paths=sobol' j1.pm
pm-shoot -q -n 3000 -s 9 mirror.pms -o r.pm
check "the default is random" grep -aqx 'light_paths=random' r.pm
pm-build -q j1.pm r.pm -o both.pm
check "a map of both is light_paths=mixed" grep -aqx 'light_paths=mixed' both.pm
pm-dump --stats both.pm >dump.txt 2>&1
check "pm-dump shows light_paths" grep -qx 'light_paths: mixed' dump.txt
expect_fail "an unknown --light-paths is refused" 2 "^pm-shoot: --light-paths: unknown 'halton'" \
	pm-shoot --light-paths halton mirror.pms -o x.pm
sed 's/^light_paths=sobol$/light_paths=quasi/' j1.pm >bad.pm
expect_fail "a bad light_paths key is refused with the file and line" 1 \
	"bad.pm.*line 13: bad light_paths 'quasi'" pm-build bad.pm -o x.pm
