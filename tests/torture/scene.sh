#!/bin/sh
# scene.sh — one scene of the torture harness: the compensated and the
# classical photon estimates, from the same photon maps, against a
# path-traced reference; and the same geometry as a furnace (every surface
# albedo 0.5, emission 1: radiance exactly 2) against the exact answer.
#
# Usage: tests/torture/scene.sh SEED|SCENE.pms DIR
#   SEED       a generated scene (tests/tools/genscene SEED)
#   SCENE.pms  a fixed scene (tests/torture/regress/); its mesh files are
#              copied with it. A scene holding the line `# torture: exact V`
#              is itself a furnace (exact radiance V): no path reference.
#              Otherwise its furnace twin is made by giving every material
#              `diffuse albedo 0.5 0.5 0.5 emit 1 1 1 twosided` and dropping
#              its point lights (unless it says `# torture: no furnace twin`).
# Writes DIR/stats.txt (key=value: scene, desc, seconds, torturestat's keys,
# and the furnace twin's with a furnace_ prefix), DIR/scene/ and
# DIR/furnace/ (the scene files; comp.exr, class.exr, ref.exr averages;
# mask.exr, the first compensated pass, whose edge layer is the edge band;
# err-comp.exr and err-class.exr, pm-diff -o against the reference).
#
# Settings (environment):
#   N=8 PHOTONS=50000 K=50 SPP=4   pass pairs (-P i/N on pm-shoot and
#                                  pm-render), photons, k, samples per pixel
#   REFPASSES=8 REFSPP=128         the path reference: REFPASSES passes of
#                                  REFSPP samples, averaged (stderr layer)
#   FURNACE=1 FURNACE_N=16         also the furnace twin (0: not), with
#                                  FURNACE_N pass pairs (no path tracing
#                                  there, so more passes are cheap)
#   SIZE="W H"                     override the image size (default: the
#                                  scene's; genscene's default is 96 72)
#   J=0                            threads per program (0: all cores)
#   TIMEOUT=120                    seconds any one program may run (0: no
#                                  limit); past it the scene fails with a
#                                  line "scene.sh: TIMEOUT: ..." on stderr
#   PM_BIN                         the programs (default build/bin); the
#                                  helpers are in $PM_BIN/../tests/tools
set -eu
here=$(cd "$(dirname "$0")" && pwd)
top=$(cd "$here/../.." && pwd)
bin=${PM_BIN:-$top/build/bin}
tools=$bin/../tests/tools
N=${N:-8} PHOTONS=${PHOTONS:-50000} K=${K:-50} SPP=${SPP:-4}
REFPASSES=${REFPASSES:-8} REFSPP=${REFSPP:-128}
FURNACE=${FURNACE:-1} FURNACE_N=${FURNACE_N:-16} SIZE=${SIZE:-} J=${J:-0} TIMEOUT=${TIMEOUT:-120}
[ $# -eq 2 ] || { echo "usage: scene.sh SEED|SCENE.pms DIR" >&2; exit 2; }
src=$1 dir=$2
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
rm -rf "$dir/scene" "$dir/furnace" "$dir/stats.txt"
start=$(date +%s.%N)

# run PROGRAM ARGS...: the program under the time limit.
run() {
	if [ "$TIMEOUT" = 0 ] || ! command -v timeout >/dev/null; then
		"$@"
		return
	fi
	st=0
	timeout "$TIMEOUT" "$@" || st=$?
	[ "$st" -eq 124 ] && echo "scene.sh: TIMEOUT: $(basename "$1") ran over $TIMEOUT s: $*" >&2
	return "$st"
}

# copy_scene FROM.pms TODIR: the scene (image size overridden by SIZE) and
# the mesh files it names.
copy_scene() {
	mkdir -p "$2"
	if [ -n "$SIZE" ]; then
		sed "/^[ 	]*camera/s/size[ 	][ 	]*[0-9][0-9]*[ 	][ 	]*[0-9][0-9]*/size $SIZE/" "$1" >"$2/scene.pms"
	else
		cp "$1" "$2/scene.pms"
	fi
	for m in $(awk '$1 == "mesh" { print $2 }' "$1"); do
		mkdir -p "$2/$(dirname "$m")"
		cp "$(dirname "$1")/$m" "$2/$m"
	done
}

exact=
case $src in
*.pms)
	[ -f "$src" ] || { echo "scene.sh: cannot open '$src'" >&2; exit 1; }
	name=$(basename "$src" .pms)
	copy_scene "$src" "$dir/scene"
	# the description: the comment lines at the top, joined
	desc=$(awk '!/^#/ { exit } !/^# torture:/ { sub(/^# */, ""); printf "%s%s", n++ ? " " : "", $0 }' "$src")
	exact=$(sed -n 's/^# torture: exact \([0-9.]*\).*/\1/p' "$src" | head -n 1)
	# `# torture: no furnace twin` where the twin is no furnace: two
	# coplanar two-sided emitters (a floor laid exactly on a floor) emit
	# into a gap of no thickness, which the path tracer too reads bright.
	if [ -z "$exact" ] && [ "$FURNACE" = 1 ] && ! grep -q '^# torture: no furnace twin' "$src"; then
		copy_scene "$src" "$dir/furnace"
		{
			echo "# torture: exact 2"
			sed -e 's/^\([ 	]*material[ 	][ 	]*[^ 	#]*\).*/\1 diffuse albedo 0.5 0.5 0.5 emit 1 1 1 twosided/' \
			    -e '/^[ 	]*pointlight/d' "$dir/furnace/scene.pms"
		} >"$dir/furnace/scene.tmp"
		mv "$dir/furnace/scene.tmp" "$dir/furnace/scene.pms"
	fi
	;;
