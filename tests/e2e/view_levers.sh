# view_levers.sh — the view pass's cost levers change the noise, never the
# expected image: several shadow rays per camera sample (-l) and the photon
# estimate once per pixel (--estimates pixel), each against a closed form,
# and -l with the noise it is there to remove.
. "$PM_TOP/tests/lib.sh"
tools=$PM_BIN/../tests/tools

# A 1 x 1 emitter of radiance 3 facing down at height 0.5 over a floor of
# albedo 0.5 (analytic.sh's): the floor under its centre reads rho Le F.
cp "$PM_TOP/tests/scenes/area.pms" .
want=$(awk 'BEGIN { pi = 3.14159265358979; A = 1; B = 1
	F = (A / sqrt(1 + A*A) * atan2(B, sqrt(1 + A*A)) + B / sqrt(1 + B*B) * atan2(A, sqrt(1 + B*B))) / (2 * pi)
	printf "%.9g", 0.5 * 3 * 4 * F }')
tol=$(awk -v w="$want" 'BEGIN { print w * 0.01 }')
# The view pass's direct light (shadow rays to the lamp, and BSDF samples
# that find it through the emitter scan rather than a full ray), with a
# photon map that adds nothing (the lamp's albedo is 0 and photons only
# land on the floor, whose estimate goes to the indirect layer).
pm-shoot -q -n 20000 -s 1 area.pms -o area.ph && pm-build -q area.ph -o area.map
for l in 1 16; do
	pm-render -q -p $((1024 / l)) -l $l -s 2 area.pms area.map -o area-l$l.exr 2>/dev/null
	"$tools/exrstat" --window 3,3,5,5 --layer direct area-l$l.exr >a$l.txt
	num_near "-l $l: direct light of a square emitter is rho Le F" "$(kv a$l.txt mean)" "$want" "$tol"
done

# The noise -l takes out: the spread of one pixel's direct light over four
# seeds, with 1 and with 16 shadow rays per camera sample (4 samples per
# pixel so that the shadow rays' noise is what is seen).
for l in 1 16; do
	for s in 1 2 3 4; do
		pm-render -q -p 4 -l $l -s $s area.pms area.map -o n$l-$s.exr 2>/dev/null
	done
	pm-average -q n$l-1.exr n$l-2.exr n$l-3.exr n$l-4.exr -o n$l.exr
	"$tools/exrstat" --layer stderr n$l.exr >s$l.txt
done
r=$(awk -v a="$(kv s1.txt mean)" -v b="$(kv s16.txt mean)" 'BEGIN { printf "%.3f", (b > 0 ? a / b : 0) }')
check "-l 16 has less than half the direct light's noise of -l 1 (ratio $r)" \
	awk -v r="$r" 'BEGIN { exit !(r > 2) }'

# The furnace (albedo 0.5, emission 1: radiance 2 everywhere), where every
# estimate, and so every per-pixel reuse of one, must read 2.
cat >furnace.pms <<'SCENE'
camera eye 0 1 2.6  look 0 1 -3  up 0 1 0  fov 50  size 32 24
material f diffuse albedo 0.5 0.5 0.5 emit 1 1 1
box f -2 0 -3  2 2.5 3 inward
box f -0.6 0 -1.6  0.6 0.8 -0.8
SCENE
pm-shoot -q -n 100000 -s 4 furnace.pms | pm-build -q -o furnace.map
for e in pixel sample; do
	pm-render -q -p 8 --estimates $e -s 4 furnace.pms furnace.map -o f-$e.exr 2>/dev/null
	"$tools/exrstat" f-$e.exr >f$e.txt
	num_near "--estimates $e: the furnace reads 2" "$(kv f$e.txt mean)" 2 0.03
