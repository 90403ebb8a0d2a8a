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


def key_cells(row):
    """Index, Name and Quantity of a row of the sheet or the CSV."""
    return [row[0], row[1], row[bom.QUANTITY]]


def placements(asm):
    return {p.Name: bits(p.Placement) for p in da.placed_parts(asm)}


def cells(sheet):
    """The sheet's cells as text, row by row, as far as the header's columns (A..I)."""
    out = []
    r = 1
    while sheet.getContents("A%d" % r) or sheet.getContents("B%d" % r):
        out.append([sheet.getContents("%s%d" % (c, r)) for c in "ABCDEFGHI"])
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
        self.assertEqual(key_cells(rows[2]), ["'2", "Bolt", "4"])  # an index stays text ("2", "2.1")
        self.assertEqual(float(sheet.get("H3")), bill[1].mass)  # the number, as computed
        self.assertEqual(len(rows), 7)
        # Again: the same sheet, no second one; a fifth bolt counted.
        b = self.doc.addObject("Part::Feature", "Bolt")
        b.Shape = Part.makeCylinder(3, 20)
        da.add_part(self.asm, b)
        undo_before = self.doc.UndoCount
        again, bill = bom.write_sheet(self.asm)
        self.assertIs(again, sheet)
        self.assertEqual([o for o in self.doc.Objects if o.TypeId == "Spreadsheet::Sheet"], [sheet])
        self.assertEqual(sheet.getContents("E3"), "5")
        self.assertEqual(self.doc.UndoCount, undo_before + 1)
        self.doc.undo()
        self.assertEqual(sheet.getContents("E3"), "4")
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
        self.assertEqual([key_cells(r) for r in read[1:]], [[r.index, r.name, str(r.quantity)] for r in bill])
        self.assertEqual(float(read[2][7]), bill[1].mass)  # all its digits
        self.assertAlmostEqual(float(read[2][7]), math.pi * 9 * 20 * STEEL, delta=1e-9)
        self.assertEqual(read[3][7], "")
        for row in cells(sheet)[1:]:
            self.assertIn([c.lstrip("'") for c in key_cells(row)], [key_cells(r) for r in read])

    def test_refused_choice_changes_nothing(self):
        count = len(self.doc.Objects)
        with self.assertRaisesRegex(ValueError, "rows, indented, expanded"):
            bom.write_sheet(self.asm, "nested")
        self.assertEqual(len(self.doc.Objects), count)


class PartNumbers(unittest.TestCase):
    """The hardware of Hardware, given part numbers and descriptions: on the parts where they are
    defined, in the bill's Part number and Description columns, the sheet's and the CSV's."""

    setUp, tearDown = Hardware.setUp, Hardware.tearDown

    def test_part_numbers_and_descriptions_in_the_bill_sheet_and_csv(self):
        bolts = self.bolts
        plate = self.doc.getObject("Plate")
        self.assertEqual(plate.PartNumber, "")  # every part of the workbench has the property
        plate.Label2 = "Base plate, 5 mm"  # FreeCAD's own Description (the tree's column)
        n = self.doc.UndoCount
        self.assertIs(bom.set_part_info(bolts[0], " ISO 4017 M6x20 ", "Hex bolt"), bolts[0])
        self.assertEqual(self.doc.UndoCount, n + 1)
        self.assertEqual((bolts[0].PartNumber, bolts[0].Label2), ("ISO 4017 M6x20", "Hex bolt"))
        # One bolt numbered, three not: two parts now (the same shape, not the same part).
        got = [(r.name, r.part_number, r.description, r.quantity) for r in bom.rows(self.asm)[:3]]
        self.assertEqual(got, [("Plate", "", "Base plate, 5 mm", 1), ("Bolt", "ISO 4017 M6x20", "Hex bolt", 1),
                               ("Bolt001", "", "", 3)])
        for b in bolts[1:]:
            bom.set_part_info(b, "ISO 4017 M6x20", "Hex bolt")
        bill = bom.rows(self.asm)
        self.assertEqual([(r.name, r.part_number, r.quantity) for r in bill[:2]],
                         [("Plate", "", 1), ("Bolt", "ISO 4017 M6x20", 4)])
        sheet, bill = bom.write_sheet(self.asm)
        self.assertEqual(cells(sheet)[0][2:4], ["Part number", "Description"])
        self.assertEqual(cells(sheet)[2][:5], ["'2", "Bolt", "ISO 4017 M6x20", "Hex bolt", "4"])
        self.assertEqual(cells(sheet)[1][3], "Base plate, 5 mm")
        path = bom.write_csv(bill, os.path.join(self.tmp.name, "numbered.csv"))
        with open(path, newline="", encoding="utf-8") as f:
            read = list(csv.reader(f))
        self.assertEqual(read[2][:5], ["2", "Bolt", "ISO 4017 M6x20", "Hex bolt", "4"])
        self.assertEqual(read[1][2:4], ["", "Base plate, 5 mm"])

    def test_typed_with_the_sheet_in_one_undo_step_and_refusals(self):
        pin = [p for p in da.parts(self.asm) if p.Label == "Pin"][0]
        sheet, _ = bom.write_sheet(self.asm)
        n = self.doc.UndoCount
        bom.write_sheet(self.asm, part_info={pin: ("P-2x10", "Dowel pin 2 x 10")})
        self.assertEqual(self.doc.UndoCount, n + 1)
        self.assertEqual(sheet.getContents("C4"), "P-2x10")
        self.doc.undo()
        self.assertEqual((pin.PartNumber, pin.Label2, sheet.getContents("C4")), ("", "", ""))
        count = len(self.doc.Objects)
        for number, text, message in (("P-1\nP-2", None, "^Pin: the part number is one line of text"),
                                      (12, None, "^Pin: the part number is text, not 12$"),
                                      ("P-3", "a\tb", "^Pin: the description is one line of text")):
            with self.assertRaisesRegex(ValueError, message):
                bom.set_part_info(pin, number, text)
            with self.assertRaisesRegex(ValueError, message):
                bom.write_sheet(self.asm, part_info={pin: (number, text)})
            self.assertEqual((pin.PartNumber, pin.Label2, self.doc.UndoCount, len(self.doc.Objects)), ("", "", n, count))
            self.assertEqual(sheet.getContents("C4"), "")


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
        self.assertEqual(key_cells(cells(sheet)[3]), ["'2.1", self.leg_parts[0], "1"])


