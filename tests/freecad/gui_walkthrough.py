"""docs/workbench.md's walkthrough as a designer does it, in real FreeCAD under Xvfb (1280x900):
every reference picked by Coin3D mouse events (a move, then a press and a release) at a pixel
where the 3D view draws that edge or face (the view asked what is under the pixel,
getObjectInfo), the view turned when the edge is hidden (a pin's bottom circle seen from below);
values typed into the panels' quantity boxes key by key with their units; Enter, and the undo
and redo keys in the 3D view (through the X server by xdotool when it is installed); a mouse
drag in drag mode; save, close and reopen. Each test class opens and closes its own documents;
screenshots go to DISPCON_GUI_OUT. Quits FreeCAD itself; writes 0 to <out>/status-walkthrough
when every test passed."""
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
os.environ["DISPCON_GUI_IMPORT_ONLY"] = "1"
import gui_workbench as gw  # noqa: E402  (its helpers and its set-up)

import FreeCAD as App  # noqa: E402
import FreeCADGui as Gui  # noqa: E402
from dispcon_fc.qt import QtCore, QtGui, QtWidgets  # noqa: E402

PARTS = os.path.join(REPO, "samples", "freecad", "parts")
TURNS = (None, "viewTop", "viewIsometric", "viewBottom", "viewFront", "viewRear")


def pixel_of(view, obj, sub):
    """A pixel (Coin3D's, from the bottom left) where the view draws `obj`'s element `sub`
    nearest under the cursor, as FreeCAD's getObjectInfo says; None when it is hidden."""
    element = obj.Shape.getElement(sub)
    for f in (0.3, 0.6, 0.8, 0.1, 0.45, 0.9):
        if hasattr(element, "FirstParameter"):
            p = element.valueAt(element.FirstParameter + f * (element.LastParameter - element.FirstParameter))
        else:
            u0, u1, v0, v1 = element.ParameterRange
            p = element.valueAt(u0 + f * (u1 - u0), v0 + (1 - f) * (v1 - v0))
        x, y = view.getPointOnScreen(p)
        for dx, dy in ((0, 0), (1, 0), (-1, 0), (0, 1), (0, -1), (2, 0), (-2, 0), (0, 2), (0, -2)):
            info = view.getObjectInfo((x + dx, y + dy))
            if info and info.get("Object") == obj.Name and info.get("Component") == sub:
                return x + dx, y + dy
    return None


def click(view, x, y):
    """The cursor moved to (x, y), the left button pressed and released there."""
    gw.mouse(view, "move", x, y)
    gw.settle()
    gw.mouse(view, "press", x, y)
    gw.mouse(view, "release", x, y)
    gw.settle()


def pick(view, obj, sub):
    """Clicks `obj`'s element `sub` where the view draws it, turning the view (top, isometric,
    below, front, rear) until it shows; returns the pixel."""
    for turn in TURNS:
        if turn:
            getattr(view, turn)()
            Gui.SendMsgToActiveView("ViewFit")
            gw.settle()
        at = pixel_of(view, obj, sub)
        if at is not None:
            click(view, *at)
            return at
    raise AssertionError("%s's %s is drawn nowhere the view can turn to" % (obj.Label, sub))


def key(widget, k, text="", modifiers=QtCore.Qt.NoModifier):
    """A key pressed and released on `widget` (released only if the press left it alive: Enter
    closes a task panel and deletes its fields)."""
    from dispcon_fc.qt import is_alive

    for kind in (QtCore.QEvent.KeyPress, QtCore.QEvent.KeyRelease):
        if is_alive(widget):
            QtWidgets.QApplication.sendEvent(widget, QtGui.QKeyEvent(kind, k, modifiers, text))


def type_into(box, text, enter=False):
    """`text` typed key by key into a quantity box (or a line edit), what was there selected
    first (Ctrl+A), as a person types; Enter at the end when asked."""
    edit = box.lineEdit() if hasattr(box, "lineEdit") else box
    edit.setFocus()
    key(edit, QtCore.Qt.Key_A, "", QtCore.Qt.ControlModifier)
    for ch in text:
        code = ord(ch.upper()) if ch.isalnum() else QtCore.Qt.Key_unknown
        key(edit, QtCore.Qt.Key(code), ch)
    gw.settle()
    if enter:
        key(edit, QtCore.Qt.Key_Return)
        gw.settle()
        gw.settle()


