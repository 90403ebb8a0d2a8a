"""A Fixed or a Slider made while its parts are askew (freecadcmd): a new one takes part 2's turn
about the axis from the picked elements' frames (TwistFrom "Picked frames", as FreeCAD 1.x's
Assembly lines up a joint's two coordinate systems), so it means the same whatever pose the parts
were in when it was made, and snaps them square; a joint of a document saved before TwistFrom
existed keeps the turn it was made with (data/twist-before.FCStd, made by make_twist_fixture.py
with the workbench of then, and what that workbench's solves gave: twist-before.json), and so does
a Cylindrical saved by the fifteenth round's starting workbench (data/cylindrical-before.FCStd,
make_cylindrical_fixture.py). Each test opens and closes its own documents."""
import json
import math
import os
import re
import shutil
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
from dispcon_fc import adapter, objects, operations, studies  # noqa: E402
import parts  # noqa: E402
import test_headless as th  # noqa: E402

DATA = os.path.join(HERE, "data")
Z = App.Vector(0, 0, 1)


def close_all():
    for name in list(App.listDocuments()):
        App.closeDocument(name)


def pin(o, x, z=0.0):
    return (o, parts.circle_edge(o.Shape, App.Vector(x, 0, z)))


def stored(facts):
    return App.Placement(App.Vector(*facts["base"]), App.Rotation(*facts["q"]))


def base_and_arm(doc):
    """A grounded link (1 long) and a free one (2 long), the Fixed joint's parts."""
    asm = da.create_assembly(doc)
    made = []
    for name, length in (("Base", 1), ("Arm", 2)):
        o = doc.addObject("Part::Feature", name)
        o.Shape = parts.link(length)
        da.add_part(asm, o, grounded=name == "Base")
        made.append(o)
    return asm, made[0], made[1]


TURNED = App.Rotation(Z, 40).multiply(App.Rotation(App.Vector(1, 0, 0), 20))  # about z, then tipped


