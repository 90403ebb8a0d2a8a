"""A joint whose reference is lost (freecadcmd): its part deleted, its part taken out of the
assembly, or its picked edge gone from a PartDesign Pad made shorter. The joint's references are
read by one reader (adapter.references), so the user reads the same sentence, naming the joint
and saying what to do, from every path: Solve's and Check's message, an edit of its TwistFrom (by
edit_joint or in the property editor), of its type, of its frame, the Drive; and each refusal
leaves the document as it was, every property of every object. Each test opens and closes its own
document."""
import math
import os
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "freecad_workbench"))
sys.path.insert(0, os.path.join(REPO, "samples", "freecad"))

import FreeCAD as App  # noqa: E402
import Part  # noqa: E402

import dispcon_fc.assembly as da  # noqa: E402
from dispcon_fc import adapter, objects, operations  # noqa: E402
import parts  # noqa: E402

Z = App.Vector(0, 0, 1)
PICK_AGAIN = "pick that reference again (double-click the joint)"


def close_all():
    for name in list(App.listDocuments()):
        App.closeDocument(name)


def _plain(v):
    """A property's value as plain data, to compare a document before and after."""
    if isinstance(v, App.DocumentObject):
        return ("object", v.Name)
    if isinstance(v, (list, tuple)):
        return tuple(_plain(x) for x in v)
    if isinstance(v, App.Placement):
        return ("placement", tuple(v.Base), tuple(v.Rotation.Q))
    if isinstance(v, App.Vector):
        return ("vector", tuple(v))
    if isinstance(v, App.Units.Quantity):
        return ("quantity", v.Value, str(v.Unit))
    if isinstance(v, Part.Shape):
        return ("shape", v.exportBrepToString())
    return repr(v)


def state(doc):
    """Every property of every object of `doc`, as plain data."""
    return {(o.Name, name): _plain(getattr(o, name)) for o in doc.Objects for name in o.PropertiesList}


def _sketch(body, name, geometry):
    sk = body.newObject("Sketcher::SketchObject", name)
    sk.MapMode = "Deactivated"  # on the body's xy plane
    for g in geometry:
        sk.addGeometry(g, False)
    return sk


def frame_with_pin(doc):
    """A PartDesign Body: a plate (a Pad, 4 x 1, 1 high) with a pin (a Pad of a circle of radius
    0.2 at (3, 0), 2 high) standing 1 above it; the pin's top circle, at z = 2, is the edge a
    joint is picked on. Returns the body, the pin's Pad and that edge's name."""
    body = doc.addObject("PartDesign::Body", "Body")
    corners = [(-0.5, -0.5), (3.5, -0.5), (3.5, 0.5), (-0.5, 0.5)]
    plate = _sketch(body, "Plate", [Part.LineSegment(App.Vector(*a, 0), App.Vector(*b, 0))
                                    for a, b in zip(corners, corners[1:] + corners[:1])])
    pad = body.newObject("PartDesign::Pad", "Pad")
    pad.Profile, pad.Length = plate, 1
    pin_sketch = _sketch(body, "PinCircle", [Part.Circle(App.Vector(3, 0, 0), Z, 0.2)])
    pin_pad = body.newObject("PartDesign::Pad", "PinPad")
    pin_pad.Profile, pin_pad.Length = pin_sketch, 2
    doc.recompute()
    top = parts.circle_edge(body.Shape, App.Vector(3, 0, 2))
    return body, pin_pad, top


def crank_on_pin(doc):
    """An assembly: the Body (grounded, labelled Frame) and a link (Crank) pinned on the pin's top
    circle by a Revolute limited to 0..90 deg (labelled Crank pin), solved."""
    asm = da.create_assembly(doc)
    body, pin_pad, top = frame_with_pin(doc)
    body.Label = "Frame"
    da.add_part(asm, body, grounded=True)
    crank = doc.addObject("Part::Feature", "Crank")
    crank.Shape = parts.link(1.5)
    da.add_part(asm, crank)
    crank.Placement = App.Placement(App.Vector(3, 0, 2), App.Rotation(Z, 30))
    j = da.add_joint(asm, "Revolute", (body, top), (crank, parts.circle_edge(crank.Shape, App.Vector(0, 0, 0))),
                     rotation=(0, 90))
    j.Label = "Crank pin"
    r = da.solve(asm)
    assert r.converged, r.message
    return asm, body, pin_pad, top, crank, j


