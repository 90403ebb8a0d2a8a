"""Nested sub-assemblies in real FreeCAD (freecadcmd): the walker of test_subassembly.py (the leg
of leg.FCStd placed four times on a frame) saved as walker.FCStd and placed twice on a track in
parade.FCStd, flexible and rigid at each level, and the parade placed again in a festival (three
levels). Degrees of freedom against the sum of the walkers', poses against the walker's own file
and Freudenstein's closure, every joint of every level within 1e-9, a save and reopen keeping every
placement, the .dcl round trip, cycles refused by name. Each class opens and closes its own
documents."""
import math
import os
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
os.environ["DISPCON_SUB_IMPORT_ONLY"] = "1"  # test_subassembly's helpers, not its tests

import test_subassembly as ts  # noqa: E402
from test_subassembly import App, add_pedal, angle_in, da, digest, gaps, parts, th, turned_about_pin  # noqa: E402

STANDS = ((0, 0), (12, 0))


def inside(obj):
    """Every link and nested instance inside an instance, at any depth."""
    out = []
    for o in obj.Group:
        out.append(o)
        if da.is_sub_assembly(o):
            out += inside(o)
    return out


def named(container, path):
    """The object at a dotted path of labels inside an instance: named(walk2, "Leg3.Crank")."""
    obj = container
    for head in path.split("."):
        obj = next(o for o in obj.Group if o.Label == "%s.%s" % (obj.Label, head))
    return obj


def placements(objs):
    return {o.Name: (o.Placement, getattr(o, "LocalPlacement", None)) for o in objs}


def make_walker_file(tmp, rigid_legs=False, hip_joints=("Fixed",) * 4):
    """leg.FCStd and walker.FCStd (saved, solved); returns (leg path, walker path, walker doc)."""
    leg = ts.make_leg(tmp)
    doc, asm, frame, subs = ts.make_walker(tmp, leg, rigid=rigid_legs, hip_joints=hip_joints)
    doc.save()
    return leg, doc.FileName, doc


def make_parade(tmp, walker, rigid, stand_joints=("Fixed", "Fixed"), name="parade"):
    """A grounded track with a boss per stand and walker.FCStd placed on each (Walk1, Walk2),
    each walker's frame held on its stand by stand_joints[k], its frame's first boss 0.2 above."""
    doc = App.newDocument(name)
    doc.saveAs(os.path.join(tmp, name + ".FCStd"))
    asm = da.create_assembly(doc, "Parade")
    track = doc.addObject("Part::Feature", "Track")
    track.Shape = parts.frame(STANDS)
    da.add_part(asm, track, grounded=True)
    edge = parts.circle_edge(parts.frame(ts.LEGS), App.Vector(0, 0, 0))
    walks = []
    for k, ((x, y), kind) in enumerate(zip(STANDS, stand_joints)):
        w = da.insert_sub_assembly(asm, walker, placement=App.Placement(App.Vector(x + 1, y + 1, 0.5), App.Rotation()),
                                   rigid=rigid, name="Walk%d" % (k + 1))
        ref = [(w, "Frame." + edge), (asm, "Walk%d.Frame.%s" % (k + 1, edge))][k % 2]
        da.add_joint(asm, kind, (track, parts.circle_edge(track.Shape, App.Vector(x, y, 0.1))), ref, offset=0.2)
        walks.append(w)
    r = da.solve(asm)
    assert r.converged, r.message
    return doc, asm, track, walks


def relative_to(obj, frame):
    return frame.Placement.inverse().multiply(obj.Placement)


class Parade(unittest.TestCase):
    RIGID, RIGID_LEGS, HIPS, STANDS = False, False, ("Fixed",) * 4, ("Fixed", "Fixed")

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.leg, self.walker, self.wdoc = make_walker_file(self.tmp.name, self.RIGID_LEGS, self.HIPS)
        self.digests = (digest(self.leg), digest(self.walker))
        self.doc, self.asm, self.track, self.walks = make_parade(self.tmp.name, self.walker, self.RIGID, self.STANDS)

    def tearDown(self):
        for name in list(App.listDocuments()):
            App.closeDocument(name)
        self.tmp.cleanup()

    def assert_files_unchanged(self):
        self.assertEqual((digest(self.leg), digest(self.walker)), self.digests, "the parade wrote to a placed file")

    def assert_joints_hold(self, asm=None):
        checked = 0
        for gap, tilt, label in gaps(asm or self.asm):
            self.assertLess(gap, 1e-9, label)
            self.assertLess(tilt, 1e-9, label)
            checked += 1
        return checked

    def assert_locals(self):
        """Every link and nested instance where its container's Placement and its own
        LocalPlacement put it (what a save stores, per instance)."""
        for w in self.walks:
            for o in inside(w):
                container = next(i for i in o.InList if da.is_sub_assembly(i))
                self.assertTrue(th.same(container.Placement.multiply(o.LocalPlacement), o.Placement, 1e-12), o.Label)

    def assert_legs_closed(self, walks, prefix=""):
        for w in walks:
            frame = named(w, "Frame")
            for k in (1, 2, 3, 4):
                hip, crank, rocker = (named(w, "Leg%d.%s" % (k, p)) for p in ("Hip", "Crank", "Rocker"))
                self.assertTrue(th.same(relative_to(hip, frame), self.walker_pose("Leg%d.Hip" % k), 1e-9), hip.Label)
                err = math.remainder(angle_in(rocker, hip) - th.freudenstein(angle_in(crank, hip)), 2 * math.pi)
                self.assertLess(abs(err), 1e-8, rocker.Label)

    def walker_pose(self, label):
        """A part's pose in walker.FCStd, relative to its frame: what the walker's own file says."""
        frame = next(p for p in da.parts(self.wdoc.getObject("Walker")) if p.Label == "Frame")
        obj = next(o for o in self.wdoc.Objects if o.Label == label)
        return relative_to(obj, frame)


