# textures.sh — image and checker textures against the numbers physics
# gives: a floor under a distant light reads albedo(u, v) E cos(theta) / pi
# in each square of a checkerboard and in each quadrant of an 8-bit sRGB
# image (decoded to linear); a closed furnace whose albedo is a uniform
# texture reads Le / (1 - rho); one with a checkerboard albedo reads from
# the photon map what the path tracer reads; results do not depend on the
# thread count; bad textures are refused naming the file and line.
. "$PM_TOP/tests/lib.sh"
tools=$PM_BIN/../tests/tools
pi=3.14159265358979

# The floor [-1, 1]^2 seen from straight above; (u, v) runs from its
# corner (-1, -1) along +z (u) and +x (v). Light at 60 degrees: E cos = 1.5.
cat >chk.pms <<'SCENE'
camera eye 0 1 0  look 0 0 0  up 0 0 -1  fov 90  size 16 16
texture chk checker 0.2 0.3 0.4  0.8 0.7 0.6  scale 2 2
material floor diffuse albedo tex chk
quad floor -1 0 -1  -1 0 1  1 0 1  1 0 -1
distantlight dir 1.7320508 -1 0  irradiance 3 3 3
SCENE
pm-render -q -e path -p 4 chk.pms -o chk.exr
# Quadrant centres: pixels (4, 4) and (11, 11) are one colour, (11, 4) and
# (4, 11) the other.
for px in 4,4 11,11 11,4 4,11; do "$tools/exrstat" --pixel $px chk.exr | sed -n 's/^mean: //p'; done >q.txt
a=$(awk 'BEGIN { print 0.3 * 1.5 / '$pi' }'); b=$(awk 'BEGIN { print 0.7 * 1.5 / '$pi' }')
set -- $(cat q.txt)
if awk -v x="$1" -v y="$2" 'BEGIN { exit !(x < 0.2) }'; then lo1=$1 lo2=$2 hi1=$3 hi2=$4; else lo1=$3 lo2=$4 hi1=$1 hi2=$2; fi
for v in $lo1 $lo2; do num_near "checker dark square: albedo E cos / pi" "$v" "$a" "$(awk -v w=$a 'BEGIN { print w * 0.01 }')"; done
for v in $hi1 $hi2; do num_near "checker light square: albedo E cos / pi" "$v" "$b" "$(awk -v w=$b 'BEGIN { print w * 0.01 }')"; done

# The same floor as a mesh whose file carries (u, v): OBJ vt, and PLY
# under each of the names files use.
printf 'v -1 0 -1\nv -1 0 1\nv 1 0 1\nv 1 0 -1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n' >floor.obj
for uv in "u v" "s t" "texture_u texture_v" "texture_s texture_t" obj; do
	if [ "$uv" = obj ]; then f=floor.obj; else
		f=floor.ply
		set -- $uv
		printf 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty float %s\nproperty float %s\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n-1 0 -1 0 0\n-1 0 1 1 0\n1 0 1 1 1\n1 0 -1 0 1\n4 0 1 2 3\n' $1 $2 >floor.ply
	fi
	sed "s/^quad .*/mesh $f floor/" chk.pms >m.pms
	pm-render -q -e path -p 1 m.pms -o m.exr
	check "(u, v) from the mesh file ($uv)" test "$("$tools/exrstat" --pixel 4,4 m.exr | sed -n 's/^mean: //p')" != "$("$tools/exrstat" --pixel 11,4 m.exr | sed -n 's/^mean: //p')"
done

# An 8-bit image of four quadrants, 2 x 2 texels each (so the quadrants'
# centres read one value under bilinear filtering): codes 40, 90, 160, 250.
printf 'P5\n4 4\n255\n' >quads.pgm
printf '\050\050\132\132\050\050\132\132\240\240\372\372\240\240\372\372' >>quads.pgm
sed 's/^texture .*/texture img image quads.pgm/; s/tex chk/tex img/' chk.pms >img.pms
pm-render -q -e path -p 4 img.pms -o img.exr
for px in 4,4 11,4 4,11 11,11; do "$tools/exrstat" --pixel $px img.exr | sed -n 's/^mean: //p'; done | sort -g >got.txt
for c in 40 90 160 250; do awk -v c=$c 'BEGIN { x = c / 255; l = x <= 0.04045 ? x / 12.92 : ((x + 0.055) / 1.055) ^ 2.4; printf "%.9g\n", l * 1.5 / '$pi' }'; done >want.txt
paste got.txt want.txt | while read g w; do
	num_near "8-bit sRGB texel decoded to linear: $w" "$g" "$w" "$(awk -v w=$w 'BEGIN { print w * 0.01 }')"
done

