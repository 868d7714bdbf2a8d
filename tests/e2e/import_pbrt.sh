# import_pbrt.sh — pm-import on pbrt-v4 scenes written here, each pinning a
# convention with a number: where a lamp at +x lands with and without the
# leading "Scale -1 1 1" (pbrt's LookAt is left-handed: plain, +x is on the
# left), the fov on the shorter axis in both aspects, a directly seen
# emitter reading L x scale, a one-sided emitter lighting only its front
# (the floor under it reads the analytic rho E / pi), area light "power",
# a point light's intensity, instancing, includes and named coordinate
# systems, and the notes for what pm cannot represent.
. "$PM_TOP/tests/lib.sh"
stat="$PM_BIN/../tests/tools/exrstat"
px() { "$stat" --pixel "$2" "$1" | sed -n 's/^mean: //p'; }
win() { "$stat" --window "$2" "$1" | sed -n 's/^mean: //p'; }

# cam FLIP W H: camera at z = 5 looking at the origin, fov 40
cam() {
	echo "# written by import_pbrt.sh"
	echo 'Option "disablepixeljitter" true'
	[ "$1" = flip ] && echo 'Scale -1 1 1'
	echo 'LookAt 0 0 5  0 0 0  0 1 0'
	echo 'Camera "perspective" "float fov" [ 40 ]'
	echo "Film \"rgb\" \"integer xresolution\" [ $2 ] \"integer yresolution\" [ $3 ] \"string filename\" \"out.exr\""
	echo 'Sampler "independent" "integer pixelsamples" 16'
	echo 'WorldBegin'
}
# a lamp from x 0.5 to 1.5, y -0.5 to 0.5, facing +z (the camera), L 3
lamp='AttributeBegin
AreaLightSource "diffuse" "rgb L" [ 1.5 1.5 1.5 ] "float scale" 2
Shape "trianglemesh" "point3 P" [ 0.5 -0.5 0  1.5 -0.5 0  1.5 0.5 0  0.5 0.5 0 ]
  "integer indices" [ 0 1 2  0 2 3 ]
AttributeEnd'

# Orientation: 48 x 32, vertical fov 40: 8.79 px per unit at z = 0, so the
# lamp covers columns 10.8-19.6 (left) or 28.4-37.2 (right) of 48.
{ cam plain 48 32; echo "$lamp"; } >plain.pbrt
{ cam flip 48 32; echo "$lamp"; } >flip.pbrt
for s in plain flip; do
	pm-import -q $s.pbrt -o $s/scene.pms 2>err.txt
	check "$s: imports ($(head -c 200 err.txt))" test -s $s/scene.pms
	pm-render -q -e path -p 64 $s/scene.pms -o $s.exr
done
num_near "plain LookAt (left-handed): lamp at +x seen on the left, reads L x scale" "$(px plain.exr 15,16)" 3 1e-4
num_near "plain LookAt: nothing on the right" "$(px plain.exr 32,16)" 0 0
num_near "Scale -1 1 1 first: lamp at +x on the right, reads 3" "$(px flip.exr 32,16)" 3 1e-4
num_near "Scale -1 1 1 first: nothing on the left" "$(px flip.exr 15,16)" 0 0
# The lamp's width in pixels from a row's mean: 1 unit = 8.79 px.
num_near "plain: the lamp is 8.79 px wide (fov 40 vertical in 48x32)" \
	"$(awk -v m="$(win plain.exr 0,16,48,17)" 'BEGIN { print m * 48 / 3 }')" 8.79 0.15

# The lamp turned away from the camera: dark, unless "twosided" (written
# quoted here, as pbrt also accepts).
{ cam plain 48 32; echo "$lamp" | sed 's/^Shape/ReverseOrientation\nShape/'; } >back.pbrt
{ cam plain 48 32; echo "$lamp" | sed 's/^Shape/ReverseOrientation\nShape/; s/"float scale" 2/"float scale" 2 "bool twosided" "true"/'; } >both.pbrt
for s in back both; do
	pm-import -q $s.pbrt -o $s/scene.pms && pm-render -q -e path -p 4 $s/scene.pms -o $s.exr
done
num_near "a one-sided lamp turned away (ReverseOrientation) is black" "$(px back.exr 15,16)" 0 1e-6
num_near "the same lamp two-sided reads 3" "$(px both.exr 15,16)" 3 1e-4

