"""Builds the FreeCAD samples from the STEP parts in samples/freecad/parts/: a crank-rocker
four-bar, a slider-crank engine and a spatial RSSR linkage, each an assembly with picked joints,
snapped into place. Run with freecadcmd:

    freecadcmd samples/freecad/build_samples.py --out build/samples

Writes fourbar.FCStd, slider-crank.FCStd, rssr.FCStd, fourbar-clash.FCStd (a post in the
crank's way: a design that collides), side-rods.FCStd (twenty parts) and the couplings of
couplings.py (three-gears, planetary, steering, vice), and prints the time of each snap. Then the
reused sub-assembly: leg.FCStd (a four-bar leg on its hip plate) placed four times on a frame,
linked from that file, in walker.FCStd (flexible: each leg moves, here each at another crank
angle) and walker-rigid.FCStd (rigid: each leg moves as one part); and nested: walker.FCStd placed
twice on a track in parade.FCStd (flexible walkers of flexible legs, 8 degrees of freedom)."""
import math
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(sys.argv[-1] if sys.argv[-1].endswith(".py") else __file__))
for arg in sys.argv:
    if arg.endswith("build_samples.py"):
        HERE = os.path.dirname(os.path.abspath(arg))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "freecad_workbench"))
sys.path.insert(0, HERE)

import FreeCAD as App  # noqa: E402

import couplings  # noqa: E402
import dispcon_fc.assembly as da  # noqa: E402
import parts  # noqa: E402

PARTS = os.path.join(HERE, "parts")


def step(name, shape_fn):
    """The STEP file of a part, written from parts.py when missing."""
    path = os.path.join(PARTS, name + ".step")
    if not os.path.exists(path):
        parts.write_step(shape_fn(), path)
    return path


def pin(obj, local, top=False):
    """The pin at `local`: its boss's bottom circle, or its top one (the part above sits there:
    parts stack in layers and touch without overlapping)."""
    x, y, z = local
    return (obj, parts.circle_edge(obj.Shape, App.Vector(x, y, z + (0.1 if top else 0.0))))


def place(obj, x, y, z, deg=0.0, axis=(0, 0, 1)):
    obj.Placement = App.Placement(App.Vector(x, y, z), App.Rotation(App.Vector(*axis), deg))


def fourbar(doc):
    asm = da.create_assembly(doc, "FourBar")
    g = da.import_part(asm, step("ground-3", lambda: parts.ground([(0, 0), (3, 0)])), "Ground", grounded=True)
    crank = da.import_part(asm, step("link-1", lambda: parts.link(1)), "Crank")
    coupler = da.import_part(asm, step("link-3", lambda: parts.link(3)), "Coupler")
    rocker = da.import_part(asm, step("link-2.5", lambda: parts.link(2.5)), "Rocker")
    # Layers: the crank and the rocker on the ground's bosses, the coupler on top of them.
    place(crank, 0.1, -0.1, 0.15, 23)
    place(coupler, 1.2, 0.6, 0.2, 11)
    place(rocker, 2.9, 0.2, 0.1, 109)
    da.add_joint(asm, "Revolute", pin(g, (0, 0, 0), top=True), pin(crank, (0, 0, 0)))
    da.add_joint(asm, "Revolute", pin(crank, (1, 0, 0), top=True), pin(coupler, (0, 0, 0)))
    da.add_joint(asm, "Revolute", pin(coupler, (3, 0, 0)), pin(rocker, (2.5, 0, 0), top=True))
    da.add_joint(asm, "Revolute", pin(g, (3, 0, 0), top=True), pin(rocker, (0, 0, 0)))
    return asm


def fourbar_clash(doc):
    """The four-bar with a post standing where the crank passes (pointing down, -y): a design
    that collides, for the CI example's failure."""
    asm = fourbar(doc)
    asm.Label = "FourBarClash"
    post = da.import_part(asm, step("stop-post", lambda: parts.block(0.2, 0.2, 0.3)), "Stop", grounded=True)
    place(post, -0.1, -1.0, 0.0)
    return asm


def slider_crank(doc):
    asm = da.create_assembly(doc, "SliderCrank")
    g = da.import_part(asm, step("ground-rail", lambda: parts.ground_with_rail([(0, 0)], (1.5, 5.0))),
                       "Ground", grounded=True)
    crank = da.import_part(asm, step("link-1", lambda: parts.link(1)), "Crank")
    rod = da.import_part(asm, step("link-3", lambda: parts.link(3)), "Rod")
    piston = da.import_part(asm, step("piston", parts.piston), "Piston")
    # Layers: the crank on the ground's boss, the rod on the crank, the piston under the rod's
    # end, sliding on the rail.
    place(crank, 0, 0, 0.15, 30)
    place(rod, 0.8, 0.5, 0.2, -10)
    place(piston, 3.5, 0.1, 0.1)
    da.add_joint(asm, "Revolute", pin(g, (0, 0, 0), top=True), pin(crank, (0, 0, 0)))
    da.add_joint(asm, "Revolute", pin(crank, (1, 0, 0), top=True), pin(rod, (0, 0, 0)))
    top = parts.face_at_height(piston.Shape, 0.1)
    da.add_joint(asm, "Ball", pin(rod, (3, 0, 0)), (piston, top))
    da.add_joint(asm, "Slider", (g, parts.line_edge_along_x(g.Shape, -0.3, 0.1)),
                 (piston, parts.line_edge_along_x(piston.Shape, -0.2)))
    return asm