done
pm-render -q -p 8 -j 1 -s 4 furnace.pms furnace.map -o f-j1.exr 2>/dev/null
pm-render -q -p 8 -j 2 -s 4 furnace.pms furnace.map -o f-j2.exr 2>/dev/null
pm-diff f-j1.exr f-j2.exr >j.txt
check "--estimates pixel: the same image on 1 and 2 threads" test "$(kv j.txt max_abs)" = 0
# Once per pixel is the point: the same samples, fewer estimates. The count
# layer is the photons per estimate, so compare time-free: the pixel mode
# reuses, hence its indirect layer is constant within a pixel's polygon and
# differs from the sample mode's (which must not be bit-identical to it).
pm-diff -l indirect f-pixel.exr f-sample.exr >ps.txt
check "--estimates pixel and sample differ (the reuse happens)" test "$(kv ps.txt max_abs)" != 0

# Where the estimate's support changes fast, whether one is reused must not
# depend on that estimate: decided on the estimate reused, it kept dim ones
# (wide support) and diluted bright ones, and the caustic under a glass
# sphere read 10-13 % dark against --estimates sample. Twelve pass pairs,
# each map rendered both ways with the same seed; the ratio of the window
# means (the caustic on the floor) averaged over them is within 1.1 % of 1
# when both modes have the same expectation.
grep -v 'sphere chrome' "$PM_TOP/examples/caustic/caustic.pms" | sed 's/size 256 256/size 64 64/' >glass.pms
for i in 1 2 3 4 5 6 7 8 9 10 11 12; do
	pm-shoot -q -n 200000 -P $i/12 glass.pms | pm-build -q -o g.map
	for e in pixel sample; do
		pm-render -q --estimates $e -P $i/12 glass.pms g.map -o g-$e.exr
		"$tools/exrstat" --window 36,53,50,63 g-$e.exr | kv /dev/stdin mean >g-$e.txt
	done
	awk -v a="$(cat g-pixel.txt)" -v b="$(cat g-sample.txt)" 'BEGIN { print a / b }'
done >ratios.txt
r=$(awk '{ s += $1 } END { printf "%.4f", s / NR }' ratios.txt)
num_near "--estimates pixel and sample: the same caustic (window ratio $r)" "$r" 1 0.035

# Pixels across edges: a floor of 40 strips 5 cm wide, alternately dark and
# light (each strip its own patch), in a closed room (the photons the
# estimate counts have bounced), seen at 7 cm a pixel, so that a pixel's
# 16 samples land on two or three patches. Each patch keeps its own
# estimate in the pixel; one reused on another patch would carry that
# patch's albedo (0.2 against 0.8) across the edge. The indirect layer's
# mean over the image, --estimates pixel over sample on the same maps and
# camera samples, averaged over six pass pairs, is within 1 % of 1.
{
	echo "camera eye 0 1.2 0  look 0 0 0  up 0 0 -1  fov 50  size 16 16"
	echo "material lamp diffuse albedo 0 0 0 emit 6 6 6"
	echo "material dark diffuse albedo 0.2 0.2 0.2"
	echo "material light diffuse albedo 0.8 0.8 0.8"
	echo "quad lamp -0.3 1.9 -0.3  0.3 1.9 -0.3  0.3 1.9 0.3  -0.3 1.9 0.3"
	echo "box light -1 -0.01 -1  1 2 1 inward"
	awk 'BEGIN { for (i = 0; i < 40; i++) { a = -1 + 0.05 * i; b = a + 0.05
		printf "quad %s %g 0 -1  %g 0 1  %g 0 1  %g 0 -1\n", i % 2 ? "dark" : "light", a, a, b, b } }'
} >strips.pms
for i in 1 2 3 4 5 6; do
	pm-shoot -q -n 50000 -P $i/6 strips.pms | pm-build -q -o s.map
	for e in pixel sample; do
		pm-render -q --estimates $e -P $i/6 strips.pms s.map -o s-$e.exr
		"$tools/exrstat" --layer indirect s-$e.exr | kv /dev/stdin mean >s-$e.txt
	done
	awk -v a="$(cat s-pixel.txt)" -v b="$(cat s-sample.txt)" 'BEGIN { print a / b }'
done >sratios.txt
r=$(awk '{ s += $1 } END { printf "%.4f", s / NR }' sratios.txt)
num_near "--estimates pixel and sample: the same strips across edges (ratio $r)" "$r" 1 0.01
