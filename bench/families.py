#!/usr/bin/env python3
"""families.py — the scene families of bench/families.sh: rooms of the
meshes users bring, written as .pms scenes plus OBJ files.

Usage: bench/families.py OUTDIR [--size W H] [--seed S] [FAMILY ...]
  Writes OUTDIR/FAMILY/FAMILY.pms (and its OBJ files) for each family named
  (default all) and prints one line per family: name, polygons, what it is.

Families (each in a room of 4 x 2.6 x 5 m lit by an area light 1 mm under
the ceiling, facing down, but cove's; seeded, so the same seed writes the
same bytes):
  prims    Blender-primitive-like curved meshes on a floor and a shelf: a UV
           sphere 48 x 24, a torus 48 x 16, an open 48-sided tube, a
           subdivided blobby head (an icosphere of 5120 triangles, displaced)
  dense    a bumpy sphere and a torus of 102 400 triangles each
  scanned  a displaced blob of irregular triangles of very different sizes
           (random 1-to-3 splits, so slivers next to large faces)
  soup     the room as six separate quads, furniture and curved meshes as
           polygon soups (every face its own vertices, as flat-shaded
           exports write them)
  thin     the room as six separate quads holding thin parts: a staircase of
           eight step blocks with coincident faces, a bookshelf of 2 cm
           panels with books touching or 1 mm apart, a slatted chair on a
           5 mm rug
  cove     thin's room and parts lit by a cove light: the lamp turned to
           face the ceiling, 15 cm under it and 10-30 cm from the back
           wall, so that the room's light comes off a strip of ceiling by
           that wall and rises toward the wall-ceiling corner
A family is one function below; add one by writing another and listing it in
FAMILIES."""
import math
import os
import random
import sys

W, H, D = 4.0, 2.6, 5.0


def fmt(v):
    s = "%.6f" % v
    s = s.rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