class WalkerPartNumbers(unittest.TestCase):
    """A placed leg's part numbers are leg.FCStd's: shown in the walker's bill, set only there."""

    def test_set_in_the_placed_file_shown_here_refused_here(self):
        with tempfile.TemporaryDirectory() as tmp:
            leg = ts.make_leg(tmp)
            legdoc = App.openDocument(leg)
            legasm = da.top_assemblies(legdoc)[0]
            crank = [p for p in da.parts(legasm) if p.Label == "Crank"][0]
            bom.set_part_info(crank, "L-100", "Crank, 1 mm")
            bom.set_part_info(legasm, "A-10", "Four-bar leg")
            doc, asm, frame, subs = ts.make_walker(tmp, leg, rigid=False)
            try:
                got = [(r.index, r.name, r.part_number, r.description, r.quantity) for r in bom.rows(asm, "indented")]
                self.assertIn(("2", "Leg", "A-10", "Four-bar leg", 4), got)
                self.assertIn(("2.2", "Crank", "L-100", "Crank, 1 mm", 1), got)
                link = ts.part(subs[0], "Crank")
                undo = doc.UndoCount
                for obj, label in ((link, "Crank"), (subs[0], "Leg")):
                    with self.assertRaisesRegex(ValueError, "^%s is defined in leg.FCStd: set its part number and "
                                                            "description there" % label):
                        bom.set_part_info(obj, "X")
                self.assertEqual((crank.PartNumber, doc.UndoCount), ("L-100", undo))
            finally:
                for name in list(App.listDocuments()):
                    App.closeDocument(name)


def centres(view):
    """The centres of the exploded view's solids, in the order of its Parts."""
    return [s.BoundBox.Center for s in view.Shape.Solids]


