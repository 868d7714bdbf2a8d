#!/bin/sh
# scenes.sh — extreme scenes through the whole pipeline (issue 24): each
# scene goes through pm-shoot (with caustic and guide maps, at a shutter
# time near 1), pm-build (and its density control), pm-render with every
# estimator of -e (and final gathering with both maps) and pm-tonemap, and
# must end, within a time bound, either with images whose pixels are all
# finite or with pm-shoot's one-line refusal "pm-shoot: FILE:LINE: ..."
# (exit 1, no output), which pm-render must then give too; a generated
# scene marked "tame" (every extreme inside the range of formats/scene.md)
# must render. Prints "ok - " / "not ok - " lines.
#
# Usage: scenes.sh BUILD_DIR SEED_FIRST SEED_LAST [KEEP_DIR]
#        scenes.sh BUILD_DIR --cases DIR...
# The first form makes each scene with tests/tools/genextreme; a scene that
# fails is copied to KEEP_DIR/seed-N (to keep it, move it to
# tests/fuzz/regress/pipeline/). The second replays saved cases: each DIR
# holds a scene.pms and the mesh files it names.
# Settings: T (seconds per program run, default 120), N (photons, 1500).
B=$(cd "$1" && pwd) || exit 2
shift
T=${T:-120}
N=${N:-1500}
export PATH="$B/bin:$PATH"
stat="$B/tests/tools/exrstat"
# Outside tests/run.sh (make fuzz-scenes) a sanitizer's report must not
# pass for a refusal: a distinct exit status.
export ASAN_OPTIONS="${ASAN_OPTIONS:-exitcode=99:intercept_tls_get_addr=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-halt_on_error=1:exitcode=99}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# run NAME PROG ARGS...: PROG under the time bound, stderr to $work/err;
# sets rc (124 and up: killed, hung or crashed)
run() {
	timeout -s KILL "$T" "$@" >/dev/null 2>"$work/err" </dev/null
	rc=$?
}
# finite FILE: every pixel of an EXR is a finite number
finite() {
	"$stat" "$1" >"$work/stat" 2>&1 &&
		awk '/^(min|max|mean):/ { if ($2 !~ /^[-+]?[0-9.]+(e[-+]?[0-9]+)?$/) bad = 1; n++ }
		     END { exit bad || n < 3 }' "$work/stat"
}
# refusal PROG FILE: the one stderr line is "PROG: FILE:LINE: message"
refusal() {
	[ "$(wc -l <"$work/err")" -eq 1 ] && grep -q "^$1: $2:[0-9][0-9]*: ." "$work/err"
}

# case NAME DIR: the drill on DIR/scene.pms; 0 if it passed
drill() {
	name=$1
	# in a copy: saved cases stay as they are
	rm -rf "$work/case" && cp -r "$2" "$work/case" || exit 9
	( cd "$work/case" || exit 9
	# pass 8 of 8: a shutter time near 1, where 'move' has moved things
	run pm-shoot -q -n "$N" -P 8/8 scene.pms -o p.pm --caustic c.pm --guide g.pm
	if [ "$rc" -eq 1 ] && refusal pm-shoot scene.pms && [ ! -e p.pm ]; then
		run pm-render -q -p 1 -P 8/8 -e path scene.pms -o out-path.exr
		if [ "$rc" -eq 1 ] && refusal pm-render scene.pms && [ ! -e out-path.exr ]; then
			case $name in *"(tame"*)
				echo "not ok - $name: in range, yet refused: $(cut -c1-200 "$work/err")"; exit 1 ;;
			esac
			echo "ok - $name: refused: $(cut -c1-150 "$work/err")"; exit 0
		fi
		echo "not ok - $name: pm-shoot refused, pm-render -e path exit $rc: $(head -c 200 "$work/err")"; exit 1
	fi
	[ "$rc" -eq 0 ] || { echo "not ok - $name: pm-shoot exit $rc: $(head -c 300 "$work/err")"; exit 1; }
	for b in "p.pm -o m.pm" "c.pm -o cm.pm" "g.pm -o gm.pm" "--density scene.pms p.pm -o dm.pm"; do
		run pm-build -q $b
		[ "$rc" -eq 0 ] || { echo "not ok - $name: pm-build $b: exit $rc: $(head -c 300 "$work/err")"; exit 1; }
	done
	for e in classical compensated photons path gather; do
		case $e in
		path) run pm-render -q -p 1 -P 8/8 -e path scene.pms -o out-$e.exr ;;
		gather) run pm-render -q -p 1 -P 8/8 -g 2 --caustic cm.pm --guide gm.pm scene.pms m.pm -o out-$e.exr ;;
		compensated) run pm-render -q -p 1 -P 8/8 -e $e scene.pms dm.pm -o out-$e.exr ;;
		*) run pm-render -q -p 1 -P 8/8 -e $e scene.pms m.pm -o out-$e.exr ;;
		esac
		[ "$rc" -eq 0 ] || { echo "not ok - $name: pm-render -e $e exit $rc: $(head -c 300 "$work/err")"; exit 1; }
		finite out-$e.exr || { echo "not ok - $name: pm-render -e $e: pixels not finite: $(tr '\n' ' ' <"$work/stat")"; exit 1; }
	done
	# and the preview of one of them
	run pm-tonemap out-compensated.exr -o out.png
	[ "$rc" -eq 0 ] || { echo "not ok - $name: pm-tonemap exit $rc: $(head -c 300 "$work/err")"; exit 1; }
	echo "ok - $name: clean images" )
}

fails=0
if [ "$1" = --cases ]; then
	shift
	for d in "$@"; do
		drill "case $(basename "$d")" "$d" || fails=$((fails + 1))
	done
else
	first=$1 last=$2 keep=${3:-}
	s=$first
	while [ "$s" -le "$last" ]; do
		d="$work/seed-$s"
		what=$("$B/tests/tools/genextreme" "$s" "$d") || { echo "not ok - seed $s: genextreme failed"; exit 1; }
		if ! drill "seed $s ($what)" "$d"; then
			fails=$((fails + 1))
			[ -n "$keep" ] && mkdir -p "$keep" && rm -rf "$keep/seed-$s" && cp -r "$d" "$keep/seed-$s"
		fi
		rm -rf "$d"
		s=$((s + 1))
	done
fi
[ "$fails" -eq 0 ]
