"""Real parts for the FreeCAD samples: links with pin bosses, a ground plate, a piston, made with
FreeCAD's Part module (OpenCascade) and written as STEP files."""
import math
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


def circle_edge(shape, point, tol=1e-6, radius=None):
    """The name of the circular edge of `shape` centred on `point` (in the shape's own frame), of
    `radius` when given, at the lowest height: the edge a designer would click for a pin there."""
    best = None
    to_local = shape.Placement.inverse()
    for i, e in enumerate(shape.Edges):
        c = getattr(e.Curve, "Center", None)
        if c is None or not hasattr(e.Curve, "Radius") or (radius is not None and abs(e.Curve.Radius - radius) > tol):
            continue
        local = to_local.multVec(c)
        if (local - point).Length < tol:
            z = local.z
            if best is None or z < best[1]:
                best = ("Edge%d" % (i + 1), z)
    if best is None:
        raise ValueError("no circular edge at %s" % point)
    return best[0]


def line_edge_along_x(shape, y, z=0.0):
    """The name of the straight edge of `shape` along x at this y and height z (in the shape's own
    frame): what a designer clicks for a slot or a slider's side."""
    to_local = shape.Placement.inverse()
    for i, e in enumerate(shape.Edges):
        a, b = to_local.multVec(e.Vertexes[0].Point), to_local.multVec(e.Vertexes[-1].Point)
        if (e.Curve.TypeId == "Part::GeomLine" and abs(a.z - z) < 1e-9 and abs(b.z - z) < 1e-9
                and abs(a.y - y) < 1e-9 and abs(b.y - y) < 1e-9 and abs(b.x - a.x) > 0.1):
            return "Edge%d" % (i + 1)
    raise ValueError("no edge along x at y = %g, z = %g" % (y, z))


def face_at_height(shape, z):
    """The name of the first face of `shape` whose centre is at height z (in the shape's own
    frame): a block's top or bottom face."""
    to_local = shape.Placement.inverse()
    for i, f in enumerate(shape.Faces):
        if abs(to_local.multVec(f.CenterOfMass).z - z) < 1e-9:
            return "Face%d" % (i + 1)
    raise ValueError("no face at height %g" % z)


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


# Couplings (issue 11): gears, a ring, a rack, a screw and its vice, as simple solids whose
# circular edges are the pitch circles a designer picks.


def gear(radius, teeth, thickness=0.1, hub=0.15):
    """A spur gear on z: a disc of the pitch radius (its bottom circle, at z = 0, is the pitch
    circle to pick) with `teeth` teeth standing on its rim above z = 0.02, and a round hub on
    top (a pin's circle at its centre)."""
    disc = Part.makeCylinder(radius, thickness)
    depth = 2.2 * radius / teeth  # a module of radius / teeth, teeth 2.2 modules deep
    width = math.pi * radius / teeth
    tooth = Part.makeBox(depth, width, thickness - 0.02, App.Vector(radius - depth / 2, -width / 2, 0.02))
    ring = [tooth.copy() for _ in range(teeth)]
    for k, t in enumerate(ring):
        t.rotate(App.Vector(0, 0, 0), App.Vector(0, 0, 1), 360.0 * k / teeth)
    boss = Part.makeCylinder(hub, 0.05, App.Vector(0, 0, thickness))
    return disc.fuse(ring + [boss]).removeSplitter()


def ring_gear(radius, thickness=0.1, rim=0.25, lift=0.06):
    """An internal gear's ring on z: an annulus whose inner circle (radius, at z = 0) is the pitch
    circle, held by three spokes on a hub at its centre, `lift` above the ring's top so the sun
    and the planets turn beneath them."""
    ring = Part.makeCylinder(radius + rim, thickness).cut(Part.makeCylinder(radius, thickness))
    top = thickness + lift
    extra = [Part.makeCylinder(0.15, 0.05, App.Vector(0, 0, top))]
    for k in range(3):
        a = math.radians(60 + 120 * k)
        s = Part.makeBox(radius + rim / 2, 0.08, 0.05, App.Vector(0, -0.04, top))
        s.rotate(App.Vector(0, 0, 0), App.Vector(0, 0, 1), math.degrees(a))
        post = Part.makeBox(0.1, 0.1, lift + 0.05, App.Vector((radius + rim / 2) * math.cos(a) - 0.05,
                                                              (radius + rim / 2) * math.sin(a) - 0.05, thickness))
        extra += [s, post]
    return ring.fuse(extra).removeSplitter()


