# import_lights.sh — pbrt-v4's spot, distant and infinite lights and
# Mitsuba 3's spot, directional and constant emitters through pm-import,
# each read back from a diffuse floor against its closed form: a distant
# light of irradiance E at angle theta gives rho E cos(theta) / pi, a spot
# of intensity I at height h gives rho I / (pi h^2) on its axis and 0
# outside its cone, a constant sky of radiance L gives rho L; pbrt's
# equal-area image sky, resampled to lat-long, lights the floor as turned.
. "$PM_TOP/tests/lib.sh"
stat="$PM_BIN/../tests/tools/exrstat"
win() { "$stat" --window "$2" "$1" | sed -n "s/^$3: //p"; }
pi=3.14159265358979

# pbrt-v4: a grey floor (rho 0.5) at y = 0 seen from straight above.
pbrt() {
	echo 'LookAt 0 0.5 0.001  0 0 0  0 1 0'
	echo "Camera \"perspective\" \"float fov\" [ $1 ]"
	echo 'Film "rgb" "integer xresolution" [ 33 ] "integer yresolution" [ 33 ] "string filename" "out.exr"'
	echo 'WorldBegin'
	echo 'Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]'
	echo 'Shape "trianglemesh" "point3 P" [ -9 0 -9  -9 0 9  9 0 9  9 0 -9 ] "integer indices" [ 0 1 2 0 2 3 ]'
	echo "$2"
}
# Mitsuba 3: the same floor and camera.
mitsuba() {
	cat <<XML
<scene version="3.0.0">
	<sensor type="perspective">
		<float name="fov" value="$1"/>
		<transform name="to_world"><lookat origin="0, 0.5, 0.001" target="0, 0, 0" up="0, 1, 0"/></transform>
		<film type="hdrfilm"><integer name="width" value="33"/><integer name="height" value="33"/></film>
	</sensor>
	<shape type="rectangle">
		<transform name="to_world"><scale value="9"/><rotate x="1" angle="-90"/></transform>
		<bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf>
	</shape>
	$2
</scene>
XML
}
run() {   # NAME: import NAME.pbrt or NAME.xml, render NAME.exr
	f=$(ls $1.pbrt $1.xml 2>/dev/null)
	pm-import -q "$f" -o $1/scene.pms 2>$1.err
	check "$1: imports ($(head -c 200 $1.err))" test -s $1/scene.pms
	pm-render -q -e path -p "${2:-1}" $1/scene.pms -o $1.exr
}

# Distant: L 2 x scale 1.5 (pbrt) and irradiance 3 (Mitsuba), travelling
# along (1, -2, 0): cos theta = 2 / sqrt(5) on the floor.
want=$(awk -v pi=$pi 'BEGIN { printf "%.9g", 0.5 * 3 * 2 / sqrt(5) / pi }')
pbrt 2 'LightSource "distant" "point3 from" [ 0 0 0 ] "point3 to" [ 1 -2 0 ] "rgb L" [ 2 2 2 ] "float scale" 1.5' >sun.pbrt
mitsuba 2 '<emitter type="directional"><vector name="direction" x="1" y="-2" z="0"/><rgb name="irradiance" value="3"/></emitter>' >msun.xml
pbrt 2 'LightSource "distant" "point3 from" [ 0 0 0 ] "point3 to" [ 1 -2 0 ] "rgb L" [ 1 1 1 ] "float illuminance" 3' >lux.pbrt
for s in sun msun lux; do run $s 4; done
num_near "pbrt distant L x scale on a floor: rho E cos / pi" "$(win sun.exr 0,0,33,33 mean)" "$want" 1e-5
num_near "Mitsuba directional irradiance: rho E cos / pi" "$(win msun.exr 0,0,33,33 mean)" "$want" 1e-5
num_near "pbrt distant with illuminance 3: rho E cos / pi" "$(win lux.exr 0,0,33,33 mean)" "$want" 1e-5