class FlexibleParade(Parade):

    def test_dof_is_the_walkers_sum_and_a_nested_crank_drags_alone(self):
        walker_dof = da.check(self.wdoc.getObject("Walker"))["dof"]
        self.assertEqual(walker_dof, 4)
        c = da.check(self.asm)
        self.assertEqual(c["dof"], 2 * walker_dof, c["message"])
        self.assertEqual(c["part_dof"]["Walk2.Leg3.Crank"], 1)
        self.assertEqual(c["part_dof"]["Walk1.Frame"], 0)
        self.assertEqual(sorted(j.Label for j in c["redundant"]),
                         ["Walk%d.Leg%d.Revolute003" % (w, k) for w in (1, 2) for k in (1, 2, 3, 4)])
        # The frames sit on their stands, 0.2 above each boss's top: the Fixed joints' offset.
        for w, (x, y) in zip(self.walks, STANDS):
            self.assertTrue(th.same(named(w, "Frame").Placement,
                                    App.Placement(App.Vector(x, y, 0.3), App.Rotation()), 1e-9), w.Label)
        # Inside each walker: the hips where walker.FCStd has them against the frame (bolted on),
        # and each leg a four-bar (its crank free: the snap onto the stands turned it as it needed).
        self.assert_legs_closed(self.walks)
        crank, hip, rocker = (named(self.walks[1], "Leg3." + p) for p in ("Crank", "Hip", "Rocker"))
        start = angle_in(crank, hip)
        before = placements(da.placed_parts(self.asm))
        r = da.drag(self.asm, crank, turned_about_pin(crank, 40), steps=20)
        self.assertTrue(r.converged)
        self.assertAlmostEqual(math.remainder(angle_in(crank, hip) - start - math.radians(40), 2 * math.pi), 0,
                               delta=1e-9)
        err = math.remainder(angle_in(rocker, hip) - th.freudenstein(angle_in(crank, hip)), 2 * math.pi)
        self.assertLess(abs(err), 1e-8)
        leg3 = named(self.walks[1], "Leg3")
        for o in da.placed_parts(self.asm):
            if o not in da.instance_parts(leg3) or o == hip:
                # The other legs only polished to the solve's tolerance (the snap left them within it).
                self.assertTrue(th.same(o.Placement, before[o.Name][0], 1e-9), o.Label)
        self.assertEqual(self.assert_joints_hold(), 2 + 2 * (4 + 4 * 4))
        self.assert_locals()
        self.assert_files_unchanged()

    def test_saved_and_reopened_every_placement_kept(self):
        crank = named(self.walks[0], "Leg2.Crank")
        self.assertTrue(da.drag(self.asm, crank, turned_about_pin(crank, 70), steps=10).converged)
        saved = {o.Label: (o.Placement, o.LocalPlacement, getattr(o, "SourceName", None), getattr(o, "Rigid", None))
                 for w in self.walks for o in inside(w)}
        saved.update({w.Label: (w.Placement, None, None, w.Rigid) for w in self.walks})
        path = self.doc.FileName
        self.doc.save()
        for name in list(App.listDocuments()):
            App.closeDocument(name)
        doc = App.openDocument(path)
        asm = doc.getObject("Parade")
        walks = da.sub_assemblies(asm)
        self.assertEqual([w.Label for w in walks], ["Walk1", "Walk2"])
        seen = 0
        for w in walks:
            for o in [w] + inside(w):
                pl, local, source, rigid = saved.pop(o.Label)
                self.assertTrue(th.same(o.Placement, pl, 1e-12), o.Label)
                if local is not None:
                    self.assertTrue(th.same(o.LocalPlacement, local, 1e-12), o.Label)
                self.assertEqual(getattr(o, "SourceName", None), source, o.Label)
                self.assertEqual(getattr(o, "Rigid", None), rigid, o.Label)
                seen += 1
        self.assertEqual(saved, {})
        self.assertEqual(seen, 2 * (1 + 1 + 4 * 5))
        self.assertEqual(da.check(asm)["dof"], 8)
        before = placements(da.placed_parts(asm))
        r = da.solve(asm)
        self.assertTrue(r.converged, r.message)
        for o in da.placed_parts(asm):
            self.assertTrue(th.same(o.Placement, before[o.Name][0], 1e-9), o.Label)
        self.asm, self.walks = asm, walks
        self.assert_joints_hold()
        self.assert_files_unchanged()

    def test_saved_where_the_workbench_is_missing_then_reopened_with_it(self):
        crank = named(self.walks[1], "Leg4.Crank")
        self.assertTrue(da.drag(self.asm, crank, turned_about_pin(crank, 30), steps=5).converged)
        saved = placements([o for w in self.walks for o in [w] + inside(w)])
        path = self.doc.FileName
        self.doc.save()
        for name in list(App.listDocuments()):
            App.closeDocument(name)
        with tempfile.TemporaryDirectory() as home:
            th.freecad_session(WITHOUT_WORKBENCH, home, path)
        doc = App.openDocument(path)
        nested = [doc.getObject(n) for n in saved if da.is_sub_assembly(doc.getObject(n))
                  and getattr(doc.getObject(n), "SourceName", "")]
        self.assertEqual(len(nested), 8)
        self.assertTrue(all(n.Proxy is None for n in nested))  # lost in that session, found by DispconType
        for name, (pl, local) in saved.items():
            o = doc.getObject(name)
            self.assertTrue(th.same(o.Placement, pl, 1e-12), o.Label)
            if local is not None:
                self.assertTrue(th.same(o.LocalPlacement, local, 1e-12), o.Label)
        asm = doc.getObject("Parade")
        self.assertEqual(da.check(asm)["dof"], 8)
        self.assertTrue(da.solve(asm).converged)
        self.assertTrue(all(isinstance(n.Proxy, da.SubAssemblyProxy) for n in nested))
        self.asm, self.walks = asm, da.sub_assemblies(asm)
        self.assert_joints_hold()
        self.assert_files_unchanged()

    def test_dcl_round_trip_names_every_level(self):
        dcl = os.path.join(self.tmp.name, "parade.dcl")
        da.export_dcl(self.asm, dcl)
        with open(dcl) as f:
            text = f.read()
        for label in ("Walk2.Leg4.Revolute003", "Walk1.Fixed"):
            self.assertIn('"%s"' % label, text)
        before = placements(da.placed_parts(self.asm))
        crank = named(self.walks[1], "Leg1.Crank")
        self.assertTrue(da.drag(self.asm, crank, turned_about_pin(crank, -50), steps=10).converged)
        self.assertFalse(th.same(crank.Placement, before[crank.Name][0], 1e-3))
        da.import_dcl(self.asm, dcl)
        for o in da.placed_parts(self.asm):
            self.assertTrue(th.same(o.Placement, before[o.Name][0], 1e-9), o.Label)
        self.assert_locals()

    def test_moving_a_walker_carries_every_level(self):
        w = self.walks[0]
        local = {o.Name: o.Placement for o in inside(w)}
        move = App.Placement(App.Vector(3, -2, 1), App.Rotation(App.Vector(0, 0, 1), 30))
        w.Placement = move.multiply(w.Placement)
        for o in inside(w):
            self.assertTrue(th.same(o.Placement, move.multiply(local[o.Name]), 1e-12), o.Label)
        self.assert_locals()
        # Solve puts it back on its stand, whole.
        self.assertTrue(da.solve(self.asm).converged)
        self.assertTrue(th.same(named(w, "Frame").Placement, App.Placement(App.Vector(0, 0, 0.3), App.Rotation()),
                                1e-9))
        self.assert_joints_hold()

    def test_three_levels_a_festival_of_parades(self):
        asm, parade = festival(self)
        c = da.check(asm)
        self.assertEqual(c["dof"], 8, c["message"])
        self.assertEqual(c["part_dof"]["P1.Walk2.Leg4.Crank"], 1)
        crank, _ = da.resolve(asm, asm, "P1.Walk2.Leg4.Crank.Edge1")
        hip, _ = da.resolve(asm, parade, "Walk2.Leg4.Hip.Edge1")
        rocker = named(parade, "Walk2.Leg4.Rocker")
        self.assertEqual((crank.Label, hip.Label), ("P1.Walk2.Leg4.Crank", "P1.Walk2.Leg4.Hip"))
        # The track's boss bottom on the ground's boss top, 0.5 up: the parade 0.6 above where its
        # file has it. What does not move in the parade (its frames and hips) where the parade has
        # it against the track, to 1e-8: each solve (the parade's, this one) holds a Fixed joint's
        # angle to 1e-9, which 6 to 8 along a frame makes a few 1e-9. Each leg a four-bar.
        track = named(parade, "Track")
        self.assertTrue(th.same(track.Placement, App.Placement(App.Vector(0, 0, 0.6), App.Rotation()), 1e-9))
        fixed = [o for o in da.placed_parts(asm)[2:] if c["part_dof"][o.Label] == 0]
        self.assertEqual(len(fixed), 2 * (1 + 4))
        for o in fixed:
            there = next(p for p in self.doc.Objects if p.Label == o.Label[len("P1."):])
            self.assertTrue(th.same(relative_to(o, track), relative_to(there, self.track), 1e-8), o.Label)
        self.assert_legs_closed([named(parade, "Walk1"), named(parade, "Walk2")])
        before = placements(da.placed_parts(asm))
        self.assertTrue(da.drag(asm, crank, turned_about_pin(crank, 25), steps=10).converged)
        err = math.remainder(angle_in(rocker, hip) - th.freudenstein(angle_in(crank, hip)), 2 * math.pi)
        self.assertLess(abs(err), 1e-8)
        # The rest polished to the solve's tolerance at most (a few 1e-9, as above).
        moved = {o.Name for o in da.instance_parts(named(parade, "Walk2.Leg4"))} - {hip.Name}
        for o in da.placed_parts(asm):
            if o.Name not in moved:
                self.assertTrue(th.same(o.Placement, before[o.Name][0], 1e-8), o.Label)
        self.assertEqual(self.assert_joints_hold(asm), 1 + 2 + 2 * (4 + 4 * 4))
        self.assert_files_unchanged()


