"""Documents for test_fcstd.py, made in real FreeCAD (freecadcmd): the FreeCAD samples (STEP
parts, samples/freecad/build_samples.py) and documents with known answers. The output folder is
$DISPCON_FCSTD_OUT (freecadcmd takes arguments for files to open)."""
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(sys.argv[-1] if sys.argv[-1].endswith(".py") else __file__))
for arg in sys.argv:
    if arg.endswith("make_fcstd_docs.py"):
        HERE = os.path.dirname(os.path.abspath(arg))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "freecad_workbench"))
sys.path.insert(0, os.path.join(REPO, "samples", "freecad"))

import FreeCAD as App  # noqa: E402
import Part  # noqa: E402

import dispcon_fc.assembly as da  # noqa: E402
import parts  # noqa: E402

OUT = os.environ["DISPCON_FCSTD_OUT"]
os.makedirs(OUT, exist_ok=True)
FACTS = {}


def pin(obj, x, top=False):
    return (obj, parts.circle_edge(obj.Shape, App.Vector(x, 0, 0.1 if top else 0.0)))


def layered_fourbar(doc, a, b, c, d, crank_deg):
    """Ground pins at (0, 0) and (d, 0); crank a on the first, coupler b on the crank, rocker c
    under the coupler's end and on the second pin: every part in its own layer. The crank is
    placed at `crank_deg` (its joint's value then, counted from the pins' circles' x's), the rest
    roughly."""
    asm = da.create_assembly(doc, "Linkage")
    g = doc.addObject("Part::Feature", "Ground")
    g.Shape = parts.ground([(0, 0), (d, 0)])
    da.add_part(asm, g, grounded=True)
    crank, coupler, rocker = (doc.addObject("Part::Feature", n) for n in ("Crank", "Coupler", "Rocker"))
    crank.Shape, coupler.Shape, rocker.Shape = parts.link(a), parts.link(b), parts.link(c)
    for p in (crank, coupler, rocker):
        da.add_part(asm, p)
    t = math.radians(crank_deg)
    crank.Placement = App.Placement(App.Vector(0, 0, 0.1), App.Rotation(App.Vector(0, 0, 1), crank_deg))
    tip = App.Vector(a * math.cos(t), a * math.sin(t), 0.2)
    coupler.Placement = App.Placement(tip, App.Rotation(App.Vector(0, 0, 1), 10))
    rocker.Placement = App.Placement(App.Vector(d, 0, 0.1), App.Rotation(App.Vector(0, 0, 1), 100))
    joints = [da.add_joint(asm, "Revolute", pin(g, 0, top=True), pin(crank, 0)),
              da.add_joint(asm, "Revolute", pin(crank, a, top=True), pin(coupler, 0)),
              da.add_joint(asm, "Revolute", pin(coupler, b), pin(rocker, c, top=True)),
              da.add_joint(asm, "Revolute", pin(g, d, top=True), pin(rocker, 0))]
    joints[0].Label = "CrankPivot"
    return asm, g, crank, coupler, rocker


def save(doc, name):
    path = os.path.join(OUT, name + ".FCStd")
    doc.saveAs(path)
    App.closeDocument(doc.Name)
    return path


def double_rocker():
    # a = 2.2, b = 1.5, c = 2.5, d = 3: Grashof with the coupler shortest, so the input swings
    # between the poses where coupler and rocker are folded (|AD| = c - b) and stretched
    # (|AD| = b + c): cos(theta) = (a^2 + d^2 - |AD|^2) / (2 a d).
    a, b, c, d = 2.2, 1.5, 2.5, 3.0
    doc = App.newDocument("rocker")
    crank_deg = 60.0
    layered_fourbar(doc, a, b, c, d, crank_deg)
    stretched = math.acos((a * a + d * d - (b + c) ** 2) / (2 * a * d))
    folded = math.acos((a * a + d * d - (c - b) ** 2) / (2 * a * d))
    FACTS["double-rocker"] = {"crank_deg": crank_deg, "stretched": stretched, "folded": folded}
    save(doc, "double-rocker")


def obstacle():
    # A pin of radius rho at radius R, angle phi from the crank's pivot, in the crank's layer: the
    # crank (half width w) touches it while R sin|theta - phi| < w + rho.
    doc = App.newDocument("obstacle")
    crank_deg = 20.0
    asm, g, crank, coupler, rocker = layered_fourbar(doc, 1.0, 3.0, 2.5, 3.0, crank_deg)
    R, phi, rho, w = 0.7, 200.0, 0.02, 0.1
    pole = doc.addObject("Part::Feature", "Pole")
    pole.Shape = Part.makeCylinder(rho, 0.06, App.Vector(0, 0, 0))
    pole.Placement = App.Placement(App.Vector(R * math.cos(math.radians(phi)), R * math.sin(math.radians(phi)), 0.12),
                                   App.Rotation())
    da.add_part(asm, pole, grounded=True)
    half = math.degrees(math.asin((w + rho) / R))
    FACTS["obstacle"] = {"crank_deg": crank_deg, "first": phi - half, "last": phi + half}
    save(doc, "obstacle")


def conflicting():
    doc = App.newDocument("conflict")
    asm, g, crank, coupler, rocker = layered_fourbar(doc, 1.0, 3.0, 2.5, 3.0, 20.0)
    far = doc.addObject("Part::Feature", "Far")
    far.Shape = parts.ground([(9, 0)])
    da.add_part(asm, far, grounded=True)
    bad = da.add_joint(asm, "Ball", (far, parts.circle_edge(far.Shape, App.Vector(9, 0, 0))),
                       pin(rocker, 2.5, top=True))
    bad.Label = "Unreachable pin"
    asm.MaxIterations = 500
    save(doc, "conflicting")


def not_an_assembly():
    doc = App.newDocument("plain")
    box = doc.addObject("Part::Box", "Box")
    box.Label = "Just a box"
    doc.recompute()
    save(doc, "not-an-assembly")


def linked_part_gone():
    library = App.newDocument("library")
    bar = library.addObject("Part::Feature", "LibraryBar")
    bar.Shape = parts.link(2.0)
    library_path = os.path.join(OUT, "library-gone.FCStd")
    library.saveAs(library_path)
    doc = App.newDocument("linked")
    doc.saveAs(os.path.join(OUT, "linked-gone.FCStd"))
    asm = da.create_assembly(doc)
    base = doc.addObject("Part::Feature", "Base")
    base.Shape = parts.ground([(0, 0)])
    da.add_part(asm, base, grounded=True)
    linked = da.link_part(asm, library_path, "LibraryBar")
    linked.Label = "Borrowed bar"
    da.add_joint(asm, "Revolute", pin(base, 0, top=True), (linked, parts.circle_edge(da.shape_of(linked), App.Vector(0, 0, 0))))
    doc.save()
    App.closeDocument(doc.Name)
    App.closeDocument(library.Name)
    os.remove(library_path)


double_rocker()
obstacle()
conflicting()
not_an_assembly()
linked_part_gone()
with open(os.path.join(OUT, "facts.json"), "w") as f:
    json.dump(FACTS, f, indent=2)
print("documents in", OUT)
