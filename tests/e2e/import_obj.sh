# import_obj.sh — pm-import on an OBJ with its MTL written here: objects,
# groups and negative indices, Kd/Ks/Ns/Ke/Ni/d/illum/map_Kd by the rules
# of the README, the default framing of the bounding sphere, --camera in
# pm's own conventions (+x on the right seen from +z) and --size.
. "$PM_TOP/tests/lib.sh"
stat="$PM_BIN/../tests/tools/exrstat"
px() { "$stat" --pixel "$2" "$1" | sed -n 's/^mean: //p'; }

cat >m.mtl <<'EOF'
newmtl lamp
Kd 0 0 0
Ke 3 3 3
newmtl matte
Kd 0.6 0.5 0.4
map_Kd wood.png
newmtl shiny
Kd 0.5 0.5 0.5
Ks 0.7 0.7 0.7
Ns 50
newmtl glass
Kd 1 1 1
Ni 1.45
d 0.2
newmtl chrome
Kd 0 0 0
Ks 0.9 0.9 0.9
illum 3
EOF
# The lamp: x 0.5..1.5, y -0.5..0.5 at z = 0, counter-clockwise from +z.
cat >s.obj <<'EOF'
mtllib m.mtl
o lamp
v 0.5 -0.5 0
v 1.5 -0.5 0
v 1.5 0.5 0
v 0.5 0.5 0
usemtl lamp
f -4 -3 -2 -1
g rest
v -1 -1 -1
v 1 -1 -1
v 1 -1 -2
usemtl matte
f 5 6 7
usemtl shiny
f 5/1 6/1 7/1
usemtl glass
f 5//1 6//1 7//1
usemtl chrome
f -3/1/1 -2/1/1 -1/1/1
EOF
pm-import s.obj -o def/scene.pms 2>notes.txt
check "imports" test -s def/scene.pms
# Bounding box x -1..1.5, y -1..0.5, z -2..0: centre (0.25, -0.25, -1),
# radius sqrt(1.25^2 + 0.75^2 + 1) / ... = half the diagonal = 1.7678;
# fov 40 on the shorter axis: distance r / sin 20 = 5.1687.
eye=$(sed -n 's/^camera eye \([^ ]*\) \([^ ]*\) \([^ ]*\) .*/\1 \2 \3/p' def/scene.pms)
num_near "default framing: eye x at the centre" "$(echo $eye | cut -d' ' -f1)" 0.25 1e-6
num_near "default framing: eye z = centre + r / sin(20)" "$(echo $eye | cut -d' ' -f3)" \
	"$(awk 'BEGIN { r = sqrt(2.5^2 + 1.5^2 + 2^2) / 2; print -1 + r / sin(20 * 3.14159265358979 / 180) }')" 1e-4
check "default size 640 x 480, fov 40" grep -q 'fov 40  size 640 480$' def/scene.pms
check "Ke: an emitting material" grep -q 'diffuse albedo 0 0 0 emit 3 3 3$' def/scene.pms
check "Kd only: diffuse" grep -q 'diffuse albedo 0.6 0.5 0.4$' def/scene.pms
check "Kd + Ks > 1: glossy scaled to 1/1.2, exponent Ns" \
	grep -q 'glossy kd 0.416666667 0.416666667 0.416666667 ks 0.583333333 0.583333333 0.583333333 exponent 50$' def/scene.pms
check "d < 1: glass of ior Ni" grep -q 'glass ior 1.45 tint 1 1 1$' def/scene.pms
check "illum 3 without Kd: a mirror of Ks" grep -q 'mirror reflect 0.9 0.9 0.9$' def/scene.pms
check "map_Kd: noted with its material's line" grep -q "^pm-import: m.mtl:4: material 'matte' (mtl): texture 'wood.png' not mapped" notes.txt
check "d: noted with its material's line" grep -q "^pm-import: m.mtl:11: material 'glass' (mtl): transparency" notes.txt

# --camera in pm's conventions, --size: 48 x 32, vertical fov 40, the lamp
# at +x on the right (columns 28.4-37.2).
pm-import -q s.obj --camera 'eye 0 0 5 look 0 0 0 up 0 1 0 fov 40' --size 48 32 -o cam/scene.pms
pm-render -q -e path -p 4 cam/scene.pms -o cam.exr
num_near "--camera: the lamp at +x on the right, reads Ke" "$(px cam.exr 32,16)" 3 1e-4
num_near "--camera: nothing on the left" "$(px cam.exr 15,16)" 0 0
