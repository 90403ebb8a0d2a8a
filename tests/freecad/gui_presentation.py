"""The bill of materials and the exploded view in real FreeCAD under Xvfb (1280x900): their
commands in the Presentation toolbar (icons, tooltips, visible at 1280 px), the BOM panel (its
table, the sub-assemblies choice, Export CSV, OK writing the spreadsheet, shown), the Exploded view
panel (units, the slider's live preview, the assembly's parts hidden while the view is shown and
back, to the bit, when it is hidden; Cancel), with screenshots (bom-sheet.png, exploded.png) for
a person to look at. Quits FreeCAD itself; writes 0 to <out>/status-presentation when every test
passed."""
import csv
import os
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
os.environ["DISPCON_GUI_IMPORT_ONLY"] = "1"
os.environ["DISPCON_SUB_IMPORT_ONLY"] = "1"
os.environ["DISPCON_PRESENTATION_IMPORT_ONLY"] = "1"

import FreeCAD as App  # noqa: E402
import FreeCADGui as Gui  # noqa: E402
import gui_workbench as gw  # noqa: E402  (puts the workbench on sys.path)
from dispcon_fc.qt import QtCore, QtGui, QtWidgets  # noqa: E402
import test_presentation as tp  # noqa: E402
import test_subassembly as ts  # noqa: E402

COMMANDS = ("Dispcon_BillOfMaterials", "Dispcon_ExplodedView")


def coloured(icon, size=32):
    image = icon.pixmap(size, size).toImage()
    return sum(1 for x in range(0, size, 2) for y in range(0, size, 2) if QtGui.QColor(image.pixel(x, y)).alpha() > 0)


def grab(name):
    """The main window as it is (a spreadsheet's view is a widget: a grab reads it)."""
    gw.settle()
    path = os.path.join(gw.OUT, name + ".png")
    os.makedirs(gw.OUT, exist_ok=True)
    gw.mw().grab().save(path)
    return path


