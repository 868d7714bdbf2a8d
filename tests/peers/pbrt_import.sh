# pbrt_import.sh — pm-import against pbrt-v4 itself: grey scenes written
# here, rendered by pbrt and by pm (pm-import, then pm's path tracer), each
# pinning one part of the import by the images' agreement: camera (framing,
# fov on the shorter axis, both aspects), orientation (plain LookAt and
# "Scale -1 1 1"), units (emitters seen directly, L x scale, power),
# emitters (one-sided, two-sided, point, spot, distant, infinite) and each
# mapped material.
#
# Tolerances. Where pm's model is pbrt's (diffuse surfaces, area, point,
# spot, distant and infinite lights, smooth glass) the images differ by
# Monte Carlo noise only: two renders of 256 samples a pixel leave about
# 1 % rms over the 8 x 8 blocks of a lit room and up to 4 % on its darkest
# block (measured), so those scenes ask the mean within 2 %, block rms
# <= 3 %, the worst block within 10 % ("exact" below); a mirrored image, a
# wrong fov or a wrong unit moves whole blocks by tens of percent. Mapped
# materials get wider bounds, each explained where it is checked.
. "$PM_TOP/tests/peers/lib.sh"
exact="0.02 0.03 0.10"

# cam [flip] EYE LOOK : the pbrt camera lines (fov set by FOV, default 50).
cam() {
	[ "$1" = flip ] && echo 'Scale -1 1 1'
	echo "LookAt $2  $3  0 1 0"
	echo "Camera \"perspective\" \"float fov\" [ ${FOV:-50} ]"
}
# quad MATERIAL-LINE P0 P1 P2 P3 : a quad whose front (pbrt's normal, the
# winding's cross product) is (P1 - P0) x (P2 - P0).
quad() {
	echo "Shape \"trianglemesh\" \"point3 P\" [ $1  $2  $3  $4 ] \"integer indices\" [ 0 1 2  0 2 3 ]"
}
# room RHO : the closed box x -1..1, y 0..2, z -1..1 of grey albedo RHO.
room() {
	echo "Material \"diffuse\" \"rgb reflectance\" [ $1 $1 $1 ]"
	quad '-1 0 -1' '-1 0 1' '1 0 1' '1 0 -1'      # floor
	quad '-1 2 -1' '1 2 -1' '1 2 1' '-1 2 1'      # ceiling
	quad '-1 0 -1' '1 0 -1' '1 2 -1' '-1 2 -1'    # back
	quad '-1 0 1' '-1 2 1' '1 2 1' '1 0 1'        # front
	quad '-1 0 -1' '-1 2 -1' '-1 2 1' '-1 0 1'    # left (-x)
	quad '1 0 -1' '1 0 1' '1 2 1' '1 2 -1'        # right (+x)
}
# lamp L [EXTRA] : a 0.5 x 0.5 ceiling lamp off centre toward +x and -z,
# facing down, radiance L (EXTRA: more AreaLightSource parameters), at
# height LAMPY (default 1.99).
lamp() {
	echo 'AttributeBegin'
	echo "AreaLightSource \"diffuse\" \"rgb L\" [ $1 $1 $1 ] ${2:-}"
	echo 'Material "diffuse" "rgb reflectance" [ 0 0 0 ]'
	y=${LAMPY:-1.99}
	quad "0.1 $y -0.6" "0.6 $y -0.6" "0.6 $y -0.1" "0.1 $y -0.1"
	echo 'AttributeEnd'
}
# panel : a small bright panel high on the back wall at +x, facing +z: a
# mirrored or misframed image moves it by many blocks.
panel() {
	echo 'AttributeBegin'
	echo 'AreaLightSource "diffuse" "rgb L" [ 6 6 6 ]'
	quad '0.4 1.3 -0.99' '0.8 1.3 -0.99' '0.8 1.7 -0.99' '0.4 1.7 -0.99'
	echo 'AttributeEnd'
}
# both NAME TOLERANCES... : render NAME.pbrt with pbrt and pm (as many
# samples a pixel as the file gives pbrt), compare.
both() {
	n=$1; shift
	peer_render "$n"; pm_path "$n" "$(sed -n 's/.*"integer pixelsamples" \([0-9]*\).*/\1/p' "$n.pbrt")"
	peer_compare "$n" "$n.pm.exr" "$n.ref.exr" "$@"
}

# Camera and orientation: the lit room from inside, looking at the back
# wall, landscape and portrait, plain LookAt (pbrt's left-handed image) and
# with "Scale -1 1 1" first (the right-handed one).
for v in plain flip; do
	{ cam $v '0 1 0.9' '0 1 -1'; peer_film orient_$v 64 48
	  echo WorldBegin; room 0.5; lamp 4; panel; } >orient_$v.pbrt
	both orient_$v $exact
