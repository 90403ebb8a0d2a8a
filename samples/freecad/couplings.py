"""The coupling samples (issue 11), built as a designer builds them in the workbench: STEP parts
imported, joints made from picked circular and straight edges. Each builder returns the assembly
(not yet solved) and its parts by name; build_samples.py solves and saves them, the tests drive
them.

- three_gears: three gears on axles of a plate, radii 1, 2, 1.5 (20, 40, 30 teeth), two Gears
  joints whose ratios come from the picked pitch circles (1/2 and 4/3). One degree of freedom.
- planetary: sun (radius 1), three planets (0.5) on a carrier (arm 1.5), ring (2): Gears from the
  sun to each planet, Belt (an internal mesh turns the same way) from each planet to the ring.
  Two degrees of freedom; Willis: (w_sun - w_carrier) / (w_ring - w_carrier) = -2.
- steering: a pinion (radius 0.3) turning on the frame drives a rack sliding along x
  (RackPinion), tie rods from the rack's ends to two knuckles pivoting on the frame. One degree
  of freedom.
- vice: a lead screw (pitch 0.2) in the frame's nut (Screw), pushing a jaw that slides on the
  frame's bed and turns freely on the screw's end. One degree of freedom."""
import math
import os

import FreeCAD as App

import dispcon_fc.assembly as da
import parts

PARTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "parts")


def step(name, shape_fn):
    """The STEP file of a part, written from parts.py when missing."""
    path = os.path.join(PARTS, name + ".step")
    if not os.path.exists(path):
        parts.write_step(shape_fn(), path)
    return path


def place(obj, x, y, z, deg=0.0, axis=(0, 0, 1)):
    obj.Placement = App.Placement(App.Vector(x, y, z), App.Rotation(App.Vector(*axis), deg))


def circle(obj, centre, radius=None):
    """The circular edge of `obj` centred on `centre` (the part's own frame), of `radius` when
    given: what a designer clicks for a pitch circle or a pin."""
    return (obj, parts.circle_edge(obj.Shape, App.Vector(*centre), radius=radius))


def line(obj, through, direction=(1, 0, 0)):
    """The longest straight edge of `obj` along `direction` through the point `through` (the
    part's own frame)."""
    inv = obj.Placement.inverse()
    through, direction = App.Vector(*through), App.Vector(*direction)
    best = None
    for i, e in enumerate(obj.Shape.Edges):
        if e.Curve.TypeId != "Part::GeomLine":
            continue
        a, b = inv.multVec(e.Vertexes[0].Point), inv.multVec(e.Vertexes[-1].Point)
        d = b - a
        if d.cross(direction).Length > 1e-9 * d.Length:
            continue
        off = through - a
        if (off - direction * off.dot(direction)).Length < 1e-6 and (best is None or d.Length > best[0]):
            best = (d.Length, i)
    if best is None:
        raise ValueError("%s has no straight edge along %s through %s" % (obj.Label, direction, through))
    return (obj, "Edge%d" % (best[1] + 1))


def three_gears(doc):
    asm = da.create_assembly(doc, "ThreeGears")
    plate = da.import_part(asm, step("gear-plate", lambda: parts.plate_with([(0, 0), (3, 0), (6.5, 0)], [], margin=2.3)),
                           "Plate", grounded=True)
    sizes = (("G1", 1.0, 20, (0, 0)), ("G2", 2.0, 40, (3, 0)), ("G3", 1.5, 30, (6.5, 0)))
    gears = {}
    for k, (name, r, z, (x, y)) in enumerate(sizes):
        g = da.import_part(asm, step("gear-%d" % z, lambda r=r, z=z: parts.gear(r, z)), name)
        place(g, x + 0.05 * k, y - 0.04, 0.12, 4.0 * k)  # roughly on its axle
        da.add_joint(asm, "Revolute", circle(plate, (x, y, 0.1), 0.15), circle(g, (0, 0, 0), r))
        gears[name] = (g, r)
    # The meshes: a pitch circle on each gear (the ratio is r1 / r2).
    da.add_joint(asm, "Gears", circle(gears["G1"][0], (0, 0, 0), 1.0), circle(gears["G2"][0], (0, 0, 0), 2.0))
    da.add_joint(asm, "Gears", circle(gears["G2"][0], (0, 0, 0), 2.0), circle(gears["G3"][0], (0, 0, 0), 1.5))
    return asm, {"Plate": plate, **{n: g for n, (g, _) in gears.items()}}


