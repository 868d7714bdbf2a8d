# lights.sh — the lights that are not polygons of their own, against closed
# forms and against the path tracer: a floor under a distant light reads
# rho E cos(theta) / pi; a box under a constant sky reads rho Le (no
# interreflection reaches a convex object); a floor below a disk lamp reads
# rho Le a^2 / (h^2 + a^2), below a spherical one rho Le a^2 / h^2; a spot's
# axis reads rho I / (pi h^2); a box on a floor under an image sky reads
# the same from the photon map as from the path tracer; results do not
# depend on the number of threads.
. "$PM_TOP/tests/lib.sh"
tools=$PM_BIN/../tests/tools

# Looking straight down at the floor; a narrow fov.
cat >sun.pms <<'SCENE'
camera eye 0 0.5 0  look 0 0 0  up 0 0 -1  fov 2  size 8 8
material floor diffuse albedo 0.8 0.5 0.2
quad floor -10 0 -10  -10 0 10  10 0 10  10 0 -10
distantlight irradiance 3 3 3  dir 1 -2 0
SCENE
want=$(awk 'BEGIN { printf "%.9g", 0.5 * 3 * 2 / sqrt(5) / 3.14159265358979 }')
pm-render -e path -p 4 sun.pms -o sun.exr 2>/dev/null
"$tools/exrstat" sun.exr >s.txt
num_near "distant light on a floor, path: rho E cos / pi" "$(kv s.txt mean)" "$want" "$(awk -v w="$want" 'BEGIN { print w * 1e-5 }')"
pm-shoot -n 2000 sun.pms 2>/dev/null | pm-build 2>/dev/null | pm-render -p 4 sun.pms - -o sunc.exr 2>/dev/null
"$tools/exrstat" sunc.exr >s.txt
num_near "distant light on a floor, compensated" "$(kv s.txt mean)" "$want" "$(awk -v w="$want" 'BEGIN { print w * 1e-5 }')"

# A box seen face on under a constant sky of 2: rho Le = 1.2 wherever.
cat >sky.pms <<'SCENE'
camera eye 0 0 4  look 0 0 0  up 0 1 0  fov 10  size 16 16
material white diffuse albedo 0.6 0.6 0.6
box white -1 -1 -1  1 1 1
envlight radiance 2 2 2
SCENE
pm-render -e path -p 64 sky.pms -o sky.exr 2>/dev/null
"$tools/exrstat" sky.exr >s.txt
num_near "convex box under a constant sky reads rho Le" "$(kv s.txt mean)" 1.2 0.006

# A disk lamp of radius 0.5 at height 1 over a floor, and a sphere lamp
# of radius 0.25 whose centre is at height 1.
cat >disk.pms <<'SCENE'
camera eye 0 0.05 0  look 0 0 0  up 0 0 -1  fov 2  size 8 8
material floor diffuse albedo 0.5 0.5 0.5
material lamp diffuse albedo 0 0 0 emit 4 4 4
quad floor -10 0 -10  -10 0 10  10 0 10  10 0 -10
disk lamp 0 1 0  0 -1 0  0.5
SCENE
pm-render -e path -p 64 -l 4 disk.pms -o disk.exr 2>/dev/null
"$tools/exrstat" disk.exr >s.txt
num_near "floor under a disk lamp: rho Le a^2 / (h^2 + a^2)" "$(kv s.txt mean)" 0.4 0.004
sed 's/^disk .*/sphere lamp 0 1 0 0.25 subdiv 6/' disk.pms >ball.pms
pm-render -e path -p 64 -l 4 ball.pms -o ball.exr 2>/dev/null
"$tools/exrstat" ball.exr >s.txt
num_near "floor under a sphere lamp: rho Le a^2 / h^2" "$(kv s.txt mean)" 0.125 0.00125

# A spot 2 above the floor: on its axis rho I / (pi h^2); outside its cone 0.
cat >spot.pms <<'SCENE'
camera eye 0 0.5 0  look 0 0 0  up 0 0 -1  fov 120  size 33 33
material floor diffuse albedo 0.5 0.5 0.5
quad floor -10 0 -10  -10 0 10  10 0 10  10 0 -10
spotlight 0 2 0  to 0 0 0  intensity 8 8 8  cone 20 10
SCENE
pm-render -e path -p 1 spot.pms -o spot.exr 2>/dev/null
"$tools/exrstat" --pixel 16,16 spot.exr >s.txt
num_near "spot light's axis: rho I / (pi h^2)" "$(kv s.txt mean)" "$(awk 'BEGIN { printf "%.9g", 0.5 * 8 / (3.14159265358979 * 4) }')" 3e-4
"$tools/exrstat" --window 0,0,2,2 spot.exr >s.txt
check "outside the spot's cone the floor is black" test "$(kv s.txt max)" = 0

# A box on a floor under a lat-long sky brighter overhead: the photon
# map's indirect light agrees with the path tracer's.
"$tools/mkimg" -v 3,3,3 top.exr 16 8
cat >room.pms <<'SCENE'
camera eye 0 2 5  look 0 0.5 0  up 0 1 0  fov 40  size 24 18
material white diffuse albedo 0.7 0.7 0.7
quad white -3 0 -3  -3 0 3  3 0 3  3 0 -3
box white -0.7 0 -0.7  0.7 1.2 0.7
envlight image top.exr scale 0.5 rotate 1 0 0 10
SCENE
pm-render -e path -p 256 room.pms -o ref.exr 2>/dev/null
"$tools/exrstat" ref.exr >r.txt
pm-shoot -n 200000 room.pms 2>/dev/null | pm-build 2>/dev/null >map
pm-render -p 16 room.pms map -o pm.exr 2>/dev/null
"$tools/exrstat" pm.exr >c.txt
num_near "sky over a box and floor: photon map mean near the path tracer's" "$(kv c.txt mean)" "$(kv r.txt mean)" "$(awk -v w="$(kv r.txt mean)" 'BEGIN { print w * 0.02 }')"
pm-shoot -j 1 -n 20000 room.pms 2>/dev/null >a1
pm-shoot -j 2 -n 20000 room.pms 2>/dev/null >a2
check "sky photons identical for -j 1 and -j 2" cmp -s a1 a2
# Outputs record their command lines: the same names, in two directories.
mkdir j1 j2
(cd j1 && pm-render -j 1 -p 2 ../room.pms ../map -o v.exr 2>/dev/null)
(cd j2 && pm-render -j 2 -p 2 ../room.pms ../map -o v.exr 2>/dev/null)
check "sky view pass identical for -j 1 and -j 2" cmp -s j1/v.exr j2/v.exr

expect_fail "zero direction of a distant light" 1 "^pm-render: bad.pms:4: distantlight: dir must not be zero" \
	pm-render -e path "$(sed 's/dir 1 -2 0/dir 0 0 0/' sun.pms >bad.pms; echo bad.pms)" -o bad.exr
printf 'PF\n2 1\n-1.0\n' >nan.pfm
printf '\000\000\300\177\000\000\200\077\000\000\200\077\000\000\200\077\000\000\200\077\000\000\200\077' >>nan.pfm
sed 's/^envlight .*/envlight image nan.pfm/' sky.pms >bad.pms
expect_fail "NaN texel in a sky" 1 "^pm-render: bad.pms:4: envlight: 'nan.pfm': texel (0, 0) is nan" \
	pm-render -e path bad.pms -o bad.exr
sed 's/^envlight .*/envlight image none.hdr/' sky.pms >bad.pms
expect_fail "missing sky image" 1 "^pm-render: bad.pms:4: 'none.hdr': cannot read image" \
	pm-render -e path bad.pms -o bad.exr