WITHOUT_WORKBENCH = th.BARE_SESSION + """
subs = [o for o in doc.Objects if "DispconType" in o.PropertiesList and o.DispconType == "SubAssembly"]
assert len(subs) == 10, [o.Name for o in doc.Objects]
assert sum(1 for s in subs if getattr(s, "SourceName", "")) == 8 and all(s.Proxy is None for s in subs)
doc.save()
print("SESSION OK")
sys.exit(0)
"""


class RigidParade(Parade):
    # Rigid walkers (their legs flexible inside): Walk1 turns on a revolute, Walk2 is bolted on.
    RIGID, STANDS = True, ("Revolute", "Fixed")

    def test_a_rigid_walker_is_its_file_solved_and_one_body(self):
        c = da.check(self.asm)
        self.assertEqual(c["dof"], 1, c["message"])
        self.assertEqual(c["part_dof"], {"Track": 0, "Walk1": 1, "Walk2": 0})
        # Every part and nested instance, at any depth: the instance's Placement times its pose
        # in walker.FCStd (the walker's own solve, in its frame).
        for w in self.walks:
            for o in inside(w):
                there = next(p for p in self.wdoc.Objects if p.Label == o.Label.split(".", 1)[1])
                self.assertTrue(th.same(o.Placement, w.Placement.multiply(there.Placement), 1e-9), o.Label)
        self.assert_locals()

    def test_dragging_a_nested_part_turns_the_walker_whole(self):
        w1 = self.walks[0]
        objs = inside(w1)
        rel = {o.Name: relative_to(o, w1) for o in objs}
        others = placements(inside(self.walks[1]))
        rocker = named(w1, "Leg2.Rocker")
        grab = rocker.Placement.multVec(App.Vector(1.25, 0, 0.1))
        pivot = App.Vector(0, 0, 0)
        d = da.PointDrag(self.asm, rocker, grab)
        for k in range(1, 11):
            d.move(pivot + App.Rotation(App.Vector(0, 0, 1), 3 * k).multVec(grab - pivot))
        d.finish()
        self.assertGreater(math.degrees(w1.Placement.Rotation.Angle), 5)
        for o in objs:
            self.assertTrue(th.same(relative_to(o, w1), rel[o.Name], 1e-12), o.Label)
        for o in inside(self.walks[1]):
            self.assertTrue(th.same(o.Placement, others[o.Name][0], 1e-12), o.Label)
        self.assert_joints_hold()
        self.assert_locals()
        # Saved and reopened: every placement of every level back.
        saved = placements([self.walks[1], w1] + objs + inside(self.walks[1]))
        path = self.doc.FileName
        self.doc.save()
        for name in list(App.listDocuments()):
            App.closeDocument(name)
        doc = App.openDocument(path)
        for name, (pl, local) in saved.items():
            o = doc.getObject(name)
            self.assertTrue(th.same(o.Placement, pl, 1e-12), o.Label)
            if local is not None:
                self.assertTrue(th.same(o.LocalPlacement, local, 1e-12), o.Label)
        self.assertEqual(da.check(doc.getObject("Parade"))["dof"], 1)
        self.assert_files_unchanged()

    def test_inside_a_rigid_walker_a_leg_is_as_its_file_says(self):
        leg = named(self.walks[0], "Leg1")
        self.assertFalse(leg.Rigid)
        self.assertEqual(leg.getEditorMode("Rigid"), ["ReadOnly"])
        self.doc.UndoMode = 1
        undo = self.doc.UndoCount
        with self.assertRaisesRegex(ValueError, r"^Walk1.Leg1 is inside Walk1, which is rigid: it moves as "
                                                r"walker.FCStd has it \(make Walk1 flexible first\)$"):
            da.set_rigid(leg, True)
        self.assertEqual((leg.Rigid, self.doc.UndoCount), (False, undo))
        da.set_rigid(self.walks[0], False)  # the top one is the designer's: one undo step
        self.assertEqual(self.doc.UndoCount, undo + 1)
        self.assertEqual(leg.getEditorMode("Rigid"), [])  # its container flexible: this place's to set
        c = da.check(self.asm)
        # Walk1 flexible: its frame's turn on the revolute, and each of its legs' crank; Walk2: 0.
        self.assertEqual(c["dof"], 1 + 4, c["message"])
        self.assertEqual(c["part_dof"]["Walk1.Leg1.Crank"], 1)
        da.set_rigid(leg, True)  # now it can be: Walk1's frame and three legs move
        self.assertEqual(da.check(self.asm)["dof"], 1 + 3)
        self.doc.undo()
        self.doc.undo()
        self.assertEqual((self.walks[0].Rigid, leg.Rigid, leg.getEditorMode("Rigid")), (True, False, ["ReadOnly"]))
        self.assertEqual(da.check(self.asm)["dof"], 1)


