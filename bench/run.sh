#!/bin/sh
# run.sh — the benchmark behind `make bench` and `make bench-quick`: speed
# against error for the example scenes and a furnace scene, each hot part
# against its anchor, memory, threads and the paper's workload. Writes
# bench/results/ (TSVs and gnuplot PNGs) and BENCHMARKS.md.
#
# Usage: bench/run.sh quick|full [BUILD_DIR]
#   BUILD_DIR holds bin/ and bench/ (default build). Environment:
#   BENCH_CACHE  where path-traced references and run images go
#                (default BUILD_DIR/bench-cache; references are reused)
#   BENCH_JOBS   pass pairs run at once, each on one thread (default nproc)
#
# Times: every pass pair runs single-threaded (pm-shoot -j 1 | pm-build -j 1 |
# pm-render -j 1), BENCH_JOBS of them at once, and its wall time is
# recorded; a series' time after N passes is the sum over its first N passes,
# i.e. core-seconds (wall time on one core; divide by the cores for the wall
# time of a parallel run).
set -eu
mode=${1:-quick}
top=$(cd "$(dirname "$0")/.." && pwd)
B=${2:-build}
case $B in /*) ;; *) B=$top/$B ;; esac
bin=$B/bin
bb=$B/bench
cache=${BENCH_CACHE:-$B/bench-cache}
jobs=${BENCH_JOBS:-$(nproc)}
res=$top/bench/results
doc=$top/BENCHMARKS.md
case $mode in quick|full) ;; *) echo "usage: bench/run.sh quick|full [BUILD_DIR]" >&2; exit 2 ;; esac
for p in pm-shoot pm-build pm-render pm-average; do
	[ -x "$bin/$p" ] || { echo "bench: '$bin/$p' missing: make $B first" >&2; exit 1; }
done
for p in knn hot errsplit peakrss; do
	[ -x "$bb/$p" ] || { echo "bench: '$bb/$p' missing: make bench-progs" >&2; exit 1; }
done
command -v gnuplot >/dev/null || { echo "bench: gnuplot missing: sh mk/deps.sh bench" >&2; exit 1; }
mkdir -p "$cache" "$res"
# only this script's own results: bench/*.sh besides it write theirs here too
rm -f "$res"/err-*.png "$res"/edge-*.png "$res"/split-*.png "$res"/runs.tsv "$res"/micro.tsv "$res"/levers.tsv
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
log() { echo "bench: $*" >&2; }
now() { date +%s.%N; }
# fsub A B: A - B for decimal strings
fsub() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", a - b }'; }
# kv FILE KEY: the value of a "key<TAB>value" line
kv() { awk -F'\t' -v k="$2" '$1 == k { print $2; exit }' "$1"; }
micro=$res/micro.tsv
: >"$micro"
# add PREFIX FILE: copy FILE's key/value lines into micro.tsv, keys prefixed
add() { awk -F'\t' -v p="$1" 'NF == 2 { print p "." $1 "\t" $2 }' "$2" >>"$micro"; }

if [ "$mode" = quick ]; then
	KNN_Q=160000 RUNS=3 HOT_N=200000 SHOOT_N=500000
	SWEEP_SCENES="cornell caustic room furnace" NMAX=8 PHOTONS="100000" KS=50 KS_AT=
	REF_PASSES=16 REF_SPP=256 REF_PASSES_room=64 SIZE_cornell="128 128" SIZE_caustic="128 128" SIZE_room="128 96"
	SIZE_furnace="64 48"
else
	KNN_Q=1000000 RUNS=5 HOT_N=1000000 SHOOT_N=1000000
	SWEEP_SCENES="cornell caustic room furnace" NMAX=64 PHOTONS="100000 400000" KS="25 100" KS_AT=200000
	REF_PASSES=32 REF_SPP=1024 REF_PASSES_room=128 SIZE_cornell="256 256" SIZE_caustic="256 256" SIZE_room="256 192"
	SIZE_furnace="128 96"
fi
SPP=4 BASE_K=50
# The speed-against-error sweep's view passes: pm-render's defaults, the
# settings with the best measured efficiency (BENCHMARKS.md, "Levers"); the
# path tracer, the competitor, with its own best (one shadow ray per vertex;
# 64 camera samples per pass pair).
VIEW_ARGS="-p 16 -l 4" PATH_ARGS="-p 64 -l 1"

# ---- the scenes, copied with their meshes so the camera size can change --
mkscene() { # NAME SRC_DIR SRC_FILE W H
	d=$cache/scenes/$1-$4x$5
	mkdir -p "$d"
	cp "$2"/* "$d"/ 2>/dev/null || true
	sed "s/^\(camera .*\)size  *[0-9][0-9]*  *[0-9][0-9]*/\1size $4 $5/" "$2/$3" >"$d/$1.pms"
	echo "$d/$1.pms"
}
mkdir -p "$tmp/furnace"
# rho = 0.5, Le = 1 everywhere: the exact radiance is 1 / (1 - 0.5) = 2.
cat >"$tmp/furnace/furnace.pms" <<'SCENE'
camera eye 0 1 2.6  look 0 1 -3  up 0 1 0  fov 50  size 64 48
material f diffuse albedo 0.5 0.5 0.5 emit 1 1 1
box f -2 0 -3  2 2.5 3 inward
box f -0.6 0 -1.6  0.6 0.8 -0.8
box f 1.2 0 -2.6  1.9 1.6 -1.9
SCENE
scene_of() { # NAME -> path of the sweep copy
	sn=$1
	eval "set -- \$SIZE_$sn"
	case $sn in
	furnace) mkscene furnace "$tmp/furnace" furnace.pms "$1" "$2" ;;
	*) mkscene "$sn" "$top/examples/$sn" "$sn.pms" "$1" "$2" ;;
	esac
}

