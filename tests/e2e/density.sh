# density.sh — pm-build --density (lib/estimators/density.h): fewer photons where the
# camera does not need them, the same total power (the records' power
# encoding aside), the same map for any -j; recorded in the map's header and
# the image; and on the furnace (exact radiance 2) the picture stays right.
. "$PM_TOP/tests/lib.sh"
T=$PM_BIN/../tests/tools

cp "$PM_TOP/tests/scenes/furnace.pms" furnace.pms
pm-shoot -q -n 60000 -s 3 furnace.pms -o shot.pm
pm-build -q shot.pm -o plain.pm
pm-build -q -j 1 --density furnace.pms --density-pixels 3 shot.pm >dc.pm
pm-build -q -j 2 --density furnace.pms --density-pixels 3 shot.pm >dc2.pm
pm-dump --stats plain.pm >plain.txt
pm-dump --stats dc.pm >dc.txt
n_plain=$(kv plain.txt photons) n_dc=$(kv dc.txt photons)
check "density control stores fewer photons ($n_dc of $n_plain)" \
	awk -v a="$n_dc" -v b="$n_plain" 'BEGIN { exit !(a > 0 && a < 0.8 * b) }'
check "and emits as many (the same light pass)" test "$(kv dc.txt emitted)" = "$(kv plain.txt emitted)"
# Energy: each channel's total power equal within 1e-4: the photons that
# took on others' power are stored again with 10-bit mantissas, rounded
# half up; here every photon carries the same power, so shares like 1/2 meet
# ties, and the total reads 1.2e-5 high. Without the hand-over it would lose
# the dropped photons' power, 60 % of it.
set -- $(kv plain.txt total_power)
p1=$1 p2=$2 p3=$3
set -- $(kv dc.txt total_power)
check "total power kept: $1 $2 $3 against $p1 $p2 $p3" awk -v a="$1 $2 $3" -v b="$p1 $p2 $p3" 'BEGIN {
	split(a, x, " "); split(b, y, " ")
	for (i = 1; i <= 3; i++) { d = x[i] / y[i] - 1; if (!(d < 1e-4 && d > -1e-4)) exit 1 }
	exit 0 }'
check "-j 1 and -j 2 write the same map" cmp -s dc.pm dc2.pm
check "the header says density=pixels 3 k 50" grep -aqx 'density=pixels 3 k 50' dc.pm
check "a plain map says density=off" grep -aqx 'density=off' plain.pm

pm-render -q -e compensated -p 16 -s 5 furnace.pms dc.pm -o dc.exr
pm-render -q -e compensated -p 16 -s 5 furnace.pms plain.pm -o plain.exr
"$T/exrstat" --window 12,9,28,21 dc.exr >dc-img.txt
num_near "furnace from the controlled map: centre mean = 2" "$(kv dc-img.txt mean)" 2 0.06
"$T/exrattr" dc.exr pm.density >attr.txt 2>&1
check "pm-render records pm.density" grep -qx 'pixels 3 k 50' attr.txt
"$T/exrattr" plain.exr pm.density >attr.txt 2>&1
check "and off for a plain map" grep -qx 'off' attr.txt

expect_fail "--density with another scene is refused" 1 "not the photons' scene" \
	pm-build --density "$PM_TOP/tests/scenes/mirror.pms" shot.pm -o x.pm
check "no output then" test ! -e x.pm
expect_fail "--density-pixels without --density is refused" 2 "need --density SCENE" \
	pm-build --density-pixels 3 shot.pm -o x.pm
sed 's/^density=off$/density=lots/' plain.pm >bad.pm
expect_fail "a bad density key is refused with the file and line" 1 \
	"bad.pm.*line 14: bad density 'lots'" pm-build bad.pm -o x.pm