class FixedMadeAskew(unittest.TestCase):
    def tearDown(self):
        close_all()

    def test_snaps_the_parts_square_whatever_the_pose_it_was_made_in(self):
        """Made with the arm turned 40 degrees about z and tipped 20 about x, the Fixed joint
        lines up the bosses' circles' own frames: the arm stands square on the base (as made
        unturned), its boss on the base's far one; made in another pose, it means the same."""
        doc = App.newDocument("fixed_askew")
        asm, base, arm = base_and_arm(doc)
        arm.Placement = App.Placement(App.Vector(1.0, 0.05, 0.1), TURNED)
        j = da.add_joint(asm, "Fixed", pin(base, 1, 0.1), pin(arm, 0))
        self.assertEqual(j.TwistFrom, objects.PICKED_FRAMES)
        r = da.solve(asm)
        self.assertTrue(r.converged, r.message)
        self.assertLess(arm.Placement.Rotation.Angle, 1e-9, arm.Placement)
        self.assertLess((arm.Placement.Base - App.Vector(1, 0, 0.1)).Length, 1e-9, arm.Placement)
        first = arm.Placement
        # Another pose when made (turned -70 about z, tipped about y): the same solved pose.
        doc.removeObject(j.Name)
        arm.Placement = App.Placement(App.Vector(-0.4, 0.7, 0.5),
                                      App.Rotation(Z, -70).multiply(App.Rotation(App.Vector(0, 1, 0), 35)))
        da.add_joint(asm, "Fixed", pin(base, 1, 0.1), pin(arm, 0))
        self.assertTrue(da.solve(asm).converged)
        self.assertTrue(th.same(arm.Placement, first, 1e-9), (arm.Placement, first))

    def test_made_from_the_pose_it_holds_the_arm_turned_as_it_stood(self):
        """twist_from="Pose when made" (a script's, the panel's choice): the turn the arm had
        about the axis when made is held, 40 degrees, as every joint did before the choice."""
        doc = App.newDocument("fixed_pose")
        asm, base, arm = base_and_arm(doc)
        arm.Placement = App.Placement(App.Vector(1.0, 0.05, 0.1), App.Rotation(Z, 40))
        j = da.add_joint(asm, "Fixed", pin(base, 1, 0.1), pin(arm, 0), twist_from=objects.POSE_WHEN_MADE)
        self.assertEqual(j.TwistFrom, objects.POSE_WHEN_MADE)
        self.assertTrue(da.solve(asm).converged)
        self.assertAlmostEqual(math.degrees(th.angle_of(arm)), 40.0, delta=1e-7)
        # Set to the picked frames (validated at the engine first): square.
        operations.edit_joint(j, twist_from=objects.PICKED_FRAMES)
        self.assertTrue(da.solve(asm).converged)
        self.assertLess(arm.Placement.Rotation.Angle, 1e-9, arm.Placement)
        # Back to the pose: the turn it has now (square) is held; turned by hand, it comes back.
        operations.edit_joint(j, twist_from=objects.POSE_WHEN_MADE)
        arm.Placement = App.Placement(arm.Placement.Base, App.Rotation(Z, 25))
        self.assertTrue(da.solve(asm).converged)
        self.assertLess(arm.Placement.Rotation.Angle, 1e-9, arm.Placement)

    def test_saved_and_reopened_it_keeps_the_picked_frames(self):
        doc = App.newDocument("fixed_saved")
        asm, base, arm = base_and_arm(doc)
        arm.Placement = App.Placement(App.Vector(1.0, 0.05, 0.1), TURNED)
        name = da.add_joint(asm, "Fixed", pin(base, 1, 0.1), pin(arm, 0)).Name
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "picked.FCStd")
            doc.saveAs(path)
            App.closeDocument(doc.Name)
            doc = App.openDocument(path)
            j = doc.getObject(name)
            self.assertEqual(j.TwistFrom, objects.PICKED_FRAMES)
            asm = da.top_assemblies(doc)[0]
            self.assertTrue(da.solve(asm).converged)
            self.assertLess(doc.getObject("Arm").Placement.Rotation.Angle, 1e-9)

    def test_a_bad_choice_is_refused_naming_the_joint(self):
        doc = App.newDocument("fixed_bad")
        asm, base, arm = base_and_arm(doc)
        j = da.add_joint(asm, "Fixed", pin(base, 1, 0.1), pin(arm, 0))
        perps = (App.Vector(j.Perp1), App.Vector(j.Perp2))
        with self.assertRaisesRegex(ValueError, r"^%s: twist from 'sideways' is not one of 'Picked frames', "
                                                r"'Pose when made'$" % j.Label):
            operations.edit_joint(j, twist_from="sideways")
        self.assertEqual((j.TwistFrom, App.Vector(j.Perp1), App.Vector(j.Perp2)), (objects.PICKED_FRAMES,) + perps)
        with self.assertRaisesRegex(ValueError, r"^Ball: a Ball joint measures no turn about its axis to take "
                                                r"from anywhere \(only Fixed, Revolute, Slider, Cylindrical\)$"):
            da.add_joint(asm, "Ball", pin(base, 0, 0.1), pin(arm, 2), twist_from=objects.PICKED_FRAMES)
        # The property editor shows it on a Fixed, a Revolute, a Slider or a Cylindrical only.
        self.assertEqual(j.getEditorMode("TwistFrom"), [])
        operations.edit_joint(j, joint_type="Revolute")
        self.assertEqual(j.getEditorMode("TwistFrom"), [])
        operations.edit_joint(j, joint_type="Ball")
        self.assertEqual(j.getEditorMode("TwistFrom"), ["Hidden"])


def turned_about_z(o):
    """The part's turn about z in degrees, checked to be about z alone."""
    axis = o.Placement.Rotation.multVec(Z)
    assert (axis - Z).Length < 1e-9, o.Placement
    return math.degrees(th.angle_of(o))