# ---- machine -----------------------------------------------------------
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
mem=$(awk '/^MemTotal/ { printf "%.1f GB", $2 / 1048576 }' /proc/meminfo)
printf 'machine.load_start\t%s\n' "$(cut -d' ' -f1-3 /proc/loadavg)" >>"$micro"
printf 'machine.nproc\t%s\nmachine.cpu\t%s\nmachine.memory\t%s\nmachine.date\t%s\nmachine.mode\t%s\n' \
	"$(nproc)" "$cpu" "$mem" "$(date -u '+%Y-%m-%d %H:%M UTC')" "$mode" >>"$micro"
t_start=$(now)

# ---- the kd-tree against nanoflann --------------------------------------
log "k-nearest: ours against nanoflann (1M photons, k = 50)"
"$bb/knn" -n 1000000 -q "$KNN_Q" -k 50 -r "$RUNS" >"$tmp/knn.tsv" 2>/dev/null
add knn "$tmp/knn.tsv"

# ---- rays against Embree, estimates, build --------------------------------
for name in cornell room; do
	log "hot parts on $name ($HOT_N photons)"
	"$bb/hot" -n "$HOT_N" -k 50 -r "$RUNS" "$top/examples/$name/$name.pms" >"$tmp/hot-$name.tsv" 2>/dev/null
	add "hot.$name" "$tmp/hot-$name.tsv"
done

# ---- memory --------------------------------------------------------------
log "memory: bytes per photon, pm-render peak RSS"
cs=$top/examples/cornell/cornell.pms
for n in 250000 1000000; do
	"$bin/pm-shoot" -q -n $n -s 1 "$cs" -o "$tmp/m$n.ph"
	"$bin/pm-build" -q "$tmp/m$n.ph" -o "$tmp/m$n.map"
	"$bb/peakrss" "$bin/pm-render" -p 1 "$cs" "$tmp/m$n.map" -o "$tmp/m$n.exr" >"$tmp/rss$n.tsv" 2>/dev/null
done
fsize=$(wc -c <"$tmp/m1000000.map")
cnt=$("$bin/pm-dump" "$tmp/m1000000.map" --stats 2>/dev/null | awk '/^photons:/ { print $2; exit }')
[ -n "$cnt" ] || cnt=1000000
r1=$(kv "$tmp/rss250000.tsv" peak_rss_kb) r2=$(kv "$tmp/rss1000000.tsv" peak_rss_kb)
{
	printf 'mem.file_bytes_per_photon\t%s\n' "$(awk -v s="$fsize" -v n="$cnt" 'BEGIN { printf "%.2f", s / n }')"
	printf 'mem.record_bytes\t20\n'
	printf 'mem.render_peak_rss_MB_1M\t%s\n' "$(awk -v r="$r2" 'BEGIN { printf "%.1f", r / 1024 }')"
	printf 'mem.render_peak_rss_MB_250k\t%s\n' "$(awk -v r="$r1" 'BEGIN { printf "%.1f", r / 1024 }')"
	printf 'mem.render_MB_per_M_photons\t%s\n' "$(awk -v a="$r1" -v b="$r2" 'BEGIN { printf "%.1f", (b - a) / 1024 / 0.75 }')"
} >>"$micro"
rm -f "$tmp"/m*.ph "$tmp"/m*.exr

