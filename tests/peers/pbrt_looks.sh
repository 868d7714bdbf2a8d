# pbrt_looks.sh — issue 23's looks against pbrt-v4: image textures (an
# 8-bit sRGB PNG and a float PFM, with uv scale), a checkerboard, a sphere
# of 80 facets with per-vertex normals, spot, distant and infinite lights
# (constant, and an equal-area sky image that pm-import resamples to
# lat-long), sphere and disk area lights. Grey scenes written here,
# rendered by pbrt and by pm (pm-import, then pm's path tracer; two also
# through the photon pipeline).
#
# Tolerances. Where pm's model is pbrt's the images differ by Monte Carlo
# noise (lib.sh: about 1 % rms over 8 x 8 blocks at 256 samples a pixel)
# and, on textures, by filtering: pbrt's default imagemap filter is
# bilinear, as pm's lookup, so "exact" is lib.sh's (mean 2 %, block rms
# 3 %, worst block 10 %). The equal-area sky is resampled by pm-import
# into lat-long by nearest texel, which moves texels by up to half a texel
# at the horizon: seen directly it reads within 4 % mean, 15 % block rms
# (measured at the import: +3.4 %, 15 %); lighting a floor only, its
# resampling averages out ("exact"). The photon pipeline's estimate is
# biased by its support (k photons): mean 3 %, block rms 6 %, worst 20 %.
. "$PM_TOP/tests/peers/lib.sh"
exact="0.02 0.03 0.10"
photons="0.03 0.06 0.20"

cam() {
	echo 'Scale -1 1 1'
	echo "LookAt $1  $2  0 1 0"
	echo "Camera \"perspective\" \"float fov\" [ ${FOV:-45} ]"
}
# floor MATERIAL-OR-TEXTURE-LINES : the 4 x 4 floor at y = 0 facing up, uv
# 0..1 across it.
floor() {
	echo 'Shape "trianglemesh" "point3 P" [ -2 0 -2  -2 0 2  2 0 2  2 0 -2 ] "integer indices" [ 0 1 2  0 2 3 ] "point2 uv" [ 0 0  0 1  1 1  1 0 ]'
}
sun() { echo 'LightSource "distant" "point3 from" [ 0.3 1 0.5 ] "point3 to" [ 0 0 0 ] "rgb L" [ 3 3 3 ]'; }
both() {
	n=$1; shift
	peer_render "$n"; pm_path "$n"
	peer_compare "$n" "$n.pm.exr" "$n.ref.exr" "$@"
}
view() { cam '0 3.2 3.2' '0 0 0'; peer_film "$1" 64 48; echo WorldBegin; }

# Images: an 8 x 8 grey PNG (8-bit, sRGB-encoded ramp across and down) and
# a 4 x 4 float PFM (linear values 0.1 .. 0.85), written by python3.
python3 - <<'PY'
import struct, zlib
w = h = 8
rows = b''.join(b'\x00' + bytes(min(255, 20 + 24 * x + 4 * y) for x in range(w)) for y in range(h))
def chunk(t, d):
    return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
open('ramp.png', 'wb').write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 0, 0, 0, 0))
    + chunk(b'IDAT', zlib.compress(rows)) + chunk(b'IEND', b''))
v = [0.1 + 0.05 * i for i in range(16)]
with open('lin.pfm', 'wb') as f:
    f.write(b'PF\n4 4\n-1.0\n')
    for y in range(4):
        for x in range(4):
            f.write(struct.pack('<fff', *([v[4 * y + x]] * 3)))
# An equal-area sky: bright toward the square's +u corner, dim elsewhere.
with open('sky.pfm', 'wb') as f:
    n = 32
    f.write(b'PF\n%d %d\n-1.0\n' % (n, n))
    for y in range(n):
        for x in range(n):
            L = 0.3 + 1.5 * (x + 0.5) / n + 0.5 * (y + 0.5) / n
            f.write(struct.pack('<fff', L, L, L))
PY

# Textures on a floor under the sun.
{ view tex_png; sun
  echo 'Texture "t" "spectrum" "imagemap" "string filename" "ramp.png"'
  echo 'Material "diffuse" "texture reflectance" "t"'; floor; } >tex_png.pbrt
both tex_png $exact
{ view tex_pfm; sun
  echo 'Texture "t" "spectrum" "imagemap" "string filename" "lin.pfm" "float uscale" 2 "float vscale" 3'
  echo 'Material "diffuse" "texture reflectance" "t"'; floor; } >tex_pfm.pbrt
both tex_pfm $exact
{ view checker; sun
  echo 'Texture "t" "spectrum" "checkerboard" "float uscale" 6 "float vscale" 6 "rgb tex1" [ 0.8 0.8 0.8 ] "rgb tex2" [ 0.2 0.2 0.2 ]'
  echo 'Material "diffuse" "texture reflectance" "t"'; floor; } >checker.pbrt
both checker $exact