class RevoluteLimitsMadeTurned(unittest.TestCase):
    """A Revolute's (and a Cylindrical's) turn limits count from the picked frames (TwistFrom
    "Picked frames", a new joint's): limits 0..90 deg stop part 2 where the picked circles' x's
    (the parts' own x) are 0 and 90 degrees apart, whatever the pose it was made in."""

    def tearDown(self):
        close_all()

    def made_at(self, kind, made, tipped=None):
        doc = App.newDocument("limits_made")
        asm, base, arm = base_and_arm(doc)
        rot = App.Rotation(Z, made)
        if tipped is not None:
            rot = rot.multiply(App.Rotation(App.Vector(1, 0, 0), tipped))
        arm.Placement = App.Placement(App.Vector(1.0, 0.05, 0.1), rot)
        j = da.add_joint(asm, kind, pin(base, 1, 0.1), pin(arm, 0), rotation=(0, 90))
        self.assertEqual(j.TwistFrom, objects.PICKED_FRAMES)
        return asm, arm, j

    def stops(self, asm, arm, j, start):
        """Solved from the arm turned `start` degrees about z: its turn then, and the joint's."""
        arm.Placement = App.Placement(App.Vector(1, 0, 0.1), App.Rotation(Z, start))
        r = da.solve(asm)
        self.assertTrue(r.converged, r.message)
        base = j.Reference1[0]
        return turned_about_z(arm), math.degrees(studies.joint_value(j, base.Placement, arm.Placement))

    def test_stops_at_the_picked_frames_0_and_90_whatever_the_pose_made_in(self):
        for kind, made, tipped in (("Revolute", 40, None), ("Revolute", -70, 25), ("Revolute", 0, None),
                                   ("Cylindrical", 130, 15)):
            asm, arm, j = self.made_at(kind, made, tipped)
            for start, want in ((-30, 0.0), (45, 45.0), (120, 90.0)):
                turn, value = self.stops(asm, arm, j, start)
                self.assertAlmostEqual(turn, want, delta=1e-6, msg=(kind, made, start))
                self.assertAlmostEqual(value, want, delta=1e-6, msg=(kind, made, start))
            close_all()

    def test_pose_when_made_counts_from_the_turn_made_in(self):
        """twist_from="Pose when made": 0..90 counts from the 40 degrees it was made at; set to
        the picked frames (edit_joint, the engine's door first), from the circles' x's."""
        doc = App.newDocument("limits_pose")
        asm, base, arm = base_and_arm(doc)
        arm.Placement = App.Placement(App.Vector(1.0, 0.05, 0.1), App.Rotation(Z, 40))
        j = da.add_joint(asm, "Revolute", pin(base, 1, 0.1), pin(arm, 0), rotation=(0, 90),
                         twist_from=objects.POSE_WHEN_MADE)
        self.assertEqual(j.TwistFrom, objects.POSE_WHEN_MADE)
        self.assertAlmostEqual(self.stops(asm, arm, j, 10)[0], 40.0, delta=1e-6)
        self.assertAlmostEqual(self.stops(asm, arm, j, 150)[0], 130.0, delta=1e-6)
        operations.edit_joint(j, twist_from=objects.PICKED_FRAMES)
        self.assertAlmostEqual(self.stops(asm, arm, j, 150)[0], 90.0, delta=1e-6)
        self.assertAlmostEqual(self.stops(asm, arm, j, -20)[0], 0.0, delta=1e-6)


def open_fixture(test, name):
    """Opens a copy of data/<name>.FCStd for `test` (the file itself is never written) and returns
    the facts its maker recorded in data/<name>.json; tearDown closes it and removes the copy."""
    test.tmp = tempfile.mkdtemp()
    path = os.path.join(test.tmp, name + ".FCStd")
    shutil.copy(os.path.join(DATA, name + ".FCStd"), path)
    with open(os.path.join(DATA, name + ".json")) as f:
        facts = json.load(f)
    test.doc = App.openDocument(path)
    return facts


