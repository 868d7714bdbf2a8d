# orientation.sh — the camera conventions formats/scene.md states, checked
# by rendering: a lamp at +x seen from +z (up +y) lands in the image's
# right half, seen from -z in its left half; a lamp at +y lands in the top
# half (image row 0 is the top). Also the rotation example there: a box
# rotated about its own centre stays where it was.
. "$PM_TOP/tests/lib.sh"
stat="$PM_BIN/../tests/tools/exrstat"

# lamp X0 Y0 X1 Y1: a two-sided emitting quad in the plane z = 0
lamp() { echo "quad lamp $1 $2 0  $3 $2 0  $3 $4 0  $1 $4 0"; }
# render NAME EYE-Z LAMP-LINE: the lamp seen from (0, 0, EYE-Z), up +y
render() {
	{ echo "camera eye 0 0 $2  look 0 0 0  up 0 1 0  fov 40  size 16 12"
	  echo "material lamp diffuse albedo 0 0 0 emit 1 1 1 twosided"
	  echo "$3"; } >"$1.pms"
	pm-render -q -e path -p 1 "$1.pms" -o "$1.exr" || notok "$1" "pm-render failed"
}
# mean FILE X0,Y0,X1,Y1: mean pixel value over the window
mean() { "$stat" --window "$2" "$1" | sed -n 's/^mean: //p'; }
# brighter NAME FILE WIN-A WIN-B: window A lit, window B dark
brighter() {
	a=$(mean "$2" "$3") b=$(mean "$2" "$4")
	if awk -v a="$a" -v b="$b" 'BEGIN { exit !(a > 0.01 && b == 0) }'; then ok "$1"
	else notok "$1" "lit half $a, dark half $b"; fi
}
left=0,0,8,12 right=8,0,16,12 top=0,0,16,6 bottom=0,6,16,12

render px-front 5 "$(lamp 0.3 -0.5 1.5 0.5)"
brighter "+x seen from +z is on the right" px-front.exr $right $left
render px-back -5 "$(lamp 0.3 -0.5 1.5 0.5)"
brighter "+x seen from -z is on the left" px-back.exr $left $right
render py-front 5 "$(lamp -0.5 0.3 0.5 1.2)"
brighter "+y is at the top (row 0)" py-front.exr $top $bottom

# rotating about the object's own centre (formats/scene.md's example): the
# box centred at (1, 0.3, 0) turned 45 degrees about y stays on the right
render spin 5 "box lamp 0.7 0 -0.3  1.3 0.6 0.3  translate -1 -0.3 0  rotate 0 1 0 45  translate 1 0.3 0"
brighter "a box rotated about its own centre stays in place" spin.exr $right $left
render fly 5 "box lamp 0.7 0 -0.3  1.3 0.6 0.3  rotate 0 1 0 180"
brighter "a box rotated about the origin moves (to -x)" fly.exr $left $right