class Blocks(unittest.TestCase):
    """Cubes of 10 mm: a base and three blocks, at known places."""

    PLACES = ((0, 0, 0), (30, 0, 0), (0, 40, 0), (0, 0, 50))

    def setUp(self):
        make_blocks(self)

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
        view = exploded.new_exploded_view(self.asm, mode="Stack", direction=App.Vector(0, 0, 2), distance=15)
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
        self.assertEqual(list(view.StepDistances), [100.0])
        # A refused setting changes nothing.
        count = len(self.doc.Objects)
        with self.assertRaisesRegex(ValueError, "^step 1: the direction has no length$"):
            exploded.set_explosion(view, mode="Direction", direction=App.Vector())
        self.assertEqual(list(view.StepModes), ["Radial"])
        with self.assertRaisesRegex(ValueError, "^step 1: the way is one of Radial, Direction, Stack, not 'Sideways'$"):
            exploded.set_explosion(view, mode="Sideways")
        with self.assertRaisesRegex(ValueError, "it is not a part"):
            da.add_part(self.asm, view)
        self.assertEqual(len(self.doc.Objects), count)
        self.assertEqual(placements(self.asm), self.before)

    def test_a_part_moved_moves_its_exploded_copy(self):
        view = exploded.new_exploded_view(self.asm, mode="Stack", direction=App.Vector(1, 0, 0), distance=7)
        block = self.doc.getObject("Block3")
        block.Placement = App.Placement(App.Vector(60, 0, 0), block.Placement.Rotation)
        self.doc.recompute()
        # Block3 is now the farthest along x: rank 2 (Block0 and Block2 share x = 0's level... by
        # their centres, which their rotations set apart: counted here from the shapes).
        xs = [p.Shape.BoundBox.Center.x for p in da.parts(self.asm)]
        levels = sorted(set(round(x, 9) for x in xs))
        for x, got in zip(xs, view.Offsets):
            self.assertLess((got - App.Vector(7 * levels.index(round(x, 9)), 0, 0)).Length, 1e-9)


def make_blocks(test):
    """Blocks.PLACES' cubes in an assembly of a new document (undo on): test.doc, test.asm,
    test.before (the placements, to the bit)."""
    test.doc = App.newDocument("blocks")
    test.doc.UndoMode = 1
    test.asm = da.create_assembly(test.doc)
    for k, p in enumerate(Blocks.PLACES):
        o = test.doc.addObject("Part::Feature", "Block%d" % k)
        o.Shape = Part.makeBox(10, 10, 10)
        o.Placement = App.Placement(App.Vector(*p), App.Rotation(App.Vector(1, 2, 3), 7 * k))
        da.add_part(test.asm, o, grounded=k == 0)
    test.before = placements(test.asm)


def expected_offsets(objs, steps):
    """{Name: offset} after steps [(names moved, mode, distance, direction)], computed here from the
    parts' boxes: each step from where the ones before left them (the rules of docs/workbench.md)."""
    boxes = {o.Name: o.Shape.BoundBox for o in objs}
    off = {n: App.Vector() for n in boxes}

    def centre(names):
        box = App.BoundBox()
        for n in names:
            b = App.BoundBox(boxes[n])
            b.move(off[n])
            box.add(b)
        return box.Center

    for names, mode, distance, direction in steps:
        d = App.Vector(direction) if direction is not None else None
        if mode == "Direction":
            moves = {n: d.normalize() * distance for n in names}
        elif mode == "Radial":
            c = centre(list(boxes))
            far = max((centre([n]) - c).Length for n in names)
            moves = {n: (centre([n]) - c) * (distance / far) for n in names}
        else:
            d.normalize()
            levels = sorted(set(round(centre([n]).dot(d), 6) for n in names))
            moves = {n: d * (distance * levels.index(round(centre([n]).dot(d), 6))) for n in names}
        for n, m in moves.items():
            off[n] = off[n] + m
    return off


def step_lists(view):
    return (list(view.StepModes), list(view.StepDistances), [tuple(v) for v in view.StepDirections],
            [p.Name for p in view.StepParts], list(view.StepSizes))


