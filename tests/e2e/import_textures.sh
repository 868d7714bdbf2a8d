# import_textures.sh — pbrt-v4 textures and shading normals through
# pm-import, read back from a floor lit by a distant light of irradiance pi
# from straight above (so a diffuse floor reads its albedo): a
# checkerboard's two squares, the same through a "scale" texture, an 8-bit
# image texture decoded from sRGB (the image copied beside the scene), and
# vertex normals N tilted 60 degrees halving the floor's reading; Mitsuba's
# checkerboard, and its obj shapes' uv and normals under a bitmap.
. "$PM_TOP/tests/lib.sh"
stat="$PM_BIN/../tests/tools/exrstat"
win() { "$stat" --window "$2" "$1" | sed -n "s/^$3: //p"; }

# The floor from x, z = -1 to 1 carries (u, v) from 0 to 1; 33 x 33 pixels
# see x, z within +-0.73, the squares' edges on the middle row and column.
pbrt() {
	echo 'LookAt 0 2 0  0 0 0  0 0 1'
	echo 'Camera "perspective" "float fov" [ 40 ]'
	echo 'Film "rgb" "integer xresolution" [ 33 ] "integer yresolution" [ 33 ] "string filename" "out.exr"'
	echo 'WorldBegin'
	echo 'LightSource "distant" "point3 from" [ 0 1 0 ] "point3 to" [ 0 0 0 ] "rgb L" [ 3.14159265358979 3.14159265358979 3.14159265358979 ]'
	echo "$1"
	echo 'Shape "trianglemesh" "point3 P" [ -1 0 -1  1 0 -1  1 0 1  -1 0 1 ] "point2 uv" [ 0 0  1 0  1 1  0 1 ]'
	echo '  "integer indices" [ 0 2 1  0 3 2 ]'
}
run() {
	pm-import -q $1.pbrt -o $1/scene.pms 2>$1.err
	check "$1: imports ($(head -c 200 $1.err))" test -s $1/scene.pms
	pm-render -q -e path -p 4 $1/scene.pms -o $1.exr
}
quads() {   # the four squares' means
	for w in 2,2,14,14 19,2,31,14 2,19,14,31 19,19,31,31; do win $1.exr $w mean; done
}

pbrt 'Texture "ck" "spectrum" "checkerboard" "float uscale" 2 "float vscale" 2 "rgb tex1" [ 0.8 0.8 0.8 ] "rgb tex2" [ 0.2 0.2 0.2 ]
Material "diffuse" "texture reflectance" "ck"' >ck.pbrt
pbrt 'Texture "ck0" "spectrum" "checkerboard" "float uscale" 2 "float vscale" 2 "rgb tex1" [ 1.6 1.6 1.6 ] "rgb tex2" [ 0.4 0.4 0.4 ]
Texture "ck" "spectrum" "scale" "texture tex" "ck0" "float scale" 0.5
Material "diffuse" "texture reflectance" "ck"' >sck.pbrt
for s in ck sck; do
	run $s
	set -- $(quads $s)
	num_near "$s: a square reads tex1 (0.8)" "$(printf '%s\n' "$@" | sort -g | tail -n 1)" 0.8 1e-5
	num_near "$s: a square reads tex2 (0.2)" "$(printf '%s\n' "$@" | sort -g | head -n 1)" 0.2 1e-5
	num_near "$s: diagonal squares alike" "$1" "$4" 1e-6
	num_near "$s: neighbours differ by 0.6" "$(awk -v a="$1" -v b="$2" 'BEGIN { d = a - b; print d < 0 ? -d : d }')" 0.6 1e-5
done
check "the checker's uscale/vscale are pm's scale" grep -q '^texture t0 checker .* scale 2 2 offset 0 0' ck/scene.pms

# An 8-bit grey image of 128: sRGB-decoded 0.2158605 everywhere.
printf 'P2\n2 2\n255\n128 128\n128 128\n' >grey.pgm
pbrt 'Texture "im" "spectrum" "imagemap" "string filename" "grey.pgm"
Material "diffuse" "texture reflectance" "im"' >im.pbrt
run im
num_near "imagemap: 8-bit 128 reads its sRGB decoding" "$(win im.exr 0,0,33,33 mean)" 0.2158605 1e-5
img=$(sed -n 's/^texture t0 image \([^ ]*\) .*/\1/p' im/scene.pms)
check "the image is copied beside the scene" cmp -s "im/$img" grey.pgm
check "the mesh file carries u and v" grep -aq '^property float u$' "im/$(sed -n 's/^mesh \([^ ]*\) .*/\1/p' im/scene.pms)"
# A missing image: noted with its line, the constant colour used.
sed 's/grey.pgm/none.pgm/' im.pbrt >miss.pbrt
pm-import miss.pbrt -o miss/scene.pms 2>miss.err
check "a missing image is noted with the Texture's line" grep -q 'miss.pbrt:6: image .*none.pgm.* cannot be read' miss.err
check "... and the scene is written without it" grep -q '^material .* diffuse albedo 0.5 0.5 0.5' miss/scene.pms

