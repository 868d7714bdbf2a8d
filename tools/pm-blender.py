# pm-blender.py — Blender's scene as a pm scene, run by Blender itself:
#
#   blender -b FILE.blend --python tools/pm-blender.py -- OUT_DIR [--size W H]
#
# writes OUT_DIR/scene.pms (formats/scene.md) and a binary PLY per object
# and material beside it, as pm-import does: the active camera (its sensor
# fit, both aspects), every renderable object as Blender's depsgraph
# evaluates it (modifiers applied, instances expanded, transforms to world),
# Principled, Diffuse, Glossy, Glass and Emission materials mapped by the
# rules of README ("Your own scenes"), point and area lights in Cycles'
# units (measured: a point light of P W has intensity P / 4 pi, an area
# light of P W and area A radiance P / 4A; an emission strength S is
# radiance S). What cannot be mapped is printed and kept as comments.
# The files appear whole or not at all: meshes under names made from their
# contents, the scene renamed into place last.
import hashlib
import math
import os
import struct
import sys
import tempfile

import bpy

notes = []


def note(what):
    if what not in notes:
        notes.append(what)


def die(msg):
    sys.stderr.write("pm-blender: %s\n" % msg)
    sys.stderr.flush()
    os._exit(1)


def args():
    a = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    size = None
    out = None
    i = 0
    while i < len(a):
        if a[i] == "--size" and i + 2 < len(a):
            size = (int(a[i + 1]), int(a[i + 2]))
            i += 3
        elif out is None:
            out = a[i]
            i += 1
        else:
            die("usage: blender -b FILE.blend --python pm-blender.py -- OUT_DIR [--size W H]")
    if out is None:
        die("usage: blender -b FILE.blend --python pm-blender.py -- OUT_DIR [--size W H]")
    return out, size


def num(x):
    return "%.9g" % (0.0 if abs(x) < 1e-30 else x)


def clamp01(c):
    return [min(1.0, max(0.0, x)) for x in c]


def blinn(alpha):
    # the Blinn lobe of the Beckmann distribution of the same width
    if alpha < 0.0014142:
        return 1e6
    return max(1.0, 2.0 / (alpha * alpha) - 2.0)


# ---- camera ----

def camera_line(sc, size):
    cam = sc.camera
    if cam is None or cam.type != 'CAMERA':
        die("the scene has no active camera")
    r = sc.render
    if size:
        w, h = size
    else:
        w = int(r.resolution_x * r.resolution_percentage / 100)
        h = int(r.resolution_y * r.resolution_percentage / 100)
    if r.pixel_aspect_x != r.pixel_aspect_y:
        note("camera: non-square pixels taken as square")
    d = cam.data
    if d.type != 'PERSP':
        die("camera '%s': pm has only the perspective camera" % cam.name)
    if d.shift_x or d.shift_y:
        note("camera: lens shift dropped")
    if d.dof.use_dof:
        note("camera: depth of field dropped")
    fit = d.sensor_fit
    if fit == 'AUTO':
        fit = 'HORIZONTAL' if w >= h else 'VERTICAL'
        sensor = d.sensor_width
    else:
        sensor = d.sensor_width if fit == 'HORIZONTAL' else d.sensor_height
    t = sensor / (2 * d.lens)
    ty = t if fit == 'VERTICAL' else t * h / w
    fovy = math.degrees(2 * math.atan(ty))
    m = cam.matrix_world
    eye = m.translation
    fwd = -(m.to_3x3().col[2]).normalized()
    up = (m.to_3x3().col[1]).normalized()
    look = eye + fwd
    return "camera eye %s %s %s  look %s %s %s  up %s %s %s  fov %s  size %d %d\n" % (
        num(eye.x), num(eye.y), num(eye.z), num(look.x), num(look.y), num(look.z),
        num(up.x), num(up.y), num(up.z), num(fovy), w, h)


# ---- materials ----

def surface_node(mat):
    if mat is None or not mat.use_nodes or mat.node_tree is None:
        return None
    out = None
    for n in mat.node_tree.nodes:
        if n.type == 'OUTPUT_MATERIAL' and (out is None or n.is_active_output):
            out = n
    if out is None or not out.inputs['Surface'].is_linked:
        return None
    return out.inputs['Surface'].links[0].from_node


def value(node, name, what):
    i = node.inputs[name]
    if i.is_linked:
        note("%s: input '%s' is linked (a texture or node network): its default value used" % (what, name))
    v = i.default_value
    try:
        return list(v)[:3]
    except TypeError:
        return v


