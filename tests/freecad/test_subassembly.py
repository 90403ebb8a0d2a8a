"""Sub-assemblies in real FreeCAD (freecadcmd): a four-bar leg saved as its own .FCStd, placed
four times on a frame (linked from that file, or from the same document), flexible and rigid;
drags in each place, degrees of freedom counted by hand, save and reopen (also through a session
without the workbench), and the leg's file never written to. Each class opens and closes its own
documents."""
import hashlib
import math
import os
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "freecad_workbench"))
sys.path.insert(0, os.path.join(REPO, "samples", "freecad"))
sys.path.insert(0, HERE)
os.environ["DISPCON_IMPORT_ONLY"] = "1"  # test_headless's helpers, not its tests

import FreeCAD as App  # noqa: E402

import dispcon_fc.assembly as da  # noqa: E402
import parts  # noqa: E402
import test_headless as th  # noqa: E402

LEGS = ((0, 0), (6, 0), (0, 6), (6, 6))


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def make_leg(tmp):
    """The leg: test_headless's four-bar (ground plate grounded, A=1, B=3, C=2.5, D=3) solved
    and saved as leg.FCStd; returns its path."""
    doc = App.newDocument("leg")
    asm, g, crank, coupler, rocker = th.fourbar(doc, tmp)
    asm.Label = "Leg"
    g.Label, crank.Label, rocker.Label = "Hip", "Crank", "Rocker"
    assert da.solve(asm).converged
    path = os.path.join(tmp, "leg.FCStd")
    doc.saveAs(path)
    App.closeDocument(doc.Name)
    return path


def part(sub, label):
    return next(p for p in da.instance_parts(sub) if p.LinkedObject.Label == label)


def make_walker(tmp, source, rigid, hip_joints=("Fixed",) * 4, name="walker"):
    """A grounded frame with a boss under each leg and `source` (a path or an assembly) placed
    at LEGS, each hip pinned on its boss by hip_joints[k] (Fixed or Revolute), 0.1 above it."""
    doc = App.newDocument(name) if isinstance(source, str) else source.Document
    if isinstance(source, str):
        doc.saveAs(os.path.join(tmp, name + ".FCStd"))
    asm = da.create_assembly(doc, "Walker")
    frame = doc.addObject("Part::Feature", "Frame")
    frame.Shape = parts.frame(LEGS)
    da.add_part(asm, frame, grounded=True)
    subs = []
    for k, ((x, y), kind) in enumerate(zip(LEGS, hip_joints)):
        sub = da.insert_sub_assembly(asm, source, placement=App.Placement(App.Vector(x, y, 0.2), App.Rotation()),
                                     rigid=rigid, name="Leg%d" % (k + 1))
        edge = parts.circle_edge(part(sub, "Hip").LinkedObject.Shape, App.Vector(0, 0, 0))
        boss = parts.circle_edge(frame.Shape, App.Vector(x, y, 0.1))
        # The three reference forms: (instance, "Hip.EdgeN"), (assembly, "LegK.Hip.EdgeN"), (link, "EdgeN").
        ref = [(sub, "Hip." + edge), (asm, "%s.Hip.%s" % (sub.Label, edge)), (part(sub, "Hip"), edge)][k % 3]
        da.add_joint(asm, kind, (frame, boss), ref, offset=0.1)
        subs.append(sub)
    r = da.solve(asm)
    assert r.converged, r.message
    return doc, asm, frame, subs


def gaps(asm):
    """Every joint's gap, from the document's placements (not the solver's): its two points
    apart, and its two axes' sine, for every joint of the parent and of each flexible leg."""
    a = da.Adapter(asm)
    out = []
    for j in a.joints:
        p1, p2 = j.Reference1[0].Placement, j.Reference2[0].Placement
        w1 = p1.multVec(j.Point1 + j.Axis1 * j.Offset.Value)
        w2 = p2.multVec(j.Point2)
        a1, a2 = p1.Rotation.multVec(j.Axis1), p2.Rotation.multVec(j.Axis2)
        out.append(((w1 - w2).Length, a1.cross(a2).Length, j.Label))
    return out


