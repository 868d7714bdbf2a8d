# closed_room.sh — a room written as one closed mesh whose faces point out
# (a cube scaled up in a modelling program, exported with the camera and
# the lamp inside it; renderers with two-sided surfaces do not mind). pm
# takes a closed surface for a solid with its matter behind its faces, so
# such a room would have its air taken for matter; a closed surface round
# the camera's eye is turned over (formats/scene.md, "Solids: which side
# is matter"), and the compensated estimate must read what it reads in the
# same room written as `box ... inward`. Before that rule it read 25 % dark
# here, and a furnace wound so read 1.5 for 2.
. "$PM_TOP/tests/lib.sh"
stat=$PM_BIN/../tests/tools/exrstat

# room.obj: the six faces of [-2, 2] x [0, 2.5] x [-3, 3], each with corners
# of its own (a polygon soup, as flat-shaded exports write), counter-
# clockwise seen from outside the room.
awk 'BEGIN {
	split("-2 0 -3  2 0 -3  2 2.5 -3  -2 2.5 -3  -2 0 3  2 0 3  2 2.5 3  -2 2.5 3", c, " ")
	split("1 4 3 2  5 6 7 8  1 2 6 5  4 8 7 3  1 5 8 4  2 3 7 6", f, " ")
	for (i = 1; i <= 24; i++) {
		printf "v %s %s %s\n", c[3 * f[i] - 2], c[3 * f[i] - 1], c[3 * f[i]]
		if (i % 4 == 0) printf "f %d %d %d %d\n", i - 3, i - 2, i - 1, i
	}
}' >room.obj

head='camera eye 0 1.25 2.4  look 0 1 -3  up 0 1 0  fov 60  size 48 36'
# scene NAME ROOM-LINE MATERIAL-LINES...: the room lit by a lamp 1 mm under
# its ceiling (one-sided, facing down), a block on its floor
scene() {
	n=$1 room=$2
	{ echo "$head"; echo "material w diffuse albedo 0.6 0.6 0.6"
	  echo "material lamp diffuse albedo 0 0 0 emit 8 8 8"
	  echo "quad lamp -0.4 2.499 -1.4  0.4 2.499 -1.4  0.4 2.499 -0.6  -0.4 2.499 -0.6"
	  echo "box w -0.5 0 -2  0.5 0.6 -1.2"
	  echo "$room"; } >"$n.pms"
}
scene out "mesh room.obj w"
scene box "box w -2 0 -3  2 2.5 3 inward"
for n in out box; do
	for i in 1 2 3 4; do
		pm-shoot -n 40000 -P $i/4 $n.pms | pm-build | pm-render -q -P $i/4 -p 4 $n.pms - -o $n-$i.exr
	done
	pm-average -q $n-*.exr -o $n.exr
	"$stat" $n.exr >$n.txt
done
a=$(kv out.txt mean) b=$(kv box.txt mean)
echo "# mean: outward closed mesh $a, box inward $b"
num_near "lit room as a closed mesh facing out reads as the same room inward" \
	"$(awk -v a="$a" -v b="$b" 'BEGIN { print a / b }')" 1 0.03

# The furnace (every surface albedo 0.5, emission 1 on both sides): 2
# everywhere.
{ echo "$head"; echo "material f diffuse albedo 0.5 0.5 0.5 emit 1 1 1 twosided"
  echo "mesh room.obj f"; echo "box f -0.5 0 -2  0.5 0.6 -1.2"; } >furnace.pms
for i in 1 2 3 4; do
	pm-shoot -n 40000 -P $i/4 furnace.pms | pm-build | pm-render -q -P $i/4 -p 4 furnace.pms - -o f-$i.exr
done
pm-average -q f-*.exr -o furnace.exr
"$stat" furnace.exr >furnace.txt
num_near "furnace room as a closed mesh facing out reads 2" "$(kv furnace.txt mean)" 2 0.03
num_near "furnace room as a closed mesh facing out: no pixel off by 15%" "$(kv furnace.txt min)" 2 0.3
