# reference.sh — the photon-map renders agree with an independent estimate
# of the same scene: the unbiased path tracer (which shares only ray casting,
# materials and lights with them, not the photon map, the kd-tree or the
# estimates). A box with a soft-glossy wall, a strong-glossy wall, a mirror
# block, a glass ball, an area light and a point light.
. "$PM_TOP/tests/lib.sh"
cat >box.pms <<'SCENE'
camera eye 0 1 3.4  look 0 1 0  up 0 1 0  fov 45  size 32 24
material white diffuse albedo 0.7 0.7 0.7
material red diffuse albedo 0.6 0.1 0.1
material soft glossy kd 0.4 0.5 0.3 ks 0.3 0.3 0.3 exponent 10
material lamp diffuse albedo 0 0 0 emit 8 8 8
material shiny glossy kd 0.2 0.2 0.2 ks 0.6 0.6 0.6 exponent 400
material mirror mirror reflect 0.9 0.9 0.9
material glass glass ior 1.5
quad white -1 0 -1  1 0 -1  1 0 1  -1 0 1
quad white -1 2 -1  -1 2 1  1 2 1  1 2 -1
quad soft -1 0 -1  -1 2 -1  1 2 -1  1 0 -1
quad red -1 0 -1  -1 0 1  -1 2 1  -1 2 -1
quad shiny 1 0 -1  1 2 -1  1 2 1  1 0 1
quad lamp -0.3 1.99 -0.3  0.3 1.99 -0.3  0.3 1.99 0.3  -0.3 1.99 0.3
box mirror -0.7 0 -0.7  -0.2 0.5 -0.3
sphere glass 0.4 0.35 0.3 0.3 subdiv 3
pointlight 0.5 1.5 0.5 power 2 2 2
SCENE
pm-render -e path -p 1024 -s 1 box.pms -o ref.exr
for est in classical compensated; do
	for i in 1 2 3 4 5 6 7 8; do
		pm-shoot -n 50000 -s $i box.pms | pm-build | pm-render -e $est -p 16 -s $i box.pms - -o $est-$i.exr
	done
	pm-average -q $est-[0-9]*.exr -o $est.exr
	pm-diff $est.exr ref.exr >$est.txt
	echo "# $est vs path: mean $(kv $est.txt mean_a) / $(kv $est.txt mean_b), rmse $(kv $est.txt rmse), relmse $(kv $est.txt relmse)"
	awk -v a="$(kv $est.txt mean_a)" -v b="$(kv $est.txt mean_b)" 'BEGIN { d = a / b - 1; exit !(d < 0.02 && d > -0.02) }' &&
		ok "$est image mean within 2% of the path tracer" ||
		notok "$est image mean within 2% of the path tracer" "$(kv $est.txt mean_a) vs $(kv $est.txt mean_b)"
	num_near "$est relMSE vs the path tracer small" "$(kv $est.txt relmse)" 0 0.01
done
