"""The bill of materials and the exploded view in real FreeCAD (freecadcmd), against answers
counted or computed here: parts counted as they were made, masses from the boxes' and cylinders'
volumes and the materials' densities, offsets from the parts' centres, placements compared to the
bit. Each class opens and closes its own documents."""
import csv
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
os.environ["DISPCON_SUB_IMPORT_ONLY"] = "1"

import FreeCAD as App  # noqa: E402
import Part  # noqa: E402

import dispcon_fc.assembly as da  # noqa: E402
from dispcon_fc import bom, exploded  # noqa: E402
import test_headless as th  # noqa: E402
import test_subassembly as ts  # noqa: E402

STEEL, ALUMINIUM = 7900e-6, 2700e-6  # g/mm³ (7900 and 2700 kg/m³)


def bits(pl):
    """A placement as its exact numbers (two placements equal to the bit have equal tuples)."""
    return tuple(pl.Base) + tuple(pl.Rotation.Q)


def placements(asm):
    return {p.Name: bits(p.Placement) for p in da.placed_parts(asm)}


def cells(sheet):
    """The sheet's cells as text, row by row, as far as the header's columns (A..G)."""
    out = []
    r = 1
    while sheet.getContents("A%d" % r) or sheet.getContents("B%d" % r):
        out.append([sheet.getContents("%s%d" % (c, r)) for c in "ABCDEFG"])
        r += 1
    return out


