"""A Fixed or a Slider made while its parts are askew (freecadcmd): a new one takes part 2's turn
about the axis from the picked elements' frames (TwistFrom "Picked frames", as FreeCAD 1.x's
Assembly lines up a joint's two coordinate systems), so it means the same whatever pose the parts
were in when it was made, and snaps them square; a joint of a document saved before TwistFrom
existed keeps the turn it was made with (data/twist-before.FCStd, made by make_twist_fixture.py
with the workbench of then, and what that workbench's solves gave: twist-before.json). Each test
opens and closes its own documents."""
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
from dispcon_fc import adapter, objects, operations  # noqa: E402
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
        with self.assertRaisesRegex(ValueError, r"^Revolute: a Revolute joint holds no turn about its axis to "
                                                r"take from anywhere \(only Fixed, Slider\)$"):
            da.add_joint(asm, "Revolute", pin(base, 0, 0.1), pin(arm, 2), twist_from=objects.PICKED_FRAMES)
        # The property editor shows it on a Fixed or a Slider only.
        self.assertEqual(j.getEditorMode("TwistFrom"), [])
        operations.edit_joint(j, joint_type="Revolute")
        self.assertEqual(j.getEditorMode("TwistFrom"), ["Hidden"])


class SavedBefore(unittest.TestCase):
    """data/twist-before.FCStd, saved by the workbench of main e05b94a (before TwistFrom)."""

    def setUp(self):
        self.tmp = tempfile.mkdtemp()
        path = os.path.join(self.tmp, "twist-before.FCStd")
        shutil.copy(os.path.join(DATA, "twist-before.FCStd"), path)  # the file itself is never written
        with open(os.path.join(DATA, "twist-before.json")) as f:
            self.facts = json.load(f)
        self.doc = App.openDocument(path)
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
                               for c in (FixedMadeAskew, SavedBefore, PickedAcross))
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
    failed = len(result.failures) + len(result.errors)
    print("%d passed, %d failed" % (result.testsRun - failed, failed))
    sys.exit(1 if failed else 0)