class Lost(unittest.TestCase):
    """The same sentence from every path, nothing changed by a refusal."""

    def tearDown(self):
        close_all()

    def refused(self, doc, said, call):
        before = state(doc)
        with self.assertRaises(ValueError) as caught:
            call()
        self.assertEqual(str(caught.exception), said)
        self.assertEqual(state(doc), before)

    def every_path(self, asm, j, said):
        doc = asm.Document
        r = da.solve(asm)
        self.assertIn("skipped " + said, r.message)
        self.assertEqual(r.skipped, [j])
        c = da.check(asm)
        self.assertIn("skipped " + said, c["message"])
        self.assertEqual(c["skipped"], [j])
        self.refused(doc, said, lambda: da.edit_joint(j, twist_from=objects.POSE_WHEN_MADE))
        self.refused(doc, said, lambda: da.edit_joint(j, joint_type="Cylindrical"))
        self.refused(doc, said, lambda: da.edit_joint(j, joint_type="Gears"))  # one that reads the features now
        self.refused(doc, said, lambda: da.edit_joint(j, frame=(10, 0, 0)))
        self.refused(doc, said, lambda: da.drive_to(asm, j, 45))
        # The property editor cannot refuse before the value changes: the joint puts it back.
        before = state(doc)
        j.TwistFrom = objects.POSE_WHEN_MADE
        self.assertEqual(j.TwistFrom, objects.PICKED_FRAMES)
        self.assertEqual(state(doc), before)

    def test_an_edge_gone_from_a_pad_made_shorter(self):
        doc = App.newDocument("edge_gone")
        asm, body, pin_pad, top, crank, j = crank_on_pin(doc)
        pin_pad.Length = 0.5  # the pin sunk into the plate: its top circle is no edge any more
        doc.recompute()
        self.assertGreater(int(top[len("Edge"):]), len(body.Shape.Edges))
        self.every_path(asm, j, "Crank pin: Frame has no %s any more, its shape changed: %s" % (top, PICK_AGAIN))
        # Made long again, the edge is back under its name: the joint holds again.
        pin_pad.Length = 2
        doc.recompute()
        r = da.solve(asm)
        self.assertTrue(r.converged, r.message)
        self.assertEqual(r.skipped, [])

    def test_a_part_deleted(self):
        doc = App.newDocument("part_deleted")
        asm, body, pin_pad, top, crank, j = crank_on_pin(doc)
        doc.removeObject(crank.Name)
        self.every_path(asm, j, "Crank pin: one of its parts was deleted: pick its two references again "
                                "(double-click the joint) or delete the joint")

    def test_a_part_taken_out_of_the_assembly(self):
        doc = App.newDocument("part_out")
        asm, body, pin_pad, top, crank, j = crank_on_pin(doc)
        asm.removeObject(crank)
        self.assertNotIn(crank, asm.Group)
        self.every_path(asm, j, "Crank pin: Crank is not a part of the assembly: add it to the assembly, or %s"
                        % PICK_AGAIN)

    def test_the_reader_itself(self):
        """references(): each reference's part, element and feature as the parts stand now."""
        doc = App.newDocument("reader")
        asm, body, pin_pad, top, crank, j = crank_on_pin(doc)
        (p1, s1, f1), (p2, s2, f2) = adapter.references(j, {p.Name for p in da.placed_parts(asm)})
        self.assertEqual((p1, s1, p2), (body, top, crank))
        self.assertEqual(f1.kind, "circle")
        self.assertLess((f1.point - App.Vector(3, 0, 2)).Length, 1e-9)
        self.assertLess((f2.point - App.Vector(3, 0, 2)).Length, 1e-9)  # solved: the crank's pin on it
        self.assertIsNone(adapter.references(j, features=False)[0].feature)