class SavedBefore(unittest.TestCase):
    """data/twist-before.FCStd, saved by the workbench of main e05b94a (before TwistFrom)."""

    def setUp(self):
        self.facts = open_fixture(self, "twist-before")
        self.asm = {a.Label: a for a in da.top_assemblies(self.doc)}

    def tearDown(self):
        close_all()
        shutil.rmtree(self.tmp)

    def joint(self, asm, kind):
        return next(j for j in da.joints(self.asm[asm]) if j.JointType == kind)

    def test_its_joints_keep_the_pose_when_made(self):
        for asm, kind in (("Askew", "Fixed"), ("SliderCrank", "Slider")):
            self.assertEqual(self.joint(asm, kind).TwistFrom, objects.POSE_WHEN_MADE)
        # TwistFrom added on restore touches nothing: the Slider is touched as it was saved (made
        # last, no recompute before the save; the workbench of then reopens it so too).
        self.assertEqual([o.Label for o in self.doc.Objects if "Touched" in o.State], ["Slider"])

    def test_the_askew_fixed_solves_to_the_same_placement(self):
        r = da.solve(self.asm["Askew"])
        self.assertTrue(r.converged, r.message)
        self.assertEqual(self.facts["Askew"]["converged"], True)
        arm = self.doc.getObject("Arm")
        want = stored(self.facts["Askew"]["Arm"])
        self.assertTrue(th.same(arm.Placement, want, 1e-9), (arm.Placement, want))
        self.assertAlmostEqual(abs(math.degrees(th.angle_of(arm))), 40.0, delta=3.0)  # still turned
        # Set to the picked frames in the property editor (no edit_joint): the next solve reads
        # them from the circles and stands the arm square.
        self.joint("Askew", "Fixed").TwistFrom = objects.PICKED_FRAMES
        r = da.solve(self.asm["Askew"])
        self.assertTrue(r.converged, r.message)
        self.assertLess(arm.Placement.Rotation.Angle, 1e-9, arm.Placement)

    def test_the_slider_made_after_the_ball_still_fails_and_says_what_to_do(self):
        """As the workbench of then: no pose holds the piston turned as it stood; the message
        now speaks of TwistFrom, and set so, the slider-crank closes."""
        moving = [self.doc.getObject(n) for n in ("Crank", "Rod", "Piston")]
        before = [o.Placement for o in moving]
        r = da.solve(self.asm["SliderCrank"])
        self.assertFalse(r.converged)
        self.assertEqual(self.facts["SliderCrank"]["converged"], False)
        for o, was in zip(moving, before):
            self.assertEqual(o.Placement, was)
            self.assertTrue(th.same(o.Placement, stored(self.facts["SliderCrank"][o.Label]), 1e-12))
        slider = self.joint("SliderCrank", "Slider")
        self.assertRegex(r.message, r"%s was made with Piston's axis \d+ degrees or more off Ground's and, its "
                                    r"TwistFrom being 'Pose when made', holds Piston turned about it as it stood "
                                    r"then: if the joints cannot hold so, set its TwistFrom to 'Picked frames' "
                                    r"\(the joint panel's Twist from\)" % slider.Label)
        operations.edit_joint(slider, twist_from=objects.PICKED_FRAMES)
        r = da.solve(self.asm["SliderCrank"])
        self.assertTrue(r.converged, r.message)
        th.is_slider_crank(self.doc.getObject("Crank"), self.doc.getObject("Piston"))