def material_line(name, mat):
    """The pm material words for a Blender material."""
    what = "material '%s'" % (mat.name if mat else "none")
    node = surface_node(mat)
    while node is not None and node.type in ('MIX_SHADER', 'ADD_SHADER'):
        note("%s: %s: its first shader stands for it" % (what, node.name))
        k = 1 if node.type == 'MIX_SHADER' else 0
        if not node.inputs[k].is_linked:
            node = None
            break
        node = node.inputs[k].links[0].from_node
    if node is None:
        c = list(mat.diffuse_color)[:3] if mat else [0.8, 0.8, 0.8]
        return "diffuse albedo %s %s %s" % tuple(num(x) for x in clamp01(c)), None
    t = node.type
    if t == 'EMISSION':
        c = value(node, 'Color', what)
        s = value(node, 'Strength', what)
        return "diffuse albedo 0 0 0", [x * s for x in c]
    if t == 'BSDF_DIFFUSE':
        return "diffuse albedo %s %s %s" % tuple(num(x) for x in clamp01(value(node, 'Color', what))), None
    if t == 'BSDF_GLOSSY':
        c = clamp01(value(node, 'Color', what))
        a = value(node, 'Roughness', what) ** 2
        if a == 0:
            return "mirror reflect %s %s %s" % tuple(num(x) for x in c), None
        return "glossy kd 0 0 0 ks %s %s %s exponent %s" % (num(c[0]), num(c[1]), num(c[2]), num(blinn(a))), None
    if t == 'BSDF_GLASS':
        c = clamp01(value(node, 'Color', what))
        if value(node, 'Roughness', what) > 0:
            note("%s: rough glass taken as smooth" % what)
        return "glass ior %s tint %s %s %s" % (num(value(node, 'IOR', what)), num(c[0]), num(c[1]), num(c[2])), None
    if t == 'BSDF_PRINCIPLED':
        base = clamp01(value(node, 'Base Color', what))
        metal = value(node, 'Metallic', what)
        rough = value(node, 'Roughness', what)
        trans = value(node, 'Transmission', what)
        es = value(node, 'Emission Strength', what)
        emit = [x * es for x in value(node, 'Emission', what)]
        emit = emit if max(emit) > 0 else None
        a = rough * rough
        if trans > 0.5 and not emit:
            note("%s: Principled with transmission %.3g: glass" % (what, trans))
            return "glass ior %s tint %s %s %s" % (num(value(node, 'IOR', what)), num(base[0]), num(base[1]), num(base[2])), None
        if metal > 0.5 and not emit:
            note("%s: Principled metallic %.3g: a conductor of its base colour" % (what, metal))
            if a == 0:
                return "mirror reflect %s %s %s" % tuple(num(x) for x in base), None
            return "glossy kd 0 0 0 ks %s %s %s exponent %s" % (num(base[0]), num(base[1]), num(base[2]), num(blinn(a))), emit
        f0 = min(1.0, 0.08 * value(node, 'Specular', what))
        note("%s: Principled: diffuse x (1 - F0) plus a Blinn lobe of F0 = %.3g" % (what, f0))
        kd = [x * (1 - f0) for x in base]
        return "glossy kd %s %s %s ks %s %s %s exponent %s" % (
            num(kd[0]), num(kd[1]), num(kd[2]), num(f0), num(f0), num(f0), num(blinn(a))), emit
    note("%s: shader '%s' has no pm model: grey diffuse 0.5" % (what, node.name))
    return "diffuse albedo 0.5 0.5 0.5", None


# ---- meshes ----

def ply_bytes(verts, faces):
    head = ("ply\nformat binary_little_endian 1.0\ncomment pm-blender\nelement vertex %d\n"
            "property float x\nproperty float y\nproperty float z\nelement face %d\n"
            "property list uchar uint vertex_indices\nend_header\n" % (len(verts), len(faces)))
    b = bytearray(head.encode())
    for v in verts:
        b += struct.pack("<3f", *v)
    for f in faces:
        b += struct.pack("<B%dI" % len(f), len(f), *f)
    return bytes(b)


