# passes.sh — what bench/consistent.sh and bench/ldpaths.sh share, sourced
# after they set top and B: the programs, the scenes at a given size, and
# the path-traced references (cached).
bin=$B/bin bb=$B/bench
cache=${BENCH_CACHE:-$B/bench-cache}
res=$top/bench/results
REF_PASSES=${REF_PASSES:-4} REF_SPP=${REF_SPP:-256}
for p in "$bin/pm-shoot" "$bin/pm-build" "$bin/pm-render" "$bin/pm-average" "$bin/pm-diff" "$bb/errsplit"; do
	[ -x "$p" ] || { echo "$0: '$p' missing: make bench-progs" >&2; exit 1; }
done
mkdir -p "$res" "$cache"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# scene NAME W H: writes NAME's scene at W x H (furnace and mirror from
# tests/scenes, the others from examples/ with their meshes) and prints its
# path.
scene() {
	d=$tmp/scene-$1-$2x$3
	mkdir -p "$d"
	case $1 in
	furnace|mirror) src=$top/tests/scenes/$1.pms ;;
	*) cp "$top/examples/$1"/* "$d"/; src=$top/examples/$1/$1.pms ;;
	esac
	sed "s/^\(camera .*\)size  *[0-9][0-9]*  *[0-9][0-9]*/\1size $2 $3/" "$src" >"$d/$1.pms"
	echo "$d/$1.pms"
}

# reference NAME SCENE: prints the path of SCENE's path-traced reference,
# REF_PASSES passes of REF_SPP samples, rendering it if it is not cached.
reference() {
	r=$cache/ref-$1-$(cksum <"$2" | cut -d' ' -f1)-$REF_PASSES-$REF_SPP.exr
	if [ ! -s "$r" ]; then
		echo "$0: $1 reference, $REF_PASSES x $REF_SPP spp path-traced" >&2
		for i in $(seq 1 "$REF_PASSES"); do
			"$bin/pm-render" -q -j 1 -e path -p "$REF_SPP" -s "1000$i" "$2" -o "$tmp/ref-$i.exr"
		done
		"$bin/pm-average" -q "$tmp"/ref-*.exr -o "$r.tmp.exr" && mv "$r.tmp.exr" "$r"
		rm -f "$tmp"/ref-*.exr
	fi
	echo "$r"
}