# Closed furnaces of six quads (each with its (u, v)), emitting 1.
room() {
	cat <<SCENE
camera eye 0 1 2.6  look 0 1 -3  up 0 1 0  fov 50  size 24 18
$1
material f diffuse albedo tex t emit 1 1 1 twosided
quad f -2 0 -3  2 0 -3  2 0 3  -2 0 3
quad f -2 2.5 -3  -2 2.5 3  2 2.5 3  2 2.5 -3
quad f -2 0 -3  -2 2.5 -3  2 2.5 -3  2 0 -3
quad f -2 0 3  2 0 3  2 2.5 3  -2 2.5 3
quad f -2 0 -3  -2 0 3  -2 2.5 3  -2 2.5 -3
quad f 2 0 -3  2 2.5 -3  2 2.5 3  2 0 3
SCENE
}
"$tools/mkimg" -v 0.5,0.5,0.5 half.exr 4 4
room "texture t image half.exr" >uni.pms
pm-render -q -e path -p 64 uni.pms -o uni.exr
"$tools/exrstat" uni.exr >u.txt
num_near "furnace with a uniform texture: Le / (1 - rho) = 2" "$(kv u.txt mean)" 2 0.02
pm-shoot -q -n 100000 uni.pms | pm-build -q | pm-render -q -p 8 uni.pms - -o unic.exr
"$tools/exrstat" unic.exr >u.txt
num_near "the same from the photon map" "$(kv u.txt mean)" 2 0.06

room "texture t checker 0.2 0.2 0.2  0.8 0.8 0.8  scale 3 3" >chk2.pms
pm-render -q -e path -p 128 chk2.pms -o ref.exr
pm-shoot -q -n 200000 chk2.pms >shot.pm
pm-build -q shot.pm -o map.pm
pm-render -q -p 8 chk2.pms map.pm -o pm.exr
"$tools/exrstat" ref.exr >r.txt
"$tools/exrstat" pm.exr >c.txt
check "checkerboard furnace is brighter than its emission" awk -v a="$(kv r.txt mean)" 'BEGIN { exit !(a > 1.3) }'
num_near "checkerboard furnace: photon map mean near the path tracer's" "$(kv c.txt mean)" "$(kv r.txt mean)" "$(awk -v w="$(kv r.txt mean)" 'BEGIN { print w * 0.03 }')"
mkdir j1 j2
(cd j1 && pm-shoot -q -j 1 -n 20000 ../chk2.pms -o s.pm && pm-render -q -j 1 -p 2 ../chk2.pms ../map.pm -o v.exr)
(cd j2 && pm-shoot -q -j 2 -n 20000 ../chk2.pms -o s.pm && pm-render -q -j 2 -p 2 ../chk2.pms ../map.pm -o v.exr)
check "textured photons identical for -j 1 and -j 2" cmp -s j1/s.pm j2/s.pm
check "textured view pass identical for -j 1 and -j 2" cmp -s j1/v.exr j2/v.exr

sed 's/^texture .*/texture img image nowhere.png/; s/tex chk/tex img/' chk.pms >bad.pms
expect_fail "missing texture file" 1 "^pm-render: bad.pms:2: 'nowhere.png': cannot read image" pm-render -e path bad.pms -o bad.exr
printf 'P5\n0 0\n255\n' >empty.pgm
sed 's/^texture .*/texture img image empty.pgm/; s/tex chk/tex img/' chk.pms >bad.pms
expect_fail "texture of zero size" 1 "^pm-render: bad.pms:2: 'empty.pgm': image has no pixels" pm-render -e path bad.pms -o bad.exr
"$tools/mkimg" -n 1,2 nan.exr 4 4
sed 's/^texture .*/texture img image nan.exr/; s/tex chk/tex img/' chk.pms >bad.pms
expect_fail "NaN texel" 1 "^pm-render: bad.pms:2: texture: 'nan.exr': texel (1, 2) is nan" pm-render -e path bad.pms -o bad.exr
printf 'not an image\n' >junk.png
sed 's/^texture .*/texture img image junk.png/; s/tex chk/tex img/' chk.pms >bad.pms
expect_fail "unreadable texture" 1 "^pm-render: bad.pms:2: 'junk.png': cannot read image" pm-render -e path bad.pms -o bad.exr
sed 's/tex chk/tex nope/' chk.pms >bad.pms
expect_fail "unknown texture" 1 "^pm-render: bad.pms:3: material 'floor': unknown texture 'nope'" pm-render -e path bad.pms -o bad.exr

