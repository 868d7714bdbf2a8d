# import_mitsuba.sh — pm-import on Mitsuba 3 XML scenes written here: a
# lamp at +x lands on the right (Mitsuba's lookat is right-handed), fov_axis
# x, y and smaller in both aspects, <default>/$name, <include>, <ref id>,
# to_world children applied in the order written, a directly seen area
# emitter reading its radiance, a one-sided emitter lighting only its front
# (flip_normals turns it away), a point light's intensity, the bsdf rules.
. "$PM_TOP/tests/lib.sh"
stat="$PM_BIN/../tests/tools/exrstat"
px() { "$stat" --pixel "$2" "$1" | sed -n 's/^mean: //p'; }
win() { "$stat" --window "$2" "$1" | sed -n 's/^mean: //p'; }
fov_of() { sed -n 's/^camera .* fov \([0-9.e+-]*\) .*/\1/p' "$1"; }

# scene AXIS W H: camera at z = 5 looking at the origin, fov 40 on AXIS;
# the lamp (an included file) from x 0.5 to 1.5, facing the camera, L 3.
scene() {
	cat <<EOF
<scene version="3.0.0">
	<default name="fov" value="40"/>
	<sensor type="perspective">
		<float name="fov" value="\$fov"/>
		<string name="fov_axis" value="$1"/>
		<transform name="to_world">
			<lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/>
		</transform>
		<film type="hdrfilm">
			<integer name="width" value="$2"/>
			<integer name="height" value="$3"/>
		</film>
	</sensor>
	<include filename="lamp.xml"/>
</scene>
EOF
}
cat >lamp.xml <<'EOF'
<scene version="3.0.0">
	<bsdf type="diffuse" id="black"><rgb name="reflectance" value="0"/></bsdf>
	<shape type="rectangle">
		<transform name="to_world">
			<scale value="0.5"/>
			<translate x="1"/>
		</transform>
		<ref id="black"/>
		<emitter type="area"><rgb name="radiance" value="3, 3, 3"/></emitter>
	</shape>
</scene>
EOF
# x, 48 x 32: horizontal fov 40, 13.19 px per unit: the lamp covers
# columns 30.6-43.8 (right). y: vertical fov 40, 8.79 px per unit,
# columns 28.4-37.2. smaller in a 32 x 48 portrait: horizontal 40, 8.79
# px per unit, columns 20.4-29.2.
scene x 48 32 >x.xml
scene y 48 32 >y.xml
scene smaller 32 48 >s.xml
for s in x y s; do
	pm-import -q $s.xml -o $s/scene.pms 2>err.txt
	check "$s: imports ($(head -c 200 err.txt))" test -s $s/scene.pms
	pm-render -q -e path -p 64 $s/scene.pms -o $s.exr
done
num_near "lookat: lamp at +x seen on the right, reads its radiance 3" "$(px x.exr 37,16)" 3 1e-4
num_near "lookat: nothing on the left" "$(px x.exr 10,16)" 0 0
num_near "fov_axis x (the default): vertical fov 2 atan(tan 20 x 32/48) = 27.278" "$(fov_of x/scene.pms)" 27.2781 0.001
num_near "fov_axis x: the lamp is 13.19 px wide" \
	"$(awk -v m="$(win x.exr 0,16,48,17)" 'BEGIN { print m * 48 / 3 }')" 13.19 0.2
num_near "fov_axis y: vertical 40" "$(fov_of y/scene.pms)" 40 1e-6
num_near "fov_axis y: the lamp is 8.79 px wide" \
	"$(awk -v m="$(win y.exr 0,16,48,17)" 'BEGIN { print m * 48 / 3 }')" 8.79 0.15
num_near "fov_axis smaller, portrait: vertical 2 atan(tan 20 x 48/32) = 57.265" "$(fov_of s/scene.pms)" 57.2651 0.001
num_near "fov_axis smaller, portrait: lamp on the right, reads 3" "$(px s.exr 24,24)" 3 1e-4

# A sensor whose to_world mirrors x after the lookat shows the mirror
# image: the lamp on the left (pm mirrors the world to show it).
scene x 48 32 | sed 's|<lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/>|&<scale x="-1"/>|' >m.xml
pm-import -q m.xml -o m/scene.pms && pm-render -q -e path -p 4 m/scene.pms -o m.exr
num_near "a mirroring sensor transform: the lamp on the left, reads 3" "$(px m.exr 10,16)" 3 1e-4
num_near "... nothing on the right" "$(px m.exr 37,16)" 0 0
# fov_axis larger on the portrait: 40 is the vertical angle; diagonal on the
# landscape: tan(fov_y/2) = tan 20 x 32 / sqrt(48^2 + 32^2): fov_y 22.97.
scene larger 32 48 >l.xml
scene diagonal 48 32 >d.xml
pm-import -q l.xml -o l/scene.pms && pm-import -q d.xml -o d/scene.pms
num_near "fov_axis larger, portrait: vertical 40" "$(fov_of l/scene.pms)" 40 1e-6
num_near "fov_axis diagonal, landscape: vertical 22.97" "$(fov_of d/scene.pms)" \
	"$(awk 'BEGIN { t = sin(20 * 3.14159265358979 / 180) / cos(20 * 3.14159265358979 / 180) * 32 / sqrt(48 * 48 + 32 * 32); print 2 * atan2(t, 1) * 180 / 3.14159265358979 }')" 1e-4

