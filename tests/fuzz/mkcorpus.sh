#!/bin/sh
# mkcorpus.sh — (re)makes the seed corpora in tests/fuzz/corpus/ from the
# built programs and the bundled examples: small valid inputs of each kind
# that the fuzzers mutate. Usage: sh tests/fuzz/mkcorpus.sh BUILD_DIR
set -e
B=$(cd "${1:-build}" && pwd)
top=$(cd "$(dirname "$0")/../.." && pwd)
c=$top/tests/fuzz/corpus
mk=$B/tests/tools/mkphotons
mkimg=$B/tests/tools/mkimg
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
rm -rf "$c"
mkdir -p "$c/photons" "$c/exr" "$c/scene" "$c/mesh"

# photon files and maps: tiny, empty, merged, two planes
"$mk" -n 5 -s 1 -o "$c/photons/five.pm"
"$mk" -n 0 -o "$c/photons/empty.pm"
"$mk" -n 40 -s 2 -p x=0 -p y=1 -o "$tmp/a.pm"
"$B/bin/pm-build" "$tmp/a.pm" -o "$c/photons/map40.pm"
"$mk" -n 7 -s 3 -e 100 -o "$tmp/b.pm"
"$B/bin/pm-build" "$c/photons/five.pm" "$tmp/b.pm" -o "$c/photons/merged.pm"

# images: the writer's output (small, with attributes and extra channels)
"$mkimg" -a pm.passes=1 -a pm.seed=7 "$c/exr/flat.exr" 3 2
"$mkimg" -p ramp -c m2.R=0.25 -c count=1 "$c/exr/ramp.exr" 5 4
"$mkimg" -n 1,1 "$c/exr/nan.exr" 4 4
"$mkimg" "$c/exr/wide.exr" 40 1
# half and uint channels, tiles, a data window off the origin: what the
# image unit test writes with the OpenEXR core API directly
(cd "$tmp" && "$B/tests/test_image" >/dev/null)
cp "$tmp/scan.exr" "$c/exr/half-uint-scan.exr"
cp "$tmp/tiled.exr" "$c/exr/half-uint-tiled.exr"

# scenes: the format page's statements, meshes beside them (see fuzz_scene.c)
cat >"$c/scene/small.pms" <<'S'
camera eye 0 1 5  look 0 1 0  up 0 1 0  fov 45  size 32 24
material white diffuse albedo 0.7 0.7 0.7
material lamp  diffuse albedo 0.5 0.5 0.5 emit 10 10 10
box  white -2 0 -2  2 3 2 inward
quad lamp  -0.3 2.99 -0.3  0.3 2.99 -0.3  0.3 2.99 0.3  -0.3 2.99 0.3
sphere white 0 0.5 0 0.5 subdiv 1
S
cat >"$c/scene/all.pms" <<'S'
# every statement and word
camera look 0 0 0 eye 1 2 3 fov 30 up 0 1 0 size 8 8
glossy_threshold 50
material red   diffuse albedo 0.63 0.065 0.05 twosided
material floor glossy kd 0.28 0.17 0.09 ks 0.55 0.55 0.55 exponent 400 emit 1 1 1
material satin glossy exponent 12 kd 0.4 0.3 0.2 ks 0.1 0.1 0.1
material chrome mirror reflect 0.9 0.9 0.9
material crystal glass ior 1.5 tint 0.95 1 0.97
triangle red 0 0 0  1 0 0  0 1 0 scale 2 rotate 0 1 0 90 translate 1 0 0 move 0 0 .5
quad chrome 0 0 0 1 0 0 1 1 0 0 1 0 scale 1 -1 1
box crystal -1 -1 -1 1 1 1
sphere satin 0 0 0 1 subdiv 2 move 1 0 0
mesh cube.obj floor rotate 1 1 1 30
mesh tri.off red translate 0 0 -1
pointlight 0 5 0 power 10 10 10 move 0 1e-3 0
S
cp "$top/examples/cornell/cornell.pms" "$c/scene/cornell.pms"
sed -i 's/short.obj/cube.obj/; s/tall.obj/tri.off/' "$c/scene/cornell.pms"

# meshes: the first byte picks the format (fuzz_mesh.c: obj off ply stl om)
{ printf '\000'; cat "$top/examples/cornell/short.obj"; } >"$c/mesh/short.obj"
{ printf '\000'; printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n'; } >"$c/mesh/tet.obj"
{ printf '\001'; printf 'OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n'; } >"$c/mesh/quad.off"
{ printf '\002'; printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n'; } >"$c/mesh/tri.ply"
{ printf '\002'; printf 'ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n'
  printf '\000\000\000\000\000\000\000\000\000\000\000\000\000\000\200\077\000\000\000\000\000\000\000\000\000\000\000\000\000\000\200\077\000\000\000\000'
  printf '\003\000\000\000\000\001\000\000\000\002\000\000\000'; } >"$c/mesh/tri-bin.ply"
{ printf '\003'; printf 'solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n'; } >"$c/mesh/tri.stl"
echo "corpus: $(find "$c" -type f | wc -l) files, $(du -sk "$c" | cut -f1) KiB"