# OpenImageIO is a module loaded when an image is first read
# (lib/scene/oiio.h): a scene without images needs none, and one with an
# image refuses, naming the file, where the module is missing or broken.
check "pm-render does not link OpenImageIO" sh -c "! ldd '$PM_BIN/pm-render' | grep -q OpenImageIO"
check "... its module does" sh -c "ldd '$PM_BIN/../lib/pm/pm-oiio.so' | grep -q OpenImageIO"
mkdir nomod badmod
PM_PLUGIN_DIR=$PWD/nomod pm-render -q -e path -p 1 chk.pms -o nomod.exr
check "a scene without images renders without the module" "$tools/exrstat" nomod.exr
sed 's/^texture .*/texture img image quads.pgm/; s/tex chk/tex img/' chk.pms >img2.pms
expect_fail "module missing: the image refused, the module named" 1 \
	"^pm-render: img2.pms:2: 'quads.pgm': cannot read image: OpenImageIO module pm-oiio.so not in PM_PLUGIN_DIR" \
	env PM_PLUGIN_DIR="$PWD/nomod" pm-render -e path img2.pms -o nomod2.exr
check "... and no image written" test ! -e nomod2.exr
echo 'not a shared object' >badmod/pm-oiio.so
expect_fail "module broken: the loader's reason given" 1 \
	"^pm-render: img2.pms:2: 'quads.pgm': cannot read image: OpenImageIO module: .*badmod/pm-oiio.so" \
	env PM_PLUGIN_DIR="$PWD/badmod" pm-render -e path img2.pms -o nomod2.exr

# Filtered lookups: a floor checkered in squares of half a unit to the
# horizon, lit so that it reads its albedo (E = pi from straight above).
# Where a camera sample's footprint (half a pixel at 4 samples) spans many
# squares (the first floor rows under the horizon) each pixel reads the
# squares' mean, 0.5, whichever points its samples land on: measured rms
# 0.0105 (checker, exact box mean) and 0.0075 (a 2 x 2 image of texels 1
# and 0, OpenImageIO's MIP levels), where point sampling read 0.145 and
# 0.080 at these 4 samples a pixel. Near the camera, where a texel spans
# pixels, the image is looked up as before (its last rows' spread, 0.188,
# is what point sampling gave) and the checker's squares stay sharp
# (0.284; 0.294 point-sampled).
printf 'P2\n2 2\n255\n255 0\n0 255\n' >ck.pgm
for k in checker image; do
	if [ $k = checker ]; then tx="texture ck checker 0.8 0.8 0.8  0.2 0.2 0.2 scale 400 400"
	else tx="texture ck image ck.pgm scale 200 200"; fi
	cat >far$k.pms <<SCENE
camera eye 0 1 0  look 0 0.7 -10  up 0 1 0  fov 40  size 64 48
$tx
material fl diffuse albedo tex ck
quad fl -100 0 100  100 0 100  100 0 -100  -100 0 -100
distantlight dir 0 -1 0  irradiance 3.14159265 3.14159265 3.14159265
SCENE
	pm-render -q -e path -p 4 -j 2 far$k.pms -o far$k.exr
	pm-render -q -e path -p 4 -j 1 far$k.pms -o far${k}1.exr
	"$tools/exrstat" --dump far$k.exr >far$k.dump
	"$tools/exrstat" --dump far${k}1.exr >far${k}1.dump
	check "far $k: -j 1 and -j 2 alike" cmp -s far$k.dump far${k}1.dump
	# The mean and rms about 0.5 of the first six rows all floor (the
	# sky reads 0), and the spread of the last three.
	awk '{ s[$2] += $3; q[$2] += ($3 - 0.5) ^ 2; n[$2]++; if (!($3 > 0)) sky[$2] = 1; if ($2 + 0 > Y) Y = $2 + 0 }
	END { for (y = 0; y <= Y && f < 6; y++) if (!(y in sky)) { f++; m += s[y]; e += q[y]; c += n[y] }
	      for (y = Y - 2; y <= Y; y++) { a += s[y]; b += q[y]; k += n[y] }
	      printf "far_mean: %.6f\nfar_rms: %.6f\nnear_sd: %.6f\n", m / c, sqrt(e / c), sqrt(b / k - (a / k - 0.5) ^ 2) }' far$k.dump >far$k.txt
	num_near "far $k: the far rows read the squares' mean" "$(kv far$k.txt far_mean)" 0.5 0.01
	check "far $k: every far pixel within rms 0.02 of it ($(kv far$k.txt far_rms))" \
		awk -v a="$(kv far$k.txt far_rms)" 'BEGIN { exit !(a < 0.02) }'
	check "far $k: the near rows stay sharp ($(kv far$k.txt near_sd))" \
		awk -v a="$(kv far$k.txt near_sd)" 'BEGIN { exit !(a > 0.15) }'
done
