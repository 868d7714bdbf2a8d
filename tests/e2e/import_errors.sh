# import_errors.sh — malformed inputs to pm-import: one stderr line naming
# the file and line, exit 1, and nothing written: no output directory when
# there was none, the previous scene and meshes byte for byte when there
# was one. Also the command-line errors (exit 2).
. "$PM_TOP/tests/lib.sh"

cam='LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
WorldBegin'
lamp='AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]
Shape "trianglemesh" "point3 P" [ 0 0 0  1 0 0  1 1 0 ] "integer indices" [ 0 1 2 ]'

# fails NAME PATTERN INPUT: exit 1, one line matching, no out/ made
fails() {
	rm -rf out
	expect_fail "$1" 1 "$2" pm-import "$3" -o out/scene.pms
	check "$1: nothing written" test ! -e out
}

printf '%s\n%s\nFooBar 1 2 3\n' "$cam" "$lamp" >unknown.pbrt
fails "unknown directive" "^pm-import: unknown.pbrt:7: unknown directive 'FooBar'$" unknown.pbrt
printf '%s\nInclude "nope.pbrt"\n' "$cam" >inc.pbrt
fails "missing include" "^pm-import: inc.pbrt:5: cannot open 'nope.pbrt': No such file or directory$" inc.pbrt
printf 'Include "b.pbrt"\n' >a.pbrt
printf '\n\nInclude "a.pbrt"\n' >b.pbrt
fails "include recursion" "^pm-import: b.pbrt:3: 'a.pbrt' includes itself (recursion)$" a.pbrt
printf '%s\nShape "plymesh" "string filename" "gone.ply"\n' "$cam" >mesh.pbrt
fails "missing mesh" "^pm-import: mesh.pbrt:5: cannot open 'gone.ply'\|^pm-import: mesh.pbrt:5: 'gone.ply': cannot open" mesh.pbrt
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n3 0 1 7\n' >bad.ply
printf '%s\nShape "plymesh" "string filename" "bad.ply"\n' "$cam" >badply.pbrt
fails "PLY index out of range" "^pm-import: badply.pbrt:5: 'bad.ply': face 0: vertex index 7 out of range$" badply.pbrt
head -c $(($(sed -n '1,/end_header/p' bad.ply | wc -c) + 8)) bad.ply >cut.ply
sed 's/bad.ply/cut.ply/' badply.pbrt >cutply.pbrt
fails "truncated PLY" "^pm-import: cutply.pbrt:5: 'cut.ply': truncated in vertex" cutply.pbrt
printf '%s\nShape "trianglemesh" "point3 P" [ 0 0 0 1 0 0 1 1 0 ] "integer indices" [ 0 1 3 ]\n' "$cam" >idx.pbrt
fails "trianglemesh index out of range" "^pm-import: idx.pbrt:5: trianglemesh: index 3 out of range (3 points)$" idx.pbrt
printf '%s\nShape "sphere" "float radius" [ 1\n' "$cam" >open.pbrt
fails "missing ]" "^pm-import: open.pbrt:6: parameter 'radius': missing ']'$" open.pbrt
printf '%s\nMaterial "diffuse" "string name\n' "$cam" >str.pbrt
fails "unterminated string" "^pm-import: str.pbrt:5: unterminated string$" str.pbrt
printf '%s\nAttributeEnd\n' "$cam" >pop.pbrt
fails "AttributeEnd without AttributeBegin" "^pm-import: pop.pbrt:5: AttributeEnd without a matching begin$" pop.pbrt
printf '%s\n' "$cam" 'Shape "sphere"' >dark.pbrt
fails "no light pm can render" "^pm-import: dark.pbrt: no light pm can render" dark.pbrt

# Mitsuba: truncated XML, an unknown element, a missing include.
printf '<scene version="3.0.0">\n<sensor type="perspective">\n<float name="fov" value="40"/>\n' >cut.xml
fails "truncated XML" "^pm-import: cut.xml:4: XML: no element found$" cut.xml
printf '<scene version="3.0.0">\n<sensor type="perspective"><float name="fov" value="40"/></sensor>\n<thing/>\n</scene>\n' >elem.xml
fails "unknown element" "^pm-import: elem.xml:3: unknown element <thing> in <scene>$" elem.xml
printf '<scene version="3.0.0">\n<include filename="none.xml"/>\n</scene>\n' >inc.xml
fails "missing XML include" "^pm-import: inc.xml:2: cannot open 'none.xml': No such file or directory$" inc.xml
printf '<scene version="3.0.0">\n<include filename="self.xml"/>\n</scene>\n' >self.xml
fails "XML include recursion" "^pm-import: self.xml:2: 'self.xml' includes itself (recursion)$" self.xml

# OBJ: an index past the vertices, an unknown material.
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 4\n' >far.obj
fails "OBJ index out of range" "^pm-import: far.obj:4: f: vertex index 4 out of range (3 vertices so far)$" far.obj
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl nope\nf 1 2 3\n' >mtl.obj
fails "OBJ unknown material" "^pm-import: mtl.obj:4: usemtl: unknown material 'nope'$" mtl.obj

