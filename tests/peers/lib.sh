# lib.sh — helpers for the peer comparisons (make check-peers, run.sh):
# scenes written in pbrt-v4's format, rendered by pbrt-v4 itself ($PM_PBRT)
# and by pm (pm-import, then pm's path tracer or its photon pipeline), and
# the two images compared by whole-image and block means. Sourced by
# tests/peers/pbrt_*.sh, each run in a fresh directory with $PM_TOP, $PM_BIN
# and $PM_PBRT set. pbrt-v4 is spectral: only grey scenes (r = g = b
# everywhere) are compared, where it and an RGB renderer agree exactly.
. "$PM_TOP/tests/lib.sh"
peer_blocks="$PM_BIN/../tests/tools/exrblocks"
peer_stat="$PM_BIN/../tests/tools/exrstat"
# Samples per pixel of each renderer: 256 leave about 1 % noise rms on 8 x 8
# blocks of 8 x 8 pixels of a lit grey room (measured: 0.4 % at 1024).
PEER_SPP=${PEER_SPP:-256}
PM_SPP=${PM_SPP:-256}

# peer_film NAME W H [SPP] : pbrt's image, sampler and integrator lines.
# The box filter of radius 0.5 with jittered samples averages each pixel's
# area, as pm's pixel-area samples do; the path integrator's depth is left
# unbounded in effect (pm has no depth cap; pbrt's Russian roulette ends
# paths without bias).
peer_film() {
	echo "Film \"rgb\" \"integer xresolution\" [ $2 ] \"integer yresolution\" [ $3 ] \"string filename\" \"$1.ref.exr\""
	echo 'PixelFilter "box" "float xradius" 0.5 "float yradius" 0.5'
	echo "Sampler \"independent\" \"integer pixelsamples\" ${4:-$PEER_SPP}"
	echo 'Integrator "path" "integer maxdepth" 1000'
}

# peer_render NAME : pbrt renders NAME.pbrt into NAME.ref.exr.
peer_render() {
	rm -f "$1.ref.exr"
	"$PM_PBRT" --nthreads "${PEER_THREADS:-2}" --quiet "$1.pbrt" >"$1.pbrt.log" 2>&1 ||
		echo "not ok - $1: pbrt failed: $(tail -n 3 "$1.pbrt.log" | tr '\n' ' ')"
}

# pm_import NAME : pm-import NAME.pbrt into NAME/scene.pms (notes in NAME.notes).
pm_import() {
	pm-import "$1.pbrt" -o "$1/scene.pms" 2>"$1.notes" ||
		echo "not ok - $1: pm-import failed: $(head -c 300 "$1.notes")"
}

# pm_path NAME [SPP] : pm-import, then pm's path tracer into NAME.pm.exr.
pm_path() {
	pm_import "$1" && pm-render -q -e path -p "${2:-$PM_SPP}" "$1/scene.pms" -o "$1.pm.exr"
}

# pm_photons NAME PHOTONS [EST [K [SPP]]] : pm-import, then pm-shoot |
# pm-build | pm-render with estimator EST (default compensated) into
# NAME.ph.exr.
pm_photons() {
	pm_import "$1" && pm-shoot -q -n "$2" "$1/scene.pms" | pm-build -q |
		pm-render -q -e "${3:-compensated}" -k "${4:-50}" -p "${5:-16}" "$1/scene.pms" - -o "$1.ph.exr"
}

# peer_pixel FILE X,Y and peer_window FILE X0,Y0,X1,Y1 : the channel mean.
peer_pixel() { "$peer_stat" --pixel "$2" "$1" | sed -n 's/^mean: //p'; }
peer_window() { "$peer_stat" --window "$2" "$1" | sed -n 's/^mean: //p'; }

# peer_compare LABEL PM.exr REF.exr MEAN RMS MAX [GRID] : pm's image against
# pbrt's: |mean ratio - 1| <= MEAN, and over a GRID x GRID grid of block
# means (default 8) the relative differences' rms <= RMS and largest <= MAX.
# Prints one ok / not ok line carrying the numbers (they are the report).
peer_compare() {
	if [ ! -f "$2" ] || [ ! -f "$3" ]; then
		echo "not ok - $1: missing image ($2 or $3)"; return
	fi
	"$peer_blocks" --grid "${7:-8}" "$2" "$3" >cmp.txt || {
		echo "not ok - $1: exrblocks failed"; return; }
	r=$(kv cmp.txt mean_ratio) a=$(kv cmp.txt block_rel_rms) m=$(kv cmp.txt block_rel_max)
	line="$1: pm/pbrt mean $r (pm $(kv cmp.txt mean_a), pbrt $(kv cmp.txt mean_b)), blocks rms $a, max $m at $(kv cmp.txt worst_block)"
	if awk -v r="$r" -v a="$a" -v m="$m" -v t="$4" -v ta="$5" -v tm="$6" \
		'BEGIN { d = r - 1; if (d < 0) d = -d; exit !(d <= t && a <= ta && m <= tm) }'; then
		echo "ok - $line"
	else
		echo "not ok - $line (want mean within $4, rms <= $5, max <= $6)"
	fi
}
