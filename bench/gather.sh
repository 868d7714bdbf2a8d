#!/bin/sh
# gather.sh — final gathering against direct visualization (issue 11): error
# against time on the Cornell box, the caustic scene (a glass and a mirror
# sphere) and the room, whole image and edge band; and the caustic's energy
# in a window in front of the glass sphere. Writes bench/results/gather.tsv,
# bench/results/gather-caustic.tsv (every pass's window mean in
# gather-caustic-passes.tsv) and bench/results/gather-SCENE.png.
#
# Usage: bench/gather.sh [BUILD_DIR]   (default build; make all-tests
# first: it reads window means with tests/tools/exrstat)
# Environment (defaults in brackets): GATHER_PARTS which parts to run
# ["sweep caustic"], GATHER_NMAX pass pairs per mode in the sweep [4],
# GATHER_PHOTONS global photons per pass [50000], GATHER_CAUSTIC caustic
# photons per pass [50000], GATHER_RAYS gather rays per pixel [64],
# GATHER_SIZE "W H" of the Cornell and caustic images [64 64] (the room's
# height is 3/4 of it), GATHER_SPP camera samples per pixel [4]; for the
# caustic part GATHER_CNMAX passes [64], GATHER_CPHOTONS [200000],
# GATHER_CCAUSTIC [100000] and GATHER_CREF path-traced passes of 1024 spp
# for the window's reference [64, at least 2]; BENCH_CACHE where
# references are kept [BUILD_DIR/bench-cache].
#
# Errors are pm-diff's against a path-traced reference, of the beauty and
# of the indirect layer (everything but the emission and direct light of
# the first surface, which every mode computes alike; its noise would
# otherwise decide the comparison), the latter also over the edge band
# (the compensated estimate's edge layer, as bench/run.sh takes it).
#
# Every pass pair runs single-threaded, one after the other:
#   pm-shoot -j 1 [--caustic c --caustic-photons C] | pm-build -j 1 | pm-render -j 1
# and a mode's time after N passes is the sum of their wall times
# (core-seconds). The direct modes shoot no caustic map; the gathering
# modes do, and their time includes it.
set -eu
top=$(cd "$(dirname "$0")/.." && pwd)
B=${1:-build}
case $B in /*) ;; *) B=$top/$B ;; esac
bin=$B/bin
cache=${BENCH_CACHE:-$B/bench-cache}
PARTS=${GATHER_PARTS:-sweep caustic}
NMAX=${GATHER_NMAX:-4} P=${GATHER_PHOTONS:-50000} C=${GATHER_CAUSTIC:-50000}
CNMAX=${GATHER_CNMAX:-64} CP=${GATHER_CPHOTONS:-200000} CC=${GATHER_CCAUSTIC:-100000}
CREF=${GATHER_CREF:-64}
G=${GATHER_RAYS:-64} SPP=${GATHER_SPP:-4}
set -- ${GATHER_SIZE:-64 64}
W=$1 H=$2
res=$top/bench/results
for p in pm-shoot pm-build pm-render pm-average; do
	[ -x "$bin/$p" ] || { echo "gather: '$bin/$p' missing: make first" >&2; exit 1; }
done
[ -x "$B/tests/tools/exrstat" ] || { echo "gather: '$B/tests/tools/exrstat' missing: make all-tests" >&2; exit 1; }
mkdir -p "$res" "$cache/ref"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
log() { echo "gather: $*" >&2; }
now() { date +%s.%N; }

# The modes: a name, and pm-render's options. Gathering reads the
# compensated estimate (pm-render's default) where rays land.
modes="direct-classical direct-compensated gather gather-irr gather-guided gather-irr-guided"
opts_of() {
	case $1 in
	direct-classical) echo "-e classical" ;;
	direct-compensated) echo "-e compensated" ;;
	gather) echo "-g $G --irradiance 0" ;;
	gather-irr) echo "-g $G --irradiance 4" ;;
	gather-guided) echo "-g $G --irradiance 0 --guided" ;;
	gather-irr-guided) echo "-g $G --irradiance 4 --guided" ;;
	esac
}

# scene NAME W H: a copy of the example at W x H, meshes beside it
scene() {
	d=$tmp/scenes/$1
	mkdir -p "$d"
	cp "$top/examples/$1"/* "$d"/
	sed "s/^\(camera .*\)size  *[0-9][0-9]*  *[0-9][0-9]*/\1size $2 $3/" "$top/examples/$1/$1.pms" >"$d/$1.pms"
	echo "$d/$1.pms"
}

