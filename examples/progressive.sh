#!/bin/sh
# progressive.sh — progressive refinement (paper §4: "adding pairs … until
# the achieved image quality is good enough"): pass pairs in rounds that
# double, each round averaged and merged into the running average (averages
# of averages are exact), a preview PNG per round, until the estimated
# relative error falls below TARGET.
#
# Usage: examples/progressive.sh SCENE TARGET
#   TARGET: the mean standard error over pixels and R, G, B divided by the
#   mean radiance, both from `pm-average --stats` (mean_stderr / mean), e.g.
#   0.01 for 1%.
# Settings from the environment: FIRST=2 passes in round 1 (at least 2: one
#   pass has no spread to estimate from), ROUNDS=8 at most, PHOTONS=100000
#   per pass, SPP=16, K=50, EST=compensated, P=cores in parallel,
#   OUT=examples/out/progressive, PM_BIN=build/bin.
# Round r runs passes -P 1/n … n/n with n = FIRST·2^(r−1): each round is a
# complete stratified set of shutter times, and its seeds differ from every
# other round's (the seed depends on I and N). Writes OUT/round-R/pass-I.exr,
# OUT/round-R.exr (the round's average), OUT/image.exr (the running average),
# OUT/round-R.png and OUT/image.png (previews); prints one line per round:
#   round R: passes P mean_stderr S mean M relative X
# and on stderr the progress of each round's passes, and at the end one
# summary line: passes, seconds, relative standard error
# (examples/fanout/progress.sh).
# Exit status: 0 when the target is reached, 1 if ROUNDS rounds did not reach
# it (image.exr then holds every pass run), 2 for a bad command line.
set -eu
if [ $# -ne 2 ]; then
	echo "usage: progressive.sh SCENE TARGET" >&2
	exit 2
fi
top=$(cd "$(dirname "$0")/.." && pwd)
scene=$(cd "$(dirname "$1")" && pwd)/$(basename "$1") target=$2
awk -v t="$target" 'BEGIN { exit !(t + 0 > 0) }' || { echo "progressive.sh: TARGET '$target' is not a number > 0" >&2; exit 2; }
bin=${PM_BIN:-$top/build/bin}
FIRST=${FIRST:-2} ROUNDS=${ROUNDS:-8} P=${P:-$(nproc)}
out=${OUT:-$top/examples/out/progressive}
[ "$FIRST" -ge 2 ] || { echo "progressive.sh: FIRST must be at least 2" >&2; exit 2; }
export PM_BIN="$bin" PHOTONS=${PHOTONS:-100000} SPP=${SPP:-16} K=${K:-50} EST=${EST:-compensated}
. "$top/examples/fanout/progress.sh"
mkdir -p "$out"
rm -f "$out/image.exr"
n=$FIRST r=1
while [ "$r" -le "$ROUNDS" ]; do
	dir=$out/round-$r
	mkdir -p "$dir"
	progress_begin "$n" "round $r"
	(cd "$dir" && seq 1 "$n" | xargs -P "$P" -I{} sh "$top/examples/fanout/pass.sh" {} "$n" "$scene")
	progress_end
	"$bin/pm-average" -q $(seq -f "$dir/pass-%g.exr" 1 "$n") -o "$out/round-$r.exr"
	if [ -e "$out/image.exr" ]; then
		# pm-average refuses to write over an input: a new file, then a rename.
		"$bin/pm-average" -q "$out/image.exr" "$out/round-$r.exr" -o "$out/image-next.exr"
		mv "$out/image-next.exr" "$out/image.exr"
	else
		cp "$out/round-$r.exr" "$out/image.exr"
	fi
	"$bin/pm-tonemap" -q "$out/image.exr" -o "$out/round-$r.png"
	cp "$out/round-$r.png" "$out/image.png"
	stats=$("$bin/pm-average" --stats "$out/image.exr")
	line=$(echo "$stats" | awk -v r="$r" '
		/^passes:/ { p = $2 } /^mean_stderr:/ { s = $2 } /^mean:/ { m = $2 }
		END { printf "round %d: passes %d mean_stderr %.6g mean %.6g relative %.6g\n", r, p, s, m, (m > 0 ? s / m : 0) }')
	echo "$line"
	if echo "$line" | awk -v t="$target" '{ exit !(NF == 10 && $NF < t) }'; then
		echo "target $target reached: $out/image.exr, preview $out/image.png"
		progress_summary progressive.sh "$out/image.exr"
		exit 0
	fi
	n=$((n * 2)) r=$((r + 1))
done
progress_summary progressive.sh "$out/image.exr"
echo "progressive.sh: target $target not reached after $ROUNDS rounds; $out/image.exr has them all" >&2
exit 1