class Hardware(unittest.TestCase):
    """A plate (aluminium, its own Material), four bolts (steel, by a material object naming
    them), two pins of different shapes both labelled Pin, and two links of different lengths."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.doc = App.newDocument("bom")
        self.doc.UndoMode = 1
        self.asm = da.create_assembly(self.doc)
        plate = self.doc.addObject("Part::Feature", "Plate")
        plate.Shape = Part.makeBox(100, 50, 5)
        plate.addProperty("App::PropertyMap", "Material")
        plate.Material = {"Name": "Aluminium", "Density": "2700 kg/m^3"}
        da.add_part(self.asm, plate, grounded=True)
        self.bolts = []
        for k in range(4):
            b = self.doc.addObject("Part::Feature", "Bolt")
            b.Label = "Bolt"  # FreeCAD numbers them: Bolt, Bolt001, Bolt002, Bolt003
            b.Shape = Part.makeCylinder(3, 20)
            b.Placement.Base = App.Vector(10 + 25 * k, 10, 5)
            da.add_part(self.asm, b)
            self.bolts.append(b)
        steel = self.doc.addObject("App::MaterialObjectPython", "Steel")
        steel.Material = {"Name": "Steel", "Density": "7900 kg/m^3"}
        steel.addProperty("App::PropertyLinkSubList", "References")
        steel.References = [(b, "Solid1") for b in self.bolts]
        for radius in (2, 2.5):
            p = self.doc.addObject("Part::Feature", "Pin")
            p.Label = "Pin"
            p.Shape = Part.makeCylinder(radius, 10)
            da.add_part(self.asm, p)
        # A density without its unit is not guessed at: the name kept, no mass.
        p.addProperty("App::PropertyMap", "Material")
        p.Material = {"Name": "Brass?", "Density": "8500"}
        self.links = [da.import_part(self.asm, th.parts.write_step(th.parts.link(n), os.path.join(self.tmp.name,
                                                                                              "link-%d.step" % n)))
                      for n in (1, 3)]
        self.doc.recompute()

    def tearDown(self):
        App.closeDocument(self.doc.Name)
        self.tmp.cleanup()

    def test_quantities_materials_and_masses(self):
        self.assertEqual([b.Label for b in self.bolts], ["Bolt", "Bolt001", "Bolt002", "Bolt003"])
        bill = bom.rows(self.asm)
        got = [(r.index, r.name, r.quantity, r.material) for r in bill]
        self.assertEqual(got, [("1", "Plate", 1, "Aluminium"), ("2", "Bolt", 4, "Steel"), ("3", "Pin", 1, ""),
                               ("4", "Pin001", 1, "Brass?"), ("5", "link-1", 1, ""), ("6", "link-3", 1, "")])
        plate, bolt, pin, pin2 = bill[:4]
        self.assertAlmostEqual(plate.volume, 100 * 50 * 5, delta=1e-6)
        self.assertAlmostEqual(plate.mass, 100 * 50 * 5 * ALUMINIUM, delta=1e-9)  # 67.5 g
        self.assertAlmostEqual(bolt.volume, math.pi * 9 * 20, delta=1e-6)
        self.assertAlmostEqual(bolt.mass, math.pi * 9 * 20 * STEEL, delta=1e-9)
        self.assertAlmostEqual(pin2.volume, math.pi * 2.5 ** 2 * 10, delta=1e-6)
        # No material: no mass, whatever the workbench's solver weight (Density) says.
        self.assertIsNone(pin.mass)
        self.assertIsNone(pin2.mass)
        self.assertEqual(self.links[0].Density, 1.0)
        self.assertIsNone(bill[4].mass)

    def test_sheet_written_once_updated_and_one_undo_step(self):
        sheet, bill = bom.write_sheet(self.asm)
        self.assertEqual(sheet.TypeId, "Spreadsheet::Sheet")
        self.assertEqual(sheet.Label, "BOM of Assembly")
        rows = cells(sheet)
        self.assertEqual(rows[0], list(bom.COLUMNS))
        self.assertEqual(rows[2][:3], ["'2", "Bolt", "4"])  # an index stays text ("2", "2.1")
        self.assertEqual(float(sheet.get("F3")), bill[1].mass)  # the number, as computed
        self.assertEqual(len(rows), 7)
        # Again: the same sheet, no second one; a fifth bolt counted.
        b = self.doc.addObject("Part::Feature", "Bolt")
        b.Shape = Part.makeCylinder(3, 20)
        da.add_part(self.asm, b)
        undo_before = self.doc.UndoCount
        again, bill = bom.write_sheet(self.asm)
        self.assertIs(again, sheet)
        self.assertEqual([o for o in self.doc.Objects if o.TypeId == "Spreadsheet::Sheet"], [sheet])
        self.assertEqual(sheet.getContents("C3"), "5")
        self.assertEqual(self.doc.UndoCount, undo_before + 1)
        self.doc.undo()
        self.assertEqual(sheet.getContents("C3"), "4")
        # A row fewer (the pins gone): no stale row left behind.
        for p in [o for o in da.parts(self.asm) if o.Label.startswith("Pin")]:
            self.asm.removeObject(p)
        bom.write_sheet(self.asm)
        self.assertEqual(len(cells(sheet)), 5)
        self.assertEqual(sheet.getContents("B4"), "link-1")

    def test_csv_is_the_sheet(self):
        sheet, bill = bom.write_sheet(self.asm)
        path = bom.write_csv(bill, os.path.join(self.tmp.name, "bom.csv"))
        with open(path, newline="", encoding="utf-8") as f:
            read = list(csv.reader(f))
        self.assertEqual(read[0], list(bom.COLUMNS))
        self.assertEqual([r[:3] for r in read[1:]], [[r.index, r.name, str(r.quantity)] for r in bill])
        self.assertEqual(float(read[2][5]), bill[1].mass)  # all its digits
        self.assertAlmostEqual(float(read[2][5]), math.pi * 9 * 20 * STEEL, delta=1e-9)
        self.assertEqual(read[3][5], "")
        for row in cells(sheet)[1:]:
            self.assertIn([c.lstrip("'") for c in row[:3]], [r[:3] for r in read])

    def test_refused_choice_changes_nothing(self):
        count = len(self.doc.Objects)
        with self.assertRaisesRegex(ValueError, "rows, indented, expanded"):
            bom.write_sheet(self.asm, "nested")
        self.assertEqual(len(self.doc.Objects), count)


class Walker(unittest.TestCase):
    """The leg of leg.FCStd (Hip, Crank, Coupler, Rocker) placed four times on a frame."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        leg = ts.make_leg(cls.tmp.name)
        legdoc = App.openDocument(leg)
        cls.leg_parts = [p.Label for p in da.parts(da.top_assemblies(legdoc)[0])]
        cls.doc, cls.asm, cls.frame, cls.subs = ts.make_walker(cls.tmp.name, leg, rigid=False)

    @classmethod
    def tearDownClass(cls):
        for name in list(App.listDocuments()):
            App.closeDocument(name)
        cls.tmp.cleanup()

    def test_sub_assemblies_as_rows_indented_and_expanded(self):
        self.assertEqual(len(self.leg_parts), 4)
        rows = [(r.index, r.name, r.quantity, r.source) for r in bom.rows(self.asm, "rows")]
        self.assertEqual(rows, [("1", "Frame", 1, ""), ("2", "Leg", 4, "leg.FCStd")])
        indented = bom.rows(self.asm, "indented")
        self.assertEqual([(r.index, r.name, r.quantity) for r in indented],
                         [("1", "Frame", 1), ("2", "Leg", 4)] +
                         [("2.%d" % (k + 1), label, 1) for k, label in enumerate(self.leg_parts)])
        # A leg's volume is its parts'.
        self.assertAlmostEqual(indented[1].volume, sum(r.volume for r in indented[2:]), delta=1e-9)
        expanded = bom.rows(self.asm, "expanded")
        self.assertEqual([(r.name, r.quantity) for r in expanded],
                         [("Frame", 1)] + [(label, 4) for label in self.leg_parts])
        sheet, _ = bom.write_sheet(self.asm, "indented")
        self.assertEqual(sheet.SubAssemblies, "indented")
        self.assertEqual(cells(sheet)[3][:3], ["'2.1", self.leg_parts[0], "1"])