class TwistFromInThePropertyEditor(unittest.TestCase):
    """TwistFrom set in the property editor means what the joint panel and edit_joint make it
    mean: "Pose when made" takes the turn part 2 has now (a Revolute's limits then count from
    it), "Picked frames" the picked elements' frames, at once, not at some later solve."""

    def tearDown(self):
        close_all()

    def crank_at(self, doc, degrees):
        asm, body, pin_pad, top, crank, j = crank_on_pin(doc)
        crank.Placement = App.Placement(App.Vector(3, 0, 2), App.Rotation(Z, degrees))
        return asm, crank, j

    def stop(self, asm, crank, start):
        """The crank's turn about z after a solve from `start` degrees."""
        crank.Placement = App.Placement(App.Vector(3, 0, 2), App.Rotation(Z, start))
        r = da.solve(asm)
        self.assertTrue(r.converged, r.message)
        q = crank.Placement.Rotation
        return math.degrees(math.atan2(q.multVec(App.Vector(1, 0, 0)).y, q.multVec(App.Vector(1, 0, 0)).x))

    def test_pose_when_made_set_in_the_editor_is_edit_joints(self):
        by_editor, by_edit = App.newDocument("by_editor"), App.newDocument("by_edit")
        (asm1, crank1, j1), (asm2, crank2, j2) = self.crank_at(by_editor, 40), self.crank_at(by_edit, 40)
        self.assertAlmostEqual(self.stop(asm1, crank1, 120), 90.0, delta=1e-6)  # from the picked frames
        crank1.Placement = crank2.Placement = App.Placement(App.Vector(3, 0, 2), App.Rotation(Z, 40))
        j1.TwistFrom = objects.POSE_WHEN_MADE  # as the property editor sets it
        da.edit_joint(j2, twist_from=objects.POSE_WHEN_MADE)
        for name in ("Perp1", "Perp2"):
            self.assertLess((getattr(j1, name) - getattr(j2, name)).Length, 1e-12, name)
        # The limits now count from the crank's 40 degrees: 0..90 stops it at 40 and 130.
        self.assertAlmostEqual(self.stop(asm1, crank1, 10), 40.0, delta=1e-6)
        self.assertAlmostEqual(self.stop(asm1, crank1, 150), 130.0, delta=1e-6)
        # And back to the picked frames in the editor: 0 and 90 again.
        j1.TwistFrom = objects.PICKED_FRAMES
        self.assertAlmostEqual(self.stop(asm1, crank1, 150), 90.0, delta=1e-6)
        self.assertAlmostEqual(self.stop(asm1, crank1, -20), 0.0, delta=1e-6)

    def test_an_undo_puts_back_what_the_change_took(self):
        """The property editor's change is one undo step with the twist it took: undone, the
        joint's twist references are those of before, whatever the parts' pose."""
        doc = App.newDocument("undo_twist")
        doc.UndoMode = 1
        asm, crank, j = self.crank_at(doc, 40)
        perps = (App.Vector(j.Perp1), App.Vector(j.Perp2))
        doc.openTransaction("Edit TwistFrom")
        j.TwistFrom = objects.POSE_WHEN_MADE
        doc.commitTransaction()
        self.assertGreater((j.Perp2 - perps[1]).Length, 1e-3)  # the crank's 40 degrees taken
        crank.Placement = App.Placement(App.Vector(3, 0, 2), App.Rotation(Z, 70))
        doc.undo()
        self.assertEqual(j.TwistFrom, objects.PICKED_FRAMES)
        for got, want in zip((j.Perp1, j.Perp2), perps):
            self.assertLess((got - want).Length, 1e-12)
        # The other way: an undo back to "Pose when made" keeps the turn taken at 40 degrees, not
        # the 70 the crank stands at when undone.
        crank.Placement = App.Placement(App.Vector(3, 0, 2), App.Rotation(Z, 40))
        doc.openTransaction("Edit joint")
        da.edit_joint(j, twist_from=objects.POSE_WHEN_MADE, undo_step=False)
        doc.commitTransaction()
        perps = (App.Vector(j.Perp1), App.Vector(j.Perp2))
        doc.openTransaction("Edit TwistFrom")
        j.TwistFrom = objects.PICKED_FRAMES
        doc.commitTransaction()
        crank.Placement = App.Placement(App.Vector(3, 0, 2), App.Rotation(Z, 70))
        doc.undo()
        self.assertEqual(j.TwistFrom, objects.POSE_WHEN_MADE)
        for got, want in zip((j.Perp1, j.Perp2), perps):
            self.assertLess((got - want).Length, 1e-12)


suite = unittest.TestSuite(unittest.defaultTestLoader.loadTestsFromTestCase(c)
                           for c in (Lost, TwistFromInThePropertyEditor))
result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
failed = len(result.failures) + len(result.errors)
print("%d passed, %d failed" % (result.testsRun - failed, failed))
sys.exit(1 if failed else 0)
