"""The workbench's scripting API in real FreeCAD (freecadcmd): build assemblies from parts and
picked sub-elements, solve, drag, save, reopen, against analytic answers."""
import math
import os
import sys
import tempfile
import traceback

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "freecad_workbench"))
sys.path.insert(0, os.path.join(REPO, "samples", "freecad"))

import FreeCAD as App  # noqa: E402

import dispcon_fc.assembly as da  # noqa: E402
import parts  # noqa: E402

A, B, C, D = 1.0, 3.0, 2.5, 3.0


def freudenstein(t):
    Ax, Ay = A * math.cos(t), A * math.sin(t)
    L = math.hypot(D - Ax, Ay)
    x = (B * B - C * C + L * L) / (2 * L)
    h = math.sqrt(B * B - x * x)
    ux, uy = (D - Ax) / L, -Ay / L
    Bx, By = Ax + x * ux - h * uy, Ay + x * uy + h * ux
    return math.atan2(By, Bx - D)


def angle_of(obj):
    x = obj.Placement.Rotation.multVec(App.Vector(1, 0, 0))
    return math.atan2(x.y, x.x)


def fourbar(doc, tmp):
    """Ground plate, crank, coupler and rocker as real parts; the crank and the rocker come from
    STEP files; revolutes from picked circular edges."""
    asm = da.create_assembly(doc)
    g = doc.addObject("Part::Feature", "Ground")
    g.Shape = parts.ground([(0, 0), (D, 0)])
    da.add_part(asm, g, grounded=True)
    crank = da.import_part(asm, parts.write_step(parts.link(A), os.path.join(tmp, "crank.step")))
    coupler = doc.addObject("Part::Feature", "Coupler")
    coupler.Shape = parts.link(B)
    da.add_part(asm, coupler)
    rocker = da.import_part(asm, parts.write_step(parts.link(C), os.path.join(tmp, "rocker.step")))
    # Rough placements, off their joints.
    crank.Placement = App.Placement(App.Vector(0.1, -0.1, 0.05), App.Rotation(App.Vector(0, 0, 1), 23))
    coupler.Placement = App.Placement(App.Vector(1.2, 0.6, -0.1), App.Rotation(App.Vector(0, 0, 1), 11))
    rocker.Placement = App.Placement(App.Vector(2.9, 0.2, 0.1), App.Rotation(App.Vector(0, 0, 1), 109))

    def pin(obj, local):
        return (obj, parts.circle_edge(obj.Shape, App.Vector(*local)))

    da.add_joint(asm, "Revolute", pin(g, (0, 0, 0)), pin(crank, (0, 0, 0)))
    da.add_joint(asm, "Revolute", pin(crank, (A, 0, 0)), pin(coupler, (0, 0, 0)))
    da.add_joint(asm, "Revolute", pin(coupler, (B, 0, 0)), pin(rocker, (C, 0, 0)))
    da.add_joint(asm, "Revolute", pin(g, (D, 0, 0)), pin(rocker, (0, 0, 0)))
    return asm, g, crank, coupler, rocker


FAILED = []


def same(p, q, tol):
    """Two placements equal within tol (position and rotation)."""
    return (p.Base - q.Base).Length <= tol and abs(p.Rotation.multiply(q.Rotation.inverted()).Angle) <= tol


TESTS = []


def test(fn):
    TESTS.append(fn)
    return fn


def run(fn):
    try:
        fn()
        print("ok   " + fn.__name__)
    except Exception:
        FAILED.append(fn.__name__)
        print("FAIL " + fn.__name__)
        traceback.print_exc()
    return fn


@test
def test_fourbar_snaps_and_follows_freudenstein():
    with tempfile.TemporaryDirectory() as tmp:
        doc = App.newDocument("fourbar")
        asm, g, crank, coupler, rocker = fourbar(doc, tmp)
        ground_before = g.Placement
        r = da.solve(asm)
        assert r.converged, r.message
        assert same(g.Placement, ground_before, 1e-12), "the grounded part moved"
        t = angle_of(crank)
        assert abs(angle_of(rocker) - freudenstein(t)) < 1e-8, (angle_of(rocker), freudenstein(t))
        # Drag the crank by 60 degrees: the rocker follows the closure.
        target = App.Placement(App.Vector(0, 0, 0), App.Rotation(App.Vector(0, 0, 1), math.degrees(t) + 60))
        r = da.drag(asm, crank, target, steps=30)
        assert r.converged, r.message
        assert abs(angle_of(crank) - (t + math.radians(60))) < 1e-9
        err = abs(math.remainder(angle_of(rocker) - freudenstein(angle_of(crank)), 2 * math.pi))
        assert err < 1e-8, err
        report = da.check(asm)
        assert report["dof"] == 1, report
        App.closeDocument(doc.Name)


