#!/bin/sh
# scenes.sh — make check-scenes: pm-import on the public scenes of
# ../shared/scenes (three CC0 scenes of Bitterli's collection, not part of
# the repository; skipped when absent), pm's path tracer on each imported
# scene, and its agreement with the reference image shipped beside it,
# compared at an eighth of the reference's size (the reference box-averaged
# 8 x 8, pm rendered with its pixel-area samples at that size, so both are
# averages over the same pixel footprints): the whole-image mean within 3 %,
# and the 16 x 16 grid of block means within the scene's tolerance:
#   cornell-box (pbrt and Mitsuba): every material exact (diffuse), so the
#     blocks differ by noise only (512 samples a pixel: 0.6 % rms, 2.7 % at
#     most measured): rms <= 2 %, max <= 6 %;
#   veach-mis: conductors of roughness 0.01-0.25 become Blinn lobes, whose
#     highlights are narrower in the tails than GGX's (-70 % to +30 % on the
#     plates' blocks): rms <= 30 %, max <= 80 %. Measured against pbrt-v4
#     on the same file at 160 x 90 (as make check-peers renders): with
#     the plates made diffuse, pm reads 0.992 of pbrt (block rms 1.5 %: the
#     camera, the sphere lights and the rest import exactly); as mirrors,
#     0.989 (rms 6.6 %); the file's maxdepth 3 against 100 moves pbrt by
#     0.16 % (rms 1.5 %), so pm's lack of a depth cap does not matter here.
#     With the file's roughness pbrt's plates read 2-17 times its mirror
#     plates (the lights' highlights spread by GGX's long tails) while pm's
#     Blinn plates read 0.1-0.6 of its mirrors: pm 0.647 of pbrt overall,
#     plates -60 to -94 %. That is the mapping, not a bug. pbrt-v4 itself
#     reads 1.52 times the shipped Tungsten reference here (plates 2-3.5
#     times), so the reference's agreement with pm (0.984) is partly luck;
#   water-caustic: its floor is lit only through the water by a light of
#     2e-5 m^2: pm's path tracer does not converge on it (mean 0.73 or 1.14,
#     block rms 480 % or 770 %, as its roulette changes the noise, at 256
#     samples), a known failure reported only. pm's photon
#     pipeline (2M photons, compensated, the paper's method) is checked
#     too: mean 0.983, block rms 11 % (<= 15 % asked). Its worst block
#     (-92 %) holds the light's mirror image in the water, a quarter of a
#     reference pixel of radiance ~4e4 that 16 samples a pixel hit 0.06
#     times on average: pbrt-v4's own SPPM at this size misses it the same
#     way (-92.6 %), so it stays a known failure, of sampling. Against
#     pbrt-v4 SPPM at 128 x 128 (64 passes, radius 0.05): pm's photons read
#     1.015 of pbrt at maxdepth 64 (rms 4.4 %, max 15 %), 1.049 at the
#     file's maxdepth 9 (pm has no depth cap; pbrt itself reads +3.4 % from
#     9 to 64).
# Usage: tests/public/scenes.sh BUILD_DIR
top=$(cd "$(dirname "$0")/../.." && pwd)
B=$(cd "$1" && pwd)
src=${PM_SCENES:-$top/../shared/scenes}
if [ ! -d "$src" ]; then echo "check-scenes: no $src, skipped"; exit 0; fi
PATH="$B/bin:$PATH"
blocks="$B/tests/tools/exrblocks"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pass=0 fail=0
# one NAME INPUT W H SPP RMS MAX [known]; PHOTONS=N one ...: pm-shoot -n N |
# pm-build | pm-render -e compensated instead of the path tracer
one() {
	name=$1 in=$2 w=$3 h=$4 spp=$5 trms=$6 tmax=$7 known=${8:-}
	ref=$(dirname "$in")/TungstenRender.exr
	[ -f "$ref" ] || ref=$src/$(echo "$name" | cut -d- -f1-2)/pbrt/TungstenRender.exr
	if ! pm-import -q "$in" --size "$w" "$h" -o "$work/$name/scene.pms" 2>"$work/err"; then
		echo "not ok - $name: import failed: $(cat "$work/err")"; fail=$((fail + 1)); return
	fi
	start=$(date +%s)
	if [ -n "${PHOTONS:-}" ]; then
		pm-shoot -q -n "$PHOTONS" "$work/$name/scene.pms" | pm-build -q |
			pm-render -q -e compensated -p "$spp" "$work/$name/scene.pms" - -o "$work/$name.exr"
	else
		pm-render -q -e path -p "$spp" "$work/$name/scene.pms" -o "$work/$name.exr"
	fi || { echo "not ok - $name: render failed"; fail=$((fail + 1)); return; }
	"$blocks" "$work/$name.exr" "$ref" >"$work/$name.txt"
	kv() { sed -n "s/^$1: //p" "$work/$name.txt"; }
	ratio=$(kv mean_ratio) rms=$(kv block_rel_rms) max=$(kv block_rel_max)
	line="$name: ${w}x$h, $spp spp, $(( $(date +%s) - start )) s: mean pm/ref $ratio, blocks rel rms $rms, max $max (at $(kv worst_block))"
	if awk -v r="$ratio" -v a="$rms" -v m="$max" -v ta="$trms" -v tm="$tmax" \
		'BEGIN { exit !(r >= 0.97 && r <= 1.03 && a <= ta && m <= tm) }'; then
		echo "ok - $line"; pass=$((pass + 1))
	elif [ -n "$known" ]; then
		echo "known failure - $line ($known)"
	else
		echo "not ok - $line (want mean within 3 %, rms <= $trms, max <= $tmax)"; fail=$((fail + 1))
	fi
}
one cornell-box-pbrt "$src/cornell-box/pbrt/scene-v4.pbrt" 128 128 512 0.02 0.06
one cornell-box-mitsuba "$src/cornell-box/mitsuba/scene_v3.xml" 128 128 512 0.02 0.06
one veach-mis "$src/veach-mis/pbrt/scene-v4.pbrt" 160 90 256 0.30 0.80
one water-caustic "$src/water-caustic/pbrt/scene-v4.pbrt" 128 128 256 0.1 0.3 \
	"caustics through water from a light of 2e-5 m^2: the path tracer does not converge"
PHOTONS=2000000 one water-caustic-photons "$src/water-caustic/pbrt/scene-v4.pbrt" 128 128 16 0.15 0.3 \
	"one block holds the light's tiny mirror image in the water, which 16 samples a pixel miss (-92 %; pbrt's SPPM too)"
echo "check-scenes: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
