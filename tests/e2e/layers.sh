# layers.sh — parallel layers in a furnace (every surface albedo 0.5 and
# emission 1: radiance exactly 2 everywhere): a picture 1 cm in front of the
# far wall, a rug 5 mm above the floor and a box resting on the floor. The
# paper's target area (eq. 4) would count the wall behind the picture, the
# floor under the rug and under the box as well, and read low there; the
# compensated estimate takes the hidden part out (lib/estimators/overlap.h).
. "$PM_TOP/tests/lib.sh"
tools=$PM_BIN/../tests/tools
cat >layers.pms <<'SCENE'
camera eye 0 1.2 2.5  look 0 0.6 -3  up 0 1 0  fov 55  size 64 48
material f diffuse albedo 0.5 0.5 0.5 emit 1 1 1
box f -2 0 -3  2 2.5 3 inward
quad f -1 0.5 -2.99  1 0.5 -2.99  1 1.5 -2.99  -1 1.5 -2.99
quad f -1.5 0.005 -2.5  -1.5 0.005 -0.5  -0.5 0.005 -0.5  -0.5 0.005 -2.5
box f 0.4 0 -1.8  1.0 0.5 -1.2
SCENE
for i in 1 2 3 4 5 6 7 8; do
	pm-shoot -n 40000 -s $i layers.pms | pm-build | pm-render -k 100 -p 4 -s $i layers.pms - -o pass-$i.exr
done
pm-average -q pass-*.exr -o layers.exr
"$tools/exrstat" layers.exr >all.txt
# The picture fills the middle of the image; the rug is low on the left.
"$tools/exrstat" --window 24,14,40,22 layers.exr >picture.txt
"$tools/exrstat" --window 8,38,20,46 layers.exr >rug.txt
"$tools/exrstat" --window 44,34,52,40 layers.exr >box.txt
for f in all picture rug box; do echo "# $f: mean $(kv $f.txt mean) min $(kv $f.txt min) max $(kv $f.txt max)"; done
num_near "furnace with layers: mean 2" "$(kv all.txt mean)" 2 0.03
num_near "picture in front of a wall reads 2" "$(kv picture.txt mean)" 2 0.05
num_near "rug on the floor reads 2" "$(kv rug.txt mean)" 2 0.05
num_near "box resting on the floor reads 2" "$(kv box.txt mean)" 2 0.05
num_near "nowhere below 1.8" "$(kv all.txt min)" 2 0.2

# Thin walls: a closed room split in two by a wall 2 cm thick (a solid box)
# or by a two-sided sheet; the floor, ceiling and side walls run through
# under and beside it as single polygons; the light is in the far half. No
# light can reach the near half: every pixel there is exactly 0. Photons on
# the far side's floor lie inside the cube of points near the wall's foot;
# the compensated estimate must not let them through (the classical one
# does).
for wall in "box w -2 0 -0.01  2 2.5 0.01" "quad w -2 0 0  2 0 0  2 2.5 0  -2 2.5 0"; do
	cat >thin.pms <<SCENE
camera eye 0 1 2.9  look 0 0.2 0  up 0 1 0  fov 60  size 48 36
material w diffuse albedo 0.6 0.6 0.6
material lamp diffuse albedo 0 0 0 emit 10 10 10
box w -2 0 -3  2 2.5 3 inward
$wall
quad lamp -0.5 2.49 -2  0.5 2.49 -2  0.5 2.49 -1  -0.5 2.49 -1
SCENE
	kind=${wall%% *}
	pm-shoot -n 100000 -s 1 thin.pms | pm-build -o thin.pm
	for est in classical compensated; do
		pm-render -e $est -k 50 -p 2 -s 1 thin.pms thin.pm -o thin-$est.exr
		"$tools/exrstat" thin-$est.exr >thin-$est.txt
		echo "# $kind wall, $est: max $(kv thin-$est.txt max)"
	done
	check "no light through a thin $kind wall (compensated)" test "$(kv thin-compensated.txt max)" = 0
	check "the classical estimate leaks through the $kind wall" test "$(kv thin-classical.txt max)" != 0
done