# Vertex normals: the floor's N tilted 60 degrees about z (and turned by a
# Rotate the transform carries them through) shade it as a surface at 60
# degrees to the light: rho cos 60 = 0.4 for rho 0.8.
{ echo 'LookAt 0 2 0  0 0 0  0 0 1'
  echo 'Camera "perspective" "float fov" [ 40 ]'
  echo 'Film "rgb" "integer xresolution" [ 33 ] "integer yresolution" [ 33 ] "string filename" "out.exr"'
  echo 'WorldBegin'
  echo 'LightSource "distant" "point3 from" [ 0 1 0 ] "point3 to" [ 0 0 0 ] "rgb L" [ 3.14159265358979 3.14159265358979 3.14159265358979 ]'
  echo 'Material "diffuse" "rgb reflectance" [ 0.8 0.8 0.8 ]'
  echo 'Rotate 90 0 1 0'
  echo 'Shape "trianglemesh" "point3 P" [ -1 0 -1  1 0 -1  1 0 1  -1 0 1 ] "integer indices" [ 0 2 1  0 3 2 ]'
  echo '  "normal N" [ 0.866025404 0.5 0  0.866025404 0.5 0  0.866025404 0.5 0  0.866025404 0.5 0 ]'
} >nrm.pbrt
sed '/normal N/d' nrm.pbrt >flat.pbrt
run nrm
run flat
num_near "vertex normals 60 degrees off the light: rho cos 60" "$(win nrm.exr 0,0,33,33 mean)" 0.4 1e-5
num_near "the same floor without N: rho" "$(win flat.exr 0,0,33,33 mean)" 0.8 1e-5
check "the mesh file carries nx ny nz" grep -aq '^property float nx$' "nrm/$(sed -n 's/^mesh \([^ ]*\) .*/\1/p' nrm/scene.pms)"

# Mitsuba 3: a checkerboard (color0 0.8, color1 0.2, squares half a unit
# of uv) on a rectangle (uv (x + 1) / 2, (y + 1) / 2), by <ref> to a
# top-level texture; the same directional light (irradiance pi).
# msensor: Mitsuba's camera looking down at the floor, 33 x 33.
msensor() {
	cat <<XML
	<sensor type="perspective">
		<float name="fov" value="40"/>
		<transform name="to_world"><lookat origin="0, 2, 0" target="0, 0, 0" up="0, 0, 1"/></transform>
		<film type="hdrfilm"><integer name="width" value="33"/><integer name="height" value="33"/></film>
	</sensor>
XML
}
mlight='<emitter type="directional"><vector name="direction" x="0" y="-1" z="0"/><rgb name="irradiance" value="3.14159265358979"/></emitter>'
mck() {
	echo '<scene version="3.0.0">'
	msensor
	cat <<XML
	<texture type="checkerboard" id="ck"><rgb name="color0" value="0.8"/><rgb name="color1" value="0.2"/></texture>
	$mlight
	<shape type="rectangle">
		<transform name="to_world"><rotate x="1" angle="-90"/></transform>
		<bsdf type="diffuse">$1</bsdf>
	</shape>
</scene>
XML
}
mck '<ref name="reflectance" id="ck"/>' >mck.xml
mck '<texture type="checkerboard" name="reflectance"><rgb name="color0" value="0.8"/><rgb name="color1" value="0.2"/></texture>' >mck2.xml
for s in mck mck2; do
	pm-import -q $s.xml -o $s/scene.pms 2>$s.err
	check "$s: imports ($(head -c 200 $s.err))" test -s $s/scene.pms
	pm-render -q -e path -p 4 $s/scene.pms -o $s.exr
	set -- $(quads $s)
	num_near "Mitsuba $s: a square reads color0 (0.8)" "$(printf '%s\n' "$@" | sort -g | tail -n 1)" 0.8 1e-5
	num_near "Mitsuba $s: a square reads color1 (0.2)" "$(printf '%s\n' "$@" | sort -g | head -n 1)" 0.2 1e-5
	num_near "Mitsuba $s: diagonal squares alike" "$1" "$4" 1e-6