class Steps(unittest.TestCase):
    """An exploded view as a list of steps, each moving chosen blocks, applied in order: against
    offsets computed here (expected_offsets), every placement to the bit, one undo step each."""

    def setUp(self):
        make_blocks(self)
        self.b = [self.doc.getObject("Block%d" % k) for k in range(4)]

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def assertOffsets(self, view, want):
        got = dict(zip([p.Name for p in view.Parts], view.Offsets))
        self.assertEqual(sorted(got), sorted(want))
        for name, w in want.items():
            self.assertLess((got[name] - w).Length, 1e-9, name)
        for p, c in zip(view.Parts, centres(view)):
            self.assertLess((c - (p.Shape.BoundBox.Center + want[p.Name])).Length, 1e-9, p.Name)

    def test_steps_in_order_reordered_and_removed(self):
        b0, b1, b2, b3 = self.b
        every = [o.Name for o in self.b]
        n = self.doc.UndoCount
        view = exploded.new_exploded_view(self.asm, steps=[
            exploded.Step([b1], "Direction", 15, App.Vector(2, 0, 0)),
            exploded.Step(self.b, "Radial", 20)])
        self.assertEqual(self.doc.UndoCount, n + 1)
        first = expected_offsets(self.b, [([b1.Name], "Direction", 15, (1, 0, 0)), (every, "Radial", 20, None)])
        self.assertOffsets(view, first)
        # Block1 went 15 along x first: the radial step measured from there (not from its place).
        self.assertGreater((first["Block1"] - expected_offsets(self.b, [(every, "Radial", 20, None)])["Block1"]
                            - App.Vector(15, 0, 0)).Length, 0.5)
        # The lines: Block1's way in two pieces, the others' in one.
        self.assertEqual(len(view.Shape.Edges) - 4 * 12, 5)
        self.assertEqual(placements(self.asm), self.before)
        # The radial step first: from the places, then Block1 along x.
        exploded.move_step(view, 1, 0)
        self.assertEqual(self.doc.UndoCount, n + 2)
        self.assertOffsets(view, expected_offsets(self.b, [(every, "Radial", 20, None),
                                                           ([b1.Name], "Direction", 15, (1, 0, 0))]))
        # A third step: Block2 and Block3 stacked along -z, 7 mm apart.
        exploded.add_step(view, [b2, b3], "Stack", 7, (0, 0, -1))
        three = [(every, "Radial", 20, None), ([b1.Name], "Direction", 15, (1, 0, 0)),
                 (["Block2", "Block3"], "Stack", 7, (0, 0, -1))]
        self.assertOffsets(view, expected_offsets(self.b, three))
        self.assertEqual(step_lists(view)[0], ["Radial", "Direction", "Stack"])
        exploded.remove_step(view, 0)
        self.assertOffsets(view, expected_offsets(self.b, three[1:]))
        self.assertEqual(self.doc.UndoCount, n + 4)
        self.doc.undo()
        self.assertOffsets(view, expected_offsets(self.b, three))
        self.doc.undo()
        self.doc.undo()
        self.assertOffsets(view, first)
        self.assertEqual(placements(self.asm), self.before)

    def test_refused_steps_change_nothing(self):
        b0, b1, b2, b3 = self.b
        view = exploded.new_exploded_view(self.asm, distance=5)
        was, undo, count = step_lists(view), self.doc.UndoCount, len(self.doc.Objects)
        stray = self.doc.addObject("Part::Feature", "Stray")
        stray.Shape = Part.makeBox(1, 1, 1)
        count += 1
        for steps, message in (
                ([exploded.Step(self.b, "Radial", 5), exploded.Step([], "Direction", 3)],
                 "^step 2 moves no part: choose the parts it moves$"),
                ([exploded.Step([b1, stray], "Direction", 3)], "^step 1: Stray is not a part of Assembly$"),
                ([exploded.Step([b1], "Direction", float("nan"))], r"^step 1: the distance must be a number of mm "
                                                                  r"\(it is nan\)$"),
                ([exploded.Step([b1, b2, b1], "Radial", 3)], r"^step 1 moves Block1 twice \(Block1 and Block1\)$"),
                ([exploded.Step([b1], "Stack", 3, App.Vector())], "^step 1: the direction has no length$")):
            with self.assertRaisesRegex(ValueError, message):
                exploded.set_steps(view, steps)
            self.assertEqual((step_lists(view), self.doc.UndoCount, len(self.doc.Objects)), (was, undo, count))
        with self.assertRaisesRegex(ValueError, "has no step 3"):
            exploded.remove_step(view, 2)
        self.assertEqual(placements(self.asm), self.before)
        # Set in the property editor: the recompute takes it through the same door, marks the view.
        view.StepModes = ["Sideways"]
        self.doc.recompute()
        self.assertFalse(view.isValid())
        view.StepModes = ["Radial"]
        self.doc.recompute()
        self.assertTrue(view.isValid())
        self.assertEqual(step_lists(view), was)

    def test_saved_and_reopened_steps_and_offsets_kept(self):
        b0, b1, b2, b3 = self.b
        view = exploded.new_exploded_view(self.asm, steps=[
            exploded.Step([b3], "Direction", 12.5, App.Vector(0, 0, 1)),
            exploded.Step([b1, b2], "Radial", 8)])
        lists, offs = step_lists(view), [tuple(v) for v in view.Offsets]
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "steps.FCStd")
            self.doc.saveAs(path)
            App.closeDocument(self.doc.Name)
            self.doc = App.openDocument(path)
            asm = da.top_assemblies(self.doc)[0]
            view = exploded.views_of(asm)[0]
            self.assertEqual(step_lists(view), lists)
            self.assertEqual([tuple(v) for v in view.Offsets], offs)
            self.doc.recompute()
            for got, was in zip(view.Offsets, offs):
                self.assertLess((got - App.Vector(*was)).Length, 1e-9)


