# compensated.sh — the paper's claim, measured against an exact answer: in a
# closed furnace room with a table (concave room edges and corners, convex
# table edges), every surface albedo 0.5 and emission 1, the radiance is
# exactly 2 everywhere. The compensated estimate stays within a stated bound
# everywhere; the classical estimate's error in the edge band (pixels whose
# estimate's support meets another surface: the `edge` layer) is larger.
# Also: the image is invariant under translation by 1e4 and scaling by 1e-3
# and 1e3 (radiance does not depend on units or placement).
. "$PM_TOP/tests/lib.sh"
tools=$PM_BIN/../tests/tools

# room.pms SCALE OFFSET: the scene with every coordinate x -> x * SCALE + OFFSET.
room() {
	awk -v s="$1" -v t="$2" '
	function p(i) { return $i * s + t }
	/^camera/ { print "camera eye", p(3), p(4), p(5), "look", p(7), p(8), p(9), "up 0 1 0 fov 60 size 96 72"; next }
	/^box/ { printf "box f %.17g %.17g %.17g %.17g %.17g %.17g %s\n", p(3), p(4), p(5), p(6), p(7), p(8), $9; next }
	{ print }' <<'SCENE'
camera eye 1.6 1.7 2.6  look -0.3 0.4 -1.2  up 0 1 0  fov 60  size 96 72
material f diffuse albedo 0.5 0.5 0.5 emit 1 1 1
box f -2 0 -3  2 2.5 3 inward
box f -0.6 0.7 -1.6  0.6 0.8 -0.8
box f -0.55 0 -1.55  -0.45 0.7 -1.45
box f 0.45 0 -1.55  0.55 0.7 -1.45
box f -0.55 0 -0.95  -0.45 0.7 -0.85
box f 0.45 0 -0.95  0.55 0.7 -0.85
SCENE
}
room 1 0 >room.pms
"$tools/mkimg" -v 2,2,2 exact.exr 96 72

# 16 pass pairs of 50k photons, k = 100: large supports, so that the edge
# band is wide and the estimators' bias shows above the noise.
for est in classical compensated; do
	for i in $(seq 1 16); do
		pm-shoot -n 50000 -s $i room.pms | pm-build | pm-render -e $est -k 100 -p 4 -s $i room.pms - -o pass-$est-$i.exr
	done
	pm-average -q pass-$est-*.exr -o $est.exr
done
# The edge band is the compensated renders' (one cube of the edges).
for est in classical compensated; do
	pm-diff -o $est-err.exr $est.exr exact.exr >$est-all.txt
	pm-diff -m pass-compensated-1.exr -c edge $est.exr exact.exr >$est-edge.txt
	pm-diff -m pass-compensated-1.exr -c '!edge' $est.exr exact.exr >$est-flat.txt
	echo "# $est: rmse all $(kv $est-all.txt rmse) edge $(kv $est-edge.txt rmse) flat $(kv $est-flat.txt rmse); max_abs $(kv $est-all.txt max_abs); edge pixels $(kv $est-edge.txt pixels)"
done
check "edge band is not empty" test "$(kv compensated-edge.txt pixels)" -gt 300
num_near "compensated mean = 2" "$(kv compensated-all.txt mean_a)" 2 0.01
num_near "compensated within 10% of exact everywhere" "$(kv compensated-all.txt max_abs)" 0 0.2
num_near "compensated edge-band rmse <= 2%" "$(kv compensated-edge.txt rmse)" 0 0.04
awk -v c="$(kv classical-edge.txt rmse)" -v p="$(kv compensated-edge.txt rmse)" 'BEGIN { exit !(c > 1.5 * p) }' &&
	ok "classical edge error > 1.5x compensated (paper §3)" ||
	notok "classical edge error > 1.5x compensated (paper §3)" "classical $(kv classical-edge.txt rmse), compensated $(kv compensated-edge.txt rmse)"
# Away from edges the two agree: both are within noise of the exact answer.
num_near "classical flat rmse small" "$(kv classical-flat.txt rmse)" 0 0.04

# Invariance: one pass, same seed, at 1e4 from the origin and at scales
# 1e-3 and 1e3. The photon paths differ by rounding, so compare to the
# noise between two seeds of the original.
pm-shoot -n 50000 -s 1 room.pms | pm-build | pm-render -k 100 -p 4 -s 1 room.pms - -o base.exr
pm-shoot -n 50000 -s 2 room.pms | pm-build | pm-render -k 100 -p 4 -s 2 room.pms - -o base2.exr
pm-diff base.exr base2.exr >noise.txt
for v in "1 10000" "0.001 0" "1000 0"; do
	room $v >moved.pms
	pm-shoot -n 50000 -s 1 moved.pms | pm-build | pm-render -k 100 -p 4 -s 1 moved.pms - -o moved.exr
	pm-diff moved.exr base.exr >moved.txt
	echo "# scale/offset $v: rmse $(kv moved.txt rmse) vs noise $(kv noise.txt rmse), mean $(kv moved.txt mean_a)"
	awk -v m="$(kv moved.txt rmse)" -v n="$(kv noise.txt rmse)" 'BEGIN { exit !(m <= 1.5 * n) }' &&
		ok "image unchanged beyond noise at scale/offset $v" ||
		notok "image unchanged beyond noise at scale/offset $v" "rmse $(kv moved.txt rmse), noise $(kv noise.txt rmse)"
	num_near "mean unchanged at scale/offset $v" "$(kv moved.txt mean_a)" "$(kv noise.txt mean_a)" 0.01
done