# reference NAME SCENE: 8 path-traced passes of 1024 spp, cached by the
# scene's bytes
reference() {
	key=$(cat "$(dirname "$2")"/* | cksum | awk '{ print $1 "-8-1024" }')
	r=$cache/ref/gather-$1-$key.exr
	if [ ! -s "$r" ]; then
		log "reference for $1: 8 path-traced passes of 1024 spp"
		for i in 1 2 3 4 5 6 7 8; do
			"$bin/pm-render" -q -e path -p 1024 -s "1000$i" "$2" -o "$tmp/ref-$i.exr"
		done
		"$bin/pm-average" -q "$tmp"/ref-*.exr -o "$r.tmp.exr"
		mv "$r.tmp.exr" "$r"
		# the passes stay beside it, for the caustic part's standard error
		for i in 1 2 3 4 5 6 7 8; do
			mv "$tmp/ref-$i.exr" "${r%.exr}-pass$i.exr"
		done
	fi
	echo "$r"
}

# ref_passes NAME SCENE N: N path-traced passes of 1024 spp like
# reference NAME's (REF-pass1.exr ... beside it; the first 8 are the ones
# it averages, rendered again with the same seeds where a cache made before
# they were kept lacks them); prints their names
ref_passes() {
	r=$(reference "$1" "$2")
	i=1
	while [ $i -le "$3" ]; do
		f=${r%.exr}-pass$i.exr
		if [ ! -s "$f" ]; then
			log "reference for $1: pass $i of $3 (for the window's standard error)"
			"$bin/pm-render" -q -e path -p 1024 -s "1000$i" "$2" -o "$f.tmp.exr"
			mv "$f.tmp.exr" "$f"
		fi
		echo "$f"
		i=$((i + 1))
	done
}

# mean WIN IMG: the mean of R, G, B over the window X0,Y0,X1,Y1 (inclusive)
mean() {
	"$B/tests/tools/exrstat" --window "$1" "$2" | sed -n 's/^mean: //p'
}

# diff A REF [MASK] [LAYER]: "rmse<TAB>relmse" of A against REF
diff() {
	"$bin/pm-diff" ${4:+-l "$4"} ${3:+-m "$3" -c edge} "$1" "$2" |
		awk '/^rmse:/ { r = $2 } /^relmse:/ { m = $2 } END { printf "%s\t%s", r, m }'
}

# passes SCENE MODE N PHOTONS CAUSTIC: N pass pairs into $tmp/pass-I.exr,
# wall times into $tmp/t-I
passes() {
	o=$(opts_of "$2")
	i=1
	while [ $i -le "$3" ]; do
		a=$(now)
		case $2 in
		direct-*)
			"$bin/pm-shoot" -q -j 1 -n "$4" -s $i "$1" | "$bin/pm-build" -q -j 1 -o "$tmp/g.pm"
			# shellcheck disable=SC2086
			"$bin/pm-render" -q -j 1 $o -p "$SPP" -s $i "$1" "$tmp/g.pm" -o "$tmp/pass-$i.exr" ;;
		*)
			"$bin/pm-shoot" -q -j 1 -n "$4" --caustic "$tmp/c.ph" --caustic-photons "$5" -s $i "$1" |
				"$bin/pm-build" -q -j 1 -o "$tmp/g.pm"
			"$bin/pm-build" -q -j 1 "$tmp/c.ph" -o "$tmp/c.pm"
			# shellcheck disable=SC2086
			"$bin/pm-render" -q -j 1 $o -p "$SPP" -s $i "$1" "$tmp/g.pm" --caustic "$tmp/c.pm" \
				-o "$tmp/pass-$i.exr" ;;
		esac
		b=$(now)
		awk -v a="$a" -v b="$b" 'BEGIN { printf "%.3f\n", b - a }' >"$tmp/t-$i"
		i=$((i + 1))
	done
}

# average N: the first N passes into $tmp/avg.exr; prints their time
average() {
	# shellcheck disable=SC2046
	"$bin/pm-average" -q $(seq 1 "$1" | sed "s|.*|$tmp/pass-&.exr|") -o "$tmp/avg.exr"
	seq 1 "$1" | sed "s|.*|$tmp/t-&|" | xargs cat | awk '{ s += $1 } END { printf "%.2f", s }'
}

hq=$((H * 3 / 4))
case " $PARTS " in *" sweep "*)
out=$res/gather.tsv
printf 'scene\tmode\tpasses\ttime_s\trmse\trelmse\tind_rmse\tind_relmse\tedge_ind_rmse\tedge_ind_relmse\n' >"$out"
for name in cornell caustic room; do
	case $name in room) sc=$(scene room "$W" "$hq") ;; *) sc=$(scene "$name" "$W" "$H") ;; esac
	ref=$(reference "$name" "$sc")
	mask=$tmp/mask-$name.exr
	"$bin/pm-shoot" -q -n "$P" -s 999 "$sc" | "$bin/pm-build" -q |
		"$bin/pm-render" -q -p "$SPP" -s 999 "$sc" - -o "$mask"
	for mode in $modes; do
		log "$name: $mode, $NMAX pass pairs"
		passes "$sc" "$mode" "$NMAX" "$P" "$C"
		n=1
		while [ $n -le "$NMAX" ]; do
			t=$(average $n)
			printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$mode" "$n" "$t" \
				"$(diff "$tmp/avg.exr" "$ref")" "$(diff "$tmp/avg.exr" "$ref" "" indirect)" \
				"$(diff "$tmp/avg.exr" "$ref" "$mask" indirect)" >>"$out"
			n=$((n * 2))
		done
		rm -f "$tmp"/pass-*.exr "$tmp"/t-*
	done
done
;; esac

# The caustic the glass sphere focuses onto the floor in front of it
# (x 36-50, y 53-63 of 64 x 64, scaled to the size): every pass's window
# mean against the reference's, after 1, 2, 4 ... CNMAX passes (CNMAX
# always), with more photons. ratio is the mean of the passes' ratios (the
# ratio of their average), stderr its standard error (the passes' sample
# standard deviation over sqrt(passes)). The window's reference is the mean
# of CREF path-traced passes (the first 8 those of the sweep's reference
# image), ref_stderr its standard error relative to it.
# Every pass's window mean is in gather-caustic-passes.tsv (the reference's
# as mode "reference").
case " $PARTS " in *" caustic "*)
cout=$res/gather-caustic.tsv
pout=$res/gather-caustic-passes.tsv
printf 'mode\tphotons\tcaustic_photons\tpasses\twindow\tmean\treference\tratio\tstderr\tref_stderr\n' >"$cout"
printf 'mode\tpass\twindow\tmean\tratio\n' >"$pout"
sc=$(scene caustic "$W" "$H")
ref=$(reference caustic "$sc")
win=$((36 * W / 64)),$((53 * H / 64)),$((50 * W / 64)),$((H - 1))
i=1
for f in $(ref_passes caustic "$sc" "$CREF"); do
	printf 'reference\t%s\t%s\t%s\n' $i "$win" "$(mean "$win" "$f")"
	i=$((i + 1))
done >"$tmp/refm"
# the reference's mean and relative standard error from its passes
r=$(awk -F'\t' '{ n++; s += $4 } END { printf "%.9g", s / n }' "$tmp/refm")
rse=$(awk -F'\t' -v m="$r" '{ n++; q += ($4 - m) ^ 2 } END { printf "%.5f", sqrt(q / (n - 1) / n) / m }' "$tmp/refm")
awk -F'\t' -v OFS='\t' -v r="$r" '{ print $0, sprintf("%.5f", $4 / r) }' "$tmp/refm" >>"$pout"
log "caustic window $win: reference mean $r (relative standard error $rse over $CREF passes; the 8-pass reference image's $(mean "$win" "$ref"))"
for mode in $modes; do
	case $mode in direct-*) cc=0 ;; *) cc=$CC ;; esac
	log "caustic window: $mode, $CNMAX pass pairs of $CP (+ $cc caustic) photons"
	passes "$sc" "$mode" "$CNMAX" "$CP" "$CC"
	i=1
	while [ $i -le "$CNMAX" ]; do
		m=$(mean "$win" "$tmp/pass-$i.exr")
		printf '%s\t%s\t%s\t%s\t%s\n' "$mode" $i "$win" "$m" \
			"$(awk -v a="$m" -v b="$r" 'BEGIN { printf "%.5f", a / b }')"
		i=$((i + 1))
	done >"$tmp/m"
	cat "$tmp/m" >>"$pout"
	n=1
	while :; do
		[ "$n" -gt "$CNMAX" ] && n=$CNMAX
		head -n "$n" "$tmp/m" | awk -F'\t' -v OFS='\t' -v mode="$mode" -v cp="$CP" -v cc="$cc" \
			-v win="$win" -v r="$r" -v rse="$rse" '
			{ k++; s += $4; x += $5; q += $5 * $5 }
			END { mr = x / k
				if (k > 1) { v = (q - k * mr * mr) / (k - 1); if (v < 0) v = 0
					se = sprintf("%.4f", sqrt(v / k)) } else se = "NA"
				print mode, cp, cc, k, win, sprintf("%.9g", s / k), r, sprintf("%.4f", mr), se, rse }' >>"$cout"
		[ "$n" -eq "$CNMAX" ] && break
		n=$((n * 2))
	done
	rm -f "$tmp"/pass-*.exr "$tmp"/t-*
done
;; esac

# Plots: the indirect layer's RMSE against time per scene, whole image and
# edge band.
case " $PARTS " in *" sweep "*) plot=1 ;; *) plot=0 ;; esac
if [ $plot = 1 ] && command -v gnuplot >/dev/null; then
	for name in cornell caustic room; do
		pl="" ple=""
		for mode in $modes; do
			awk -F'\t' -v s="$name" -v m="$mode" '$1 == s && $2 == m { print $4, $7, $9 }' "$out" >"$tmp/$mode.dat"
			pl="$pl${pl:+, }'$tmp/$mode.dat' using 1:2 with linespoints title '$mode'"
			ple="$ple${ple:+, }'$tmp/$mode.dat' using 1:3 with linespoints title '$mode'"
		done
		gnuplot <<EOF
set terminal png size 1000,420
set output '$res/gather-$name.png'
set multiplot layout 1,2 title '$name: indirect layer RMSE against time (core-seconds), averages of 1, 2, 4 ... pass pairs'
set logscale xy
set xlabel 'time (s)'
set ylabel 'RMSE (indirect)'
set key top right font ',8'
set title 'whole image'
plot $pl
set title 'edge band'
plot $ple
unset multiplot
EOF
	done
fi
log "wrote $res/gather.tsv, gather-caustic.tsv and gather-*.png (the parts run: $PARTS)"