class LimitsSavedBefore(unittest.TestCase):
    """data/limits-before.FCStd, saved by the workbench of main e05b94a (make_limits_fixture.py):
    Revolutes limited to 0..90 deg, made with their links turned 40 degrees, their limits then
    counting from there."""

    def setUp(self):
        self.facts = open_fixture(self, "limits-before")["Limited"]
        self.asm = da.top_assemblies(self.doc)[0]

    def tearDown(self):
        close_all()
        shutil.rmtree(self.tmp)

    def test_its_revolutes_keep_their_limits_meaning(self):
        revolutes = [j for j in da.joints(self.asm) if j.JointType == "Revolute"]
        self.assertEqual([j.TwistFrom for j in revolutes], [objects.POSE_WHEN_MADE] * 2)
        r = da.solve(self.asm)
        self.assertTrue(r.converged, r.message)
        self.assertTrue(self.facts["converged"])
        for name, turn in (("Below", 40.0), ("Above", 130.0)):
            o = self.doc.getObject(name)
            want = stored(self.facts[name])
            self.assertTrue(th.same(o.Placement, want, 1e-9), (name, o.Placement, want))
            self.assertAlmostEqual(turned_about_z(o), turn, delta=1e-6)  # 0 and 90 from the 40 made at
        # Set to the picked frames (the property editor's way): 0..90 from the circles' x's.
        for j in revolutes:
            j.TwistFrom = objects.PICKED_FRAMES
        self.doc.getObject("Below").Placement = App.Placement(App.Vector(0, 0, -0.1), App.Rotation(Z, -20))
        r = da.solve(self.asm)
        self.assertTrue(r.converged, r.message)
        self.assertAlmostEqual(turned_about_z(self.doc.getObject("Below")), 0.0, delta=1e-6)
        self.assertAlmostEqual(turned_about_z(self.doc.getObject("Above")), 90.0, delta=1e-6)


class CylindricalSavedBefore(unittest.TestCase):
    """data/cylindrical-before.FCStd, saved by the workbench of the fifteenth round's start (main
    3d84d20, make_cylindrical_fixture.py): two Cylindricals limited to a turn of 0..90 deg and a
    travel of 0..0.5, made with their links turned 40 degrees, one counting its turn from the
    picked frames, the other from the pose when made; reopened, each keeps its meaning."""

    def setUp(self):
        self.facts = open_fixture(self, "cylindrical-before")["Sleeves"]
        self.asm = da.top_assemblies(self.doc)[0]

    def tearDown(self):
        close_all()
        shutil.rmtree(self.tmp)

    def test_its_cylindricals_keep_their_meaning(self):
        self.assertEqual({j.Label: j.TwistFrom for j in da.joints(self.asm)}, self.facts["TwistFrom"])
        r = da.solve(self.asm)
        self.assertTrue(r.converged, r.message)
        self.assertTrue(self.facts["converged"])
        for name, turn, z in (("Picked", 90.0, 0.6), ("Posed", 40.0, -0.1)):
            o = self.doc.getObject(name)
            want = stored(self.facts[name])
            self.assertTrue(th.same(o.Placement, want, 1e-9), (name, o.Placement, want))
            self.assertAlmostEqual(turned_about_z(o), turn, delta=1e-6)  # at a limit of its turn
            self.assertAlmostEqual(o.Placement.Base.z, z, delta=1e-9)  # and of its travel


def vertex_at(o, local):
    """The name of the vertex of `o` at `local` (a point of its own frame)."""
    back = o.Placement.inverse()
    return next("Vertex%d" % (k + 1) for k, v in enumerate(o.Shape.Vertexes) if (back.multVec(v.Point) - local).Length < 1e-9)


