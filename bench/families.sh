#!/bin/sh
# families.sh — the compensated estimate's price and the pipeline's
# efficiency on the meshes users bring (issue 21): for each scene, one view
# pass's time with the compensated and with the classical estimate (their
# ratio is the estimate's price), and at equal time the efficiency
# 1 / (relMSE x seconds) of N pass pairs (pm-shoot | pm-build | pm-render,
# averaged with pm-average) against pm's path tracer, both against a
# converged path-traced reference.
#
# Usage: bench/families.sh [quick|mid|full] [BUILD_DIR]   (default quick,
# build; needs bin/ and bench/errsplit: make bench-progs). Environment,
# defaults by mode (quick | mid | full):
#   SCENES   cornell room caustic and bench/families.py's families
#            (prims dense scanned soup thin cove); add a family there and here
#   SIZE     image width: 96 | 256 | 256 (height by the scene's aspect)
#   PHOTONS  photons per pass: 200000
#   K        photons per estimate (pm-render -k) for the price and every
#            photon-map series: 50, pm-render's default
#   RUNS     view-pass timings per estimator, median taken: 3 | 3 | 5
#   N        pass pairs per estimator for the efficiency: 8 | 8 | 32
#   REF_PASSES x REF_SPP  the reference: 8 x 256 | 8 x 256 | 32 x 1024 (cached in
#            BENCH_CACHE, default BUILD_DIR/bench-cache)
#   J        threads per program: 2
#   GATHER   final gathering's rays per pixel for the series with it
#            (gather-compensated, gather-classical; pm-render -g): 32; 0
#            leaves those series out
#   BUDGET   seconds a scene's compensated series may take: 120 | 300 | 1200;
#            past it (and after 2 pass pairs) the series stops, and a view
#            pass that takes more than BUDGET / 4 is timed once, not RUNS
#            times, and one over BUDGET / 2 gets no efficiency series (a
#            dense mesh can cost minutes per pass: that is the price being
#            measured, not a reason to wait an hour)
# Times are wall seconds with J threads (pm-render's defaults otherwise:
# -k 50 -p 16 -l 4; the path tracer -p 64 -l 1, its best per bench/run.sh).
# The path tracer runs passes until it has used the compensated run's time.
# relMSE has the reference's own variance taken out (bench/errsplit.c).
# Writes bench/results/families-cost.tsv and families-efficiency.tsv.
set -eu
mode=${1:-quick}
top=$(cd "$(dirname "$0")/.." && pwd)
B=${2:-build}
case $B in /*) ;; *) B=$top/$B ;; esac
case $mode in
quick) d_size=96 d_runs=3 d_n=8 d_rp=8 d_rs=256 d_budget=120 ;;
mid) d_size=256 d_runs=3 d_n=8 d_rp=8 d_rs=256 d_budget=300 ;;
full) d_size=256 d_runs=5 d_n=32 d_rp=32 d_rs=1024 d_budget=1200 ;;
*) echo "usage: bench/families.sh [quick|mid|full] [BUILD_DIR]" >&2; exit 2 ;;
esac
SCENES=${SCENES:-cornell room caustic prims dense scanned soup thin cove}
SIZE=${SIZE:-$d_size} PHOTONS=${PHOTONS:-200000} K=${K:-50} RUNS=${RUNS:-$d_runs} N=${N:-$d_n} J=${J:-2} GATHER=${GATHER:-32}
REF_PASSES=${REF_PASSES:-$d_rp} REF_SPP=${REF_SPP:-$d_rs} BUDGET=${BUDGET:-$d_budget}
. "$top/bench/passes.sh"
command -v python3 >/dev/null || { echo "$0: python3 missing (bench/families.py writes the scenes)" >&2; exit 1; }
cost=$res/families-cost.tsv eff=$res/families-efficiency.tsv
printf 'scene\tpolygons\tsize\tcompensated_s\tclassical_s\tratio\n' >"$cost"
printf 'scene\tmethod\tpasses\tseconds\trelmse\tefficiency\tvs_path\n' >"$eff"
series="compensated classical path"
[ "$GATHER" -gt 0 ] && series="compensated classical gather-compensated gather-classical path"
now() { date +%s.%N; }
log() { echo "families: $*" >&2; }
# median of the numbers on stdin
median() { sort -g | awk '{ a[NR] = $1 } END { print NR % 2 ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
# timed CMD...: runs CMD, prints its wall seconds
timed() { t0=$(now); "$@"; t1=$(now); awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f\n", b - a }'; }

python3 "$top/bench/families.py" "$tmp/fam" --size "$SIZE" "$SIZE" >"$tmp/fam.txt"
for name in $SCENES; do
	case $name in
	cornell|caustic) sc=$(scene "$name" "$SIZE" "$SIZE") ;;
	room) sc=$(scene room "$SIZE" $((SIZE * 3 / 4))) ;;
	*)
		[ -f "$tmp/fam/$name/$name.pms" ] || { echo "$0: unknown scene '$name'" >&2; exit 2; }
		sc=$tmp/fam/$name/$name.pms
		;;
	esac
	npoly=$(awk -F'\t' -v n="$name" '$1 == n { print $2 + 0 }' "$tmp/fam.txt")
	[ -n "$npoly" ] || npoly=-
	size=$(sed -n 's/^camera .*size  *\([0-9]*\)  *\([0-9]*\).*/\1x\2/p' "$sc")

	# The price: one view pass on one photon map, each estimator RUNS times.
	log "$name ($size): view pass, compensated and classical, $PHOTONS photons, k $K, $RUNS runs each"
	"$bin/pm-shoot" -q -j "$J" -n "$PHOTONS" -s 1 "$sc" | "$bin/pm-build" -q -j "$J" -o "$tmp/map.pm"
	for est in compensated classical; do
		: >"$tmp/runs"
		for r in $(seq 1 "$RUNS"); do
			timed "$bin/pm-render" -q -j "$J" -e $est -k "$K" -s 1 "$sc" "$tmp/map.pm" -o "$tmp/v.exr" >>"$tmp/runs"
			awk -v t="$(tail -n 1 "$tmp/runs")" -v b="$BUDGET" 'BEGIN { exit !(t > b / 4) }' && break
		done
		median <"$tmp/runs" >"$tmp/t-$est"
	done
	awk -v OFS='\t' -v n="$name" -v p="$npoly" -v s="$size" -v c="$(cat "$tmp/t-compensated")" \
		-v k="$(cat "$tmp/t-classical")" 'BEGIN { print n, p, s, c, k, sprintf("%.2f", c / k) }' >>"$cost"

	# The efficiency at equal time, against a converged reference; not
	# where one compensated view pass alone takes half the budget.
	if awk -v t="$(cat "$tmp/t-compensated")" -v b="$BUDGET" 'BEGIN { exit !(t > b / 2) }'; then
		log "$name: a compensated view pass takes over BUDGET / 2 = $BUDGET / 2 s: no efficiency series"
		for est in $series; do printf '%s\t%s\t-\t-\t-\t-\t-\n' "$name" $est; done >>"$eff"
		continue
	fi
	rk=$cache/fam-ref-$name-$(cat "$sc" "$(dirname "$sc")"/*.obj 2>/dev/null | cksum | cut -d' ' -f1)-$REF_PASSES-$REF_SPP.exr
	if [ ! -s "$rk" ]; then
		log "$name: reference, $REF_PASSES x $REF_SPP spp path-traced"
		for i in $(seq 1 "$REF_PASSES"); do
			"$bin/pm-render" -q -j "$J" -e path -p "$REF_SPP" -s "1000$i" "$sc" -o "$tmp/ref-$i.exr"
		done
		"$bin/pm-average" -q "$tmp"/ref-*.exr -o "$rk.tmp.exr" && mv "$rk.tmp.exr" "$rk"
		rm -f "$tmp"/ref-*.exr
	fi
	tcomp=
	for est in $series; do
		case $est in
		gather-*) e=${est#gather-} g=$GATHER ;;
		*) e=$est g=0 ;;
		esac
		log "$name: $est pass pairs"
		t=0 i=0
		while :; do
			i=$((i + 1))
			if [ $est = path ]; then
				s=$(timed "$bin/pm-render" -q -j "$J" -e path -p 64 -l 1 -P "$i/1000" "$sc" -o "$tmp/pass-$i.exr")
			else
				s=$(timed sh -c '"$1/pm-shoot" -q -j "$2" -n "$3" -P "$4" "$5" | "$1/pm-build" -q -j "$2" |
					"$1/pm-render" -q -j "$2" -e "$6" -g "$8" -k "$9" -P "$4" "$5" - -o "$7"' sh \
					"$bin" "$J" "$PHOTONS" "$i/$N" "$sc" $e "$tmp/pass-$i.exr" $g "$K")
			fi
			t=$(awk -v a="$t" -v b="$s" 'BEGIN { print a + b }')
			if [ $est = path ]; then
				awk -v t="$t" -v c="$tcomp" 'BEGIN { exit !(t < c) }' || break
			else
				[ "$i" -lt "$N" ] || break
				if [ "$i" -ge 2 ] && awk -v t="$t" -v b="$BUDGET" 'BEGIN { exit !(t > b) }'; then
					break
				fi
			fi
		done
		[ $est = compensated ] && tcomp=$t
		"$bin/pm-average" -q $(seq -f "$tmp/pass-%g.exr" 1 "$i") -o "$tmp/avg-$est.exr"
		rm -f "$tmp"/pass-*.exr
		# errsplit: pixels mse rmse relmse passvar relpassvar refvar relrefvar
		"$bb/errsplit" "$tmp/avg-$est.exr" "$rk" | awk -v OFS='\t' -v n="$name" -v e="$est" -v p="$i" -v t="$t" '{
			r = $4 - $8; if (r < 1e-9) r = 1e-9
			printf "%s\t%s\t%d\t%.2f\t%.4g\t%.4g\n", n, e, p, t, r, 1 / (r * t) }' >>"$tmp/eff-$name"
	done
	pe=$(awk -F'\t' '$2 == "path" { print $6 }' "$tmp/eff-$name")
	awk -F'\t' -v OFS='\t' -v pe="$pe" '{ print $0, sprintf("%.2f", $6 / pe) }' "$tmp/eff-$name" >>"$eff"
done
cat "$cost" "$eff"