*)
	name=$src
	sz=
	[ -n "$SIZE" ] && sz="--size $SIZE"
	desc=$("$tools/genscene" "$src" "$dir/scene" $sz)
	if [ "$FURNACE" = 1 ]; then
		"$tools/genscene" "$src" "$dir/furnace" --furnace $sz >/dev/null
		grep -q '^# torture: no furnace twin' "$dir/furnace/scene.pms" && rm -rf "$dir/furnace"
	fi
	;;
esac

# halves DIR PREFIX OUT: the odd and the even passes DIR/PREFIX-I.exr
# averaged apart, OUT-A.exr and OUT-B.exr: their errors' noise is
# independent, which torturestat --halves uses to take noise out of the
# edge band's error.
halves() {
	"$bin/pm-average" -q $(ls "$1/$2"-*.exr | awk -F- '{ n = $NF; sub(/\.exr$/, "", n) } n % 2 == 1') -o "$3-A.exr"
	"$bin/pm-average" -q $(ls "$1/$2"-*.exr | awk -F- '{ n = $NF; sub(/\.exr$/, "", n) } n % 2 == 0') -o "$3-B.exr"
}

# photon_passes SCENEDIR [PASSES]: PASSES (default N) pass pairs, each map
# rendered with both estimators; averages comp.exr and class.exr and their
# halves; mask.exr = compensated pass 1.
photon_passes() {
	sd=$1 i=1 N=${2:-$N}
	while [ "$i" -le "$N" ]; do
		run "$bin/pm-shoot" -q -j "$J" -n "$PHOTONS" -P "$i/$N" "$sd/scene.pms" -o "$sd/photons.pm"
		run "$bin/pm-build" -q -j "$J" "$sd/photons.pm" -o "$sd/map.pm"
		rm -f "$sd/photons.pm"
		run "$bin/pm-render" -q -j "$J" -e compensated -k "$K" -p "$SPP" -P "$i/$N" "$sd/scene.pms" "$sd/map.pm" -o "$sd/pass-comp-$i.exr"
		run "$bin/pm-render" -q -j "$J" -e classical -k "$K" -p "$SPP" -P "$i/$N" "$sd/scene.pms" "$sd/map.pm" -o "$sd/pass-class-$i.exr"
		i=$((i + 1))
	done
	rm -f "$sd/map.pm"
	"$bin/pm-average" -q "$sd"/pass-comp-*.exr -o "$sd/comp.exr"
	"$bin/pm-average" -q "$sd"/pass-class-*.exr -o "$sd/class.exr"
	halves "$sd" pass-comp "$sd/comp"
	halves "$sd" pass-class "$sd/class"
	mv "$sd/pass-comp-1.exr" "$sd/mask.exr"
	rm -f "$sd"/pass-*.exr
}