# Portrait 32 x 48: fov 40 is the horizontal angle, pm's vertical one is
# 2 atan(tan 20 x 48/32) = 57.265; the horizontal scale is again 8.79 px/unit.
{ cam plain 32 48; echo "$lamp"; } >tall.pbrt
pm-import -q tall.pbrt -o tall/scene.pms
fov=$(sed -n 's/^camera .* fov \([0-9.e+-]*\) .*/\1/p' tall/scene.pms)
num_near "portrait: fov on the shorter (horizontal) axis, vertical 57.265" "$fov" 57.2651 0.001
pm-render -q -e path -p 64 tall/scene.pms -o tall.exr
num_near "portrait: lamp at columns 2.8-11.6 (left), reads 3" "$(px tall.exr 7,24)" 3 1e-4
num_near "portrait: the lamp is 8.79 px wide" \
	"$(awk -v m="$(win tall.exr 0,24,32,25)" 'BEGIN { print m * 32 / 3 }')" 8.79 0.15
fov=$(sed -n 's/^camera .* fov \([0-9.e+-]*\) .*/\1/p' plain/scene.pms)
num_near "landscape: fov 40 is the vertical angle" "$fov" 40 1e-6

# A one-sided square lamp (2 x 2, L 1) at height 1 over a grey floor
# (rho 0.5), facing down, the camera between them: below its centre E = L x 4 x corner(1, 1, 1),
# corner(a, b, c) = 1/2 [a/sqrt(a^2+c^2) atan(b/sqrt(a^2+c^2)) + (a<->b)],
# so the floor reads rho E / pi = 0.5 x 4 x 0.5 x 2 x 0.7071 x 0.6155 / pi.
floor_scene() {
	echo 'LookAt 0 0.5 0.001  0 0 0  0 1 0'
	echo 'Camera "perspective" "float fov" [ 10 ]'
	echo 'Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ] "string filename" "out.exr"'
	echo 'WorldBegin'
	echo 'Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]'
	echo 'Shape "trianglemesh" "point3 P" [ -5 0 -5  -5 0 5  5 0 5  5 0 -5 ] "integer indices" [ 0 1 2 0 2 3 ]'
	echo 'AttributeBegin'
	echo "$1"
	echo 'AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]'
	echo 'Material "diffuse" "rgb reflectance" [ 0 0 0 ]'
	echo 'Translate 0 1 0'
	echo 'Rotate 90 1 0 0'
	echo 'Shape "bilinearmesh" "point3 P" [ -1 -1 0  1 -1 0  -1 1 0  1 1 0 ]'
	echo 'AttributeEnd'
}
want=$(awk 'BEGIN { a = 1 / sqrt(2); print 0.5 * 4 * 0.5 * 2 * a * atan2(a, 1) / 3.14159265358979 }')
floor_scene "" >down.pbrt
floor_scene "ReverseOrientation" >up.pbrt
for s in down up; do
	pm-import -q $s.pbrt -o $s/scene.pms && pm-render -q -e path -p 256 $s/scene.pms -o $s.exr
done
# (the 8 x 8 pixels see +-0.044 around the centre, where E is within 0.1 %
# of the centre's; 256 samples a pixel leave 0.3 % noise)
num_near "one-sided lamp facing the floor: rho E / pi = $want" "$(win down.exr 0,0,8,8)" "$want" 0.003
num_near "the same lamp reversed (ReverseOrientation) leaves the floor dark" "$(win up.exr 0,0,8,8)" 0 0

# "power": a 2 x 2 one-sided lamp of power 4 pi has radiance
# 4 pi / (pi x 4) = 1, so the same floor reading.
sed 's/"rgb L" \[ 1 1 1 \]/"rgb L" [ 1 1 1 ] "float power" 12.566370614/; s/"bilinearmesh"/"bilinearmesh"/' down.pbrt >power.pbrt
pm-import -q power.pbrt -o power/scene.pms
num_near "power 4 pi over area 4 (one-sided): radiance 1" \
	"$(sed -n 's/.* emit \([0-9.e+-]*\) .*/\1/p' power/scene.pms)" 1 1e-6

