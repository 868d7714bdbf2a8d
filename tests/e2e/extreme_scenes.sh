# extreme_scenes.sh — the range of formats/scene.md ("Range", issue 24):
# scenes with extreme but parseable values end with clean images or a
# one-line refusal naming FILE:LINE, never an abort inside Embree; a scene
# scaled within the range renders as it does at scale 1.
. "$PM_TOP/tests/lib.sh"
scenes="$PM_TOP/tests/fuzz/scenes.sh"
B="$PM_BIN/.."

# every scene that ever failed the drill, then a few generated ones: four
# tame (in range, so they must render): a room 1e9 across by 'scale' with
# fov 179.999, ior 1e-30, move, a slab 1e12 wide and three lights of 1e29
# W; a room 1e-7 across with albedo 1 under that slab, exponent 3e38; one
# 1e-8 across with exponent 1e30 and a mesh vertex at 1e-30; a closed room
# 1e11 across with albedo 1 and fov 0.01; and one wild scene (fov 1e-45,
# refused). More: make fuzz-scenes N=...
sh "$scenes" "$B" --cases "$PM_TOP"/tests/fuzz/regress/pipeline/*/
for s in 9 33 55 47 4; do
	sh "$scenes" "$B" "$s" "$s"
done

# the messages: file, line, statement, and the range's page
room() {  # room UNIT POWER EXTRA-LINE: the unit room, scaled by writing
	u=$1
	cat <<S
camera eye 0 $u $(awk "BEGIN{print 0.95*$u}")  look 0 $u 0  up 0 1 0  fov 60  size 12 9
material w diffuse albedo 0.7 0.7 0.7
material g glossy kd 0.2 0.2 0.2 ks 0.5 0.5 0.5 exponent 30
box w -$u 0 -$u $u $(awk "BEGIN{print 2*$u}") $u inward
box g $(awk "BEGIN{print -0.3*$u, 0, -0.3*$u, 0.3*$u, 0.6*$u, 0.3*$u}")
pointlight 0 $(awk "BEGIN{print 1.9*$u}") 0 power $2 $2 $2
$3
S
}
room 1 10 'box w -1 0.2 -0.2 1e12 0.4 0.2' >edge.pms
check "a vertex at 1e12 is in range" pm-shoot -q -n 100 edge.pms -o edge.pm
room 1 10 'box w -1 0.2 -0.2 1.0001e12 0.4 0.2' >past.pms
expect_fail "a vertex past 1e12: refused at its line" 1 '^pm-shoot: past.pms:7: box: a vertex reaches 1.*e+12' \
	pm-shoot -q -n 100 past.pms -o out.pm
check "... and nothing written" [ ! -e out.pm ]
room 1 10 'sphere w 0 0.5 0 0.1 move 0 -1.1e12 0' >move.pms
expect_fail "'move' past 1e12: refused" 1 "^pm-render: move.pms:7: sphere: a vertex with 'move' reaches" \
	pm-render -q -p 1 -e path move.pms -o out.exr
room 1e-10 1e-19 '' >tiny.pms
sed -i 's/^camera.*/camera eye 0 0 1  look 0 0 0  up 0 1 0  fov 60  size 12 9/' tiny.pms
expect_fail "a scene 2e-10 across: refused at the last line" 1 '^pm-shoot: tiny.pms:7: the scene is 2e-10 across' \
	pm-shoot -q -n 100 tiny.pms -o out.pm
room 1 1e31 '' >power.pms
expect_fail "a point light over 1e30 W: refused at its line" 1 '^pm-shoot: power.pms:6: pointlight: power 1e+31' \
	pm-shoot -q -n 100 power.pms -o out.pm
room 0.01 1e27 '' >power2.pms
expect_fail "a point light over 1e30 W per extent squared: refused" 1 \
	'^pm-shoot: power2.pms:7: pointlight 1 of the file: power 1e+27 is more than 1e+30 times' \
	pm-shoot -q -n 100 power2.pms -o out.pm
# Distant and environment lights: bounded in their own units and counted in the total by what they send through the scene's disk.
room 1 10 'distantlight dir 0 -1 0 irradiance 1e31 1e31 1e31' >sun.pms
expect_fail "a distant light over 1e30 W/m^2: refused at its line" 1 \
	'^pm-shoot: sun.pms:7: distantlight: irradiance 1e+31 W/m^2' pm-shoot -q -n 100 sun.pms -o out.pm
room 1 10 'distantlight dir 0 -1 0 irradiance 2e29 2e29 2e29' >sun2.pms
expect_fail "a sun of 2e29 W/m^2 on a room 2 across (E pi r^2 = 1.9e30 W): over 1e30 W in all" 1 \
	'^pm-shoot: sun2.pms:7: the lights emit .* more than' pm-shoot -q -n 100 sun2.pms -o out.pm
room 1 10 'material hot diffuse albedo 0.5 0.5 0.5 emit 1e31 0 0' >emit.pms
expect_fail "emit over 1e30: refused at the material" 1 "^pm-shoot: emit.pms:7: material 'hot': emit 1e+31" \
	pm-shoot -q -n 100 emit.pms -o out.pm
room 1 10 '' | sed 's/fov 60/fov 179.9999/' >fov.pms
expect_fail "fov 179.9999: past 179.999" 1 '^pm-shoot: fov.pms:1: camera: fov 179.9998[0-9]* is outside' \
	pm-shoot -q -n 100 fov.pms -o out.pm
room 1 10 '' | sed 's/fov 60/fov 179.99999999/' >fov2.pms
expect_fail "fov 179.99999999, 180 as a float: refused" 1 '^pm-shoot: fov2.pms:1: camera: fov 180 is outside' \
	pm-shoot -q -n 100 fov2.pms -o out.pm

# Scale invariance within the range: the room at unit 1e-9 and 5e11 (2e-9
# and 1e12 across, the ends of the range), its point light's power scaled
# with the unit squared, has the radiance of the room at unit 1 (the same
# paths up to rounding), for each estimate.
room 1 10 '' >u1.pms
room 1e-9 1e-17 '' >us.pms
room 5e11 2.5e24 '' >ul.pms
for u in u1 us ul; do
	pm-shoot -q -n 20000 -s 3 $u.pms -o $u.pm && pm-build -q $u.pm -o $u.map ||
		notok "shoot $u" "failed"
	for e in classical compensated photons path; do
		m=$u.map; [ $e = path ] && m=
		pm-render -q -p 4 -s 3 -e $e $u.pms $m -o $u-$e.exr || notok "render $u $e" "failed"
		kv=$("$B/tests/tools/exrstat" $u-$e.exr | sed -n 's/^mean: //p')
		eval "mean_${u}_$e=\$kv"
	done
done
for e in classical compensated photons path; do
	eval "a=\$mean_u1_$e b=\$mean_us_$e c=\$mean_ul_$e"
	tol=$(awk "BEGIN{print 0.01*$a}")
	num_near "$e at unit 1e-9 reads as at unit 1 ($b vs $a)" "$b" "$a" "$tol"
	num_near "$e at unit 5e11 reads as at unit 1 ($c vs $a)" "$c" "$a" "$tol"
done