# ---- threads -------------------------------------------------------------
log "threads: 1 -> $(nproc)"
med() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
timeit() { # RUNS CMD...: median wall seconds
	n=$1; shift
	i=0
	while [ $i -lt "$n" ]; do
		t0=$(now); "$@" >/dev/null 2>&1; t1=$(now)
		fsub "$t1" "$t0"; echo
		i=$((i + 1))
	done | med
}
nt=$(nproc)
ts1=$(timeit "$RUNS" "$bin/pm-shoot" -q -j 1 -n "$SHOOT_N" -s 2 "$cs" -o "$tmp/t.ph")
tsn=$(timeit "$RUNS" "$bin/pm-shoot" -q -j "$nt" -n "$SHOOT_N" -s 2 "$cs" -o "$tmp/t.ph")
"$bin/pm-shoot" -q -n 200000 -s 2 "$cs" | "$bin/pm-build" -q -o "$tmp/t.map"
tr1=$(timeit "$RUNS" "$bin/pm-render" -j 1 "$cs" "$tmp/t.map" -o "$tmp/t.exr")
trn=$(timeit "$RUNS" "$bin/pm-render" -j "$nt" "$cs" "$tmp/t.map" -o "$tmp/t.exr")
{
	printf 'threads.n\t%s\n' "$nt"
	printf 'threads.shoot_s_1\t%s\nthreads.shoot_s_n\t%s\n' "$ts1" "$tsn"
	printf 'threads.shoot_speedup\t%s\n' "$(awk -v a="$ts1" -v b="$tsn" 'BEGIN { printf "%.2f", a / b }')"
	printf 'threads.render_s_1\t%s\nthreads.render_s_n\t%s\n' "$tr1" "$trn"
	printf 'threads.render_speedup\t%s\n' "$(awk -v a="$tr1" -v b="$trn" 'BEGIN { printf "%.2f", a / b }')"
} >>"$micro"
rm -f "$tmp"/m*.map "$tmp"/t*

# ---- the paper's workload -------------------------------------------------
# 50 pass pairs of 1M photons, k = 50, 512 x 512, the room. Full: all 50,
# BENCH_JOBS at a time. Quick: BENCH_JOBS pass pairs, scaled to 50.
log "the paper's workload (room, 512 x 512, 1M photons, k = 50)"
rs=$(mkscene room "$top/examples/room" room.pms 512 512)
pw=$tmp/paper
mkdir -p "$pw"
if [ "$mode" = quick ]; then np=$jobs; else np=50; fi
t0=$(now)
seq 1 "$np" | xargs -P "$jobs" -I{} sh -c '
	a=$(date +%s.%N)
	"$1/pm-shoot" -q -j 1 -n 1000000 -s {} "$2" -o "$3/{}.ph"
	b=$(date +%s.%N)
	"$1/pm-build" -q -j 1 "$3/{}.ph" -o "$3/{}.map"
	c=$(date +%s.%N)
	"$1/pm-render" -j 1 -k 50 -p '"$SPP"' -s {} "$2" "$3/{}.map" -o "$3/pass-{}.exr" 2>/dev/null
	d=$(date +%s.%N)
	rm -f "$3/{}.ph" "$3/{}.map"
	echo "$a $b $c $d" >"$3/{}.t"' sh "$bin" "$rs" "$pw"
