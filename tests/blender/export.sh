# export.sh — make check-blender: Blender scenes built from bpy primitives
# here, saved as .blend, exported by tools/pm-blender.py and rendered by pm:
# the camera's framing in both aspects and sensor fits (a lamp's position
# and width in pixels), orientation (+x on the right, as Blender shows it),
# modifiers and transforms applied, and the lights in Cycles' units (the
# floor under a point and an area light reads what Cycles renders there:
# 0.3166 and 1.7313, measured with Cycles 3.4 and equal to the analytic
# rho E / pi for intensity P / 4 pi and radiance P / 4A).
. "$PM_TOP/tests/lib.sh"
stat="$PM_BIN/../tests/tools/exrstat"
px() { "$stat" --pixel "$2" "$1" | sed -n 's/^mean: //p'; }
win() { "$stat" --window "$2" "$1" | sed -n 's/^mean: //p'; }

# build NAME PYTHON: runs the lines after a common prelude, saves NAME.blend
build() {
	cat >"$1.py" <<PY
import bpy, math, sys
for o in list(bpy.data.objects):
    bpy.data.objects.remove(o)
sc = bpy.context.scene
sc.world = None
def mat(name, kind, color, strength=1.0):
    m = bpy.data.materials.new(name); m.use_nodes = True
    nt = m.node_tree; nt.nodes.remove(nt.nodes["Principled BSDF"])
    n = nt.nodes.new(kind); n.inputs["Color"].default_value = color + (1,)
    if kind == "ShaderNodeEmission": n.inputs["Strength"].default_value = strength
    nt.links.new(n.outputs[0], nt.nodes["Material Output"].inputs["Surface"])
    return m
def cam(loc, rot, w, h, lens, fit="AUTO"):
    bpy.ops.object.camera_add(location=loc, rotation=rot)
    c = bpy.context.object; c.data.lens = lens; c.data.sensor_width = 36; c.data.sensor_fit = fit
    sc.camera = c
    sc.render.resolution_x = w; sc.render.resolution_y = h; sc.render.resolution_percentage = 100
$2
bpy.ops.wm.save_as_mainfile(filepath="$PWD/$1.blend")
PY
	blender -b --factory-startup --python "$1.py" >"$1.log" 2>&1
	check "$1.blend built" test -s "$1.blend"
	blender -b "$1.blend" --python "$PM_TOP/tools/pm-blender.py" -- "$1" >"$1.export.log" 2>&1
	check "$1 exported ($(grep -i 'error\|pm-blender' "$1.export.log" | head -c 200))" test -s "$1/scene.pms"
}
# The lamp: a 1 x 1 plane at x = 1 in the plane y = 0, facing -y (the camera
# at y = -5 looking along +y, up +z), emission 3.
lamp='bpy.ops.mesh.primitive_plane_add(size=1, location=(1, 0, 0), rotation=(math.pi / 2, 0, 0))
bpy.context.object.data.materials.append(mat("lamp", "ShaderNodeEmission", (1.0, 1.0, 1.0), 3.0))'
lens=$(awk 'BEGIN { print 18 / (sin(20 * 3.14159265358979 / 180) / cos(20 * 3.14159265358979 / 180)) }')
# landscape 48 x 32, AUTO fit: horizontal fov 40, 13.19 px per unit, lamp
# columns 30.6-43.8
build wide "cam((0, -5, 0), (math.pi / 2, 0, 0), 48, 32, $lens)
$lamp"
pm-render -q -e path -p 64 wide/scene.pms -o wide.exr
num_near "landscape, sensor fit auto: lamp at +x on the right, reads 3" "$(px wide.exr 37,16)" 3 1e-4
num_near "... nothing on the left" "$(px wide.exr 10,16)" 0 0
num_near "... the lamp is 13.19 px wide (fov 40 horizontal)" \
	"$(awk -v m="$(win wide.exr 0,16,48,17)" 'BEGIN { print m * 48 / 3 }')" 13.19 0.2
# portrait 32 x 48, AUTO fit: the fov spans the larger (vertical) axis: 24 px
# for tan 20 x 5 units, 13.19 px per unit; the lamp from column 22.6 to past
# the right edge, 9.40 px of the row
build tall "cam((0, -5, 0), (math.pi / 2, 0, 0), 32, 48, $lens)
$lamp"
pm-render -q -e path -p 64 tall/scene.pms -o tall.exr
num_near "portrait, sensor fit auto: fov 40 vertical" "$(sed -n 's/^camera .* fov \([0-9.e+-]*\) .*/\1/p' tall/scene.pms)" 40 1e-4
num_near "... the lamp covers 9.40 px of the row (13.19 px per unit)" \
	"$(awk -v m="$(win tall.exr 0,24,32,25)" 'BEGIN { print m * 32 / 3 }')" 9.40 0.15
# landscape with the sensor fit vertical: fov 40 vertical
build vfit "cam((0, -5, 0), (math.pi / 2, 0, 0), 48, 32, 24 / 2 / math.tan(math.radians(20)) , 'VERTICAL')
bpy.context.object.data.sensor_height = 24
$lamp"
num_near "landscape, sensor fit vertical: fov 40 vertical" "$(sed -n 's/^camera .* fov \([0-9.e+-]*\) .*/\1/p' vfit/scene.pms)" 40 1e-4

# Lights over a floor of albedo 0.5, the camera between: a point light of
# 100 W at height 2, a 2 x 2 area light of 100 W at height 1.
floor='bpy.ops.mesh.primitive_plane_add(size=20)
bpy.context.object.data.materials.append(mat("floor", "ShaderNodeBsdfDiffuse", (0.5, 0.5, 0.5)))
cam((0, 0, 0.5), (0, 0, 0), 8, 8, 18 / math.tan(math.radians(2.5)))'
build point "$floor
bpy.ops.object.light_add(type='POINT', location=(0, 0, 2)); bpy.context.object.data.energy = 100
bpy.context.object.data.shadow_soft_size = 0"
pm-render -q -e path -p 64 point/scene.pms -o point.exr
num_near "point light 100 W at 2: the floor reads 0.3166 (Cycles 0.31659)" "$(win point.exr 0,0,8,8)" 0.3166 0.002
build area "$floor
bpy.ops.object.light_add(type='AREA', location=(0, 0, 1)); bpy.context.object.data.energy = 100
bpy.context.object.data.size = 2"
pm-render -q -e path -p 256 area/scene.pms -o area.exr
num_near "area light 2 x 2, 100 W at 1: the floor reads 1.7313 (Cycles)" "$(win area.exr 0,0,8,8)" 1.7313 0.02

# Modifiers and transforms: a cube (8 vertices, 6 faces) under a level-1
# subdivision modifier has 26 vertices and 24 faces; scaled by 2 and moved
# to x = 3 its vertices span x 1..5.
build mods "$lamp
cam((0, -5, 0), (math.pi / 2, 0, 0), 16, 16, 50)
bpy.ops.mesh.primitive_cube_add(location=(3, 0, 0)); c = bpy.context.object; c.scale = (2, 2, 2)
c.modifiers.new('s', 'SUBSURF').levels = 1; c.modifiers['s'].render_levels = 1"
n=0 ok=0
for f in mods/*.ply; do
	v=$(sed -n 's/^element vertex //p' "$f" | head -1) fc=$(sed -n 's/^element face //p' "$f" | head -1)
	[ "$v $fc" = "26 24" ] && ok=1
done
check "a subdivided cube: 26 vertices, 24 faces" test $ok -eq 1
