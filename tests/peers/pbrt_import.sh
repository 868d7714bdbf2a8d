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
# facing down, radiance L (EXTRA: more AreaLightSource parameters).
lamp() {
	echo 'AttributeBegin'
	echo "AreaLightSource \"diffuse\" \"rgb L\" [ $1 $1 $1 ] ${2:-}"
	echo 'Material "diffuse" "rgb reflectance" [ 0 0 0 ]'
	quad '0.1 1.99 -0.6' '0.6 1.99 -0.6' '0.6 1.99 -0.1' '0.1 1.99 -0.1'
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
# both NAME TOLERANCES... : render NAME.pbrt with pbrt and pm, compare.
both() {
	n=$1; shift
	peer_render "$n"; pm_path "$n"
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
