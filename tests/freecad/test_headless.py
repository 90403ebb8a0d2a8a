"""The workbench's scripting API in real FreeCAD (freecadcmd): build assemblies from parts and
picked sub-elements, solve, drag, save, reopen, against analytic answers."""
import ast
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import traceback
import unittest

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
    return angle_of_placement(obj.Placement)


def angle_of_placement(pl):
    x = pl.Rotation.multVec(App.Vector(1, 0, 0))
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
        # Named by the result; the joint's Violated, like every other bit, as it was.
        assert bad in r.violated and not bad.Violated, r.message
        assert bad.Label in r.message
        for p, pl in zip((crank, coupler, rocker), before):
            assert same(p.Placement, pl, 1e-12), "a failed solve moved %s" % p.Label
        report = da.check(asm)
        assert report["conflicting"] == [bad], report
        App.closeDocument(doc.Name)


@test
def test_failed_solve_is_no_undo_step_and_writes_nothing():
    """A failed Solve leaves no undo step and no property written or object touched: the first
    undo takes back the joint that made it fail (the third audit found "Solve assembly" in the
    undo list, its Residual, Violated and LastSolve, before "Add joint"). Saved after that undo
    and reopened, nothing is touched."""
    with tempfile.TemporaryDirectory() as tmp:
        doc = App.newDocument("conflictundo")
        doc.UndoMode = 1
        asm, g, crank, coupler, rocker = fourbar(doc, tmp)
        asm_name = asm.Name
        assert da.solve(asm).converged
        far = doc.addObject("Part::Feature", "Far")
        far.Shape = parts.ground([(9, 0)])
        da.add_part(asm, far, grounded=True)
        doc.recompute()
        bad = da.add_joint(asm, "Ball", (far, parts.circle_edge(far.Shape, App.Vector(9, 0, 0))),
                           (rocker, parts.circle_edge(rocker.Shape, App.Vector(C, 0, 0))))
        bad.Label = "Rod-to-ground"
        doc.recompute()
        undo_names = list(doc.UndoNames)
        assert undo_names[0] == "Add joint", undo_names
        values = {(o.Name, p): repr(o.getPropertyByName(p)) for o in doc.Objects for p in o.PropertiesList
                  if p not in ("Shape", "Proxy")}
        r = da.solve(asm)
        assert not r.converged and bad in r.violated, r.message
        assert list(doc.UndoNames) == undo_names, doc.UndoNames
        after = {(o.Name, p): repr(o.getPropertyByName(p)) for o in doc.Objects for p in o.PropertiesList
                 if p not in ("Shape", "Proxy")}
        changed = sorted(k for k in values if values[k] != after[k])
        assert not changed, changed
        touched = [o.Name for o in doc.Objects if "Touched" in o.State]
        assert not touched, touched
        # A drag and a drive of the assembly that does not hold are refused with no step either.
        for refused in (lambda: da.drag(asm, coupler, App.Placement(App.Vector(1, 1, 0), App.Rotation())),
                        lambda: da.drive_to(asm, da.joints(asm)[0], 30.0)):
            try:
                refused()
                raise AssertionError("moved an assembly that does not hold")
            except ValueError as e:
                assert "does not hold" in str(e), e
            assert list(doc.UndoNames) == undo_names, doc.UndoNames
        name = bad.Name
        doc.undo()  # the joint goes, not the failed Solve's marks
        assert doc.getObject(name) is None, doc.UndoNames
        # The undo changed the Assembly's Group with no recompute after: touched, and FreeCAD
        # saves the mark. The reopened document has nothing touched (the Assembly computes
        # nothing; the third audit's reopened slider-crank showed it touched).
        assert "Touched" in asm.State, asm.State
        path = os.path.join(tmp, "undone.FCStd")
        doc.saveAs(path)
        App.closeDocument(doc.Name)
        doc = App.openDocument(path)
        touched = [o.Name for o in doc.Objects if "Touched" in o.State]
        assert not touched, touched
        asm = doc.getObject(asm_name)
        assert da.solve(asm).converged
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
    line = parts.line_edge_along_x(g.Shape, -0.3)
    piston_edge = parts.line_edge_along_x(piston.Shape, -0.2)
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


def sample_slider_crank(doc):
    """samples/freecad's slider-crank, its parts placed as build_samples.py places them and no
    joint yet: (asm, ground, crank, rod, piston) and the Ball's and the Slider's references."""
    asm = da.create_assembly(doc)
    made = []
    for name, shape in (("Ground", parts.ground_with_rail([(0, 0)], (1.5, 5.0))), ("Crank", parts.link(1)),
                        ("Rod", parts.link(3)), ("Piston", parts.piston())):
        o = doc.addObject("Part::Feature", name)
        o.Shape = shape
        da.add_part(asm, o, grounded=name == "Ground")
        made.append(o)
    g, crank, rod, piston = made
    crank.Placement = App.Placement(App.Vector(0, 0, 0.15), App.Rotation(App.Vector(0, 0, 1), 30))
    rod.Placement = App.Placement(App.Vector(0.8, 0.5, 0.2), App.Rotation(App.Vector(0, 0, 1), -10))
    piston.Placement = App.Placement(App.Vector(3.5, 0.1, 0.1), App.Rotation())

    def pin(o, x, z):
        return (o, parts.circle_edge(o.Shape, App.Vector(x, 0, z)))

    da.add_joint(asm, "Revolute", pin(g, 0, 0.1), pin(crank, 0, 0))
    da.add_joint(asm, "Revolute", pin(crank, 1, 0.1), pin(rod, 0, 0))
    ball = (pin(rod, 3, 0), (piston, parts.face_at_height(piston.Shape, 0.1)))
    slider = ((g, parts.line_edge_along_x(g.Shape, -0.3, 0.1)),
              (piston, parts.line_edge_along_x(piston.Shape, -0.2)))
    return asm, (g, crank, rod, piston), ball, slider


def is_slider_crank(crank, piston):
    """The piston upright on the rail (its top centre at y = -0.1, z = 0.2) and 3 from the end
    of the crank (1 long, turning in the plane about the origin)."""
    t = angle_of(crank)
    top = piston.Placement.multVec(App.Vector(0, 0, 0.1))
    assert abs(piston.Placement.Rotation.Angle) < 1e-8, piston.Placement
    assert abs(top.y + 0.1) < 1e-8 and abs(top.z - 0.2) < 1e-8, top
    assert abs((top - App.Vector(math.cos(t), math.sin(t), 0.2)).Length - 3) < 1e-8, top


@test
def test_sample_slider_crank_joint_by_joint():
    """The third audit's slider-crank made joint by joint, a solve after each (as the joint
    panel's preview does). The Slider first, then the Ball, closes. In the sample's order the
    Ball's solve tips the free piston over; the Slider made then takes the piston's turn about the
    rail from the picked edges' frames (TwistFrom "Picked frames", the default) and closes too.
    Made to hold the turn the piston had then ("Pose when made", as every Slider did before the
    fourteenth round: about 67 degrees), no pose holds it with the Ball and the crank's plane, so
    its solve fails, moves nothing and says what to do; done so, it closes."""
    doc = App.newDocument("slider_order")
    asm, (g, crank, rod, piston), ball, slider = sample_slider_crank(doc)
    assert da.solve(asm).converged
    da.add_joint(asm, "Slider", *slider)
    assert da.solve(asm).converged
    da.add_joint(asm, "Ball", *ball)
    r = da.solve(asm)
    assert r.converged, r.message
    is_slider_crank(crank, piston)
    assert "made with" not in r.message, r.message
    App.closeDocument(doc.Name)

    for twist in (None, "Pose when made"):
        doc = App.newDocument("slider_order")
        asm, (g, crank, rod, piston), ball, slider = sample_slider_crank(doc)
        assert da.solve(asm).converged
        da.add_joint(asm, "Ball", *ball)
        assert da.solve(asm).converged
        assert piston.Placement.Rotation.Angle > 1.0, piston.Placement  # tipped over
        j = da.add_joint(asm, "Slider", *slider, **({"twist_from": twist} if twist else {}))
        if twist is None:  # the default: the picked frames
            assert j.TwistFrom == "Picked frames", j.TwistFrom
            r = da.solve(asm)
            assert r.converged, r.message
            is_slider_crank(crank, piston)
            App.closeDocument(doc.Name)
            continue
        before = [o.Placement for o in (crank, rod, piston)]
        r = da.solve(asm)
        assert not r.converged, r.message
        assert [o.Placement for o in (crank, rod, piston)] == before
        said = re.search(r"%s was made with Piston's axis (\d+) degrees or more off Ground's and, its TwistFrom "
                         r"being 'Pose when made', holds Piston turned about it as it stood then: if the joints "
                         r"cannot hold so, set its TwistFrom to 'Picked frames' \(the joint panel's Twist from\), "
                         r"which lines up the picked elements' frames whatever the pose" % j.Label, r.message)
        assert said and 60 <= int(said.group(1)) <= 90, r.message  # the piston's x edge points nearly down
        # As the message says.
        da.edit_joint(j, twist_from="Picked frames")
        r = da.solve(asm)
        assert r.converged, r.message
        is_slider_crank(crank, piston)
        App.closeDocument(doc.Name)


# ---------------------------------------------------------------------------------------------
# Installed like an addon, and nothing lost where the workbench is missing. These run FreeCAD
# sessions of their own (freecadcmd in a subprocess) with a temporary HOME, so neither the
# workbench on this test's path nor one installed for the user can help them.

FREECADCMD = "freecadcmd"
BUILD = os.path.dirname(os.environ["DISPCON_PYTHONPATH"]) if os.environ.get("DISPCON_PYTHONPATH") else os.path.join(REPO, "build")


def bare_env(home):
    """The environment of a FreeCAD session that knows nothing of dispcon but what `home` holds."""
    env = {k: v for k, v in os.environ.items() if k not in ("DISPCON_PYTHONPATH", "PYTHONPATH")}
    env["HOME"] = home
    env.pop("XDG_DATA_HOME", None)
    env.pop("XDG_CONFIG_HOME", None)
    return env