class PerPlaceRigidity(Parade):
    """The parade's two walkers (flexible, each leg a flexible instance of leg.FCStd): a leg made
    rigid in one walker only. The degrees of freedom are counted here from leg.FCStd's own check
    (a flexible leg bolted by its hip: the leg's; a rigid one: 0, six held by six), not from the
    parade's; the drag, the .dcl file (solved by the engine alone) and a save agree."""

    def leg_dof(self):
        return da.check(da.top_assemblies(App.getDocument("leg"))[0])["dof"]

    def expected_dof(self, walks=None):
        legs = [named(w, "Leg%d" % k) for w in (walks or self.walks) for k in (1, 2, 3, 4)]
        return sum(0 if ts_rigid(leg) else self.leg_dof() for leg in legs)

    def test_one_walkers_leg_rigid_the_other_walkers_flexible(self):
        self.assertEqual(self.leg_dof(), 1)
        w1leg2, w2leg2 = named(self.walks[0], "Leg2"), named(self.walks[1], "Leg2")
        self.assertEqual((w1leg2.Rigid, w1leg2.getEditorMode("Rigid")), (False, []))
        self.doc.UndoMode = 1
        undo = self.doc.UndoCount
        da.set_rigid(w1leg2, True)
        self.assertEqual(self.doc.UndoCount, undo + 1)
        self.assertEqual((w1leg2.Rigid, w1leg2.RigidInFile, w2leg2.Rigid), (True, False, False))
        c = da.check(self.asm)
        self.assertEqual(self.expected_dof(), 7)
        self.assertEqual(c["dof"], self.expected_dof(), c["message"])
        self.assertEqual(c["part_dof"]["Walk1.Leg2"], 0)
        self.assertNotIn("Walk1.Leg2.Crank", c["part_dof"])
        self.assertEqual(c["part_dof"]["Walk2.Leg2.Crank"], 1)
        self.assertEqual(sorted(j.Label for j in c["redundant"]),
                         sorted("Walk%d.Leg%d.Revolute003" % (w, k) for w in (1, 2) for k in (1, 2, 3, 4)
                                if (w, k) != (1, 2)))
        # The .dcl file: the rigid leg one body, its joints not there; the engine alone counts 7.
        dcl = os.path.join(self.tmp.name, "parade.dcl")
        da.export_dcl(self.asm, dcl)
        with open(dcl) as f:
            text = f.read()
        self.assertNotIn('"Walk1.Leg2.Revolute"', text)
        self.assertIn('"Walk2.Leg2.Revolute"', text)
        from dispcon_fc import engine

        self.assertEqual(engine.load().load(dcl).check(tolerance=1e-9).dof, 7)
        # Solved: the rigid leg as leg.FCStd has it, in its hip's frame (its crank at the file's angle).
        self.assertTrue(da.solve(self.asm).converged)
        legdoc = App.getDocument("leg")
        hip = named(w1leg2, "Hip")
        for part in ("Crank", "Coupler", "Rocker"):
            there = next(o for o in legdoc.Objects if o.Label == part)
            here = relative_to(named(w1leg2, part), hip)
            self.assertTrue(th.same(here, relative_to(there, legdoc.getObject(hip.LinkedObject.Name)), 1e-9), part)
        # Dragging the rigid leg's crank moves nothing (the leg bolted on whole); the other
        # walker's leg 2 turns its crank as a four-bar, the rest staying.
        crank1, crank2 = named(w1leg2, "Crank"), named(w2leg2, "Crank")
        before = placements(da.placed_parts(self.asm))
        da.drag(self.asm, crank1, turned_about_pin(crank1, 30), steps=5)
        for o in da.placed_parts(self.asm):
            self.assertTrue(th.same(o.Placement, before[o.Name][0], 1e-9), o.Label)
        hip2, rocker2 = named(w2leg2, "Hip"), named(w2leg2, "Rocker")
        start = angle_in(crank2, hip2)
        self.assertTrue(da.drag(self.asm, crank2, turned_about_pin(crank2, 30), steps=5).converged)
        self.assertAlmostEqual(math.remainder(angle_in(crank2, hip2) - start - math.radians(30), 2 * math.pi), 0,
                               delta=1e-9)
        err = math.remainder(angle_in(rocker2, hip2) - th.freudenstein(angle_in(crank2, hip2)), 2 * math.pi)
        self.assertLess(abs(err), 1e-8)
        for o in da.instance_parts(w1leg2):
            self.assertTrue(th.same(o.Placement, before[o.Name][0], 1e-9), o.Label)
        self.assert_joints_hold()
        self.assert_locals()
        # Saved and reopened: each place's setting kept.
        path = self.doc.FileName
        self.doc.save()
        for name in list(App.listDocuments()):
            App.closeDocument(name)
        doc = App.openDocument(path)
        walks = da.sub_assemblies(doc.getObject("Parade"))
        self.assertEqual([(named(w, "Leg2").Rigid, named(w, "Leg2").RigidInFile) for w in walks],
                         [(True, False), (False, False)])
        self.assertEqual(named(walks[0], "Leg2").getEditorMode("Rigid"), [])
        self.assertEqual(da.check(doc.getObject("Parade"))["dof"], self.expected_dof(walks))
        self.assert_files_unchanged()

    def test_places_not_set_follow_their_file_places_set_keep_theirs(self):
        da.set_rigid(named(self.walks[0], "Leg2"), True)
        # walker.FCStd's Leg3 made rigid there: both walkers' Leg3 follow (neither set here).
        walker = self.wdoc.getObject("Walker")
        da.set_rigid(next(s for s in da.sub_assemblies(walker) if s.Label == "Leg3"), True)
        self.wdoc.save()
        from dispcon_fc import subassembly

        self.assertEqual(subassembly.out_of_step(self.asm), self.walks)
        self.assertEqual(da.check(self.asm)["dof"], 8 - 1 - 2)  # taken as the file says before a Solve
        self.assertTrue(da.solve(self.asm).converged)
        got = {(w.Label, k): (named(w, "Leg%d" % k).Rigid, named(w, "Leg%d" % k).RigidInFile)
               for w in self.walks for k in (2, 3)}
        self.assertEqual(got, {("Walk1", 2): (True, False), ("Walk1", 3): (True, True),
                               ("Walk2", 2): (False, False), ("Walk2", 3): (True, True)})
        self.assertEqual(da.check(self.asm)["dof"], self.expected_dof())
        self.assertEqual(self.expected_dof(), 5)
        # Set flexible in this place against its file, then as its file has it again.
        w2leg3 = named(self.walks[1], "Leg3")
        da.set_rigid(w2leg3, False)
        self.assertEqual(da.check(self.asm)["dof"], 6)
        da.set_rigid(w2leg3, None)
        self.assertEqual((w2leg3.Rigid, da.check(self.asm)["dof"]), (True, 5))
        with self.assertRaisesRegex(ValueError, r"^Walk1: rigid is True or False \(None, as its file has it, is for "
                                                r"a nested instance\)$"):
            da.set_rigid(self.walks[0], None)

    def test_a_festival_one_walker_rigid_the_other_flexible(self):
        # parade.FCStd has Walk2's Leg4 rigid (set in that place): the festival's P1 takes it so.
        da.set_rigid(named(self.walks[1], "Leg4"), True)
        self.doc.save()
        asm, parade = festival(self)
        self.assertTrue(named(parade, "Walk2.Leg4").Rigid)
        walker_dof = da.check(self.wdoc.getObject("Walker"))["dof"]
        self.assertEqual(walker_dof, 4)
        self.assertEqual(da.check(asm)["dof"], 2 * walker_dof - 1)
        p1w1, p1w2 = named(parade, "Walk1"), named(parade, "Walk2")
        asm.Document.UndoMode = 1
        da.set_rigid(p1w1, True)
        c = da.check(asm)
        # Counted here: a rigid walker on its stand 0; the flexible one its flexible legs' (3 of 4).
        want = sum(0 if ts_rigid(w) else sum(0 if ts_rigid(named(w, "Leg%d" % k)) else self.leg_dof()
                                             for k in (1, 2, 3, 4)) for w in (p1w1, p1w2))
        self.assertEqual(want, 3)
        self.assertEqual(c["dof"], want, c["message"])
        self.assertEqual(c["part_dof"]["P1.Walk1"], 0)
        self.assertNotIn("P1.Walk1.Leg1.Crank", c["part_dof"])
        self.assertEqual(c["part_dof"]["P1.Walk2.Leg1.Crank"], 1)
        # Inside the rigid walker the legs are as walker.FCStd has them: read only, refused.
        inner = named(p1w1, "Leg1")
        self.assertEqual(inner.getEditorMode("Rigid"), ["ReadOnly"])
        with self.assertRaisesRegex(ValueError, r"^P1.Walk1.Leg1 is inside P1.Walk1, which is rigid: it moves as "
                                                r"walker.FCStd has it \(make P1.Walk1 flexible first\)$"):
            da.set_rigid(inner, True)
        # Solved: the parts of the rigid walker where walker.FCStd has them against its frame.
        self.assertTrue(da.solve(asm).converged)
        frame = named(p1w1, "Frame")
        for k in (1, 2, 3, 4):
            for part in ("Hip", "Crank", "Rocker"):
                o = named(p1w1, "Leg%d.%s" % (k, part))
                self.assertTrue(th.same(relative_to(o, frame), self.walker_pose("Leg%d.%s" % (k, part)), 1e-9), o.Label)
        da.set_rigid(named(p1w2, "Leg1"), True)
        self.assertEqual(da.check(asm)["dof"], 2)
        self.assertTrue(da.solve(asm).converged)
        # Every joint that holds here: the ground's, the two stands', P1.Walk2's four hips and the
        # four revolutes of each of its two flexible legs (the rigid ones' hold inside them).
        self.assertEqual(self.assert_joints_hold(asm), 1 + 2 + 4 + 2 * 4)