XDOTOOL = shutil.which("xdotool")


def x_keys(widget, keys):
    """`keys` (xdotool's names: ctrl+z) pressed on the X server with `widget` focused: a real
    keyboard's events, which go through Qt's shortcuts (a QKeyEvent sent to a widget does not)."""
    window = widget.window()
    subprocess.run([XDOTOOL, "windowfocus", "--sync", str(int(window.winId()))], check=False)
    widget.setFocus()
    gw.settle()
    time.sleep(0.6)  # FreeCAD enables Undo and Redo on a timer after each change
    gw.settle()
    subprocess.run([XDOTOOL, "key", keys], check=True)
    end = time.time() + 0.5
    while time.time() < end:
        gw.settle()
        time.sleep(0.02)


def view_widget(view):
    """The Quarter widget drawing `view` (its keyboard focus is the 3D view's)."""
    sub = gw.mw().findChild(QtWidgets.QMdiArea).activeSubWindow()
    return sub.findChildren(QtWidgets.QGraphicsView)[0]


def centres_meet(j):
    """The two picked circles of revolute `j` on one axis at one point (their centres and
    axes, where the parts are now), within its assembly's tolerance (the largest violation
    accepted, mm)."""
    from dispcon_fc import geometry

    tol = next(p for p in j.InList if j in getattr(p, "Group", [])).Tolerance
    f1 = geometry.feature(j.Reference1[0], j.Reference1[1][0])
    f2 = geometry.feature(j.Reference2[0], j.Reference2[1][0])
    return (f1.point - f2.point).Length <= tol and f1.axis.cross(f2.axis).Length <= tol


