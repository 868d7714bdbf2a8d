# motion.sh — motion blur (paper §4): 16 pass pairs, each at the time -P I/16
# derives, average into the blur of a moving emitter whose footprint is
# known exactly from the geometry, and a still render at t = 0 shows none.
#
# An emitting quad (radiance 1, albedo 0, nothing else in view) 1 unit wide
# moves 4 units along +x over the shutter. The camera looks straight at it,
# 8 pixels per unit: the quad starts on columns 8..15 and rows 4..11 and
# sweeps to columns 40..47. A point of the sweep between x = -2 and x = 1
# (columns 16..39) is covered for 1/4 of the shutter, so the averaged image
# reads 1/4 there; columns 8..15 and 40..47 ramp; everything else is 0. The
# image holds the quad's area, 64 pixels, at every time: its mean is 1/16.
# A white floor and ceiling out of view give the light pass photons to store.
# exrstat windows are X0,Y0,X1,Y1 with X1 and Y1 excluded.
. "$PM_TOP/tests/lib.sh"
stat=$PM_BIN/../tests/tools/exrstat

cat >moving.pms <<'SCENE'
camera eye 0 0 10  look 0 0 0  up 0 1 0  fov 11.42118627  size 64 16
material lamp diffuse albedo 0 0 0 emit 1 1 1
material white diffuse albedo 0.8 0.8 0.8
quad lamp -3 -0.5 0  -2 -0.5 0  -2 0.5 0  -3 0.5 0  move 4 0 0
quad white -20 -3 12  20 -3 12  20 -3 -10  -20 -3 -10
quad white -20 3 -10  20 3 -10  20 3 12  -20 3 12
SCENE

N=16
for i in $(seq 1 $N); do
	pm-shoot -q -n 500 -P $i/$N moving.pms | pm-build -q |
		pm-render -q -e classical -p 16 -P $i/$N moving.pms - -o pass-$i.exr || notok "pass $i" "failed"
done
pm-average -q $(seq -f 'pass-%g.exr' 1 $N) -o blur.exr
pm-render -q -e path -p 16 -t 0 moving.pms -o still.exr

"$stat" blur.exr >all.txt
num_near "blur: the image holds the quad's area (mean 1/16)" "$(kv all.txt mean)" 0.0625 0.002
"$stat" --window 16,4,40,12 blur.exr >mid.txt
num_near "blur: the middle of the sweep reads 1/4 (mean)" "$(kv mid.txt mean)" 0.25 0.02
# 16 stratified times: a quarter of the shutter holds 3 to 5 of them.
check "blur: every pixel of the middle of the sweep in [3/16, 5/16] (min $(kv mid.txt min))" \
	awk -v a="$(kv mid.txt min)" 'BEGIN { exit !(a >= 0.15) }'
check "blur: ... (max $(kv mid.txt max))" awk -v a="$(kv mid.txt max)" 'BEGIN { exit !(a <= 0.35) }'
"$stat" --window 8,4,16,12 blur.exr >start.txt
num_near "blur: the start ramps up (mean 1/8)" "$(kv start.txt mean)" 0.125 0.02
for w in 0,0,64,4 0,12,64,16 0,4,8,12 48,4,64,12; do
	"$stat" --window $w blur.exr >out.txt
	check "blur: nothing outside the sweep ($w)" test "$(kv out.txt max)" = 0
done

"$stat" --window 16,4,40,12 still.exr >smid.txt
check "still t=0: nothing in the middle of the sweep" test "$(kv smid.txt max)" = 0
"$stat" --window 8,4,16,12 still.exr >sstart.txt
num_near "still t=0: the quad where it starts" "$(kv sstart.txt mean)" 1 0.001