def ts_rigid(inst):
    """Whether an instance is rigid in its place (its Rigid, as this test set it)."""
    return bool(inst.Rigid)


def festival(test):
    """test's parade (saved) placed flexible as P1 in a festival on a grounded boss: (asm, P1)."""
    test.doc.save()
    doc = App.newDocument("festival")
    doc.saveAs(os.path.join(test.tmp.name, "festival.FCStd"))
    asm = da.create_assembly(doc, "Festival")
    ground = doc.addObject("Part::Feature", "Ground")
    ground.Shape = parts.frame([(0, 0)])
    da.add_part(asm, ground, grounded=True)
    parade = da.insert_sub_assembly(asm, test.doc.FileName, rigid=False, name="P1",
                                    placement=App.Placement(App.Vector(0, 0, 1), App.Rotation()))
    # The track's first boss, bottom circle, on the ground's boss top.
    edge = parts.circle_edge(test.track.Shape, App.Vector(0, 0, 0))
    da.add_joint(asm, "Fixed", (ground, parts.circle_edge(ground.Shape, App.Vector(0, 0, 0.1))),
                 (parade, "Track." + edge), offset=0.5)
    assert da.solve(asm).converged
    return asm, parade


def world_overlaps(objs, skip=()):
    """{frozenset of two labels: overlap volume} of the pairs of `objs` whose solids overlap, by
    OpenCASCADE's boolean common of their world shapes (boxes first): the answer the workbench's
    interference check (its own cached test) is compared with."""
    import Part

    shapes = [(o.Label, Part.getShape(o)) for o in objs]
    out = {}
    for i, (la, a) in enumerate(shapes):
        for lb, b in shapes[i + 1:]:
            if frozenset((la, lb)) in skip or not a.BoundBox.intersect(b.BoundBox):
                continue
            v = a.common(b).Volume
            if v > 1e-6 * min(a.Volume, b.Volume):
                out[frozenset((la, lb))] = v
    return out


