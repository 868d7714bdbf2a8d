# soup_room.sh — a room built as six separate quads (a polygon soup of
# sheets, as modelling tools export rooms, not one closed `box ... inward`)
# with a table that is one OBJ polygon soup (every face its own vertices):
# as a furnace (every surface albedo 0.5, emission 1, two-sided) the
# radiance is exactly 1 / (1 - 0.5) = 2 everywhere. The compensated
# estimate must read 2 where the wall meets the ceiling, in the strip of
# wall just below that edge and on the ceiling just above it (issue 21
# reported a dark strip there on such a room), and away from it.
. "$PM_TOP/tests/lib.sh"
tools=$PM_BIN/../tests/tools

# The table: a top on four legs, five boxes' faces, none shared.
awk 'function box(x0, y0, z0, x1, y1, z1,   i, f, c) {
	split(x0 " " y0 " " z0 " " x1 " " y0 " " z0 " " x1 " " y1 " " z0 " " x0 " " y1 " " z0 " " \
	      x0 " " y0 " " z1 " " x1 " " y0 " " z1 " " x1 " " y1 " " z1 " " x0 " " y1 " " z1, c, " ")
	split("1 4 3 2 5 6 7 8 1 2 6 5 4 8 7 3 1 5 8 4 2 3 7 6", f, " ")
	for (i = 1; i <= 24; i++) {
		printf "v %s %s %s\n", c[3 * f[i] - 2], c[3 * f[i] - 1], c[3 * f[i]]
		if (i % 4 == 0) { printf "f %d %d %d %d\n", n + 1, n + 2, n + 3, n + 4; n += 4 }
	}
}
BEGIN {
	box(-0.6, 0.7, -2.2, 0.6, 0.75, -1.4)
	box(-0.6, 0, -2.2, -0.55, 0.7, -2.15); box(0.55, 0, -2.2, 0.6, 0.7, -2.15)
	box(-0.6, 0, -1.45, -0.55, 0.7, -1.4); box(0.55, 0, -1.45, 0.6, 0.7, -1.4)
}' >table.obj
cat >room.pms <<'SCENE'
camera eye 0 1.25 2.9  look 0 1.25 -3  up 0 1 0  fov 60  size 64 48
material f diffuse albedo 0.5 0.5 0.5 emit 1 1 1 twosided
quad f -2 0 -3  -2 0 3  2 0 3  2 0 -3
quad f -2 2.5 -3  2 2.5 -3  2 2.5 3  -2 2.5 3
quad f -2 0 -3  2 0 -3  2 2.5 -3  -2 2.5 -3
quad f -2 0 3  -2 2.5 3  2 2.5 3  2 0 3
quad f -2 0 -3  -2 2.5 -3  -2 2.5 3  -2 0 3
quad f 2 0 -3  2 0 3  2 2.5 3  2 2.5 -3
mesh table.obj f
SCENE
for i in $(seq 1 8); do
	pm-shoot -n 50000 -P $i/8 room.pms | pm-build | pm-render -P $i/8 room.pms - -o pass-$i.exr
done
pm-average -q pass-*.exr -o comp.exr
# The back wall's top edge is at row 15.2 (1.25 above the eye at 5.9,
# tan 30 degrees to 24 rows); the wall runs over columns 18-45.
"$tools/exrstat" --window 20,16,44,19 comp.exr >below.txt
"$tools/exrstat" --window 20,12,44,15 comp.exr >above.txt
"$tools/exrstat" comp.exr >all.txt
echo "# wall below the edge $(kv below.txt mean), ceiling above it $(kv above.txt mean), image $(kv all.txt mean)"
num_near "room of six quads: whole image reads 2" "$(kv all.txt mean)" 2 0.02
num_near "room of six quads: wall strip below the wall-ceiling edge reads 2" "$(kv below.txt mean)" 2 0.03
num_near "room of six quads: ceiling strip above the edge reads 2" "$(kv above.txt mean)" 2 0.03
num_near "room of six quads: no pixel off by 10%" "$(kv all.txt min)" 2 0.2