# A point light of intensity I = 2 at height 2 over the floor: E = I / h^2,
# floor rho E / pi; pm's power is 4 pi I.
{ echo 'LookAt 0 3 0.001  0 0 0  0 1 0'
  echo 'Camera "perspective" "float fov" [ 5 ]'
  echo 'Film "rgb" "integer xresolution" [ 8 ] "integer yresolution" [ 8 ] "string filename" "out.exr"'
  echo 'WorldBegin'
  echo 'Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]'
  echo 'Shape "trianglemesh" "point3 P" [ -5 0 -5  -5 0 5  5 0 5  5 0 -5 ] "integer indices" [ 0 1 2 0 2 3 ]'
  echo 'AttributeBegin Translate 0 1 0 LightSource "point" "rgb I" [ 1 1 1 ] "float scale" 2 "point3 from" [ 0 1 0 ] AttributeEnd'
  echo 'LightSource "goniometric" "rgb I" [ 1 1 1 ]'
} >point.pbrt
pm-import point.pbrt -o point/scene.pms 2>notes.txt
pm-render -q -e path -p 16 point/scene.pms -o point.exr
num_near "point light I = 2 at height 2: floor reads 0.5 x 2/4 / pi" "$(win point.exr 3,3,5,5)" \
	"$(awk 'BEGIN { print 0.5 * 0.5 / 3.14159265358979 }')" 0.002
for l in goniometric; do
	check "light '$l' dropped with a note naming its line (stderr)" \
		grep -q "^pm-import: point.pbrt:[0-9]*: light '$l': pm has no such light, dropped" notes.txt
	check "light '$l': the same note in the .pms" grep -q "^#   point.pbrt:[0-9]*: light '$l'" point/scene.pms
done

# Instances, includes, named coordinate systems and TransformBegin/End: a
# black square defined once in an included file, instanced at +x in front
# of a lamp wall (L 3) and once out of view: the wall is hidden on the left
# only. The object's second square carries an area light, which pbrt-v4
# does not support in instances: the square stays, black (so at x = -1 it
# hides the wall too), and so in pm.
{ echo 'Material "diffuse" "rgb reflectance" [ 0 0 0 ]'
  echo 'Shape "trianglemesh" "point3 P" [ -0.5 -0.5 0  0.5 -0.5 0  0.5 0.5 0  -0.5 0.5 0 ] "integer indices" [ 0 1 2  0 2 3 ]'
  echo 'AttributeBegin AreaLightSource "diffuse" "rgb L" [ 9 9 9 ] Translate -2 0 0'
  echo 'Shape "trianglemesh" "point3 P" [ -0.5 -0.5 0  0.5 -0.5 0  0.5 0.5 0  -0.5 0.5 0 ] "integer indices" [ 0 1 2  0 2 3 ]'
  echo 'AttributeEnd'; } >part.pbrt
{ cam plain 48 32
  echo 'CoordinateSystem "origin"'
  echo 'AttributeBegin AreaLightSource "diffuse" "rgb L" [ 3 3 3 ]'
  echo 'Shape "trianglemesh" "point3 P" [ -9 -9 -1  9 -9 -1  9 9 -1  -9 9 -1 ] "integer indices" [ 0 1 2  0 2 3 ]'
  echo 'AttributeEnd'
  echo 'ObjectBegin "blocker"'
  echo 'Include "part.pbrt"'
  echo 'ObjectEnd'
  echo 'TransformBegin Translate 1 0 0 ObjectInstance "blocker" TransformEnd'
  echo 'Translate 0 100 0'
  echo 'ObjectInstance "blocker"'
  echo 'CoordSysTransform "origin"'
  echo 'Shape "sphere" "float radius" 0.001'; } >inst.pbrt
pm-import inst.pbrt -o inst/scene.pms 2>notes.txt
pm-render -q -e path -p 4 inst/scene.pms -o inst.exr
num_near "an included square instanced at +x hides the lamp wall on the left" "$(px inst.exr 15,16)" 0 0
num_near "... the object's area light does not emit: black at x = -1" "$(px inst.exr 32,16)" 0 1e-6
num_near "... and the wall reads 3 between them" "$(px inst.exr 24,16)" 3 1e-4
check "two instances of two squares flattened: five meshes in all" test "$(grep -c '^mesh ' inst/scene.pms)" -eq 5
check "the area light inside the object noted" \
	grep -q "^pm-import: part.pbrt:4: area light on a shape inside ObjectBegin: it does not emit" notes.txt

