# thin_cover.sh — a shadow ray stops short of the light's surface by the
# tracer's offset measured across that surface, not along the ray: an
# emitter under an opaque lid a little more than that offset above it (a
# floor quad laid 0.07 mm over an emitting floor, as the torture
# generator's furnace twins have them) sends no light past the lid. The
# offset here is about 0.048 mm (formats/scene.md: 1e-5 of the scene's
# diagonal plus the coordinates' rounding); stopping twice that short
# along a steep ray skipped the lid and lit the ceiling.
. "$PM_TOP/tests/lib.sh"

stat=$PM_BIN/../tests/tools/exrstat
{ echo "camera eye 0 1 2.5  look 0 2 0  up 0 1 0  fov 40  size 24 18"
  echo "material lamp diffuse albedo 0 0 0 emit 10 10 10"
  echo "material black diffuse albedo 0 0 0"
  echo "material white diffuse albedo 0.8 0.8 0.8"
  echo "quad lamp  -0.5 0 0.5  0.5 0 0.5  0.5 0 -0.5  -0.5 0 -0.5"
  echo "quad black  -0.7 0.00007 0.7  0.7 0.00007 0.7  0.7 0.00007 -0.7  -0.7 0.00007 -0.7"
  echo "quad white  -1.5 2 -1.5  1.5 2 -1.5  1.5 2 1.5  -1.5 2 1.5"; } >cover.pms
# The same without the lid: the ceiling is lit, so the picture above is
# not black for some other reason.
grep -v '^quad black' cover.pms >open.pms
pm-render -q -e path -p 4 -s 1 cover.pms -o cover.exr
pm-render -q -e path -p 4 -s 1 open.pms -o open.exr
shut=$("$stat" cover.exr | sed -n 's/^max: *//p') lit=$("$stat" open.exr | sed -n 's/^max: *//p')
echo "# ceiling under the lid 0.07 mm over the lamp: max $shut; without the lid: max $lit"
check "no light past a lid 0.07 mm over the lamp (path tracer)" awk -v m="$shut" 'BEGIN { exit !(m == 0) }'
check "light without the lid" awk -v m="$lit" 'BEGIN { exit !(m > 0.01) }'
# A photon pass: its direct light takes the same shadow rays.
pm-shoot -q -n 20000 -s 1 cover.pms | pm-build -q -o cover.pm
pm-render -q -p 4 -s 1 cover.pms cover.pm -o cover-c.exr
shut=$("$stat" cover-c.exr | sed -n 's/^max: *//p')
check "no light past the lid (compensated view pass)" awk -v m="$shut" 'BEGIN { exit !(m == 0) }'