# Spot 2 above the floor aiming down, I 8: rho I / (pi h^2) on the axis;
# the 33 x 33 image spans 120 degrees, its corners outside the cone.
axis=$(awk -v pi=$pi 'BEGIN { printf "%.9g", 0.5 * 8 / (pi * 4) }')
pbrt 120 'LightSource "spot" "point3 from" [ 0 2 0 ] "point3 to" [ 0 0 0 ] "rgb I" [ 4 4 4 ] "float scale" 2 "float coneangle" 20 "float conedeltaangle" 10' >spot.pbrt
mitsuba 120 '<emitter type="spot"><transform name="to_world"><lookat origin="0, 2, 0" target="0, 0, 0" up="0, 0, 1"/></transform><rgb name="intensity" value="8"/><float name="cutoff_angle" value="20"/><float name="beam_width" value="10"/></emitter>' >mspot.xml
for s in spot mspot; do run $s; done
num_near "pbrt spot I x scale on its axis: rho I / (pi h^2)" "$(win spot.exr 16,16,17,17 mean)" "$axis" 3e-4
num_near "Mitsuba spot intensity on its axis: rho I / (pi h^2)" "$(win mspot.exr 16,16,17,17 mean)" "$axis" 3e-4
num_near "pbrt spot: black outside its cone" "$(win spot.exr 0,0,2,2 max)" 0 0
num_near "Mitsuba spot: black outside its cone" "$(win mspot.exr 0,0,2,2 max)" 0 0
check "pbrt spot: smoothstep falloff, cone 20 10" grep -q '^spotlight .* cone 20 10 falloff smooth' spot/scene.pms
check "Mitsuba spot: linear falloff, cone 20 10" grep -q '^spotlight .* cone 20 10 falloff linear' mspot/scene.pms
# pbrt "power" 2 pi sets I so the spot emits it: I = 1 / (1 - (cos 20 + cos 10) / 2).
sed 's/"float scale" 2/"float power" 6.283185307/' spot.pbrt >pspot.pbrt
pm-import -q pspot.pbrt -o pspot/scene.pms
num_near "pbrt spot power: I = power / (2 pi (1 - (cos a0 + cos a1) / 2))" \
	"$(sed -n 's/.* intensity \([0-9.e+-]*\) .*/\1/p' pspot/scene.pms)" \
	"$(awk -v pi=$pi 'BEGIN { printf "%.9g", 4 / (1 - (cos(20 * pi / 180) + cos(10 * pi / 180)) / 2) }')" 1e-6

# A constant sky of radiance 2 (pbrt L 1 x scale 2, Mitsuba radiance 2):
# an infinite floor reads rho L = 1.
pbrt 2 'LightSource "infinite" "rgb L" [ 1 1 1 ] "float scale" 2' >sky.pbrt
mitsuba 2 '<emitter type="constant"><rgb name="radiance" value="2"/></emitter>' >msky.xml
pbrt 2 'LightSource "infinite" "rgb L" [ 1 1 1 ] "float illuminance" 6.283185307' >skylux.pbrt
for s in sky msky skylux; do run $s 16; done
num_near "pbrt infinite L x scale: a floor reads rho L" "$(win sky.exr 0,0,33,33 mean)" 1 0.01
num_near "Mitsuba constant radiance: a floor reads rho L" "$(win msky.exr 0,0,33,33 mean)" 1 0.01
num_near "pbrt infinite illuminance 2 pi: L = 2, floor reads 1" "$(win skylux.exr 0,0,33,33 mean)" 1 0.01

# pbrt-v4's image skies are equal-area octahedral squares, resampled into
# pm's lat-long map: a 64 x 64 image of radiance 1 inside the diamond
# |u'| + |v'| < 1 (the light's +z hemisphere), 0 outside (texels centred
# on the edge 0.5, sRGB 188). Turned by
# Rotate -90 1 0 0 (+z up) the floor sees a sky of 1 and reads rho = 0.5;
# unturned, the bright half is sideways and lights half the floor's
# cosine-weighted hemisphere: 0.25.
awk 'BEGIN { print "P2\n64 64\n255"; for (y = 0; y < 64; y++) for (x = 0; x < 64; x++) {
	u = 2 * (x + 0.5) / 64 - 1; v = 2 * (y + 0.5) / 64 - 1; if (u < 0) u = -u; if (v < 0) v = -v
	print (u + v < 0.999 ? 255 : u + v < 1.001 ? 188 : 0) } }' >eqsky.pgm
pbrt 2 'AttributeBegin Rotate -90 1 0 0 LightSource "infinite" "string filename" "eqsky.pgm" AttributeEnd' >equp.pbrt
pbrt 2 'LightSource "infinite" "string filename" "eqsky.pgm"' >eqside.pbrt
for s in equp eqside; do run $s 16; done
num_near "equal-area sky, +z turned up: the floor reads rho" "$(win equp.exr 0,0,33,33 mean)" 0.5 0.01
num_near "equal-area sky unturned: half the hemisphere, rho / 2" "$(win eqside.exr 0,0,33,33 mean)" 0.25 0.01
pm-import eqside.pbrt -o eqside/scene.pms 2>eqside.err
check "the resampling is noted with its line" grep -q 'eqside.pbrt:7: .*equal-area square resampled' eqside.err