def old_view(doc, asm, mode, distance, direction=(0, 0, 1), expand=False):
    """An exploded view as the workbench made it before steps (one explosion: Mode, Direction,
    Distance, ExpandSubAssemblies), its proxy of the same class: what such a saved file holds."""
    from dispcon_fc import objects

    obj = doc.addObject("Part::FeaturePython", "ExplodedView")
    obj.Proxy = exploded.ExplodedViewProxy.__new__(exploded.ExplodedViewProxy)
    objects._mark(obj, "ExplodedView")
    for kind, name in (("App::PropertyLink", "Assembly"), ("App::PropertyEnumeration", "Mode"),
                       ("App::PropertyVector", "Direction"), ("App::PropertyDistance", "Distance"),
                       ("App::PropertyBool", "ExpandSubAssemblies"), ("App::PropertyBool", "Lines")):
        obj.addProperty(kind, name, "Exploded view", "")
    obj.addProperty("App::PropertyLinkList", "Parts", "Result", "")
    obj.addProperty("App::PropertyVectorList", "Offsets", "Result", "")
    obj.Label = "Exploded view of %s" % asm.Label
    obj.Assembly = asm
    obj.Mode = ["Radial", "Direction"]
    obj.Mode = mode
    obj.Direction = App.Vector(*direction)
    obj.Distance = distance
    obj.ExpandSubAssemblies = expand
    obj.Lines = True
    obj.Shape = Part.makeCompound([da.shape_of(p).copy() for p in da.placed_parts(asm)])
    return obj


class Migrated(unittest.TestCase):
    """A document with a view made before steps opens with that explosion as one step, drawn as
    the old rule drew it (Radial: from the assembly's centre; Direction: stacked, now Stack)."""

    def test_old_radial_and_direction_views_become_one_step(self):
        with tempfile.TemporaryDirectory() as tmp:
            holder = unittest.TestCase()
            make_blocks(holder)
            doc, asm = holder.doc, holder.asm
            old_view(doc, asm, "Radial", 20)
            old_view(doc, asm, "Direction", 15, (0, 0, -2))
            path = os.path.join(tmp, "old.FCStd")
            doc.saveAs(path)
            App.closeDocument(doc.Name)
            doc = App.openDocument(path)
            try:
                asm = da.top_assemblies(doc)[0]
                blocks = da.parts(asm)
                names = [b.Name for b in blocks]
                radial, stack = exploded.views_of(asm)
                for view in (radial, stack):
                    self.assertNotIn("Mode", view.PropertiesList)
                    self.assertNotIn("Distance", view.PropertiesList)
                self.assertEqual(step_lists(radial), (["Radial"], [20.0], [(0.0, 0.0, 1.0)], names, [4]))
                self.assertEqual(step_lists(stack)[:2], (["Stack"], [15.0]))
                doc.recompute()
                for view, want in ((radial, expected_offsets(blocks, [(names, "Radial", 20, None)])),
                                   (stack, expected_offsets(blocks, [(names, "Stack", 15, (0, 0, -1))]))):
                    got = dict(zip([p.Name for p in view.Parts], view.Offsets))
                    for n in names:
                        self.assertLess((got[n] - want[n]).Length, 1e-9, (view.Label, n))
                for b in blocks:  # not moved (a save keeps a rotation to about 1e-16)
                    self.assertTrue(th.same(b.Placement, App.Placement(*[App.Vector(*holder.before[b.Name][:3]),
                                                                          App.Rotation(*holder.before[b.Name][3:])]),
                                            1e-12), b.Label)
            finally:
                App.closeDocument(doc.Name)