def freecad_session(script, home, *args):
    """Runs `script` (text) in a fresh freecadcmd; returns its output; fails on a non-zero exit."""
    path = os.path.join(home, "session.py")
    with open(path, "w") as f:
        f.write(script)
    run = subprocess.run([FREECADCMD, path] + list(args), env=bare_env(home), cwd=home,
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
    if run.returncode != 0 or "SESSION OK" not in run.stdout:
        raise AssertionError("the FreeCAD session failed (exit %d):\n%s" % (run.returncode, run.stdout[-3000:]))
    return run.stdout


def rounded(value):
    """Floats to 9 decimals (a saved document keeps a fixed number of decimals), inside tuples too."""
    if isinstance(value, float):
        return round(value, 9) + 0.0
    if isinstance(value, tuple):
        return tuple(rounded(v) for v in value)
    return value


# What a session may change without a person changing anything: the proxy itself, the shape (a
# result, compared by volume below), recompute state, and the last solve's outcome.
NOT_SETTINGS = {"Proxy", "Shape", "ExpressionEngine", "Label2", "Visibility", "Residual", "Violated", "LastSolve"}


def plain(value):
    """A property's value as plain data to compare: objects by label, quantities by value."""
    if hasattr(value, "Label") and hasattr(value, "TypeId"):
        return value.Label
    if isinstance(value, (list, tuple)):
        return tuple(plain(v) for v in value)
    if isinstance(value, App.Placement):
        return plain(tuple(value.Base) + tuple(value.Rotation.Q))
    if isinstance(value, App.Vector):
        return plain(tuple(value))
    if hasattr(value, "Value") and hasattr(value, "Unit"):
        return rounded(float(value.Value))
    return rounded(value)


def settings_of(doc):
    """Every property of an assembly and of its parts and joints, by object label: the joints, their
    limits and every setting, whatever properties the workbench gives them."""
    asm = next(o for o in doc.Objects if o.TypeId == "App::DocumentObjectGroupPython")
    out = {}
    for o in [asm] + list(asm.Group):
        values = {p: plain(getattr(o, p)) for p in o.PropertiesList if p not in NOT_SETTINGS}
        if hasattr(o, "Shape"):
            values["volume"] = rounded(o.Shape.Volume)
        out[o.Label] = values
    return out


def saved_fourbar(tmp):
    """A four-bar with limits and settings changed from their defaults, saved: its path and values."""
    doc = App.newDocument("settings")
    asm, g, crank, coupler, rocker = fourbar(doc, tmp)
    js = da.joints(asm)
    da.set_limits(js[0], rotation=(-170, 170), move=0.25)
    da.set_limits(js[1], travel=(-1, 2), cone=30)
    js[2].Label = "Coupler to rocker"
    asm.Tolerance = 1e-8
    asm.MaxIterations = 777
    coupler.Density = 2.5
    rocker.AbilityToRotate = 0.5
    assert da.solve(asm).converged
    path = os.path.join(tmp, "fourbar.FCStd")
    doc.saveAs(path)
    values = settings_of(doc)
    App.closeDocument(doc.Name)
    return path, values


# A session script's opening: the workbench must not be importable; the document named last opens.
BARE_SESSION = """
import sys
import FreeCAD as App
try:
    import dispcon_fc
    raise SystemExit("the workbench was importable: this session must not have it")
except ImportError:
    pass
doc = App.openDocument(sys.argv[-1])
"""

WITHOUT_WORKBENCH = BARE_SESSION + """joints = [o for o in doc.Objects if "JointType" in o.PropertiesList]
assert len(joints) == 4, [o.Name for o in doc.Objects]
assert all(j.Proxy is None for j in joints), [j.Proxy for j in joints]
doc.save()
print("SESSION OK")
sys.exit(0)
"""


class NothingLostWithoutTheWorkbench(unittest.TestCase):
    def test_saved_without_the_workbench_then_reopened_with_it(self):
        with tempfile.TemporaryDirectory() as tmp:
            path, values = saved_fourbar(tmp)
            freecad_session(WITHOUT_WORKBENCH, tmp, path)
            doc = App.openDocument(path)
            try:
                asm = doc.getObject("Assembly")
                # The proxies did not survive that session; the stored properties did.
                self.assertIsNone(da.joints(asm)[0].Proxy)
                self.assertEqual(settings_of(doc), values)
                self.assertEqual(len(da.joints(asm)), 4)
                # Solve works, and really solves: the crank knocked off its pin comes back.
                crank = doc.getObject("crank")
                pin = crank.Placement
                crank.Placement = App.Placement(pin.Base + App.Vector(0.2, 0.1, 0), pin.Rotation)
                r = da.solve(asm)
                self.assertTrue(r.converged, r.message)
                self.assertGreater(r.iterations, 0)
                self.assertNotIn("0 iterations", r.message)
                self.assertLess((crank.Placement.Base - pin.Base).Length, 1e-7)
                # ... and the joints have their proxies back (saved with them from now on).
                self.assertTrue(all(isinstance(j.Proxy, da.JointProxy) for j in da.joints(asm)))
                self.assertIsInstance(asm.Proxy, da.AssemblyProxy)
                doc.save()
            finally:
                App.closeDocument(doc.Name)
            doc = App.openDocument(path)
            try:
                self.assertTrue(all(isinstance(j.Proxy, da.JointProxy) for j in da.joints(doc.getObject("Assembly"))))
            finally:
                App.closeDocument(doc.Name)

    def test_an_assembly_saved_before_dispcon_type_is_still_recognised(self):
        # The layout of the first workbench: no DispconType, the tolerance a plain float.
        doc = App.newDocument("legacy")
        try:
            asm = doc.addObject("App::DocumentObjectGroupPython", "Assembly")
            asm.addProperty("App::PropertyFloat", "Tolerance", "Dispcon", "").Tolerance = 2e-7
            asm.addProperty("App::PropertyInteger", "MaxIterations", "Dispcon", "").MaxIterations = 55
            asm.addProperty("App::PropertyString", "LastSolve", "Dispcon", "")
            self.assertTrue(da.is_assembly(asm))
            self.assertTrue(da.adopt(asm))
            self.assertEqual(asm.getTypeIdOfProperty("Tolerance"), "App::PropertyPrecision")
            self.assertEqual((asm.Tolerance, asm.MaxIterations, asm.DispconType), (2e-7, 55, "Assembly"))
        finally:
            App.closeDocument(doc.Name)


INSTALLED = """
import os
import sys
import FreeCAD as App
mod = os.path.join(App.getUserAppDataDir(), "Mod", "Dispcon")
assert "dispcon_fc" not in sys.modules
meta = App.Metadata(os.path.join(mod, "package.xml"))
wb = meta.Content["workbench"][0]
assert (meta.Name, wb.Classname) == ("Dispcon", "DispconWorkbench"), (meta.Name, wb.Classname)
assert os.path.isfile(os.path.join(mod, meta.Icon)), meta.Icon
# Restored with nothing imported first: the proxies came from the installed workbench, and
# those that a session without the workbench lost (the second file) are given back on opening.
for path in sys.argv[-2:]:
    doc = App.openDocument(path)
    joints = [o for o in doc.Objects if "JointType" in o.PropertiesList]
    assert len(joints) == 4 and all(type(j.Proxy).__name__ == "JointProxy" for j in joints), (path, [j.Proxy for j in joints])
    assert type(doc.getObject("Assembly").Proxy).__name__ == "AssemblyProxy", path
assert sys.modules["dispcon_fc"].__file__.startswith(mod), sys.modules["dispcon_fc"].__file__
import dispcon_fc.assembly as da
assert da.engine.load().__file__.startswith(mod), da.engine.load().__file__
asm = doc.getObject("Assembly")
crank = doc.getObject("crank")
pin = crank.Placement
crank.Placement = App.Placement(pin.Base + App.Vector(0.2, 0.1, 0), pin.Rotation)
r = da.solve(asm)
assert r.converged and r.iterations > 0 and (crank.Placement.Base - pin.Base).Length < 1e-7, r.message
print("SESSION OK")
sys.exit(0)
"""


class InstalledLikeAnAddon(unittest.TestCase):
    def test_install_restore_with_nothing_imported_then_uninstall(self):
        with tempfile.TemporaryDirectory() as tmp:
            path, _ = saved_fourbar(tmp)
            lost = os.path.join(tmp, "lost.FCStd")
            shutil.copy(path, lost)
            freecad_session(WITHOUT_WORKBENCH, tmp, lost)
            home = os.path.join(tmp, "home")
            os.makedirs(home)
            env = bare_env(home)
            env.update(DISPCON_NO_BUILD="1", DISPCON_BUILD=BUILD)
            script = os.path.join(REPO, "scripts", "install-freecad")
            out = subprocess.run([script], env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            self.assertEqual(out.returncode, 0, out.stdout)
            mod = os.path.join(home, ".local", "share", "FreeCAD", "Mod", "Dispcon")
            self.assertIn(mod, out.stdout)
            self.assertTrue(os.path.isfile(os.path.join(mod, "package.xml")))
            freecad_session(INSTALLED, home, lost, path)
            out = subprocess.run([script, "--uninstall"], env=env, stdout=subprocess.PIPE,
                                 stderr=subprocess.STDOUT, text=True)
            self.assertEqual(out.returncode, 0, out.stdout)
            self.assertFalse(os.path.exists(mod))


# ---------------------------------------------------------------------------------------------
# Robust commands: each bug a designer met, as a regression test.


def arm_on_base(doc, base_label="Base plate"):
    asm = da.create_assembly(doc)
    base = doc.addObject("Part::Feature", "Base")
    base.Label = base_label
    base.Shape = parts.ground([(0, 0)])
    da.add_part(asm, base, grounded=True)
    arm = doc.addObject("Part::Feature", "Arm")
    arm.Shape = parts.link(1.5)
    da.add_part(asm, arm)
    return asm, base, arm


def pin(obj, local):
    return (obj, parts.circle_edge(da.shape_of(obj), App.Vector(*local)))


class Messages(unittest.TestCase):
    """What Solve says in the status bar and the joint panel, in a person's grammar: one
    iteration is not "1 iterations", and a solve that moved nothing does not say "0 iterations"."""

    def setUp(self):
        self.doc = App.newDocument("messages")

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def test_plural(self):
        from dispcon_fc.adapter import plural
        self.assertEqual([plural(n, "iteration") for n in (0, 1, 2, 31)],
                         ["0 iterations", "1 iteration", "2 iterations", "31 iterations"])

    def test_solve_counts_its_iterations_in_words(self):
        import types
        from dispcon_fc.adapter import Adapter, ALREADY_HELD, Result
        asm, base, arm = arm_on_base(self.doc)
        da.add_joint(asm, "Revolute", pin(arm, (0, 0, 0)), pin(base, (0, 0, 0)))
        arm.Placement = App.Placement(App.Vector(0.3, -0.2, 0.1), App.Rotation(App.Vector(0, 0, 1), 20))
        r = da.solve(asm)
        self.assertTrue(r.converged, r.message)
        self.assertGreater(r.iterations, 0)
        self.assertEqual(r.message, "solved in %d iteration%s" % (r.iterations, "" if r.iterations == 1 else "s"))
        self.assertEqual(asm.LastSolve, r.message)
        # Solved again where every joint holds: nothing moved, and it says so.
        again = da.solve(asm)
        self.assertEqual((again.converged, again.iterations, again.message), (True, 0, ALREADY_HELD))
        # The engine's answer of one and of two iterations, worded by the same Result.
        adapter = Adapter(asm)
        for n, text in ((1, "solved in 1 iteration"), (2, "solved in 2 iterations")):
            engine_says = types.SimpleNamespace(converged=True, iterations=n, max_residual=0.0, violated=[],
                                                constraints=[])
            self.assertEqual(Result(adapter, engine_says).message, text)


class Recorder:
    """A document observer: every property changed, as (object name, property)."""

    def __init__(self):
        self.changed = []

    def slotChangedObject(self, obj, prop):
        self.changed.append((obj.Name, prop))

    def slotChangedDocument(self, doc, prop):
        self.changed.append(("<document>", prop))


class SolveWritesOnlyWhatChanged(unittest.TestCase):
    """Opening a solved document and pressing Solve leaves it unmodified: no placement, residual,
    Violated or LastSolve is written when the solve moved nothing (any write marks the document
    modified in the GUI, even of the value it had)."""

    def setUp(self):
        self.tmp = tempfile.mkdtemp()
        path, _ = saved_fourbar(self.tmp)
        self.doc = App.openDocument(path)
        self.asm = next(o for o in self.doc.Objects if "LastSolve" in o.PropertiesList)

    def tearDown(self):
        App.closeDocument(self.doc.Name)
        shutil.rmtree(self.tmp)

    def solve_recorded(self):
        rec = Recorder()
        App.addDocumentObserver(rec)
        try:
            result = da.solve(self.asm)
        finally:
            App.removeDocumentObserver(rec)
        return result, rec.changed

    def test_a_solve_that_moved_nothing_changes_nothing(self):
        from dispcon_fc.adapter import ALREADY_HELD
        last = self.asm.LastSolve
        self.assertRegex(last, r"^solved in \d+ iterations?$")
        placements = {o.Name: (tuple(o.Placement.Base), o.Placement.Rotation.Q) for o in da.parts(self.asm)}
        result, changed = self.solve_recorded()
        self.assertEqual((result.converged, result.iterations, result.message), (True, 0, ALREADY_HELD))
        self.assertEqual(changed, [])
        self.assertFalse(self.doc.isTouched())
        self.assertEqual([o.Name for o in self.doc.Objects if "Touched" in o.State], [])
        self.assertEqual(self.asm.LastSolve, last)
        self.assertEqual({o.Name: (tuple(o.Placement.Base), o.Placement.Rotation.Q) for o in da.parts(self.asm)},
                         placements)
        # Again, in the same session: still nothing.
        self.assertEqual(self.solve_recorded()[1], [])

    def test_a_solve_that_moves_writes_what_moved(self):
        coupler = next(o for o in da.parts(self.asm) if o.Label == "Coupler")
        ground = next(o for o in da.parts(self.asm) if o.Grounded)
        coupler.Placement = App.Placement(App.Vector(1.2, 0.6, -0.1), App.Rotation(App.Vector(0, 0, 1), 11))
        self.doc.recompute()
        result, changed = self.solve_recorded()
        self.assertTrue(result.converged, result.message)
        self.assertGreater(result.iterations, 0)
        self.assertIn((coupler.Name, "Placement"), changed)
        self.assertNotIn((ground.Name, "Placement"), changed)  # grounded: never written
        self.assertIn((self.asm.Name, "LastSolve"), changed)
        self.assertEqual(self.asm.LastSolve, result.message)
        # The joints pulled apart by the move hold again, and say so.
        self.assertTrue(all(not j.Violated and j.Residual <= self.asm.Tolerance for j in da.joints(self.asm)))

    def test_a_failed_solve_then_an_idle_one_rewrite_the_message(self):
        from dispcon_fc.operations import _new_news
        from dispcon_fc.adapter import ALREADY_HELD
        self.assertFalse(_new_news("solved in 1 iteration", ALREADY_HELD))
        self.assertFalse(_new_news(ALREADY_HELD, ALREADY_HELD))
        # After a failure, or a message with a skipped joint, "already holds" is news.
        self.assertTrue(_new_news("could not make every joint hold; still violated: J (residual 0.5)", ALREADY_HELD))
        self.assertTrue(_new_news("solved in 3 iterations; skipped J", ALREADY_HELD))
        self.assertTrue(_new_news("", ALREADY_HELD))
        self.assertTrue(_new_news(ALREADY_HELD, "solved in 2 iterations"))


class StudyInWords(unittest.TestCase):
    """The motion study and the check as the workbench says them: angles in degrees with their
    unit, counts in words; the command line's own wording (study.message) stays as it is."""

    def setUp(self):
        self.doc = App.newDocument("words")
        self.asm, self.base, self.arm = arm_on_base(self.doc)
        # The arm on top of the plate's boss (touching, not overlapping), turning about it.
        self.joint = da.add_joint(self.asm, "Revolute", pin(self.arm, (0, 0, 0)), pin(self.base, (0, 0, 0.1)))
        self.assertTrue(da.solve(self.asm).converged)

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def block(self, y):
        """A grounded block across the arm's circle (radius 1.5) at (0, y..y+0.2)."""
        import Part

        b = self.doc.addObject("Part::Feature", "Block")
        b.Shape = Part.makeBox(0.2, 0.2, 0.3, App.Vector(-0.1, y, -0.1))
        da.add_part(self.asm, b, grounded=True)
        return b

    def ranges(self, text):
        return [(float(a), float(b)) for a, b in re.findall(r"from (-?[\d.]+)° to (-?[\d.]+)°", text)]

    def test_a_sweep_says_degrees_and_counts_its_pairs_in_words(self):
        from dispcon_fc import feedback, studies

        self.block(0.8)
        one = studies.export_drive_study(self.asm, self.joint)
        self.assertIn("1 pair of parts collides", one.message)  # the command line's (radians)
        text = feedback.study_message(one)
        self.assertRegex(text, r"^'Revolute' moves freely from -?[\d.]+° to -?[\d.]+°; 1 pair of parts collides: "
                               r"'Arm' and 'Block' from [\d.]+° to [\d.]+°$")
        self.assertNotIn("rad", text)
        self.block(-1.0)
        two = feedback.study_message(studies.export_drive_study(self.asm, self.joint))
        self.assertIn("; 2 pairs of parts collide: 'Arm' and 'Block' from ", two)
        self.assertIn(", 'Arm' and 'Block001' from ", two)
        (start, stop), *hits = self.ranges(two)
        self.assertAlmostEqual(stop - start, 360.0, places=6)  # a whole turn
        # The strip 0.2 wide meets a block 0.2 wide at 0.8 from the pin while its edge passes
        # the near corners: 2 asin(0.1 / |(0.1, 0.8)|) + 2 atan(0.1 / 0.8) = 28.5° wide, centred
        # across the pin from one block to the other (90° and 270°, the joint's sense either way);
        # the sweep's degree steps land inside by up to one.
        width = math.degrees(2 * math.asin(0.1 / math.hypot(0.1, 0.8)) + 2 * math.atan2(0.1, 0.8))
        self.assertEqual(len(hits), 2)
        centres = sorted(math.remainder((a + b) / 2 - start, 360.0) % 360.0 for a, b in hits)
        for got, want in zip(centres, (90.0, 270.0)):
            self.assertAlmostEqual(got, want, delta=1.0)
        for a, b in hits:
            self.assertGreater(b - a, width - 2.0)
            self.assertLessEqual(b - a, width)

    def test_the_check_counts_in_words(self):
        # The same revolute twice: one of them repeats the other. The engine's line counts in
        # words (the Report view shows it as it is).
        da.add_joint(self.asm, "Revolute", pin(self.arm, (0, 0, 0)), pin(self.base, (0, 0, 0.1)))
        c = da.check(self.asm)
        self.assertEqual(len(c["redundant"]), 1, c["message"])
        self.assertRegex(c["message"], r"\b1 redundant joint(,|$)")
        self.assertNotIn("(s)", c["message"])


class RobustOperations(unittest.TestCase):
    def setUp(self):
        self.doc = App.newDocument("robust")

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def test_drive_turns_the_free_part_when_the_grounded_one_was_picked_second(self):
        asm, base, arm = arm_on_base(self.doc)
        j = da.add_joint(asm, "Revolute", pin(arm, (0, 0, 0)), pin(base, (0, 0, 0)))
        self.assertTrue(da.solve(asm).converged)
        start = angle_of(arm)
        reached = da.drive(asm, j, [10, 20, 30])
        self.assertEqual(reached, 30)
        self.assertAlmostEqual(math.degrees(math.remainder(angle_of(arm) - start, 2 * math.pi)), 30, places=6)
        self.assertEqual(base.Placement, App.Placement())

    def test_drive_to_sets_the_joint_value_whichever_part_is_grounded(self):
        # The Drive panel's operation: the joint's value as its limits measure it, reached by
        # turning the free part (here part 1, the grounded base picked second), one undo step.
        self.doc.UndoMode = 1  # freecadcmd keeps no undo steps by default
        asm, base, arm = arm_on_base(self.doc)
        j = da.add_joint(asm, "Revolute", pin(arm, (0, 0, 0)), pin(base, (0, 0, 0)), rotation=(-50, 50))
        self.assertTrue(da.solve(asm).converged)
        start = arm.Placement
        v0 = da.drive_value(j)
        reached, arrived = da.drive_to(asm, j, v0 + 40.0)
        self.assertTrue(arrived)
        self.assertAlmostEqual(reached, v0 + 40.0, places=9)
        self.assertAlmostEqual(da.drive_value(j), v0 + 40.0, places=7)
        # Part 2 (the base) is grounded: the arm turned by the opposite of the joint's change.
        self.assertAlmostEqual(math.degrees(math.remainder(angle_of(arm) - angle_of_placement(start), 2 * math.pi)),
                               -40.0, places=6)
        self.assertEqual(base.Placement, App.Placement())
        self.doc.undo()
        self.assertTrue(same(arm.Placement, start, 1e-9), "one undo did not put the drive back")
        # Outside the limits: refused by label before anything moves.
        with self.assertRaisesRegex(ValueError, "Revolute.*outside its limits"):
            da.drive_to(asm, j, v0 + 60.0)
        self.assertTrue(same(arm.Placement, start, 1e-12))
        with self.assertRaisesRegex(ValueError, "a drive sets"):
            da.drive_value(da.add_joint(asm, "Ball", pin(arm, (1.5, 0, 0)), pin(base, (0, 0, 0))))

    def test_a_mouse_event_where_the_last_pull_settled_solves_nothing(self):
        # Drag mode's mouse drag: an event at the point where the last pull settled (the cursor
        # at the same pixel) leaves the model as it is, without a pull; a pull stopped by its
        # iteration cap while still getting nearer goes on from where it stopped.
        asm, base, arm = arm_on_base(self.doc)
        da.add_joint(asm, "Revolute", pin(base, (0, 0, 0)), pin(arm, (0, 0, 0)))
        self.assertTrue(da.solve(asm).converged)
        d = da.PointDrag(asm, arm, arm.Placement.multVec(App.Vector(1.5, 0, 0.1)), live=False)
        engine, statuses = d.puller, []

        class Counted:
            def pull_to(self, target):
                r = engine.pull_to(target)
                statuses.append(r.status)
                return r

        d.puller = Counted()

        def settle(target):
            """Moves until a pull settles (out of reach, at the nearest pose)."""
            for _ in range(5):
                self.assertTrue(d.move(target))
                self.assertTrue(d.changed)
                if statuses[-1] != "iteration-limit":
                    break
            self.assertEqual(statuses[-1], "out-of-reach", statuses)

        far = App.Vector(0, 3, 0.1)  # twice the arm's reach from its pin, in the grabbed point's plane
        settle(far)
        pulls, poses = len(statuses), d.adapter.model.poses()
        self.assertTrue(d.move(far))  # the same point again: the linkage stays where it settled
        self.assertFalse(d.changed)
        self.assertEqual(len(statuses), pulls)
        self.assertTrue((d.adapter.model.poses() == poses).all())
        beside = far + App.Vector(0.1, 0, 0)  # moved: pulled again
        settle(beside)
        self.assertGreater(len(statuses), pulls)
        d.finish()
        tip = arm.Placement.multVec(App.Vector(1.5, 0, 0.1))
        self.assertAlmostEqual((tip - beside).Length, math.hypot(beside.x, beside.y) - 1.5, delta=1e-6)

    def test_a_joint_whose_part_was_deleted_is_named_and_skipped(self):
        asm, base, arm = arm_on_base(self.doc)
        da.add_joint(asm, "Revolute", pin(base, (0, 0, 0)), pin(arm, (0, 0, 0)))
        tip = self.doc.addObject("Part::Feature", "Tip")
        tip.Label = "Tip link"
        tip.Shape = parts.link(0.5)
        da.add_part(asm, tip)
        lost = da.add_joint(asm, "Revolute", pin(arm, (1.5, 0, 0)), pin(tip, (0, 0, 0)))
        lost.Label = "Elbow"
        self.doc.removeObject(tip.Name)
        r = da.solve(asm)
        self.assertTrue(r.converged, r.message)
        said = "Elbow: one of its parts was deleted: pick its two references again (double-click the joint) or delete the joint"
        self.assertIn("skipped " + said, r.message)
        self.assertEqual(r.skipped, [lost])
        c = da.check(asm)
        self.assertEqual(c["skipped"], [lost])
        self.assertIn("Elbow", c["message"])
        with self.assertRaises(ValueError) as caught:
            da.drive(asm, lost, [10])
        self.assertEqual(str(caught.exception), said)

    def test_limits_crossed_in_the_property_editor_are_named_in_the_designers_words(self):
        """The fourth audit: a turn's Min set above its Max in the property editor (which the
        panel's check does not see) made Solve and Check say "constraint: twist: min 1.0472 is
        above max 0.5"; now the joint's label, the limits in degrees, and what to do."""
        asm, base, arm = arm_on_base(self.doc)
        j = da.add_joint(asm, "Revolute", pin(base, (0, 0, 0)), pin(arm, (0, 0, 0)), rotation=(-45, 28.6479))
        j.Label = "Frame-Wheel"
        j.RotationMin = App.Units.Quantity("60 deg")  # as the property editor sets it
        said = "Frame-Wheel: its turn's Min 60° is above its Max 28.6479°: set Min below Max"
        with self.assertRaisesRegex(ValueError, said):
            da.solve(asm)
        with self.assertRaisesRegex(ValueError, said):
            da.check(asm)
        with self.assertRaisesRegex(ValueError, said):
            da.drag(asm, arm, arm.Placement)
        j.RotationMin = App.Units.Quantity("-45 deg")
        self.assertTrue(da.solve(asm).converged)

    def test_crossed_travel_and_angle_are_the_engines_refusal_in_the_designers_words(self):
        """One door: the engine refuses crossed bounds (dispcon.LimitError: which, as given, in
        which unit) and the adapter says it with the joint's label, in mm or degrees as the panel
        writes them; the workbench no longer checks them itself."""
        asm, base, arm = arm_on_base(self.doc)
        j = da.add_joint(asm, "Slider", pin(base, (0, 0, 0)), pin(arm, (0, 0, 0)), travel=(-2, 3))
        j.Label = "Rail"
        j.TravelMin = 5  # as the property editor sets it
        with self.assertRaisesRegex(ValueError, "^Rail: its travel's Min 5 mm is above its Max 3 mm: set Min "
                                                r"below Max \(double-click Rail to open its panel\)$"):
            da.solve(asm)
        j.TravelMin = -2
        self.assertTrue(da.solve(asm).converged)
        a = da.add_joint(asm, "Angle", pin(base, (0, 0, 0)), pin(arm, (0, 0, 0)), angle=(10, 80))
        a.Label = "Tilt"
        a.AngleMin = App.Units.Quantity("95 deg")
        with self.assertRaisesRegex(ValueError, "^Tilt: its angle's Min 95° is above its Max 80°"):
            da.check(asm)

    def test_crossed_limits_are_asked_of_the_engine(self):
        """add_joint's and edit_joint's refusal of a Min above its Max, and the joint panel's hint,
        come from the engine's door (a model of their own), whatever the joint's type takes."""
        from dispcon_fc import operations

        dispcon = da.engine.load()
        key, refusal = operations.crossed_limit(rotation=(40, 30), travel=(1, 2))
        self.assertEqual(key, "rotation")
        self.assertIsInstance(refusal, dispcon.LimitError)
        self.assertEqual((refusal.statement, refusal.unit), ("twist", "angle"))
        self.assertAlmostEqual(math.degrees(refusal.min), 40)
        key, refusal = operations.crossed_limit(rotation=False, travel=(5, 2.5))
        self.assertEqual((key, refusal.statement, refusal.min, refusal.max, refusal.unit),
                         ("travel", "axial", 5, 2.5, "length"))
        self.assertIsNone(operations.crossed_limit(rotation=(30, 30), travel=(0, 1), angle=(0, 200)))
        # A limit the joint's type does not take is refused as well: it holds when the type changes.
        asm, base, arm = arm_on_base(self.doc)
        j = da.add_joint(asm, "Revolute", pin(base, (0, 0, 0)), pin(arm, (0, 0, 0)))
        with self.assertRaisesRegex(ValueError, "^Revolute: travel min 5 mm is above max 2.5 mm$"):
            da.edit_joint(j, travel=(5, 2.5))
        self.assertFalse(j.HasTravelLimits)

    def test_an_imported_part_whose_import_was_redone_reopens_untouched(self):
        """The fourth audit: every step undone then redone (Ctrl+Z, Ctrl+Shift+Z) and saved, the
        reopened document had its four imported parts touched (a recompute waiting, in the tree):
        an undo or redo of a drag writes their Placements with no recompute after, and FreeCAD
        saves the mark. An imported part computes nothing (its shape is given), so the mark is
        cleared on restore, as the assembly's is."""
        self.doc.UndoMode = 1
        asm = da.create_assembly(self.doc)
        part = da.import_part(asm, os.path.join(REPO, "samples", "freecad", "parts", "link-1.step"), "Wheel")
        name = part.Name
        da.drag(asm, part, App.Placement(App.Vector(1, 2, 0), App.Rotation(App.Vector(0, 0, 1), 30)))
        self.assertNotIn("Touched", part.State)
        self.doc.undo()
        self.doc.redo()
        self.assertIn("Touched", self.doc.getObject(name).State)  # what the saved file holds
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "redone.FCStd")
            self.doc.saveAs(path)
            App.closeDocument(self.doc.Name)
            self.doc = App.openDocument(path)
            self.assertEqual([o.Label for o in self.doc.Objects if "Touched" in o.State], [])

    def test_opening_a_saved_assembly_changes_nothing(self):
        # The samples are made so: opening one must not mark it touched (nothing to save).
        asm, g, crank, coupler, rocker = fourbar(self.doc, tempfile.mkdtemp())
        self.assertTrue(da.solve(asm).converged)
        path = os.path.join(tempfile.mkdtemp(), "opened.FCStd")
        name = asm.Name
        self.doc.saveAs(path)
        App.closeDocument(self.doc.Name)
        self.doc = App.openDocument(path)
        self.assertFalse(self.doc.isTouched())
        self.assertEqual([o.Label for o in self.doc.Objects if "Touched" in o.State], [])
        self.assertEqual(len(da.joints(self.doc.getObject(name))), 4)

    def test_derived_joint_properties_are_read_only_in_the_editor(self):
        # The picked geometry (made again from the references at every solve) and the last
        # solve's outcome are read in the property editor, never typed there; the settings stay
        # editable. Kept through a save and a reopen.
        from dispcon_fc import objects

        asm, g, crank, coupler, rocker = fourbar(self.doc, tempfile.mkdtemp())
        self.assertTrue(da.solve(asm).converged)
        j = da.joints(asm)[0]
        for name in ("Point1", "Axis1", "Perp1", "Point2", "Axis2", "Perp2", "Feature1", "Feature2",
                     "Residual", "Violated"):
            self.assertIn("ReadOnly", j.getEditorMode(name), name)
        for name in ("Offset", "Reversed", "RotationMin", "HasRotationLimits", "JointType", "FrameYaw"):
            self.assertNotIn("ReadOnly", j.getEditorMode(name), name)
        j.Point1 = j.Point1  # scripts still write them
        path = os.path.join(tempfile.mkdtemp(), "readonly.FCStd")
        name = j.Name
        self.doc.saveAs(path)
        App.closeDocument(self.doc.Name)
        self.doc = App.openDocument(path)
        self.assertIn("ReadOnly", self.doc.getObject(name).getEditorMode("Axis2"))
        self.assertEqual(objects.DERIVED[-1], "Violated")

    def test_point_on_curve_reads_the_live_curve(self):
        # A revolute between the base's boss and the arm's tip boss, turned into a PointOnCurve:
        # the arm's tip pin must then run on the base's boss edge (radius 0.15) ...
        asm, base, arm = arm_on_base(self.doc)
        arm.Placement = App.Placement(App.Vector(-1.4, 0.1, 0), App.Rotation())
        j = da.add_joint(asm, "Revolute", pin(base, (0, 0, 0)), pin(arm, (1.5, 0, 0)))
        da.edit_joint(j, joint_type="PointOnCurve")
        r = da.solve(asm)
        self.assertTrue(r.converged, r.message)
        tip = arm.Placement.multVec(App.Vector(1.5, 0, 0))
        self.assertAlmostEqual(math.hypot(tip.x, tip.y), 0.15, delta=0.15 * (1 - math.cos(math.pi / 64)) + 1e-7)
        self.assertAlmostEqual(tip.z, 0, places=7)
        # ... and on the boss as it is now, when the base's shape grows to twice its size.
        bigger = base.Shape.copy()
        bigger.scale(2.0)
        base.Shape = bigger
        r = da.solve(asm)
        self.assertTrue(r.converged, r.message)
        tip = arm.Placement.multVec(App.Vector(1.5, 0, 0))
        self.assertAlmostEqual(math.hypot(tip.x, tip.y), 0.3, delta=0.3 * (1 - math.cos(math.pi / 64)) + 1e-7)

    def test_joints_follow_their_parts_edited_geometry(self):
        # A post made parametric (a Part::Cylinder), an arm pinned on its top circle: making the
        # post taller moves the pin, and the arm follows at the next solve.
        asm = da.create_assembly(self.doc)
        post = self.doc.addObject("Part::Cylinder", "Post")
        post.Radius, post.Height = 0.15, 1.0
        self.doc.recompute()
        da.add_part(asm, post, grounded=True)
        arm = self.doc.addObject("Part::Feature", "Arm")
        arm.Shape = parts.link(1.5)
        da.add_part(asm, arm)
        top = next("Edge%d" % (k + 1) for k, e in enumerate(post.Shape.Edges)
                   if hasattr(e.Curve, "Radius") and abs(e.Curve.Center.z - 1.0) < 1e-9)
        pin_edge = parts.circle_edge(arm.Shape, App.Vector(0, 0, 0))
        j = da.add_joint(asm, "Revolute", (post, top), (arm, pin_edge))
        j.Label = "Post pin"
        self.assertTrue(da.solve(asm).converged)
        self.assertAlmostEqual(arm.Placement.multVec(App.Vector(0, 0, 0)).z, 1.0, places=7)
        post.Height = 2.5
        self.doc.recompute()
        r = da.solve(asm)
        self.assertTrue(r.converged, r.message)
        self.assertAlmostEqual(arm.Placement.multVec(App.Vector(0, 0, 0)).z, 2.5, places=7)
        self.assertAlmostEqual(j.Point1.z, 2.5, places=9)  # stored: the marker follows too
        # The post's radius grows: its top circle's centre and axis stay, so nothing moves.
        before = arm.Placement
        post.Radius = 0.3
        self.doc.recompute()
        self.assertTrue(da.solve(asm).converged)
        self.assertTrue(same(arm.Placement, before, 1e-9))
        # The referenced edge gone (the post is now a sphere: no such edge): the joint is named
        # and skipped, nothing raises.
        import Part

        plain_post = self.doc.addObject("Part::Feature", "PlainPost")
        plain_post.Label = "Plain post"
        plain_post.Shape = post.Shape.copy()
        da.add_part(asm, plain_post, grounded=True)
        k = da.add_joint(asm, "Revolute", (plain_post, top), (arm, pin_edge))
        k.Label = "Plain pin"
        plain_post.Shape = Part.makeSphere(0.3)
        r = da.solve(asm)
        self.assertIn("skipped Plain pin: Plain post has no %s any more, its shape changed: pick that "
                      "reference again (double-click the joint)" % top, r.message)
        self.assertEqual(r.skipped, [k])
        self.assertIn(k, da.check(asm)["skipped"])

    def test_point_on_curve_needs_an_edge_and_says_so(self):
        asm, base, arm = arm_on_base(self.doc)
        face = next("Face%d" % (i + 1) for i, f in enumerate(base.Shape.Faces) if f.Surface.TypeId == "Part::GeomPlane")
        j = da.add_joint(asm, "Ball", (base, face), pin(arm, (0, 0, 0)))
        with self.assertRaisesRegex(ValueError, "needs an edge of Base plate"):
            da.edit_joint(j, joint_type="PointOnCurve")
        self.assertEqual(j.JointType, "Ball")

    def test_every_joint_type_is_a_row_of_the_engines_table(self):
        from dispcon_fc import adapter, engine
        dispcon = engine.load()
        # Every type the workbench offers is a row; only the couplings wait for an engine that
        # has their rows (and then every type is offered).
        offered = adapter.offered_types(dispcon)
        self.assertLessEqual(set(da.JOINT_TYPES) - set(offered), set(da.COUPLINGS))
        kinds = {t: adapter.kind_of(dispcon, t)["name"] for t in offered}
        self.assertEqual(kinds["PointOnLine"], "point_on_line")
        self.assertEqual(sorted(set(kinds.values())), sorted(kinds.values()))
        asm, base, arm = arm_on_base(self.doc)
        made = ["Fixed", "Revolute", "Slider", "Cylindrical", "Ball", "Planar", "PointOnLine",
                "PointOnPlane", "Angle"]
        for t in made:
            da.add_joint(asm, t, pin(base, (0, 0, 0)), pin(arm, (0, 0, 0)))
        # Limits a kind does not take stay in the properties and out of the model.
        j = da.add_joint(asm, "Revolute", pin(base, (0, 0, 0)), pin(arm, (0, 0, 0)), rotation=(-20, 30),
                         travel=(0, 5))
        model = adapter.Adapter(asm).model
        self.assertEqual([model.joint(i).kind for i in range(model.joint_count())],
                         [kinds[t] for t in made] + ["revolute"])
        self.assertTrue(j.HasTravelLimits)
        self.assertRegex(model.to_dcl(), r"twist [^;]* min -0\.349065850398865\d* max 0\.523598775598298\d*;")

    def test_a_scripted_drag_past_a_limit_says_where_it_stopped_from_the_placement_asked(self):
        """The fifth audit: a script's drag() past a limit returned the engine's last step,
        "'p2_Platform' stays 40 / 10 / 2 from its target" for 1 / 4 / 20 steps: the model's
        internal name, measured from that step's own target. Now the part's label, the distance
        from the placement asked, the steps made, and the limit that holds it."""
        for steps, made, stopped, why in ((1, 0, 0.0, "the next step: out of reach: 'Arm' stays 7 "),
                                          (4, 1, 2.5, "the next step: out of reach: 'Arm' stays 2 "),
                                          (20, 6, 3.0, "Rail is at its limit, 3 mm$")):
            doc = App.newDocument("drag%d" % steps)
            self.addCleanup(App.closeDocument, doc.Name)
            asm, base, arm = arm_on_base(doc)
            j = da.add_joint(asm, "Slider", pin(base, (0, 0, 0)), pin(arm, (0, 0, 0)), travel=(-2, 3))
            j.Label = "Rail"
            r = da.drag(asm, arm, App.Placement(App.Vector(0, 0, 10), App.Rotation()), steps=steps)
            self.assertFalse(r.converged)
            self.assertEqual((r.steps, r.steps_made), (steps, made))
            self.assertAlmostEqual(arm.Placement.Base.z, stopped, delta=1e-9)
            self.assertRegex(r.message, "^Arm stops %g mm from the placement asked, after %d of %d steps?: %s"
                             % (10 - stopped, made, steps, why))
            self.assertIsNone(re.search(r"\bp\d+_", r.message), r.message)
        asm, base, arm = arm_on_base(self.doc)
        da.add_joint(asm, "Slider", pin(base, (0, 0, 0)), pin(arm, (0, 0, 0)), travel=(-2, 3))
        r = da.drag(asm, arm, App.Placement(App.Vector(0, 0, 2), App.Rotation()), steps=4)
        self.assertTrue(r.converged)
        self.assertEqual(r.message, "Arm moved in 4 steps")

    def test_errors_name_parts_by_their_labels(self):
        asm, base, arm = arm_on_base(self.doc)
        da.add_joint(asm, "Revolute", pin(base, (0, 0, 0)), pin(arm, (0, 0, 0)))
        self.assertTrue(da.solve(asm).converged)
        with self.assertRaisesRegex(ValueError, "^Base plate is grounded"):
            da.drag(asm, base, App.Placement(App.Vector(1, 0, 0), App.Rotation()))
        # The engine's own messages come back with labels, not the model's names.
        far = self.doc.addObject("Part::Feature", "Far")
        far.Label = "Far post"
        far.Shape = parts.ground([(9, 0)])
        da.add_part(asm, far, grounded=True)
        bad = da.add_joint(asm, "Ball", pin(far, (9, 0, 0)), pin(arm, (1.5, 0, 0)))
        bad.Label = "Tip pin"
        asm.MaxIterations = 300
        c = da.check(asm)
        text = " ".join([c["message"]] + c["advice"])
        self.assertIsNone(re.search(r"\bp\d+_", text), text)
        # The advice names the joint to fix by its label and its parts', never by its index.
        self.assertIsNone(re.search(r"joint #\d", text), text)
        culprit = c["conflicting"][0]
        self.assertIn(culprit, (bad, da.joints(asm)[0]))
        self.assertEqual("remove or loosen '%s' (joint between '%s' and 'Arm'): the other joints then hold"
                         % (culprit.Label, "Far post" if culprit == bad else "Base plate"), c["advice"][0])

    def test_a_refused_operation_changes_nothing(self):
        asm, base, arm = arm_on_base(self.doc)
        before = sorted(o.Name for o in self.doc.Objects)
        for call, pattern in (
                (lambda: da.add_joint(asm, "Revolute", pin(base, (0, 0, 0)), pin(arm, (0, 0, 0)), rotation=(40, 30)),
                 "rotation min 40 deg is above max 30 deg"),
                (lambda: da.add_joint(asm, "Revolute", (base, "Edge999"), pin(arm, (0, 0, 0))), "Edge999"),
                (lambda: da.add_joint(asm, "Hinge", pin(base, (0, 0, 0)), pin(arm, (0, 0, 0))), "unknown joint type")):
            with self.assertRaisesRegex(Exception, pattern):
                call()
            self.assertEqual(sorted(o.Name for o in self.doc.Objects), before)
        j = da.add_joint(asm, "Revolute", pin(base, (0, 0, 0)), pin(arm, (0, 0, 0)), rotation=(-10, 10))
        with self.assertRaisesRegex(ValueError, "rotation min 50 deg is above max 20 deg"):
            da.edit_joint(j, joint_type="Slider", rotation=(50, 20))
        self.assertEqual((j.JointType, j.RotationMin.Value, j.RotationMax.Value), ("Revolute", -10, 10))

    def test_a_failed_step_inside_an_operation_is_rolled_back(self):
        asm, base, arm = arm_on_base(self.doc)
        self.assertEqual(self.doc.UndoMode, 0)  # freecadcmd's default: no undo of its own
        before = sorted(o.Name for o in self.doc.Objects)
        with self.assertRaises(RuntimeError):
            with da.transaction(self.doc, "Half done"):
                self.doc.addObject("Part::Feature", "Stray")
                arm.Placement = App.Placement(App.Vector(5, 5, 5), App.Rotation())
                raise RuntimeError("stop")
        self.assertEqual(sorted(o.Name for o in self.doc.Objects), before)
        self.assertEqual(arm.Placement, App.Placement())
        self.assertEqual(self.doc.UndoMode, 0)

    def test_new_assemblies_take_the_preferences(self):
        p = App.ParamGet("User parameter:BaseApp/Preferences/Mod/Dispcon")
        saved = (p.GetString("Tolerance", ""), p.GetInt("MaxIterations", 0), p.GetInt("DragSteps", 0))
        try:
            p.SetString("Tolerance", "1e-7")
            p.SetInt("MaxIterations", 321)
            p.SetInt("DragSteps", 7)
            asm = da.create_assembly(self.doc)
            self.assertEqual((asm.Tolerance, asm.MaxIterations), (1e-7, 321))
            self.assertEqual(asm.getTypeIdOfProperty("Tolerance"), "App::PropertyPrecision")
            self.assertEqual(da.preferences()["DragSteps"], 7)
            p.SetString("Tolerance", "tight")
            self.assertEqual(da.preferences()["Tolerance"], 1e-9)
        finally:
            for name, value in zip(("Tolerance", "MaxIterations", "DragSteps"), saved):
                if not value:
                    p.RemString(name) if name == "Tolerance" else p.RemInt(name)
                elif name == "Tolerance":
                    p.SetString(name, value)
                else:
                    p.SetInt(name, value)

    def test_insert_a_part_from_another_file(self):
        with tempfile.TemporaryDirectory() as tmp:
            library = App.newDocument("library")
            bar = library.addObject("Part::Feature", "Bar")
            bar.Label = "Long bar"
            bar.Shape = parts.link(2.0)
            library_path = os.path.join(tmp, "library.FCStd")
            library.saveAs(library_path)
            try:
                asm, base, arm = arm_on_base(self.doc)
                self.doc.saveAs(os.path.join(tmp, "robust.FCStd"))
                self.assertEqual([o.Label for o in da.linkable_objects(library_path)], ["Long bar"])
                linked = da.link_part(asm, library_path)
                self.assertEqual((linked.TypeId, linked.LinkedObject, linked.Label), ("App::Link", bar, "Long bar"))
                self.assertIn(linked, da.parts(asm))
                before = sorted(o.Name for o in self.doc.Objects)
                with self.assertRaisesRegex(ValueError, "has no object Nothing"):
                    da.link_part(asm, library_path, "Nothing")
                self.assertEqual(sorted(o.Name for o in self.doc.Objects), before)
            finally:
                App.closeDocument(library.Name)


class Samples(unittest.TestCase):
    def test_build_samples_writes_into_the_out_folder(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "samples")
            env = dict(os.environ)
            run = subprocess.run([FREECADCMD, os.path.join(REPO, "samples", "freecad", "build_samples.py"), "--out", out],
                                 env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=600)
            self.assertEqual(run.returncode, 0, run.stdout[-2000:])
            self.assertNotIn("not supported", run.stdout)
            # The coupling samples (couplings.py) too: the engine has the coupling rows.
            self.assertEqual(sorted(os.listdir(out)), ["fourbar-clash.FCStd", "fourbar.FCStd", "leg.FCStd",
                                                  "parade.FCStd", "planetary.FCStd", "rssr.FCStd", "side-rods.FCStd",
                                                  "slider-crank.FCStd", "steering.FCStd", "three-gears.FCStd",
                                                  "vice.FCStd", "walker-rigid.FCStd", "walker.FCStd"])


class WorkbenchFiles(unittest.TestCase):
    def test_methods_use_no_name_from_the_top_of_init_files(self):
        """FreeCAD 0.20 runs Init.py and InitGui.py so that their top-level names are gone by the time
        a method of theirs runs (installed, the workbench once failed to start: "name 'TOOLBAR' is
        not defined"): methods import what they use."""
        for name in ("Init.py", "InitGui.py"):
            tree = ast.parse(open(os.path.join(REPO, "freecad_workbench", name)).read())
            top = set()
            for node in tree.body:
                if isinstance(node, (ast.Import, ast.ImportFrom)):
                    top |= {(a.asname or a.name).split(".")[0] for a in node.names}
                elif isinstance(node, (ast.FunctionDef, ast.ClassDef)):
                    top.add(node.name)
                elif isinstance(node, ast.Assign):
                    top |= {n.id for t in node.targets for n in ast.walk(t) if isinstance(n, ast.Name)}
            for cls in (n for n in tree.body if isinstance(n, ast.ClassDef)):
                for method in (n for n in cls.body if isinstance(n, ast.FunctionDef)):
                    used = {n.id for n in ast.walk(method) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
                    local = {n.id for n in ast.walk(method) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}
                    local |= {(a.asname or a.name).split(".")[0] for n in ast.walk(method)
                              if isinstance(n, (ast.Import, ast.ImportFrom)) for a in n.names}
                    self.assertEqual((used & top) - local, set(), "%s: %s.%s" % (name, cls.name, method.name))


    def test_qt_comes_through_freecads_shim(self):
        """Qt is imported through FreeCAD's PySide shim (dispcon_fc/qt.py), never a binding by name,
        so the workbench runs on whichever Qt FreeCAD was built with."""
        bindings = {"PySide2", "PySide6", "shiboken2", "shiboken6"}
        for root, _, files in os.walk(os.path.join(REPO, "freecad_workbench")):
            for name in (f for f in files if f.endswith(".py")):
                path = os.path.join(root, name)
                if os.path.relpath(path, REPO) == os.path.join("freecad_workbench", "dispcon_fc", "qt.py"):
                    continue
                for node in ast.walk(ast.parse(open(path).read())):
                    names = ([a.name for a in node.names] if isinstance(node, ast.Import)
                             else [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
                    for n in names:
                        self.assertNotIn(n.split(".")[0], bindings, "%s:%d imports %s" % (path, node.lineno, n))
        from dispcon_fc import qt
        self.assertTrue(qt.QtCore.__name__.startswith("PySide"))
        self.assertTrue(hasattr(qt.QtWidgets, "QWidget"))

class FrameCase(unittest.TestCase):
    """An arm fixed on a base, for the offsets of part 2's joint frame."""

    def setUp(self):
        self.doc = App.newDocument("frame")

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def fixed(self):
        asm, base, arm = arm_on_base(self.doc)
        arm.Placement = App.Placement(App.Vector(0.2, 0.1, 0.3), App.Rotation(App.Vector(0, 0, 1), 20))
        j = da.add_joint(asm, "Fixed", pin(base, (0, 0, 0)), pin(arm, (0, 0, 0)))
        self.assertTrue(da.solve(asm).converged)
        return asm, base, arm, j

    def reopened(self, tmp, name):
        """The document saved as `name` in `tmp` and opened again: its assembly, joint and arm."""
        path = os.path.join(tmp, name)
        self.doc.saveAs(path)
        App.closeDocument(self.doc.Name)
        self.doc = App.openDocument(path)
        asm = next(o for o in self.doc.Objects if da.is_assembly(o))
        return asm, da.joints(asm)[0], self.doc.getObject("Arm")

    def assertPlaced(self, pl, expected, tol=1e-7):
        self.assertLess((pl.Base - expected.Base).Length, tol, (pl, expected))
        self.assertLess(pl.Rotation.multiply(expected.Rotation.inverted()).Angle, tol, (pl, expected))


class FrameRotation(FrameCase):
    """The rotation offset of part 2's joint frame (yaw, pitch, roll), against the pose it must
    give: the pose without it turned by as much about the joint's frame."""

    def test_a_turned_frame_turns_part_2_in_the_joints_frame(self):
        asm, base, arm, j = self.fixed()
        p0 = arm.Placement
        point, axis = base.Placement.multVec(j.Point1), base.Placement.Rotation.multVec(j.Axis1)
        da.edit_joint(j, frame=(30, 0, 0))
        self.assertEqual((j.FrameYaw.Value, j.FramePitch.Value, j.FrameRoll.Value), (30, 0, 0))
        self.assertTrue(da.solve(asm).converged)
        turn = App.Rotation(axis, 30)  # yaw: about the joint's axis, right-handed
        self.assertPlaced(arm.Placement, App.Placement(point + turn.multVec(p0.Base - point),
                                                       turn.multiply(p0.Rotation)))
        # Pitch 90: part 2's picked axis stands across part 1's, their points still together.
        da.edit_joint(j, joint_type="Revolute", frame=(0, 90, 0))
        self.assertTrue(da.solve(asm).converged)
        a1 = base.Placement.Rotation.multVec(j.Axis1)
        a2 = arm.Placement.Rotation.multVec(j.Axis2)
        self.assertLess(abs(a1.dot(a2)) / (a1.Length * a2.Length), 1e-8)
        self.assertLess((base.Placement.multVec(j.Point1) - arm.Placement.multVec(j.Point2)).Length, 1e-8)
        # Back to none: the pose without it.
        da.edit_joint(j, joint_type="Fixed", frame=(0, 0, 0))
        self.assertTrue(da.solve(asm).converged)
        self.assertPlaced(arm.Placement, p0)

    def test_saved_refused_and_types_without_a_frame(self):
        asm, base, arm, j = self.fixed()
        # The property editor shows what the type takes: a frame, no ratio nor phase.
        self.assertEqual([j.getEditorMode(n) for n in ("FrameYaw", "Ratio", "Phase", "MeshOffset")],
                         [[], ["Hidden"], ["Hidden"], ["Hidden"]])
        j.JointType = "Ball"  # as the property editor changes it
        self.assertEqual(j.getEditorMode("FrameYaw"), ["Hidden"])
        j.JointType = "Fixed"
        da.edit_joint(j, frame=(-45, 0, 10))
        self.assertTrue(da.solve(asm).converged)
        placed = arm.Placement
        # Refused at the engine's door (a NaN angle turns the axis into NaNs), nothing changed.
        with self.assertRaisesRegex(ValueError, "Fixed"):
            da.edit_joint(j, frame=(float("nan"), 0, 0))
        self.assertEqual((j.FrameYaw.Value, j.FramePitch.Value, j.FrameRoll.Value), (-45, 0, 10))
        with self.assertRaisesRegex(ValueError, "Ball joint's frame takes no rotation offset"):
            da.edit_joint(j, joint_type="Ball", frame=(10, 0, 0))
        self.assertEqual(j.JointType, "Fixed")
        with tempfile.TemporaryDirectory() as tmp:
            asm, j, arm = self.reopened(tmp, "frame.FCStd")
            self.assertEqual((j.FrameYaw.Value, j.FramePitch.Value, j.FrameRoll.Value), (-45, 0, 10))
            self.assertTrue(da.solve(asm).converged)
            self.assertPlaced(arm.Placement, placed, 1e-9)


class FrameTranslation(FrameCase):
    """The translation offset of part 2's joint frame across the axis (FrameX, FrameY), against
    the pose it must give: the pose without it moved by as much along the joint frame's x and y
    (part 1's twist reference, and the axis times it, in the world)."""

    def joint_axes(self, base, j):
        """The joint frame's x and y in the world: part 1's twist reference made square to its
        axis, and the axis times it."""
        rot = base.Placement.Rotation
        z = rot.multVec(j.Axis1).normalize()
        x = rot.multVec(j.Perp1)
        x = (x - z * x.dot(z)).normalize()
        return x, z.cross(x), z

    def test_a_moved_frame_moves_part_2_in_the_joints_frame(self):
        asm, base, arm, j = self.fixed()
        p0 = arm.Placement
        x, y, z = self.joint_axes(base, j)
        da.edit_joint(j, shift=(0.25, -0.1))
        self.assertEqual((j.FrameX.Value, j.FrameY.Value), (0.25, -0.1))
        self.assertTrue(da.solve(asm).converged)
        self.assertPlaced(arm.Placement, App.Placement(p0.Base + x * 0.25 - y * 0.1, p0.Rotation))
        # Turned and moved: yawed about the joint's point, then moved in the joint's frame.
        point = base.Placement.multVec(j.Point1)
        da.edit_joint(j, frame=(30, 0, 0), shift=(0.2, 0.0))
        self.assertTrue(da.solve(asm).converged)
        turn = App.Rotation(z, 30)
        self.assertPlaced(arm.Placement, App.Placement(point + turn.multVec(p0.Base - point) + x * 0.2,
                                                       turn.multiply(p0.Rotation)))
        # A revolute so moved turns part 2 about part 1's axis with its picked point 0.3 off it,
        # driven or not.
        da.edit_joint(j, joint_type="Revolute", frame=(0, 0, 0), shift=(0.0, 0.3))
        self.assertTrue(da.solve(asm).converged)
        for angle in (0, 40, 95):
            if angle:
                da.drive(asm, j, [angle])
            p2 = arm.Placement.multVec(j.Point2)
            off = p2 - point
            self.assertAlmostEqual((off - z * off.dot(z)).Length, 0.3, delta=1e-8)
        # Back to none: the pose without it.
        da.edit_joint(j, joint_type="Fixed", shift=(0, 0))
        self.assertTrue(da.solve(asm).converged)
        self.assertPlaced(arm.Placement, p0)

    def test_the_moved_frame_saved_refused_and_types_without_one(self):
        asm, base, arm, j = self.fixed()
        self.assertEqual([j.getEditorMode(n) for n in ("FrameX", "FrameY")], [[], []])
        j.JointType = "Ball"  # as the property editor changes it
        self.assertEqual([j.getEditorMode(n) for n in ("FrameX", "FrameY")], [["Hidden"], ["Hidden"]])
        j.JointType = "Fixed"
        da.edit_joint(j, shift=(0.1, 0.2))
        self.assertTrue(da.solve(asm).converged)
        placed = arm.Placement
        # Refused at the engine's door (a NaN moves part 2's point to NaNs), nothing changed.
        for bad in ((float("nan"), 0), (0, float("inf"))):
            with self.assertRaisesRegex(ValueError, "Fixed.*frame moved"):
                da.edit_joint(j, shift=bad)
            self.assertEqual((j.FrameX.Value, j.FrameY.Value), (0.1, 0.2))
        with self.assertRaisesRegex(ValueError, "not \\('a', 0\\)"):
            da.edit_joint(j, shift=("a", 0))
        with self.assertRaisesRegex(ValueError, "Ball joint's frame takes no translation offset"):
            da.edit_joint(j, joint_type="Ball", shift=(0.3, 0))
        self.assertEqual(j.JointType, "Fixed")
        with self.assertRaisesRegex(ValueError, "frame takes no translation offset"):
            da.add_joint(asm, "Ball", pin(base, (0, 0, 0)), pin(arm, (0, 0, 0)), shift=(0.1, 0))
        self.assertEqual(len(da.joints(asm)), 1)  # the refused joint undone
        self.assertPlaced(arm.Placement, placed, 1e-12)
        with tempfile.TemporaryDirectory() as tmp:
            asm, j, arm = self.reopened(tmp, "moved.FCStd")
            self.assertEqual((j.FrameX.Value, j.FrameY.Value), (0.1, 0.2))
            self.assertTrue(da.solve(asm).converged)
            self.assertPlaced(arm.Placement, placed, 1e-9)

    def test_a_moved_and_turned_frame_through_a_dcl_file(self):
        """FrameX 0.3, FrameY -0.2 and a yaw of 30 degrees exported to a .dcl and imported into a
        fresh document holding the same parts and joint. The .dcl format has no statement for a
        joint frame's offset (shared/spec/format.md), so the file holds part 2's point, axis and
        twist reference moved and turned by it: the command line solves it to the same poses, the
        import places the parts there and leaves the joint's properties as the designer set them,
        and a Solve afterwards moves nothing (the joint and the file agree)."""
        def built(doc):
            asm, base, arm = arm_on_base(doc)
            arm.Placement = App.Placement(App.Vector(0.2, 0.1, 0.3), App.Rotation(App.Vector(0, 0, 1), 20))
            j = da.add_joint(asm, "Fixed", pin(base, (0, 0, 0)), pin(arm, (0, 0, 0)),
                             frame=(30, 0, 0), shift=(0.3, -0.2))
            return asm, arm, j

        def frame_of(j):
            return [getattr(j, n).Value for n in ("FrameX", "FrameY", "FrameYaw", "FramePitch", "FrameRoll")]

        asm, arm, j = built(self.doc)
        self.assertTrue(da.solve(asm).converged)
        set_by_hand = frame_of(j)
        self.assertEqual(set_by_hand, [0.3, -0.2, 30, 0, 0])
        solved = arm.Placement
        # Part 2 stands where the offsets put it: its picked point 0.3, -0.2 off part 1's in the
        # joint's frame (part 1's twist reference, and the axis times it), turned by the yaw.
        base = self.doc.getObject("Base")
        x, y, z = self.joint_axes(base, j)
        off = arm.Placement.multVec(j.Point2) - base.Placement.multVec(j.Point1)
        self.assertLess((off - (x * 0.3 - y * 0.2)).Length, 1e-9)
        fresh = App.newDocument("frame_dcl")
        try:
            with tempfile.TemporaryDirectory() as tmp:
                path = os.path.join(tmp, "moved.dcl")
                da.export_dcl(asm, path)
                self.assertEqual(frame_of(j), set_by_hand)  # exporting changes nothing
                # The command line's side: the file alone solves to the workbench's pose.
                m = da.engine.load().load(path)
                self.assertTrue(m.assemble().converged)
                m.save(path)
                asm2, arm2, j2 = built(fresh)
                self.assertGreater((arm2.Placement.Base - solved.Base).Length, 0.1)  # not solved yet
                da.import_dcl(asm2, path)
                self.assertPlaced(arm2.Placement, solved, 1e-9)
                self.assertEqual(frame_of(j2), set_by_hand)
                r = da.solve(asm2)
                self.assertTrue(r.converged)
                self.assertEqual(r.iterations, 0)
                self.assertPlaced(arm2.Placement, solved, 1e-9)
                # Into the original document too: nothing of the joint lost, the pose the same.
                da.import_dcl(asm, path)
                self.assertEqual(frame_of(j), set_by_hand)
                self.assertPlaced(arm.Placement, solved, 1e-9)
        finally:
            App.closeDocument(fresh.Name)


class MarkerLayout(unittest.TestCase):
    """markers.spread, the screen layout of the joints' markers, against what it promises."""

    def test_crowded_markers_are_set_a_gap_apart_and_lone_ones_stay(self):
        from dispcon_fc import markers

        gap = 40.0
        # A planet's three (10 px apart on a line), three at one point seeded side by side, one alone.
        anchors = [(0, 0), (10, 0), (20, 0), (300, 300), (300, 300), (300, 300), (-400, 50)]
        seeds = [(0, 0)] * 3 + [(0, 0), (gap, 0), (2 * gap, 0)] + [(0, 0)]
        out = markers.spread(anchors, gap, seeds)
        pos = [(a[0] + o[0], a[1] + o[1]) for a, o in zip(anchors, out)]
        for i in range(len(pos)):
            for k in range(i + 1, len(pos)):
                self.assertGreaterEqual(math.hypot(pos[i][0] - pos[k][0], pos[i][1] - pos[k][1]), gap - 1e-6)
        self.assertEqual(out[6], (0.0, 0.0))  # nothing crowds it: not moved
        self.assertEqual(out[3:6], [(0.0, 0.0), (gap, 0.0), (2 * gap, 0.0)])  # seeded apart already
        # The line's three pushed apart along it, the middle one staying at its point.
        self.assertAlmostEqual(pos[1][0], 10.0, delta=1e-6)
        self.assertTrue(all(abs(p[1]) < 1e-9 for p in pos[:3]))
        # None goes further than its seed and a gap from its point.
        self.assertTrue(all(math.hypot(*o) <= math.hypot(*s) + gap + 1e-9 for o, s in zip(out, seeds)))
        # A crowd with no room beside its joints (thirty along 300 pixels, as a long chain seen
        # whole) keeps its seeds; a readable group apart from it is still set apart.
        line = [(10.0 * k, 0.0) for k in range(30)] + [(0.0, 500.0), (5.0, 500.0)]
        out = markers.spread(line, gap)
        self.assertEqual(out[:30], [(0.0, 0.0)] * 30)
        self.assertAlmostEqual(math.hypot(out[31][0] - out[30][0] + 5.0, out[31][1] - out[30][1]), gap, delta=1e-3)

    def test_a_slanted_chain_without_room_is_left_as_seeded_without_passes(self):
        # A chain seen slantwise (a zoomed 400-joint chain in an isometric view): its box has
        # room for its markers, the strip they can reach has not. It is left as seeded at once,
        # where it was pushed to and fro for every pass before going back to its seeds anyway.
        from dispcon_fc import markers

        gap = 46.2
        chain = [(6.0 * k, 4.0 * k) for k in range(120)]
        n = len(chain)
        # The room is an upper bound of the strip within a gap and a half of the joints (at most
        # its length times three gaps and the ends' discs, cells whole), far below the box.
        room = markers._room(markers.np.array(chain), [1.5 * gap] * n, gap)
        length = math.hypot(6.0 * (n - 1), 4.0 * (n - 1))
        self.assertGreaterEqual(room, length * 3 * gap)
        self.assertLess(room, 0.5 * (6.0 * n + 2 * gap) * (4.0 * n + 2 * gap))
        self.assertGreater(0.866 * n * gap * gap, room)  # so: no room for a gap between them
        passes = []
        bincount = markers.np.bincount
        markers.np.bincount = lambda *a, **k: passes.append(1) or bincount(*a, **k)
        try:
            out = markers.spread(chain, gap)
        finally:
            markers.np.bincount = bincount
        self.assertEqual(out, [(0.0, 0.0)] * n)
        self.assertEqual(passes, [], "the hopeless chain was pushed about")
        # A crowd with room in its strip is still set apart (four markers on one point).
        out = markers.spread([(0.0, 0.0)] * 4, gap)
        self.assertTrue(all(math.hypot(*o) > 1.0 for o in out))

    def test_hundreds_of_markers_are_set_apart_as_every_pair_says(self):
        # 400 markers in crowds of four over a 2000 x 1400 pixel plane (the layout runs in numpy
        # over a list of the pairs that can come within a gap): measured pair by pair afterwards.
        import random

        from dispcon_fc import markers

        gap, rng = 46.2, random.Random(7)
        anchors = []
        for _ in range(100):
            x, y = rng.uniform(0, 2000), rng.uniform(0, 1400)
            anchors += [(x + rng.uniform(-8, 8), y + rng.uniform(-8, 8)) for _ in range(4)]
        out = markers.spread(anchors, gap)
        pos = [(a[0] + o[0], a[1] + o[1]) for a, o in zip(anchors, out)]
        moved = [k for k, o in enumerate(out) if o != (0.0, 0.0)]
        self.assertGreater(len(moved), 250)  # most crowds were set apart, not left as seeded
        # A marker moved is a gap from every other marker, and no further than a gap from its point.
        for i in moved:
            self.assertLessEqual(math.hypot(*out[i]), gap + 1e-9)
            for k in range(len(pos)):
                if k != i:
                    self.assertGreaterEqual(math.hypot(pos[i][0] - pos[k][0], pos[i][1] - pos[k][1]),
                                            gap * (1 - 1e-3) - 1e-9)

    def test_markers_off_the_screen_are_not_laid_out(self):
        from dispcon_fc import markers

        gap = 40.0
        crowd = [(0, 0), (10, 0), (20, 0)]
        far = [(5000 + x, y) for x, y in crowd]
        seeds = [(0.0, 0.0)] * 6
        box = (-640, -450, 640, 450)
        out = markers.spread(crowd + far, gap, seeds, box=box)
        self.assertEqual(out[3:], [(0.0, 0.0)] * 3)  # three gaps and a cap off the screen: as seeded
        self.assertEqual(out[:3], markers.spread(crowd, gap, seeds[:3]))  # on it: as without a box
        # Without the box, the far crowd is set apart as the near one is.
        whole = markers.spread(crowd + far, gap, seeds)
        for a, b in zip(whole[:3], whole[3:]):
            self.assertAlmostEqual(a[0], b[0], delta=1e-9)
            self.assertAlmostEqual(a[1], b[1], delta=1e-9)

    def test_stacks_find_a_place_across_the_grid_of_cells(self):
        # Two points a hair apart on either side of a cell's edge are one place; a point further
        # than the tolerance from the stack's first starts a stack of its own, even where it is
        # within the tolerance of the second; a point within reach of two stacks' firsts joins
        # the earlier, as a walk over the stacks in order does.
        from dispcon_fc import markers

        tol, z = 1e-6, App.Vector(0, 0, 1)
        frames = [("a", App.Vector(tol * 0.9995, 0, 0), z), ("b", App.Vector(tol * 1.0005, 0, 0), z),
                  ("c", App.Vector(tol * 2.0, 0, 0), z), ("d", App.Vector(tol * 1.9, tol * 0.1, 0), z),
                  ("e", App.Vector(tol * 0.9995, 0, 0), App.Vector(1, 0, 0))]
        out = markers.stacks(frames, tol)
        self.assertEqual(sorted(out), ["b", "d", "e"])  # c: a stack's first
        self.assertLessEqual((frames[3][1] - frames[2][1]).Length, tol)  # d within reach of c too
        self.assertEqual((out["b"][0], out["d"][0], out["e"][0]), (1, 2, 3))
        # The stack's direction is across its first marker's axis (z: along -x, as before).
        self.assertAlmostEqual((out["e"][1] - out["b"][1]).Length, 0.0, delta=1e-15)
        self.assertAlmostEqual(abs(out["b"][1].x), 1.0, delta=1e-12)


def pad_body(doc, name, rect, holes, thick, placement):
    """A PartDesign Body as a designer makes one: a sketch on its XY plane (a rectangle and
    circular holes of radius 2) padded `thick`; returns the Body."""
    import Part
    import Sketcher

    body = doc.addObject("PartDesign::Body", name)
    sk = body.newObject("Sketcher::SketchObject", name + "Sketch")
    sk.Support = (body.Origin.OriginFeatures[3], [""])
    sk.MapMode = "FlatFace"
    x0, y0, x1, y1 = rect
    corners = [App.Vector(x0, y0, 0), App.Vector(x1, y0, 0), App.Vector(x1, y1, 0), App.Vector(x0, y1, 0)]
    for i in range(4):
        sk.addGeometry(Part.LineSegment(corners[i], corners[(i + 1) % 4]), False)
    for i in range(4):
        sk.addConstraint(Sketcher.Constraint("Coincident", i, 2, (i + 1) % 4, 1))
    for x, y in holes:
        sk.addGeometry(Part.Circle(App.Vector(x, y, 0), App.Vector(0, 0, 1), 2.0), False)
    pad = body.newObject("PartDesign::Pad", name + "Pad")
    pad.Profile = sk
    pad.Length = thick
    sk.Visibility = False  # as PartDesign's Pad command leaves it
    body.Placement = placement
    doc.recompute()
    return body


def circle_named(obj, centre):
    """The name of `obj`'s circular edge centred at world point `centre`."""
    from dispcon_fc.objects import shape_of

    for i, e in enumerate(shape_of(obj).Edges):
        c = getattr(e.Curve, "Center", None)
        if c is not None and (c - App.Vector(*centre)).Length < 1e-9:
            return "Edge%d" % (i + 1)
    raise AssertionError("%s has no circle at %s" % (obj.Label, centre))


class PartDesignBodies(unittest.TestCase):
    """Parts made as PartDesign Bodies in the assembly's document (not imported): a click on a
    Body in the 3D view selects its tip feature (Pad), named so or by its path from the Body or
    from a sub-assembly's link to it; each means the Body, or the link."""

    def setUp(self):
        self.doc = App.newDocument("bodies")
        self.base = pad_body(self.doc, "Base", (-15, -5, 130, 5), [(0, 0)], 5, App.Placement(App.Vector(0, 0, -5), App.Rotation()))
        self.arm = pad_body(self.doc, "Arm", (-5, -5, 105, 5), [(0, 0), (100, 0)], 5,
                            App.Placement(App.Vector(0, 0, 0), App.Rotation(App.Vector(0, 0, 1), 30)))

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def test_adding_a_bodys_tip_adds_the_body_and_leaves_the_tip_in_it(self):
        asm = da.create_assembly(self.doc)
        self.assertIs(da.add_part(asm, self.base.Tip, grounded=True), self.base)
        self.assertEqual([o.Name for o in asm.Group], ["Base"])
        self.assertIn(self.base.Tip, self.base.Group)  # the Pad still in its Body, the Body whole
        self.assertTrue(self.base.Grounded)
        sketch = self.arm.Group[0] if self.arm.Group[0].TypeId.startswith("Sketcher") else self.arm.Group[1]
        with self.assertRaisesRegex(ValueError, "ArmSketch is a feature of the body Arm, not a part: add Arm itself"):
            da.add_part(asm, sketch)
        self.assertIn(sketch, self.arm.Group)

    def test_a_pick_named_from_the_tip_is_the_bodys_or_its_links(self):
        from dispcon_fc import subassembly
        from dispcon_fc.objects import picked

        pad = self.base.Tip
        self.assertEqual(picked(pad, "Face1"), (self.base, "Face1"))
        self.assertEqual(picked(self.base, "BasePad.Face1"), (self.base, "Face1"))
        self.assertEqual(picked(self.base, "Face1"), (self.base, "Face1"))
        asm = da.create_assembly(self.doc)
        da.add_part(asm, self.base, grounded=True)
        da.add_part(asm, self.arm)
        hole = circle_named(self.base, (0, 0, 0))
        j = da.add_joint(asm, "Revolute", (pad, hole), (self.arm, "ArmPad." + circle_named(self.arm, (0, 0, 0))))
        self.assertEqual((j.Reference1[0], j.Reference1[1][0]), (self.base, hole))
        self.assertIs(j.Reference2[0], self.arm)
        self.assertTrue(da.solve(asm).converged)
        # A flexible sub-assembly's link to the Body: picked by the path from the link.
        top = da.create_assembly(self.doc, "Top")
        inst = subassembly.insert_sub_assembly(top, asm, placement=App.Placement(App.Vector(0, 0, 30), App.Rotation()),
                                               rigid=False)
        link = next(o for o in inst.Group if o.TypeId == "App::Link" and o.LinkedObject is self.arm)
        end = link.Placement.multVec(App.Vector(100, 0, 5))
        self.assertEqual(picked(link, "ArmPad.Edge3"), (link, "Edge3"))
        other = pad_body(self.doc, "Other", (-5, -5, 5, 5), [(0, 0)], 5, App.Placement(end, App.Rotation()))
        da.add_part(top, other)
        k = da.add_joint(top, "Revolute", (link, "ArmPad." + circle_named(link, (end.x, end.y, end.z))),
                         (other.Tip, circle_named(other, (end.x, end.y, end.z))))
        self.assertIs(k.Reference1[0], link)
        self.assertIs(k.Reference2[0], other)


UNIT_TESTS = (NothingLostWithoutTheWorkbench, InstalledLikeAnAddon, RobustOperations, Samples, WorkbenchFiles,
              MarkerLayout, FrameRotation, FrameTranslation, Messages, SolveWritesOnlyWhatChanged,
              StudyInWords, PartDesignBodies)


def run_unit_tests():
    """The unittest classes, counted with the tests above; returns (passed, failed)."""
    suite = unittest.TestSuite(unittest.defaultTestLoader.loadTestsFromTestCase(c) for c in UNIT_TESTS)
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
    failed = len(result.failures) + len(result.errors)
    return result.testsRun - failed, failed


if not os.environ.get("DISPCON_IMPORT_ONLY"):
    for fn in TESTS:
        run(fn)
    unit_passed, unit_failed = run_unit_tests()
    passed = len(TESTS) - len(FAILED) + unit_passed
    print("%d passed, %d failed" % (passed, len(FAILED) + unit_failed))
    if FAILED or unit_failed:
        sys.exit(1)
    # freecadcmd would open the arguments after this script as documents.
    sys.exit(0)
