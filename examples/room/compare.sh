#!/bin/sh
# compare.sh — the paper's figure 3 for the room: the same N photon maps
# shown with the classical estimate (a) and the compensated one (b), side by
# side, plus their difference. Settings as in examples/passes.sh (N, PHOTONS,
# SPP, K, P, OUT, PM_BIN). Progress and a summary (of the compensated
# average) on stderr, as examples/fanout/progress.sh shows them.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
top=$(cd "$here/../.." && pwd)
bin=${PM_BIN:-$top/build/bin}
N=${N:-8} PHOTONS=${PHOTONS:-200000} SPP=${SPP:-16} K=${K:-50}
P=${P:-$(nproc)}
out=${OUT:-$top/examples/out}
scene=$here/room.pms
d=$out/figure3
mkdir -p "$d"
export bin scene d N PHOTONS SPP K PM_BIN="$bin"
. "$top/examples/fanout/progress.sh"
progress_begin "$N" figure3
# One photon map per pass, rendered twice, then dropped.
seq 1 "$N" | xargs -P "$P" -I{} sh -c '
	set -e
	"$bin/pm-shoot" -q -j 1 -n "$PHOTONS" -P {}/"$N" "$scene" | "$bin/pm-build" -q -j 1 -o "$d/map-{}.pm"
	for est in classical compensated; do
		"$bin/pm-render" -q -j 1 -e $est -k "$K" -p "$SPP" -P {}/"$N" "$scene" "$d/map-{}.pm" -o "$d/$est-{}.exr"
	done
	rm -f "$d/map-{}.pm"
	echo {} >>"$PM_PROGRESS_LOG"'
progress_end
for est in classical compensated; do
	"$bin/pm-average" -q "$d"/$est-[0-9]*.exr -o "$out/room-$est.exr"
done
"$bin/pm-tonemap" "$out/room-classical.exr" "$out/room-compensated.exr" -o "$out/figure3.png"
"$bin/pm-diff" -o "$out/room-difference.exr" "$out/room-classical.exr" "$out/room-compensated.exr" >"$out/room-difference.txt"
"$bin/pm-tonemap" -q -c clamp --abs -e 3 "$out/room-difference.exr" -o "$out/figure3-difference.png"
progress_summary figure3 "$out/room-compensated.exr"
echo "figure 3: classical | compensated from the same $N photon maps in $out/figure3.png;"
echo "  |classical - compensated| / compensated (x8) in $out/figure3-difference.png"
