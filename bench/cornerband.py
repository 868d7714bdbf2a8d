#!/usr/bin/env python3
"""cornerband.py - how an image reads in narrow bands along the top of a
room's walls, against a reference, window by window (issue 21's dark strip:
a strip some 35 pixels long under the wall-ceiling corner, which averages
over a whole wall hide).

    cornerband.py [-s SEGMENTS] [-l LAYER] SCENE.pms REF.exr IMG.exr [IMG.exr ...]

SCENE's walls are its vertical `quad` lines whose top edge lies in the plane
of a horizontal `quad` (the ceiling), named by their line. Each wall's top is cut into SEGMENTS
pieces along its length, and each piece into bands 3-30 mm, 30-100 mm and
100-250 mm below the top. The points of a piece and band are projected with
SCENE's camera (formats/scene.md: eye, look, up, vertical fov, size), and
the pixels they fall on make its window. Prints one line per window with
more than 8 pixels: wall, band, piece, pixels, REF's mean there, and
sum(IMG) / sum(REF) over the window for each IMG (the pixels' mean of R, G,
B, or of LAYER's: -l indirect compares the photon estimate alone, with the
path tracer's light after its first bounce; where a wall sees a light, that
layer also holds the share of direct light the path tracer's BSDF samples
find, which a photon pass files as direct, so compare totals there). Pass
the odd and the even half of a series as two IMGs: a bias shows in both,
noise does not.

Pixels are read through tests/tools/exrstat --dump (EXRSTAT, default
build/tests/tools/exrstat: `make build/tests/tools/exrstat`)."""
import math
import os
import subprocess
import sys

BANDS = ((0.003, 0.03), (0.03, 0.1), (0.1, 0.25))


def die(msg):
    sys.stderr.write("cornerband: %s\n" % msg)
    sys.exit(1)


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def unit(a):
    n = math.sqrt(dot(a, a))
    return tuple(x / n for x in a)


def read_scene(path):
    cam, quads = None, []
    try:
        lines = open(path).read().split("\n")
    except OSError as e:
        die("%s: %s" % (path, e.strerror))
    for no, line in enumerate(lines, 1):
        w = line.split("#", 1)[0].split()
        if not w:
            continue
        try:
            if w[0] == "camera":
                kv = {w[i]: w[i + 1:i + 4] for i in range(1, len(w) - 1) if w[i].isalpha()}
                cam = {k: tuple(map(float, kv[k])) for k in ("eye", "look", "up")}
                cam["fov"] = float(kv["fov"][0])
                cam["size"] = (int(kv["size"][0]), int(kv["size"][1]))
            elif w[0] == "quad" and len(w) >= 14:
                v = [float(x) for x in w[2:14]]
                quads.append((no, [tuple(v[3 * i:3 * i + 3]) for i in range(4)]))
        except (KeyError, ValueError, IndexError):
            die("%s:%d: cannot read this line" % (path, no))
    if cam is None:
        die("%s: no camera line" % path)
    return cam, quads


def horizontal(q):
    return all(abs(p[1] - q[0][1]) < 1e-6 for p in q)


def vertical(q):
    n = cross(sub(q[1], q[0]), sub(q[3], q[0]))
    return abs(n[1]) <= 1e-6 * math.sqrt(dot(n, n))


def walls(quads):
    """(name, corner at the top, unit direction along the top, length) per
    vertical quad whose top edge lies in a horizontal quad's plane."""
    flat = {round(q[0][1], 6) for _, q in quads if horizontal(q)}
    out = []
    for no, q in quads:
        top = max(p[1] for p in q)
        if not vertical(q) or round(top, 6) not in flat:
            continue
        up = [p for p in q if abs(p[1] - top) < 1e-6]
        if len(up) != 2:
            continue
        a, b = up
        d = sub(b, a)
        length = math.sqrt(dot(d, d))
        if length <= 0:
            continue
        out.append(("line %d" % no, a, unit(d), length))
    return out


def load(path, exrstat, w, h, layer):
    cmd = [exrstat, "--dump"] + (["--layer", layer] if layer else []) + [path]
    try:
        res = subprocess.run(cmd, capture_output=True, text=True)
    except OSError as e:
        die("%s: %s" % (exrstat, e.strerror))
    if res.returncode != 0:
        die("%s: %s" % (path, res.stderr.strip() or "exrstat failed"))
    px = [0.0] * (w * h)
    for line in res.stdout.split("\n"):
        f = line.split()
        if len(f) == 3:
            x, y = int(f[0]), int(f[1])
            if 0 <= x < w and 0 <= y < h:
                px[y * w + x] = float(f[2])
    return px


def main(argv):
    seg, layer = 10, None
    while len(argv) > 1 and argv[1] in ("-s", "-l"):
        if len(argv) < 3:
            die("%s needs a value" % argv[1])
        if argv[1] == "-s":
            if not argv[2].isdigit() or int(argv[2]) < 1:
                die("-s needs a positive number of pieces")
            seg = int(argv[2])
        else:
            layer = argv[2]
        argv = argv[:1] + argv[3:]
    if len(argv) < 4:
        sys.stderr.write("usage: cornerband.py [-s SEGMENTS] [-l LAYER] SCENE.pms REF.exr IMG.exr [IMG.exr ...]\n")
        return 2
    cam, quads = read_scene(argv[1])
    w, h = cam["size"]
    exrstat = os.environ.get("EXRSTAT", "build/tests/tools/exrstat")
    ref = load(argv[2], exrstat, w, h, layer)
    imgs = [load(p, exrstat, w, h, layer) for p in argv[3:]]
    f = unit(sub(cam["look"], cam["eye"]))
    r = unit(cross(f, cam["up"]))
    u = cross(r, f)
    t = math.tan(math.radians(cam["fov"] / 2))
    aspect = w / h

    def pixel(p):
        d = sub(p, cam["eye"])
        z = dot(d, f)
        if z <= 0:
            return None
        x = int((dot(d, r) / z / (t * aspect) + 1) / 2 * w)
        y = int((1 - dot(d, u) / z / t) / 2 * h)
        return y * w + x if 0 <= x < w and 0 <= y < h else None

    found = walls(quads)
    if not found:
        die("%s: no wall quad meets a horizontal quad at its top" % argv[1])
    for name, a, d, length in found:
        for lo, hi in BANDS:
            for s in range(seg):
                win = set()
                for i in range(40):
                    along = length * (s + (i + 0.5) / 40) / seg
                    for j in range(12):
                        down = lo + (hi - lo) * (j + 0.5) / 12
                        p = pixel((a[0] + d[0] * along, a[1] - down, a[2] + d[2] * along))
                        if p is not None:
                            win.add(p)
                if len(win) <= 8:
                    continue
                sr = sum(ref[k] for k in win)
                if not sr > 0:
                    continue
                ratios = " ".join("%.3f" % (sum(img[k] for k in win) / sr) for img in imgs)
                print("%s\t%.3f-%.3f m\t%d\t%d px\t%.4g\t%s" % (name, lo, hi, s, len(win), sr / len(win),
                                                             ratios))
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except BrokenPipeError:     # a reader such as head stopped early
        sys.stderr.close()
        sys.exit(1)