t1=$(now)
"$bin/pm-average" "$pw"/pass-*.exr -o "$pw/avg.exr"
t2=$(now)
# The estimates' share: hot.c on this scene and photon count gives the
# compensated estimates at first hits per camera ray and their cost; camera
# paths that reflect off the strong-glossy floor make more, so this is a
# lower bound of the estimates' time.
"$bb/hot" -n 1000000 -k 50 -r 1 "$rs" >"$tmp/hot-paper.tsv" 2>/dev/null
frac=$(awk -F'\t' '$1 == "pixels" { p = $2 } $1 == "estimates" { e = $2 } END { print e / p }' "$tmp/hot-paper.tsv")
us=$(kv "$tmp/hot-paper.tsv" us_compensated)
printf 'paper.us_per_estimate\t%s\npaper.first_hit_estimates_per_ray\t%s\n' "$us" "$frac" >>"$micro"
cat "$pw"/*.t | awk -v np="$np" -v frac="$frac" -v us="$us" -v wall="$(fsub "$t1" "$t0")" \
	-v avg="$(fsub "$t2" "$t1")" -v jobs="$jobs" -v mode="$mode" -v spp="$SPP" '
	{ sh += $2 - $1; bu += $3 - $2; re += $4 - $3 }
	END {
		s = 50 / np      # scale to 50 pass pairs (1 in full mode)
		est = 50 * 512 * 512 * spp * frac * us * 1e-6
		printf "paper.passes_run\t%d\n", np
		printf "paper.extrapolated\t%s\n", np < 50 ? "yes" : "no"
		printf "paper.shoot_core_s\t%.1f\n", sh * s
		printf "paper.build_core_s\t%.1f\n", bu * s
		printf "paper.render_core_s\t%.1f\n", re * s
		printf "paper.estimate_core_s\t%.1f\n", est
		printf "paper.trace_core_s\t%.1f\n", re * s - est
		printf "paper.average_s\t%.1f\n", avg * (np < 50 ? 50 / np : 1)
		printf "paper.total_wall_s\t%.1f\n", wall * s + avg * (np < 50 ? 50 / np : 1)
	}' >>"$micro"
rm -rf "$pw"

# ---- speed against error ---------------------------------------------------
runs=$res/runs.tsv
printf 'scene\test\tphotons\tk\tpasses\ttime_s\trmse\trelmse\tmse\tpassvar\trelpassvar\trefvar\trelrefvar\tedge_rmse\tedge_relmse\tedge_mse\tedge_passvar\tedge_refvar\tpixels\tedge_pixels\tedge_relrefvar\tedge_relpassvar\trest_relmse\trest_relpassvar\trest_relrefvar\n' >"$runs"

# reference NAME SCENE: prints the reference image path (made once, cached by
# the scene's bytes, its meshes' and the reference settings)
# The room's reference takes more passes: the path tracer's noise there is
# about 10 times the Cornell box's at equal time.
reference() {
	eval "np=\${REF_PASSES_$1:-$REF_PASSES}"
	key=$(cat "$(dirname "$2")"/* | cksum | awk -v s="$np-$REF_SPP" '{ print $1 "-" s }')
	r=$cache/ref/$1-$key.exr
	if [ ! -s "$r" ]; then
		log "reference for $1: $np path-traced passes of $REF_SPP spp (cached in $cache/ref)"
		mkdir -p "$cache/ref" "$tmp/ref"
		seq 1 "$np" | xargs -P "$jobs" -I{} "$bin/pm-render" -j 1 -e path -p "$REF_SPP" \
			-s "1000{}" "$2" -o "$tmp/ref/{}.exr" 2>/dev/null
		"$bin/pm-average" "$tmp/ref"/*.exr -o "$r.tmp.exr"
		mv "$r.tmp.exr" "$r"
		rm -rf "$tmp/ref"
	fi
	echo "$r"
}

# series NAME SCENE EST PHOTONS K REFARGS MASK: NMAX pass pairs, then the
# errors of the averages of the first 1, 2, 4, ... NMAX
series() {
	d=$tmp/s
	rm -rf "$d"
	mkdir -p "$d"
	log "$1: $3, $4 photons, k = $5, $NMAX pass pairs"
	seq 1 "$NMAX" | xargs -P "$jobs" -I{} sh -c '
		a=$(date +%s.%N)
		if [ "$5" = path ]; then
			"$1/pm-render" -j 1 -e path $8 -s {} "$2" -o "$3/pass-{}.exr" 2>/dev/null
		else
			"$1/pm-shoot" -q -j 1 -n "$4" -s {} "$2" | "$1/pm-build" -q -j 1 |
				"$1/pm-render" -j 1 -e "$5" -k "$6" $7 -s {} "$2" - -o "$3/pass-{}.exr" 2>/dev/null
		fi
		b=$(date +%s.%N)
		echo "$a $b" | awk "{ print \$2 - \$1 }" >"$3/{}.t"' sh "$bin" "$2" "$d" "$4" "$3" "$5" "$VIEW_ARGS" "$PATH_ARGS"
	n=1
	while [ $n -le "$NMAX" ]; do
		files=$(seq 1 $n | sed "s|.*|$d/pass-&.exr|")
		a=$(now)
		# shellcheck disable=SC2086
		"$bin/pm-average" $files -o "$d/avg.exr"
		b=$(now)
		t=$(seq 1 $n | sed "s|.*|$d/&.t|" | xargs cat | awk -v avg="$(fsub "$b" "$a")" '{ s += $1 } END { printf "%.3f", s + avg }')
		# shellcheck disable=SC2086
		all=$("$bb/errsplit" $6 "$d/avg.exr" $7)
		# shellcheck disable=SC2086
		edge=$("$bb/errsplit" -m "$8" -c edge $6 "$d/avg.exr" $7)
		# shellcheck disable=SC2086
		rest=$("$bb/errsplit" -m "$8" -c '!edge' $6 "$d/avg.exr" $7)
		# errsplit: pixels mse rmse relmse passvar relpassvar refvar relrefvar
		printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$1" "$3" "$4" "$5" "$n" "$t" "$all" "$edge" "$rest" |
			awk -F'\t' -v OFS='\t' '{ print $1,$2,$3,$4,$5,$6,$9,$10,$8,$11,$12,$13,$14,$17,$18,$16,$19,$21,$7,$15,$22,$20,$26,$28,$30 }' >>"$runs"
		n=$((n * 2))
	done
	rm -rf "$d"
}

for name in $SWEEP_SCENES; do
	sc=$(scene_of "$name")
	if [ "$name" = furnace ]; then refargs="-v 2" refimg=""; else refargs="" refimg=$(reference "$name" "$sc"); fi
	# the edge band: pixels whose compensated estimate (k = 50, the first
	# photon count) meets another surface's plane, from one pass
	set -- $PHOTONS
	mask=$cache/mask-$name.exr
	"$bin/pm-shoot" -q -n "$1" -s 999 "$sc" | "$bin/pm-build" -q |
		"$bin/pm-render" -k $BASE_K $VIEW_ARGS -s 999 "$sc" - -o "$mask" 2>/dev/null
	series "$name" "$sc" path 0 0 "$refargs" "$refimg" "$mask"
	for P in $PHOTONS; do
		for est in classical compensated; do
			series "$name" "$sc" "$est" "$P" "$BASE_K" "$refargs" "$refimg" "$mask"
		done
	done
	if [ -n "$KS_AT" ]; then
		for k in $KS; do
			for est in classical compensated; do
				series "$name" "$sc" "$est" "$KS_AT" "$k" "$refargs" "$refimg" "$mask"
			done
		done
	fi
done
printf 'sweep.view_args\t%s\nsweep.path_args\t%s\n' "$VIEW_ARGS" "$PATH_ARGS" >>"$micro"

# ---- levers: one view-pass setting at a time, side by side -----------------
# lever SCENE LABEL PHOTONS ARGS: LEVER_N pass pairs (PHOTONS = 0: the path
# tracer), their core-seconds, relMSE less the reference's, efficiency.
levers=$res/levers.tsv
printf 'scene\tlabel\tphotons\targs\tpasses\ttime_s\trelmse\tefficiency\n' >"$levers"
LEVER_N=8
lever() {
	d=$tmp/lv
	rm -rf "$d"
	mkdir -p "$d"
	sc=$(scene_of "$1")
	ref=$(reference "$1" "$sc")
	log "lever: $1, $2 ($4)"
	seq 1 "$LEVER_N" | xargs -P "$jobs" -I{} sh -c '
		a=$(date +%s.%N)
		if [ "$4" = 0 ]; then
			"$1/pm-render" -j 1 -e path $5 -s {} "$2" -o "$3/pass-{}.exr" 2>/dev/null
		else
			"$1/pm-shoot" -q -j 1 -n "$4" -s {} "$2" | "$1/pm-build" -q -j 1 |
				"$1/pm-render" -j 1 -k 50 $5 -s {} "$2" - -o "$3/pass-{}.exr" 2>/dev/null
		fi
		b=$(date +%s.%N)
		echo "$a $b" | awk "{ print \$2 - \$1 }" >"$3/{}.t"' sh "$bin" "$sc" "$d" "$3" "$4"
	"$bin/pm-average" "$d"/pass-*.exr -o "$d/avg.exr"
	t=$(cat "$d"/*.t | awk '{ s += $1 } END { printf "%.3f", s }')
	"$bb/errsplit" "$d/avg.exr" "$ref" | awk -F'\t' -v OFS='\t' -v sc="$1" -v l="$2" -v p="$3" -v a="$4" \
		-v n="$LEVER_N" -v t="$t" '{ r = $4 - $8; if (r < 1e-9) r = 1e-9; print sc, l, p, a, n, t, r, 1 / (r * t) }' >>"$levers"
	rm -rf "$d"
}
# ---- speckles: the room's 50-pair average against its reference ------------
# Pixels more than 5 standard errors (both averages' stderr) from the
# reference, in the edge band and away from it: speckles show as isolated
# pixels away from edges; a bias beyond the noise as runs along the edges.
log "speckles: 50 pass pairs of the room (200000 photons)"
sc=$(scene_of room)
ref=$(reference room "$sc")
d=$tmp/sp
mkdir -p "$d"
seq 1 50 | xargs -P "$jobs" -I{} sh -c '"$1/pm-shoot" -q -j 1 -n 200000 -P {}/50 "$2" |
	"$1/pm-build" -q -j 1 | "$1/pm-render" -q -j 1 -P {}/50 "$2" - -o "$3/p{}.exr"' sh "$bin" "$sc" "$d"
"$bin/pm-average" -q "$d"/p*.exr -o "$d/avg.exr"
{
	printf 'speckle.pixels\t%s\n' "$(awk -v s="$SIZE_room" 'BEGIN { split(s, a, " "); print a[1] * a[2] }')"
	printf 'speckle.over5_edge\t%s\n' "$("$bb/errsplit" -s 5 -m "$d/avg.exr" -c edge "$d/avg.exr" "$ref")"
	printf 'speckle.over5_rest\t%s\n' "$("$bb/errsplit" -s 5 -m "$d/avg.exr" -c '!edge' "$d/avg.exr" "$ref")"
	printf 'speckle.edge_fraction\t%s\n' "$("$bb/errsplit" -z edge "$d/avg.exr")"
} >>"$micro"
rm -rf "$d"

lever cornell "path tracer, 1 shadow ray per vertex" 0 "-p 64 -l 1"
lever cornell "path tracer, 4 shadow rays at the first vertex" 0 "-p 64 -l 4"
lever cornell "pm 0.13's view pass: -p 4, 1 shadow ray, an estimate per sample" 100000 "-p 4 -l 1 --estimates sample"
lever cornell "... the estimate once per pixel" 100000 "-p 4 -l 1 --estimates pixel"
lever cornell "... and 4 shadow rays per sample" 100000 "-p 4 -l 4"
lever cornell "... and 16 samples per pixel (the default)" 100000 "-p 16 -l 4"
lever cornell "32 samples, 1 shadow ray" 100000 "-p 32 -l 1"
lever cornell "the default, k = 100 with twice the photons" 200000 "-p 16 -l 4 -k 100"
lever room "path tracer" 0 "-p 64 -l 1"
lever room "the default (-p 16 -l 4)" 100000 "-p 16 -l 4"
lever room "-p 4 -l 4" 100000 "-p 4 -l 4"
lever room "-p 64 -l 4" 100000 "-p 64 -l 4"
# ---- the optional modes' own benchmarks (full mode only: tens of minutes) --
# Each writes its TSVs and plots to bench/results; their prose lives in
# bench/sections/ (appended to BENCHMARKS.md by report.sh).
if [ "$mode" = full ]; then
	for s in consistent ldpaths density gather guide looks; do
		log "bench/$s.sh"
		BENCH_CACHE=$cache sh "$top/bench/$s.sh" "$B" >&2 || log "bench/$s.sh failed"
	done
fi
t_end=$(now)
printf 'machine.load_end\t%s\n' "$(cut -d' ' -f1-3 /proc/loadavg)" >>"$micro"
printf 'machine.bench_wall_s\t%s\n' "$(fsub "$t_end" "$t_start")" >>"$micro"

sh "$top/bench/report.sh" "$res" "$doc" "$mode"
log "wrote $doc and $res/"
