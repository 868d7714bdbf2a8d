# import_ply.sh — the PLY variants pbrt-v4 scenes ship, each made here and
# read through Shape "plymesh": ASCII, binary little- and big-endian,
# gzip-compressed, quads and triangles mixed, uv named u/v, s/t or
# texture_u/texture_v, normals that decide the front, extra elements and
# properties skipped. Each is checked by the vertex and face counts of the
# mesh pm-import writes (welded: the 3 x 3 grid's 9 vertices).
. "$PM_TOP/tests/lib.sh"

# A 2 x 2 grid of unit quads in z = 0 (9 vertices, 4 faces), front +z.
ascii_grid() {
	printf 'ply\nformat ascii 1.0\ncomment made by import_ply.sh\nelement vertex 9\n'
	printf 'property float x\nproperty float y\nproperty float z\nproperty float %s\nproperty float %s\n' "$1" "$2"
	printf 'element face 4\nproperty list uchar int vertex_indices\nelement extra 1\nproperty int junk\nend_header\n'
	for y in 0 1 2; do for x in 0 1 2; do echo "$x $y 0 0.5 0.5"; done; done
	printf '4 0 1 4 3\n4 1 2 5 4\n4 3 4 7 6\n4 4 5 8 7\n7\n'
}
# The same in binary: floats 0, 1, 2 as IEEE bytes; little or big endian.
f32() {
	case "$1$2" in
	0le|0be) printf '\000\000\000\000' ;;
	1le) printf '\000\000\200\077' ;; 1be) printf '\077\200\000\000' ;;
	2le) printf '\000\000\000\100' ;; 2be) printf '\100\000\000\000' ;;
	esac
}
i32() { if [ "$2" = le ]; then printf "\\$(printf %03o "$1")\\000\\000\\000"; else printf "\\000\\000\\000\\$(printf %03o "$1")"; fi; }
bin_grid() {
	e=$1
	fmt=binary_little_endian; [ "$e" = be ] && fmt=binary_big_endian
	printf 'ply\nformat %s 1.0\nelement vertex 9\n' $fmt
	printf 'property float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\n'
	printf 'property float texture_u\nproperty float texture_v\n'
	printf 'element face 5\nproperty list uchar int vertex_indices\nend_header\n'
	for y in 0 1 2; do for x in 0 1 2; do f32 $x $e; f32 $y $e; f32 0 $e; f32 0 $e; f32 0 $e; f32 1 $e; f32 0 $e; f32 1 $e; done; done
	# two triangles and three quads, wound clockwise from +z: the
	# normals (+z) turn them round
	printf '\003'; for i in 0 4 1; do i32 $i $e; done
	printf '\003'; for i in 0 3 4; do i32 $i $e; done
	for q in '1 4 5 2' '3 6 7 4' '4 7 8 5'; do printf '\004'; for i in $q; do i32 $i $e; done; done
}
ascii_grid u v >uv.ply
ascii_grid s t >st.ply
ascii_grid u v >gz.ply && gzip -9 gz.ply
bin_grid le >le.ply
bin_grid be >be.ply

for m in uv.ply st.ply gz.ply.gz le.ply be.ply; do
	{ echo 'LookAt 0 0 5  0 0 0  0 1 0'
	  echo 'Camera "perspective" "float fov" 40'
	  echo 'Film "rgb" "integer xresolution" 8 "integer yresolution" 8'
	  echo 'WorldBegin'
	  echo 'AreaLightSource "diffuse" "rgb L" [ 1 1 1 ]'
	  echo "Shape \"plymesh\" \"string filename\" \"$m\""; } >s.pbrt
	rm -rf out
	pm-import -q s.pbrt -o out/scene.pms 2>err.txt
	if ! test -s out/scene.pms; then notok "$m loads" "$(head -c 300 err.txt)"; continue; fi
	ply=out/$(sed -n 's/^mesh \([^ ]*\) .*/\1/p' out/scene.pms)
	v=$(sed -n 's/^element vertex //p' "$ply") f=$(sed -n 's/^element face //p' "$ply")
	want=4; case $m in le.ply|be.ply) want=5 ;; esac
	check "$m: 9 vertices, $want faces" test "$v $f" = "9 $want"
	# Front toward the camera: the lamp is seen (not its back), at +x
	# on the left as pbrt shows it.
	pm-render -q -e path -p 1 out/scene.pms -o out.exr
	num_near "$m: its front faces the camera (reads L)" \
		"$("$PM_BIN/../tests/tools/exrstat" --pixel 3,3 out.exr | sed -n 's/^mean: //p')" 1 1e-5
done