def poses(subs):
    return {p.Name: p.Placement for s in subs for p in da.instance_parts(s)}


def relative(a, b):
    return a.Placement.inverse().multiply(b.Placement)


def turned_about_pin(obj, degrees):
    """`obj`'s placement turned about z through its own origin (the crank's hip pin)."""
    pl = obj.Placement
    return App.Placement(pl.Base, App.Rotation(App.Vector(0, 0, 1), degrees).multiply(pl.Rotation))


def turn_cranks(asm, subs, degrees=(0, 90, 180, 270)):
    """Each leg's crank turned by its own angle about its hip pin (the places move
    independently), each drag converged."""
    for sub, deg in zip(subs, degrees):
        crank = part(sub, "Crank")
        if deg:
            assert da.drag(asm, crank, turned_about_pin(crank, deg), steps=max(2, deg // 10)).converged


def add_pedal(leg, crank):
    """The leg gains a part after it was placed: a pedal fixed on its crank's far pin."""
    pedal = leg.Document.addObject("Part::Feature", "Pedal")
    pedal.Shape = parts.link(0.5)
    pedal.Placement = crank.Placement.multiply(App.Placement(App.Vector(1, 0, 0.1), App.Rotation()))
    da.add_part(leg, pedal)
    da.add_joint(leg, "Fixed", (crank, parts.circle_edge(crank.Shape, App.Vector(1, 0, 0.1))),
                 (pedal, parts.circle_edge(pedal.Shape, App.Vector(0, 0, 0))))
    return pedal


def angle_in(obj, frame):
    x = frame.Placement.inverse().multiply(obj.Placement).Rotation.multVec(App.Vector(1, 0, 0))
    return math.atan2(x.y, x.x)


class Walker(unittest.TestCase):
    """Each test with its own leg.FCStd (and its digest) and walker, closed afterwards."""

    RIGID, HIP_JOINTS = False, ("Fixed",) * 4

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.leg = make_leg(self.tmp.name)
        self.before = digest(self.leg)
        self.doc, self.asm, self.frame, self.subs = make_walker(self.tmp.name, self.leg, rigid=self.RIGID,
                                                                hip_joints=self.HIP_JOINTS)

    def tearDown(self):
        for name in list(App.listDocuments()):
            App.closeDocument(name)
        self.tmp.cleanup()


class Flexible(Walker):

    def test_each_leg_drags_alone_and_every_joint_holds(self):
        leg1 = self.subs[0]
        crank, hip, rocker = part(leg1, "Crank"), part(leg1, "Hip"), part(leg1, "Rocker")
        start = angle_in(crank, hip)
        others = {n: pl for n, pl in poses(self.subs[1:]).items()}
        r = da.drag(self.asm, crank, turned_about_pin(crank, 40), steps=20)
        self.assertTrue(r.converged)
        self.assertAlmostEqual(math.remainder(angle_in(crank, hip) - start - math.radians(40), 2 * math.pi), 0, delta=1e-9)
        # Leg 1 is a four-bar: its rocker follows Freudenstein's closure, in the leg's frame.
        err = math.remainder(angle_in(rocker, hip) - th.freudenstein(angle_in(crank, hip)), 2 * math.pi)
        self.assertLess(abs(err), 1e-8)
        for n, pl in poses(self.subs[1:]).items():
            self.assertTrue(th.same(pl, others[n], 1e-12), "%s moved with leg 1" % n)
        # Its hip, bolted on, stays (within the solver's tolerance).
        self.assertTrue(th.same(hip.Placement, self.subs[0].Placement, 1e-9))
        for gap, tilt, label in gaps(self.asm):
            self.assertLess(gap, 1e-9, label)
            self.assertLess(tilt, 1e-9, label)
        # Then leg 3 alone: leg 1 stays where its drag left it.
        leg1_now = poses(self.subs[:1])
        crank3 = part(self.subs[2], "Crank")
        self.assertTrue(da.drag(self.asm, crank3, turned_about_pin(crank3, -25), steps=10).converged)
        for n, pl in poses(self.subs[:1]).items():
            self.assertTrue(th.same(pl, leg1_now[n], 1e-12), n)
        # The per-instance placements are kept in the parent: in the leg's frame, as placed.
        for s in self.subs:
            for p in da.instance_parts(s):
                self.assertTrue(th.same(s.Placement.multiply(p.LocalPlacement), p.Placement, 1e-12), p.Label)
        self.assertEqual(digest(self.leg), self.before, "solving the walker wrote to leg.FCStd")

    def test_moving_an_instance_carries_its_parts_and_dcl_round_trip(self):
        leg4 = self.subs[3]
        local = {p.Name: p.LocalPlacement for p in da.instance_parts(leg4)}
        dcl = os.path.join(self.tmp.name, "walker.dcl")
        da.export_dcl(self.asm, dcl)
        before = poses(self.subs)
        # The instance's Placement moved in the property editor: its parts come along.
        leg4.Placement = App.Placement(App.Vector(9, 9, 1), App.Rotation(App.Vector(0, 0, 1), 30))
        for p in da.instance_parts(leg4):
            self.assertTrue(th.same(p.Placement, leg4.Placement.multiply(local[p.Name]), 1e-12), p.Label)
        leg4.Placement = App.Placement(App.Vector(6, 6, 0.2), App.Rotation())
        crank = part(self.subs[0], "Crank")
        self.assertTrue(da.drag(self.asm, crank, turned_about_pin(crank, 50), steps=5).converged)
        # Back from the .dcl: every leg's parts where they were, kept in their instances' frames too.
        da.import_dcl(self.asm, dcl)
        for s in self.subs:
            for p in da.instance_parts(s):
                self.assertTrue(th.same(p.Placement, before[p.Name], 1e-9), p.Label)
                self.assertTrue(th.same(s.Placement.multiply(p.LocalPlacement), p.Placement, 1e-12), p.Label)

    def test_dof_counted_by_hand(self):
        # Each leg: 4 bodies (24) - Fixed (6) - 4 revolutes of a planar loop (20, 3 of them
        # redundant: 17) = 1; four legs: 4.
        c = da.check(self.asm)
        self.assertEqual(c["dof"], 4, c["message"])
        self.assertEqual(c["part_dof"]["Leg2.Crank"], 1)
        self.assertEqual(c["part_dof"]["Leg2.Hip"], 0)
        # Only each leg's loop repeats equations; the hips are held by the Fixed joints alone (the
        # leg's file grounds its hip plate: here it is free, as FreeCAD 1.x has it).
        self.assertEqual(sorted(j.Label for j in c["redundant"]), ["Leg%d.Revolute003" % k for k in (1, 2, 3, 4)])
        self.assertTrue(all(not p.Grounded for s in self.subs for p in da.instance_parts(s)))
        # A leg made rigid contributes 6 minus what holds it: 6 - 6 = 0.
        da.set_rigid(self.subs[0], True)
        self.assertEqual(da.check(self.asm)["dof"], 3)
        da.set_rigid(self.subs[0], False)
        self.assertEqual(da.check(self.asm)["dof"], 4)

    def test_saved_reopened_without_then_with_the_workbench(self):
        crank2 = part(self.subs[1], "Crank")
        self.assertTrue(da.drag(self.asm, crank2, turned_about_pin(crank2, 70), steps=10).converged)
        path = self.doc.FileName
        self.doc.save()
        saved = {p.Label: (p.Placement, p.LocalPlacement) for s in self.subs for p in da.instance_parts(s)}
        for name in list(App.listDocuments()):
            App.closeDocument(name)
        # Opened where the workbench is missing (a session of its own), then saved.
        with tempfile.TemporaryDirectory() as home:
            th.freecad_session(WITHOUT_WORKBENCH, home, path)
        doc = App.openDocument(path)
        asm = doc.getObject("Walker")
        subs = da.sub_assemblies(asm)
        self.assertEqual([s.Label for s in subs], ["Leg1", "Leg2", "Leg3", "Leg4"])
        self.assertTrue(all(s.Proxy is None for s in subs))  # lost in that session, found by DispconType
        for s in subs:
            self.assertFalse(s.Rigid)
            self.assertEqual(s.Assembly.Label, "Leg")
            for p in da.instance_parts(s):
                pl, local = saved[p.Label]
                self.assertTrue(th.same(p.Placement, pl, 1e-9) and th.same(p.LocalPlacement, local, 1e-9), p.Label)
        self.assertEqual(da.check(asm)["dof"], 4)
        r = da.solve(asm)
        self.assertTrue(r.converged, r.message)
        self.assertTrue(all(isinstance(s.Proxy, da.SubAssemblyProxy) for s in subs))
        for p in da.instance_parts(subs[1]):
            self.assertTrue(th.same(p.Placement, saved[p.Label][0], 1e-9), p.Label)
        self.assertEqual(digest(self.leg), self.before, "a session wrote to leg.FCStd")


WITHOUT_WORKBENCH = th.BARE_SESSION + """
subs = [o for o in doc.Objects if "DispconType" in o.PropertiesList and o.DispconType == "SubAssembly"]
assert len(subs) == 4, [o.Name for o in doc.Objects]
assert all(s.Proxy is None and s.Assembly is not None and len(s.Group) == 4 for s in subs)
doc.save()
print("SESSION OK")
sys.exit(0)
"""


class Rigid(Walker):
    # Leg 1 turns about its hip pin (a revolute); legs 2-4 are bolted on (Fixed).
    RIGID, HIP_JOINTS = True, ("Revolute", "Fixed", "Fixed", "Fixed")

    def test_a_rigid_leg_moves_as_one_part(self):
        leg1 = self.subs[0]
        ps = da.instance_parts(leg1)
        inside = [relative(ps[0], p) for p in ps[1:]]
        others = poses(self.subs[1:])
        crank = part(leg1, "Crank")
        r = da.drag(self.asm, crank, turned_about_pin(crank, 35), steps=10)
        self.assertTrue(r.converged)
        # The crank's drag turned the whole leg about its hip pin: nothing inside it moved.
        self.assertAlmostEqual(math.degrees(leg1.Placement.Rotation.Angle), 35, delta=1e-7)
        for rel, p in zip(inside, ps[1:]):
            self.assertTrue(th.same(relative(ps[0], p), rel, 1e-12), p.Label)
        for n, pl in poses(self.subs[1:]).items():
            self.assertTrue(th.same(pl, others[n], 1e-12), n)
        for gap, tilt, label in gaps(self.asm):
            self.assertLess(gap, 1e-9, label)
        # Its parts' placements in the instance are the leg's own, solved in its file.
        leg_doc = App.getDocument("leg")
        for p in ps:
            self.assertTrue(th.same(p.LocalPlacement, leg_doc.getObject(p.LinkedObject.Name).Placement, 1e-9))
        self.assertEqual(digest(self.leg), self.before)

    def test_a_mouse_drag_on_a_rigid_legs_part_turns_the_leg(self):
        # What drag mode does with the mouse: the grabbed point of the rocker pulled round the hip pin.
        leg1 = self.subs[0]
        ps = da.instance_parts(leg1)
        inside = [relative(ps[0], p) for p in ps[1:]]
        rocker = part(leg1, "Rocker")
        grab = rocker.Placement.multVec(App.Vector(1.25, 0, 0.1))
        pivot = leg1.Placement.Base
        d = da.PointDrag(self.asm, rocker, grab)
        for k in range(1, 11):
            d.move(pivot + App.Rotation(App.Vector(0, 0, 1), 3 * k).multVec(grab - pivot))
        d.finish()
        self.assertAlmostEqual(math.degrees(leg1.Placement.Rotation.Angle), 30, delta=0.5)
        for rel, p in zip(inside, ps[1:]):
            self.assertTrue(th.same(relative(ps[0], p), rel, 1e-12), p.Label)
        for gap, tilt, label in gaps(self.asm):
            self.assertLess(gap, 1e-9, label)

    def test_a_sweep_turns_a_rigid_leg_about_its_hip(self):
        import dispcon_fc.studies as st

        before = poses(self.subs)
        r = st.sweep(self.asm, "Revolute", steps=24, interference=False).to_json()
        self.assertFalse(r["locked"], r["message"])
        self.assertTrue(all(sample["converged"] for sample in r["samples"]))
        labels = [j["label"] for j in r["joints"]]
        turn = [sample["joint_values"][labels.index("Revolute")] for sample in r["samples"]]
        self.assertGreater(max(turn) - min(turn), 6.0)
        # A study changes nothing in the document.
        for n, pl in poses(self.subs).items():
            self.assertTrue(th.same(pl, before[n], 0), n)

    def test_dof_six_minus_what_holds_it(self):
        # Leg 1: 6 - 5 (a revolute) = 1; legs 2-4: 6 - 6 = 0.
        c = da.check(self.asm)
        self.assertEqual(c["dof"], 1, c["message"])
        self.assertEqual(c["part_dof"], {"Frame": 0, "Leg1": 1, "Leg2": 0, "Leg3": 0, "Leg4": 0})
        # Bolted on, it cannot be dragged at all.
        crank = part(self.subs[1], "Crank")
        before = poses(self.subs)
        r = da.drag(self.asm, crank, turned_about_pin(crank, 30), steps=5)
        self.assertFalse(r.converged)
        for n, pl in poses(self.subs).items():
            self.assertTrue(th.same(pl, before[n], 1e-12), n)

    def test_saved_and_reopened(self):
        self.assertTrue(da.drag(self.asm, part(self.subs[0], "Crank"),
                                turned_about_pin(part(self.subs[0], "Crank"), 50), steps=5).converged)
        saved = {s.Label: (s.Placement, s.Rigid) for s in self.subs}
        path = self.doc.FileName
        self.doc.save()
        for name in list(App.listDocuments()):
            App.closeDocument(name)
        doc = App.openDocument(path)
        asm = doc.getObject("Walker")
        for s in da.sub_assemblies(asm):
            self.assertTrue(th.same(s.Placement, saved[s.Label][0], 1e-9), s.Label)
            self.assertTrue(s.Rigid)
            for p in da.instance_parts(s):
                self.assertTrue(th.same(p.Placement, s.Placement.multiply(p.LocalPlacement), 1e-9), p.Label)
        self.assertEqual(da.check(asm)["dof"], 1)
        self.assertEqual(digest(self.leg), self.before)


class SameDocument(unittest.TestCase):
    def test_an_assembly_of_this_document_placed_twice(self):
        import dispcon_fc.studies as st

        with tempfile.TemporaryDirectory() as tmp:
            doc = App.newDocument("both")
            leg, g, crank, coupler, rocker = th.fourbar(doc, tmp)
            leg.Label, g.Label, crank.Label, rocker.Label = "Leg", "Hip", "Crank", "Rocker"
            self.assertTrue(da.solve(leg).converged)
            doc, asm, frame, subs = make_walker(tmp, leg, rigid=False, hip_joints=("Fixed", "Fixed"))
            # Only two legs: make_walker stops with the joints it was given.
            self.assertEqual(len(subs), 2)
            with self.assertRaisesRegex(ValueError, "contain itself"):
                da.insert_sub_assembly(leg, asm)
            source = {p.Name: p.Placement for p in da.parts(leg)}
            other = poses(subs[1:])
            c1 = part(subs[0], "Crank")
            self.assertTrue(da.drag(asm, c1, turned_about_pin(c1, 60), steps=10).converged)
            for n, pl in poses(subs[1:]).items():
                self.assertTrue(th.same(pl, other[n], 1e-12), n)
            for p in da.parts(leg):  # the placed assembly itself never moves with its instances
                self.assertTrue(th.same(p.Placement, source[p.Name], 0), p.Label)
            self.assertEqual(da.check(asm)["dof"], 2)
            # The leg gains a part (a pedal on its crank's far pin): Check says Solve brings it in,
            # and Solve does, in each instance.
            add_pedal(leg, crank)
            with self.assertRaisesRegex(ValueError, "Leg1: .* lacks \\(Pedal\\): Solve brings them in"):
                da.check(asm)
            self.assertTrue(da.solve(asm).converged)
            self.assertEqual([len(da.instance_parts(s)) for s in subs], [5, 5])
            self.assertEqual(da.check(asm)["dof"], 2)
            c2 = part(subs[1], "Crank")
            self.assertTrue(da.drag(asm, c2, turned_about_pin(c2, 30), steps=5).converged)
            for gap, tilt, label in gaps(asm):
                self.assertLess(gap, 1e-9, label)
            path = os.path.join(tmp, "both.FCStd")
            doc.saveAs(path)
            App.closeDocument(doc.Name)
            # The command line's opener takes the top assembly (the walker, not the leg it places).
            doc, top = st.open_assembly(path)
            try:
                self.assertEqual(top.Label, "Walker")
                self.assertEqual(st.check(top, interference=False)["dof"], 2)
            finally:
                App.closeDocument(doc.Name)


class Refused(unittest.TestCase):
    def test_bad_input_is_named_and_changes_nothing(self):
        with tempfile.TemporaryDirectory() as tmp:
            doc = App.newDocument("refused")
            asm = da.create_assembly(doc, "Top")
            with self.assertRaisesRegex(ValueError, "save"):
                da.insert_sub_assembly(asm, os.path.join(tmp, "leg.FCStd"))
            doc.saveAs(os.path.join(tmp, "refused.FCStd"))
            with self.assertRaisesRegex(ValueError, "no such file"):
                da.insert_sub_assembly(asm, os.path.join(tmp, "nowhere.FCStd"))
            make_leg(tmp)
            # A relative path works from here, and is stored so that it works from anywhere.
            cwd = os.getcwd()
            os.chdir(os.path.dirname(tmp))
            try:
                sub = da.insert_sub_assembly(asm, os.path.join(os.path.basename(tmp), "leg.FCStd"), name="Leg1")
            finally:
                os.chdir(cwd)
            doc.save()
            App.closeDocument(doc.Name)
            App.closeDocument("leg")
            doc = App.openDocument(os.path.join(tmp, "refused.FCStd"))
            asm = doc.getObject("Top")
            sub = da.sub_assemblies(asm)[0]
            self.assertEqual(sub.Assembly.Label, "Leg")
            self.assertTrue(all(p.LinkedObject is not None for p in da.instance_parts(sub)))
            with self.assertRaisesRegex(ValueError, "Leg1 has no part Foot"):
                da.add_joint(asm, "Fixed", (sub, "Foot.Edge1"), (sub, "Hip.Edge1"))
            count = len(doc.Objects)
            with self.assertRaisesRegex(ValueError, "Top has no sub-assembly Leg9"):
                da.add_joint(asm, "Fixed", (asm, "Leg9.Hip.Edge1"), (sub, "Hip.Edge1"))
            self.assertEqual(len(doc.Objects), count)
            for name in list(App.listDocuments()):
                App.closeDocument(name)


if not os.environ.get("DISPCON_SUB_IMPORT_ONLY"):  # gui_subassembly.py imports the helpers only
    suite = unittest.TestSuite(unittest.defaultTestLoader.loadTestsFromTestCase(c)
                               for c in (Flexible, Rigid, SameDocument, Refused))
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
    failed = len(result.failures) + len(result.errors)
    print("%d passed, %d failed" % (result.testsRun - failed, failed))
    # freecadcmd would open the arguments after this script as documents.
    sys.exit(1 if failed else 0)