# path_reference SCENEDIR: ref.exr, REFPASSES passes of the path tracer.
path_reference() {
	sd=$1 i=1
	while [ "$i" -le "$REFPASSES" ]; do
		run "$bin/pm-render" -q -j "$J" -e path -p "$REFSPP" -P "$i/$REFPASSES" "$sd/scene.pms" -o "$sd/pass-path-$i.exr"
		i=$((i + 1))
	done
	"$bin/pm-average" -q "$sd"/pass-path-*.exr -o "$sd/ref.exr"
	halves "$sd" pass-path "$sd/ref"
	rm -f "$sd"/pass-path-*.exr
}

# errmaps SCENEDIR REF: err-comp.exr, err-class.exr ((estimate - ref) / ref).
errmaps() {
	"$bin/pm-diff" -o "$1/err-comp.exr" "$1/comp.exr" "$2" >/dev/null
	"$bin/pm-diff" -o "$1/err-class.exr" "$1/class.exr" "$2" >/dev/null
}

{
	echo "scene=$name"
	echo "desc=$desc"
	echo "settings=N=$N PHOTONS=$PHOTONS K=$K SPP=$SPP REFPASSES=$REFPASSES REFSPP=$REFSPP size=$(sed -n 's/^[ 	]*camera.*size[ 	][ 	]*\([0-9]*\)[ 	][ 	]*\([0-9]*\).*/\1x\2/p' "$dir/scene/scene.pms")"
} >"$dir/stats.tmp"
photon_passes "$dir/scene"
if [ -n "$exact" ]; then
	"$tools/mkimg" -v "$exact,$exact,$exact" "$dir/scene/ref.exr" \
		$(sed -n 's/^[ 	]*camera.*size[ 	][ 	]*\([0-9]*\)[ 	][ 	]*\([0-9]*\).*/\1 \2/p' "$dir/scene/scene.pms")
	"$tools/torturestat" --comp "$dir/scene/comp.exr" --class "$dir/scene/class.exr" --exact "$exact" \
		--mask "$dir/scene/mask.exr" --halves "$dir/scene/comp-A.exr" "$dir/scene/comp-B.exr" \
		"$dir/scene/class-A.exr" "$dir/scene/class-B.exr" --verdict >>"$dir/stats.tmp"
else
	path_reference "$dir/scene"
	"$tools/torturestat" --comp "$dir/scene/comp.exr" --class "$dir/scene/class.exr" --ref "$dir/scene/ref.exr" \
		--mask "$dir/scene/mask.exr" --halves "$dir/scene/comp-A.exr" "$dir/scene/comp-B.exr" \
		"$dir/scene/class-A.exr" "$dir/scene/class-B.exr" "$dir/scene/ref-A.exr" "$dir/scene/ref-B.exr" \
		--verdict >>"$dir/stats.tmp"
fi
errmaps "$dir/scene" "$dir/scene/ref.exr"
if [ -f "$dir/furnace/scene.pms" ]; then
	photon_passes "$dir/furnace" "$FURNACE_N"
	"$tools/mkimg" -v 2,2,2 "$dir/furnace/exact.exr" \
		$(sed -n 's/^[ 	]*camera.*size[ 	][ 	]*\([0-9]*\)[ 	][ 	]*\([0-9]*\).*/\1 \2/p' "$dir/furnace/scene.pms")
	"$tools/torturestat" --comp "$dir/furnace/comp.exr" --class "$dir/furnace/class.exr" --exact 2 \
		--mask "$dir/furnace/mask.exr" --halves "$dir/furnace/comp-A.exr" "$dir/furnace/comp-B.exr" \
		"$dir/furnace/class-A.exr" "$dir/furnace/class-B.exr" --verdict | sed 's/^/furnace_/' >>"$dir/stats.tmp"
	errmaps "$dir/furnace" "$dir/furnace/exact.exr"
fi
echo "seconds=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')" >>"$dir/stats.tmp"
mv "$dir/stats.tmp" "$dir/stats.txt"