# A failed re-import leaves the previous scene and its meshes as they were.
printf '%s\n%s\n' "$cam" "$lamp" >good.pbrt
pm-import -q good.pbrt -o keep/scene.pms
ls -l keep >before.txt; cat keep/* >before.bin
expect_fail "re-import of a bad file fails" 1 "unknown directive" pm-import unknown.pbrt -o keep/scene.pms
ls -l keep >after.txt; cat keep/* >after.bin
check "a failed re-import leaves the old scene and meshes untouched" cmp -s before.bin after.bin
check "... and no file added or removed" cmp -s before.txt after.txt

# Command line (exit 2).
expect_fail "output not .pms" 2 "the output is a scene: name it NAME.pms" pm-import good.pbrt -o out.exr
expect_fail "unknown extension" 2 "unknown format" pm-import good.txt -o out/scene.pms
expect_fail "--size wants two numbers" 2 "^pm-import: --size" pm-import good.pbrt -o out/scene.pms --size 8
expect_fail "bad --camera" 2 "^pm-import: --camera: want" pm-import good.pbrt -o out/scene.pms --camera 'eye 0 0 5'

# Cut short anywhere: every prefix at 16 points of a pbrt file with an
# instanced PLY mesh, a Mitsuba file and an OBJ+MTL is either read (exit
# 0) or refused with one line (exit 1); never a crash (the ASan tree
# checks memory too), never output left behind by a refusal.
printf 'ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n' >tri.ply
printf '\000\000\000\000\000\000\000\000\000\000\000\000\000\000\200\077\000\000\000\000\000\000\000\000\000\000\200\077\000\000\200\077\000\000\000\000\003\000\000\000\000\001\000\000\000\002\000\000\000' >>tri.ply
{ printf '%s\n%s\n' "$cam" "$lamp"
  echo 'ObjectBegin "o" Shape "plymesh" "string filename" "tri.ply" ObjectEnd'
  echo 'AttributeBegin Translate 1 0 0 ObjectInstance "o" AttributeEnd'
  echo 'Material "coateddiffuse" "rgb reflectance" [ 0.5 0.5 0.5 ] "float roughness" 0.1'
  echo 'Shape "sphere" "float radius" 0.5'; } >whole.pbrt
printf '<scene version="3.0.0">\n<default name="f" value="40"/>\n<sensor type="perspective"><float name="fov" value="$f"/><transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform><film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>\n<bsdf type="roughplastic" id="p"><rgb name="diffuse_reflectance" value="0.5"/></bsdf>\n<shape type="ply"><string name="filename" value="tri.ply"/><ref id="p"/><emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>\n</scene>\n' >whole.xml
printf 'newmtl l\nKe 1 1 1\nKd 0.5 0.5 0.5\n' >whole.mtl
printf 'mtllib whole.mtl\no a\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nusemtl l\nf 1/1 2/1 3/1\nf -3 -2 -1\n' >whole.obj
for f in whole.pbrt whole.xml whole.obj; do
	pm-import -q $f -o full/scene.pms 2>err.txt
	check "$f whole: imports ($(head -c 200 err.txt))" test -s full/scene.pms
done
for f in whole.pbrt whole.xml whole.obj tri.ply; do
	n=$(wc -c <$f) bad=
	cp $f keep.$f
	for k in 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16; do
		head -c $((n * k / 17)) keep.$f >$f
		case $f in tri.ply) in=whole.pbrt ;; *) in=$f ;; esac
		rm -rf cut
		pm-import -q $in -o cut/scene.pms >/dev/null 2>err.txt
		rc=$?
		if [ $rc -ne 0 ] && { [ $rc -ne 1 ] || [ "$(wc -l <err.txt)" -ne 1 ] || [ -e cut ]; }; then bad="$bad $k/17:rc=$rc"; fi
	done
	cp keep.$f $f
	check "$f cut short at 16 points: exit 0, or 1 with one line and nothing written:${bad:- yes}" test -z "$bad"
done

# A scene beyond pm's range (formats/scene.md, "Range") is the input's
# fault, not pm-import's: the message names the source file, and nothing
# is written.
{ echo 'LookAt 0 0 5  0 0 0  0 1 0'
  echo 'Camera "perspective" "float fov" [ 40 ]'
  echo 'WorldBegin'
  echo 'AreaLightSource "diffuse" "rgb L" [ 1e35 1e35 1e35 ]'
  echo 'Shape "trianglemesh" "point3 P" [ -1 -1 0  1 -1 0  1 1 0 ] "integer indices" [ 0 1 2 ]'; } >hot.pbrt
expect_fail "out of range: the source file named, not called a pm-import bug" 1 \
	"^pm-import: hot.pbrt: the scene is beyond what pm renders: material .*emit 1e+35" pm-import hot.pbrt -o hot/scene.pms
check "out of range: nothing written" test ! -e hot