class Walker(unittest.TestCase):
    """The walker of test_subassembly (a frame, the leg of leg.FCStd placed four times), the frame
    of steel."""

    @classmethod
    def setUpClass(cls):
        import dispcon_fc.assembly as da

        cls.da = da
        cls.tmp = tempfile.TemporaryDirectory()
        leg = ts.make_leg(cls.tmp.name)
        cls.doc, cls.asm, cls.frame, cls.subs = ts.make_walker(cls.tmp.name, leg, rigid=False)
        ts.turn_cranks(cls.asm, cls.subs)
        cls.frame.addProperty("App::PropertyMap", "Material")
        cls.frame.Material = {"Name": "Steel", "Density": "7900 kg/m^3"}
        cls.frame.ViewObject.ShapeColor = (0.2, 0.4, 0.8, 0.0)
        cls.doc.UndoMode = 1
        cls.view = gw.activate(cls.doc)
        cls.view.viewIsometric()
        Gui.SendMsgToActiveView("ViewFit")
        gw.settle()

    @classmethod
    def tearDownClass(cls):
        if Gui.Control.activeDialog():
            Gui.Control.closeDialog()
        gw.close_documents()
        cls.tmp.cleanup()

    def tearDown(self):
        if Gui.Control.activeDialog():
            Gui.Control.closeDialog()
        gw.settle()
        # Back to the 3D view of the walker (a test may leave the spreadsheet's view in front).
        gw.activate(self.doc)
        gw.settle()

    def test_commands_in_their_toolbar_visible_at_1280(self):
        window = gw.mw()
        window.showNormal()
        window.setGeometry(0, 0, 1280, 900)
        gw.settle()
        for n in COMMANDS + gw.MAIN:
            a = gw.action(n)
            self.assertIsNotNone(a, n)
            tb = gw.toolbar_of(n)
            self.assertTrue(tb.isVisible(), n)
            w = tb.widgetForAction(a)
            self.assertTrue(w is not None and w.isVisible(), "%s is hidden behind a toolbar's >> at 1280 px" % n)
            right = w.mapTo(window, QtCore.QPoint(w.width(), 0)).x()
            self.assertLessEqual(right, window.width(), n)
        for n in COMMANDS:
            a = gw.action(n)
            self.assertEqual(gw.toolbar_of(n).objectName(), "Dispcon Presentation")
            self.assertGreater(coloured(a.icon()), 20, n)
            a.icon().pixmap(64, 64).save(os.path.join(gw.OUT, "icon-%s.png" % n[len("Dispcon_"):]))
            self.assertTrue(a.toolTip().strip())
        Gui.Selection.clearSelection()
        gw.settle()
        self.assertTrue(Gui.isCommandActive("Dispcon_BillOfMaterials"))
        self.assertTrue(Gui.isCommandActive("Dispcon_ExplodedView"))

    def test_bom_panel_choice_csv_and_the_sheet(self):
        from dispcon_fc import bom, panels
        from dispcon_fc.panels.bom import BomPanel

        legs = [p.Label for p in self.da.parts(self.subs[0].Assembly)]
        Gui.Selection.clearSelection()
        Gui.runCommand("Dispcon_BillOfMaterials")
        gw.settle()
        panel = panels.last_panel
        self.assertIsInstance(panel, BomPanel)
        table = panel.table
        # Indented by default: Frame, Leg x4, then the leg's four parts, one each.
        self.assertEqual(table.rowCount(), 2 + len(legs))
        self.assertEqual([table.item(r, 1).text() for r in range(table.rowCount())], ["Frame", "Leg"] + legs)
        q, pn, desc, mat, mass_col = (bom.COLUMNS.index(c) for c in ("Quantity", "Part number", "Description",
                                                                    "Material", "Mass (g)"))
        self.assertEqual(table.item(1, q).text(), "4")
        self.assertEqual(table.item(0, mat).text(), "Steel")
        mass = self.frame.Shape.Volume * 7900e-6  # g
        self.assertAlmostEqual(float(table.item(0, mass_col).text()), mass, delta=mass * 1e-5)
        self.assertEqual(table.item(1, mass_col).text(), "")  # the legs' parts have no material
        # The frame's part number and description typed in the table; the leg's cannot be (leg.FCStd's).
        self.assertTrue(table.item(0, pn).flags() & QtCore.Qt.ItemIsEditable)
        self.assertFalse(table.item(1, pn).flags() & QtCore.Qt.ItemIsEditable)
        self.assertIn("leg.FCStd", table.item(1, pn).toolTip())
        table.item(0, pn).setText("F-2024-01")
        gw.settle()
        table.item(0, desc).setText("Walker frame\nwelded")  # two lines: refused, put back
        gw.settle()
        self.assertIn("one line of text", panel.message.text())
        self.assertEqual(table.item(0, desc).text(), "")
        table.item(0, desc).setText("Walker frame, welded")
        gw.settle()
        self.assertEqual((table.item(0, pn).text(), table.item(0, desc).text()), ("F-2024-01", "Walker frame, welded"))
        self.assertEqual(self.frame.PartNumber, "")  # nothing written before OK
        panel.choice.setCurrentIndex(2)  # expanded
        gw.settle()
        self.assertEqual([(table.item(r, 1).text(), table.item(r, q).text()) for r in range(table.rowCount())],
                         [("Frame", "1")] + [(label, "4") for label in legs])
        self.assertEqual(table.item(0, pn).text(), "F-2024-01")  # kept across the choice
        path = os.path.join(self.tmp.name, "walker-bom.csv")
        panel.export_csv(path)
        with open(path, newline="", encoding="utf-8") as f:
            read = list(csv.reader(f))[1:]
        self.assertEqual([[r[1], r[q]] for r in read], [["Frame", "1"]] + [[l, "4"] for l in legs])
        self.assertEqual(read[0][pn:desc + 1], ["F-2024-01", "Walker frame, welded"])
        panel.choice.setCurrentIndex(1)  # back to indented, written so
        gw.settle()
        gw.shot("bom-panel", self.view)
        undo = self.doc.UndoCount
        panel.accept()
        gw.settle()
        self.assertEqual(self.doc.UndoCount, undo + 1)  # the part number and the sheet: one step
        self.assertEqual((self.frame.PartNumber, self.frame.Label2), ("F-2024-01", "Walker frame, welded"))
        sheet = bom.sheet_of(self.asm)
        self.assertEqual(tp.key_cells(tp.cells(sheet)[2]), ["'2", "Leg", "4"])
        self.assertEqual([c.lstrip("'") for c in tp.cells(sheet)[1][pn:desc + 1]], ["F-2024-01", "Walker frame, welded"])
        self.assertFalse(Gui.Control.activeDialog())
        # Shown as a designer opens it (double-click in the tree), looked at in bom-sheet.png.
        Gui.getDocument(self.doc.Name).setEdit(sheet.Name)
        gw.settle()
        gw.mw().findChild(QtWidgets.QMdiArea).activeSubWindow().showMaximized()
        path = grab("bom-sheet")
        self.assertGreater(os.path.getsize(path), 10000)
        Gui.getDocument(self.doc.Name).resetEdit()
        gw.settle()
        # Run again: the same sheet, no second one.
        Gui.runCommand("Dispcon_BillOfMaterials")
        gw.settle()
        panels.last_panel.accept()
        gw.settle()
        self.assertEqual([o for o in self.doc.Objects if o.TypeId == "Spreadsheet::Sheet"], [sheet])
        # Back to the 3D view.
        for w in gw.mw().findChild(QtWidgets.QMdiArea).subWindowList():
            if w.widget() is not None and "Spreadsheet" in type(w.widget()).__name__ or "BOM" in w.windowTitle():
                w.close()
        gw.settle()

    def test_exploded_panel_slider_hides_parts_and_toggles_back(self):
        from dispcon_fc import exploded, panels
        from dispcon_fc.panels.exploded import ExplodedPanel

        before = tp.placements(self.asm)
        drawn = self.da.placed_parts(self.asm) + self.da.joints(self.asm)
        self.assertTrue(all(o.ViewObject.Visibility for o in drawn))
        Gui.Selection.clearSelection()
        Gui.runCommand("Dispcon_ExplodedView")
        gw.settle()
        panel = panels.last_panel
        self.assertIsInstance(panel, ExplodedPanel)
        view = panel.view
        self.assertTrue(view.ViewObject.Visibility)
        self.assertFalse(any(o.ViewObject.Visibility for o in drawn), "the assembled parts still show")
        self.assertTrue(panel.distance.text().endswith("mm"), panel.distance.text())
        # The slider previews: at 3/10 of its travel, the farthest unit 0.3 x reach away.
        panel.slider.setValue(300)
        gw.settle()
        # (as the box shows it, to its decimals: what is drawn is what is read)
        want = float(panel.distance.property("rawValue"))
        self.assertAlmostEqual(want, panel.reach * 0.3, delta=0.01)
        self.assertEqual(list(view.StepDistances), [want])
        self.assertAlmostEqual(max(v.Length for v in view.Offsets), want, delta=1e-9)
        # Typed: 2 mm, the slider follows.
        panel.distance.setProperty("rawValue", 2.0)
        gw.settle()
        self.assertAlmostEqual(view.StepDistances[0], 2.0, delta=1e-12)
        self.assertEqual(panel.slider.value(), int(round(2.0 / panel.reach * 1000)))
        # Each part of a leg alone: the legs unticked, their parts ticked.
        tick(panel, lambda o: not self.da.is_sub_assembly(o))
        self.assertEqual(len(view.StepParts), 1 + 4 * 4)
        panel.distance.setProperty("rawValue", 4.0)  # far enough apart to see each part
        gw.settle()
        # Drawn in the parts' colours: the frame's (blue) on as many faces as it has, first.
        colours = view.ViewObject.DiffuseColor
        self.assertEqual(len(colours), len(view.Shape.Faces))
        n = len(self.frame.Shape.Faces)
        self.assertEqual(view.Parts[0], self.frame)
        self.assertEqual(colours[:n], [self.frame.ViewObject.ShapeColor] * n)
        self.assertNotIn(self.frame.ViewObject.ShapeColor, colours[n:])
        Gui.SendMsgToActiveView("ViewFit")
        gw.shot("exploded-panel", self.view)
        panel.accept()
        gw.settle()
        self.assertEqual(tp.placements(self.asm), before)
        self.assertTrue(view.ViewObject.Proxy.getIcon().endswith("Dispcon_ExplodedView.svg"))
        Gui.SendMsgToActiveView("ViewFit")
        gw.settle()
        path = gw.shot("exploded", self.view)
        self.assertGreater(os.path.getsize(path), 10000)
        # Hidden (Space in the tree): the assembled parts and markers again, every placement to the bit.
        view.ViewObject.Visibility = False
        gw.settle()
        self.assertTrue(all(o.ViewObject.Visibility for o in drawn))
        self.assertEqual(tp.placements(self.asm), before)
        gw.shot("exploded-hidden", self.view)
        # Shown again: the parts hidden again.
        view.ViewObject.Visibility = True
        gw.settle()
        self.assertFalse(any(o.ViewObject.Visibility for o in drawn))
        # Deleted while shown (the Delete key): the parts come back.
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(view)
        Gui.runCommand("Std_Delete")
        gw.settle()
        self.assertEqual(exploded.views_of(self.asm), [])
        self.assertTrue(all(o.ViewObject.Visibility for o in drawn))
        self.assertEqual(tp.placements(self.asm), before)

    def test_cancel_removes_a_new_view_and_shows_the_parts(self):
        from dispcon_fc import exploded
        from dispcon_fc.panels import exploded as ep

        for v in exploded.views_of(self.asm):
            self.doc.removeObject(v.Name)
        drawn = self.da.placed_parts(self.asm) + self.da.joints(self.asm)
        for o in drawn:
            o.ViewObject.Visibility = True
        count = len(self.doc.Objects)
        panel = ep.open_panel(self.asm)
        gw.settle()
        self.assertEqual(len(self.doc.Objects), count + 1)
        panel.slider.setValue(500)
        gw.settle()
        panel.reject()
        gw.settle()
        self.assertEqual(len(self.doc.Objects), count)
        self.assertEqual(exploded.views_of(self.asm), [])
        self.assertTrue(all(o.ViewObject.Visibility for o in drawn))


    def pixel_of(self, view, part):
        """A pixel of the 3D view where `view` (the exploded view) shows `part`'s copy, found by
        asking the view what is under points of the copy's faces; None when none shows."""
        from dispcon_fc import exploded

        piece = view.Shape.childShapes()[list(p.Name for p in view.Parts).index(part.Name)]
        for face in sorted(piece.Faces, key=lambda f: -f.Area):
            centre = face.CenterOfMass
            for v in [centre] + [centre + (vx.Point - centre) * 0.5 for vx in face.Vertexes]:
                x, y = (int(round(c)) for c in self.view.getPointOnScreen(v))
                info = self.view.getObjectInfo((x, y))
                if info and info.get("Object") == view.Name and \
                        exploded.part_at(view, info.get("Component")) == part:
                    return x, y
        return None

    def click(self, x, y):
        gw.mouse(self.view, "press", x, y)
        gw.mouse(self.view, "release", x, y)
        gw.settle()

    def test_a_steps_parts_picked_in_the_3d_view(self):
        """With the panel open, a click on a part's copy in the 3D view ticks it in the chosen step
        (a part of a leg: the leg, which moves as one), a second click unticks it; the view
        redraws at once."""
        from dispcon_fc import exploded
        from dispcon_fc.panels import exploded as ep

        for v in exploded.views_of(self.asm):
            exploded.show(v, False)
            self.doc.removeObject(v.Name)
        before = tp.placements(self.asm)
        panel = ep.open_panel(self.asm)
        gw.settle()
        view = panel.view
        Gui.Selection.clearSelection()
        panel.add_button.click()  # a step of no part yet: refused until it has one
        gw.settle()
        self.assertEqual(panel.current, 1)
        Gui.SendMsgToActiveView("ViewFit")
        gw.settle()
        ticked = lambda: [panel.parts.item(k).text().strip() for k in range(panel.parts.count())  # noqa: E731
                          if panel.parts.item(k).checkState() == QtCore.Qt.Checked]
        self.assertEqual(ticked(), [])
        first = {p.Name: App.Vector(v) for p, v in zip(view.Parts, view.Offsets)}
        at = self.pixel_of(view, self.frame)
        self.assertIsNotNone(at, "the frame's copy is nowhere on the screen")
        self.click(*at)
        self.assertEqual(ticked(), ["Frame"])
        # The frame is grounded: a view moves it like any part its step names (as FreeCAD 1.x's
        # exploded views move a grounded part picked for a move); its Placement never changes.
        self.assertTrue(self.frame.Grounded)
        distance = panel.steps[1].distance
        offsets = {p.Name: App.Vector(v) for p, v in zip(view.Parts, view.Offsets)}
        self.assertLess((offsets[self.frame.Name] - first[self.frame.Name] - App.Vector(0, 0, distance)).Length, 1e-9)
        self.assertEqual(Gui.Selection.getSelection(), [], "the pick left a selection behind")
        # A part inside leg 2: the leg, as one.
        coupler = next(p for p in self.da.instance_parts(self.subs[1]) if p.LinkedObject.Label == "Coupler")
        at2 = self.pixel_of(view, coupler)
        self.assertIsNotNone(at2, "leg 2's coupler's copy is nowhere on the screen")
        self.click(*at2)
        self.assertEqual(ticked(), ["Frame", self.subs[1].Label])
        offsets = {p.Name: App.Vector(v) for p, v in zip(view.Parts, view.Offsets)}
        for p in self.da.nested_parts(self.subs[1]):
            self.assertLess((offsets[p.Name] - first[p.Name] - App.Vector(0, 0, distance)).Length, 1e-9, p.Label)
        gw.shot("exploded-picked", self.view)
        # Picked again (where the frame's copy is drawn now): out of the step.
        at = self.pixel_of(view, self.frame)
        self.click(*at)
        self.assertEqual(ticked(), [self.subs[1].Label])
        panel.reject()
        gw.settle()
        self.assertEqual(tp.placements(self.asm), before)

    def test_exploded_steps_added_reordered_and_removed_in_the_panel(self):
        from dispcon_fc import exploded
        from dispcon_fc.panels import exploded as ep

        for v in exploded.views_of(self.asm):
            exploded.show(v, False)
            self.doc.removeObject(v.Name)
        before = tp.placements(self.asm)
        leg2 = self.subs[1]
        count, undo = len(self.doc.Objects), self.doc.UndoCount
        panel = ep.open_panel(self.asm)
        gw.settle()
        view = panel.view
        panel.distance.setProperty("rawValue", 3.0)
        gw.settle()
        one = {p.Name: App.Vector(v) for p, v in zip(view.Parts, view.Offsets)}
        # Add a step with leg 2 selected in the tree: it moves leg 2 (as one) along +Z.
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(leg2)
        panel.add_button.click()
        gw.settle()
        self.assertEqual(panel.step_list.count(), 2)
        self.assertEqual(panel.step_list.currentRow(), 1)
        self.assertEqual([panel.parts.item(k).text().strip() for k in range(panel.parts.count())
                          if panel.parts.item(k).checkState() == QtCore.Qt.Checked], ["Leg2"])
        panel.distance.setProperty("rawValue", 5.0)
        gw.settle()
        self.assertEqual(panel.step_list.item(1).text(), "2. Along a direction, 5 mm: 1 part")
        legs2 = {p.Name for p in self.da.nested_parts(leg2)}
        for p, v in zip(view.Parts, view.Offsets):
            want = one[p.Name] + (App.Vector(0, 0, 5) if p.Name in legs2 else App.Vector())
            self.assertLess((v - want).Length, 1e-9, p.Label)
        # Up: leg 2 lifted first, then everything away from the centre (from where leg 2 is drawn).
        panel.up_button.click()
        gw.settle()
        self.assertEqual(list(view.StepModes), ["Direction", "Radial"])
        self.assertEqual(panel.step_list.item(0).text(), "1. Along a direction, 5 mm: 1 part")
        self.assertFalse(panel.up_button.isEnabled())
        # A step with nothing selected: said in the panel, OK disabled, until it is removed.
        Gui.Selection.clearSelection()
        panel.add_button.click()
        gw.settle()
        self.assertEqual(panel.message.text(), "step 2 moves no part: choose the parts it moves")
        self.assertFalse(panel.ok_button().isEnabled())
        self.assertEqual(list(view.StepModes), ["Direction", "Radial"])  # the view as it was
        Gui.SendMsgToActiveView("ViewFit")
        gw.shot("exploded-steps-refused", self.view)
        panel.remove_button.click()
        gw.settle()
        self.assertTrue(panel.ok_button().isEnabled())
        self.assertEqual(panel.step_list.count(), 2)
        Gui.SendMsgToActiveView("ViewFit")
        path = gw.shot("exploded-steps", self.view)
        self.assertGreater(os.path.getsize(path), 10000)
        panel.accept()
        gw.settle()
        self.assertEqual((len(self.doc.Objects), self.doc.UndoCount), (count + 1, undo + 1))
        self.assertEqual(list(view.StepModes), ["Direction", "Radial"])
        self.assertEqual(tp.placements(self.asm), before)
        # Opened again: its two steps, the first chosen.
        panel = ep.open_panel(self.asm, view)
        gw.settle()
        self.assertEqual([panel.step_list.item(k).text()[:2] for k in range(2)], ["1.", "2."])
        self.assertEqual(panel.mode.itemData(panel.mode.currentIndex()), "Direction")
        panel.reject()
        gw.settle()
        self.assertEqual(list(view.StepModes), ["Direction", "Radial"])