done
# The panel's side: in pbrt's plain image +x is on the left.
l=$(peer_window orient_plain.ref.exr 0,0,32,24) r=$(peer_window orient_plain.ref.exr 32,0,64,24)
check "plain LookAt: pbrt shows the +x panel on the left ($l > $r)" awk -v l="$l" -v r="$r" 'BEGIN { exit !(l > r) }'
l=$(peer_window orient_plain.pm.exr 0,0,32,24) r=$(peer_window orient_plain.pm.exr 32,0,64,24)
check "plain LookAt: pm too ($l > $r)" awk -v l="$l" -v r="$r" 'BEGIN { exit !(l > r) }'
{ cam plain '0 1 0.9' '0 1 -1'; peer_film portrait 48 64
  echo WorldBegin; room 0.5; lamp 4; panel; } >portrait.pbrt
both portrait $exact
FOV=30 && { cam flip '0 1.2 0.5' '0.3 1.5 -1'; peer_film narrow 64 40
  echo WorldBegin; room 0.5; lamp 4; panel; } >narrow.pbrt
both narrow $exact
FOV=50

# Units: emitters seen directly. Black panels on the back wall: one of
# "rgb L" 1.5 x "scale" 2, one given by "power" 3 pi x 0.08, one the same
# two-sided. pbrt-v4 applies "power" to each triangle's own light, so a
# quad of two triangles of 0.08 m^2 each has radiance power / (pi x 0.08)
# = 3 one-sided, half that two-sided; each pixel at a panel's centre reads
# it in both renderers, and the room they light agrees.
{ cam plain '0 1 0.9' '0 1 -1'; peer_film units 64 48
  echo WorldBegin; room 0.5
  echo 'AttributeBegin AreaLightSource "diffuse" "rgb L" [ 1.5 1.5 1.5 ] "float scale" 2'
  echo 'Material "diffuse" "rgb reflectance" [ 0 0 0 ]'
  quad '-0.8 1.2 -0.99' '-0.4 1.2 -0.99' '-0.4 1.6 -0.99' '-0.8 1.6 -0.99'
  echo 'AttributeEnd'
  echo 'AttributeBegin AreaLightSource "diffuse" "rgb L" [ 1 1 1 ] "float power" 0.75398224'
  echo 'Material "diffuse" "rgb reflectance" [ 0 0 0 ]'
  quad '-0.2 1.2 -0.99' '0.2 1.2 -0.99' '0.2 1.6 -0.99' '-0.2 1.6 -0.99'
  echo 'AttributeEnd'
  echo 'AttributeBegin AreaLightSource "diffuse" "rgb L" [ 1 1 1 ] "float power" 0.75398224 "bool twosided" true'
  echo 'Material "diffuse" "rgb reflectance" [ 0 0 0 ]'
  quad '0.4 1.2 -0.99' '0.8 1.2 -0.99' '0.8 1.6 -0.99' '0.4 1.6 -0.99'
  echo 'AttributeEnd'; } >units.pbrt
both units $exact
# 64 x 48, fov 50 vertical at distance 1.89 (27.2 px a unit): the panels'
# centres (x -0.6, 0, 0.6, y 1.4; mirrored by the plain LookAt) fall at
# pixels (48, 13), (32, 13) and (15, 13), 5 px from their edges; the 5 x 5
# pixels around each are averaged, since pbrt's 4 wavelengths a sample
# leave about 1 % colour noise on a pixel of 256 samples (0.3 % on 25:
# asked within 0.5 %).
for p in "46,11,51,16 3 L_x_scale 0.015" "30,11,35,16 3 power,_one-sided 0.015" "13,11,18,16 1.5 power,_two-sided 0.0075"; do
	set -- $p
	num_near "units: $(echo $3 | tr _ " "): pbrt reads $2" "$(peer_window units.ref.exr "$1")" "$2" "$4"
	num_near "units: $(echo $3 | tr _ " "): pm reads $2" "$(peer_window units.pm.exr "$1")" "$2" "$4"
done

# Emitters: the lamp lowered to 1.6 and turned up (ReverseOrientation: it
# lights the ceiling only; a dim room, so 1024 samples a pixel for 1 %
# noise), the same two-sided, a point, a spot light.
{ cam plain '0 1 0.9' '0 1 -1'; peer_film oneside 64 48 1024
  echo WorldBegin; room 0.5; LAMPY=1.6 lamp 4 | sed 's/^AttributeBegin/&\nReverseOrientation/'; } >oneside.pbrt