def rssr(doc):
    """A spatial RSSR linkage: a crank turning about z, a rod with ball joints at both ends, and a
    rocker turning about x on a post."""
    asm = da.create_assembly(doc, "RSSR")
    g = da.import_part(asm, step("ground-1", lambda: parts.ground([(0, 0)])), "Ground", grounded=True)
    post = da.import_part(asm, step("post-x", parts.post), "Post", grounded=True)
    place(post, 2.0, 1.0, 0.8)
    crank = da.import_part(asm, step("link-1", lambda: parts.link(1)), "Crank")
    rod = da.import_part(asm, step("link-2.5", lambda: parts.link(2.5)), "Rod")
    rocker = da.import_part(asm, step("link-1.5", lambda: parts.link(1.5)), "Rocker")
    place(crank, 0, 0, 0.12, 20)
    place(rod, 0.9, 0.4, 0.4, 25)
    rocker.Placement = App.Placement(App.Vector(2.2, 1.0, 0.8),
                                     App.Rotation(App.Vector(0, 1, 0), 90).multiply(App.Rotation(App.Vector(0, 0, 1), -60)))
    da.add_joint(asm, "Revolute", pin(g, (0, 0, 0), top=True), pin(crank, (0, 0, 0)))
    da.add_joint(asm, "Ball", pin(crank, (1, 0, 0), top=True), pin(rod, (0, 0, 0)))
    da.add_joint(asm, "Ball", pin(rod, (2.5, 0, 0)), pin(rocker, (1.5, 0, 0)))
    # The rocker beside the post's boss (its far end circle), not through it.
    da.add_joint(asm, "Revolute", pin(post, (0.1, 0, 0)), pin(rocker, (0, 0, 0)))
    return asm


def side_rods(doc, cranks=18, pitch=3.0):
    """Twenty parts: `cranks` cranks on a ground's bosses, all pinned to one side rod on top (a
    locomotive's wheels): one degree of freedom, many redundant joints. The speed sample."""
    asm = da.create_assembly(doc, "SideRods")
    xs = [pitch * k for k in range(cranks)]
    g = da.import_part(asm, step("ground-%d" % cranks, lambda: parts.ground([(x, 0) for x in xs])),
                       "Ground", grounded=True)
    rod = da.import_part(asm, step("side-rod-%d" % cranks, lambda: parts.bar(xs)), "SideRod")
    place(rod, 0.9, 0.2, 0.2, 2)
    for k, x in enumerate(xs):
        crank = da.import_part(asm, step("link-1", lambda: parts.link(1)), "Crank%d" % (k + 1))
        place(crank, x, 0, 0.1, 10)
        da.add_joint(asm, "Revolute", pin(g, (x, 0, 0), top=True), pin(crank, (0, 0, 0)))
        da.add_joint(asm, "Revolute", pin(crank, (1, 0, 0), top=True), pin(rod, (x, 0, 0)))
    return asm


def leg(doc):
    """The leg: the four-bar on its hip plate (the plate grounded in this file)."""
    asm = fourbar(doc)
    asm.Label = "Leg"
    next(p for p in da.parts(asm) if p.Label == "Ground").Label = "Hip"
    return asm


LEGS = ((0, 0), (6, 0), (0, 6), (6, 6))


def walker(doc, leg_path, rigid):
    """A frame with four bosses and the leg of `leg_path` placed on each, linked from that file:
    each leg's hip bolted to the frame (a Fixed joint from the boss's top to the hip's pin, 0.1
    above it so the plates touch). Flexible: 4 degrees of freedom (a crank per leg); rigid: 0."""
    asm = da.create_assembly(doc, "Walker")
    frame = da.import_part(asm, step("frame-4", lambda: parts.frame(LEGS)), "Frame", grounded=True)
    for k, (x, y) in enumerate(LEGS):
        sub = da.insert_sub_assembly(asm, leg_path, placement=App.Placement(App.Vector(x, y, 0.2), App.Rotation()),
                                     rigid=rigid, name="Leg%d" % (k + 1))
        hip = next(p for p in da.instance_parts(sub) if p.LinkedObject.Label == "Hip")
        edge = parts.circle_edge(hip.LinkedObject.Shape, App.Vector(0, 0, 0))
        da.add_joint(asm, "Fixed", pin(frame, (x, y, 0), top=True), (sub, "Hip." + edge), offset=0.1)
    return asm