class Scene:
    def __init__(self, d, name, size, seed):
        self.d, self.name, self.size, self.seed = d, name, size, seed
        self.rng = random.Random("%s-%d" % (name, seed))
        self.lines, self.mats, self.npoly, self.nmesh = [], [], 0, 0

    def mat(self, name, spec):
        if any(m.split()[1] == name for m in self.mats):
            return
        self.mats.append("material %s %s" % (name, spec))

    def box(self, m, lo, hi, inward=False):
        self.lines.append("box %s %s  %s%s" % (m, " ".join(map(fmt, lo)), " ".join(map(fmt, hi)),
                                              " inward" if inward else ""))
        self.npoly += 6

    def quad(self, m, p):
        self.lines.append("quad %s  %s" % (m, "  ".join(" ".join(map(fmt, v)) for v in p)))
        self.npoly += 1

    def mesh(self, m, verts, faces, soup=False, what="mesh"):
        """An OBJ of faces (lists of indices into verts); soup: every face
        its own vertices, so the mesh has no shared edge (an open sheet)."""
        self.nmesh += 1
        fn = "%s%d.obj" % (self.name, self.nmesh)
        with open(os.path.join(self.d, fn), "w") as f:
            f.write("# %s%s (bench/families.py)\n" % (what, ", polygon soup" if soup else ""))
            if soup:
                k = 1
                for fc in faces:
                    for i in fc:
                        f.write("v %s\n" % " ".join(map(fmt, verts[i])))
                    f.write("f %s\n" % " ".join(str(k + j) for j in range(len(fc))))
                    k += len(fc)
            else:
                for v in verts:
                    f.write("v %s\n" % " ".join(map(fmt, v)))
                for fc in faces:
                    f.write("f %s\n" % " ".join(str(i + 1) for i in fc))
        self.lines.append("mesh %s %s" % (fn, m))
        self.npoly += len(faces)

    def soup_box(self, m, lo, hi, soup=True):
        v, f = box_mesh(lo, hi)
        self.mesh(m, v, f, soup=soup, what="a box")

    def room(self, quads):
        """The room: one closed box seen from inside, or six separate
        quads facing in (a polygon soup of walls)."""
        if not quads:
            self.box("wall", (0, 0, 0), (W, H, D), inward=True)
            return
        x0, y0, z0, x1, y1, z1 = 0, 0, 0, W, H, D
        self.quad("floor", [(x0, y0, z0), (x0, y0, z1), (x1, y0, z1), (x1, y0, z0)])
        self.quad("wall", [(x0, y1, z0), (x1, y1, z0), (x1, y1, z1), (x0, y1, z1)])
        self.quad("wall", [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0)])
        self.quad("wall", [(x0, y0, z1), (x0, y1, z1), (x1, y1, z1), (x1, y0, z1)])
        self.quad("wall", [(x0, y0, z0), (x0, y1, z0), (x0, y1, z1), (x0, y0, z1)])
        self.quad("wall", [(x1, y0, z0), (x1, y0, z1), (x1, y1, z1), (x1, y1, z0)])

    def write(self, eye, look, fov=55, lamp=None):
        """lamp: the light's quad, in the order that makes it face the way
        it emits; by default 0.9 x 0.7 m at the ceiling's centre, facing
        down."""
        w, h = self.size
        hx, hz = 0.45, 0.35
        cx, cz, y = W / 2, D / 2, H - 0.001
        lamp = lamp or [(cx - hx, y, cz - hz), (cx + hx, y, cz - hz), (cx + hx, y, cz + hz), (cx - hx, y, cz + hz)]
        with open(os.path.join(self.d, self.name + ".pms"), "w") as f:
            f.write("# %s (bench/families.py)\n" % self.name)
            f.write("camera eye %s  look %s  up 0 1 0  fov %s  size %d %d\n" % (
                " ".join(map(fmt, eye)), " ".join(map(fmt, look)), fmt(fov), w, h))
            f.write("material wall diffuse albedo 0.75 0.74 0.72\n")
            f.write("material floor diffuse albedo 0.45 0.38 0.3\n")
            f.write("material lamp diffuse albedo 0.5 0.5 0.5 emit 12 11.5 10.5\n")
            for m in self.mats:
                f.write(m + "\n")
            f.write("quad lamp  %s\n" % "  ".join(" ".join(map(fmt, v)) for v in lamp))
            for line in self.lines:
                f.write(line + "\n")
        return self.npoly + 1


def box_mesh(lo, hi):
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    f = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [3, 7, 6, 2], [0, 4, 7, 3], [1, 2, 6, 5]]
    return v, f


def place(verts, s=1.0, t=(0, 0, 0), rot=0.0):
    c, n = math.cos(rot), math.sin(rot)
    return [(s * (x * c + z * n) + t[0], s * y + t[1], s * (-x * n + z * c) + t[2]) for x, y, z in verts]


def rest(verts, y0):
    """Moves verts up or down so that their lowest point is at y0."""
    lo = min(v[1] for v in verts)
    return [(x, y - lo + y0, z) for x, y, z in verts]


def uv_sphere(nu, nv, r=1.0):
    """Blender's UV sphere: nu segments, nv rings; quads and pole triangles."""
    verts = [(0, r, 0)]
    for j in range(1, nv):
        th = math.pi * j / nv
        for i in range(nu):
            ph = 2 * math.pi * i / nu
            verts.append((r * math.sin(th) * math.cos(ph), r * math.cos(th), -r * math.sin(th) * math.sin(ph)))
    verts.append((0, -r, 0))
    last = len(verts) - 1
    at = lambda j, i: 1 + (j - 1) * nu + i % nu
    faces = [[0, at(1, i), at(1, i + 1)] for i in range(nu)]
    for j in range(1, nv - 1):
        faces += [[at(j, i), at(j + 1, i), at(j + 1, i + 1), at(j, i + 1)] for i in range(nu)]
    faces += [[at(nv - 1, i + 1), at(nv - 1, i), last] for i in range(nu)]
    return verts, faces


