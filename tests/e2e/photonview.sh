# photonview.sh — seeing the photon map (paper figure 3c): pm-render -e
# photons splats the photons the camera sees into their pixels. Photons
# appear only where the map has them and only where visible; an empty map
# renders black; in the furnace the splats average to the exact photon-
# carried radiance. And pm-dump --ply writes a PLY point cloud that a
# viewer's strict reader would accept.
. "$PM_TOP/tests/lib.sh"
stat=$PM_BIN/../tests/tools/exrstat
mkph=$PM_BIN/../tests/tools/mkphotons

# Camera 3 above the floor looking straight down at (0.5, 0, 0.5); image x
# runs along +x, image y along +z, 18.475 pixels per unit (fov 60, 64 px).
# mkphotons puts its photons in x, z in [0, 1) on y = 0: columns and rows
# 22.76 .. 41.24. A blind at y = 1 over x <= 0.5 hides the photons with
# x < 0.5 (the ray from the eye to a photon at x crosses y = 1 at
# 0.5 + (x - 0.5) * 2/3).
cat >floor.pms <<'SCENE'
camera eye 0.5 3 0.5  look 0.5 0 0.5  up 0 0 -1  fov 60  size 64 64
material white diffuse albedo 0.8 0.8 0.8
material lamp diffuse albedo 0 0 0 emit 5 5 5
quad white -2 0 2  2 0 2  2 0 -2  -2 0 -2
quad white -2 1 2  0.5 1 2  0.5 1 -2  -2 1 -2
quad lamp 0 4 0  1 4 0  1 4 1  0 4 1
SCENE
"$mkph" -n 300 -p y=0 -o ph.pm && pm-build -q ph.pm -o map.pm
pm-render -q -e photons --force floor.pms map.pm -o view.exr
check "-e photons renders" test -s view.exr
want=$(pm-dump --tsv map.pm | awk '$1 ~ /^-?[0-9]/ && $1 + 0 > 0.5 { n++ } END { print n + 0 }')
"$stat" --layer count view.exr >c.txt
got=$(awk -v m="$(kv c.txt mean)" -v p="$(kv c.txt pixels)" 'BEGIN { printf "%.0f", m * p }')
check "every visible photon counted once ($got of $want with x > 0.5)" test "$got" -eq "$want" -a "$want" -gt 100
for w in 0,0,32,64 42,0,64,64 0,0,64,22 0,42,64,64; do
	"$stat" --window $w view.exr >o.txt
	"$stat" --layer count --window $w view.exr >oc.txt
	check "nothing where the map has no visible photons ($w)" test "$(kv o.txt max)" = 0 -a "$(kv oc.txt max)" = 0
done
"$stat" --window 33,23,41,41 view.exr >in.txt
check "photons show where they are" awk -v m="$(kv in.txt mean)" 'BEGIN { exit !(m > 0) }'
pm-render -q -e photons --force -j 1 floor.pms map.pm -o view1.exr
pm-diff view.exr view1.exr >d.txt
check "-e photons: same pixels with 1 thread" test "$(kv d.txt max_abs)" = 0

"$mkph" -n 0 -o empty.pm && pm-build -q empty.pm -o emap.pm
pm-render -q -e photons --force floor.pms emap.pm -o empty.exr
"$stat" empty.exr >e.txt
"$stat" --layer count empty.exr >ec.txt
check "an empty map renders black" test "$(kv e.txt max)" = 0 -a "$(kv ec.txt max)" = 0
expect_fail "-e photons needs a map" 2 "pm-render: the photons estimate needs a photon map" \
	pm-render -e photons floor.pms -o x.exr

# The furnace (albedo 0.5, emission 1): radiance 2 of which the light that
# bounced at least once before, reflected, is 0.5 * 1 = 0.5. The splats'
# expected value per pixel is exactly that.
cp "$PM_TOP/tests/scenes/furnace.pms" furnace.pms
pm-shoot -q -n 100000 -s 1 furnace.pms | pm-build -q | pm-render -q -e photons furnace.pms - -o fph.exr
"$stat" fph.exr >f.txt
num_near "furnace: the photon view averages to the exact 0.5" "$(kv f.txt mean)" 0.5 0.015

# PLY: header lines as the format (Turk's PLY, ascii 1.0) requires, one
# vertex line per photon with one value per property, colours in 0..255.
pm-dump --ply map.pm >cloud.ply
check "pm-dump --ply exits 0" test $? -eq 0
awk -v N=300 '
	function bad(m) { print "bad ply: " m " (line " NR ")"; err = 1; exit 1 }
	NR == 1 { if ($0 != "ply") bad("no magic"); next }
	NR == 2 { if ($0 != "format ascii 1.0") bad("format"); next }
	!body && $1 == "comment" { next }
	!body && $1 == "element" { if (NF != 3 || $2 != "vertex" || $3 != N) bad("element"); el++; next }
	!body && $1 == "property" {
		if (!el || NF != 3 || $2 !~ /^(char|uchar|short|ushort|int|uint|float|double)$/) bad("property")
		np++; type[np] = $2; next }
	!body && $0 == "end_header" { body = 1; next }
	!body { bad("header line") }
	{ nv++; if (NF != np) bad("fields")
	  for (i = 1; i <= NF; i++) {
		if (type[i] == "uchar" && ($i !~ /^[0-9]+$/ || $i > 255)) bad("uchar")
		if (type[i] == "float" && $i !~ /^-?[0-9.]+([eE][-+]?[0-9]+)?$/) bad("float") } }
	END { if (err) exit 1; if (!body || nv != N || np != 9) { print "bad ply: " nv " vertices, " np " properties"; exit 1 } }
' cloud.ply >ply.txt
check "pm-dump --ply is valid PLY with 300 vertices ($(cat ply.txt))" test $? -eq 0
check "PLY has x y z, red green blue, nx ny nz" sh -c \
	'grep "^property" cloud.ply | awk "{ printf \"%s \", \$3 }" | grep -q "^x y z red green blue nx ny nz $"'