class NestedDrive(Parade):
    """The Drive panel's operation and the interference checks on joints and parts one and two
    levels down (a parade's walkers' legs, a festival's parade's), every level flexible."""

    def crank_revolute(self, asm, prefix):
        """The drivable joint holding the crank of the leg at `prefix` (Walk2.Leg3): the leg's
        Hip-Crank revolute, as the Drive panel lists it."""
        js = {j.Label: j for j in da.drivable_joints(asm)}
        self.assertIn(prefix + ".Revolute", js, sorted(js))
        j = js[prefix + ".Revolute"]
        self.assertEqual({j.Reference1[0].LinkedObject.Label, j.Reference2[0].LinkedObject.Label}, {"Hip", "Crank"})
        return j

    def drive_and_check(self, asm, container, prefix, degrees, still=1e-9):
        """`still`: how far the parts of the other legs may move (the solve polishes what an earlier
        snap left within its tolerance: 1.2e-9 mm in the festival, three levels up)."""
        doc = asm.Document
        doc.UndoMode = 1
        j = self.crank_revolute(asm, prefix)
        crank, hip, rocker = (named(container, prefix[len(container.Label) + 1:] + "." + p)
                              for p in ("Crank", "Hip", "Rocker"))
        start, value = angle_in(crank, hip), da.drive_value(j)
        before = placements(da.placed_parts(asm))
        undo = doc.UndoCount
        reached, arrived = da.drive_to(asm, j, value + degrees)
        self.assertTrue(arrived, reached)
        self.assertAlmostEqual(da.drive_value(j), value + degrees, delta=1e-7)
        # The crank turned by as much against its hip (measured from the placements), the rocker on
        # Freudenstein's curve, every part of the other legs where it was, every joint holding.
        turned = math.remainder(angle_in(crank, hip) - start - math.radians(degrees), 2 * math.pi)
        self.assertLess(abs(turned), 1e-9)
        err = math.remainder(angle_in(rocker, hip) - th.freudenstein(angle_in(crank, hip)), 2 * math.pi)
        self.assertLess(abs(err), 1e-8)
        leg = crank.InList[0]
        for o in da.placed_parts(asm):
            if o not in da.instance_parts(leg) or o == hip:
                self.assertTrue(th.same(o.Placement, before[o.Name][0], still), "%s moved %g" % (
                    o.Label, (o.Placement.Base - before[o.Name][0].Base).Length))
        self.assert_joints_hold(asm)
        self.assertEqual(doc.UndoCount, undo + 1, "a drive is one undo step")
        doc.undo()
        for o in da.placed_parts(asm):
            self.assertTrue(th.same(o.Placement, before[o.Name][0], 1e-12), o.Label)
        return j

    def test_drive_a_crank_one_level_down(self):
        # The parade has no drivable joint of its own (its walkers are bolted on): the Drive
        # panel lists its walkers' legs' joints.
        self.assertFalse([j for j in da.joints(self.asm) if da.drivable(j)])
        labels = [j.Label for j in da.drivable_joints(self.asm)]
        self.assertEqual(len(labels), 2 * 4 * 4, labels)  # each leg's four revolutes, in two walkers
        self.drive_and_check(self.asm, self.walks[1], "Walk2.Leg3", 40)
        self.assert_files_unchanged()

    def test_drive_a_crank_two_levels_down(self):
        asm, p1 = festival(self)
        walk2 = next(s for s in da.sub_assemblies(p1) if s.Label == "P1.Walk2")
        self.drive_and_check(asm, walk2, "P1.Walk2.Leg3", -35, still=1e-8)
        self.assert_files_unchanged()

    def test_a_rigid_walker_offers_no_joint_of_its_legs(self):
        da.set_rigid(self.walks[0], True)
        labels = [j.Label for j in da.drivable_joints(self.asm)]
        self.assertEqual(len(labels), 16, labels)
        self.assertTrue(all(label.startswith("Walk2.") for label in labels), labels)

    def check_interference(self, asm, container, prefix):
        """A post in the way of the crank at `prefix`, a quarter turn on: interference at the pose
        and along the drive, against OpenCASCADE's booleans at the same poses."""
        import Part

        j = self.crank_revolute(asm, prefix)
        crank = named(container, prefix[len(container.Label) + 1:] + ".Crank")
        value = da.drive_value(j)
        da.drive_to(asm, j, value + 90)
        box = Part.getShape(crank).BoundBox
        asm.Document.undo()
        post = asm.Document.addObject("Part::Feature", "Post")
        post.Shape = Part.makeBox(0.3, 0.3, 0.3, App.Vector(box.Center.x - 0.15, box.Center.y - 0.15,
                                                            box.Center.z - 0.15))
        da.add_part(asm, post, grounded=True)
        every = da.placed_parts(asm)
        # At the pose: the legs' pins sit 0.1 mm into the parts they join (th.fourbar's parts), in
        # every leg of every walker: each pair as the booleans find it, with its volume.
        now = {frozenset((a.Label, b.Label)): v for a, b, v in da.interference(asm)}
        expected = world_overlaps(every)
        self.assertEqual(sorted(now, key=sorted), sorted(expected, key=sorted))
        self.assertGreaterEqual(len(now), 4 * 4 * 2)
        for pair, v in expected.items():
            self.assertAlmostEqual(now[pair], v, delta=1e-6 * v, msg=str(sorted(pair)))
        angles = [0, 30, 60, 90, 120, 150]
        before = placements(every)
        hits = da.interference_along(asm, j, angles)
        for o in every:
            self.assertTrue(th.same(o.Placement, before[o.Name][0], 1e-12), "%s not put back" % o.Label)
        # The same angles, the drive made by the Drive's operation, the overlaps by booleans.
        expected = {}
        for a in angles:
            da.drive_to(asm, j, value + a)
            for pair, v in world_overlaps(every).items():
                expected[a, pair] = v
            asm.Document.undo()
        got = {(a, frozenset((pa.Label, pb.Label))): v for a, pa, pb, v in hits}
        key = lambda k: (k[0], sorted(k[1]))  # noqa: E731
        self.assertEqual(sorted(got, key=key), sorted(expected, key=key))
        for k, v in expected.items():
            self.assertAlmostEqual(got[k], v, delta=1e-6 * v, msg=str(key(k)))
        # The post in the crank's way a quarter turn on, and not at the start.
        self.assertIn((90, frozenset(("Post", crank.Label))), got)
        self.assertNotIn((0, frozenset(("Post", crank.Label))), got)
        return got

    def test_interference_one_level_down(self):
        self.doc.UndoMode = 1
        self.check_interference(self.asm, self.walks[1], "Walk2.Leg3")

    def test_interference_two_levels_down(self):
        asm, p1 = festival(self)
        asm.Document.UndoMode = 1
        walk2 = next(s for s in da.sub_assemblies(p1) if s.Label == "P1.Walk2")
        self.check_interference(asm, walk2, "P1.Walk2.Leg3")