def planetary(doc, arm=1.5):
    asm = da.create_assembly(doc, "Planetary")
    base = da.import_part(asm, step("planet-base", lambda: parts.plate_with([(0, 0)], [], margin=2.4)),
                          "Base", grounded=True)
    carrier = da.import_part(asm, step("carrier-1.5", lambda: parts.carrier(arm)), "Carrier")
    sun = da.import_part(asm, step("gear-20", lambda: parts.gear(1.0, 20)), "Sun")
    ring = da.import_part(asm, step("ring-2", lambda: parts.ring_gear(2.0)), "Ring")
    place(carrier, 0.03, -0.02, 0.1, 7)
    place(sun, -0.02, 0.03, 0.2, 3)
    place(ring, 0.02, 0.02, 0.2, -5)
    axle = circle(base, (0, 0, 0.1), 0.15)
    da.add_joint(asm, "Revolute", axle, circle(carrier, (0, 0, 0), 0.15))
    # The sun and the ring turn on the same axle, a layer above the carrier.
    da.add_joint(asm, "Revolute", axle, circle(sun, (0, 0, 0), 1.0), offset=0.1)
    da.add_joint(asm, "Revolute", axle, circle(ring, (0, 0, 0), 2.0), offset=0.1)
    named = {"Base": base, "Carrier": carrier, "Sun": sun, "Ring": ring}
    planets = []
    for k in range(3):
        a = 2 * math.pi * k / 3
        x, y = arm * math.cos(a), arm * math.sin(a)
        planet = da.import_part(asm, step("gear-10", lambda: parts.gear(0.5, 10)), "Planet%d" % (k + 1))
        place(planet, x + 0.04, y - 0.03, 0.22, 10 * k)
        da.add_joint(asm, "Revolute", circle(carrier, (x, y, 0.1), 0.15), circle(planet, (0, 0, 0), 0.5))
        named[planet.Label] = planet
        planets.append(planet)
    # The gears on their axles first, then the meshes: three planets close three loops, whose
    # couplings agree only when made with every gear in place (a designer solves, then meshes).
    da.solve(asm)
    for planet in planets:
        da.add_joint(asm, "Gears", circle(sun, (0, 0, 0), 1.0), circle(planet, (0, 0, 0), 0.5))
        da.add_joint(asm, "Belt", circle(planet, (0, 0, 0), 0.5), circle(ring, (0, 0, 0), 2.0))
    return asm, named


def steering(doc):
    asm = da.create_assembly(doc, "Steering")
    kingpins = ((-2.0, -1.1), (2.0, -1.1))
    frame = da.import_part(asm, step("steering-frame", lambda: parts.plate_with(
        [(0, 0)] + list(kingpins), [(-1.5, -0.7, 0, 3.0, 0.2, 0.1)])), "Frame", grounded=True)
    pinion = da.import_part(asm, step("gear-12", lambda: parts.gear(0.3, 12, hub=0.1)), "Pinion")
    rack = da.import_part(asm, step("rack-2.6", lambda: parts.rack(2.6, (-1.0, 1.0))), "Rack")
    place(pinion, 0.02, 0.03, 0.12, 5)
    place(rack, 0.1, -0.42, 0.1)  # slides on the rail: its orientation as it will run
    da.add_joint(asm, "Revolute", circle(frame, (0, 0, 0.1), 0.15), circle(pinion, (0, 0, 0), 0.3))
    da.add_joint(asm, "Slider", line(frame, (0, -0.5, 0.1)), line(rack, (0, -0.1, 0)))
    da.add_joint(asm, "RackPinion", circle(pinion, (0, 0, 0), 0.3), line(rack, (0, 0.1, 0.1)))
    named = {"Frame": frame, "Pinion": pinion, "Rack": rack}
    arm = math.hypot(0.2, 0.7)
    for side, (kx, ky) in zip("LR", kingpins):
        s = -1 if side == "L" else 1
        knuckle = da.import_part(asm, step("link-%.3f" % arm, lambda: parts.link(arm)), "Knuckle" + side)
        tie = da.import_part(asm, step("link-0.8", lambda: parts.link(0.8)), "TieRod" + side)
        place(knuckle, kx, ky, 0.1, math.degrees(math.atan2(0.7, -0.2 * s)) + 3)
        place(tie, s * 1.0, -0.4, 0.2, 0 if s > 0 else 180)
        da.add_joint(asm, "Revolute", circle(frame, (kx, ky, 0.1), 0.15), circle(knuckle, (0, 0, 0), 0.15))
        da.add_joint(asm, "Revolute", circle(rack, (s * 1.0, 0, 0.1), 0.12), circle(tie, (0, 0, 0), 0.15))
        da.add_joint(asm, "Revolute", circle(knuckle, (arm, 0, 0.1), 0.15), circle(tie, (0.8, 0, 0), 0.15))
        named[knuckle.Label], named[tie.Label] = knuckle, tie
    return asm, named


def vice(doc, pitch=0.2, left=False):
    asm = da.create_assembly(doc, "Vice")
    frame = da.import_part(asm, step("vice-frame", parts.vice_frame), "Frame", grounded=True)
    screw = da.import_part(asm, step("lead-screw-3", lambda: parts.lead_screw(3.0)), "LeadScrew")
    jaw = da.import_part(asm, step("vice-jaw", parts.vice_jaw), "Jaw")
    place(screw, -1.0, 0.03, -0.02, 8, (1, 0, 0))
    place(jaw, 1.05, 0.0, 0.0)  # slides on the bed: its orientation as it will run
    da.add_joint(asm, "Screw", circle(frame, (0, 0, 0), 0.1), circle(screw, (3.0, 0, 0), 0.1),
                 pitch=pitch, left=left)
    da.add_joint(asm, "Slider", line(frame, (1.0, 0.5, -0.3)), line(jaw, (0, 0.5, -0.3)))
    da.add_joint(asm, "Revolute", circle(screw, (3.0, 0, 0), 0.1), circle(jaw, (0.4, 0, 0), 0.1))
    return asm, {"Frame": frame, "Screw": screw, "Jaw": jaw}


SAMPLES = (("three-gears", three_gears), ("planetary", planetary), ("steering", steering), ("vice", vice))
