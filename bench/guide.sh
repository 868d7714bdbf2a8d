#!/bin/sh
# guide.sh — guide maps (pm-shoot --guide, pm-render --guide: importance
# sampling by the photon map where camera paths go on from strong glossy
# surfaces) against BSDF sampling alone, on scenes with a strong glossy
# floor: one pass's relative variance (relpassvar, from the spread of N pass
# pairs, bench/errsplit.c), the core-seconds of a pass pair (pm-shoot, with
# --guide for the guided mode, pm-build of the map(s), pm-render), their
# efficiency 1 / (relpassvar x seconds), and the N-pass average's relMSE
# against a path-traced reference (the mean must not move; it includes the
# reference's own noise and the photon estimate's bias, the same in both).
#
# Usage: bench/guide.sh [BUILD_DIR]   (default build; needs bin/ and
# bench/errsplit: make bench-progs). Environment, with defaults:
#   N=8 pass pairs per mode, PHOTONS=100000 per pass, SPP=16,
#   SCENES="room glossyroom glossycornell", REF_PASSES=4 REF_SPP=256
# Scenes: examples/room at 128 x 96 (the paper's strong glossy floor, lit
# mostly from the cove); glossyroom, tests/scenes/glossyroom.pms (a dark room
# whose glossy floor sees only a lit patch of ceiling), 64 x 48; glossycornell, the
# Cornell box with a strong glossy floor (kd 0.4, ks 0.35, exponent 300),
# 64 x 64. Writes bench/results/guide.tsv.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
B=${1:-build}
case $B in /*) ;; *) B=$top/$B ;; esac
N=${N:-8} PHOTONS=${PHOTONS:-100000} SPP=${SPP:-16}
SCENES=${SCENES:-room glossyroom glossycornell}
. "$top/bench/passes.sh"
out=$res/guide.tsv
printf 'scene\tmode\tpasses\tseconds_per_pass\trelpassvar\tefficiency\trelmse_vs_ref\tguide_photons\n' >"$out"

now() { date +%s.%N; }

for name in $SCENES; do
	case $name in
	room) sc=$(scene room 128 96) ;;
	glossyroom)
		mkdir -p "$tmp/gr"
		sc=$tmp/gr/glossyroom.pms
		sed 's/size 32 24/size 64 48/' "$top/tests/scenes/glossyroom.pms" >"$sc"
		;;
	glossycornell)
		c=$(scene cornell 64 64)
		sc=$(dirname "$c")/glossycornell.pms
		sed -e 's/^quad white  552.8 0 0 /quad floor  552.8 0 0 /' \
		    -e 's/^material white .*/&\nmaterial floor glossy kd 0.4 0.4 0.4 ks 0.35 0.35 0.35 exponent 300/' \
		    "$c" >"$sc"
		;;
	*) echo "$0: unknown scene '$name'" >&2; exit 2 ;;
	esac
	ref=$(reference "$name" "$sc")
	for mode in bsdf guided; do
		echo "guide: $name, $mode, $N pass pairs of $PHOTONS photons, -p $SPP" >&2
		t=0 gp=0
		for i in $(seq 1 "$N"); do
			t0=$(now)
			if [ $mode = guided ]; then
				"$bin/pm-shoot" -q -j 1 -n "$PHOTONS" -P "$i/$N" --guide "$tmp/g.ph" "$sc" |
					"$bin/pm-build" -q -j 1 -o "$tmp/map.pm"
				"$bin/pm-build" -q -j 1 "$tmp/g.ph" -o "$tmp/guide.pm"
				"$bin/pm-render" -q -j 1 -p "$SPP" -P "$i/$N" --guide "$tmp/guide.pm" "$sc" "$tmp/map.pm" \
					-o "$tmp/pass-$i.exr"
			else
				"$bin/pm-shoot" -q -j 1 -n "$PHOTONS" -P "$i/$N" "$sc" |
					"$bin/pm-build" -q -j 1 -o "$tmp/map.pm"
				"$bin/pm-render" -q -j 1 -p "$SPP" -P "$i/$N" "$sc" "$tmp/map.pm" -o "$tmp/pass-$i.exr"
			fi
			t1=$(now)
			t=$(awk -v a="$t" -v b="$t0" -v c="$t1" 'BEGIN { print a + c - b }')
		done
		[ $mode = guided ] && gp=$("$bin/pm-dump" --stats "$tmp/guide.pm" | sed -n 's/^photons: *//p')
		"$bin/pm-average" -q $(seq -f "$tmp/pass-%g.exr" 1 "$N") -o "$tmp/avg.exr"
		# errsplit: pixels mse rmse relmse passvar relpassvar refvar relrefvar
		"$bb/errsplit" "$tmp/avg.exr" "$ref" | awk -v OFS='\t' -v sc="$name" -v m="$mode" \
			-v n="$N" -v t="$t" -v gp="$gp" '{
			s = t / n
			printf "%s\t%s\t%d\t%.3f\t%.4g\t%.4g\t%.4g\t%s\n", sc, m, n, s, $6, 1 / ($6 * s), $4, gp
		}' >>"$out"
		rm -f "$tmp"/pass-*.exr
	done
done
cat "$out"