class FlexibleWalkersOfRigidLegs(Parade):
    # The walker's legs rigid in walker.FCStd (leg 1 on a revolute, 2-4 bolted: 1 DOF); two such
    # walkers placed flexible: a rigid leg nested in a flexible walker is one body of the parade.
    RIGID_LEGS, HIPS = True, ("Revolute", "Fixed", "Fixed", "Fixed")

    def test_nested_rigid_legs(self):
        self.assertEqual(da.check(self.wdoc.getObject("Walker"))["dof"], 1)
        c = da.check(self.asm)
        self.assertEqual(c["dof"], 2, c["message"])
        self.assertEqual(c["part_dof"]["Walk2.Leg1"], 1)
        self.assertEqual(c["part_dof"]["Walk2.Leg2"], 0)
        self.assertNotIn("Walk2.Leg1.Crank", c["part_dof"])
        leg = named(self.walks[1], "Leg1")
        self.assertTrue(leg.Rigid)
        objs = da.instance_parts(leg)
        rel = {o.Name: relative_to(o, leg) for o in objs}
        others = placements(inside(self.walks[0]))
        crank = named(leg, "Crank")
        frame = named(self.walks[1], "Frame")
        start = relative_to(leg, frame)
        self.assertTrue(da.drag(self.asm, crank, turned_about_pin(crank, 35), steps=10).converged)
        # The leg turned whole about its hip pin (the revolute under it), nothing inside it moved.
        turn = start.inverse().multiply(relative_to(leg, frame))
        self.assertAlmostEqual(math.degrees(turn.Rotation.Angle), 35, delta=1e-7)
        self.assertLess((turn.Rotation.Axis - App.Vector(0, 0, 1)).Length, 1e-9)
        for o in objs:
            self.assertTrue(th.same(relative_to(o, leg), rel[o.Name], 1e-12), o.Label)
        for o in inside(self.walks[0]):
            self.assertTrue(th.same(o.Placement, others[o.Name][0], 1e-12), o.Label)
        self.assert_joints_hold()
        self.assert_locals()
        self.assert_files_unchanged()


class OneDocument(unittest.TestCase):
    def test_the_leg_gains_a_part_and_solve_brings_every_level_in(self):
        with tempfile.TemporaryDirectory() as tmp:
            doc = App.newDocument("all")
            leg, g, crank, coupler, rocker = th.fourbar(doc, tmp)
            leg.Label, g.Label, crank.Label, rocker.Label = "Leg", "Hip", "Crank", "Rocker"
            self.assertTrue(da.solve(leg).converged)
            doc, walker, frame, legs = ts.make_walker(tmp, leg, rigid=False, hip_joints=("Fixed", "Fixed"))
            parade = da.create_assembly(doc, "Parade")
            track = doc.addObject("Part::Feature", "Track")
            track.Shape = parts.frame(STANDS)
            da.add_part(parade, track, grounded=True)
            edge = parts.circle_edge(frame.Shape, App.Vector(0, 0, 0))
            walks = []
            for k, (x, y) in enumerate(STANDS):
                w = da.insert_sub_assembly(parade, walker, rigid=False, name="Walk%d" % (k + 1),
                                           placement=App.Placement(App.Vector(x, y, 0.3), App.Rotation()))
                da.add_joint(parade, "Fixed", (track, parts.circle_edge(track.Shape, App.Vector(x, y, 0.1))),
                             (w, "Frame." + edge), offset=0.2)
                walks.append(w)
            self.assertTrue(da.solve(parade).converged)
            self.assertEqual(da.check(parade)["dof"], 4)
            with self.assertRaisesRegex(ValueError, "Walker cannot be placed inside Leg: it would contain itself "
                                                    "\\(Walker > Leg1 > Leg \\(all\\)\\)"):
                da.insert_sub_assembly(leg, walker)
            pedal = add_pedal(leg, crank)
            with self.assertRaisesRegex(ValueError, "Walk1.Leg1: Leg has parts this instance lacks \\(Pedal\\)"):
                da.check(parade)
            self.assertTrue(da.solve(parade).converged)
            self.assertEqual(sorted(len(da.instance_parts(named(w, "Leg%d" % k))) for w in walks for k in (1, 2)),
                             [5] * 4)
            c = da.check(parade)
            self.assertEqual(c["dof"], 4, c["message"])
            # The pedal bolted on its crank in each place, by the leg's own joint, per instance.
            pedal2 = named(walks[1], "Leg2.Pedal")
            crank2 = named(walks[1], "Leg2.Crank")
            self.assertTrue(th.same(relative_to(pedal2, crank2), relative_to(pedal, crank), 1e-9))
            self.assertTrue(da.drag(parade, crank2, turned_about_pin(crank2, 30), steps=5).converged)
            self.assertTrue(th.same(relative_to(pedal2, crank2), relative_to(pedal, crank), 1e-9))
            for gap, tilt, label in gaps(parade):
                self.assertLess(gap, 1e-9, label)
            for name in list(App.listDocuments()):
                App.closeDocument(name)


