# classical_norm.sh — pm-render --classical-norm: Jensen's classical estimate
# spreads the flux of the k nearest photons over pi r^2, r the distance to
# the k-th, and reads bright by 1/(k-1) on a flat, evenly lit surface; the
# k-1 form scales it by (k-1)/k and is unbiased there. Measured in the
# furnace of furnace.sh (radiance 2, of which the photon-map part, the
# indirect layer, is 0.5) on a window of flat far wall, at k = 10.
. "$PM_TOP/tests/lib.sh"
T=$PM_BIN/../tests/tools

cp "$PM_TOP/tests/scenes/furnace.pms" furnace.pms
# Pixels x 12..27, y 9..14: far wall only, above the table and well away
# from ceiling and side walls (the sphere stays on the wall).
W=12,9,28,15

# Three light/view pass pairs, their window means averaged: the per-pair
# noise is about 0.007 (indirect and total alike), the bias of Jensen's form
# at k = 10 is 0.5 / 9 = 0.056. An estimate per camera sample (--estimates
# sample): at k = 10 of 500000 photons the estimate's support is smaller
# than a pixel, so the 16 samples' estimates average its noise down, which
# one estimate per pixel would not.
for s in 1 2 3; do
	pm-shoot -n 500000 -s $s furnace.pms 2>/dev/null | pm-build -o map$s.pmm
	pm-render -q -e classical -k 10 -p 16 --estimates sample -s $s furnace.pms map$s.pmm -o def$s.exr
	pm-render -q -e classical -k 10 -p 16 --estimates sample -s $s --classical-norm k furnace.pms map$s.pmm -o k$s.exr
	pm-render -q -e classical -k 10 -p 16 --estimates sample -s $s --classical-norm k-1 furnace.pms map$s.pmm -o k1$s.exr
	for f in k$s k1$s; do
		"$T/exrstat" --window $W --layer indirect $f.exr | sed -n "s/^mean: /$f ind /p"
		"$T/exrstat" --window $W $f.exr | sed -n "s/^mean: /$f all /p"
	done
done >means.txt
check "k-1 form renders" test -s k11.exr

# The default is Jensen's form: the same pixels as --classical-norm k.
pm-diff def1.exr k1.exr >same.txt
check "default = --classical-norm k" test "$(kv same.txt max_abs)" = 0
check "pm.command keeps --classical-norm k-1" sh -c "'$T/exrattr' k11.exr pm.command | grep -q -e '--classical-norm k-1 '"

# mean FORM LAYER: the window mean averaged over the three pairs.
mean() { awk -v f="^$1[0-9]\$" -v l="$2" '$1 ~ f && $2 == l { s += $3; n++ } END { if (n == 3) printf "%.6f", s / n }' means.txt; }
ik=$(mean k ind) ik1=$(mean k1 ind)
# Same seeds, same hit points: the k-1 estimate is the k one times 9/10.
num_near "k-1 indirect = 9/10 of k's, estimate by estimate" \
	"$(awk -v a="$ik1" -v b="$ik" 'BEGIN { if (b > 0) print a / b }')" 0.9 0.0001
# Jensen's form: 0.5 * 10/9 = 0.556 expected; the k-1 form: 0.5.
num_near "k-1 flat-wall indirect = 0.5" "$ik1" 0.5 0.015
num_near "k flat-wall indirect reads 0.5 * k/(k-1)" "$ik" 0.5556 0.015
check "k-1 is closer to exact than k at k = 10" awk -v a="$ik1" -v b="$ik" \
	'BEGIN { da = a - 0.5; db = b - 0.5; if (da < 0) da = -da; if (db < 0) db = -db; exit !(a != "" && da + 0.03 < db) }'
num_near "k-1 flat-wall radiance = 2" "$(mean k1 all)" 2 0.025

expect_fail "--classical-norm takes k or k-1" 2 "classical-norm: unknown normalisation 'k+1'" \
	pm-render -e classical --classical-norm k+1 furnace.pms map.pmm -o bad.exr
expect_fail "--classical-norm k-1 needs -e classical" 2 "classical-norm k-1 is for -e classical" \
	pm-render --classical-norm k-1 furnace.pms map.pmm -o bad.exr
expect_fail "--classical-norm k-1 needs -k 2 or more" 2 "classical-norm k-1 needs -k 2" \
	pm-render -e classical -k 1 --classical-norm k-1 furnace.pms map.pmm -o bad.exr
check "no image from a bad command line" test ! -e bad.exr