def tick(panel, wanted):
    """Ticks in the panel's parts list the objects `wanted` says (the others unticked), unticking
    first so no step moves a part twice on the way."""
    by_name = {o.Name: o for o, _ in panel_choices(panel)}
    items = [panel.parts.item(k) for k in range(panel.parts.count())]
    for item in items:
        if not wanted(by_name[item.data(QtCore.Qt.UserRole)]):
            item.setCheckState(QtCore.Qt.Unchecked)
    for item in items:
        if wanted(by_name[item.data(QtCore.Qt.UserRole)]):
            item.setCheckState(QtCore.Qt.Checked)
    gw.settle()


def panel_choices(panel):
    from dispcon_fc import exploded

    return exploded.choices(panel.asm)


class Reopened(unittest.TestCase):
    def test_saved_while_exploded_reopens_with_its_view_and_toggles_back(self):
        import dispcon_fc.assembly as da
        from dispcon_fc import exploded

        tmp = tempfile.TemporaryDirectory()
        try:
            doc = App.newDocument("fourbar")
            asm = ts.th.fourbar(doc, tmp.name)[0]
            self.assertTrue(da.solve(asm).converged)
            assembled = os.path.join(tmp.name, "assembled.FCStd")
            doc.saveCopy(assembled)
            view = exploded.new_exploded_view(asm, distance=1.5)
            gw.settle()
            self.assertFalse(any(p.ViewObject.Visibility for p in da.parts(asm)))
            path = os.path.join(tmp.name, "exploded.FCStd")
            doc.saveAs(path)
            App.closeDocument(doc.Name)
            plain = App.openDocument(assembled)
            want = tp.placements(da.top_assemblies(plain)[0])
            App.closeDocument(plain.Name)
            doc = App.openDocument(path)
            gw.settle()
            asm = da.top_assemblies(doc)[0]
            view = exploded.views_of(asm)[0]
            self.assertIsInstance(view.ViewObject.Proxy, exploded.ViewProviderExplodedView)
            self.assertTrue(view.ViewObject.Visibility)
            self.assertFalse(any(p.ViewObject.Visibility for p in da.parts(asm)))  # as saved
            self.assertEqual(tp.placements(asm), want)
            view.ViewObject.Visibility = False
            gw.settle()
            self.assertTrue(all(o.ViewObject.Visibility for o in da.parts(asm) + da.joints(asm)))
            self.assertEqual(tp.placements(asm), want)
            App.closeDocument(doc.Name)
        finally:
            for name in list(App.listDocuments()):
                if name.startswith(("fourbar", "assembled", "exploded")):
                    App.closeDocument(name)
            tmp.cleanup()
            gw.settle()