EXPLODED_WITHOUT_WORKBENCH = th.BARE_SESSION + """
import json
views = [o for o in doc.Objects if "DispconType" in o.PropertiesList and o.DispconType == "ExplodedView"]
assert len(views) == 1, [o.Name for o in doc.Objects]
v = views[0]
parts = [o for o in doc.Objects if o.TypeId != "Spreadsheet::Sheet" and o is not v and hasattr(o, "Shape")
         and "Grounded" in o.PropertiesList]
seen = {"proxy": repr(v.Proxy), "type": v.TypeId, "modes": list(v.StepModes), "distances": list(v.StepDistances),
        "directions": [tuple(d) for d in v.StepDirections], "parts": [p.Name for p in v.StepParts],
        "sizes": list(v.StepSizes), "solids": len(v.Shape.Solids), "volume": v.Shape.Volume,
        "visible": v.Visibility, "parts_visible": [p.Visibility for p in parts]}
v.touch()
doc.recompute()
seen.update(after_solids=len(v.Shape.Solids), after_volume=v.Shape.Volume, valid=v.isValid())
print("SEEN " + json.dumps(seen))
doc.save()
print("SESSION OK")
sys.exit(0)
"""


class ExplodedWithoutTheWorkbench(unittest.TestCase):
    """A document with an exploded view of two steps, opened, recomputed and saved in a FreeCAD
    without the workbench, then reopened with it: nothing lost, and shown sensibly there (the view
    drawn, the assembled parts hidden under it; not both on top of each other)."""

    def test_opened_and_saved_without_the_workbench_then_reopened(self):
        import json

        with tempfile.TemporaryDirectory() as tmp:
            holder = unittest.TestCase()
            make_blocks(holder)
            doc, asm = holder.doc, holder.asm
            b = [doc.getObject("Block%d" % k) for k in range(4)]
            view = exploded.new_exploded_view(asm, steps=[exploded.Step([b[3]], "Direction", 9, App.Vector(0, 0, 1)),
                                                          exploded.Step(b, "Radial", 6)])
            lists, offs = step_lists(view), [tuple(v) for v in view.Offsets]
            volume = view.Shape.Volume
            # Saved by freecadcmd: what a GUI shows is the objects' own Visibility.
            self.assertTrue(view.Visibility)
            self.assertFalse(any(p.Visibility for p in da.parts(asm) + da.joints(asm)))
            path = os.path.join(tmp, "exploded.FCStd")
            doc.saveAs(path)
            App.closeDocument(doc.Name)
            doc = App.openDocument(path)
            saved = {p.Name: p.Placement for p in da.parts(da.top_assemblies(doc)[0])}
            App.closeDocument(doc.Name)
            out = th.freecad_session(EXPLODED_WITHOUT_WORKBENCH, tmp, path)
            seen = json.loads(next(line for line in out.splitlines() if line.startswith("SEEN "))[5:])
            self.assertEqual(seen["proxy"], "None")  # the workbench's proxy could not be made there
            self.assertEqual((seen["modes"], seen["distances"], [tuple(d) for d in seen["directions"]],
                              seen["parts"], seen["sizes"]), lists)
            self.assertEqual((seen["solids"], seen["after_solids"]), (4, 4))
            self.assertAlmostEqual(seen["volume"], volume, delta=1e-9)
            self.assertAlmostEqual(seen["after_volume"], volume, delta=1e-9)  # a recompute there keeps it
            self.assertTrue(seen["valid"])
            self.assertEqual((seen["visible"], seen["parts_visible"]), (True, [False] * 4))
            doc = App.openDocument(path)
            try:
                asm = da.top_assemblies(doc)[0]
                view = exploded.views_of(asm)[0]  # its proxy back
                self.assertIsInstance(view.Proxy, exploded.ExplodedViewProxy)
                self.assertEqual(step_lists(view), lists)
                doc.recompute()
                for got, was in zip(view.Offsets, offs):
                    self.assertLess((got - App.Vector(*was)).Length, 1e-9)
                for p in da.parts(asm):  # as saved (a save keeps a rotation to about 1e-16)
                    self.assertTrue(th.same(p.Placement, saved[p.Name], 1e-12), p.Label)
                exploded.set_explosion(view, step=1, distance=3)
                self.assertEqual(list(view.StepDistances), [9.0, 3.0])
                exploded.show(view, False)
                self.assertFalse(view.Visibility)
                self.assertTrue(all(p.Visibility for p in da.parts(asm)))
            finally:
                App.closeDocument(doc.Name)


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
                               for c in (Hardware, PartNumbers, Walker, WalkerPartNumbers, Blocks, Steps, Migrated,
                                         ExplodedWithoutTheWorkbench, SavedExploded, FollowsTheAssembly,
                                         ExplodedWalker, Parade))
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
    failed = len(result.failures) + len(result.errors)
    print("%d passed, %d failed" % (result.testsRun - failed, failed))
    # freecadcmd would open the arguments after this script as documents.
    sys.exit(1 if failed else 0)
