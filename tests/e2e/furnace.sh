# furnace.sh — closed rooms whose every surface has albedo rho and emits Le:
# the exact radiance is Le / (1 - rho) everywhere (a geometric series of
# bounces). The path tracer must match it everywhere; the photon estimates
# (direct + estimate) must match it away from edges.
. "$PM_TOP/tests/lib.sh"

# rho = 0.5, Le = 1: exact radiance 2. A box room with a table in it, the
# camera inside looking at the far wall (its centre is flat wall).
cp "$PM_TOP/tests/scenes/furnace.pms" furnace.pms
dump=$PM_BIN/../tests/tools/exrstat

pm-render -e path -p 256 -s 3 furnace.pms -o path.exr 2>err.txt
check "furnace path renders" test -s path.exr
pm-diff path.exr path.exr >/dev/null 2>&1
# Mean over the whole image, and the worst pixel (noise at 256 spp is small).
"$dump" path.exr >path.txt
num_near "furnace path mean = 2" "$(kv path.txt mean)" 2 0.02
num_near "furnace path min pixel" "$(kv path.txt min)" 2 0.25
num_near "furnace path max pixel" "$(kv path.txt max)" 2 0.25

for est in classical compensated; do
	pm-shoot -n 200000 -s 5 furnace.pms | pm-build | pm-render -e $est -p 16 -s 5 furnace.pms - -o $est.exr
	# The centre window of the image sees only the flat far wall.
	"$dump" --window 12,9,28,21 $est.exr >$est.txt
	num_near "furnace $est centre mean = 2" "$(kv $est.txt mean)" 2 0.06
done