# A FreeCAD GUI without the workbench (tp's bare session's environment, this display): opens the
# document, says what it shows, saves a screenshot of the main window with its 3D view, saves the
# document and quits.
BARE_GUI = """
import json, os, sys
import FreeCAD as App
import FreeCADGui as Gui
try:
    import dispcon_fc
    raise SystemExit("the workbench was importable: this session must not have it")
except ImportError:
    pass
from PySide import QtGui
path, out = os.environ["DISPCON_BARE_DOC"], os.environ["DISPCON_BARE_OUT"]
seen = {}
try:
    Gui.getMainWindow().setGeometry(0, 0, 1280, 900)
    doc = App.openDocument(path)
    Gui.updateGui()
    view = next(o for o in doc.Objects if getattr(o, "DispconType", "") == "ExplodedView")
    parts = [o for o in doc.Objects if "Grounded" in o.PropertiesList and o.TypeId != "App::DocumentObjectGroupPython"]
    joints = [o for o in doc.Objects if "JointType" in o.PropertiesList]
    seen = {"proxy": repr(view.Proxy), "shown": view.ViewObject.Visibility, "solids": len(view.Shape.Solids),
            "faces": len(view.Shape.Faces), "colours": len(view.ViewObject.DiffuseColor),
            "parts_shown": [p.ViewObject.Visibility for p in parts], "joints_shown": [j.ViewObject.Visibility for j in joints],
            "steps": list(view.StepModes)}
    v3d = Gui.ActiveDocument.ActiveView
    v3d.viewIsometric()
    v3d.fitAll()
    Gui.updateGui()
    v3d.saveImage(out, 1000, 700, "White")
    doc.save()
    seen["saved"] = True
except Exception as e:
    seen["error"] = repr(e)
with open(out + ".json", "w") as f:
    json.dump(seen, f)
os._exit(0)
"""


