# analytic.sh — the conventions and direct light against closed forms:
# a directly seen emitter reads its radiance; a Lambertian floor under a
# point light reads rho Phi / (4 pi^2 H^2); under a square emitter of
# radiance Le it reads rho Le F, F the form factor to the square (Howell's
# catalogue, differential area to a parallel rectangle at a corner, times 4).
. "$PM_TOP/tests/lib.sh"
tools=$PM_BIN/../tests/tools

# Looking straight down at the floor point under the light; up is -z so
# that image y runs along +z. A narrow fov so the centre pixels see x ~ 0.
cat >point.pms <<'SCENE'
camera eye 0 0.5 0  look 0 0 0  up 0 0 -1  fov 2  size 8 8
material floor diffuse albedo 0.8 0.5 0.2
quad floor -10 0 -10  -10 0 10  10 0 10  10 0 -10
pointlight 0 2 0 power 100 100 100
SCENE
pm-render -e path -p 16 point.pms -o point.exr 2>/dev/null
"$tools/exrstat" --window 3,3,5,5 point.exr >p.txt
# rho = 0.8, 0.5, 0.2 (mean 0.5); Phi = 100; H = 2: 0.5 * 100 / (4 pi^2 4)
want=$(awk 'BEGIN { printf "%.9g", 0.5 * 100 / (4 * 3.14159265358979 ^ 2 * 4) }')
num_near "point light on a floor: rho Phi / (4 pi^2 H^2)" "$(kv p.txt mean)" "$want" "$(awk -v w="$want" 'BEGIN { print w * 0.002 }')"

# A 1 x 1 emitter of radiance 3 facing down at height 0.5; the camera sits
# just below it and looks down through nothing but air.
cp "$PM_TOP/tests/scenes/area.pms" .
pm-render -e path -p 256 area.pms -o area.exr 2>/dev/null
"$tools/exrstat" --window 3,3,5,5 area.exr >a.txt
want=$(awk 'BEGIN { pi = 3.14159265358979; A = 1; B = 1   # a = b = 0.5, H = 0.5
	F = (A / sqrt(1 + A*A) * atan2(B, sqrt(1 + A*A)) + B / sqrt(1 + B*B) * atan2(A, sqrt(1 + B*B))) / (2 * pi)
	printf "%.9g", 0.5 * 3 * 4 * F }')
num_near "square emitter over a floor: rho Le F" "$(kv a.txt mean)" "$want" "$(awk -v w="$want" 'BEGIN { print w * 0.01 }')"

# Looking up at the emitter: every pixel reads its radiance exactly.
cat >see.pms <<'SCENE'
camera eye 0 0.2 0  look 0 1 0  up 0 0 -1  fov 30  size 8 8
material lamp diffuse albedo 0 0 0 emit 3 2 1
quad lamp -0.5 0.5 -0.5  0.5 0.5 -0.5  0.5 0.5 0.5  -0.5 0.5 0.5
SCENE
pm-render -e path -p 4 see.pms -o see.exr 2>/dev/null
"$tools/exrstat" see.exr >s.txt
check "directly seen emitter reads its radiance" test "$(kv s.txt min)" = 2 -a "$(kv s.txt max)" = 2
# Seen from behind, a one-sided emitter is black.
sed 's/look 0 1 0/look 0 -1 0/; s/eye 0 0.2 0/eye 0 0.8 0/' see.pms >behind.pms
pm-render -e path -p 4 behind.pms -o behind.exr 2>/dev/null
"$tools/exrstat" behind.exr >b.txt
check "one-sided emitter is black from behind" test "$(kv b.txt max)" = 0
