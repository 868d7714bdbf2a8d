# mirror_share.sh — estimates past mirrors and glass, shared a pixel
# (pm-render(1), --estimates): the camera sees a room only in a mirror, so
# every photon estimate of the picture is taken past it, in the specular
# layer. The samples that follow one chain of mirrors and glass share an
# estimate where their first two land close together, so that layer must
# differ from --estimates sample (same seed, same map, so the same samples:
# only the sharing differs) while keeping its expected value, measured over
# passes; a mirror with a textured reflectance shares nothing (its weight
# varies from point to point), so there the two modes give the same bits
# with --past-glossy 1, while by default (4) the estimate past it is taken
# on one camera sample in four, weighted four times: other bits, the same
# expected value.
. "$PM_TOP/tests/lib.sh"

# scene NAME REFLECT: a room lit from its ceiling, the camera looking at a
# mirror that fills the view
scene() {
	{ echo "camera eye 1 1.2 3.5  look 1 1.1 0  up 0 1 0  fov 30  size 24 18"
	  echo "texture chk checker 0.9 0.9 0.9  0.6 0.6 0.6 scale 4 4"
	  echo "material w diffuse albedo 0.6 0.55 0.5"
	  echo "material red diffuse albedo 0.7 0.1 0.1"
	  echo "material lamp diffuse albedo 0 0 0 emit 6 6 6"
	  echo "material glass mirror reflect $2"
	  echo "box w 0 0 0  2 2.4 4 inward"
	  echo "box red 0.3 0 2.2  0.9 0.7 2.8"
	  echo "quad lamp 0.6 2.399 1.6  1.4 2.399 1.6  1.4 2.399 2.4  0.6 2.399 2.4"
	  echo "quad glass 0.05 0.05 0.02  1.95 0.05 0.02  1.95 2.35 0.02  0.05 2.35 0.02"; } >"$1.pms"
}
scene plain "0.9 0.9 0.9"
scene tex "tex chk"
stat=$PM_BIN/../tests/tools/exrstat
for s in plain tex; do
	pm-shoot -q -n 60000 -s 1 $s.pms | pm-build -o $s.pm
	for i in 1 2 3 4 5 6 7 8; do
		for m in pixel sample; do
			pm-render -q -s $i --estimates $m --past-glossy 1 $s.pms $s.pm -o $s-$m-$i.exr
		done
		pm-render -q -s $i $s.pms $s.pm -o $s-past4-$i.exr
	done
done
pm-diff -l specular plain-pixel-1.exr plain-sample-1.exr >plain1.txt
pm-diff -l specular tex-pixel-1.exr tex-sample-1.exr >tex1.txt
rm_pixel=$(kv plain1.txt rmse) rm_tex=$(kv tex1.txt rmse)
echo "# specular layer, pixel against sample: plain mirror rmse $rm_pixel, textured $rm_tex"
check "a plain mirror's estimates are shared (the modes differ)" \
	awk -v a="$rm_pixel" 'BEGIN { exit !(a > 0) }'
check "a textured mirror's are not (the modes give the same bits)" \
	awk -v a="$rm_tex" 'BEGIN { exit !(a == 0) }'
for m in pixel sample; do
	pm-average -q $(for i in 1 2 3 4 5 6 7 8; do echo plain-$m-$i.exr; done) -o plain-$m.exr
done
pm-average -q $(for i in 1 2 3 4 5 6 7 8; do echo tex-sample-$i.exr; done) -o tex-sample.exr
pm-average -q $(for i in 1 2 3 4 5 6 7 8; do echo tex-past4-$i.exr; done) -o tex-past4.exr
pm-diff -l specular tex-past4-1.exr tex-sample-1.exr >tex4.txt
rm_tex4=$(kv tex4.txt rmse)
echo "# specular layer, textured mirror, --past-glossy 4 against sample: rmse $rm_tex4"
check "past a textured mirror, --past-glossy 4 takes fewer estimates (the images differ)" \
	awk -v a="$rm_tex4" 'BEGIN { exit !(a > 0) }'
check "--past-glossy 4 is recorded in the image" \
	test "$("$PM_BIN/../tests/tools/exrattr" tex-past4-1.exr pm.past_glossy)" = 4
pm-diff -l specular tex-past4.exr tex-sample.exr >mean4.txt
a=$(kv mean4.txt mean_a) b=$(kv mean4.txt mean_b)
echo "# specular layer mean over 8 passes, textured mirror: --past-glossy 4 $a, every sample $b"
num_near "one sample in four, weighted, keeps the expected value (within 1 %)" \
	"$(awk -v a="$a" -v b="$b" 'BEGIN { print a / b }')" 1 0.01
pm-diff -l specular plain-pixel.exr plain-sample.exr >mean.txt
a=$(kv mean.txt mean_a) b=$(kv mean.txt mean_b)
echo "# specular layer mean over 8 passes: pixel $a, sample $b"
num_near "sharing past the mirror keeps the expected value (within 1 %)" \
	"$(awk -v a="$a" -v b="$b" 'BEGIN { print a / b }')" 1 0.01