class FourBarFromScratch(unittest.TestCase):
    """The walkthrough's four-bar: parts imported through the command, the plate grounded after
    a click on it, four revolutes picked edge by edge in the 3D view (the cursor resting on each
    edge first, so the marker to come is drawn there when the click comes: it took the click,
    which selected nothing, on the crank's pin seen isometric, until markers were made
    unpickable), typed limits, Enter, a mouse drag, the undo keys, save, close and reopen."""

    def setUp(self):
        gw.close_dialog()
        self.doc = App.newDocument("WalkthroughFourBar")
        self.tmp = tempfile.mkdtemp()

    def tearDown(self):
        from dispcon_fc import dragging

        gw.close_dialog()
        dragging.stop()
        gw.close_documents()
        shutil.rmtree(self.tmp, ignore_errors=True)

    def import_part(self, name):
        """Import part, its file dialog answered with the file (as scripts/walkthrough.py does)."""
        dialog = QtWidgets.QFileDialog.getOpenFileName
        QtWidgets.QFileDialog.getOpenFileName = staticmethod(lambda *a, **k: (os.path.join(PARTS, name), ""))
        try:
            gw.action("Dispcon_ImportPart").trigger()
        finally:
            QtWidgets.QFileDialog.getOpenFileName = dialog
        gw.settle()
        return self.doc.Objects[-1]

    def test_the_four_bar_built_by_picks_typed_and_reopened(self):
        from dispcon_fc import dragging, objects
        from dispcon_fc.panels import joint as jp
        import parts

        gw.action("Dispcon_CreateAssembly").trigger()
        asm = [o for o in self.doc.Objects if objects.is_assembly(o)][0]
        made = [self.import_part(n) for n in ("ground-3.step", "link-1.step", "link-3.step", "link-2.5.step")]
        self.assertEqual([o.Label for o in made], ["ground-3", "link-1", "link-3", "link-2.5"])
        ground, crank, coupler, rocker = made
        for obj, label in zip(made, ("Ground", "Crank", "Coupler", "Rocker")):
            obj.Label = label
        crank.Placement = App.Placement(App.Vector(-0.6, -1.2, 0.15), App.Rotation(App.Vector(0, 0, 1), 40))
        coupler.Placement = App.Placement(App.Vector(0.8, 1.4, 0.2), App.Rotation(App.Vector(0, 0, 1), -5))
        rocker.Placement = App.Placement(App.Vector(4.2, -0.4, 0.1), App.Rotation(App.Vector(0, 0, 1), 80))
        view = Gui.getDocument(self.doc.Name).ActiveView
        view.viewTop()
        Gui.SendMsgToActiveView("ViewFit")
        gw.settle()
        # The plate selected by a click on its top face, then Ground.
        top = max((k for k, f in enumerate(ground.Shape.Faces) if f.normalAt(0, 0).z > 0.5),
                  key=lambda k: ground.Shape.Faces[k].Area)
        Gui.Selection.clearSelection()
        pick(view, ground, "Face%d" % (top + 1))
        self.assertEqual([s.Object for s in Gui.Selection.getSelectionEx()], [ground])
        gw.settle()
        gw.action("Dispcon_Ground").trigger()
        self.assertTrue(ground.Grounded)
        Gui.Selection.clearSelection()
        gw.shot("walkthrough-parts")

        def edge(obj, x, top):
            return (obj, parts.circle_edge(obj.Shape, App.Vector(x, 0, 0.1 if top else 0.0)))

        pairs = (("Ground-Crank", edge(ground, 0, True), edge(crank, 0, False)),
                 ("Crank-Coupler", edge(crank, 1, True), edge(coupler, 0, False)),
                 ("Coupler-Rocker", edge(coupler, 3, False), edge(rocker, 2.5, True)),
                 ("Rocker-Ground", edge(ground, 3, True), edge(rocker, 0, False)))
        joints = []
        for label, r1, r2 in pairs:
            Gui.Selection.clearSelection()
            gw.action("Dispcon_JointRevolute").trigger()
            gw.settle()
            panel = jp.current()
            pick(view, *r1)
            self.assertEqual([(o.Name, s) for o, s in panel.refs], [(r1[0].Name, r1[1])], label)
            pick(view, *r2)
            gw.settle()
            self.assertIsNotNone(panel.joint, "%s: no joint after the second pick" % label)
            self.assertTrue(centres_meet(panel.joint), "%s: the parts did not snap (%s)" % (label, panel.message.text()))
            if label == "Ground-Crank":
                gw.shot("walkthrough-revolute")
            panel.joint.Label = label
            joints.append(panel.joint)
            panel.ok_button().click()
            gw.settle()
        self.assertEqual(len(objects.joints(asm)), 4)
        for j in joints:
            self.assertTrue(centres_meet(j), j.Label)
        # Typed with units: the crank's turn limited to -0.5 rad .. 150 deg; Enter is OK.
        joints[0].ViewObject.Proxy.doubleClicked(joints[0].ViewObject)
        gw.settle()
        panel = jp.current()
        panel.has_rotation.click()
        type_into(panel.rot_min, "-0.5 rad")
        type_into(panel.rot_max, "150 deg")
        self.assertTrue(panel.ok_button().isEnabled(), panel.message.text())
        type_into(panel.rot_max, "", enter=True)  # Enter in a field of the task panel: OK
        self.assertTrue(panel.closed, "Enter did not close the panel")
        self.assertAlmostEqual(joints[0].RotationMin.getValueAs("deg").Value, -math.degrees(0.5), places=9)
        self.assertAlmostEqual(joints[0].RotationMax.getValueAs("deg").Value, 150.0, places=9)
        # Drag mode: press on the coupler, move, release: the crank turns, every joint holds.
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(asm)
        gw.action("Dispcon_Drag").trigger()
        gw.settle()
        before = {o.Name: o.Placement for o in made}
        at = pixel_of(view, coupler, "Face%d" % (1 + max(range(len(coupler.Shape.Faces)),
                                                           key=lambda k: coupler.Shape.Faces[k].Area
                                                           if coupler.Shape.Faces[k].normalAt(0, 0).z > 0.5 else 0)))
        if at is None:
            view.viewTop()
            Gui.SendMsgToActiveView("ViewFit")
            gw.settle()
            x, y = view.getPointOnScreen(coupler.Placement.multVec(App.Vector(1.5, 0, 0.1)))
            at = (x, y)
        x0, y0 = at
        gw.mouse(view, "press", x0, y0)
        for k in range(1, 21):
            gw.mouse(view, "move", x0 - 2 * k, y0 - 2 * k)
            gw.settle()
        gw.mouse(view, "release", x0 - 40, y0 - 40)
        gw.settle()
        dragging.stop()
        turned = crank.Placement.Rotation.multiply(before[crank.Name].Rotation.inverted()).Angle
        self.assertGreater(turned, 0.01, "the crank did not follow the drag")
        for j in joints:
            self.assertTrue(centres_meet(j), "%s broken by the drag" % j.Label)
        self.assertEqual(self.doc.UndoNames[0], "Drag Coupler")
        dragged = {o.Name: o.Placement for o in made}
        gw.shot("walkthrough-dragged")
        # Ctrl+Z in the 3D view takes the drag back; Ctrl+Shift+Z (FreeCAD's redo key on Linux:
        # Qt's QKeySequence::Redo; Ctrl+Y is not bound) does it again.
        if XDOTOOL:
            x_keys(view_widget(view), "ctrl+z")
            self.assertTrue(gw.same(crank.Placement, before[crank.Name], 1e-12), "Ctrl+Z did not undo the drag")
            x_keys(view_widget(view), "ctrl+shift+z")
            self.assertTrue(gw.same(crank.Placement, dragged[crank.Name], 1e-12), "Ctrl+Shift+Z did not redo it")
        # Saved, closed and reopened: every joint with its references and limits, the parts
        # where they were, and a Solve that moves nothing.
        path = os.path.join(self.tmp, "fourbar.FCStd")
        self.doc.saveAs(path)
        refs = {j.Label: (j.Reference1[0].Name, j.Reference1[1], j.Reference2[0].Name, j.Reference2[1])
                for j in joints}
        crank_joint = joints[0].Name
        App.closeDocument(self.doc.Name)
        gw.settle()
        self.doc = App.openDocument(path)
        gw.settle()
        asm = [o for o in self.doc.Objects if objects.is_assembly(o)][0]
        again = {j.Label: (j.Reference1[0].Name, j.Reference1[1], j.Reference2[0].Name, j.Reference2[1])
                 for j in objects.joints(asm)}
        self.assertEqual(again, refs)
        for name, placement in dragged.items():
            self.assertTrue(gw.same(self.doc.getObject(name).Placement, placement, 1e-12), name)
        j1 = self.doc.getObject(crank_joint)
        self.assertAlmostEqual(j1.RotationMin.getValueAs("deg").Value, -math.degrees(0.5), places=9)
        for j in objects.joints(asm):
            self.assertTrue(centres_meet(j), j.Label)
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(asm)
        gw.action("Dispcon_Solve").trigger()
        gw.settle()
        self.assertIn("nothing moved", gw.mw().statusBar().currentMessage())
        gw.shot("walkthrough-reopened")