class Cycles(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.leg, self.walker, self.wdoc = make_walker_file(self.tmp.name)

    def tearDown(self):
        for name in list(App.listDocuments()):
            App.closeDocument(name)
        self.tmp.cleanup()

    def unchanged(self, doc):
        return (len(doc.Objects), doc.UndoCount)

    def test_placed_inside_itself_directly_or_through_files(self):
        walker = self.wdoc.getObject("Walker")
        before = self.unchanged(self.wdoc)
        with self.assertRaisesRegex(ValueError, r"^Walker cannot be placed inside Walker: it would contain itself "
                                                r"\(Walker \(walker.FCStd\)\)$"):
            da.insert_sub_assembly(walker, walker)
        self.assertEqual(self.unchanged(self.wdoc), before)
        # The leg of leg.FCStd given the walker that places it: through the file.
        legdoc = App.getDocument("leg")
        leg = legdoc.getObject("Assembly") if legdoc.getObject("Assembly") else da.top_assemblies(legdoc)[0]
        before = self.unchanged(legdoc)
        with self.assertRaisesRegex(ValueError, r"^Walker cannot be placed inside Leg: it would contain itself "
                                                r"\(Walker > Leg1 > Leg \(leg.FCStd\)\)$"):
            da.insert_sub_assembly(leg, self.walker)
        self.assertEqual(self.unchanged(legdoc), before)
        # Two files down: a parade of walkers placed in the leg.
        pdoc, parade, _, _ = make_parade(self.tmp.name, self.walker, rigid=True)
        pdoc.save()
        with self.assertRaisesRegex(ValueError, r"\(Parade > Walk1 > Walker > Leg1 > Leg \(leg.FCStd\)\)$"):
            da.insert_sub_assembly(leg, pdoc.FileName)
        self.assertEqual(len(legdoc.Objects), before[0])

    def test_a_cycle_made_behind_the_workbenchs_back_is_refused_by_name(self):
        # As a file edited elsewhere could make it: the walker's Leg3 now places the walker.
        walker = self.wdoc.getObject("Walker")
        leg3 = next(s for s in da.sub_assemblies(walker) if s.Label == "Leg3")
        pdoc, parade, _, walks = make_parade(self.tmp.name, self.walker, rigid=True)
        leg3.Assembly = walker
        for call in (lambda: da.check(walker), lambda: da.solve(walker)):
            with self.assertRaisesRegex(ValueError, r"^Leg3: Walker would contain itself \(Walker > Walker\): an "
                                                    "assembly cannot be placed inside itself"):
                call()
        # Rigid walkers in the parade: the walker's own solve meets it, one level down.
        before = placements(da.placed_parts(parade))
        with self.assertRaisesRegex(ValueError, r"Leg3: Walker would contain itself"):
            da.solve(parade)
        for o in da.placed_parts(parade):
            self.assertTrue(th.same(o.Placement, before[o.Name][0], 0), o.Label)


class Transactions(unittest.TestCase):
    def test_placing_a_walker_is_one_undo_step_and_refusals_change_nothing(self):
        with tempfile.TemporaryDirectory() as tmp:
            leg, walker, wdoc = make_walker_file(tmp)
            doc = App.newDocument("one")
            doc.UndoMode = 1
            doc.saveAs(os.path.join(tmp, "one.FCStd"))
            asm = da.create_assembly(doc, "Top")
            count, undo = len(doc.Objects), doc.UndoCount
            w = da.insert_sub_assembly(asm, walker, rigid=False, name="W")
            self.assertEqual(len(doc.Objects), count + 1 + 1 + 4 * 5)
            self.assertEqual(doc.UndoCount, undo + 1)
            with self.assertRaisesRegex(ValueError, r"W has no part Leg9 \(parts: Frame, Leg1 \(a sub-assembly\)"):
                da.add_joint(asm, "Fixed", (w, "Leg9.Hip.Edge1"), (w, "Frame.Edge1"))
            with self.assertRaisesRegex(ValueError, r"W.Leg2 has no part Foot"):
                da.add_joint(asm, "Fixed", (asm, "W.Leg2.Foot.Edge1"), (w, "Frame.Edge1"))
            self.assertEqual(doc.UndoCount, undo + 1)
            doc.undo()
            self.assertEqual(len(doc.Objects), count)
            for name in list(App.listDocuments()):
                App.closeDocument(name)


if not os.environ.get("DISPCON_NESTED_IMPORT_ONLY"):  # gui_subassembly.py imports the helpers only
    suite = unittest.TestSuite(unittest.defaultTestLoader.loadTestsFromTestCase(c)
                               for c in (FlexibleParade, RigidParade, PerPlaceRigidity, FlexibleWalkersOfRigidLegs,
                                         NestedDrive, OneDocument, Cycles, Transactions)
                               if not os.environ.get("DISPCON_NESTED_ONLY") or c.__name__ == os.environ["DISPCON_NESTED_ONLY"])
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
    failed = len(result.failures) + len(result.errors)
    print("%d passed, %d failed" % (result.testsRun - failed, failed))
    sys.exit(1 if failed else 0)