def main():
    out, size = args()
    pms = out if out.endswith(".pms") else os.path.join(out, "scene.pms")
    d = os.path.dirname(os.path.abspath(pms))
    os.makedirs(d, exist_ok=True)
    stem = os.path.basename(pms)[:-4]
    sc = bpy.context.scene
    dg = bpy.context.evaluated_depsgraph_get()
    body = [camera_line(sc, size)]
    mats = {}
    lines = []
    written = []
    nlights = 0
    for inst in dg.object_instances:
        ob = inst.object
        if ob.type == 'LIGHT':
            L = ob.data
            m = inst.matrix_world
            p = m.translation
            c = list(L.color)
            if L.type == 'POINT':
                if L.shadow_soft_size > 0:
                    note("light '%s': radius %.3g taken as a point" % (ob.name, L.shadow_soft_size))
                # Cycles: intensity P / 4 pi, so pm's power is P.
                lines.append("pointlight %s %s %s power %s %s %s\n" % (
                    num(p.x), num(p.y), num(p.z), num(L.energy * c[0]), num(L.energy * c[1]), num(L.energy * c[2])))
                nlights += 1
            elif L.type == 'AREA':
                sx = L.size * m.to_3x3().col[0].length
                sy = (L.size_y if L.shape in ('RECTANGLE', 'ELLIPSE') else L.size) * m.to_3x3().col[1].length
                ell = L.shape in ('DISK', 'ELLIPSE')
                area = math.pi * sx * sy / 4 if ell else sx * sy
                rad = [L.energy / (4 * area) * x for x in c]   # Cycles: P / 4A
                key = ("light", tuple(rad))
                if key not in mats:
                    mats[key] = "m%d" % len(mats)
                    body.append("material %s diffuse albedo 0 0 0 emit %s %s %s\n" % (mats[key], num(rad[0]), num(rad[1]), num(rad[2])))
                n = 48 if ell else 4
                pts = []
                for k in range(n):
                    if ell:
                        a = -2 * math.pi * k / n
                        q = (0.5 * L.size * math.cos(a), 0.5 * (L.size_y if L.shape == 'ELLIPSE' else L.size) * math.sin(a), 0)
                    else:
                        hx, hy = 0.5 * L.size, 0.5 * (L.size_y if L.shape == 'RECTANGLE' else L.size)
                        q = ((-hx, -hy, 0), (-hx, hy, 0), (hx, hy, 0), (hx, -hy, 0))[k]
                    pts.append(m @ __import__('mathutils').Vector(q))
                # Blender's area light shines along its local -z: corners
                # counter-clockwise seen from there.
                lines.append("mesh %s %s\n" % (write_mesh(d, stem, [tuple(v) for v in pts], [list(range(n))], written), mats[key]))
                nlights += 1
            else:
                note("light '%s' (%s): pm has no such light yet, dropped" % (ob.name, L.type.lower()))
            continue
        if ob.type not in ('MESH', 'CURVE', 'SURFACE', 'META', 'FONT'):
            continue
        try:
            me = ob.to_mesh()
        except RuntimeError:
            continue
        if me is None:
            continue
        m = inst.matrix_world.copy()
        flip = m.to_3x3().determinant() < 0
        verts = [tuple(m @ v.co) for v in me.vertices]
        groups = {}
        for poly in me.polygons:
            vs = list(poly.vertices)
            if flip:
                vs.reverse()
            groups.setdefault(poly.material_index, []).append(vs)
        for mi, faces in sorted(groups.items()):
            mat = ob.material_slots[mi].material if mi < len(ob.material_slots) else None
            key = ("mat", mat.name if mat else None)
            if key not in mats:
                words, emit = material_line(None, mat)
                mats[key] = "m%d" % len(mats)
                tail = ""
                if emit and max(emit) > 0:
                    if not words.startswith(("diffuse", "glossy")):
                        words = "diffuse albedo 0 0 0"
                    tail = " emit %s %s %s" % tuple(num(x) for x in emit)
                mats[key + ("emit",)] = bool(tail)
                body.append("material %s %s%s\n" % (mats[key], words, tail))
            used = sorted({i for f in faces for i in f})
            remap = {v: k for k, v in enumerate(used)}
            lines.append("mesh %s %s\n" % (write_mesh(d, stem, [verts[i] for i in used], [[remap[i] for i in f] for f in faces], written), mats[key]))
            if mats.get(key + ("emit",)):
                nlights += 1
        ob.to_mesh_clear()
    if sc.world and sc.world.use_nodes:
        for n in sc.world.node_tree.nodes:
            if n.type == 'BACKGROUND' and n.inputs['Strength'].default_value > 0 and \
                    max(list(n.inputs['Color'].default_value)[:3]) > 0:
                note("world background: pm has no environment light yet, dropped")
    if nlights == 0:
        for f in written:
            os.unlink(f)
        die("no light pm can render (every light was dropped)")
    text = "# pm scene exported from %s by pm-blender.py\n" % (bpy.data.filepath or "an unsaved scene")
    if notes:
        text += "# approximated or dropped:\n" + "".join("#   %s\n" % n for n in notes)
    text += "".join(body) + "".join(lines)
    fd, tmp = tempfile.mkstemp(prefix="." + stem + ".pm-tmp-", dir=d)
    with os.fdopen(fd, "w") as f:
        f.write(text)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, pms)
    for n in notes:
        sys.stderr.write("pm-blender: %s\n" % n)


def write_mesh(d, stem, verts, faces, written):
    data = ply_bytes(verts, faces)
    name = "%s-%s.ply" % (stem, hashlib.sha256(data).hexdigest()[:16])
    path = os.path.join(d, name)
    if not os.path.exists(path):
        fd, tmp = tempfile.mkstemp(prefix="." + name + ".pm-tmp-", dir=d)
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
        written.append(path)
    return name


main()
