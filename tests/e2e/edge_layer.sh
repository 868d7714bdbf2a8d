# edge_layer.sh — pm-render's edge layer (formats/image.md) is about the
# support of the estimate each sample used. With estimates once a pixel
# and patch (the default), a pixel's later samples reuse one estimate made
# at another point, and take its flag: on a floor seen whole by every
# pixel, a pixel's 16 samples use at most two estimates (the first, used
# once, and the one the rest reuse), so the layer reads 0, 1/16, 15/16 or
# 1 there. With an estimate at every sample (--estimates sample) each sample asks
# at its own point, and pixels across the band's border read in between,
# which is what the first check would catch if reused samples asked anew.
. "$PM_TOP/tests/lib.sh"
tools=$PM_BIN/../tests/tools

# A floor seen from 1 m straight above (fov 40: the view meets the floor
# within 0.364 of the axis), and a wall just beyond the view at x = 0.40:
# estimates near the right border reach it, the camera never sees it.
cat >edge.pms <<'SCENE'
camera eye 0 1 0  look 0 0 0  up 0 0 -1  fov 40  size 32 32
material g diffuse albedo 0.5 0.5 0.5
quad g -3 0 -3  -3 0 3  3 0 3  3 0 -3
quad g 0.4 0 -3  0.4 0 3  0.4 2 3  0.4 2 -3
pointlight 0 0.9 0 power 50 50 50
SCENE
pm-shoot -q -n 20000 -s 1 edge.pms | pm-build -q -o map.pm
for e in classical compensated; do
	pm-render -q -e $e -s 1 -o $e-pixel.exr edge.pms map.pm
	pm-render -q -e $e -s 1 --estimates sample -o $e-sample.exr edge.pms map.pm
	for m in pixel sample; do
		"$tools/exrstat" --layer edge --dump $e-$m.exr |
			awk '{ v = $3 * 16; if (v > 0.01 && (v < 0.99 || v > 1.01) && (v < 14.99 || v > 15.01) && v < 15.99) mid++
			       if ($3 > 0.5) band++ }
			     END { printf "mid: %d\nband: %d\n", mid, band }' >$e-$m.txt
	done
	echo "# $e: band pixels $(kv $e-pixel.txt band) (pixel) $(kv $e-sample.txt band) (sample); in between $(kv $e-pixel.txt mid), $(kv $e-sample.txt mid)"
	check "$e: the floor near the unseen wall is in the edge band" test "$(kv $e-pixel.txt band)" -ge 16
	check "$e: away from it, not" test "$(kv $e-pixel.txt band)" -le 512
	check "$e, estimates once a pixel: each pixel's samples take their estimates' flags (0, 1/16, 15/16, 1)" \
		test "$(kv $e-pixel.txt mid)" -eq 0
	check "$e, an estimate at every sample: pixels across the band's border read in between" \
		test "$(kv $e-sample.txt mid)" -ge 4
	check "$e: the two ways agree on the band within a column of pixels" \
		test "$(( $(kv $e-pixel.txt band) - $(kv $e-sample.txt band) ))" -le 32 -a \
		"$(( $(kv $e-sample.txt band) - $(kv $e-pixel.txt band) ))" -le 32
done