both oneside $exact
{ cam plain '0 1 0.9' '0 1 -1'; peer_film twoside 64 48
  echo WorldBegin; room 0.5; LAMPY=1.6 lamp 4 '"bool twosided" true'; } >twoside.pbrt
both twoside $exact
{ cam plain '0 1 0.9' '0 1 -1'; peer_film point 64 48
  echo WorldBegin; room 0.5
  echo 'LightSource "point" "rgb I" [ 2 2 2 ] "float scale" 1.5 "point3 from" [ 0.4 1.6 -0.5 ]'; } >point.pbrt
both point $exact
{ cam plain '0 1 0.9' '0 1 -1'; peer_film spot 64 48
  echo WorldBegin; room 0.5
  echo 'LightSource "spot" "rgb I" [ 5 5 5 ] "point3 from" [ 0 1.9 0 ] "point3 to" [ 0.5 0 -0.6 ] "float coneangle" 30 "float conedeltaangle" 10'; } >spot.pbrt
both spot $exact
# Distant and infinite lights over an open floor with a block on it, seen
# from above (no sky in view).
open() {
	echo 'Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]'
	quad '-6 0 -6' '-6 0 6' '6 0 6' '6 0 -6'
	echo 'AttributeBegin Translate 0.3 0.4 -0.2'
	quad '-0.4 0 -0.4' '-0.4 0 0.4' '0.4 0 0.4' '0.4 0 -0.4'
	quad '-0.4 -0.4 -0.4' '0.4 -0.4 -0.4' '0.4 0 -0.4' '-0.4 0 -0.4'
	quad '-0.4 -0.4 0.4' '-0.4 0 0.4' '0.4 0 0.4' '0.4 -0.4 0.4'
	quad '-0.4 -0.4 -0.4' '-0.4 0 -0.4' '-0.4 0 0.4' '-0.4 -0.4 0.4'
	quad '0.4 -0.4 -0.4' '0.4 -0.4 0.4' '0.4 0 0.4' '0.4 0 -0.4'
	echo 'AttributeEnd'
}
{ cam plain '0 3 2' '0 0 0'; peer_film distant 64 48
  echo WorldBegin; open
  echo 'LightSource "distant" "rgb L" [ 2 2 2 ] "point3 from" [ 1 2 0.5 ] "point3 to" [ 0 0 0 ]'; } >distant.pbrt
both distant $exact
{ cam plain '0 3 2' '0 0 0'; peer_film sky 64 48
  echo WorldBegin; open
  echo 'LightSource "infinite" "rgb L" [ 0.7 0.7 0.7 ]'; } >sky.pbrt
both sky $exact

# Materials: a sphere of each in the lit room (plus a pane for the thin
# ones), seen at 64 x 48 from the room's front.
# mat NAME MATERIAL-LINES [SHAPE] : write NAME.pbrt.
mat() {
	{ cam plain '0 1 0.9' '0 0.7 -0.5'; peer_film "$1" 64 48 "${SPP:-256}"
	  echo WorldBegin; room 0.5; lamp 4
	  echo 'AttributeBegin'; echo "$2"
	  echo "${3:-Translate -0.1 0.45 -0.3 Shape \"sphere\" \"float radius\" 0.45}"
	  echo 'AttributeEnd'; } >"$1.pbrt"
}
# pane: a vertical 1.4 x 1.2 pane across the room in front of the camera.
pane='Shape "trianglemesh" "point3 P" [ -0.7 0.1 0.2  0.7 0.1 0.2  0.7 1.3 0.2  -0.7 1.3 0.2 ] "integer indices" [ 0 1 2  0 2 3 ]'

# Exact: diffuse; a mix of two diffuse (pm: the blended albedo); smooth
# glass (the sphere's caustic on the floor is found by both path tracers
# through the lamp's light on the diffuse floor, hence 1024 samples).
mat diffuse 'Material "diffuse" "rgb reflectance" [ 0.8 0.8 0.8 ]'
both diffuse $exact
mat mix 'MakeNamedMaterial "a" "string type" "diffuse" "rgb reflectance" [ 0.9 0.9 0.9 ]
MakeNamedMaterial "b" "string type" "diffuse" "rgb reflectance" [ 0.1 0.1 0.1 ]
Material "mix" "string materials" [ "a" "b" ] "float amount" 0.3'
both mix $exact
SPP=1024; mat dielectric 'Material "dielectric" "float eta" 1.5'; SPP=256
both dielectric $exact
# The same scene through pm's photon pipeline (the paper's method: 400k
# photons, compensated estimate, k 50): the estimate blurs light over the
# photons' cube, most at the room's corners and the caustic's rim, so its
# blocks are asked within 10 % rms and 40 % (measured 5.4 % and 29 %), the
# whole within 3 % (measured 0.1 %).
pm_photons dielectric 400000 compensated 50 16
peer_compare "dielectric, photon map" dielectric.ph.exr dielectric.ref.exr 0.03 0.10 0.40