@test
def test_failed_solve_moves_nothing_and_names_the_joint():
    with tempfile.TemporaryDirectory() as tmp:
        doc = App.newDocument("conflict")
        asm, g, crank, coupler, rocker = fourbar(doc, tmp)
        # A pin that cannot be reached: the rocker's tip to a boss 6 away from its pivot.
        far = doc.addObject("Part::Feature", "Far")
        far.Shape = parts.ground([(9, 0)])
        da.add_part(asm, far, grounded=True)
        bad = da.add_joint(asm, "Ball", (far, parts.circle_edge(far.Shape, App.Vector(9, 0, 0))),
                           (rocker, parts.circle_edge(rocker.Shape, App.Vector(C, 0, 0))))
        asm.MaxIterations = 500
        before = [p.Placement for p in (crank, coupler, rocker)]
        r = da.solve(asm)
        assert not r.converged
        assert bad in r.violated and bad.Violated, r.message
        assert bad.Label in r.message
        for p, pl in zip((crank, coupler, rocker), before):
            assert same(p.Placement, pl, 1e-12), "a failed solve moved %s" % p.Label
        report = da.check(asm)
        assert report["conflicting"] == [bad], report
        App.closeDocument(doc.Name)


@test
def test_saved_and_reopened_intact():
    with tempfile.TemporaryDirectory() as tmp:
        doc = App.newDocument("saved")
        asm, g, crank, coupler, rocker = fourbar(doc, tmp)
        da.set_limits(da.joints(asm)[0], rotation=(-170, 170))
        assert da.solve(asm).converged
        path = os.path.join(tmp, "fourbar.FCStd")
        doc.saveAs(path)
        rocker_before, rocker_name = rocker.Placement, rocker.Name
        App.closeDocument(doc.Name)
        doc = App.openDocument(path)
        asm = doc.getObject("Assembly")
        js = da.joints(asm)
        assert len(js) == 4 and [j.JointType for j in js] == ["Revolute"] * 4
        assert js[0].HasRotationLimits and abs(js[0].RotationMax.Value - 170) < 1e-9
        assert js[2].Reference1[0].Name == "Coupler"
        assert doc.getObject("Ground").Grounded
        assert same(doc.getObject(rocker_name).Placement, rocker_before, 1e-12)
        r = da.solve(asm)
        assert r.converged and r.iterations == 0, r.message
        App.closeDocument(doc.Name)


@test
def test_undo_restores_the_placements():
    with tempfile.TemporaryDirectory() as tmp:
        doc = App.newDocument("undo")
        doc.UndoMode = 1
        asm, g, crank, coupler, rocker = fourbar(doc, tmp)
        before = rocker.Placement
        assert da.solve(asm).converged
        assert not same(rocker.Placement, before, 1e-9)
        doc.undo()
        assert same(rocker.Placement, before, 1e-12), "undo did not restore the solve"
        App.closeDocument(doc.Name)


@test
def test_dcl_round_trip():
    with tempfile.TemporaryDirectory() as tmp:
        doc = App.newDocument("dcl")
        asm, g, crank, coupler, rocker = fourbar(doc, tmp)
        path = os.path.join(tmp, "fourbar.dcl")
        da.export_dcl(asm, path)
        dispcon = da.engine.load()
        m = dispcon.load(path)
        assert m.assemble().converged
        m.save(path)
        da.import_dcl(asm, path)
        assert da.solve(asm).iterations == 0
        App.closeDocument(doc.Name)


