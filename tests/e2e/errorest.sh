# errorest.sh — the standard-error layer of an average against the true
# error, on a scene with a known answer: the furnace (every surface albedo
# 0.5 and emitting 1, so the exact radiance is 1 / (1 - 0.5) = 2 everywhere).
# The predicted RMSE is the root mean square of stderr.R/G/B over the pixels
# compared; the measured RMSE is pm-diff's against a constant 2 image. They
# must agree within a factor of 1.5.
#
# The stderr sees only the spread between passes, not bias. The path tracer
# has none; the compensated estimate has a little near edges and corners
# (about 0.018 RMS here at 5000 photons per pass), which at 16 passes is
# small against the noise (0.029): the test compares the whole image there,
# and also the pixels away from edges (the average's edge layer <= 0.5),
# where the bias is negligible. At 64 passes the whole-image noise falls to
# 0.014 and the edge bias would show (measured RMSE/predicted about 1.6).
. "$PM_TOP/tests/lib.sh"
mkimg=$PM_BIN/../tests/tools/mkimg

cp "$PM_TOP/tests/scenes/furnace.pms" furnace.pms
"$mkimg" -v 2,2,2 -c stderr.R=0 -c stderr.G=0 -c stderr.B=0 exact.exr 40 30

# ratio NAME AVG [MASK-ARGS...]: measured RMSE / predicted RMSE in [1/1.5, 1.5].
ratio() {
	n=$1 a=$2; shift 2
	pm-diff "$@" "$a" exact.exr >m.txt && pm-diff "$@" -l stderr "$a" exact.exr >p.txt ||
		{ notok "$n" "pm-diff failed"; return; }
	m=$(kv m.txt rmse) p=$(kv p.txt rmse)
	if awk -v m="$m" -v p="$p" 'BEGIN { exit !(p > 0 && m / p <= 1.5 && p / m <= 1.5) }'; then ok "$n"
	else notok "$n" "measured rmse $m, predicted $p"; fi
}

N=16
for i in $(seq 1 $N); do
	pm-render -q -e path -p 4 -P $i/$N furnace.pms -o path-$i.exr
	pm-shoot -q -n 5000 -P $i/$N furnace.pms | pm-build -q |
		pm-render -q -e compensated -p 4 -P $i/$N furnace.pms - -o comp-$i.exr
done
pm-average -q path-*.exr -o path.exr
pm-average -q comp-*.exr -o comp.exr
pm-average --stats path.exr >s.txt
check "16 passes averaged" test "$(kv s.txt passes)" = 16
num_near "path: the mean is the exact 2" "$(kv s.txt mean)" 2 0.02
ratio "path, 16 passes: stderr predicts the RMSE against the exact image (factor 1.5)" path.exr
ratio "compensated, 16 passes: stderr predicts the RMSE (factor 1.5)" comp.exr
ratio "compensated, 16 passes, away from edges: stderr predicts the RMSE (factor 1.5)" comp.exr -m comp.exr -c '!edge'
# The check can fail: an average of 4 of the passes, compared with the
# stderr of all 16, misses by a factor of about 2.
pm-average -q comp-1.exr comp-2.exr comp-3.exr comp-4.exr -o four.exr
pm-diff four.exr exact.exr >m.txt
pm-diff -l stderr comp.exr exact.exr >p.txt
check "the 16-pass stderr does not predict a 4-pass error" \
	awk -v m="$(kv m.txt rmse)" -v p="$(kv p.txt rmse)" 'BEGIN { exit !(m / p > 1.5) }'