def centres(view):
    """The centres of the exploded view's solids, in the order of its Parts."""
    return [s.BoundBox.Center for s in view.Shape.Solids]


class Blocks(unittest.TestCase):
    """Cubes of 10 mm: a base and three blocks, at known places."""

    PLACES = ((0, 0, 0), (30, 0, 0), (0, 40, 0), (0, 0, 50))

    def setUp(self):
        self.doc = App.newDocument("blocks")
        self.doc.UndoMode = 1
        self.asm = da.create_assembly(self.doc)
        for k, p in enumerate(self.PLACES):
            o = self.doc.addObject("Part::Feature", "Block%d" % k)
            o.Shape = Part.makeBox(10, 10, 10)
            o.Placement = App.Placement(App.Vector(*p), App.Rotation(App.Vector(1, 2, 3), 7 * k))
            da.add_part(self.asm, o, grounded=k == 0)
        self.before = placements(self.asm)

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def test_radial_offsets_from_the_centre(self):
        view = exploded.new_exploded_view(self.asm, distance=20)
        own = [p.Shape.BoundBox.Center for p in da.parts(self.asm)]
        box = App.BoundBox()
        for p in da.parts(self.asm):
            box.add(p.Shape.BoundBox)
        far = max((c - box.Center).Length for c in own)
        for c, got, offset in zip(own, centres(view), view.Offsets):
            want = (c - box.Center) * (20 / far)
            self.assertLess((offset - want).Length, 1e-9)
            self.assertLess((got - (c + want)).Length, 1e-9)
            # Outward: along the line from the centre.
            self.assertGreater(offset.dot(c - box.Center), 0)
        self.assertAlmostEqual(max(v.Length for v in view.Offsets), 20, delta=1e-9)
        self.assertEqual(len(view.Shape.Edges) - sum(len(p.Shape.Edges) for p in da.parts(self.asm)), 4)
        self.assertEqual(placements(self.asm), self.before)

    def test_direction_stacks_the_parts(self):
        # Two blocks side by side at the bottom: one level; each next level 15 mm further on -z.
        self.doc.getObject("Block1").Placement = App.Placement(App.Vector(30, 0, 0), App.Rotation())
        self.doc.getObject("Block0").Placement = App.Placement()
        self.doc.getObject("Block2").Placement = App.Placement(App.Vector(0, 40, 20), App.Rotation())
        self.doc.getObject("Block3").Placement = App.Placement(App.Vector(0, 0, 50), App.Rotation())
        before = placements(self.asm)
        view = exploded.new_exploded_view(self.asm, mode="Direction", direction=App.Vector(0, 0, 2), distance=15)
        want = [App.Vector(0, 0, 0), App.Vector(0, 0, 0), App.Vector(0, 0, 15), App.Vector(0, 0, 30)]
        for got, w in zip(view.Offsets, want):
            self.assertLess((got - w).Length, 1e-12)
        # Reversed direction: the top stays, the rest go down.
        exploded.set_explosion(view, direction=App.Vector(0, 0, -1))
        want = [App.Vector(0, 0, -30), App.Vector(0, 0, -30), App.Vector(0, 0, -15), App.Vector(0, 0, 0)]
        for got, w in zip(view.Offsets, want):
            self.assertLess((got - w).Length, 1e-12)
        self.assertEqual(placements(self.asm), before)

    def test_placements_never_touched_and_one_undo_step(self):
        n = self.doc.UndoCount
        view = exploded.new_exploded_view(self.asm, distance=5)
        self.assertEqual(self.doc.UndoCount, n + 1)
        for d in (0, 12.5, 100, 1e-3):
            exploded.set_explosion(view, distance=d)
            self.assertEqual(placements(self.asm), self.before)
        self.assertAlmostEqual(max(v.Length for v in view.Offsets), 1e-3, delta=1e-15)
        self.doc.undo()
        self.assertAlmostEqual(view.Distance.Value, 100, delta=1e-12)
        # A refused setting changes nothing.
        count = len(self.doc.Objects)
        with self.assertRaisesRegex(ValueError, "no length"):
            exploded.set_explosion(view, mode="Direction", direction=App.Vector())
        self.assertEqual(view.Mode, "Radial")
        with self.assertRaisesRegex(ValueError, "mode is one of"):
            exploded.set_explosion(view, mode="Sideways")
        with self.assertRaisesRegex(ValueError, "it is not a part"):
            da.add_part(self.asm, view)
        self.assertEqual(len(self.doc.Objects), count)
        self.assertEqual(placements(self.asm), self.before)

    def test_a_part_moved_moves_its_exploded_copy(self):
        view = exploded.new_exploded_view(self.asm, mode="Direction", direction=App.Vector(1, 0, 0), distance=7)
        block = self.doc.getObject("Block3")
        block.Placement = App.Placement(App.Vector(60, 0, 0), block.Placement.Rotation)
        self.doc.recompute()
        # Block3 is now the farthest along x: rank 2 (Block0 and Block2 share x = 0's level... by
        # their centres, which their rotations set apart: counted here from the shapes).
        xs = [p.Shape.BoundBox.Center.x for p in da.parts(self.asm)]
        levels = sorted(set(round(x, 9) for x in xs))
        for x, got in zip(xs, view.Offsets):
            self.assertLess((got - App.Vector(7 * levels.index(round(x, 9)), 0, 0)).Length, 1e-9)