@test
def test_interference_at_the_pose_and_along_a_sweep():
    import Part

    with tempfile.TemporaryDirectory() as tmp:
        doc = App.newDocument("clash")
        asm, g, crank, coupler, rocker = fourbar(doc, tmp)
        assert da.solve(asm).converged
        # An obstacle where the crank passes when it points down (angle -90 degrees).
        block = doc.addObject("Part::Feature", "Block")
        block.Shape = Part.makeBox(0.2, 0.2, 0.3, App.Vector(-0.1, -0.9, -0.1))
        da.add_part(asm, block, grounded=True)
        # Parts hinged together touch at their bosses by design: only the block counts here.
        touching = [(j.Reference1[0], j.Reference2[0]) for j in da.joints(asm)]
        at_pose = [(a.Name, b.Name) for a, b, v in da.interference(asm)
                   if (a, b) not in touching and (b, a) not in touching]
        assert at_pose == [], at_pose
        before = crank.Placement
        hits = da.interference_along(asm, da.joints(asm)[0], range(0, 360, 10), ignore=touching)
        # (The coplanar links also cross each other's bosses on the way: real clashes of this
        # design, reported too; the block's are the ones placed on purpose.)
        block_hits = [(t, a, b) for t, a, b, _ in hits if "Block" in (a.Name, b.Name)]
        crank_hits = [t for t, a, b in block_hits if crank.Name in (a.Name, b.Name)]
        assert crank_hits, "the crank never met the block"
        # Only the crank and the coupler's boss on its tip come near the block.
        assert all({a.Name, b.Name} <= {"Block", crank.Name, coupler.Name} for _, a, b in block_hits)
        angles = sorted({round(t) for t in crank_hits})
        start = math.degrees(angle_of(crank))
        assert all(abs(math.remainder(math.radians(start + t + 90), 2 * math.pi)) < math.radians(40)
                   for t in angles), (start, angles)
        assert same(crank.Placement, before, 1e-12), "the sweep did not put the parts back"
        App.closeDocument(doc.Name)


@test
def test_iges_brep_and_linked_parts():
    with tempfile.TemporaryDirectory() as tmp:
        # A pendulum: an IGES bar hinged to a BREP post, and a linked bar from another .FCStd
        # hinged to the IGES bar's tip.
        iges = os.path.join(tmp, "bar.iges")
        parts.link(1.0).exportIges(iges)
        brep = os.path.join(tmp, "post.brep")
        parts.ground([(0, 0)]).exportBrep(brep)
        library = App.newDocument("library")
        lib_bar = library.addObject("Part::Feature", "LibraryBar")
        lib_bar.Shape = parts.link(2.0)
        library_path = os.path.join(tmp, "library.FCStd")
        library.saveAs(library_path)
        doc = App.newDocument("formats")
        asm = da.create_assembly(doc)
        try:
            da.link_part(asm, library_path, "LibraryBar")
            raise AssertionError("linking from an unsaved document should be refused")
        except ValueError as e:
            assert "save" in str(e)
        doc.saveAs(os.path.join(tmp, "formats.FCStd"))
        # A file that is not there, or not a CAD file, is refused and adds nothing.
        before = sorted(o.Name for o in doc.Objects)
        for bad in (os.path.join(tmp, "missing.step"), os.path.join(tmp, "library.FCStd")):
            try:
                da.import_part(asm, bad)
            except ValueError as e:
                assert str(e).startswith(bad + ": "), e
            else:
                raise AssertionError("importing %s should fail" % bad)
            assert sorted(o.Name for o in doc.Objects) == before
        post = da.import_part(asm, brep, grounded=True)
        bar = da.import_part(asm, iges)
        linked = da.link_part(asm, library_path, "LibraryBar")
        bar.Placement = App.Placement(App.Vector(0.1, 0.1, 0), App.Rotation(App.Vector(0, 0, 1), 30))
        linked.Placement = App.Placement(App.Vector(1.2, 0.3, 0), App.Rotation(App.Vector(0, 0, 1), -20))
        shape = da.shape_of
        da.add_joint(asm, "Revolute", (post, parts.circle_edge(shape(post), App.Vector(0, 0, 0))),
                     (bar, parts.circle_edge(shape(bar), App.Vector(0, 0, 0))))
        da.add_joint(asm, "Revolute", (bar, parts.circle_edge(shape(bar), App.Vector(1, 0, 0))),
                     (linked, parts.circle_edge(shape(linked), App.Vector(0, 0, 0))))
        r = da.solve(asm)
        assert r.converged, r.message
        tip = bar.Placement.multVec(App.Vector(1, 0, 0))
        assert (linked.Placement.Base - tip).Length < 1e-9
        assert abs(tip.Length - 1) < 1e-9 and abs(tip.z) < 1e-9
        assert da.check(asm)["dof"] == 2
        App.closeDocument(doc.Name)
        App.closeDocument(library.Name)