def mouse_click(widget, at=None):
    """A left click on `widget` (at its centre, or at `at`) by Qt mouse events."""
    at = at or widget.rect().center()
    for kind in (QtCore.QEvent.MouseButtonPress, QtCore.QEvent.MouseButtonRelease):
        QtWidgets.QApplication.sendEvent(widget, QtGui.QMouseEvent(kind, QtCore.QPointF(at), QtCore.Qt.LeftButton,
                                                                   QtCore.Qt.LeftButton, QtCore.Qt.NoModifier))
    gw.settle()


class PreferencesPage(unittest.TestCase):
    """Edit > Preferences > Dispcon (ui/preferences.ui, added by FreeCADGui.addPreferencePage):
    the tolerance typed and the simplified drag unticked there, OK; a new assembly takes the
    tolerance and the next mouse drag is drawn in full."""

    NAMES = ("Tolerance", "LighterDrag")

    def setUp(self):
        gw.close_dialog()
        self.params = App.ParamGet("User parameter:BaseApp/Preferences/Mod/Dispcon")
        self.saved = (self.params.GetString("Tolerance", ""), self.params.GetBool("LighterDrag", True))
        self.doc = App.newDocument("WalkthroughPreferences")
        self.seen = {}

    def tearDown(self):
        from dispcon_fc import dragging

        dragging.stop()
        tolerance, lighter = self.saved
        if tolerance:
            self.params.SetString("Tolerance", tolerance)
        else:
            self.params.RemString("Tolerance")
        self.params.SetBool("LighterDrag", lighter)
        gw.close_documents()

    def answer(self, tries=100):
        """On the preferences dialog once it shows: the Dispcon page chosen in its list, the
        tolerance typed, the simplified drag unticked, OK."""
        dialog = QtWidgets.QApplication.activeModalWidget()
        if dialog is None or not dialog.isVisible() or dialog.findChild(QtWidgets.QListWidget) is None:
            if tries:
                QtCore.QTimer.singleShot(50, lambda: self.answer(tries - 1))
            return
        groups = dialog.findChild(QtWidgets.QListWidget)
        names = [groups.item(k).text() for k in range(groups.count())]
        self.seen["groups"] = names
        if "Dispcon" in names:
            item = groups.item(names.index("Dispcon"))
            mouse_click(groups.viewport(), groups.visualItemRect(item).center())
        tolerance = dialog.findChild(QtWidgets.QLineEdit, "tolerance")
        lighter = dialog.findChild(QtWidgets.QCheckBox, "lighterDrag")
        self.seen["shown"] = tolerance is not None and tolerance.isVisible()
        if tolerance is not None and lighter is not None:
            type_into(tolerance, "1e-6")
            self.seen["ticked"] = lighter.isChecked()
            mouse_click(lighter, QtCore.QPoint(6, lighter.height() // 2))
            gw.settle()
            os.makedirs(gw.OUT, exist_ok=True)
            dialog.grab().save(os.path.join(gw.OUT, "walkthrough-preferences.png"))  # a window of its own
        ok = [b for b in dialog.findChildren(QtWidgets.QPushButton) if b.text().replace("&", "") == "OK"]
        if ok:
            mouse_click(ok[0])
        if dialog.isVisible():
            dialog.reject()

    def test_the_page_changed_by_hand_is_honoured(self):
        from dispcon_fc import dragging, objects, operations
        import parts

        self.params.SetString("Tolerance", "1e-9")
        self.params.SetBool("LighterDrag", True)
        QtCore.QTimer.singleShot(0, self.answer)
        Gui.runCommand("Std_DlgPreferences")
        gw.settle()
        self.assertIn("Dispcon", self.seen.get("groups", []))
        self.assertTrue(self.seen.get("shown"), "the Dispcon page did not show its tolerance")
        self.assertTrue(self.seen.get("ticked"), "the simplified drag was not ticked first")
        self.assertEqual(self.params.GetString("Tolerance", ""), "1e-6")
        self.assertFalse(self.params.GetBool("LighterDrag", True))
        gw.action("Dispcon_CreateAssembly").trigger()
        asm = [o for o in self.doc.Objects if objects.is_assembly(o)][-1]
        self.assertEqual(asm.Tolerance, 1e-6)
        # The next mouse drag drawn in full: each part by its own view, shaded with its edges.
        base, arm = gw.base_and_arm(asm)
        operations.add_joint(asm, "Revolute", (base, parts.circle_edge(base.Shape, App.Vector(0, 0, 0))),
                             (arm, parts.circle_edge(arm.Shape, App.Vector(0, 0, 0))))
        view = Gui.getDocument(self.doc.Name).ActiveView
        view.viewTop()
        Gui.SendMsgToActiveView("ViewFit")
        gw.settle()
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(asm)
        gw.action("Dispcon_Drag").trigger()
        gw.settle()
        x, y = view.getPointOnScreen(arm.Placement.multVec(App.Vector(1.2, 0, 0.1)))
        gw.mouse(view, "press", x, y)
        gw.mouse(view, "move", x, y + 30)
        gw.settle()
        session = dragging.active(view)
        self.assertIsNotNone(session, "no drag under way")
        self.assertIsNotNone(session.lighter, "the press did not grab the arm")
        self.assertEqual((session.lighter.markers, session.lighter.switches, session.lighter.cube), ([], [], False),
                         "the drag is drawn simplified although the page says not")
        gw.mouse(view, "release", x, y + 30)
        gw.settle()


def main():
    only = os.environ.get("DISPCON_GUI_ONLY")
    gw.run_in_gui([c for c in (FourBarFromScratch, PreferencesPage) if not only or only in c.__name__],
                  "status-walkthrough")


main()