class SavedExploded(unittest.TestCase):
    """The four-bar solved, exploded, saved and reopened: assembled as it was, exploded as it was."""

    def test_saved_while_exploded_reopens_assembled(self):
        tmp = tempfile.TemporaryDirectory()
        try:
            doc = App.newDocument("exploded")
            asm = th.fourbar(doc, tmp.name)[0]
            self.assertTrue(da.solve(asm).converged)
            # FreeCAD writes a placement to fewer digits than it holds: the same assembly saved
            # without an exploded view is what the exploded one must reopen as, to the bit.
            assembled = os.path.join(tmp.name, "assembled.FCStd")
            doc.saveCopy(assembled)
            view = exploded.new_exploded_view(asm, distance=2)
            offsets = [tuple(v) for v in view.Offsets]
            self.assertTrue(any(v != (0, 0, 0) for v in offsets))
            path = os.path.join(tmp.name, "exploded.FCStd")
            doc.saveAs(path)
            App.closeDocument(doc.Name)
            plain = App.openDocument(assembled)
            before = placements(da.top_assemblies(plain)[0])
            App.closeDocument(plain.Name)
            doc = App.openDocument(path)
            asm = da.top_assemblies(doc)[0]
            self.assertEqual(placements(asm), before)
            view = exploded.views_of(asm)[0]
            self.assertEqual([tuple(v) for v in view.Offsets], offsets)
            self.assertEqual(len(view.Shape.Solids), 4)
            self.assertIsInstance(view.Proxy, exploded.ExplodedViewProxy)
            r = da.solve(asm)
            self.assertTrue(r.converged, r.message)
            self.assertEqual(placements(asm), before)  # nothing to snap back: nothing moved
            doc.recompute()  # from the placements as saved (to FreeCAD's digits)
            for got, was in zip(view.Offsets, offsets):
                self.assertLess((got - App.Vector(*was)).Length, 1e-12)
            App.closeDocument(doc.Name)
        finally:
            tmp.cleanup()


