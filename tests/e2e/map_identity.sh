# map_identity.sh — a photon map records the identity of what the light pass
# depends on (formats/scene.md, "Scene identity"): edits that cannot change
# the photons (comments, white space, number spellings, the camera, a
# comment in a mesh file) keep a map usable; edits that do (an albedo, a
# light's power, a vertex, a mesh file's vertex, the glossy threshold) make
# pm-render refuse it. Pass images record the camera too, so pm-average
# refuses passes of different cameras. A map of an older pm is refused
# with a message that says so.
. "$PM_TOP/tests/lib.sh"

cat >s.pms <<'S'
camera eye 0 1 3.5  look 0 1 0  up 0 1 0  fov 45  size 12 9
glossy_threshold 100
material white diffuse albedo 0.7 0.7 0.7
material satin glossy kd 0.3 0.3 0.3 ks 0.4 0.4 0.4 exponent 40
material lamp  diffuse albedo 0.5 0.5 0.5 emit 5 5 5
box  white -1 0 -1  1 2 1 inward
quad lamp  -0.3 1.99 -0.3  0.3 1.99 -0.3  0.3 1.99 0.3  -0.3 1.99 0.3
mesh tet.obj satin scale 0.3
pointlight 0 1.5 0 power 1 1 1
S
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n' >tet.obj
pm-shoot -q -n 2000 -s 1 s.pms | pm-build -o map.pm || notok "setup" "pm-shoot | pm-build failed"
pm-render -q -p 1 s.pms map.pm -o a.exr || notok "setup" "pm-render failed"

# usable NAME SCENE: pm-render takes map.pm with SCENE, unforced
usable() {
	if pm-render -q -p 1 "$2" map.pm -o u.exr 2>stderr.txt; then ok "$1"
	else notok "$1" "$(head -c 300 stderr.txt)"; fi
}
# refused NAME SCENE: pm-render refuses map.pm with SCENE
refused() {
	expect_fail "$1" 1 "^pm-render: 'map.pm': photon map of another scene (light_hash " \
		pm-render -q -p 1 "$2" map.pm -o r.exr
}
# edited VERDICT NAME SED-SCRIPT: s.pms edited by SED-SCRIPT into e.pms, then VERDICT
edited() { sed "$3" s.pms >e.pms && "$1" "$2" e.pms; }

{ echo '# a comment line'; sed 's/^material white /material   white\t/; s/$/   # note/' s.pms; echo; } >comment.pms
usable "comments, blank lines and white space keep the map" comment.pms
edited usable "another spelling of the same numbers keeps the map" 's/power 1 1 1/power 1.0 1e0 1.00/; s/albedo 0.7 /albedo 0.70 /'
sed 's/eye 0 1 3.5/eye 0.2 1.1 3/; s/size 12 9/size 16 9/; s/fov 45/fov 50/' s.pms >camera.pms
usable "another camera keeps the map" camera.pms
edited usable "a renamed material keeps the map" 's/white/blanc/g'
mkdir -p m && cp s.pms m/ && { echo '# exported by hand'; cat tet.obj; } >m/tet.obj
usable "a comment in the mesh file keeps the map" m/s.pms

edited refused "an albedo change refuses the map" 's/albedo 0.7 0.7 0.7/albedo 0.7 0.71 0.7/'
edited refused "a light power change refuses the map" 's/power 1 1 1/power 1 1 2/'
edited refused "a moved vertex refuses the map" 's/^quad lamp  -0.3 1.99 -0.3/quad lamp  -0.31 1.99 -0.3/'
edited refused "a glossy threshold change refuses the map" 's/glossy_threshold 100/glossy_threshold 30/'
mkdir -p v && cp s.pms v/ && sed 's/^v 0 0 1$/v 0 0 1.5/' tet.obj >v/tet.obj
refused "a mesh file's changed vertex refuses the map" v/s.pms

# pass images: pm.scene_hash follows the light pass and the camera
pm-render -q -p 1 -s 2 comment.pms map.pm -o b.exr
check "passes of a commented copy average" pm-average -q a.exr b.exr -o ab.exr
sed 's/eye 0 1 3.5/eye 0 1 3.4/' s.pms >camera2.pms
pm-render -q -p 1 -s 2 camera2.pms map.pm -o d.exr
expect_fail "passes of another camera are not averaged" 1 "^pm-average: 'd.exr': scene hash .* differs" \
	pm-average -q a.exr d.exr -o ad.exr

# a map of the pm before light_hash (its scene_hash hashed the file's bytes)
perl -0pe 's/^light_hash=/scene_hash=/m' map.pm >old.pm
expect_fail "an older pm's map is refused as such" 1 \
	"^pm-render: 'old.pm': photon file of an older pm (it records scene_hash, not light_hash): shoot it again$" \
	pm-render -q -p 1 s.pms old.pm -o o.exr

# a pass's provenance: pm-dump --header reads an EXR's attributes
pm-dump --header a.exr >a.hdr
check "pm-dump --header on an EXR shows its size" grep -qx 'size=12 9' a.hdr
check "pm-dump --header on an EXR shows pm.scene_hash" \
	grep -qx "pm.scene_hash=$("$PM_BIN/../tests/tools/exrattr" a.exr pm.scene_hash)" a.hdr
check "pm-dump --header on an EXR shows the commands, one a line" \
	test "$(grep '^pm.command=' a.hdr | cut -d' ' -f1)" = "$(printf 'pm.command=pm-shoot\npm.command=pm-build\npm.command=pm-render')"
expect_fail "pm-dump --stats on an EXR says only --header reads images" 1 \
	"^pm-dump: 'a.exr': an OpenEXR image: only --header reads images$" pm-dump --stats a.exr
