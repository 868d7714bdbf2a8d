# layers.sh — parallel layers in a furnace (every surface albedo 0.5 and
# emission 1: radiance exactly 2 everywhere): a picture 1 cm in front of the
# far wall, a rug 5 mm above the floor and a box resting on the floor. The
# paper's target area (eq. 4) would count the wall behind the picture, the
# floor under the rug and under the box as well, and read low there; the
# compensated estimate takes the hidden part out (lib/overlap.h).
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