class FollowsTheAssembly(unittest.TestCase):
    """An exploded view redrawn in a Solve's and a drag's own undo step: at the new pose as soon as
    they return, back with the parts at undo, against the offsets computed here (radial, from the
    parts' centres), the placements written only by the solve and the drag."""

    def setUp(self):
        self.doc = App.newDocument("follows")
        self.doc.UndoMode = 1
        self.asm, self.base, self.arm = th.arm_on_base(self.doc)
        self.arm.Placement = App.Placement(App.Vector(0.2, 0.1, 0.3), App.Rotation(App.Vector(0, 0, 1), 20))
        da.add_joint(self.asm, "Revolute", th.pin(self.base, (0, 0, 0)), th.pin(self.arm, (0, 0, 0)))

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def assertDrawnAtThePose(self, view, distance):
        own = [p.Shape.BoundBox.Center for p in da.parts(self.asm)]
        box = App.BoundBox()
        for p in da.parts(self.asm):
            box.add(p.Shape.BoundBox)
        far = max((c - box.Center).Length for c in own)
        self.assertEqual(len(view.Offsets), len(own))
        for c, got, offset in zip(own, centres(view), view.Offsets):
            want = (c - box.Center) * (distance / far)
            self.assertLess((offset - want).Length, 1e-9)
            self.assertLess((got - (c + want)).Length, 1e-9)

    def test_a_solve_and_a_drag_redraw_the_view_in_their_undo_step(self):
        view = exploded.new_exploded_view(self.asm, distance=3)
        drawn = [tuple(v) for v in view.Offsets], [tuple(c) for c in centres(view)]
        before = placements(self.asm)
        n = self.doc.UndoCount
        r = da.solve(self.asm)
        self.assertTrue(r.converged and r.iterations > 0, r.message)
        self.assertNotEqual(placements(self.asm), before)
        self.assertDrawnAtThePose(view, 3)
        self.assertNotEqual([tuple(c) for c in centres(view)], drawn[1])
        self.assertEqual(self.doc.UndoCount, n + 1)  # the view's redraw is the Solve's step
        # Undo: the parts and the view together, with no recompute between.
        self.doc.undo()
        self.assertEqual(placements(self.asm), before)
        self.assertEqual(([tuple(v) for v in view.Offsets], [tuple(c) for c in centres(view)]), drawn)
        self.doc.redo()
        self.assertDrawnAtThePose(view, 3)
        # A drag as the GUI makes one (live=False: the placements written once, at release).
        solved = placements(self.asm)
        grab = self.arm.Placement.multVec(App.Vector(1.5, 0, 0))
        n = self.doc.UndoCount
        d = da.PointDrag(self.asm, self.arm, grab, live=False)
        self.assertTrue(d.move(grab + App.Vector(-0.8, 0.9, 0)))
        self.assertEqual(placements(self.asm), solved)  # nothing written before the release
        drawn = [tuple(v) for v in view.Offsets], [tuple(c) for c in centres(view)]
        d.finish()
        self.assertNotEqual(placements(self.asm), solved)
        self.assertDrawnAtThePose(view, 3)
        self.assertNotEqual([tuple(c) for c in centres(view)], drawn[1])
        self.assertEqual(self.doc.UndoCount, n + 1)
        self.doc.undo()
        self.assertEqual(placements(self.asm), solved)
        self.assertEqual(([tuple(v) for v in view.Offsets], [tuple(c) for c in centres(view)]), drawn)
        # A live drag (a script's): the same at its finish.
        turned = App.Placement(self.arm.Placement.Base, self.arm.Placement.Rotation)
        turned.rotate(self.base.Placement.multVec(App.Vector(0, 0, 0)), App.Vector(0, 0, 1), 35)
        n = self.doc.UndoCount
        self.assertTrue(da.drag(self.asm, self.arm, turned).converged)
        self.assertDrawnAtThePose(view, 3)
        self.assertEqual(self.doc.UndoCount, n + 1)