class VertexAndSphereFrames(unittest.TestCase):
    """A vertex's frame is the part's own axes, a sphere's its own, as FreeCAD 1.x's Assembly takes
    them: not the world's z at the pose the joint was made in (main 3d84d20's rule)."""

    def tearDown(self):
        close_all()

    def test_a_fixed_on_two_vertices_lines_up_the_parts_own_axes(self):
        """Made with the arm turned 40 degrees and tipped 20, or turned -70 and tipped 35 about
        y, the Fixed on a corner of each stands the arm square on the base, its corner on the
        base's (main's held it tipped as it was made)."""
        for made in (TURNED, App.Rotation(Z, -70).multiply(App.Rotation(App.Vector(0, 1, 0), 35))):
            doc = App.newDocument("vertex_fixed")
            asm = da.create_assembly(doc)
            base, arm = doc.addObject("Part::Feature", "Base"), doc.addObject("Part::Feature", "Arm")
            base.Shape, arm.Shape = parts.Part.makeBox(1, 1, 0.2), parts.Part.makeBox(0.5, 0.2, 0.1)
            da.add_part(asm, base, grounded=True)
            da.add_part(asm, arm)
            arm.Placement = App.Placement(App.Vector(1.2, 0.9, 0.4), made)
            j = da.add_joint(asm, "Fixed", (base, vertex_at(base, App.Vector(1, 1, 0.2))),
                             (arm, vertex_at(arm, App.Vector(0, 0, 0))))
            self.assertLess((j.Axis2 - Z).Length, 1e-12, j.Axis2)  # the arm's own z
            r = da.solve(asm)
            self.assertTrue(r.converged, r.message)
            self.assertLess(arm.Placement.Rotation.Angle, 1e-9, arm.Placement)
            self.assertLess((arm.Placement.Base - App.Vector(1, 1, 0.2)).Length, 1e-9, arm.Placement)
            close_all()

    def test_a_spheres_frame_is_its_own_whatever_the_pose(self):
        doc = App.newDocument("sphere_frame")
        ball = doc.addObject("Part::Feature", "Ball")
        ball.Shape = parts.Part.makeSphere(0.3, App.Vector(0.5, 0, 0), App.Vector(1, 0, 0))  # its axis the part's x
        for pose in (App.Placement(), App.Placement(App.Vector(3, 2, 1), TURNED)):
            ball.Placement = pose
            f = adapter.geometry.feature(ball, "Face1")
            self.assertEqual(f.kind, "sphere")
            self.assertLess((adapter.geometry.to_local(pose, point=f.point) - App.Vector(0.5, 0, 0)).Length, 1e-9)
            self.assertLess((adapter.geometry.to_local(pose, axis=f.axis) - App.Vector(1, 0, 0)).Length, 1e-12)
            across = adapter.geometry.to_local(pose, axis=f.across)
            self.assertLess(abs(across.dot(App.Vector(1, 0, 0))), 1e-12)
            self.assertLess((across - Z).Length, 1e-12, across)  # the sphere's own x: the part's z here


class PickedAcross(unittest.TestCase):
    """The rule for an element with no frame of its own across its axis: the part's z, x or y
    most across it (z first on a tie), made square to it; the same either way along the axis."""

    def test_the_rule(self):
        pl = App.Placement(App.Vector(3, 2, 1), App.Rotation(Z, 33))  # the pose plays no part
        line = adapter.geometry.Feature((0, 0, 0), (1, 0, 0), "line")
        for axis, want in (((1, 0, 0), (0, 0, 1)), ((-1, 0, 0), (0, 0, 1)), ((0, 0, 1), (1, 0, 0)),
                           ((0, 1, 0), (0, 0, 1)), ((0, 0.6, 0.8), (1, 0, 0))):
            got = adapter.picked_across(pl, line, App.Vector(*axis))
            self.assertLess((got - App.Vector(*want)).Length, 1e-12, (axis, got))
        # Along none of them: the one most across (here x), made square to the axis.
        a = App.Vector(0.2, 1, 0.3).normalize()
        tipped = adapter.picked_across(pl, line, a)
        self.assertLess(abs(tipped.dot(a)), 1e-12)
        self.assertLess((tipped - (App.Vector(1, 0, 0) - a * a.x).normalize()).Length, 1e-12, tipped)
        # A circle's own x, wherever the part stands: its x in the part's frame.
        circle = adapter.geometry.Feature((0, 0, 0), pl.Rotation.multVec(Z), "circle", 1.0, pl.Rotation.multVec(App.Vector(0, 1, 0)))
        got = adapter.picked_across(pl, circle, Z)
        self.assertLess((got - App.Vector(0, 1, 0)).Length, 1e-12, got)


if not os.environ.get("DISPCON_TWIST_IMPORT_ONLY"):  # run by freecadcmd as a script
    suite = unittest.TestSuite(unittest.defaultTestLoader.loadTestsFromTestCase(c)
                               for c in (FixedMadeAskew, RevoluteLimitsMadeTurned, SavedBefore, LimitsSavedBefore,
                                         CylindricalSavedBefore, VertexAndSphereFrames, PickedAcross))
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
    failed = len(result.failures) + len(result.errors)
    print("%d passed, %d failed" % (result.testsRun - failed, failed))
    sys.exit(1 if failed else 0)
