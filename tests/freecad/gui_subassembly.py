"""Sub-assemblies in real FreeCAD under Xvfb (1280x900): the Insert sub-assembly command in the
Assembly toolbar with its icon and tooltip, the tree icons of rigid and flexible instances, the
Rigid toggle in the property editor, a leg of a flexible walker dragged with the mouse while the
other legs stay, and a screenshot of the four legs (walker.png). Quits FreeCAD itself; writes 0 to
<out>/status-subassembly when every test passed."""
import os
import sys
import tempfile
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
os.environ["DISPCON_GUI_IMPORT_ONLY"] = "1"
os.environ["DISPCON_SUB_IMPORT_ONLY"] = "1"

import FreeCAD as App  # noqa: E402
import FreeCADGui as Gui  # noqa: E402
import gui_workbench as gw  # noqa: E402  (puts the workbench on sys.path)
from dispcon_fc.qt import QtCore, QtGui, QtWidgets  # noqa: E402
import test_subassembly as ts  # noqa: E402


def coloured(icon, size=32):
    image = icon.pixmap(size, size).toImage()
    return sum(1 for x in range(0, size, 2) for y in range(0, size, 2) if QtGui.QColor(image.pixel(x, y)).alpha() > 0)


class Walker(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        import dispcon_fc.assembly as da

        cls.da = da
        cls.tmp = tempfile.TemporaryDirectory()
        leg = ts.make_leg(cls.tmp.name)
        cls.doc, cls.asm, cls.frame, cls.subs = ts.make_walker(cls.tmp.name, leg, rigid=False)
        # Each leg's crank at its own angle: the four places move independently.
        ts.turn_cranks(cls.asm, cls.subs)
        cls.view = gw.activate(cls.doc)
        cls.view.viewTop()
        Gui.SendMsgToActiveView("ViewFit")
        gw.settle()

    @classmethod
    def tearDownClass(cls):
        gw.close_documents()
        cls.tmp.cleanup()

    def test_command_in_the_assembly_toolbar_with_icon_and_tooltip(self):
        a = gw.action("Dispcon_InsertSubAssembly")
        self.assertIsNotNone(a)
        self.assertEqual(gw.toolbar_of("Dispcon_InsertSubAssembly").objectName(), "Dispcon Assembly")
        self.assertGreater(coloured(a.icon()), 20)
        os.makedirs(gw.OUT, exist_ok=True)
        a.icon().pixmap(64, 64).save(os.path.join(gw.OUT, "icon-insert-sub-assembly.png"))
        self.assertIn("select the assembly to insert into", a.toolTip())
        self.assertIn(".FCStd", a.toolTip())
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(self.asm)
        gw.settle()
        self.assertTrue(a.isEnabled())

    def test_the_command_places_the_second_assembly_selected(self):
        import dispcon_fc.assembly as da

        doc = App.newDocument("insert")
        try:
            leg = ts.th.fourbar(doc, self.tmp.name)[0]
            top = da.create_assembly(doc, "Top")
            Gui.Selection.clearSelection()
            Gui.Selection.addSelection(top)
            Gui.Selection.addSelection(leg)
            Gui.runCommand("Dispcon_InsertSubAssembly")
            gw.settle()
            subs = da.sub_assemblies(top)
            self.assertEqual(len(subs), 1)
            self.assertTrue(subs[0].Rigid)
            self.assertEqual(subs[0].Assembly, leg)
            self.assertEqual(sorted(p.LinkedObject.Name for p in da.instance_parts(subs[0])),
                             sorted(p.Name for p in da.parts(leg)))
            self.assertIsNotNone(subs[0].ViewObject.Proxy)
            # With no part of its own yet, Top can still join the leg's parts and be solved.
            Gui.Selection.clearSelection()
            Gui.Selection.addSelection(top)
            gw.settle()
            self.assertTrue(gw.action("Dispcon_JointRevolute").isEnabled())
            self.assertTrue(gw.action("Dispcon_Solve").isEnabled())
        finally:
            Gui.Selection.clearSelection()
            App.closeDocument(doc.Name)
            gw.activate(self.doc)

    def test_tree_icons_and_the_rigid_toggle(self):
        from dispcon_fc import viewproviders

        sub = self.subs[3]
        proxy = sub.ViewObject.Proxy
        self.assertIsInstance(proxy, viewproviders.ViewProviderSubAssembly)
        self.assertTrue(proxy.getIcon().endswith("Dispcon_SubAssemblyFlexible.svg"))
        self.assertGreater(coloured(QtGui.QIcon(proxy.getIcon())), 20)
        QtGui.QIcon(proxy.getIcon()).pixmap(64, 64).save(os.path.join(gw.OUT, "icon-sub-assembly-flexible.png"))
        # Rigid is a checkbox of the property editor (a visible, editable bool).
        self.assertEqual(sub.getTypeIdOfProperty("Rigid"), "App::PropertyBool")
        self.assertEqual(sub.getEditorMode("Rigid"), [])
        self.assertIs(rigid_row_editable(sub), True)  # its row shown on the Data tab, editable
        sub.Rigid = True
        self.assertTrue(proxy.getIcon().endswith("Dispcon_SubAssembly.svg"))
        QtGui.QIcon(proxy.getIcon()).pixmap(64, 64).save(os.path.join(gw.OUT, "icon-sub-assembly-rigid.png"))
        sub.Rigid = False
        Gui.Selection.clearSelection()

    def test_drag_a_leg_with_the_mouse_and_screenshot(self):
        from dispcon_fc import dragging

        da = self.da
        leg2 = self.subs[1]
        coupler, crank, hip = ts.part(leg2, "Coupler"), ts.part(leg2, "Crank"), ts.part(leg2, "Hip")
        others = ts.poses(self.subs[:1] + self.subs[2:])
        Gui.runCommand("Dispcon_Drag", 1)
        mode = dragging._active
        self.assertIsNotNone(mode)
        try:
            x0, y0 = (int(v) for v in self.view.getPointOnScreen(coupler.Placement.multVec(App.Vector(1.5, 0, 0.1))))
            info = self.view.getObjectInfo((x0, y0))
            self.assertTrue(info and info["Object"] == coupler.Name, info)
            before = ts.angle_in(crank, hip)
            gw.mouse(self.view, "press", x0, y0)
            self.assertIsNotNone(mode.drag, "pressing on leg 2's coupler did not start a drag")
            for k in range(1, 21):
                gw.mouse(self.view, "move", x0 + 2 * k, y0 - 2 * k)
                Gui.updateGui()
            gw.mouse(self.view, "release", x0 + 40, y0 - 40)
        finally:
            Gui.runCommand("Dispcon_Drag", 0)
        self.assertGreater(abs(ts.angle_in(crank, hip) - before), 0.02, "leg 2's crank did not follow")
        for n, pl in ts.poses(self.subs[:1] + self.subs[2:]).items():
            self.assertTrue(ts.th.same(pl, others[n], 1e-12), "%s moved with leg 2" % n)
        for gap, tilt, label in ts.gaps(self.asm):
            self.assertLess(gap, 1e-9, label)
        self.assertEqual(da.check(self.asm)["dof"], 4)
        # Leg 2 selected: the tree shows the instances, the property editor its Rigid toggle.
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(leg2)
        Gui.SendMsgToActiveView("ViewFit")
        path = gw.shot("walker", self.view)
        Gui.Selection.clearSelection()
        self.assertTrue(os.path.getsize(path) > 10000)


class ParadeDocument(unittest.TestCase):
    """walker.FCStd (four legs of leg.FCStd, flexible) placed twice on a track, flexible, in a
    document named NAME shown in its 3D view (isometric, fit)."""

    NAME = "parade"

    @classmethod
    def setUpClass(cls):
        os.environ["DISPCON_NESTED_IMPORT_ONLY"] = "1"
        import test_nested as tn

        cls.tn = tn
        cls.tmp = tempfile.TemporaryDirectory()
        leg, walker, wdoc = tn.make_walker_file(cls.tmp.name)
        App.closeDocument(wdoc.Name)
        cls.doc, cls.asm, cls.track, cls.walks = tn.make_parade(cls.tmp.name, walker, rigid=False, name=cls.NAME)
        cls.doc.UndoMode = 1
        cls.view = gw.activate(cls.doc)
        cls.view.viewIsometric()
        Gui.SendMsgToActiveView("ViewFit")
        gw.settle()

    @classmethod
    def tearDownClass(cls):
        gw.close_documents()
        cls.tmp.cleanup()


class Parade(ParadeDocument):
    """Nested sub-assemblies: the tree shows each walker's legs inside it, a nested leg's coupler
    dragged with the mouse, a screenshot (parade.png)."""

    def tree_item(self, label):
        for tree in gw.mw().findChildren(QtWidgets.QTreeWidget):
            items = tree.findItems(label, QtCore.Qt.MatchExactly | QtCore.Qt.MatchRecursive, 0)
            if items:
                return items[0]
        return None

    def test_the_tree_nests_and_a_nested_leg_drags_with_the_mouse(self):
        import dispcon_fc.assembly as da
        from dispcon_fc import dragging, viewproviders

        tn = self.tn
        walk2 = self.walks[1]
        leg3 = tn.named(walk2, "Leg3")
        # The tree: Walk2.Leg3 under Walk2, with the flexible instance's icon; its links under it.
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(tn.named(leg3, "Coupler"))
        gw.settle()
        item = self.tree_item("Walk2.Leg3")
        self.assertIsNotNone(item)
        parent = item.parent()
        grandparent = parent.parent()
        children = [item.child(k) for k in range(item.childCount())]
        self.assertEqual((parent.text(0), grandparent.text(0)), ("Walk2", "Parade"))
        self.assertIn("Walk2.Leg3.Coupler", [c.text(0) for c in children])
        self.assertIsInstance(leg3.ViewObject.Proxy, viewproviders.ViewProviderSubAssembly)
        self.assertTrue(leg3.ViewObject.Proxy.getIcon().endswith("Dispcon_SubAssemblyFlexible.svg"))
        self.assertEqual(leg3.getEditorMode("Rigid"), [])  # each place's own, at every level
        coupler, crank, hip, rocker = (tn.named(leg3, p) for p in ("Coupler", "Crank", "Hip", "Rocker"))
        others = {o.Name: o.Placement for o in da.placed_parts(self.asm) if o not in da.instance_parts(leg3)}
        self.view.viewTop()
        Gui.SendMsgToActiveView("ViewFit")
        gw.settle()
        Gui.Selection.clearSelection()
        Gui.runCommand("Dispcon_Drag", 1)
        mode = dragging._active
        self.assertIsNotNone(mode)
        try:
            x0, y0 = (int(v) for v in self.view.getPointOnScreen(coupler.Placement.multVec(App.Vector(1.5, 0, 0.1))))
            info = self.view.getObjectInfo((x0, y0))
            self.assertTrue(info and info["Object"] == coupler.Name, info)
            before = ts.angle_in(crank, hip)
            gw.mouse(self.view, "press", x0, y0)
            self.assertIsNotNone(mode.drag, "pressing on Walk2.Leg3's coupler did not start a drag")
            for k in range(1, 16):
                gw.mouse(self.view, "move", x0 + k, y0 - k)
                Gui.updateGui()
            gw.mouse(self.view, "release", x0 + 15, y0 - 15)
        finally:
            Gui.runCommand("Dispcon_Drag", 0)
        self.assertGreater(abs(ts.angle_in(crank, hip) - before), 0.01, "Walk2.Leg3's crank did not follow")
        err = ts.math.remainder(ts.angle_in(rocker, hip) - ts.th.freudenstein(ts.angle_in(crank, hip)), 2 * ts.math.pi)
        self.assertLess(abs(err), 1e-8)
        for o in da.placed_parts(self.asm):
            if o.Name in others and o != hip:
                self.assertTrue(ts.th.same(o.Placement, others[o.Name], 1e-9), "%s moved with Walk2.Leg3" % o.Label)
        for gap, tilt, label in ts.gaps(self.asm):
            self.assertLess(gap, 1e-9, label)
        self.assertEqual(da.check(self.asm)["dof"], 8)
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(leg3)
        self.view.viewIsometric()
        Gui.SendMsgToActiveView("ViewFit")
        path = gw.shot("parade", self.view)
        Gui.Selection.clearSelection()
        self.assertTrue(os.path.getsize(path) > 10000)


class Highlight(ParadeDocument):
    """A sub-assembly instance selected in the tree (a group, which FreeCAD draws nothing of) has
    its parts drawn in the selection's green in the 3D view: a walker, and a leg nested in one."""

    NAME = "highlight"

    def green(self):
        """The rendered view's selection-green pixels: (count, their box (x0, y0, x1, y1))."""
        import numpy

        image = gw.rendered(self.view, os.path.join(gw.OUT, "_highlight.png"))
        mask = (image[:, :, 1] > 150) & (image[:, :, 0] < 110) & (image[:, :, 2] < 110)
        ys, xs = numpy.nonzero(mask)
        return int(mask.sum()), ((int(xs.min()), int(ys.min()), int(xs.max()), int(ys.max())) if len(xs) else None)

    def screen(self, links):
        """The pixel (x, y from the top) of each link's placement, as rendered()."""
        region = self.view.getViewer().getSoRenderManager().getViewportRegion()
        height = region.getViewportSizePixels()[1]
        return [(p[0], height - 1 - p[1]) for p in
                (self.view.getPointOnScreen(link.Placement.Base) for link in links)]

    def test_a_selected_instance_is_drawn_highlighted_at_any_depth(self):
        from dispcon_fc import objects, viewproviders

        by_label = {o.Label: o for o in self.doc.Objects}
        Gui.Selection.clearSelection()
        gw.settle()
        self.assertEqual(self.green()[0], 0, "green before anything is selected")
        for label in ("Walk2.Leg3", "Walk1"):
            inst = by_label[label]
            links = objects.nested_parts(inst)
            Gui.Selection.clearSelection()
            Gui.Selection.addSelection(inst)
            gw.settle()
            self.assertEqual(viewproviders.highlighted(self.doc), ([inst.Name], {p.Name for p in links}))
            count, box = self.green()
            self.assertGreater(count, 200, "%s selected: its parts are not highlighted" % label)
            gw.shot("highlight-%s" % label.replace(".", "-"))
            # Where its parts are, not elsewhere: every link's origin inside the green's box (a few
            # pixels of slack), and the box no larger than the links' spread and a part's size.
            pts = self.screen(links)
            for x, y in pts:
                self.assertTrue(box[0] - 4 <= x <= box[2] + 4 and box[1] - 4 <= y <= box[3] + 4,
                                "%s: a part at (%d, %d) outside the highlight %s" % (label, x, y, box))
            others = [p for p in objects.placed_parts(self.asm) if p not in links]
            outside = [(x, y) for x, y in self.screen(others)
                       if not (box[0] <= x <= box[2] and box[1] <= y <= box[3])]
            self.assertTrue(outside, "%s: the highlight covers every part of the parade" % label)
        # Another part selected, then nothing: no highlight left.
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(self.track)
        gw.settle()
        self.assertEqual(viewproviders.highlighted(self.doc), ([], set()))
        Gui.Selection.clearSelection()
        gw.settle()
        self.assertEqual(self.green()[0], 0, "green left after the selection was cleared")


def rigid_row_editable(obj):
    """Whether the property editor shows obj's Rigid as a value to edit: its row found by name on
    the Data tab once obj is selected (the editor fills its rows from a timer; None when it is not
    shown), and its editor mode (FreeCAD's editor reads it to make the row read only)."""
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(obj)
    # The property editor opens on the tab FreeCAD last showed (saved in its settings, so another
    # test or session can leave it on View): Rigid lives on the Data tab.
    for tabs in gw.mw().findChildren(QtWidgets.QTabWidget):
        names = [tabs.tabText(i) for i in range(tabs.count())]
        if "Data" in names and "View" in names:
            tabs.setCurrentIndex(names.index("Data"))
    deadline = time.monotonic() + 5
    while time.monotonic() < deadline:
        gw.settle()
        time.sleep(0.05)
        for tree in gw.mw().findChildren(QtWidgets.QTreeView):
            model = tree.model()
            if model is None or type(tree).__name__ == "TreeWidget":
                continue
            stack = [model.index(r, 0) for r in range(model.rowCount())]
            while stack:
                index = stack.pop()
                if model.data(index) == "Rigid":
                    return obj.getEditorMode("Rigid") == []
                stack += [model.index(r, 0, index) for r in range(model.rowCount(index))]
    return None


class PerPlace(ParadeDocument):
    """The parade's walkers, flexible: leg 2 made rigid in Walk1 only, through its Rigid in the
    property editor (editable there, read only inside a rigid walker), its icon in the tree, the
    degrees of freedom counted from leg.FCStd's (7), a screenshot (parade-per-place.png)."""

    NAME = "perplace"

    def test_a_leg_rigid_in_one_walker_only(self):
        import dispcon_fc.assembly as da

        tn = self.tn
        w1leg2, w2leg2 = tn.named(self.walks[0], "Leg2"), tn.named(self.walks[1], "Leg2")
        self.assertIs(rigid_row_editable(w1leg2), True)
        # What the property editor's checkbox does: the property set, in its own undo step.
        self.doc.openTransaction("Rigid")
        w1leg2.Rigid = True
        self.doc.commitTransaction()
        gw.settle()
        self.assertTrue(w1leg2.ViewObject.Proxy.getIcon().endswith("Dispcon_SubAssembly.svg"))
        self.assertTrue(w2leg2.ViewObject.Proxy.getIcon().endswith("Dispcon_SubAssemblyFlexible.svg"))
        leg_dof = da.check(da.top_assemblies(App.getDocument("leg"))[0])["dof"]
        c = da.check(self.asm)
        self.assertEqual(c["dof"], 7 * leg_dof, c["message"])
        self.assertEqual(c["part_dof"]["Walk1.Leg2"], 0)
        self.assertTrue(da.solve(self.asm).converged)
        for gap, tilt, label in ts.gaps(self.asm):
            self.assertLess(gap, 1e-9, label)
        # Walk1 made rigid: inside it, the legs' Rigid read only (walker.FCStd's as it is).
        da.set_rigid(self.walks[0], True)
        gw.settle()
        self.assertIs(rigid_row_editable(w1leg2), False)
        self.assertEqual(da.check(self.asm)["dof"], 4 * leg_dof)
        self.doc.undo()
        gw.settle()
        self.assertFalse(self.walks[0].Rigid)
        self.assertIs(rigid_row_editable(w1leg2), True)
        # The tree shows both places' icons; Walk1.Leg2 selected, its Rigid ticked in the editor.
        for w in self.walks:
            Gui.Selection.addSelection(tn.named(w, "Leg2.Coupler"))
        gw.settle()
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(w1leg2)
        gw.settle()
        path = gw.shot("parade-per-place", self.view)
        Gui.Selection.clearSelection()
        self.assertGreater(os.path.getsize(path), 10000)


gw.run_in_gui([c for c in (Walker, Parade, Highlight, PerPlace)
               if not os.environ.get("DISPCON_GUI_ONLY") or os.environ["DISPCON_GUI_ONLY"] in c.__name__], "status-subassembly")