class ExplodedWalker(unittest.TestCase):
    def test_a_leg_moves_as_one_or_each_part_alone(self):
        tmp = tempfile.TemporaryDirectory()
        try:
            leg = ts.make_leg(tmp.name)
            doc, asm, frame, subs = ts.make_walker(tmp.name, leg, rigid=False)
            before = placements(asm)
            view = exploded.new_exploded_view(asm, distance=3)
            by_part = {p.Name: v for p, v in zip(view.Parts, view.Offsets)}
            self.assertEqual(len(by_part), 1 + 4 * 4)
            for sub in subs:
                links = da.instance_parts(sub)
                self.assertTrue(all(by_part[l.Name] == by_part[links[0].Name] for l in links))
                # The leg as one: from the frame's and legs' box centre towards the leg's.
                box = App.BoundBox()
                for l in links:
                    box.add(da.shape_of(l).BoundBox)
                whole = App.BoundBox()
                for p in da.placed_parts(asm):
                    whole.add(da.shape_of(p).BoundBox)
                d = box.Center - whole.Center
                self.assertLess(by_part[links[0].Name].cross(d).Length, 1e-9 * d.Length * 3)
            exploded.set_explosion(view, expand_sub_assemblies=True)
            crank_offsets = [tuple(dict(zip([p.Name for p in view.Parts], view.Offsets))[ts.part(s, "Crank").Name])
                             for s in subs]
            hip_offsets = [tuple(dict(zip([p.Name for p in view.Parts], view.Offsets))[ts.part(s, "Hip").Name])
                           for s in subs]
            self.assertTrue(all(c != h for c, h in zip(crank_offsets, hip_offsets)))
            self.assertEqual(placements(asm), before)
            for name in list(App.listDocuments()):
                App.closeDocument(name)
        finally:
            tmp.cleanup()


class Parade(unittest.TestCase):
    """walker.FCStd (a frame and four legs of leg.FCStd) placed twice on a track: nested."""

    def test_nested_sub_assemblies_in_the_bill_and_the_exploded_view(self):
        os.environ["DISPCON_NESTED_IMPORT_ONLY"] = "1"
        import test_nested as tn

        tmp = tempfile.TemporaryDirectory()
        try:
            leg, walker, wdoc = tn.make_walker_file(tmp.name)
            leg_parts = [p.Label for p in da.parts(da.top_assemblies(App.openDocument(leg))[0])]
            doc, asm, track, walks = tn.make_parade(tmp.name, walker, rigid=False)
            indented = [(r.index, r.name, r.quantity) for r in bom.rows(asm, "indented")]
            self.assertEqual(indented, [("1", "Track", 1), ("2", "Walker", 2), ("2.1", "Frame", 1), ("2.2", "Leg", 4)]
                             + [("2.2.%d" % (k + 1), label, 1) for k, label in enumerate(leg_parts)])
            expanded = [(r.name, r.quantity) for r in bom.rows(asm, "expanded")]
            self.assertEqual(expanded, [("Track", 1), ("Frame", 2)] + [(label, 8) for label in leg_parts])
            rows = bom.rows(asm, "indented")
            self.assertAlmostEqual(rows[1].volume, rows[2].volume + 4 * rows[3].volume, delta=1e-9)
            # Exploded: each walker (its frame and its four legs' parts) by one offset.
            before = placements(asm)
            view = exploded.new_exploded_view(asm, distance=5)
            by_part = dict(zip([p.Name for p in view.Parts], view.Offsets))
            self.assertEqual(len(by_part), 1 + 2 * (1 + 4 * 4))
            for w in walks:
                moved = {tuple(by_part[p.Name]) for p in da.nested_parts(w)}
                self.assertEqual(len(moved), 1)
            self.assertEqual(placements(asm), before)
            for name in list(App.listDocuments()):
                App.closeDocument(name)
        finally:
            tmp.cleanup()


if __name__ == "__main__" or not os.environ.get("DISPCON_PRESENTATION_IMPORT_ONLY"):
    suite = unittest.TestSuite(unittest.defaultTestLoader.loadTestsFromTestCase(c)
                               for c in (Hardware, Walker, Blocks, SavedExploded, FollowsTheAssembly, ExplodedWalker,
                                                             Parade))
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
    failed = len(result.failures) + len(result.errors)
    print("%d passed, %d failed" % (result.testsRun - failed, failed))
    # freecadcmd would open the arguments after this script as documents.
    sys.exit(1 if failed else 0)