@test
def test_slider_crank_from_picked_faces_and_edges():
    doc = App.newDocument("slider")
    asm = da.create_assembly(doc)
    g = doc.addObject("Part::Feature", "Ground")
    g.Shape = parts.ground([(0, 0)])
    da.add_part(asm, g, grounded=True)
    crank = doc.addObject("Part::Feature", "Crank")
    crank.Shape = parts.link(1.0)
    rod = doc.addObject("Part::Feature", "Rod")
    rod.Shape = parts.link(3.0)
    piston = doc.addObject("Part::Feature", "Piston")
    piston.Shape = parts.piston()
    for p in (crank, rod, piston):
        da.add_part(asm, p)
    crank.Placement = App.Placement(App.Vector(0, 0, 0.05), App.Rotation(App.Vector(0, 0, 1), 30))
    rod.Placement = App.Placement(App.Vector(0.8, 0.5, 0), App.Rotation(App.Vector(0, 0, 1), -10))
    piston.Placement = App.Placement(App.Vector(3.5, 0.1, 0), App.Rotation())
    edge = lambda o, pt: (o, parts.circle_edge(o.Shape, App.Vector(*pt)))
    da.add_joint(asm, "Revolute", edge(g, (0, 0, 0)), edge(crank, (0, 0, 0)))
    da.add_joint(asm, "Revolute", edge(crank, (1, 0, 0)), edge(rod, (0, 0, 0)))
    # The piston: its bottom face (a plane) carries the wrist pin at its centre.
    bottom = next("Face%d" % (i + 1) for i, f in enumerate(piston.Shape.Faces)
                  if abs(f.CenterOfMass.z) < 1e-9)
    da.add_joint(asm, "Ball", edge(rod, (3, 0, 0)), (piston, bottom))
    # The slider along the ground's straight edge along x (y = -1 line of the plate, through z = 0).
    def along_x(shape, y):
        # The straight edge along x at height 0 and this y: what a designer clicks for the slot.
        local = shape.Placement.inverse()
        for i, e in enumerate(shape.Edges):
            a, b = local.multVec(e.Vertexes[0].Point), local.multVec(e.Vertexes[-1].Point)
            if (e.Curve.TypeId == "Part::GeomLine" and abs(a.z) < 1e-9 and abs(b.z) < 1e-9
                    and abs(a.y - y) < 1e-9 and abs(b.y - y) < 1e-9 and abs(b.x - a.x) > 0.1):
                return "Edge%d" % (i + 1)
        raise ValueError("no edge along x at y = %g" % y)

    line = along_x(g.Shape, -0.3)
    piston_edge = along_x(piston.Shape, -0.2)
    da.add_joint(asm, "Slider", (g, line), (piston, piston_edge))
    r = da.solve(asm)
    assert r.converged, r.message
    # The piston's bottom edge lies on the plate's edge line: y = -1 for its edge at y = -0.2.
    t = angle_of(crank)
    pin = piston.Placement.Base
    expected = math.cos(t) + math.sqrt(9 - (math.sin(t) - pin.y) ** 2)
    assert abs(pin.y + 0.1) < 1e-8, pin  # the slot's line is 0.1 below the crank's pivot
    assert abs(pin.x - expected) < 1e-8, (pin.x, expected)
    assert abs(piston.Placement.Rotation.Angle) < 1e-8
    App.closeDocument(doc.Name)


if not os.environ.get("DISPCON_IMPORT_ONLY"):
    for fn in TESTS:
        run(fn)
    print("%d passed, %d failed" % (len(TESTS) - len(FAILED), len(FAILED)))
    if FAILED:
        sys.exit(1)