def torus(nu, nv, R, r):
    verts, faces = [], []
    for i in range(nu):
        ph = 2 * math.pi * i / nu
        for j in range(nv):
            th = 2 * math.pi * j / nv
            d = R + r * math.cos(th)
            verts.append((d * math.cos(ph), r * math.sin(th), -d * math.sin(ph)))
    at = lambda i, j: (i % nu) * nv + j % nv
    for i in range(nu):
        for j in range(nv):
            faces.append([at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
    return verts, faces


def tube(n, r, h):
    """An open cylinder: n side quads, no caps (an open sheet)."""
    verts = [(r * math.cos(2 * math.pi * i / n), y, -r * math.sin(2 * math.pi * i / n)) for y in (0, h) for i in range(n)]
    faces = [[i, (i + 1) % n, n + (i + 1) % n, n + i] for i in range(n)]
    return verts, faces


def icosphere(level):
    t = (1 + 5 ** 0.5) / 2
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
             (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    verts = [tuple(c / math.sqrt(sum(x * x for x in v)) for c in v) for v in verts]
    faces = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
             [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5],
             [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    for _ in range(level):
        mid, nf = {}, []

        def m(a, b):
            k = (min(a, b), max(a, b))
            if k not in mid:
                p = [(verts[a][c] + verts[b][c]) / 2 for c in range(3)]
                l = math.sqrt(sum(x * x for x in p))
                verts.append(tuple(x / l for x in p))
                mid[k] = len(verts) - 1
            return mid[k]
        for a, b, c in faces:
            ab, bc, ca = m(a, b), m(b, c), m(c, a)
            nf += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
        faces = nf
    return verts, faces


def displace(verts, rng, amp, waves=6):
    """A smooth random bump field along each vertex's direction from the
    centre (the verts of a unit sphere): a blobby, head-like solid."""
    ks = [(rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(0, 6.3)) for _ in range(waves)]
    out = []
    for x, y, z in verts:
        s = 1 + amp * sum(math.sin(a * x + b * y + c * z + p) for a, b, c, p in ks) / waves
        out.append((x * s, y * s, z * s))
    return out


def head(rng):
    v, f = icosphere(4)
    v = displace(v, rng, 0.35)
    return [(x * 0.8, y, z * 0.9) for x, y, z in v], f


def irregular(rng, splits):
    """A closed blob of triangles of very different sizes: an icosphere's
    faces split 1-to-3 at random interior points, some many times, most
    never (no T-junctions, so it stays one closed solid)."""
    v, f = icosphere(2)
    v = list(v)
    for _ in range(splits):
        i = rng.randrange(len(f)) if rng.random() < 0.5 else len(f) - 1 - rng.randrange(min(len(f), 40))
        a, b, c = f[i]
        u, w = rng.random(), rng.random()
        if u + w > 1:
            u, w = 1 - u, 1 - w
        p = tuple(v[a][k] + u * (v[b][k] - v[a][k]) + w * (v[c][k] - v[a][k]) for k in range(3))
        l = math.sqrt(sum(x * x for x in p))
        v.append(tuple(x / l * (1 + 0.02 * rng.uniform(-1, 1)) for x in p))
        n = len(v) - 1
        f[i] = [a, b, n]
        f += [[b, c, n], [c, a, n]]
    return displace(v, rng, 0.25), f


# ---- the families ----------------------------------------------------------

def fam_prims(s, soup=False):
    r = s.rng
    s.mat("grey", "diffuse albedo 0.6 0.6 0.6")
    s.mat("red", "diffuse albedo 0.7 0.25 0.2")
    s.mat("blue", "diffuse albedo 0.2 0.3 0.65")
    s.mat("wood", "diffuse albedo 0.5 0.35 0.2")
    if not soup:
        s.room(False)
        s.box("wood", (0.2, 0.9, 0.0), (1.6, 0.94, 0.4))   # a shelf against the back wall
    else:
        s.room(True)
        s.soup_box("wood", (0.2, 0.9, 0.0), (1.6, 0.94, 0.4))
    v, f = uv_sphere(48, 24, 0.18)
    s.mesh("red", rest(place(v, t=(0.7, 0, 0.2)), 0.94), f, soup, "a UV sphere 48 x 24")
    v, f = torus(48, 16, 0.3, 0.1)
    s.mesh("blue", rest(place(v, t=(2.6, 0, 1.2)), 0), f, soup, "a torus 48 x 16")
    v, f = tube(48, 0.15, 0.5)
    s.mesh("grey", place(v, t=(1.2, 0, 1.5)), f, soup, "an open tube of 48 sides")
    v, f = head(r)
    s.mesh("grey", rest(place(v, 0.25, t=(1.9, 0, 0.9)), 0), f, soup, "a blobby head of 5120 triangles")
    return s.write((3.3, 1.5, 4.2), (1.5, 0.5, 0.8))


def fam_dense(s):
    s.mat("grey", "diffuse albedo 0.6 0.6 0.6")
    s.mat("red", "diffuse albedo 0.7 0.3 0.2")
    s.room(False)
    v, f = uv_sphere(320, 161, 1)
    v = displace(v, s.rng, 0.12, 10)
    tris = []
    for fc in f:
        tris += [fc] if len(fc) == 3 else [[fc[0], fc[1], fc[2]], [fc[0], fc[2], fc[3]]]
    s.mesh("red", rest(place(v, 0.45, t=(2.2, 0, 1.6)), 0), tris, False, "a bumpy sphere of %d triangles" % len(tris))
    v, f = torus(400, 128, 0.35, 0.12)
    tris = [t for fc in f for t in ([fc[0], fc[1], fc[2]], [fc[0], fc[2], fc[3]])]
    s.mesh("grey", rest(place(v, t=(0.9, 0, 1.0)), 0), tris, False, "a dense torus of %d triangles" % len(tris))
    return s.write((3.3, 1.5, 4.2), (1.6, 0.3, 1.2))


def fam_scanned(s):
    s.mat("stone", "diffuse albedo 0.55 0.5 0.45")
    s.mat("wood", "diffuse albedo 0.5 0.35 0.2")
    s.room(False)
    s.box("wood", (1.2, 0.0, 0.8), (2.8, 0.7, 1.8))
    v, f = irregular(s.rng, 12000)
    s.mesh("stone", rest(place(v, 0.3, t=(1.8, 0, 1.3)), 0.7), f, False, "a scanned-like blob of %d triangles" % len(f))
    v, f = irregular(s.rng, 6000)
    s.mesh("stone", rest(place(v, 0.35, t=(3.0, 0, 2.6)), 0), f, False, "a scanned-like rock of %d triangles" % len(f))
    return s.write((3.4, 1.6, 4.3), (1.9, 0.6, 1.4))


def fam_soup(s):
    s.mat("wood", "diffuse albedo 0.5 0.35 0.2")
    # a table as one soup of five boxes' faces
    v, f = [], []
    for lo, hi in [((1.0, 0.7, 1.0), (2.4, 0.74, 1.9))] + [
            ((x, 0, z), (x + 0.05, 0.7, z + 0.05)) for x in (1.05, 2.3) for z in (1.05, 1.8)]:
        bv, bf = box_mesh(lo, hi)
        f += [[i + len(v) for i in fc] for fc in bf]
        v += bv
    s.mesh("wood", v, f, True, "a table of five boxes")
    s.soup_box("wood", (2.9, 0, 0.0), (3.6, 1.2, 0.45))
    return fam_prims(s, soup=True)


def fam_thin(s, lamp=None):
    r = s.rng
    s.mat("wood", "diffuse albedo 0.55 0.4 0.25")
    s.mat("paint", "diffuse albedo 0.7 0.7 0.68")
    s.mat("rug", "diffuse albedo 0.6 0.2 0.2")
    s.room(True)
    # a staircase of eight step blocks against the left wall, rising toward
    # the back: each block from the floor to its tread, sharing its faces
    # with the next
    for i in range(8):
        s.box("paint", (0.0, 0.0, 2.9 - 0.28 * (i + 1)), (0.9, 0.18 * (i + 1), 2.9 - 0.28 * i))
    # a bookshelf of 2 cm panels against the back wall
    x0, x1, y1, dz = 1.6, 2.8, 2.0, 0.3
    s.box("wood", (x0, 0, 0.0), (x0 + 0.02, y1, dz))
    s.box("wood", (x1 - 0.02, 0, 0.0), (x1, y1, dz))
    s.box("wood", (x0 + 0.02, 0, 0.0), (x1 - 0.02, y1, 0.02))
    for k in range(5):
        y = 0.05 + k * 0.47
        s.box("wood", (x0 + 0.02, y, 0.02), (x1 - 0.02, y + 0.02, dz))
        x = x0 + 0.02
        while k < 4 and x < x1 - 0.08:
            bw = r.uniform(0.02, 0.05)
            s.box("rug" if r.random() < 0.3 else "paint", (x, y + 0.02, 0.04), (x + bw, y + 0.02 + r.uniform(0.2, 0.3), 0.04 + r.uniform(0.15, 0.24)))
            x += bw + (0 if r.random() < 0.5 else 0.001)
    # a slatted chair on a 5 mm rug
    s.box("rug", (2.2, 0, 2.2), (3.4, 0.005, 3.6))
    cx, cz, y0 = 2.8, 2.9, 0.005
    for lx in (cx - 0.2, cx + 0.17):
        for lz in (cz - 0.2, cz + 0.17):
            s.box("wood", (lx, y0, lz), (lx + 0.03, y0 + 0.45, lz + 0.03))
    for k in range(6):
        x = cx - 0.2 + k * 0.07
        s.box("wood", (x, y0 + 0.45, cz - 0.2), (x + 0.05, y0 + 0.47, cz + 0.2))
    for k in range(4):
        y = y0 + 0.55 + k * 0.1
        s.box("wood", (cx - 0.2, y, cz + 0.17), (cx + 0.2, y + 0.06, cz + 0.19))
    s.box("wood", (cx - 0.2, y0 + 0.47, cz + 0.17), (cx - 0.17, y0 + 0.95, cz + 0.2))
    s.box("wood", (cx + 0.17, y0 + 0.47, cz + 0.17), (cx + 0.2, y0 + 0.95, cz + 0.2))
    return s.write((3.75, 1.9, 4.9), (1.0, 0.9, 1.6), 72, lamp)


def fam_cove(s):
    # The lamp's corners in the order that turns it to face up (the default
    # lamp's, mirrored), by the back wall; the parts are thin's, drawn from
    # thin's seed so that only the light differs.
    y = H - 0.15
    s.rng = random.Random("thin-%d" % s.seed)
    return fam_thin(s, [(1.55, y, 0.3), (2.45, y, 0.3), (2.45, y, 0.1), (1.55, y, 0.1)])


FAMILIES = {"prims": fam_prims, "dense": fam_dense, "scanned": fam_scanned, "soup": fam_soup, "thin": fam_thin,
            "cove": fam_cove}


def main(argv):
    size, seed, names, out, i = (256, 256), 1, [], None, 0
    while i < len(argv):
        a = argv[i]
        if a == "--size":
            size = (int(argv[i + 1]), int(argv[i + 2]))
            i += 3
            continue
        if a == "--seed":
            seed = int(argv[i + 1])
            i += 2
            continue
        if out is None:
            out = a
        elif a in FAMILIES:
            names.append(a)
        else:
            sys.exit("families.py: unknown family '%s' (%s)" % (a, " ".join(FAMILIES)))
        i += 1
    if out is None:
        sys.exit("usage: families.py OUTDIR [--size W H] [--seed S] [FAMILY ...]")
    for n in names or list(FAMILIES):
        d = os.path.join(out, n)
        os.makedirs(d, exist_ok=True)
        s = Scene(d, n, size, seed)
        np = FAMILIES[n](s)
        print("%s\t%d polygons\t%s" % (n, np, os.path.join(d, n + ".pms")))


if __name__ == "__main__":
    main(sys.argv[1:])
