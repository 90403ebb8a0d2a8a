"""Real parts for the FreeCAD samples: links with pin bosses, a ground plate, a piston, made with
FreeCAD's Part module (OpenCascade) and written as STEP files."""
import os

import FreeCAD as App
import Part


def link(length, width=0.2, thickness=0.1, boss=0.15):
    """A flat link along x from (0, 0, 0) to (length, 0, 0) with a round boss at each end; the
    bosses' bottom circles are centred on the pin points (the edges to pick for revolutes)."""
    body = Part.makeBox(length, width, thickness, App.Vector(0, -width / 2, 0))
    a = Part.makeCylinder(boss, thickness, App.Vector(0, 0, 0))
    b = Part.makeCylinder(boss, thickness, App.Vector(length, 0, 0))
    return body.fuse([a, b]).removeSplitter()


def ground(pins, thickness=0.1, boss=0.15):
    """A base plate under the given pin points (bottom circles of bosses at z = 0); its long top
    edges run along x at y = -0.3 and 0.3 (a slot for a slider)."""
    xs = [p[0] for p in pins]
    plate = Part.makeBox(max(xs) - min(xs) + 1, 0.6, thickness, App.Vector(min(xs) - 0.5, -0.3, -thickness))
    bosses = [Part.makeCylinder(boss, thickness, App.Vector(x, y, 0)) for x, y in pins]
    return plate.fuse(bosses).removeSplitter()


def frame(pins, thickness=0.1, boss=0.15, margin=0.6):
    """A base plate covering the pin points (x, y) with a margin, and a boss under each (bottom
    circles at z = 0, tops at z = thickness): the common frame the walker's legs are bolted to."""
    xs, ys = [p[0] for p in pins], [p[1] for p in pins]
    plate = Part.makeBox(max(xs) - min(xs) + 2 * margin, max(ys) - min(ys) + 2 * margin, thickness,
                         App.Vector(min(xs) - margin, min(ys) - margin, -thickness))
    bosses = [Part.makeCylinder(boss, thickness, App.Vector(x, y, 0)) for x, y in pins]
    return plate.fuse(bosses).removeSplitter()


def ground_with_rail(pins, rail, thickness=0.1, boss=0.15):
    """A base plate under pins, and a rail beside x in [rail[0], rail[1]], y in [-0.6, -0.3],
    as high as the bosses: its top inner edge (y = -0.3, z = 0.1) is a slider's guide."""
    plate = ground(pins, thickness, boss)
    x0, x1 = rail
    bar = Part.makeBox(x1 - x0, 0.3, thickness, App.Vector(x0, -0.6, 0))
    base = Part.makeBox(x1 - x0, 0.6, thickness, App.Vector(x0, -0.6, -thickness))
    return plate.fuse([bar, base]).removeSplitter()


def bar(pins, width=0.2, thickness=0.1, boss=0.15):
    """A flat bar along x with a boss at each x in `pins` (bottom circles at z = 0): a side rod."""
    body = Part.makeBox(max(pins) - min(pins), width, thickness, App.Vector(min(pins), -width / 2, 0))
    return body.fuse([Part.makeCylinder(boss, thickness, App.Vector(x, 0, 0)) for x in pins]).removeSplitter()


def block(dx, dy, dz):
    """A block standing on z = 0 with a corner at the origin: an obstacle."""
    return Part.makeBox(dx, dy, dz)


def piston(size=0.4):
    """A block whose bottom face's centre is the wrist pin; its straight bottom edges along x give
    the slider's direction."""
    return Part.makeBox(size, size, 0.1, App.Vector(-size / 2, -size / 2, 0))


def circle_edge(shape, point, tol=1e-6):
    """The name of the circular edge of `shape` centred on `point` (in the shape's own frame) at
    the lowest height: the edge a designer would click for a pin there."""
    best = None
    to_local = shape.Placement.inverse()
    for i, e in enumerate(shape.Edges):
        c = getattr(e.Curve, "Center", None)
        if c is None or not hasattr(e.Curve, "Radius"):
            continue
        local = to_local.multVec(c)
        if (local - point).Length < tol:
            z = local.z
            if best is None or z < best[1]:
                best = ("Edge%d" % (i + 1), z)
    if best is None:
        raise ValueError("no circular edge at %s" % point)
    return best[0]


def write_step(shape, path):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    shape.exportStep(path)
    return path


def post(length=0.6, boss=0.15, axis=(1, 0, 0)):
    """A ground post: a base block and a boss whose axis is `axis` at the origin (the pin)."""
    v = App.Vector(*axis)
    cyl = Part.makeCylinder(boss, 0.1, App.Vector(0, 0, 0), v)
    block = Part.makeBox(0.3, 0.3, length, App.Vector(-0.15, -0.15, -length - 0.2))
    return cyl.fuse(block).removeSplitter()