# A one-sided lamp (2 x 2, L 1) at height 1 facing down over a grey floor
# (rho 0.5), the camera between them: the floor reads rho E / pi =
# 0.27706 (as import_pbrt.sh derives); flip_normals turns it up.
floor() {
	cat <<EOF
<scene version="3.0.0">
	<sensor type="perspective">
		<float name="fov" value="10"/>
		<transform name="to_world"><lookat origin="0, 0.5, 0.001" target="0, 0, 0" up="0, 1, 0"/></transform>
		<film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
	</sensor>
	<bsdf type="twosided" id="grey"><bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></bsdf>
	<shape type="rectangle">
		<transform name="to_world"><scale value="5"/><rotate x="1" angle="-90"/></transform>
		<ref id="grey"/>
	</shape>
	$1
</scene>
EOF
}
lamp='<shape type="rectangle">
		<transform name="to_world"><rotate x="1" angle="90"/><translate y="1"/></transform>
		<boolean name="flip_normals" value="FLIP"/>
		<bsdf type="diffuse"><rgb name="reflectance" value="0"/></bsdf>
		<emitter type="area"><rgb name="radiance" value="1"/></emitter>
	</shape>'
floor "$(echo "$lamp" | sed s/FLIP/false/)" >down.xml
floor "$(echo "$lamp" | sed s/FLIP/true/)" >up.xml
for s in down up; do
	pm-import -q $s.xml -o $s/scene.pms && pm-render -q -e path -p 256 $s/scene.pms -o $s.exr
done
num_near "one-sided area emitter facing the floor: rho E / pi = 0.27706" "$(win down.exr 0,0,8,8)" 0.27706 0.003
num_near "the same with flip_normals leaves the floor dark" "$(win up.exr 0,0,8,8)" 0 0

# A point light of intensity 2 at height 2: the floor reads 0.5 x 2/4 / pi.
floor '<emitter type="point"><point name="position" x="0" y="2" z="0"/><rgb name="intensity" value="2"/></emitter>
	<emitter type="projector"><rgb name="irradiance" value="1"/></emitter>' >point.xml
pm-import point.xml -o point/scene.pms 2>notes.txt
pm-render -q -e path -p 16 point/scene.pms -o point.exr
num_near "point light, intensity 2 at height 2: floor 0.0796" "$(win point.exr 0,0,8,8)" 0.0795775 0.002
check "the projector emitter dropped with a note naming its line" \
	grep -q "^pm-import: point.xml:13: light 'projector': pm has no such light, dropped" notes.txt

# The bsdf rules (README).
{ echo '<scene version="3.0.0">'
  echo '<sensor type="perspective"><float name="fov" value="40"/></sensor>'
  echo '<shape type="sphere"><emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>'
  for b in '<bsdf type="roughconductor"><string name="material" value="Au"/><float name="alpha" value="0.2"/></bsdf>' \
           '<bsdf type="conductor"/>' \
           '<bsdf type="plastic"><rgb name="diffuse_reflectance" value="0.5"/><float name="int_ior" value="1.5"/><float name="ext_ior" value="1"/></bsdf>' \
           '<bsdf type="dielectric"><string name="int_ior" value="water"/></bsdf>' \
           '<bsdf type="bumpmap"><bsdf type="diffuse"><rgb name="reflectance" value="0.3"/></bsdf></bsdf>'; do
	echo "<shape type=\"cube\">$b</shape>"
  done
  echo '</scene>'; } >mats.xml
pm-import mats.xml -o mats/scene.pms 2>notes.txt
check "roughconductor Au, alpha 0.2: glossy, gold's F0, exponent 48" \
	grep -q 'glossy kd 0 0 0 ks 1 0.766 0.336 exponent 48$' mats/scene.pms
check "conductor (material none): a perfect mirror" grep -q 'mirror reflect 1 1 1$' mats/scene.pms
kd=$(sed -n 's/.* glossy kd \([0-9.]*\) .* ks 0.04 0.04 0.04 exponent 1000000$/\1/p' mats/scene.pms)
num_near "plastic (ior 1.5): kd through the coat 0.2761 (as import_pbrt.sh), ks 0.04, smooth" "$kd" 0.2761 5e-4
check "dielectric water: ior 1.3330 / 1.000277" grep -q 'glass ior 1.33263' mats/scene.pms
check "bumpmap: its nested bsdf, with a note" grep -q 'diffuse albedo 0.3 0.3 0.3$' mats/scene.pms
check "bumpmap: the note names mats.xml:8" grep -q '^pm-import: mats.xml:8: bumpmap: dropped' notes.txt