# Mapped materials (README's table); the bounds hold what was measured
# (tests/peers numbers in the closing note of issue 22) with room for noise.
# Coated diffuse, smooth: pm's sum of a diffuse and a Blinn lobe for pbrt's
# layered coat; the whole agrees (0.7 % measured) but the lamp's highlight
# on the sphere is a narrow Blinn lobe against a sharp coat reflection, and
# the blocks around it differ up to 18 %.
mat coated 'Material "coateddiffuse" "rgb reflectance" [ 0.6 0.6 0.6 ] "float roughness" 0'
both coated 0.03 0.10 0.30
# Rough coat (roughness 0.3): Blinn for the coat's GGX, and pm's coat does
# not scatter between coat and base as pbrt's random walk does: +8 % mean,
# 22 % rms, 46 % on the highlight's blocks measured.
mat coated_rough 'Material "coateddiffuse" "rgb reflectance" [ 0.6 0.6 0.6 ] "float roughness" 0.3'
both coated_rough 0.12 0.30 0.65
# Smooth conductor (grey eta 0.2, k 3): pm's mirror of the reflectance at
# normal incidence (0.923) for pbrt's Fresnel curve, which rises toward 1 at
# grazing angles; and the lamp is seen in a mirror only by chance in both
# path tracers (no light sampling after a specular bounce): 0.6 % mean,
# 4 % rms, 23 % on the lamp's reflection measured. The same with pbrt's
# "reflectance" parameterisation.
mat conductor 'Material "conductor" "rgb eta" [ 0.2 0.2 0.2 ] "rgb k" [ 3 3 3 ] "float roughness" 0'
both conductor 0.03 0.08 0.40
mat conductor_refl 'Material "conductor" "rgb reflectance" [ 0.8 0.8 0.8 ]'
both conductor_refl 0.03 0.08 0.40
# Rough conductor (roughness 0.2): a Blinn lobe for GGX, narrower in the
# tails: -7 % mean, 16 % rms, 47 % on the highlight's blocks measured.
mat conductor_rough 'Material "conductor" "rgb eta" [ 0.2 0.2 0.2 ] "rgb k" [ 3 3 3 ] "float roughness" 0.2'
both conductor_rough 0.12 0.25 0.70
# Thin dielectric pane before the camera: pm's ior-1 glass keeps the
# straight transmission and drops the pane's reflection 2R/(1 + R) of the
# lit room behind the camera: -8 % mean, 9 % rms, 17 % measured.
mat thin 'Material "thindielectric" "float eta" 1.5' "$pane"
both thin 0.12 0.15 0.30
# Diffuse transmission: pm keeps the reflection (albedo 0.5) and drops the
# transmission (0.3). On a sphere lit from above the transmitted light is
# mostly lost inside: -9 % mean, 18 % rms, 43 % measured. A pane lit from
# behind (the lamp is beyond it) shows pm nothing of that light: reported
# as a known difference, not a bound.
mat difftrans 'Material "diffusetransmission" "rgb reflectance" [ 0.5 0.5 0.5 ] "rgb transmittance" [ 0.3 0.3 0.3 ]'
both difftrans 0.15 0.30 0.65
mat difftrans_pane 'Material "diffusetransmission" "rgb reflectance" [ 0.5 0.5 0.5 ] "rgb transmittance" [ 0.3 0.3 0.3 ]' "$pane"
peer_render difftrans_pane; pm_path difftrans_pane
KNOWN="pm has no diffuse transmission" peer_compare difftrans_pane difftrans_pane.pm.exr difftrans_pane.ref.exr 0.02 0.03 0.10
# Mix of a diffuse and a conductor (amount 0.3: pbrt picks the conductor
# 30 % of the time): pm keeps the diffuse one (the larger weight), missing
# the metal's share of the lamp's reflection: -3 % mean, 8 % rms, 43 %
# measured.
mat mix_metal 'MakeNamedMaterial "a" "string type" "diffuse" "rgb reflectance" [ 0.8 0.8 0.8 ]
MakeNamedMaterial "b" "string type" "conductor" "rgb eta" [ 0.2 0.2 0.2 ] "rgb k" [ 3 3 3 ]
Material "mix" "string materials" [ "a" "b" ] "float amount" 0.3'
both mix_metal 0.06 0.15 0.65