def crank_phases(asm, degrees=(0, 90, 180, 270)):
    """Turns each flexible leg's crank by its own angle about its hip pin: the legs in four poses."""
    for sub, deg in zip(da.sub_assemblies(asm), degrees):
        crank = next(p for p in da.instance_parts(sub) if p.LinkedObject.Label == "Crank")
        pivot = crank.Placement.multVec(App.Vector(0, 0, 0))
        turn = App.Rotation(App.Vector(0, 0, 1), deg)
        start = crank.Placement
        da.drag(asm, crank, App.Placement(pivot + turn.multVec(start.Base - pivot), turn.multiply(start.Rotation)),
                steps=max(2, int(deg / 10)))


def build_walkers(out):
    """leg.FCStd, then walker.FCStd (flexible legs in four poses) and walker-rigid.FCStd."""
    doc = App.newDocument("leg")
    r = da.solve(leg(doc))
    leg_path = os.path.abspath(os.path.join(out, "leg.FCStd"))
    doc.saveAs(leg_path)
    print("leg: %s" % r.message)
    made = []
    for name, rigid in (("walker", False), ("walker-rigid", True)):
        d = App.newDocument(name.replace("-", "_"))
        d.saveAs(os.path.join(out, name + ".FCStd"))  # linking from another file needs a saved document
        asm = walker(d, leg_path, rigid)
        t0 = time.perf_counter()
        r = da.solve(asm)
        elapsed = time.perf_counter() - t0
        if r.converged and not rigid:
            crank_phases(asm)
        print("%s: %s, snap %.1f ms, %d degrees of freedom" % (name, r.message, 1000 * elapsed, da.check(asm)["dof"]))
        if not r.converged:
            sys.exit(1)
        d.save()
        made.append(d)
        # Saved twice (before linking, and done): FreeCAD kept the first as a backup, walker.FCStd1.
        backup = d.FileName + "1"
        if os.path.exists(backup):
            os.remove(backup)
    for d in made + [doc]:
        App.closeDocument(d.Name)


STANDS = ((0, 0), (12, 0))


def build_parade(out):
    """parade.FCStd: walker.FCStd (itself four legs of leg.FCStd) placed twice on a track,
    flexible, each walker's frame bolted to its stand (a Fixed joint from the stand's top to the
    frame's first boss, 0.2 above): nested sub-assemblies, 8 degrees of freedom (4 per walker)."""
    doc = App.newDocument("parade")
    doc.saveAs(os.path.join(out, "parade.FCStd"))
    asm = da.create_assembly(doc, "Parade")
    track = doc.addObject("Part::Feature", "Track")
    track.Shape = parts.frame(STANDS)
    da.add_part(asm, track, grounded=True)
    edge = parts.circle_edge(parts.frame(LEGS), App.Vector(0, 0, 0))
    for k, (x, y) in enumerate(STANDS):
        walk = da.insert_sub_assembly(asm, os.path.join(out, "walker.FCStd"), rigid=False, name="Walk%d" % (k + 1),
                                      placement=App.Placement(App.Vector(x, y, 0.3), App.Rotation()))
        da.add_joint(asm, "Fixed", pin(track, (x, y, 0), top=True), (walk, "Frame." + edge), offset=0.2)
    t0 = time.perf_counter()
    r = da.solve(asm)
    elapsed = time.perf_counter() - t0
    print("parade: %s, snap %.1f ms, %d degrees of freedom" % (r.message, 1000 * elapsed, da.check(asm)["dof"]))
    if not r.converged:
        sys.exit(1)
    doc.save()
    backup = doc.FileName + "1"
    if os.path.exists(backup):
        os.remove(backup)
    App.closeDocument(doc.Name)


SAMPLES = (("fourbar", fourbar), ("slider-crank", slider_crank), ("rssr", rssr),
           ("fourbar-clash", fourbar_clash), ("side-rods", side_rods))
if set(da.COUPLINGS) <= set(da.offered_types(da.engine.load())):
    # The couplings (couplings.py): gears, a planetary set, a steering rack, a vice; when the
    # engine has their rows (it says so below otherwise).
    SAMPLES += tuple((name, lambda doc, build=build: build(doc)[0]) for name, build in couplings.SAMPLES)
else:
    print("%s: not built (this engine has no coupling rows)" % ", ".join(n for n, _ in couplings.SAMPLES))


def main():
    out = sys.argv[sys.argv.index("--out") + 1] if "--out" in sys.argv else os.path.join(REPO, "build", "samples")
    os.makedirs(out, exist_ok=True)
    for name, build in SAMPLES:
        doc = App.newDocument(name.replace("-", "_"))
        asm = build(doc)
        t0 = time.perf_counter()
        r = da.solve(asm)
        elapsed = time.perf_counter() - t0
        print("%s: %s, snap %.1f ms" % (name, r.message, 1000 * elapsed))
        if not r.converged:
            sys.exit(1)
        doc.saveAs(os.path.join(out, name + ".FCStd"))
        App.closeDocument(doc.Name)
    build_walkers(out)
    build_parade(out)


main()
# freecadcmd opens every argument after the script as a document once the script returns ("File
# format not supported: DIR" for --out's folder): leaving here ends the run before that.
sys.exit(0)