# A sphere of 80 facets (an icosahedron split once) with per-vertex normals
# under the sun, on a grey floor, filling the frame. The same mesh shaded
# flat in pm reads 12.6 % block rms, 64 % worst block against pbrt's smooth
# one (measured); smooth it agrees to noise, but the top blocks hold the
# floor's far edge against black, dim and noisy: rms 4 %, worst 15 %.
awk 'function key(a, b) { return a < b ? a "_" b : b "_" a }
function add(x, y, z,   l) { l = sqrt(x*x + y*y + z*z); X[n] = x/l; Y[n] = y/l; Z[n] = z/l; return n++ }
function mid(a, b,   k) { k = key(a, b); if (!(k in M)) M[k] = add(X[a] + X[b], Y[a] + Y[b], Z[a] + Z[b]); return M[k] }
BEGIN { n = 0; t = (1 + sqrt(5)) / 2
	add(-1, t, 0); add(1, t, 0); add(-1, -t, 0); add(1, -t, 0); add(0, -1, t); add(0, 1, t)
	add(0, -1, -t); add(0, 1, -t); add(t, 0, -1); add(t, 0, 1); add(-t, 0, -1); add(-t, 0, 1)
	split("0 11 5 0 5 1 0 1 7 0 7 10 0 10 11 1 5 9 5 11 4 11 10 2 10 7 6 7 1 8 3 9 4 3 4 2 3 2 6 3 6 8 3 8 9 4 9 5 2 4 11 6 2 10 8 6 7 9 8 1", F, " ")
	for (f = 0; f < 20; f++) { a = F[3*f+1]; b = F[3*f+2]; c = F[3*f+3]
		ab = mid(a, b); bc = mid(b, c); ca = mid(c, a)
		I = I " " a " " ab " " ca "  " b " " bc " " ab "  " c " " ca " " bc "  " ab " " bc " " ca }
	for (i = 0; i < n; i++) { P = P " " X[i] " " Y[i] " " Z[i]; N = N " " X[i] " " Y[i] " " Z[i] }
	printf "Shape \"trianglemesh\" \"point3 P\" [%s ] \"normal N\" [%s ] \"integer indices\" [%s ]\n", P, N, I }' >ico.txt
check "the icosphere has 80 facets" test "$(awk '{ n = 0; for (i = 1; i <= NF; i++) if ($i == "\"integer") s = i; print int((NF - s - 2) / 3) }' ico.txt)" = 80
{ cam '0 1.5 2.4' '0 0.9 0'; peer_film sphere 64 48; echo WorldBegin; sun
  echo 'Material "diffuse" "rgb reflectance" [ 0.4 0.4 0.4 ]'; floor
  echo 'AttributeBegin Translate 0 1 0 Scale 0.9 0.9 0.9'
  echo 'Material "diffuse" "rgb reflectance" [ 0.8 0.8 0.8 ]'; cat ico.txt; echo 'AttributeEnd'; } >sphere.pbrt
both sphere 0.02 0.04 0.15
pm_photons sphere 400000 compensated 50 16
peer_compare "sphere, photon map" sphere.ph.exr sphere.ref.exr $photons

# A spot light: its cone's edge and smoothstep falloff cross the floor.
{ view spot
  echo 'LightSource "spot" "point3 from" [ 0.5 2 0.3 ] "point3 to" [ -0.3 0 -0.2 ] "float coneangle" 35 "float conedeltaangle" 12 "rgb I" [ 6 6 6 ]'
  echo 'Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]'; floor; } >spot.pbrt
both spot $exact
pm_photons spot 300000 compensated 50 16
peer_compare "spot, photon map" spot.ph.exr spot.ref.exr $photons

# Infinite lights on a sphere over the floor: constant, and the image.
for s in const img; do
	{ view sky_$s
	  if [ $s = const ]; then echo 'LightSource "infinite" "rgb L" [ 0.8 0.8 0.8 ]'
	  else echo 'AttributeBegin Rotate -90 1 0 0 LightSource "infinite" "string filename" "sky.pfm" AttributeEnd'; fi
	  echo 'Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]'; floor
	  echo 'Shape "sphere" "float radius" 0.6'; } >sky_$s.pbrt
done
both sky_const $exact
both sky_img $exact

# Area lights: an emitting sphere and an emitting disk over the floor.
{ view area
  echo 'Material "diffuse" "rgb reflectance" [ 0.5 0.5 0.5 ]'; floor
  echo 'AttributeBegin Translate -0.8 0.9 0 AreaLightSource "diffuse" "rgb L" [ 3 3 3 ] Shape "sphere" "float radius" 0.25 AttributeEnd'
  echo 'AttributeBegin Translate 0.8 1.2 -0.3 Rotate 90 1 0 0 AreaLightSource "diffuse" "rgb L" [ 4 4 4 ] Shape "disk" "float radius" 0.35 AttributeEnd'; } >area.pbrt
both area $exact