done
check "Mitsuba's checkerboard: pm's scale 2 2" grep -q '^texture t0 checker .* scale 2 2 offset 0 0' mck/scene.pms

# OBJ + MTL map_Kd: a 1 x 2 image, grey 128 on its top row and black below,
# on the left square with vt (0.5, 0.75) (pm and OBJ: v = 0 is the bottom
# row), white Kd 1 on the right square, both under a lamp (Ke) centred
# above: left / right = the top texel's sRGB decoding 0.2158605.
printf 'P2\n1 2\n255\n128\n0\n' >tb.pgm
cat >t.mtl <<'MTL'
newmtl tex
Kd 1 1 1
map_Kd tb.pgm
newmtl white
Kd 1 1 1
newmtl lamp
Kd 0 0 0
Ke 1 1 1
MTL
cat >t.obj <<'OBJ'
mtllib t.mtl
v -2 0 -1
v -0.2 0 -1
v -0.2 0 1
v -2 0 1
v 0.2 0 -1
v 2 0 -1
v 2 0 1
v 0.2 0 1
v -1 2 -1
v 1 2 -1
v 1 2 1
v -1 2 1
vt 0.5 0.75
usemtl tex
f 4/1 3/1 2/1 1/1
usemtl white
f 8 7 6 5
usemtl lamp
f 9 10 11 12
OBJ
pm-import -q t.obj --camera 'eye 0 1 3 look 0 0 0 up 0 1 0 fov 60' --size 32 16 -o obj/scene.pms 2>obj.err
check "OBJ with map_Kd imports ($(head -c 200 obj.err))" test -s obj/scene.pms
check "map_Kd is pm's texture (albedo tex)" grep -q '^material .* diffuse albedo tex t0' obj/scene.pms
pm-render -q -e path -p 64 obj/scene.pms -o obj.exr
l=$(win obj.exr 4,8,12,14 mean); r=$(win obj.exr 20,8,28,14 mean)
num_near "map_Kd: textured / white = the top texel's 0.2158605" "$(awk -v l="$l" -v r="$r" 'BEGIN { print l / r }')" 0.2158605 0.01

# Mitsuba 3 obj shapes keep their uv and vertex normals. Mitsuba's obj
# loader turns v into 1 - v (flip_tex_coords, default true) and its bitmap
# has v = 0 on the top row (both read in Mitsuba 3's src/shapes/obj.cpp and
# src/textures/bitmap.cpp), so vt (0.5, 0.75) reads the top texel of the
# 1 x 2 image (sRGB 128: 0.2158605) and, with flip_tex_coords false, the
# bottom one (0). The floor under the directional light of irradiance pi
# reads the albedo; vn tilted to cos 0.8 scale it by 0.8, unless
# face_normals.
cat >mf.obj <<'OBJ'
v -1 0 -1
v 1 0 -1
v 1 0 1
v -1 0 1
vt 0.5 0.75
vn 0.6 0.8 0
f 4/1/1 3/1/1 2/1/1 1/1/1
OBJ
sed '/^vn/d; s|/1/1|/1|g' mf.obj >mft.obj
mobj() {
	echo '<scene version="3.0.0">'
	msensor
	cat <<XML
	$mlight
	<shape type="obj">
		<string name="filename" value="$1"/>$2
		<bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="tb.pgm"/></texture></bsdf>
	</shape>
</scene>
XML
}
mobj mft.obj '' >mo.xml
mobj mft.obj '<boolean name="flip_tex_coords" value="false"/>' >mo_noflip.xml
mobj mf.obj '' >mo_n.xml
mobj mf.obj '<boolean name="face_normals" value="true"/>' >mo_fn.xml
for p in "mo 0.2158605 uv_(v_flipped),_the_top_texel" "mo_noflip 0 flip_tex_coords_false:_the_bottom_texel" \
	"mo_n 0.1726884 vertex_normals_at_cos_0.8:_0.8_of_it" "mo_fn 0.2158605 face_normals:_vn_ignored"; do
	set -- $p
	pm-import -q $1.xml -o $1/scene.pms 2>$1.err
	pm-render -q -e path -p 4 $1/scene.pms -o $1.exr
	num_near "Mitsuba obj: $(echo $3 | tr _ ' ') ($2)" "$(win $1.exr 0,0,33,33 mean)" "$2" 1e-5
done