# Materials: each type maps by its rule (README), reported where approximate.
{ cam plain 16 16; echo "$lamp"
  for m in 'diffuse "rgb reflectance" [ 0.2 0.3 0.4 ]' \
           'coateddiffuse "rgb reflectance" [ 0.5 0.5 0.5 ] "float roughness" 0.01' \
           'conductor "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k" "float roughness" 0' \
           'conductor "rgb reflectance" [ 0.9 0.9 0.9 ] "float roughness" 0.04' \
           'dielectric "float eta" 1.33' 'thindielectric "float eta" 1.5' \
           'diffusetransmission "rgb transmittance" [ 0.5 0.5 0.5 ]'; do
	echo "Material \"${m%% *}\" ${m#* }"
	echo 'Shape "sphere" "float radius" 0.1'
  done; } >mats.pbrt
pm-import mats.pbrt -o mats/scene.pms 2>notes.txt
check "diffuse: albedo as given" grep -q 'diffuse albedo 0.2 0.3 0.4$' mats/scene.pms
# coated: the base's light leaves through the coat: rho (1 - F0)(1 - Fi) /
# (1 - rho Fi), Fi = 0.5963 the internal diffuse reflectance of n = 1.5
# (tabulated; Egan and Hilgeman 1979): 0.2761 for rho 0.5.
kd=$(sed -n 's/.* glossy kd \([0-9.]*\) .* ks 0.04 0.04 0.04 exponent 198$/\1/p' mats/scene.pms)
num_near "coateddiffuse: kd through the coat 0.2761, ks F0 0.04, exponent 2/0.01 - 2 = 198" "$kd" 0.2761 5e-4
check "smooth conductor (gold): a mirror of gold's normal-incidence reflectance" \
	grep -q 'mirror reflect 1 0.766 0.336$' mats/scene.pms
check "rough conductor: Blinn glossy, exponent 2/0.04 - 2 = 48" \
	grep -q 'glossy kd 0 0 0 ks 0.9 0.9 0.9 exponent 48$' mats/scene.pms
check "dielectric: glass of its eta" grep -q 'glass ior 1.33 tint 1 1 1$' mats/scene.pms
check "thindielectric: a pane, ior 1, transmission (1 - R)/(1 + R) = 0.9231" \
	grep -q 'glass ior 1 tint 0.923076923 ' mats/scene.pms
check "diffusetransmission: diffuse of its reflectance 0.25" grep -q 'diffuse albedo 0.25 0.25 0.25$' mats/scene.pms
for t in coateddiffuse conductor thindielectric diffusetransmission; do
	check "$t: its approximation noted with file:line" grep -q "^pm-import: mats.pbrt:[0-9]*: material ($t)" notes.txt
done

# Re-importing replaces the meshes: none of the old scene's are left over.
{ cam plain 48 32; echo "$lamp" | sed 's/1.5 -0.5 0  1.5 0.5/1.4 -0.5 0  1.4 0.5/'; } >plain.pbrt
pm-import -q plain.pbrt -o plain/scene.pms
check "re-import: the old mesh removed, the new one in place" test "$(ls plain | grep -c '\.ply$')" -eq 1

# loopsubdiv: a regular tetrahedron (corners (1,1,1), (1,-1,-1), (-1,1,-1),
# (-1,-1,1)) subdivided once has 4 + 6 vertices and 16 faces; Loop's rules
# put every old corner at 7/16 v + 3/16 (sum of the other three) = v / 4
# and every edge's new vertex at 3/8 (a + b) + 1/8 (c + d) = (a + b) / 4, so
# no coordinate exceeds 0.5 (the edge vertices', e.g. (0.5, 0, 0)).
{ cam plain 8 8
  echo 'AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]'
  echo 'Shape "loopsubdiv" "integer levels" 1 "point3 P" [ 1 1 1  1 -1 -1  -1 1 -1  -1 -1 1 ]'
  echo '  "integer indices" [ 0 1 2  0 3 1  0 2 3  1 3 2 ]'; } >loop.pbrt
pm-import -q loop.pbrt -o loop/scene.pms
ply=loop/$(sed -n 's/^mesh \([^ ]*\) .*/\1/p' loop/scene.pms)
check "loopsubdiv, 1 level: 10 vertices, 16 faces" \
	test "$(sed -n 's/^element vertex //p' $ply) $(sed -n 's/^element face //p' $ply)" = "10 16"
off=$(($(sed -n '1,/^end_header/p' $ply | wc -c)))
max=$(od -A n -t f4 -j $off -N 120 $ply | tr -s ' ' '\n' | grep . |
	awk '{ v = $1 < 0 ? -$1 : $1; if (v > m) m = v } END { print m }')
num_near "loopsubdiv: the largest coordinate is 0.5 (corners moved to v/4)" "$max" 0.5 1e-6