def carrier(arm, arms=3, width=0.16, thickness=0.1, boss=0.15):
    """A planet carrier on z: `arms` arms from its centre, a boss at the centre and at each arm's
    end (the planets' pins: bottom circles at z = 0)."""
    bars = [Part.makeBox(arm, width, thickness, App.Vector(0, -width / 2, 0)) for _ in range(arms)]
    bosses = [Part.makeCylinder(boss, thickness)]
    for k, b in enumerate(bars):
        a = 360.0 * k / arms
        b.rotate(App.Vector(0, 0, 0), App.Vector(0, 0, 1), a)
        bosses.append(Part.makeCylinder(boss, thickness, App.Vector(arm * math.cos(math.radians(a)),
                                                                     arm * math.sin(math.radians(a)), 0)))
    return bars[0].fuse(bars[1:] + bosses).removeSplitter()


def rack(length, pins, width=0.2, thickness=0.1, pitch=0.094, boss=0.12):
    """A rack along x centred on the origin: a bar with teeth on its +y side and a boss at each x
    of `pins` (the tie rods' pins); its bottom edge along x (y = -width / 2, z = 0) is what it
    slides on, its top toothless edge along x (y = width / 2, z = thickness) its pitch line."""
    body = Part.makeBox(length, width, thickness, App.Vector(-length / 2, -width / 2, 0))
    teeth = []
    x = -length / 2 + pitch / 4
    while x + pitch / 2 < length / 2:
        teeth.append(Part.makeBox(pitch / 2, 0.05, thickness - 0.02, App.Vector(x, width / 2, 0)))
        x += pitch
    bosses = [Part.makeCylinder(boss, thickness, App.Vector(p, 0, 0)) for p in pins]
    return body.fuse(teeth + bosses).removeSplitter()


def plate_with(pins, boxes, thickness=0.1, boss=0.15, margin=0.4):
    """A base plate under z = 0 spanning the pins and boxes, with a boss at each pin (bottom
    circle at z = 0) and the boxes ((x0, y0, z0, dx, dy, dz)) on it."""
    xs = [p[0] for p in pins] + [b[0] for b in boxes] + [b[0] + b[3] for b in boxes]
    ys = [p[1] for p in pins] + [b[1] for b in boxes] + [b[1] + b[4] for b in boxes]
    x0, x1, y0, y1 = min(xs) - margin, max(xs) + margin, min(ys) - margin, max(ys) + margin
    plate = Part.makeBox(x1 - x0, y1 - y0, thickness, App.Vector(x0, y0, -thickness))
    extra = [Part.makeCylinder(boss, thickness, App.Vector(x, y, 0)) for x, y in pins]
    extra += [Part.makeBox(dx, dy, dz, App.Vector(x, y, z)) for x, y, z, dx, dy, dz in boxes]
    return plate.fuse(extra).removeSplitter()


def lead_screw(length, radius=0.1, handle=0.6):
    """A lead screw along x from 0 to `length` (its end circles: x = 0 and x = length, centred on
    the axis) with a handle bar across its x = 0 end."""
    rod = Part.makeCylinder(radius, length, App.Vector(0, 0, 0), App.Vector(1, 0, 0))
    bar = Part.makeCylinder(0.04, handle, App.Vector(-0.06, 0, -handle / 2), App.Vector(0, 0, 1))
    return rod.fuse(bar).removeSplitter()


def vice_frame(length=3.0, half=0.5, bore=0.1):
    """A vice's frame: a bed along x (top at z = -0.3, its edge along x at y = half the slide of
    the moving jaw) and the fixed jaw at x in [-0.4, 0] with the nut's bore along x through
    (0, 0, 0) (its circular edges: x = -0.4 and x = 0)."""
    bed = Part.makeBox(length + 0.4, 2 * half, 0.2, App.Vector(-0.4, -half, -0.5))
    jaw = Part.makeBox(0.4, 2 * half, 0.7, App.Vector(-0.4, -half, -0.3))
    hole = Part.makeCylinder(bore, 0.4, App.Vector(-0.4, 0, 0), App.Vector(1, 0, 0))
    return bed.fuse(jaw).removeSplitter().cut(hole)


def vice_jaw(half=0.5, bore=0.1):
    """The moving jaw: a block x in [0, 0.4] standing on z = -0.3 (its bottom edge along x at
    y = half slides on the bed), with a hole along x through (0, 0, 0) for the screw's end."""
    block = Part.makeBox(0.4, 2 * half, 0.7, App.Vector(0, -half, -0.3))
    return block.cut(Part.makeCylinder(bore, 0.4, App.Vector(0, 0, 0), App.Vector(1, 0, 0)))