class WithoutTheWorkbench(unittest.TestCase):
    """A four-bar exploded in two steps, saved from this GUI while the view shows, opened in a
    FreeCAD GUI without the workbench (looked at: without-workbench.png), saved there, and
    reopened here: nothing lost, and the view, not the parts under it, drawn there."""

    def test_opened_in_a_gui_without_the_workbench(self):
        import json
        import subprocess

        import dispcon_fc.assembly as da
        from dispcon_fc import exploded

        tmp = tempfile.TemporaryDirectory()
        try:
            doc = App.newDocument("fourbar")
            asm, g, crank, coupler, rocker = ts.th.fourbar(doc, tmp.name)
            self.assertTrue(da.solve(asm).converged)
            view = exploded.new_exploded_view(asm, steps=[exploded.Step([coupler], "Direction", 1.5, App.Vector(0, 0, 1)),
                                                          exploded.Step([g, crank, coupler, rocker], "Radial", 2)])
            gw.settle()
            lists, offs = tp.step_lists(view), [tuple(v) for v in view.Offsets]
            placed = tp.placements(asm)
            path = os.path.join(tmp.name, "exploded.FCStd")
            doc.saveAs(path)
            App.closeDocument(doc.Name)
            gw.settle()
            home = os.path.join(tmp.name, "home")
            os.makedirs(home)
            out = os.path.join(gw.OUT, "without-workbench.png")
            macro = os.path.join(home, "bare.py")
            with open(macro, "w") as f:
                f.write(BARE_GUI)
            env = dict(ts.th.bare_env(home), DISPCON_BARE_DOC=path, DISPCON_BARE_OUT=out)
            subprocess.run(["freecad", macro], env=env, cwd=home, timeout=300,
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
            with open(out + ".json") as f:
                seen = json.load(f)
            self.assertNotIn("error", seen)
            self.assertEqual(seen["proxy"], "None")
            # Shown as saved: the exploded view, in its parts' colours. (FreeCAD 0.20 shows every
            # child of a Python group whose view provider it cannot make, whatever was saved: the
            # assembled parts under it too, as a plain Python group's children are there.)
            self.assertEqual((seen["shown"], seen["solids"], seen["steps"]), (True, 4, ["Direction", "Radial"]))
            self.assertEqual(seen["colours"], seen["faces"])
            self.assertEqual(seen["parts_shown"], [True] * 4)
            self.assertTrue(seen["saved"])
            self.assertGreater(os.path.getsize(out), 5000)
            doc = App.openDocument(path)
            gw.settle()
            asm = da.top_assemblies(doc)[0]
            view = exploded.views_of(asm)[0]  # its proxies back, the parts and markers under it hidden
            self.assertTrue(view.ViewObject.Visibility)
            self.assertFalse(any(o.ViewObject.Visibility for o in da.parts(asm) + da.joints(asm)))
            self.assertIsInstance(view.Proxy, exploded.ExplodedViewProxy)
            self.assertIsInstance(view.ViewObject.Proxy, exploded.ViewProviderExplodedView)
            self.assertEqual(tp.step_lists(view), lists)
            for p in da.parts(asm):  # a save writes a placement to about 1e-15 mm
                pl = App.Placement(App.Vector(*placed[p.Name][:3]), App.Rotation(*placed[p.Name][3:]))
                self.assertTrue(ts.th.same(p.Placement, pl, 1e-12), p.Label)
            doc.recompute()
            for got, was in zip(view.Offsets, offs):
                self.assertLess((got - App.Vector(*was)).Length, 1e-9)
            view.ViewObject.Visibility = False
            gw.settle()
            self.assertTrue(all(o.ViewObject.Visibility for o in da.parts(asm) + da.joints(asm)))
            App.closeDocument(doc.Name)
        finally:
            for name in list(App.listDocuments()):
                if name.startswith(("fourbar", "exploded")):
                    App.closeDocument(name)
            tmp.cleanup()
            gw.settle()


gw.run_in_gui([Walker, Reopened, WithoutTheWorkbench], "status-presentation")
