"""The workbench as a designer meets it, in real FreeCAD under Xvfb (1280x900): icons, toolbars,
menus, joint markers, the joint task panel, errors in the GUI and drag mode, through real Qt
widgets and Coin3D events. Each test class opens and closes its own documents. Screenshots go to
DISPCON_GUI_OUT for a person to look at. Quits FreeCAD itself; writes 0 to <out>/status-workbench
when every test passed."""
import contextlib
import math
import os
import sys
import tempfile
import time
import traceback
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
WB = os.path.join(REPO, "freecad_workbench")
OUT = os.environ.get("DISPCON_GUI_OUT", os.path.join(tempfile.gettempdir(), "dispcon-gui"))
sys.path.insert(0, WB)
sys.path.insert(0, os.path.join(REPO, "samples", "freecad"))
sys.path.insert(0, HERE)
os.environ["DISPCON_IMPORT_ONLY"] = "1"

import FreeCAD as App  # noqa: E402
import FreeCADGui as Gui  # noqa: E402
from dispcon_fc.qt import QtCore, QtGui, QtWidgets  # noqa: E402

MOTION = ("Dispcon_Solve", "Dispcon_Drag", "Dispcon_Drive")
MAIN = ("Dispcon_Solve", "Dispcon_Drag", "Dispcon_Check", "Dispcon_JointRevolute", "Dispcon_CreateAssembly")


def mw():
    return Gui.getMainWindow()


def _in_drop_downs(tb):
    """[(the drop-down's own action, the actions of its menu)] of toolbar `tb`'s drop-down
    buttons (FreeCAD's command groups: each member's action carries its CommandName)."""
    out = []
    for a in tb.actions():
        w = tb.widgetForAction(a)
        menu = w.menu() if isinstance(w, QtWidgets.QToolButton) else None
        if menu is not None:
            out.append((a, menu.actions()))
    return out


def _named(a, name):
    command = a.property("CommandName")
    if command is not None and not isinstance(command, str):
        command = bytes(command).decode()
    return a.objectName() == name or command == name


def action(name):
    """The QAction FreeCAD made for command `name` (the one in a toolbar when there is one, a
    drop-down button's member included)."""
    for tb in mw().findChildren(QtWidgets.QToolBar):
        for a in tb.actions():
            if a.objectName() == name:
                return a
        for _, members in _in_drop_downs(tb):
            for a in members:
                if _named(a, name):
                    return a
    for a in mw().findChildren(QtWidgets.QAction):
        if a.objectName() == name:
            return a
    return None


def toolbar_of(name):
    """The toolbar holding command `name`, as a button or in a drop-down button."""
    for tb in mw().findChildren(QtWidgets.QToolBar):
        if any(a.objectName() == name for a in tb.actions()):
            return tb
        if any(_named(a, name) for _, members in _in_drop_downs(tb) for a in members):
            return tb
    return None


def drop_down_of(name):
    """The toolbar action of the drop-down button holding command `name`, or None."""
    for tb in mw().findChildren(QtWidgets.QToolBar):
        for group, members in _in_drop_downs(tb):
            if any(_named(a, name) for a in members):
                return group
    return None


def settle():
    for _ in range(3):
        QtWidgets.QApplication.processEvents()
        Gui.updateGui()


def shot(name, view=None):
    """The main window as a person sees it, with the 3D view's rendering painted in (a widget
    grab cannot read OpenGL under Xvfb). Returns the file's path."""
    settle()
    os.makedirs(OUT, exist_ok=True)
    window = mw()
    image = window.grab()
    view = view or (Gui.ActiveDocument.ActiveView if Gui.ActiveDocument else None)
    mdi = window.findChild(QtWidgets.QMdiArea)
    if view is not None and mdi is not None:
        area = mdi.geometry()
        area.moveTopLeft(mdi.mapTo(window, mdi.rect().topLeft()))
        tmp = os.path.join(OUT, "_view.png")
        tab = 30 if mdi.viewMode() == QtWidgets.QMdiArea.TabbedView else 0
        view.saveImage(tmp, area.width(), area.height() - tab, "White")
        painter = QtGui.QPainter(image)
        painter.drawImage(area.topLeft(), QtGui.QImage(tmp))
        painter.end()
        os.remove(tmp)
    path = os.path.join(OUT, name + ".png")
    image.save(path)
    return path


def mouse(view, kind, x, y):
    """A Coin3D event at (x, y) in `view`: "press" or "release" of the left button, "move", or
    "esc" (the Escape key pressed), through the viewer's scene graph as a real mouse's or
    keyboard's event goes."""
    from pivy import coin

    viewer = view.getViewer()
    region = viewer.getSoRenderManager().getViewportRegion()
    if kind == "move":
        event = coin.SoLocation2Event()
    elif kind == "esc":
        event = coin.SoKeyboardEvent()
        event.setKey(coin.SoKeyboardEvent.ESCAPE)
        event.setState(coin.SoButtonEvent.DOWN)
    else:
        event = coin.SoMouseButtonEvent()
        event.setButton(coin.SoMouseButtonEvent.BUTTON1)
        event.setState(coin.SoMouseButtonEvent.DOWN if kind == "press" else coin.SoMouseButtonEvent.UP)
    event.setPosition(coin.SbVec2s(x, y))
    action = coin.SoHandleEventAction(region)
    action.setEvent(event)
    action.apply(viewer.getSoRenderManager().getSceneGraph())


def close_dialog():
    """Closes the task dialog as a person would: the joint panel by Cancel."""
    from dispcon_fc.panels import joint as jp

    panel = jp.current()
    if panel is not None:
        panel.reject()
    if Gui.Control.activeDialog():
        Gui.Control.closeDialog()
    settle()


def activate(doc):
    """`doc` the active document, of the application and of the GUI: its 3D view."""
    App.setActiveDocument(doc.Name)
    Gui.ActiveDocument = Gui.getDocument(doc.Name)
    return Gui.getDocument(doc.Name).ActiveView


def close_documents():
    """Every open document closed (a class's set-up made several), the selection cleared first."""
    Gui.Selection.clearSelection()
    for name in list(App.listDocuments()):
        App.closeDocument(name)
    settle()


def same(p, q, tol=1e-9):
    """Two placements equal within tol."""
    return (p.Base - q.Base).Length <= tol and p.Rotation.multiply(q.Rotation.inverted()).Angle <= tol


def laid_out():
    """Waits until the markers are laid out again after the camera moved (they wait for it to
    rest: viewproviders.ViewProviderAssembly.CAMERA_REST_MS)."""
    from dispcon_fc import viewproviders

    end = time.time() + 3 * viewproviders.ViewProviderAssembly.CAMERA_REST_MS / 1000.0
    while time.time() < end:
        settle()
        time.sleep(0.02)
    settle()


def coin_vec(v):
    from pivy import coin

    return coin.SbVec3f(v.x, v.y, v.z)


def rendered(view, path):
    """The view rendered at its own size as an array of RGB pixels (rows, columns, 3)."""
    region = view.getViewer().getSoRenderManager().getViewportRegion()
    w, h = region.getViewportSizePixels()
    view.saveImage(path, w, h, "White")
    try:
        return image_pixels(path)
    finally:
        os.remove(path)


def image_pixels(path):
    """The image at `path` as an array of RGB pixels (rows, columns, 3)."""
    import numpy

    image = QtGui.QImage(path).convertToFormat(QtGui.QImage.Format_RGB888)
    data = bytes(image.constBits())[:image.bytesPerLine() * image.height()]
    rows = numpy.frombuffer(data, numpy.uint8).reshape(image.height(), image.bytesPerLine())
    return rows[:, :3 * image.width()].reshape(image.height(), image.width(), 3).astype(numpy.int16)


def drawn_ring(image, around, reach):
    """The circle through the markers' orange of `image` (an array of RGB pixels), within `reach`
    pixels of `around` (column, row) when given: (its centre's column, its row, its radius), a
    least-squares circle fitted to the pixels, then again to those within 3 px of the first (the
    ring without its axis seen end on at the centre or a neighbour's edge)."""
    import numpy

    r, g, b = image[:, :, 0], image[:, :, 1], image[:, :, 2]
    rows, cols = numpy.nonzero((r > 200) & (g > 60) & (g < 170) & (b < 60))
    x, y = cols.astype(float), rows.astype(float)
    if around is not None:
        near = numpy.hypot(x - around[0], y - around[1]) < reach
        x, y = x[near], y[near]
    assert len(x) > 20, "no ring drawn (%d orange pixels)" % len(x)
    for _ in range(2):
        # x^2 + y^2 = 2 a x + 2 b y + c, c = radius^2 - a^2 - b^2 (Kasa's fit)
        (a2, b2, c), *_ = numpy.linalg.lstsq(numpy.column_stack((x, y, numpy.ones_like(x))), x * x + y * y, rcond=None)
        a, b = a2 / 2, b2 / 2
        radius = math.sqrt(c + a * a + b * b)
        keep = abs(numpy.hypot(x - a, y - b) - radius) < 3.0
        x, y = x[keep], y[keep]
    return a, b, radius


def marker_overlaps(view, joints):
    """Each joint's marker drawn alone over the parts: ({(a, b): the share of the smaller one's
    pixels that the other also covers}, {joint name: its pixel count}). Every marker is drawn
    again afterwards."""
    from dispcon_fc import viewproviders

    marks = {j.Name: viewproviders.joint_view(j).marker for j in joints}
    path = os.path.join(OUT, "_alone.png")
    try:
        for m in marks.values():
            m.set_visible(False)
        settle()
        background = rendered(view, path)
        masks = {}
        for j in joints:
            marks[j.Name].set_visible(True)
            settle()
            masks[j.Name] = (abs(rendered(view, path) - background).max(axis=2) > 40)
            marks[j.Name].set_visible(False)
    finally:
        for m in marks.values():
            m.set_visible(True)
        settle()
    sizes = {n: int(m.sum()) for n, m in masks.items()}
    overlaps = {}
    for a in range(len(joints)):
        for b in range(a + 1, len(joints)):
            ja, jb = joints[a], joints[b]
            shared = int((masks[ja.Name] & masks[jb.Name]).sum())
            overlaps[ja, jb] = shared / max(1, min(sizes[ja.Name], sizes[jb.Name]))
    return overlaps, sizes


class Documents(unittest.TestCase):
    """Each test in a fresh document, closed afterwards."""

    def setUp(self):
        close_dialog()
        self.doc = App.newDocument(self.id().split(".")[-1][:30])
        Gui.Selection.clearSelection()

    def tearDown(self):
        close_dialog()
        Gui.Selection.clearSelection()
        App.closeDocument(self.doc.Name)
        settle()

    def fourbar(self):
        from test_headless import fourbar

        out = fourbar(self.doc, OUT)
        self.view().viewIsometric()
        Gui.SendMsgToActiveView("ViewFit")
        return out

    def arm(self):
        """A grounded base and a free arm, off its pin: the two circular edges to pick."""
        from dispcon_fc import operations
        import parts

        asm = operations.create_assembly(self.doc)
        base, arm = base_and_arm(asm)
        arm.Placement = App.Placement(App.Vector(0.3, 0.2, 0.4), App.Rotation(App.Vector(0, 0, 1), 20))
        e1 = (base, parts.circle_edge(base.Shape, App.Vector(0, 0, 0)))
        e2 = (arm, parts.circle_edge(arm.Shape, App.Vector(0, 0, 0)))
        Gui.SendMsgToActiveView("ViewFit")
        return asm, base, arm, e1, e2

    def view(self):
        return Gui.ActiveDocument.ActiveView


class TestCommands(Documents):
    def test_every_command_has_an_icon_that_renders(self):
        from dispcon_fc import commands

        names = [n for n in Gui.listCommands() if n.startswith("Dispcon_")]
        self.assertGreaterEqual(len(names), 20)
        for n in names:
            a = action(n)
            self.assertIsNotNone(a, n)
            self.assertFalse(a.icon().isNull(), "%s has no icon" % n)
            image = a.icon().pixmap(32, 32).toImage()
            coloured = sum(1 for x in range(0, 32, 2) for y in range(0, 32, 2)
                           if QtGui.QColor(image.pixel(x, y)).alpha() > 0)
            self.assertGreater(coloured, 20, "%s's icon is empty" % n)
            self.assertTrue(a.toolTip().strip(), "%s has no tooltip" % n)
        self.assertTrue(commands)

    def test_joint_tooltips_say_what_to_select(self):
        tip = action("Dispcon_JointRevolute").toolTip().lower()
        self.assertIn("circular edge", tip)
        tip = action("Dispcon_JointSlider").toolTip().lower()
        self.assertIn("straight edge", tip)

    def test_main_commands_visible_at_1280(self):
        window = mw()
        window.showNormal()
        window.setGeometry(0, 0, 1280, 900)
        settle()
        self.assertLessEqual(window.width(), 1280)
        for n in MAIN:
            tb = toolbar_of(n)
            self.assertIsNotNone(tb, "%s is in no toolbar" % n)
            self.assertTrue(tb.isVisible(), "%s's toolbar is hidden" % n)
            w = tb.widgetForAction(action(n))
            self.assertIsNotNone(w, n)
            self.assertTrue(w.isVisible(), "%s is hidden behind the toolbar's >> at 1280 px" % n)
            r = w.geometry()
            self.assertTrue(tb.rect().contains(r), "%s lies outside its toolbar" % n)
            right = w.mapTo(window, QtCore.QPoint(r.width(), 0)).x()
            self.assertLessEqual(right, window.width(), n)
        titles = {toolbar_of(n).windowTitle() for n in MAIN}
        self.assertGreaterEqual(len(titles), 3, "commands should be grouped in toolbars: %s" % titles)
        shot("toolbars-1280")

    def test_toolbars_have_room_at_1280(self):
        """The workbench's toolbars in one row at 1280x900: no button behind a ">>", the row at
        most 90 % full, and every command reachable from a toolbar (as a button or in a drop-down
        button, with its icon and tooltip there) and from the Dispcon menu."""
        from dispcon_fc import commands
        from dispcon_fc.qt import is_alive

        window = mw()
        window.showNormal()
        window.setGeometry(0, 0, 1280, 900)
        settle()
        bars = [tb for tb in window.findChildren(QtWidgets.QToolBar)
                if tb.objectName().startswith("Dispcon ") and tb.isVisible()]
        self.assertEqual(sorted(tb.objectName() for tb in bars),
                         sorted("Dispcon " + title for title, _ in commands.GROUPS))
        rows = {tb.y() for tb in bars}
        self.assertEqual(len(rows), 1, "the toolbars take more than one row: %s" % sorted(rows))
        left = min(tb.mapTo(window, QtCore.QPoint(0, 0)).x() for tb in bars)
        right = max(tb.mapTo(window, QtCore.QPoint(tb.width(), 0)).x() for tb in bars)
        self.assertLessEqual(right, window.width())
        # How much of the row the buttons need: each toolbar's own size hint (a toolbar squeezed
        # into less hides its last buttons behind ">>").
        needed = sum(tb.sizeHint().width() for tb in bars)
        for tb in bars:
            ext = [b for b in tb.findChildren(QtWidgets.QToolButton) if b.objectName() == "qt_toolbar_ext_button"]
            self.assertFalse(any(b.isVisible() for b in ext), "%s hides buttons behind >>" % tb.objectName())
            self.assertGreaterEqual(tb.width(), tb.sizeHint().width(), tb.objectName())
            for a in tb.actions():
                if not a.isSeparator():
                    w = tb.widgetForAction(a)
                    self.assertTrue(w is not None and w.isVisible(), "%s is hidden" % a.objectName())
        self.assertLessEqual(needed, 0.9 * 1280, "the toolbars need %d of 1280 px" % needed)
        print("toolbars: %d px of 1280 (%.0f %%), the row %d to %d" % (needed, 100.0 * needed / 1280, left, right))
        # Every command in a toolbar, with its icon and tooltip; in a drop-down, in its menu.
        in_menu = set()
        for m in window.menuBar().findChildren(QtWidgets.QMenu):
            if is_alive(m) and m.title().replace("&", "") in ("Dispcon", "Joints"):
                in_menu |= {a.objectName() for a in m.actions()}
        grouped = {n for drop in commands.DROP_DOWNS.values() for _, _, _, members in drop for n in members}
        names = [n for _, group in commands.GROUPS for n, _ in group.commands()]
        for n in names:
            a = action(n)
            self.assertIsNotNone(toolbar_of(n), "%s is in no toolbar" % n)
            self.assertFalse(a.icon().isNull(), "%s has no icon in its toolbar" % n)
            self.assertTrue(a.toolTip().strip(), "%s has no tooltip in its toolbar" % n)
            self.assertIn(n, in_menu, "%s is not in the Dispcon menu" % n)
            self.assertEqual(drop_down_of(n) is not None, n in grouped, n)
        for n in MAIN:
            self.assertIsNone(drop_down_of(n), "%s should be a button of its own" % n)
        shot("toolbars-room-1280")

    def test_a_drop_down_runs_its_command_and_shows_it(self):
        """Choosing PointOnPlane in its drop-down opens the PointOnPlane panel, and the button then
        shows its icon (FreeCAD's command groups show the command run last)."""
        from dispcon_fc.panels import joint as jp

        self.fourbar()
        settle()
        member = action("Dispcon_JointPointOnPlane")
        group = drop_down_of("Dispcon_JointPointOnPlane")
        self.assertIsNotNone(group)
        before = group.icon().pixmap(32, 32).toImage()
        member.trigger()
        settle()
        panel = jp.current()
        self.assertIsNotNone(panel, "the drop-down's PointOnPlane opened no panel")
        self.assertEqual(panel.type_box.currentText(), "PointOnPlane")
        self.assertNotEqual(group.icon().pixmap(32, 32).toImage(), before, "the button still shows the first command")
        self.assertEqual(group.icon().pixmap(32, 32).toImage(), member.icon().pixmap(32, 32).toImage())
        panel.reject()
        settle()

    def test_menu_has_joint_submenu_and_separators(self):
        from dispcon_fc.qt import is_alive

        menus = [m for m in mw().menuBar().findChildren(QtWidgets.QMenu)
                 if is_alive(m) and m.title().replace("&", "") == "Dispcon"]
        self.assertTrue(menus, "no Dispcon menu")
        acts = menus[-1].actions()
        self.assertTrue(any(a.isSeparator() for a in acts), "no separators in the Dispcon menu")
        sub = next((a.menu() for a in acts if a.menu() is not None and "Joint" in a.text()), None)
        self.assertIsNotNone(sub, "no Joints submenu")
        from dispcon_fc import adapter, engine

        self.assertEqual(len([a for a in sub.actions() if a.objectName().startswith("Dispcon_Joint")]),
                         len(adapter.offered_types(engine.load())))

    def test_commands_greyed_out_when_they_cannot_run(self):
        # A document without an assembly: Solve, Drag, Check and the joints cannot run.
        Gui.updateCommands() if hasattr(Gui, "updateCommands") else None
        settle()
        for n in ("Dispcon_Solve", "Dispcon_Drag", "Dispcon_Check", "Dispcon_JointRevolute", "Dispcon_Ground"):
            Gui.Selection.clearSelection()
            settle()
            self.assertFalse(Gui.isCommandActive(n), "%s is active with no assembly" % n)
        self.assertTrue(Gui.isCommandActive("Dispcon_CreateAssembly"))
        self.fourbar()
        Gui.Selection.clearSelection()
        settle()
        for n in ("Dispcon_Solve", "Dispcon_Drag", "Dispcon_Check", "Dispcon_JointRevolute"):
            self.assertTrue(Gui.isCommandActive(n), "%s is greyed out with a four-bar" % n)


class TestMarkers(Documents):
    def test_a_camera_rest_reuses_the_frames_a_part_move_reads_again(self):
        """The layout a camera rest runs reads no joint from FreeCAD when nothing moved (the frames
        and stacks of the last layout), and lays the markers out the same; a part moved makes the
        next layout read every joint again."""
        from dispcon_fc import markers, objects

        (asm, g, crank, coupler, rocker), view = self.solved_in_view()
        proxy = asm.ViewObject.Proxy
        proxy.restack()
        laid = [objects.joints(asm)[k].ViewObject.Proxy.shift for k in range(4)]
        read = []
        original = markers.joint_frame

        def counting(j):
            read.append(j.Name)
            return original(j)
        markers.joint_frame = counting
        try:
            cam = view.getCameraNode()
            cam.height.setValue(cam.height.getValue() * 1.5)
            proxy.restack()  # what the camera's rest runs
            self.assertEqual(read, [], "a camera rest read the joints again")
            cam.height.setValue(cam.height.getValue() / 1.5)
            proxy.restack()
            self.assertEqual([objects.joints(asm)[k].ViewObject.Proxy.shift for k in range(4)], laid)
            crank.Placement = App.Placement(App.Vector(0, 0, 0.5), crank.Placement.Rotation)
            settle()  # the joints follow their part and ask for a layout
            self.assertEqual(sorted(set(read)), sorted(j.Name for j in objects.joints(asm)))
        finally:
            markers.joint_frame = original

    def solved_in_view(self):
        """The four-bar solved, seen whole from the isometric view: (fourbar(), the view)."""
        from dispcon_fc import operations

        made = self.fourbar()
        operations.solve(made[0])
        view = self.view()
        view.viewIsometric()
        Gui.SendMsgToActiveView("ViewFit")
        settle()
        return made, view

    def test_each_joint_has_a_marker_in_the_scene(self):
        from pivy import coin
        from dispcon_fc import objects

        (asm, g, crank, coupler, rocker), view = self.solved_in_view()
        root = view.getSceneGraph()
        coin.SoBaseKit.setSearchingChildren(True)  # the glyphs sit in a screen-scale node kit
        for j in objects.joints(asm):
            search = coin.SoSearchAction()
            search.setName("dispcon_marker_" + j.Name)
            search.apply(root)
            self.assertIsNotNone(search.getPath(), "no marker for %s in the scene" % j.Label)
            search = coin.SoSearchAction()
            search.setName("dispcon_glyph_Revolute")
            search.setInterest(coin.SoSearchAction.ALL)
            search.apply(root)
        self.assertEqual(search.getPaths().getLength(), 4)

    def test_markers_drawn_follow_hide_and_highlight(self):
        from dispcon_fc import objects, operations, viewproviders

        asm, g, crank, coupler, rocker = self.fourbar()
        operations.solve(asm)
        view = self.view()
        view.viewIsometric()
        Gui.SendMsgToActiveView("ViewFit")
        settle()
        j = objects.joints(asm)[1]  # crank - coupler

        def orange_pixels():
            path = os.path.join(OUT, "_markers.png")
            view.saveImage(path, 640, 480, "White")
            img = QtGui.QImage(path)
            n = 0
            for x in range(0, 640, 2):
                for y in range(0, 480, 2):
                    c = QtGui.QColor(img.pixel(x, y))
                    if c.red() > 200 and 60 < c.green() < 170 and c.blue() < 60:
                        n += 1
            return n

        with_markers = orange_pixels()
        self.assertGreater(with_markers, 30, "no orange marker drawn")
        shot("markers")
        # Selected in the tree: green.
        Gui.Selection.addSelection(j)
        settle()
        self.assertEqual(viewproviders.joint_view(j).marker.look, "selected")
        for other in objects.joints(asm):
            if other != j:
                self.assertEqual(viewproviders.joint_view(other).marker.look, "normal")
        shot("marker-selected")
        Gui.Selection.clearSelection()
        settle()
        self.assertEqual(viewproviders.joint_view(j).marker.look, "normal")
        # Follows its part.
        before = viewproviders.joint_view(j).marker.transform.translation.getValue().getValue()
        operations.drag(asm, crank, App.Placement(crank.Placement.Base,
                                                  App.Rotation(App.Vector(0, 0, 1), 30).multiply(crank.Placement.Rotation)))
        after = viewproviders.joint_view(j).marker.transform.translation.getValue().getValue()
        self.assertGreater(math.dist(before, after), 0.1, "the marker stayed behind its part")
        want = crank.Placement.multVec(j.Point1) if j.Reference1[0] == crank else j.Reference1[0].Placement.multVec(j.Point1)
        self.assertLess(math.dist(after, (want.x, want.y, want.z)), 1e-6)
        # Hidden with the assembly.
        asm.ViewObject.Visibility = False
        settle()
        self.assertLess(orange_pixels(), 5, "markers still drawn with the assembly hidden")
        asm.ViewObject.Visibility = True
        settle()
        self.assertGreater(orange_pixels(), 30)

    def test_markers_keep_their_size_on_the_screen_at_any_zoom(self):
        from dispcon_fc import objects, operations

        asm, g, crank, coupler, rocker = self.fourbar()
        operations.solve(asm)
        view = self.view()
        view.viewTop()
        Gui.SendMsgToActiveView("ViewFit")
        js = objects.joints(asm)
        for j in js[1:]:  # one marker alone, to measure it
            j.ViewObject.Visibility = False
        settle()

        def extents(name):
            """Width of the orange (the marker) and of the grey (the parts) drawn, in pixels."""
            path = os.path.join(OUT, name + ".png")
            view.saveImage(path, 640, 480, "White")
            img = QtGui.QImage(path)
            orange, grey = [], []
            for x in range(0, 640):
                for y in range(0, 480, 2):
                    c = QtGui.QColor(img.pixel(x, y))
                    if c.red() > 200 and 60 < c.green() < 170 and c.blue() < 60:
                        orange.append(x)
                    elif abs(c.red() - c.green()) < 12 and abs(c.green() - c.blue()) < 12 and 60 < c.red() < 230:
                        grey.append(x)
            self.assertTrue(orange and grey, "nothing drawn in %s" % path)
            return max(orange) - min(orange), max(grey) - min(grey)

        marker_near, parts_near = extents("zoom-near")
        camera = view.getCameraNode()
        camera.height.setValue(camera.height.getValue() * 3)  # zoomed out three times
        settle()
        marker_far, parts_far = extents("zoom-far")
        self.assertLess(parts_far, parts_near * 0.45, "the zoom did not shrink the parts")
        self.assertGreater(marker_near, 15)
        self.assertLess(abs(marker_far - marker_near), 0.15 * marker_near,
                        "the marker changed size with the zoom: %d px, then %d px" % (marker_near, marker_far))
        for j in js[1:]:
            j.ViewObject.Visibility = True

    def test_a_glyph_is_drawn_the_size_the_layout_counts_at_any_window_and_zoom(self):
        """A ring's radius is markers.PIXELS (14 px) on the screen at two window sizes (the view
        wider than tall, then taller than wide) and two zooms, and in images saved at other sizes,
        and a stacked marker sits where the layout puts it (its joint's point and its shift,
        PIXELS px a glyph unit). Before, FreeCAD's SoShapeScale drew a unit PIXELS * width /
        height pixels: 19.0 px in the 1052 x 772 view, 10.5 in a 656 x 876 one, so a stacked
        marker sat 1.4 times (at the third audit's 1052 x 505, 2.1 times) as far as laid out."""
        from dispcon_fc import markers, objects, operations, viewproviders
        import parts

        asm, g, crank, coupler, rocker = self.fourbar()
        self.assertTrue(operations.solve(asm).converged)
        # A second revolute on the ground's first pin (the same as the first): the second of a
        # stack at that place, set beside it.
        first = objects.joints(asm)[0]
        second = operations.add_joint(asm, "Revolute", (g, parts.circle_edge(g.Shape, App.Vector(0, 0, 0))),
                                      (crank, parts.circle_edge(crank.Shape, App.Vector(0, 0, 0))))
        self.assertTrue(operations.solve(asm).converged)
        for j in objects.joints(asm):
            j.ViewObject.Visibility = j in (first, second)
        view = self.view()
        view.viewTop()  # the pins' axes along z: the rings seen face on
        Gui.SendMsgToActiveView("ViewFit")
        laid_out()
        window = mw().geometry()
        seen = []
        try:
            for size in ((1280, 900), (800, 900)):
                mw().setGeometry(0, 0, *size)
                settle()
                Gui.SendMsgToActiveView("ViewFit")
                laid_out()
                camera = view.getCameraNode()
                fit, eye = camera.height.getValue(), App.Vector(*camera.position.getValue().getValue())
                for zoom in (1.0, 2.5):
                    # Zoomed in on the pin (the camera moved across its line of sight over it).
                    pin, ahead = markers.joint_frame(first)[0], App.Vector(0, 0, -1)
                    over = (pin - eye) - ahead * (pin - eye).dot(ahead) if zoom > 1 else App.Vector()
                    camera.position.setValue(coin_vec(eye + over))
                    camera.height.setValue(fit / zoom)
                    laid_out()
                    width, height = view.getSize()
                    self.assertIsNotNone(viewproviders.joint_view(second).shift, "the stacked marker was not set apart")
                    rot = camera.orientation.getValue()
                    right, up = (App.Vector(*rot.multVec(coin_vec(App.Vector(*v))).getValue())
                                 for v in ((1, 0, 0), (0, 1, 0)))
                    at_eye = App.Vector(*camera.position.getValue().getValue())

                    def drawn_at(point):
                        """(column, row) of the image where the view draws `point`: Coin's
                        orthographic camera spans its height over the viewport's shorter side
                        (measured: 55.2 px for 10 units at height 100 in a 552 x 772 view, 77.2
                        in 1052 x 772; FreeCAD 0.20's getPointOnScreen counts the height there)."""
                        d, scale = point - at_eye, min(width, height) / camera.height.getValue()
                        return ((width - 1) / 2 + d.dot(right) * scale, (height - 1) / 2 - d.dot(up) * scale)

                    def laid(j):
                        """Where the layout puts j's glyph centre: (column, row) of the image."""
                        x, y = drawn_at(markers.joint_frame(j)[0])
                        shift = viewproviders.joint_view(j).shift or App.Vector()
                        return (x + shift.dot(right) * markers.PIXELS, y - shift.dot(up) * markers.PIXELS)

                    # The layout counts the joints' points in pixels as the view draws them (the
                    # ground's two pins, the first joint's and the fourth's, as far apart).
                    pins = [markers.joint_frame(j)[0] for j in (first, objects.joints(asm)[3])]
                    (xa, ya), (xb, yb) = (viewproviders._screen(self.doc).pixels(p) for p in pins)
                    (va, wa), (vb, wb) = (drawn_at(p) for p in pins)
                    self.assertAlmostEqual(math.hypot(xb - xa, yb - ya), math.hypot(vb - va, wb - wa), delta=1.0,
                                           msg="the layout's pixels are not the view's (%d x %d)" % (width, height))
                    name = "marker-size-%dx%d-zoom%g" % (width, height, zoom)
                    image = rendered(view, os.path.join(OUT, "_%s.png" % name))
                    shot(name, view)
                    for j, at in ((first, laid(first)), (second, laid(second))):
                        cx, cy, r = drawn_ring(image, at, 1.6 * markers.PIXELS)
                        seen.append("%s %s: radius %.1f px, centre %.1f px from the layout's"
                                    % (name, j.Label, r, math.hypot(cx - at[0], cy - at[1])))
                        self.assertAlmostEqual(r, markers.PIXELS, delta=1.5, msg=seen[-1])
                        self.assertLess(math.hypot(cx - at[0], cy - at[1]), 2.0, seen[-1])
                # An image saved at other sizes draws a unit PIXELS pixels too (the first ring
                # alone, found wherever the image's shape puts it).
                second.ViewObject.Visibility = False
                settle()
                for w, h in ((640, 480), (400, 800)):
                    path = os.path.join(OUT, "marker-size-image-%dx%d.png" % (w, h))
                    view.saveImage(path, w, h, "White")
                    cx, cy, r = drawn_ring(image_pixels(path), None, None)
                    seen.append("image %d x %d: radius %.1f px" % (w, h, r))
                    self.assertAlmostEqual(r, markers.PIXELS, delta=1.5, msg=seen[-1])
                second.ViewObject.Visibility = True
        finally:
            mw().setGeometry(window)
            settle()
            print("marker size: " + "; ".join(seen))

    def test_every_planetary_marker_is_readable_at_fit_all_zoom(self):
        # The planetary set: the carrier, the sun and the ring turn on one axle (three revolutes
        # at one point), and each planet's axle, its mesh with the sun and its mesh with the ring
        # sit a few pixels apart at fit-all zoom: every marker is drawn alone and the pixels it
        # shares with another counted.
        from dispcon_fc import markers, operations, viewproviders
        import couplings

        if not engine_couples():
            self.skipTest("this build's engine has no coupling rows")

        asm, p = couplings.planetary(self.doc)
        self.assertTrue(operations.solve(asm).converged)
        view = self.view()
        view.viewIsometric()
        Gui.SendMsgToActiveView("ViewFit")
        laid_out()
        joints = [o for o in asm.Group if hasattr(o, "JointType")]
        self.assertEqual(len(joints), 12)
        axle = [j for j in joints if j.JointType == "Revolute" and p["Base"] in (j.Reference1[0], j.Reference2[0])]
        self.assertEqual(len(axle), 3)
        shot("planetary-markers")
        overlaps, sizes = marker_overlaps(view, joints)
        report = sorted(((f, a.Label, b.Label) for (a, b), f in overlaps.items()), reverse=True)
        print("planetary at fit-all: marker pixels %s; most shared: %s"
              % (sorted(sizes.values()), ", ".join("%s/%s %.3f" % (a, b, f) for f, a, b in report[:4])))
        for j in joints:
            self.assertGreater(sizes[j.Name], 40, "%s's marker is not drawn" % j.Label)
        for f, a, b in report:
            # A line crossing a ring shares a few pixels; a marker drawn over another shares many.
            self.assertLess(f, 0.06, "%s and %s are drawn over each other (%.0f%% of the smaller's pixels)"
                            % (a, b, 100 * f))

        def shift(j):
            """The glyph's shift off the joint's point, in glyph units, in world directions."""
            return markers.joint_placement(j).Rotation.multVec(viewproviders.joint_view(j).marker.offset_units())

        # The axle's three stay side by side, at least a gap apart; none goes far from its joint.
        shifts = [shift(j) for j in axle]
        for a in range(3):
            for b in range(a + 1, 3):
                self.assertGreaterEqual((shifts[a] - shifts[b]).Length, markers.STACK_SPACING * 0.99)
        for j in joints:
            self.assertLess(shift(j).Length, 5 * markers.STACK_SPACING, j.Label)
        # Zoomed in on one planet, its markers are far apart on the screen: each at its joint.
        planet = p["Planet1"]
        near = [j for j in joints if planet in (j.Reference1[0], j.Reference2[0])]
        self.assertEqual(len(near), 3)
        camera = view.getCameraNode()
        centre = planet.Placement.Base
        camera.position.setValue(camera.position.getValue() + coin_vec(centre - App.Vector(0, 0, 0)))
        camera.height.setValue(camera.height.getValue() / 5)
        laid_out()
        for j in near:
            self.assertLess(shift(j).Length, 1e-6, "%s is moved off its joint zoomed in" % j.Label)
        shot("planetary-markers-near")
        # A part moved: the layout follows (the axle's three still apart as the carrier turns).
        view.viewIsometric()
        Gui.SendMsgToActiveView("ViewFit")
        operations.drive_to(asm, axle[0], operations.drive_value(axle[0]) + 30.0)
        laid_out()
        overlaps, sizes = marker_overlaps(view, joints)
        self.assertLess(max(overlaps.values()), 0.06)

    def test_hovering_over_an_edge_shows_the_marker_to_come(self):
        # The cursor moved over the arm's pin edge (a Coin3D mouse move through the viewer's
        # scene graph, as a real mouse's): FreeCAD preselects the edge under it and the panel
        # draws the marker the joint would get there.
        from dispcon_fc.panels import joint as jp

        asm, base, arm, e1, e2 = self.arm()
        self.view().viewTop()
        Gui.SendMsgToActiveView("ViewFit")
        settle()
        Gui.Selection.clearSelection()
        Gui.runCommand("Dispcon_JointRevolute")
        settle()
        panel = jp.current()
        edge = arm.Shape.getElement(e2[1])
        x, y = self.view().getPointOnScreen(edge.valueAt(0.4 * edge.FirstParameter + 0.6 * edge.LastParameter))
        height = self.view().getSize()[1]
        hit = None
        for dx, dy in [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1), (2, 0), (-2, 0), (0, 2), (0, -2)]:
            mouse(self.view(), "move", int(x) + dx, int(y) + dy)
            settle()
            pre = Gui.Selection.getPreselection()
            if pre.Object is not None and pre.SubElementNames and panel.preview is not None:
                hit = pre
                break
        self.assertIsNotNone(hit, "no preselection under the cursor at %d, %d (view %d high)" % (x, y, height))
        self.assertTrue(hit.SubElementNames[0].startswith("Edge"), hit.SubElementNames)
        self.assertEqual(panel.preview.joint_type, "Revolute")
        at = panel.preview.transform.translation.getValue().getValue()
        centre = arm.Shape.getElement(hit.SubElementNames[0]).Curve.Center
        self.assertLess(math.dist(at, (centre.x, centre.y, centre.z)), 1e-6, "the preview is not at the edge's centre")
        panel.reject()

    def test_the_marker_to_come_goes_with_its_document(self):
        # The document closed while the panel shows the marker to come: the panel takes it out
        # of the view's scene graph, which it holds until then, and has no transaction left to
        # abort (its Cancel took the marker out of the graph FreeCAD had freed with the view,
        # a ref/unref of a freed node, then raised on the closed document).
        from dispcon_fc.panels import joint as jp

        asm, base, arm, e1, e2 = self.arm()
        Gui.Selection.clearSelection()
        Gui.runCommand("Dispcon_JointRevolute")
        panel = jp.current()
        Gui.Selection.setPreselection(arm, e2[1])
        settle()
        self.assertIsNotNone(panel.preview, "no marker to come")
        graph, root = panel.preview_graph, panel.preview.root
        held = graph.getRefCount()
        self.assertGreaterEqual(held, 2, "the panel does not hold the scene graph it drew into")
        self.assertEqual(root.getRefCount(), 2, "the marker to come is not in one scene graph")
        App.closeDocument(asm.Document.Name)
        self.doc = App.newDocument("WorkbenchTestAgain")  # (tearDown closes self.doc)
        settle()
        panel.reject()  # Cancel, or any selection event: the panel finds its document gone
        settle()
        self.assertTrue(panel.closed, "the panel did not notice its document closed")
        self.assertIsNone(panel.preview, "the marker to come stayed in a closed document's view")
        self.assertEqual(root.getRefCount(), 1, "the marker to come is still in a scene graph")

    def test_preselection_shows_the_marker_to_come(self):
        from pivy import coin
        from dispcon_fc.panels import joint as jp

        asm, base, arm, e1, e2 = self.arm()
        Gui.Selection.clearSelection()
        Gui.runCommand("Dispcon_JointSlider")
        panel = jp.current()
        self.assertTrue(panel.picking)
        Gui.Selection.setPreselection(arm, e2[1])
        settle()
        search = coin.SoSearchAction()
        search.setName("dispcon_preview")
        search.apply(self.view().getSceneGraph())
        self.assertIsNotNone(search.getPath(), "no preview marker under the cursor")
        self.assertEqual(panel.preview.joint_type, "Slider")
        Gui.Selection.clearPreselection()
        settle()
        panel.reject()


HEADLESS_FOURBAR = """
import os, sys
sys.path.insert(0, %r)
os.environ["DISPCON_IMPORT_ONLY"] = "1"
import FreeCAD as App
from test_headless import fourbar, da
doc = App.newDocument("headless")
asm = fourbar(doc, %r)[0]
assert da.solve(asm).converged
doc.saveAs(%r)
"""


def shifts_of(asm):
    """Each joint's marker's shift off its point (the layout's), rounded to 1e-9 glyph units."""
    from dispcon_fc import objects, viewproviders

    out = []
    for j in objects.joints(asm):
        v = viewproviders.joint_view(j).shift
        out.append(None if v is None else tuple(round(c, 9) + 0.0 for c in v))
    return out


def orange_count(view, name):
    """The markers' orange pixels in an image of the view saved at 640 x 480 (every pixel)."""
    import numpy

    path = os.path.join(OUT, name + ".png")
    view.saveImage(path, 640, 480, "White")
    image = image_pixels(path)
    r, g, b = image[:, :, 0], image[:, :, 1], image[:, :, 2]
    return int(numpy.count_nonzero((r > 200) & (g > 60) & (g < 170) & (b < 60)))


class TestMarkerFixes(Documents):
    """The fifteenth round: a resize or a change of projection lays the markers out again; a
    deleted part's joints are not drawn, and are again after an undo."""

    def crowded_fourbar(self):
        """The four-bar solved, seen from the top and zoomed out until its markers crowd (the
        layout pushes them apart): (asm, its parts, the view)."""
        from dispcon_fc import operations

        made = self.fourbar()
        self.assertTrue(operations.solve(made[0]).converged)
        view = self.view()
        view.viewTop()
        Gui.SendMsgToActiveView("ViewFit")
        camera = view.getCameraNode()
        camera.height.setValue(camera.height.getValue() * 6)
        laid_out()
        return made, view

    def test_a_resize_lays_the_markers_out_again(self):
        """Resizing the window moves no camera; the layout counted the old size (stale offsets,
        markers pushed apart as the old size had them) until the camera moved. Now the markers
        are laid out for the new size once the resize rests, as a layout run then lays them."""
        from pivy import coin

        (asm, *_), view = self.crowded_fourbar()
        proxy = asm.ViewObject.Proxy
        # One probe in the view, at the top of its scene graph.
        search = coin.SoSearchAction()
        search.setName("dispcon_layout_probe")
        search.setInterest(coin.SoSearchAction.ALL)
        search.apply(view.getSceneGraph())
        self.assertEqual(search.getPaths().getLength(), 1)
        self.assertEqual(view.getSceneGraph().getChild(0).getName().getString(), "dispcon_layout_probe")
        window = mw().geometry()
        try:
            before = shifts_of(asm)
            self.assertTrue(any(before), "nothing set apart: the test's zoom crowds nothing")
            mw().setGeometry(0, 0, 640, 900)
            settle()
            laid_out()
            after = shifts_of(asm)
            self.assertNotEqual(after, before, "the layout did not follow the resize")
            proxy.restack()  # what a layout for the new size gives
            self.assertEqual(shifts_of(asm), after)
            self.assertEqual(proxy.laid_for[:2], tuple(view.getViewer().getSoRenderManager()
                                                       .getViewportRegion().getViewportSizePixels()))
            shot("markers-after-resize", view)
        finally:
            mw().setGeometry(window)
            settle()
            laid_out()
        self.assertEqual(shifts_of(asm), before, "back at the first size, not laid out as first")

    def test_a_change_of_projection_lays_the_markers_out_and_watches_the_new_camera(self):
        """FreeCAD makes a new camera for perspective: the layout watched the old one, so no zoom
        of the new one laid the markers out. Now the switch lays them out, and so does a zoom."""
        (asm, *_), view = self.crowded_fourbar()
        proxy = asm.ViewObject.Proxy
        try:
            view.setCameraType("Perspective")
            settle()
            laid_out()
            camera = view.getCameraNode()
            self.assertFalse(proxy.laid_for[2], "the layout still counts an orthographic camera")
            self.assertEqual(proxy.camera.getTypeId().getName(), camera.getTypeId().getName())
            # Closer along the line of sight (a zoom of the new camera, nothing else told).
            rot = camera.orientation.getValue()
            ahead = App.Vector(*rot.multVec(coin_vec(App.Vector(0, 0, -1))).getValue())
            eye = App.Vector(*camera.position.getValue().getValue())
            before = shifts_of(asm)
            camera.position.setValue(coin_vec(eye + ahead * (0.6 * camera.focalDistance.getValue())))
            laid_out()
            zoomed = shifts_of(asm)
            self.assertNotEqual(zoomed, before, "the zoom of the perspective camera was not laid out")
            proxy.restack()
            self.assertEqual(shifts_of(asm), zoomed)
        finally:
            view.setCameraType("Orthographic")
            settle()
            laid_out()
        self.assertTrue(proxy.laid_for[2])

    def test_a_deleted_parts_joints_are_not_drawn_and_come_back_with_its_undo(self):
        """The fourth audit: the rack deleted, its joints' markers stayed where it had been, in
        the air. The coupler deleted (part 2 of Crank-Coupler, part 1 of Coupler-Rocker): both
        markers hidden, the other two drawn as before; an undo of the delete draws them again at
        their joints."""
        from dispcon_fc import markers, objects, viewproviders

        (asm, g, crank, coupler, rocker), view = self.crowded_fourbar()
        Gui.SendMsgToActiveView("ViewFit")
        laid_out()
        js = objects.joints(asm)
        gone = [j for j in js if coupler in (j.Reference1[0], j.Reference2[0])]
        self.assertEqual(len(gone), 2)
        marks = {j.Name: viewproviders.joint_view(j).marker for j in js}
        every = orange_count(view, "_all")
        for j in gone:
            marks[j.Name].set_visible(False)
        settle()
        without = orange_count(view, "_without")
        for j in gone:
            marks[j.Name].set_visible(True)
        settle()
        self.assertLess(without, 0.75 * every, "the two markers are not half the orange (%d of %d)" % (without, every))
        self.doc.openTransaction("Delete")
        self.doc.removeObject(coupler.Name)
        self.doc.commitTransaction()
        settle()
        laid_out()
        for j in js:
            self.assertEqual(marks[j.Name].is_visible(), j not in gone, j.Label)
        deleted = orange_count(view, "marker-part-deleted")
        shot("markers-part-deleted", view)
        self.assertLess(abs(deleted - without), 0.1 * every,
                        "drawn after the delete: %d orange pixels, %d without the two markers" % (deleted, without))
        self.doc.undo()
        settle()
        laid_out()
        self.assertIsNotNone(self.doc.getObject(coupler.Name), "the undo did not bring the coupler back")
        for j in js:
            self.assertTrue(marks[j.Name].is_visible(), "%s not drawn after the undo" % j.Label)
            at = App.Vector(*marks[j.Name].transform.translation.getValue().getValue())
            self.assertLess((at - markers.joint_frame(j)[0]).Length, 1e-6, j.Label)  # (Coin keeps floats)
        again = orange_count(view, "marker-part-undeleted")
        self.assertLess(abs(again - every), 0.1 * every, "after the undo: %d orange pixels, %d before" % (again, every))


def fourbar_in(doc):
    """test_headless's four-bar made in `doc` (its parts' STEP files in a folder of their own):
    the assembly."""
    from test_headless import fourbar

    return fourbar(doc, tempfile.mkdtemp())[0]


def headless_fourbar(path):
    """A four-bar built and saved by freecadcmd (no view state in the file, as the samples)."""
    import subprocess

    script = path + ".py"
    with open(script, "w") as f:
        f.write(HEADLESS_FOURBAR % (HERE, os.path.dirname(path), path))
    run = subprocess.run(["freecadcmd", script], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         text=True, timeout=300)
    if not os.path.isfile(path):
        raise AssertionError("freecadcmd did not save %s:\n%s" % (path, run.stdout[-2000:]))
    return path


def tree_icon(label):
    """The icon the model tree shows beside `label`, as a 16x16 image (None when not listed)."""
    for tree in mw().findChildren(QtWidgets.QTreeWidget):
        items = tree.findItems(label, QtCore.Qt.MatchExactly | QtCore.Qt.MatchRecursive, 0)
        if items:
            return items[0].icon(0).pixmap(16, 16).toImage()
    return None


class TestTreeIcons(Documents):
    def test_parts_and_grounded_parts_have_their_icons(self):
        from dispcon_fc import operations
        from dispcon_fc.viewproviders import icon
        import parts

        asm = operations.create_assembly(self.doc)
        step = parts.write_step(parts.link(1.0), os.path.join(tempfile.mkdtemp(), "link.step"))
        link = operations.import_part(asm, step, "Crank link")
        post = operations.import_part(asm, step, "Post", grounded=True)
        self.assertEqual(link.TypeId, "Part::FeaturePython")
        settle()

        def shows(label, name):
            """The tree shows icon `name` beside `label`: nearly every pixel as the icon's own
            (the tree may scale it a little), and not the part's other icon. The tree redraws
            its icons on a timer: given up to 3 s."""
            other = {"Part": "GroundedPart", "GroundedPart": "Part"}[name]

            def differing(image, which):
                want = QtGui.QIcon(icon(which)).pixmap(16, 16).toImage()
                return sum(1 for x in range(16) for y in range(16)
                           if max(abs(a - b) for a, b in zip(QtGui.QColor(image.pixel(x, y)).getRgb(),
                                                             QtGui.QColor(want.pixel(x, y)).getRgb())) > 48)

            for _ in range(30):
                image = tree_icon(label)
                self.assertIsNotNone(image, "%s is not in the tree" % label)
                if differing(image, name) < 13:
                    break
                time.sleep(0.1)
                settle()
            self.assertLess(differing(image, name), 13, "%s does not show the %s icon" % (label, name))
            self.assertGreater(differing(image, other), 25, "%s shows the %s icon" % (label, other))

        shows("Crank link", "Part")
        shows("Post", "GroundedPart")
        operations.set_grounded(link, True)
        settle()
        shows("Crank link", "GroundedPart")
        operations.set_grounded(link, False)
        settle()
        shows("Crank link", "Part")
        for tree in mw().findChildren(QtWidgets.QTreeWidget):
            tree.expandAll()
        shot("tree-icons")
        # The shape is drawn as any part's, and it is kept through a save and a reopen.
        path = os.path.join(tempfile.mkdtemp(), "parts.FCStd")
        volume = link.Shape.Volume
        self.doc.saveAs(path)
        App.closeDocument(self.doc.Name)
        self.doc = App.openDocument(path)
        settle()
        again = self.doc.getObjectsByLabel("Crank link")[0]
        self.assertAlmostEqual(again.Shape.Volume, volume, places=9)
        shows("Post", "GroundedPart")
        self.assertFalse(Gui.getDocument(self.doc.Name).Modified)


class TestRestored(unittest.TestCase):
    """Documents saved by freecadcmd, opened in the GUI: markers drawn, nothing modified."""

    @contextlib.contextmanager
    def opened(self, name):
        """A four-bar solved and saved by freecadcmd, opened in the GUI and unmodified: (its
        document, its GUI document); closed after."""
        close_dialog()
        doc = App.openDocument(headless_fourbar(os.path.join(tempfile.mkdtemp(), name)))
        try:
            settle()
            gui_doc = Gui.getDocument(doc.Name)
            self.assertFalse(gui_doc.Modified, "opening the document marked it modified")
            yield doc, gui_doc
        finally:
            App.closeDocument(doc.Name)
            settle()

    def test_a_headless_document_shows_its_markers_unmodified(self):
        from pivy import coin
        from dispcon_fc import objects, viewproviders

        with self.opened("headless-fourbar.FCStd") as (doc, gui_doc):
            self.assertFalse(doc.isTouched(), "opening the document touched it")
            asm = next(o for o in doc.Objects if objects.is_assembly(o))
            self.assertTrue(asm.ViewObject.Visibility)
            self.assertTrue(all(p.ViewObject.Visibility for p in objects.parts(asm)), "parts hidden on open")
            root = gui_doc.ActiveView.getSceneGraph()
            for j in objects.joints(asm):
                self.assertIsNotNone(viewproviders.joint_view(j), "%s has no view provider" % j.Label)
                self.assertEqual(j.ViewObject.DisplayMode, "Marker")
                search = coin.SoSearchAction()
                search.setName("dispcon_marker_" + j.Name)
                search.apply(root)
                self.assertIsNotNone(search.getPath(), "no marker for %s in the scene" % j.Label)
            gui_doc.ActiveView.viewIsometric()
            gui_doc.ActiveView.fitAll()
            shot("headless-opened")
            self.assertFalse(gui_doc.Modified)
            # The commands, not active while the document was being restored, are once it is.
            Gui.Selection.clearSelection()
            Gui.Selection.addSelection(asm)
            settle()
            self.assertTrue(Gui.isCommandActive("Dispcon_Solve"), "Solve is greyed out after the open")
            solve = [a for a in mw().findChildren(QtWidgets.QAction) if a.objectName() == "Dispcon_Solve"]
            t0 = time.perf_counter()
            while not all(a.isEnabled() for a in solve) and time.perf_counter() - t0 < 5:
                settle()
            self.assertTrue(solve and all(a.isEnabled() for a in solve), "Solve's button is greyed out after the open")
            Gui.Selection.clearSelection()

    def test_a_restored_document_places_each_marker_once(self):
        """FreeCAD restoring a document calls each joint's updateData for every property, seven
        of which placed its marker (1,226 placements and a layout during the restore for the
        100-part chain's 147 joints: docs/performance.md); now the layout once the restore is
        over places each marker once, where its joint is, drawn (hidden until then). Both ways of
        opening: a document saved with the GUI (view providers restored with it) and one saved by
        freecadcmd (given theirs while it restores)."""
        from dispcon_fc import markers, objects, operations, viewproviders

        saved = os.path.join(tempfile.mkdtemp(), "gui-fourbar.FCStd")
        doc = App.newDocument("guifourbar")
        asm = fourbar_in(doc)
        self.assertTrue(operations.solve(asm).converged)
        doc.saveAs(saved)
        App.closeDocument(doc.Name)
        settle()
        for path in (saved, headless_fourbar(os.path.join(tempfile.mkdtemp(), "headless.FCStd"))):
            placed, laid = [], []
            place, lay_out = markers.Marker.set_placement, viewproviders.ViewProviderAssembly._lay_out

            def counting_place(marker, placement):
                placed.append(marker.root.getName().getString())
                return place(marker, placement)

            def counting_lay_out(view, *args):
                laid.append(view.Object.Document.Restoring)
                return lay_out(view, *args)

            markers.Marker.set_placement = counting_place
            viewproviders.ViewProviderAssembly._lay_out = counting_lay_out
            try:
                doc = App.openDocument(path)
                settle()
            finally:
                markers.Marker.set_placement = place
                viewproviders.ViewProviderAssembly._lay_out = lay_out
            try:
                asm = next(o for o in doc.Objects if objects.is_assembly(o))
                joints = objects.joints(asm)
                self.assertEqual(sorted(placed), sorted("dispcon_marker_" + j.Name for j in joints),
                                 "%s: not each marker placed once" % os.path.basename(path))
                # Laid out once the restore ended (again when the view's camera then moves).
                self.assertTrue(laid and True not in laid, "%s: laid out during the restore (%s)"
                                % (os.path.basename(path), laid))
                for j in joints:
                    marker = viewproviders.joint_view(j).marker
                    self.assertTrue(marker.is_visible(), "%s's marker is hidden" % j.Label)
                    at = App.Vector(*marker.transform.translation.getValue().getValue())
                    self.assertLess((at - markers.joint_placement(j).Base).Length, 1e-5, j.Label)  # (floats in Coin)
            finally:
                App.closeDocument(doc.Name)
                settle()

    def test_solve_on_a_solved_document_leaves_it_unmodified(self):
        from dispcon_fc.adapter import ALREADY_HELD

        with self.opened("solved-fourbar.FCStd") as (doc, gui_doc):
            asm = next(o for o in doc.Objects if "LastSolve" in o.PropertiesList)
            last = asm.LastSolve
            Gui.runCommand("Dispcon_Solve")
            settle()
            self.assertIn("%s: %s" % (asm.Label, ALREADY_HELD), mw().statusBar().currentMessage())
            self.assertFalse(gui_doc.Modified, "a Solve that moved nothing marked the document modified")
            self.assertEqual(asm.LastSolve, last)
            # A part pulled off its joint: Solve still writes what it moved, and says so.
            coupler = doc.getObjectsByLabel("Coupler")[0]
            off = App.Placement(App.Vector(1.2, 0.6, -0.1), App.Rotation(App.Vector(0, 0, 1), 11))
            coupler.Placement = off
            Gui.runCommand("Dispcon_Solve")
            settle()
            self.assertGreater((coupler.Placement.Base - off.Base).Length, 0.1)
            self.assertRegex(asm.LastSolve, r"^solved in \d+ iterations?$")
            self.assertIn("%s: %s" % (asm.Label, asm.LastSolve), mw().statusBar().currentMessage())


def picking_panel(kind="Revolute", picks=()):
    """The joint panel of a `kind` joint opened with `picks` ((object, element) pairs) selected,
    as a designer's clicks before the command; none: the panel picking."""
    from dispcon_fc.panels import joint as jp

    Gui.Selection.clearSelection()
    for pick in picks:
        Gui.Selection.addSelection(*pick)
    Gui.runCommand("Dispcon_Joint" + kind)
    settle()
    return jp.current()


class TestJointPanel(Documents):
    def open(self, kind="Revolute"):
        asm, base, arm, e1, e2 = self.arm()
        panel = picking_panel(kind, (e1, e2))
        self.assertIsNotNone(panel, "the joint panel did not open")
        self.assertTrue(Gui.Control.activeDialog())
        return panel, asm, base, arm

    def visible_groups(self, panel):
        return {n for n, g in panel.groups.items() if g.isVisibleTo(panel.form)}

    def test_the_message_is_in_view_and_every_field_has_a_tooltip(self):
        # At 1280x900 the panel of a type with many fields is taller than the Combo View: what to
        # pick next (or what is wrong) is read without scrolling, and every field says what it is.
        from dispcon_fc.panels import joint as jp

        mw().setGeometry(0, 0, 1280, 900)
        panel, asm, base, arm = self.open("Revolute")
        scroll = panel.form.parentWidget()
        while scroll is not None and not isinstance(scroll, QtWidgets.QScrollArea):
            scroll = scroll.parentWidget()
        self.assertIsNotNone(scroll, "the panel is in no scroll area")
        for kind in ("Cylindrical", "Screw", "Revolute"):
            panel.type_box.setCurrentText(kind)
            settle()
            panel._start_picking()
            settle()
            scroll.verticalScrollBar().setValue(0)
            settle()
            self.assertIn("Pick", panel.message.text(), kind)
            viewport = scroll.viewport()
            top = panel.message.mapTo(viewport, QtCore.QPoint(0, 0)).y()
            self.assertGreaterEqual(top, 0, kind)
            self.assertLessEqual(top + panel.message.height(), viewport.height(),
                                 "%s: the message is below the fold (%d + %d px in a %d px view)"
                                 % (kind, top, panel.message.height(), viewport.height()))
            self.assertLess(top, panel.groups["reverse"].mapTo(viewport, QtCore.QPoint(0, 0)).y(), kind)
            # Nothing of it cut off on the right (a coupling's long phase line widened it).
            self.assertLessEqual(panel.form.minimumSizeHint().width(), viewport.width(),
                                 "%s: the panel is wider than the Combo View" % kind)
            self.assertLessEqual(panel.form.width(), viewport.width(), kind)
            shot("panel-message-%s" % kind.lower())
            untipped = [w.objectName() or type(w).__name__ + ":" + getattr(w, "text", lambda: "")()
                        for w in panel.form.findChildren(QtWidgets.QWidget)
                        if isinstance(w, (QtWidgets.QCheckBox, QtWidgets.QAbstractSpinBox, QtWidgets.QComboBox,
                                          QtWidgets.QPushButton))
                        and w.isVisibleTo(panel.form) and not w.toolTip().strip()
                        and not isinstance(w.parentWidget(), QtWidgets.QAbstractSpinBox)]
            self.assertEqual(untipped, [], "%s: fields without a tooltip" % kind)
        self.assertIs(jp.current(), panel)

    def test_fields_per_type_and_units(self):
        panel, asm, base, arm = self.open("Revolute")
        self.assertEqual(self.visible_groups(panel), {"reverse", "offset", "frame", "rotation", "twist"})
        self.assertIn("°", panel.rot_min.text())
        self.assertIn("mm", panel.offset.text())
        self.assertEqual(panel.ref_list.count(), 2)
        self.assertIn("Base", panel.ref_list.item(0).text())
        self.assertIn("Arm", panel.ref_list.item(1).text())
        shot("panel-revolute")
        for kind, groups in (("Slider", {"reverse", "frame", "travel", "twist"}), ("Fixed", {"reverse", "offset", "frame", "twist"}),
                             ("Cylindrical", {"reverse", "frame", "rotation", "travel", "twist"}),
                             ("Ball", {"offset", "cone"}),
                             ("PointOnCurve", set()), ("Angle", {"reverse", "angle"})):
            panel.type_box.setCurrentText(kind)
            settle()
            self.assertEqual(self.visible_groups(panel), groups, kind)
        panel.type_box.setCurrentText("Revolute")
        # It fits the Combo View: nothing of it is cut off.
        task = panel.form.parentWidget()
        while task is not None and task.width() < 50:
            task = task.parentWidget()
        self.assertLessEqual(panel.form.minimumSizeHint().width(), panel.form.width(),
                             "the panel is wider than the Combo View")
        ok = panel.ok_button()
        self.assertIsNotNone(ok)
        self.assertTrue(ok.isVisible())
        self.assertGreaterEqual(ok.parentWidget().width(), ok.parentWidget().minimumSizeHint().width())

    def test_twist_from_in_the_panel(self):
        # A Fixed made on the arm turned 20 degrees about its pin: the panel's Twist from says
        # "Picked frames" (a new joint's), its tooltip says what each choice means, and the
        # preview stands the arm square on the base (the pins' circles' frames lined up). "Pose
        # when made" chosen: the joint's TwistFrom (at the engine's door first), the arm turned
        # back as it stood when the joint was made; OK keeps it.
        from dispcon_fc import objects

        panel, asm, base, arm = self.open("Fixed")
        j = panel.joint
        self.assertIn("twist", self.visible_groups(panel))
        self.assertEqual(panel.twist.currentText(), objects.PICKED_FRAMES)
        self.assertEqual([panel.twist.itemText(k) for k in range(panel.twist.count())], list(objects.TWIST_FROM))
        for words in ("Picked frames", "Pose when made", "whatever pose", "turn limits"):
            self.assertIn(words, panel.twist.toolTip())
        self.assertEqual(j.TwistFrom, objects.PICKED_FRAMES)
        self.assertNotIn("cc0000", panel.message.styleSheet(), panel.message.text())
        self.assertLess(arm.Placement.Rotation.Angle, 1e-8, arm.Placement)
        shot("panel-twist-from")
        panel.twist.setCurrentText(objects.POSE_WHEN_MADE)
        settle()
        self.assertNotIn("cc0000", panel.message.styleSheet(), panel.message.text())
        self.assertEqual(j.TwistFrom, objects.POSE_WHEN_MADE)
        # The turn the arm had when the panel made the joint, 20 degrees about its pin, held.
        turn = arm.Placement.Rotation
        self.assertLess(abs(abs(math.degrees(turn.Angle)) - 20.0), 1e-6, arm.Placement)
        self.assertLess(abs(abs(turn.Axis.z) - 1.0), 1e-9, arm.Placement)
        # A Revolute counts its turn limits from it (shown, the choice kept; the limits' tooltips
        # say so); a Planar measures no turn: hidden.
        panel.type_box.setCurrentText("Revolute")
        settle()
        self.assertIn("twist", self.visible_groups(panel))
        self.assertEqual((j.JointType, panel.twist.currentText()), ("Revolute", objects.POSE_WHEN_MADE))
        self.assertIn("Twist from", panel.rot_min.toolTip())
        panel.type_box.setCurrentText("Planar")
        settle()
        self.assertNotIn("twist", self.visible_groups(panel))
        panel.type_box.setCurrentText("Fixed")
        settle()
        panel.ok_button().click()
        settle()
        self.assertEqual((j.JointType, j.TwistFrom), ("Fixed", objects.POSE_WHEN_MADE))

    def test_part_2s_frame_turned_in_the_panel(self):
        # The rotation offset of part 2's joint frame, in degrees: a pitch of 90 stands the arm's
        # pin axis across the base's at the preview's solve; OK keeps it, saved with the joint.
        panel, asm, base, arm = self.open("Revolute")
        j = panel.joint
        for box in panel.frame:
            self.assertIn("°", box.text())
        panel.frame[1].setProperty("rawValue", 90.0)
        settle()
        self.assertNotIn("cc0000", panel.message.styleSheet(), panel.message.text())
        self.assertEqual(j.FramePitch.Value, 90.0)
        a1 = base.Placement.Rotation.multVec(j.Axis1)
        a2 = arm.Placement.Rotation.multVec(j.Axis2)
        self.assertLess(abs(a1.dot(a2)) / (a1.Length * a2.Length), 1e-8)
        shot("panel-frame-pitch")
        panel.ok_button().click()
        settle()
        self.assertEqual((j.FrameYaw.Value, j.FramePitch.Value, j.FrameRoll.Value), (0.0, 90.0, 0.0))

    def test_part_2s_frame_moved_in_the_panel(self):
        # The translation offset of part 2's joint frame, in mm: moved 0.3 along the frame's y,
        # the arm's picked pin stands 0.3 off the base's axis at the preview's solve; OK keeps it.
        panel, asm, base, arm = self.open("Revolute")
        j = panel.joint
        self.assertEqual([box.objectName() for box in panel.shift], ["frameX", "frameY"])
        for box in panel.shift:
            self.assertIn("mm", box.text())
            self.assertTrue(box.isVisible())
        panel.shift[1].setProperty("rawValue", 0.3)
        settle()
        self.assertNotIn("cc0000", panel.message.styleSheet(), panel.message.text())
        self.assertEqual((j.FrameX.Value, j.FrameY.Value), (0.0, 0.3))
        point = base.Placement.multVec(j.Point1)
        z = base.Placement.Rotation.multVec(j.Axis1).normalize()
        off = arm.Placement.multVec(j.Point2) - point
        self.assertAlmostEqual((off - z * off.dot(z)).Length, 0.3, delta=1e-8)
        shot("panel-frame-moved")
        panel.ok_button().click()
        settle()
        self.assertEqual((j.FrameX.Value, j.FrameY.Value), (0.0, 0.3))

    def test_min_above_max_refused_in_the_panel(self):
        panel, asm, base, arm = self.open("Revolute")
        panel.has_rotation.setChecked(True)
        panel.rot_min.setProperty("rawValue", 40.0)
        panel.rot_max.setProperty("rawValue", 10.0)
        settle()
        self.assertIn("above max", panel.message.text())
        self.assertFalse(panel.ok_button().isEnabled(), "OK stays enabled with min above max")
        shot("panel-min-above-max")
        self.assertFalse(panel.accept())
        self.assertTrue(Gui.Control.activeDialog(), "the panel closed with min above max")
        panel.rot_max.setProperty("rawValue", 60.0)
        settle()
        self.assertTrue(panel.ok_button().isEnabled())
        panel.ok_button().click()
        settle()
        j = [o for o in asm.Group if hasattr(o, "JointType")][0]
        self.assertAlmostEqual(j.RotationMax.Value, 60.0)
        self.assertTrue(j.HasRotationLimits)

    def test_preview_moves_the_parts_and_cancel_removes_the_joint(self):
        panel, asm, base, arm = self.open("Revolute")
        start = App.Placement(App.Vector(0.3, 0.2, 0.4), App.Rotation(App.Vector(0, 0, 1), 20))
        # Snapped as soon as the two references were picked: the arm's pin is on the base's.
        self.assertLess(arm.Placement.Base.Length, 1e-6, "the preview did not snap the arm")
        # An offset moves it along the axis at once.
        panel.offset.setProperty("rawValue", 0.5)
        settle()
        self.assertAlmostEqual(arm.Placement.Base.z, 0.5, places=6)
        panel.reverse.setChecked(True)
        settle()
        z = arm.Placement.Rotation.multVec(App.Vector(0, 0, 1))
        self.assertLess(z.z, -0.999, "reverse did not flip the arm")
        shot("panel-preview")
        count = len(asm.Group)
        Gui.Control.activeDialog() and panel.reject()
        settle()
        self.assertEqual(len(asm.Group), count - 1, "Cancel kept the new joint")
        self.assertFalse([o for o in self.doc.Objects if hasattr(o, "JointType")])
        self.assertTrue(same(arm.Placement, start), "Cancel left the arm moved")

    def test_double_click_edits_and_cancel_restores(self):
        from dispcon_fc import operations

        asm, base, arm, e1, e2 = self.arm()
        j = operations.add_joint(asm, "Revolute", e1, e2, rotation=(-10, 10))
        operations.solve(asm)
        before = arm.Placement
        # A double-click in the tree goes to the view provider's doubleClicked.
        self.assertTrue(j.ViewObject.Proxy.doubleClicked(j.ViewObject))
        settle()
        from dispcon_fc.panels import joint as jp

        panel = jp.current()
        self.assertIs(panel.joint, j)
        self.assertTrue(panel.has_rotation.isChecked())
        panel.rot_max.setProperty("rawValue", 20.0)
        panel.offset.setProperty("rawValue", 0.3)
        settle()
        self.assertAlmostEqual(j.RotationMax.Value, 20.0)
        self.assertAlmostEqual(arm.Placement.Base.z, 0.3, places=6)
        panel.reject()
        settle()
        self.assertAlmostEqual(j.RotationMax.Value, 10.0)
        self.assertTrue(same(arm.Placement, before))

    def test_picking_in_the_panel(self):
        asm, base, arm, e1, e2 = self.arm()
        panel = picking_panel()
        self.assertTrue(panel.picking)
        self.assertIn("circular", panel.message.text())
        # Nothing to keep yet: OK is greyed out until the joint is made, and there is nothing
        # to pick "again".
        self.assertFalse(panel.ok_button().isEnabled(), "OK is enabled before anything is picked")
        self.assertFalse(panel.pick_button.isEnabled())
        Gui.Selection.addSelection(*e1)
        settle()
        self.assertFalse(panel.ok_button().isEnabled(), "OK is enabled with one reference")
        self.assertTrue(panel.pick_button.isEnabled())
        Gui.Selection.addSelection(*e2)
        settle()
        self.assertFalse(panel.picking)
        self.assertIsNotNone(panel.joint)
        self.assertTrue(panel.ok_button().isEnabled())
        self.assertLess(arm.Placement.Base.Length, 1e-6)
        panel.ok_button().click()
        settle()
        self.assertEqual(len([o for o in asm.Group if hasattr(o, "JointType")]), 1)


    def test_opening_a_panel_while_another_is_picking(self):
        # Regression: the second pick schedules the joint's creation on a timer; a panel opened
        # before it ran (a double-click, another joint command) closed the first panel's dialog
        # only, and the timer then read the first panel's deleted spin boxes ("Internal C++
        # object (QAbstractSpinBox) already deleted", seen under load).
        from dispcon_fc.panels import joint as jp

        asm, base, arm, e1, e2 = self.arm()
        Gui.Selection.clearSelection()
        Gui.runCommand("Dispcon_JointRevolute")
        settle()
        first = jp.current()
        errors = []
        hook = sys.excepthook
        sys.excepthook = lambda *exc: errors.append("".join(traceback.format_exception(*exc)))
        try:
            Gui.Selection.addSelection(*e1)
            Gui.Selection.addSelection(*e2)  # the timer is set, not yet run
            second = jp.open_panel(asm=asm, joint_type="Slider")
            settle()
        finally:
            sys.excepthook = hook
        self.assertEqual(errors, [])
        self.assertTrue(first.closed)
        self.assertIs(jp.current(), second)
        self.assertFalse([o for o in self.doc.Objects if hasattr(o, "JointType")],
                         "the first panel made its joint after it was closed")
        self.assertEqual(jp.raw(second.rot_min), 0.0)  # its widgets are alive
        self.assertTrue(second.picking)
        second.reject()

    def test_pick_again_takes_new_references(self):
        from dispcon_fc import objects
        import parts

        panel, asm, base, arm = self.open("Revolute")
        joint = panel.joint
        label = joint.Label
        far = (arm, parts.circle_edge(arm.Shape, App.Vector(1.5, 0, 0)))
        base_pin = (base, parts.circle_edge(base.Shape, App.Vector(0, 0, 0)))
        QtCore.QTimer.singleShot(0, panel.pick_button.click)  # clicked as a person clicks it
        settle()
        self.assertTrue(panel.picking)
        self.assertEqual(panel.ref_list.count(), 0)
        self.assertIn("circular", panel.message.text())
        Gui.Selection.addSelection(*base_pin)
        Gui.Selection.addSelection(*far)
        settle()
        self.assertFalse(panel.picking)
        self.assertEqual(panel.ref_list.count(), 2)
        self.assertIn(far[1], panel.ref_list.item(1).text())
        js = objects.joints(asm)
        self.assertEqual(len(js), 1, "Pick again kept the old joint")
        self.assertEqual(js[0].Label, label)
        self.assertEqual(js[0].Reference2[1], [far[1]])
        # The preview snapped the arm's far pin onto the base's pin.
        self.assertLess(arm.Placement.multVec(App.Vector(1.5, 0, 0)).Length, 1e-6)
        panel.ok_button().click()
        settle()
        self.assertEqual(len(objects.joints(asm)), 1)


class TestErrors(Documents):
    def test_failed_solve_names_and_marks_the_conflicting_joint(self):
        from dispcon_fc import objects, operations, viewproviders
        import parts

        asm, g, crank, coupler, rocker = self.fourbar()
        operations.solve(asm)
        # A fifth joint that cannot hold: the crank's far pin on the ground's second pin.
        bad = operations.add_joint(asm, "Revolute",
                                   (g, parts.circle_edge(g.Shape, App.Vector(3, 0, 0))),
                                   (crank, parts.circle_edge(crank.Shape, App.Vector(1, 0, 0))))
        bad.Label = "Impossible pin"
        lines_before = [(p.ViewObject.LineWidth, tuple(p.ViewObject.LineColor)) for p in objects.parts(asm)]
        placements = [p.Placement for p in objects.parts(asm)]
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(asm)
        Gui.runCommand("Dispcon_Solve")
        settle()
        status = mw().statusBar().currentMessage()
        self.assertIn("Impossible pin", status)
        panel_text = gui_text(Gui.Control.activeDialog() and mw())
        self.assertIn("Impossible pin", panel_text)
        self.assertEqual(viewproviders.joint_view(bad).marker.look, "error")
        for j in objects.joints(asm):
            if j != bad:
                self.assertEqual(viewproviders.joint_view(j).marker.look, "normal", j.Label)
        self.assertEqual(lines_before, [(p.ViewObject.LineWidth, tuple(p.ViewObject.LineColor))
                                        for p in objects.parts(asm)], "Solve changed how parts look")
        self.assertTrue(all(same(p.Placement, q, 1e-12) for p, q in zip(objects.parts(asm), placements)))
        shot("solve-failed")
        close_dialog()
        # Fixed: the joint goes, Solve succeeds and the highlight clears.
        self.doc.removeObject(bad.Name)
        Gui.Selection.addSelection(asm)
        Gui.runCommand("Dispcon_Solve")
        settle()
        for j in objects.joints(asm):
            self.assertEqual(viewproviders.joint_view(j).marker.look, "normal", j.Label)
        self.assertNotIn("Impossible", mw().statusBar().currentMessage())


    def test_a_joint_whose_part_was_deleted_opens_to_be_picked_again_and_check_lists_it(self):
        """The fourth audit: the rack deleted, a double-click on its Slider raised a traceback in
        the Report view (its reference is None) and opened no panel, its transaction left open;
        the Check panel said nothing of the two joints it left out."""
        from dispcon_fc import operations, panels
        from dispcon_fc.panels import joint as jp
        from dispcon_fc.panels.check import CheckPanel
        import parts

        asm = operations.create_assembly(self.doc)
        base, arm = base_and_arm(asm)
        j = operations.add_joint(asm, "Revolute", (base, parts.circle_edge(base.Shape, App.Vector(0, 0, 0))),
                                 (arm, parts.circle_edge(arm.Shape, App.Vector(0, 0, 0))))
        j.Label = "Base-Arm"
        self.doc.removeObject(arm.Name)
        settle()
        said = len(report_view_text())
        j.ViewObject.Proxy.doubleClicked(j.ViewObject)
        settle()
        panel = jp.current()
        self.assertIsNotNone(panel, "no panel opened")
        self.assertNotIn("Traceback", report_view_text()[said:])
        self.assertTrue(panel.picking)
        self.assertIn("Base-Arm lost a part (deleted): pick two circular edges", panel.message.text())
        self.assertFalse(panel.ok_button().isEnabled())
        shot("panel-joint-part-deleted")
        panel.reject()
        settle()
        self.assertIsNotNone(self.doc.getObject(j.Name), "Cancel deleted the joint")
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(asm)
        action("Dispcon_Check").trigger()
        settle()
        check = panels.current(CheckPanel)
        self.assertIsNotNone(check)
        self.assertIn("left out: Base-Arm: a part each holds was deleted",
                      check.form.findChild(QtWidgets.QTextEdit).toPlainText().replace("\n", " "))
        check.reject()

    def test_a_failed_solve_is_no_undo_step_and_saved_reopens_untouched(self):
        """The third audit: a failed Solve left "Solve assembly" in the undo list (the marks,
        Residual and LastSolve it wrote) so the first Ctrl+Z took those back, not the joint; and
        the document saved after it reopened with its Assembly touched. Now the failure writes
        nothing: the undo list, the document's modified flag and every object's state are as they
        were, the red mark and the message are the view's, and Ctrl+Z takes back the joint."""
        from dispcon_fc import objects, operations, viewproviders
        import parts

        asm, g, crank, coupler, rocker = self.fourbar()
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(asm)
        Gui.runCommand("Dispcon_Solve")
        settle()
        close_dialog()
        bad = operations.add_joint(asm, "Revolute",
                                   (g, parts.circle_edge(g.Shape, App.Vector(3, 0, 0))),
                                   (crank, parts.circle_edge(crank.Shape, App.Vector(1, 0, 0))))
        bad.Label = "Rod-to-ground"
        name = bad.Name
        self.doc.recompute()
        tmp = tempfile.mkdtemp()
        self.doc.saveAs(os.path.join(tmp, "conflict.FCStd"))
        gui_doc = Gui.getDocument(self.doc.Name)
        Gui.SendMsgToActiveView("Save")  # the GUI's save: its document no longer modified
        settle()
        self.assertFalse(gui_doc.Modified)
        undo_names = list(self.doc.UndoNames)
        self.assertEqual(undo_names[0], "Add joint", undo_names)
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(asm)
        Gui.runCommand("Dispcon_Solve")
        settle()
        self.assertIn("Rod-to-ground", mw().statusBar().currentMessage())
        self.assertIn("Rod-to-ground", gui_text(Gui.Control.activeDialog() and mw()))
        self.assertEqual(list(self.doc.UndoNames), undo_names, "the failed Solve left an undo step")
        self.assertFalse(gui_doc.Modified, "the failed Solve marked the document modified")
        self.assertEqual([o.Name for o in self.doc.Objects if "Touched" in o.State], [])
        self.assertEqual(viewproviders.joint_view(bad).marker.look, "error")
        close_dialog()
        self.assertEqual(viewproviders.joint_view(bad).marker.look, "error", "the mark went before the next solve")
        App.setActiveDocument(self.doc.Name)
        Gui.runCommand("Std_Undo")
        settle()
        self.assertIsNone(self.doc.getObject(name), "Ctrl+Z did not take back the joint")
        self.assertEqual(len(objects.joints(asm)), 4)
        # Saved after the undo (which touched the Assembly: its Group) and reopened, as the audit
        # did: nothing touched, nothing modified.
        saved = os.path.join(tmp, "after-undo.FCStd")
        self.doc.saveCopy(saved)
        reopened = App.openDocument(saved)
        try:
            settle()
            self.assertEqual([o.Name for o in reopened.Objects if "Touched" in o.State], [])
            self.assertFalse(Gui.getDocument(reopened.Name).Modified)
        finally:
            App.closeDocument(reopened.Name)
            settle()


    def test_a_marker_in_error_stays_where_the_layout_puts_it(self):
        """The third audit: the conflicting joint's red marker sat about 150 px from its joint at
        fit-all zoom. A stacked marker is set beside the first at its place (markers.stacks) and
        the layout may push it further (spread); the error look's half-again scale came before
        that shift in the scene, so a marker in error went half as far again from its joint as
        the layout put it. Its red centre on the screen is now its joint's projected point and
        the layout's shift, to a few pixels."""
        from dispcon_fc import markers, objects, operations, viewproviders
        import parts

        asm, g, crank, coupler, rocker = self.fourbar()
        operations.solve(asm)
        # On the ground's second pin, where the rocker's revolute is: the second of that stack.
        bad = operations.add_joint(asm, "Revolute",
                                   (g, parts.circle_edge(g.Shape, App.Vector(3, 0, 0))),
                                   (crank, parts.circle_edge(crank.Shape, App.Vector(1, 0, 0))))
        view = self.view()
        view.viewTop()
        Gui.SendMsgToActiveView("ViewFit")
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(asm)
        Gui.runCommand("Dispcon_Solve")
        settle()
        close_dialog()
        for j in objects.joints(asm):
            if j != bad:
                j.ViewObject.Visibility = False
        for _ in range(5):  # the layout once the camera rests
            time.sleep(0.1)
            settle()
        marker = viewproviders.joint_view(bad).marker
        self.assertEqual(marker.look, "error")
        shift = marker.offset_units().Length * markers.PIXELS
        self.assertGreater(shift, 20, "the stacked marker was not set apart")
        width, height = view.getSize()

        def drawn(name, colour):
            """The centre and the width of what is drawn in `colour` ("red", "orange") in pixels."""
            path = os.path.join(OUT, name + ".png")
            view.saveImage(path, width, height, "White")
            img = QtGui.QImage(path)
            hit = []
            for x in range(width):
                for y in range(height):
                    c = QtGui.QColor(img.pixel(x, y))
                    if c.red() > 200 and c.blue() < 70 and (c.green() < 70 if colour == "red" else 60 < c.green() < 170):
                        hit.append((x, y))
            self.assertTrue(hit, "nothing %s drawn in %s" % (colour, path))
            xs, ys = [x for x, _ in hit], [y for _, y in hit]
            return sum(xs) / len(xs), sum(ys) / len(ys), max(xs) - min(xs)

        rx, ry, red_across = drawn("marker-error-place", "red")
        marker.set_look("normal")
        settle()
        ox, oy, orange_across = drawn("marker-normal-place", "orange")
        marker.set_look("error")
        settle()
        px, py = view.getPointOnScreen(markers.joint_frame(bad)[0])
        py = height - py  # from the top, as the image
        away, normal_away = math.hypot(rx - px, ry - py), math.hypot(ox - px, oy - py)
        print("marker: the layout's shift %.1f px; drawn %.1f px from its joint in error, %.1f px normal; "
              "%d px across in error, %d px normal (view %d x %d)"
              % (shift, away, normal_away, red_across, orange_across, width, height))
        # In error the glyph is half as large again about its own centre, where it is normal.
        # (The ring is open, its arrow head another red: the centres a few pixels apart; before,
        # 47 px.)
        self.assertLess(math.hypot(rx - ox, ry - oy), 5.0, "the error look moved the marker")
        self.assertAlmostEqual(red_across / orange_across, 1.5, delta=0.15)
        # And drawn as far from its joint as the layout put it (a glyph unit PIXELS pixels: the
        # centre of its pixels a few pixels off the ring's, which is open): 45 px for 43, where a
        # unit drawn 2.1 times PIXELS in this 1052 x 505 view put it 94 px away.
        self.assertAlmostEqual(normal_away, shift, delta=5.0)


class TestDrivePanel(Documents):
    """The Drive panel: a motor on a joint, with units, limits said in the panel, the linkage
    following the value as it is typed, one undo step, Cancel putting every part back."""

    def open(self, joint):
        from dispcon_fc.panels import drive

        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(joint)
        settle()
        self.assertTrue(Gui.isCommandActive("Dispcon_Drive"), "Drive is greyed out with %s selected" % joint.Label)
        Gui.runCommand("Dispcon_Drive")
        settle()
        panel = drive.current()
        self.assertIsNotNone(panel, "the Drive panel did not open")
        return panel

    def fourbar_solved(self):
        from dispcon_fc import operations

        asm, g, crank, coupler, rocker = self.fourbar()
        self.assertTrue(operations.solve(asm).converged)
        crank_joint = [j for j in operations.joints(asm) if {j.Reference1[0], j.Reference2[0]} == {g, crank}][0]
        return asm, crank_joint, (crank, coupler, rocker)

    def test_the_linkage_follows_the_value_and_cancel_puts_it_back(self):
        from dispcon_fc import operations

        asm, joint, moving = self.fourbar_solved()
        start = [p.Placement for p in moving]
        panel = self.open(joint)
        self.assertIs(panel.joint(), joint)
        self.assertIn("°", panel.target.text())
        self.assertEqual(panel.limits.text(), "none")
        now = operations.drive_value(joint)
        self.assertAlmostEqual(raw_of(panel.target), now, places=1)
        panel.target.setProperty("rawValue", now + 30.0)
        settle()
        # The box holds what a person can type (its decimals): the joint goes there exactly.
        target = raw_of(panel.target)
        self.assertAlmostEqual(target, now + 30.0, places=1)
        self.assertAlmostEqual(operations.drive_value(joint), target, places=7)
        self.assertNotIn("cc0000", panel.message.styleSheet(), panel.message.text())
        self.assertIn("%g" % target, panel.message.text())
        self.assertTrue(panel.ok_button().isEnabled())
        # The coupler and the rocker followed; the joints still hold.
        self.assertFalse(same(moving[2].Placement, start[2], 1e-6), "the rocker did not follow")
        self.assertTrue(operations.solve(asm, undo_step=False).converged)
        self.assertEqual(panel.now.text(), "%g°" % target)
        shot("panel-drive")
        panel.reject()
        settle()
        self.assertFalse(Gui.Control.activeDialog(), "the panel stayed open")
        for p, q in zip(moving, start):
            self.assertTrue(same(p.Placement, q, 1e-9), "Cancel left %s moved" % p.Label)

    def test_the_box_is_clamped_to_the_limits_and_ok_is_one_undo_step(self):
        from dispcon_fc import operations

        asm, joint, moving = self.fourbar_solved()
        now = operations.drive_value(joint)
        # Without limits, the box's full range.
        panel = self.open(joint)
        self.assertEqual((raw_prop(panel.target, "minimum"), raw_prop(panel.target, "maximum")), (-1e6, 1e6))
        panel.reject()
        settle()
        # The top limit ends in 6 past the box's two decimals: the box rounds it up, past it.
        top = math.floor((now + 20.0) * 100) / 100 + 0.006
        operations.edit_joint(joint, rotation=(now - 20.0, top))
        self.assertTrue(operations.solve(asm).converged)
        start = [p.Placement for p in moving]
        panel = self.open(joint)
        self.assertIn("%g" % top, panel.limits.text())
        # The box's steps stop at the joint's limits, in degrees (its range stays full, so that a
        # value typed past a limit is read and refused in words: below).
        self.assertEqual(panel.ends, (math.ceil((now - 20.0) * 100) / 100, top - 0.006))
        self.assertIn("°", panel.target.text())
        panel.target.setProperty("rawValue", now + 18.0)
        settle()
        self.assertAlmostEqual(operations.drive_value(joint), raw_of(panel.target), places=7)
        # The arrows and the keyboard's steps stop at the limit: 5 degrees up from 2 below it.
        panel.target.stepBy(5)
        settle()
        # (the box shows two decimals: its end is the limit rounded inwards, which drives to the
        # limit itself; a box whose end was the limit rounded up, past it, took no step at all)
        self.assertAlmostEqual(raw_of(panel.target), top - 0.006, places=9)
        self.assertNotIn("outside", panel.message.text())
        self.assertNotIn("cc0000", panel.message.styleSheet(), panel.message.text())
        self.assertAlmostEqual(operations.drive_value(joint), top, places=7)
        # Typed as a person types: a value within the limits is taken, one past them is refused
        # in words (the box keeps it, the parts stay where they were, OK disabled).
        inside = round(now + 5.0, 2)
        type_into(panel.target, "%.2f" % inside)
        self.assertAlmostEqual(raw_of(panel.target), inside, places=9)
        self.assertAlmostEqual(operations.drive_value(joint), inside, places=7)
        type_into(panel.target, "%.2f" % (now + 45.0))
        self.assertAlmostEqual(raw_of(panel.target), round(now + 45.0, 2), places=9)
        self.assertAlmostEqual(operations.drive_value(joint), inside, places=7)
        self.assertIn("outside", panel.message.text())
        self.assertFalse(panel.ok_button().isEnabled())
        # An arrow's step from there stops at the limit and drives to it.
        up = QtGui.QKeyEvent(QtCore.QEvent.KeyPress, QtCore.Qt.Key_Up, QtCore.Qt.NoModifier)
        QtWidgets.QApplication.sendEvent(panel.target, up)
        settle()
        shot("panel-drive-clamped")
        self.assertAlmostEqual(operations.drive_value(joint), top, places=7)
        # A script's value outside the limits is still refused at the operation's door.
        with self.assertRaisesRegex(ValueError, "outside its limits"):
            operations.drive_to(asm, joint, now + 45.0, undo_step=False)
        self.assertAlmostEqual(operations.drive_value(joint), top, places=7)
        panel.target.setProperty("rawValue", now - 15.0)
        settle()
        self.assertTrue(panel.ok_button().isEnabled())
        target = raw_of(panel.target)
        self.assertAlmostEqual(operations.drive_value(joint), target, places=7)
        panel.ok_button().click()
        settle()
        self.assertFalse(Gui.Control.activeDialog(), "the panel stayed open")
        self.assertAlmostEqual(operations.drive_value(joint), target, places=7)
        # The whole drive is one undo step.
        self.doc.undo()
        for p, q in zip(moving, start):
            self.assertTrue(same(p.Placement, q, 1e-9), "one undo did not put %s back" % p.Label)

    def test_a_value_typed_past_a_limit_is_refused_in_words_not_cut_to_a_prefix(self):
        """The fourth audit: `40 deg` typed against a limit of 28.65 read `4 deg` (the box, its
        range the limits, dropped the 0) and the wheel went to 4 degrees without a word."""
        from dispcon_fc import operations

        asm, joint, moving = self.fourbar_solved()
        now = operations.drive_value(joint)
        operations.edit_joint(joint, rotation=(now - 45.0, now + 28.6479))
        self.assertTrue(operations.solve(asm).converged)
        panel = self.open(joint)
        type_into(panel.target, "%g deg" % round(now + 40.0), finish=False)
        pause(2 * 400)
        print("typed %g deg: the box reads %r" % (round(now + 40.0), panel.target.text()))
        self.assertAlmostEqual(raw_of(panel.target), round(now + 40.0), places=9)
        self.assertAlmostEqual(operations.drive_value(joint), now, places=7)
        self.assertIn("outside %s's limits" % joint.Label, panel.message.text())
        self.assertFalse(panel.ok_button().isEnabled())
        shot("panel-drive-typed-past-limit")
        self.assertFalse(panel.accept(), "OK took a value past the limit")
        self.assertAlmostEqual(operations.drive_value(joint), now, places=7)
        panel.reject()

    def test_a_typed_value_is_driven_once_typing_pauses_not_through_its_prefixes(self):
        from dispcon_fc import operations
        from dispcon_fc.panels import drive

        asm, joint, moving = self.fourbar_solved()
        panel = self.open(joint)
        now = operations.drive_value(joint)
        driven = []
        real = operations.drive_to

        def recorded(asm_, joint_, value, **kw):  # the real drive, its values kept
            driven.append(value)
            return real(asm_, joint_, value, **kw)

        operations.drive_to = recorded
        self.addCleanup(setattr, operations, "drive_to", real)
        # Typed key by key (its prefixes 1, 12, 12.5 are values the box reads): nothing is
        # driven while the keys come, then the value typed once they pause.
        target = round(now + 12.5, 2)
        text = "%.2f" % target
        type_into(panel.target, text, finish=False)
        self.assertEqual(driven, [], "driven through the prefixes of %r" % text)
        self.assertAlmostEqual(operations.drive_value(joint), now, places=7)
        pause(drive.TYPING_PAUSE_MS * 2)
        self.assertEqual(driven, [target])
        self.assertAlmostEqual(operations.drive_value(joint), target, places=7)
        self.assertIn("%g" % target, panel.message.text())
        # An arrow key's step is driven at once.
        key = QtGui.QKeyEvent(QtCore.QEvent.KeyPress, QtCore.Qt.Key_Up, QtCore.Qt.NoModifier)
        QtWidgets.QApplication.sendEvent(panel.target, key)
        settle()
        self.assertEqual(len(driven), 2)
        self.assertAlmostEqual(operations.drive_value(joint), raw_of(panel.target), places=7)
        self.assertGreater(raw_of(panel.target), target)
        # Typed, then OK before the pause: the value typed is driven, then kept as one undo step.
        last = round(now - 7.25, 2)
        type_into(panel.target, "%.2f" % last, finish=False)
        self.assertEqual(len(driven), 2)
        self.assertTrue(panel.accept())
        settle()
        self.assertEqual(driven[2:], [last])
        self.assertFalse(Gui.Control.activeDialog(), "the panel stayed open")
        self.assertAlmostEqual(operations.drive_value(joint), last, places=7)

    def test_a_slider_in_mm_and_a_lock_said_in_the_panel(self):
        from dispcon_fc import operations
        import parts

        asm, base, arm, pin, slider = slider_on_a_pin(self)
        Gui.SendMsgToActiveView("ViewFit")
        panel = self.open(slider)
        self.assertIn("mm", panel.target.text())
        panel.target.setProperty("rawValue", 0.4)
        settle()
        self.assertAlmostEqual(operations.drive_value(slider), 0.4, places=6)
        self.assertTrue(panel.ok_button().isEnabled())
        self.assertEqual(panel.ends, (-0.5, 0.5))
        panel.target.setProperty("rawValue", 0.7)  # past the limit (not typed): stops at it
        settle()
        self.assertEqual(raw_of(panel.target), 0.5)
        self.assertAlmostEqual(operations.drive_value(slider), 0.5, places=6)
        panel.target.setProperty("rawValue", 0.4)
        settle()
        panel.target.stepBy(1)  # a step of 1 mm up from 0.4 stops at 0.5
        settle()
        self.assertEqual(raw_of(panel.target), 0.5)
        self.assertNotIn("outside", panel.message.text())
        self.assertAlmostEqual(operations.drive_value(slider), 0.5, places=6)
        panel.reject()
        settle()
        self.assertAlmostEqual(operations.drive_value(slider), 0.0, places=6)
        # A lock on the way: a second, conflicting Revolute at the pin stops the travel at once.
        operations.add_joint(asm, "Revolute", pin, (arm, parts.circle_edge(arm.Shape, App.Vector(0, 0, 0))))
        panel = self.open(slider)
        panel.target.setProperty("rawValue", 0.3)
        settle()
        self.assertIn("locks", panel.message.text())
        self.assertAlmostEqual(operations.drive_value(slider), 0.0, places=6)
        panel.reject()


def base_and_arm(asm):
    """A grounded base with a pin at its origin and a free arm of 1.5 mm, added to `asm`:
    (base, arm)."""
    from dispcon_fc import operations
    import parts

    base = asm.Document.addObject("Part::Feature", "Base")
    base.Shape = parts.ground([(0, 0)])
    operations.add_part(asm, base, grounded=True)
    arm = asm.Document.addObject("Part::Feature", "Arm")
    arm.Shape = parts.link(1.5)
    operations.add_part(asm, arm)
    return base, arm


def slider_on_a_pin(test):
    """A grounded base and an arm on a Slider along the base's pin, travel -0.5 .. 0.5 mm, solved:
    (asm, base, arm, the pin's reference, the slider)."""
    from dispcon_fc import operations
    import parts

    asm = operations.create_assembly(test.doc)
    base, arm = base_and_arm(asm)
    pin = (base, parts.circle_edge(base.Shape, App.Vector(0, 0, 0)))
    slider = operations.add_joint(asm, "Slider", pin, (arm, parts.circle_edge(arm.Shape, App.Vector(0, 0, 0))),
                                  travel=(-0.5, 0.5))
    test.assertTrue(operations.solve(asm).converged)
    return asm, base, arm, pin, slider


def raw_of(box):
    return float(box.property("rawValue"))


def type_into(box, text, finish=True):
    """`text` typed into spin box `box` as a person types it (its text selected, then key after
    key through Qt key events, then the focus elsewhere; Return would press the panel's OK)."""
    box.setFocus()
    box.selectAll()
    for char in text:
        for kind in (QtCore.QEvent.KeyPress, QtCore.QEvent.KeyRelease):
            QtWidgets.QApplication.sendEvent(box, QtGui.QKeyEvent(kind, 0, QtCore.Qt.NoModifier, char))
    settle()
    if finish:
        box.clearFocus()
        settle()


def pause(ms):
    """The GUI's events processed for `ms` milliseconds, as a person's pause lets them run."""
    end = time.monotonic() + ms / 1000.0
    while time.monotonic() < end:
        settle()
        time.sleep(0.01)


def raw_prop(box, name):
    """A quantity spin box's minimum or maximum, as a number."""
    value = box.property(name)
    return float(getattr(value, "Value", value))


def answer_save_dialog(path, tries=100):
    """Types `path` into the save dialog about to open and presses Save, as a person would; again
    while that dialog stays open (under load it may not be ready for the first keystrokes)."""
    dialog = QtWidgets.QApplication.activeModalWidget()
    if isinstance(dialog, QtWidgets.QFileDialog) and dialog.isVisible():
        name = dialog.findChild(QtWidgets.QLineEdit, "fileNameEdit")
        if name is not None:
            name.setText(path)
        else:
            dialog.selectFile(path)
        dialog.accept()
    if tries and (dialog is None or isinstance(dialog, QtWidgets.QFileDialog)):
        if dialog is None or dialog.isVisible():
            QtCore.QTimer.singleShot(100, lambda: answer_save_dialog(path, tries - 1) if (
                QtWidgets.QApplication.activeModalWidget() is not None or dialog is None) else None)


class TestCheckPanel(Documents):
    def checked_fourbar(self):
        """A four-bar, solved, its assembly selected and Check run: the panel shown."""
        from dispcon_fc import operations, panels

        asm = self.fourbar()[0]
        self.assertTrue(operations.solve(asm).converged)
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(asm)
        Gui.runCommand("Dispcon_Check")
        settle()
        return panels.last_panel

    def test_the_check_panel_has_its_icon_and_units(self):
        # The task box's header shows the Check command's icon (it showed FreeCAD's logo), and
        # the overlapping parts' volume says its unit.
        from types import SimpleNamespace

        from dispcon_fc.panels import check
        from dispcon_fc.resources import icon_path

        panel = self.checked_fourbar()

        def image(icon):
            return icon.pixmap(24, 24).toImage().convertToFormat(QtGui.QImage.Format_ARGB32)

        self.assertFalse(panel.form.windowIcon().isNull(), "the check panel shows FreeCAD's logo")
        self.assertEqual(image(panel.form.windowIcon()), image(QtGui.QIcon(icon_path("Dispcon_Check.svg"))))
        shot("check-panel-icon")
        a, b = SimpleNamespace(Label="Crank"), SimpleNamespace(Label="Stop")
        text = QtGui.QTextDocument()
        text.setHtml(check.report_html(panel.result, [(a, b, 0.125)]))
        self.assertIn("volume (mm³)", text.toPlainText())
        self.assertIn("0.125", text.toPlainText())

    def test_the_check_panel_exports_its_report_and_a_motion_study(self):
        import json

        panel = self.checked_fourbar()
        out = tempfile.mkdtemp()
        QtCore.QTimer.singleShot(50, lambda: answer_save_dialog(os.path.join(out, "check.json")))
        panel.form.exportReport.click()
        settle()
        with open(os.path.join(out, "check.json")) as f:
            report = json.load(f)
        self.assertEqual(report["dof"], 1)
        self.assertIn("check.json", panel.form.report.toPlainText())
        Gui.Selection.clearSelection()
        QtCore.QTimer.singleShot(50, lambda: answer_save_dialog(os.path.join(out, "crank.svg")))
        panel.form.motionStudy.click()
        settle()
        for name in ("crank.svg", "crank-plot.svg", "crank.csv"):
            self.assertTrue(os.path.getsize(os.path.join(out, name)) > 100, name)
        with open(os.path.join(out, "crank.csv")) as f:
            self.assertGreater(len(f.readlines()), 100)
        # The study said in the workbench's words: a whole turn in degrees, no radians.
        said = panel.form.report.toPlainText().splitlines()[-1]
        self.assertRegex(said, r"^'[^']+' moves freely from -?[\d.]+° to -?[\d.]+°")
        self.assertNotIn("rad", said)
        self.assertNotIn("(s)", said)
        shot("check-exports")

    def test_the_check_is_a_report_closed_by_one_button_and_counts_in_words(self):
        self.checked_fourbar()
        # One degree of freedom (the four-bar's crank), said as a person says it.
        self.assertEqual(mw().statusBar().currentMessage(), "Check: 1 degree of freedom")
        boxes = [b for b in mw().findChildren(QtWidgets.QDialogButtonBox) if b.isVisible()]
        self.assertEqual([int(b.standardButtons()) for b in boxes], [int(QtWidgets.QDialogButtonBox.Close)])
        shot("check-close")
        boxes[0].button(QtWidgets.QDialogButtonBox.Close).click()
        settle()
        self.assertFalse(Gui.Control.activeDialog())
        self.assertFalse(any(b.isVisible() for b in mw().findChildren(QtWidgets.QDialogButtonBox)))

    def test_the_report_is_as_tall_as_its_text_its_tables_monospace(self):
        from dispcon_fc.panels import check

        panel = self.checked_fourbar()
        box = panel.form.report
        settle()
        # The whole report shows without scrolling (the four-bar's is short), the box no taller
        # than its text and a frame.
        self.assertEqual(box.verticalScrollBar().maximum(), 0)
        self.assertLessEqual(box.height(), box.document().size().height() + 2 * box.frameWidth() + 12)
        self.assertGreaterEqual(box.height(), box.document().size().height())
        # The parts' degrees of freedom: a table, a row per part and its header, in a fixed-pitch font.
        shot("check-report")

        def text(table, r, k):
            return table.cellAt(r, k).firstCursorPosition().block().text()

        tables = [f for f in box.document().rootFrame().childFrames() if isinstance(f, QtGui.QTextTable)]
        parts = [t for t in tables if [text(t, 0, k) for k in range(t.columns())] == ["part", "DOF"]]
        self.assertEqual(len(parts), 1, [[text(t, 0, k) for k in range(t.columns())] for t in tables])
        table = parts[0]
        self.assertEqual((table.rows(), table.columns()), (5, 2))
        cells = [[text(table, r, k) for k in range(2)] for r in range(5)]
        # A four-bar: its grounded part 0, each moving part 1 (the crank's turn moves them all).
        from dispcon_fc import objects

        expected = [[p.Label, "0" if p.Grounded else "1"] for p in objects.parts(panel.asm)]
        self.assertEqual(cells, [["part", "DOF"]] + expected)
        font = table.cellAt(1, 0).firstCursorPosition().charFormat().font()
        self.assertTrue(QtGui.QFontInfo(font).fixedPitch(), font.family())
        self.assertIn("degrees of freedom: 1", box.toPlainText())
        # A long report (sixty parts) stops growing at the cap and scrolls.
        c = dict(panel.result, part_dof={"Part%d" % k: k % 7 for k in range(60)})
        Gui.Control.closeDialog()
        settle()
        long_panel = check.CheckPanel(panel.asm, result=c)
        from dispcon_fc import panels

        panels.show(long_panel)
        settle()
        box = long_panel.form.report
        self.assertEqual(box.height(), check.REPORT_MAX_HEIGHT)
        self.assertGreater(box.verticalScrollBar().maximum(), 0)
        shot("check-report-long")
        Gui.Control.closeDialog()
        settle()


def gui_text(widget):
    """Every label's and text box's text under the task view."""
    out = []
    for w in mw().findChildren(QtWidgets.QLabel):
        if w.isVisible():
            out.append(w.text())
    for kind in (QtWidgets.QPlainTextEdit, QtWidgets.QTextEdit):
        for w in mw().findChildren(kind):
            if w.isVisible():
                out.append(w.toPlainText())
    return "\n".join(out)


class TestDragMode(Documents):
    def test_checkable_with_status_message_and_escape(self):
        from dispcon_fc import dragging, operations
        from pivy import coin

        asm, g, crank, coupler, rocker = self.fourbar()
        operations.solve(asm)
        a = action("Dispcon_Drag")
        self.assertTrue(a.isCheckable())
        Gui.Selection.addSelection(asm)
        a.trigger()
        settle()
        self.assertTrue(a.isChecked())
        self.assertIsNotNone(dragging.active(self.view()))
        self.assertIn("Esc", mw().statusBar().currentMessage())
        shot("drag-mode")
        # Esc in the 3D view leaves it.
        view = self.view()
        viewer = view.getViewer()
        region = viewer.getSoRenderManager().getViewportRegion()
        key = coin.SoKeyboardEvent()
        key.setKey(coin.SoKeyboardEvent.ESCAPE)
        key.setState(coin.SoButtonEvent.DOWN)
        act = coin.SoHandleEventAction(region)
        act.setEvent(key)
        act.apply(viewer.getSoRenderManager().getSceneGraph())
        settle()
        self.assertIsNone(dragging.active(view))
        self.assertFalse(a.isChecked())
        self.assertNotIn("Drag mode", mw().statusBar().currentMessage())


class TestBodies(Documents):
    """The fifth audit's scissor lift: parts made as PartDesign Bodies in the document. A click on
    a Body in the 3D view selects its tip feature (FreeCAD names the Pad); Add parts took the Pad
    out of its Body, the joint panel answered "ArmPad is not a part of Assembly" (and, on a
    sub-assembly's link to a Body, took the Body its link places), and drag mode grabbed nothing."""

    def click_on(self, view, obj, sub):
        """A Coin3D click where the view draws `obj`'s element `sub` (`obj` the Body, or a link,
        the view names as the tip's parent), the view turned from below when it is hidden, as a
        designer turns it; False when it is hidden from both."""
        from dispcon_fc.objects import shape_of

        element = shape_of(obj).getElement(sub)
        for turn in (None, "viewBottom"):
            if turn:
                getattr(view, turn)()
                Gui.SendMsgToActiveView("ViewFit")
                settle()
            if self._click_drawn(view, obj, sub, element):
                return True
        return False

    def _click_drawn(self, view, obj, sub, element):
        for f in (0.3, 0.6, 0.8, 0.1, 0.45, 0.9):
            if hasattr(element, "FirstParameter"):
                p = element.valueAt(element.FirstParameter + f * (element.LastParameter - element.FirstParameter))
            else:
                u0, u1, v0, v1 = element.ParameterRange
                p = element.valueAt(u0 + f * (u1 - u0), v0 + (1 - f) * (v1 - v0))
            x, y = view.getPointOnScreen(p)
            for dx, dy in ((0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)):
                info = view.getObjectInfo((x + dx, y + dy))
                if info and getattr(info.get("ParentObject"), "Name", "") == obj.Name and info.get("Component") == sub:
                    for kind in ("move", "press", "release"):
                        mouse(view, kind, x + dx, y + dy)
                        settle()
                    return True
        return False

    def bodies(self):
        from test_headless import pad_body

        base = pad_body(self.doc, "Base", (-15, -5, 130, 5), [(0, 0)], 5, App.Placement(App.Vector(0, 0, -5), App.Rotation()))
        arm = pad_body(self.doc, "Arm", (-5, -5, 105, 5), [(0, 0), (100, 0)], 5,
                       App.Placement(App.Vector(20, 40, 0), App.Rotation(App.Vector(0, 0, 1), 30)))
        view = self.view()
        view.viewIsometric()
        Gui.SendMsgToActiveView("ViewFit")
        settle()
        return view, base, arm

    def test_a_body_clicked_in_the_view_is_its_part_for_add_parts_joints_and_drag(self):
        from dispcon_fc import dragging, operations, subassembly
        from dispcon_fc.panels import joint as jp
        from test_headless import circle_named

        view, base, arm = self.bodies()
        asm = operations.create_assembly(self.doc)
        for body in (base, arm):
            Gui.Selection.clearSelection()
            self.assertTrue(self.click_on(view, body, "Face1"))
            self.assertEqual([o.Name for o in Gui.Selection.getSelection()], [body.Tip.Name])
            Gui.runCommand("Dispcon_AddParts")
            settle()
            self.assertIn(body, asm.Group)
            self.assertIn(body.Tip, body.Group)  # the Pad stays in its Body
        self.assertEqual(asm.Group, [base, arm])
        operations.set_grounded(base)
        # A Revolute picked by clicks on the two Bodies' circles.
        hole, pin = circle_named(base, (0, 0, 0)), circle_named(arm, tuple(arm.Placement.multVec(App.Vector(100, 0, 5))))
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(asm)
        Gui.runCommand("Dispcon_JointRevolute")
        settle()
        panel = jp.current()
        self.assertTrue(self.click_on(view, base, hole))
        self.assertEqual(panel.refs, [(base, hole)], panel.message.text())
        self.assertTrue(self.click_on(view, arm, pin))
        settle()
        self.assertEqual(panel.refs, [(base, hole), (arm, pin)], panel.message.text())
        panel.accept()
        settle()
        self.assertEqual(len(operations.joints(asm)), 1)
        axis = arm.Placement.multVec(App.Vector(100, 0, 0))  # the pin's axis onto the base's hole
        self.assertLess(math.hypot(axis.x, axis.y), 1e-6, (panel.refs, arm.Placement))
        # A flexible sub-assembly's link to the Body, clicked: the link, not the Body it places.
        top = operations.create_assembly(self.doc, "Top")
        inst = subassembly.insert_sub_assembly(top, asm, placement=App.Placement(App.Vector(0, 60, 30), App.Rotation()),
                                               rigid=False)
        asm.Visibility = False
        link = next(o for o in inst.Group if o.TypeId == "App::Link" and o.LinkedObject is arm)
        other = next(o for o in inst.Group if o.TypeId == "App::Link" and o.LinkedObject is base)
        Gui.SendMsgToActiveView("ViewFit")
        settle()
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(top)
        Gui.runCommand("Dispcon_JointFixed")
        settle()
        panel = jp.current()
        self.assertIs(panel.asm, top)
        face = "Face1"
        self.assertTrue(self.click_on(view, link, face))
        self.assertEqual(panel.refs, [(link, face)], panel.message.text())
        close_dialog()
        # Drag mode: a press on the arm grabs it; the drag turns it about the base's hole.
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(asm)
        asm.Visibility = True
        inst.Visibility = False
        for o in inst.Group:
            o.Visibility = False
        view.viewTop()
        Gui.SendMsgToActiveView("ViewFit")
        settle()
        action("Dispcon_Drag").trigger()
        settle()
        before = App.Placement(arm.Placement)
        x, y = view.getPointOnScreen(arm.Placement.multVec(App.Vector(20, 0, 5)))
        mouse(view, "press", x, y)
        for k in range(1, 11):
            mouse(view, "move", x - 3 * k, y + 3 * k)
            settle()
        mouse(view, "release", x - 30, y + 30)
        settle()
        dragging.stop(view)
        self.assertGreater(arm.Placement.Rotation.multiply(before.Rotation.inverted()).Angle, 0.05)
        axis = arm.Placement.multVec(App.Vector(100, 0, 0))
        self.assertLess(math.hypot(axis.x, axis.y), 1e-6)  # still on its pin


class TestActiveAssembly(Documents):
    def test_with_nothing_selected_a_command_works_on_the_assembly_not_placed_in_another(self):
        """The fifth audit: the arm pair, made first, placed twice in the lift; the Revolute
        command run with nothing selected opened on the pair, and every pick on the lift's parts
        was refused ("Base is not a part of Pair")."""
        from dispcon_fc import operations, subassembly
        from dispcon_fc.commands.common import active_assembly
        from dispcon_fc.panels import joint as jp

        pair = operations.create_assembly(self.doc, "Pair")
        base_and_arm(pair)
        lift = operations.create_assembly(self.doc, "Lift")
        subassembly.insert_sub_assembly(lift, pair, rigid=False)
        Gui.Selection.clearSelection()
        self.assertIs(active_assembly(), lift)
        Gui.runCommand("Dispcon_JointRevolute")
        settle()
        self.assertIs(jp.current().asm, lift)
        Gui.Selection.addSelection(pair)  # selected, it is still the one
        self.assertIs(active_assembly(), pair)


class TestDragAtALimit(Documents):
    def test_a_drag_held_by_a_limit_says_which(self):
        """The fourth audit: the wheel pulled round past its limit stopped there, the status bar
        saying only "Drag mode: ..."; now which joint's limit holds the drag."""
        from dispcon_fc import dragging, operations
        import parts

        asm = operations.create_assembly(self.doc)
        base, arm = base_and_arm(asm)
        j = operations.add_joint(asm, "Revolute", (base, parts.circle_edge(base.Shape, App.Vector(0, 0, 0))),
                                 (arm, parts.circle_edge(arm.Shape, App.Vector(0, 0, 0))), rotation=(-10, 30))
        j.Label = "Base-Arm"
        self.assertTrue(operations.solve(asm).converged)
        view = self.view()
        view.viewTop()
        Gui.SendMsgToActiveView("ViewFit")
        settle()
        Gui.Selection.addSelection(asm)
        action("Dispcon_Drag").trigger()
        settle()
        centre = view.getPointOnScreen(arm.Placement.multVec(App.Vector(0, 0, 0.1)))
        x, y = view.getPointOnScreen(arm.Placement.multVec(App.Vector(1.2, 0, 0.1)))
        r = math.hypot(x - centre[0], y - centre[1])
        a0 = math.atan2(y - centre[1], x - centre[0])
        mouse(view, "press", x, y)
        for k in range(1, 31):  # 120 degrees asked, counterclockwise
            a = a0 + math.radians(4 * k)
            x, y = int(centre[0] + r * math.cos(a)), int(centre[1] + r * math.sin(a))
            mouse(view, "move", x, y)
            settle()
        mouse(view, "release", x, y)
        settle()
        self.assertAlmostEqual(operations.drive_value(j), 30.0, places=5)
        self.assertIn("Base-Arm is at its limit, 30°: it holds the drag there", mw().statusBar().currentMessage())
        shot("drag-held-by-a-limit")
        dragging.stop(view)


def engine_couples():
    from dispcon_fc import adapter, engine, objects

    return set(objects.COUPLINGS) <= set(adapter.offered_types(engine.load()))


class TestCouplings(Documents):
    """The couplings (Gears, Belt, RackPinion, Screw) and Distance, Parallel, Perpendicular as a
    designer meets them: their commands, the gear's panel, a gear train's markers."""
    NEW = ("Gears", "Belt", "RackPinion", "Screw", "Distance", "Parallel", "Perpendicular")

    def gears(self):
        import couplings

        asm, named = couplings.three_gears(self.doc)
        self.view().viewTop()
        Gui.SendMsgToActiveView("ViewFit")
        return asm, named

    def test_commands_have_icons_and_sit_with_the_joints(self):
        from dispcon_fc.qt import is_alive

        joints_bar = toolbar_of("Dispcon_JointRevolute")
        # The menu bar's Dispcon menu as it is now (FreeCAD remakes its menus as documents come
        # and go): its Joints submenu.
        in_menu = set()
        for m in mw().menuBar().findChildren(QtWidgets.QMenu):
            if is_alive(m) and m.title().replace("&", "") == "Joints":
                in_menu |= {a.objectName() for a in m.actions()}
        for kind in self.NEW if engine_couples() else ("Distance", "Parallel", "Perpendicular"):
            n = "Dispcon_Joint" + kind
            self.assertIs(toolbar_of(n), joints_bar, "%s is not in the Joints toolbar" % n)
            self.assertIn(n, in_menu, "%s is not in the Joints submenu" % n)
            self.assertFalse(action(n).icon().isNull(), "%s has no icon" % n)
        if engine_couples():
            self.assertIn("circular edge", action("Dispcon_JointGears").toolTip())
        # Every type has its glyph (the tree's icon, the marker while picking and after).
        from dispcon_fc import markers, objects

        for kind in objects.JOINT_TYPES:
            self.assertGreaterEqual(markers.glyph(kind, 1.0).getNumChildren(), 1, kind)

    @unittest.skipUnless(engine_couples(), "this build's engine has no coupling rows")
    def test_gear_panel_shows_the_ratio_and_refuses_zero(self):
        from dispcon_fc.panels import joint as jp
        import couplings

        asm, p = self.gears()
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(*couplings.circle(p["G1"], (0, 0, 0), 1.0))
        Gui.Selection.addSelection(*couplings.circle(p["G3"], (0, 0, 0), 1.5))
        Gui.runCommand("Dispcon_JointGears")
        settle()
        panel = jp.current()
        self.assertIsNotNone(panel, "the joint panel did not open")
        self.assertEqual({n for n, g in panel.groups.items() if g.isVisibleTo(panel.form)},
                         {"reverse", "ratio", "phase"})
        self.assertAlmostEqual(panel.ratio.value(), 1.0 / 1.5, places=6)  # r1 / r2 of the picked circles
        self.assertIn("°", panel.phase.text())
        panel.ratio.setValue(0.0)
        settle()
        self.assertIn("Ratio 0", panel.message.text())
        self.assertFalse(panel.ok_button().isEnabled(), "OK stays enabled with ratio 0")
        shot("panel-gears-ratio-0")
        panel.ratio.setValue(0.75)
        settle()
        self.assertTrue(panel.ok_button().isEnabled())
        self.assertAlmostEqual(panel.joint.Ratio, 0.75)
        panel.type_box.setCurrentText("Screw")
        settle()
        self.assertEqual({n for n, g in panel.groups.items() if g.isVisibleTo(panel.form)},
                         {"reverse", "pitch", "phase", "travel"})
        self.assertIn("mm", panel.pitch.text())
        panel.reject()
        settle()
        self.assertFalse([j for j in asm.Group if getattr(j, "JointType", "") in ("Gears", "Screw")
                          and j.Reference2[0] == p["G3"] and j.Reference1[0] == p["G1"]])

    @unittest.skipUnless(engine_couples(), "this build's engine has no coupling rows")
    def test_the_mesh_offset_in_the_panel_turns_part_2_the_engines_phase_beneath(self):
        from dispcon_fc import operations
        from dispcon_fc.objects import mesh_offset, phase_value

        asm, p = self.gears()
        self.assertTrue(operations.solve(asm).converged)
        mesh = [j for j in asm.Group if getattr(j, "JointType", "") == "Gears"
                and {j.Reference1[0], j.Reference2[0]} == {p["G1"], p["G2"]}][0]
        self.assertTrue(mesh.PhaseKnown)
        mesh.ViewObject.Proxy.doubleClicked(mesh.ViewObject)
        settle()
        from dispcon_fc.panels import joint as jp

        panel = jp.current()
        self.assertIsNotNone(panel, "the joint panel did not open")
        # The offset from the mesh as made (0), in degrees; the engine's phase beside it, read only.
        self.assertIn("°", panel.phase.text())
        self.assertEqual(raw_of(panel.phase), 0.0)
        phase = phase_value(mesh)
        self.assertIn("Engine's phase: %.6g°" % phase, panel.engine_phase.text())

        def mesh_value():
            s1 = math.copysign(1, p["G1"].Placement.Rotation.multVec(mesh.Axis1).z)
            s2 = math.copysign(1, p["G2"].Placement.Rotation.multVec(mesh.Axis2).z)
            turn = [math.atan2(v.y, v.x) for v in (o.Placement.Rotation.multVec(App.Vector(1, 0, 0))
                                                    for o in (p["G1"], p["G2"]))]
            return mesh.Ratio * s1 * turn[0] + s2 * turn[1]

        before = mesh_value()
        panel.phase.setProperty("rawValue", 12.0)
        settle()
        target = raw_of(panel.phase)
        self.assertEqual(target, 12.0)
        self.assertNotIn("cc0000", panel.message.styleSheet(), panel.message.text())
        self.assertEqual(mesh_offset(mesh), 12.0)
        self.assertAlmostEqual(phase_value(mesh), phase + 12.0, places=9)
        self.assertIn("Engine's phase: %.6g°" % (phase + 12.0), panel.engine_phase.text())
        # The preview's solve turned part 2 12 degrees on against part 1.
        self.assertAlmostEqual(math.remainder(mesh_value() - before, 2 * math.pi), math.radians(12), places=7)
        shot("panel-gears-phase")
        panel.ok_button().click()
        settle()
        self.assertEqual(mesh_offset(mesh), 12.0)
        self.assertAlmostEqual(phase_value(mesh), phase + 12.0, places=9)
        self.assertTrue(mesh.PhaseKnown)
        # A screw's offset is a length.
        self.assertTrue(operations.solve(asm).converged)
        mesh.ViewObject.Proxy.doubleClicked(mesh.ViewObject)
        settle()
        panel = jp.current()
        panel.type_box.setCurrentText("Screw")
        settle()
        # A length now (FreeCAD shows a small one in um).
        self.assertRegex(panel.phase.text(), r"[µm]m$")
        panel.reject()
        settle()
        # Cancel brings the gear mesh back as it was (the Screw made in its place goes).
        kept = [j for j in asm.Group if getattr(j, "JointType", "") == "Gears"
                and {j.Reference1[0], j.Reference2[0]} == {p["G1"], p["G2"]}]
        self.assertEqual(len(kept), 1)
        self.assertEqual(mesh_offset(kept[0]), 12.0)
        self.assertAlmostEqual(phase_value(kept[0]), phase + 12.0, places=9)

    @unittest.skipUnless(engine_couples(), "this build's engine has no coupling rows")
    def test_gear_train_markers(self):
        from pivy import coin
        from dispcon_fc import operations

        asm, p = self.gears()
        self.assertTrue(operations.solve(asm).converged)
        settle()
        sg = self.view().getSceneGraph()
        found = {}
        # The glyphs sit inside FreeCAD's SoShapeScale, a node kit: searched only so (another
        # test may have turned it on already; run alone, this one must).
        coin.SoBaseKit.setSearchingChildren(True)
        for j in [o for o in asm.Group if hasattr(o, "JointType")]:
            search = coin.SoSearchAction()
            search.setName("dispcon_glyph_" + j.JointType)
            search.setInterest(coin.SoSearchAction.ALL)
            search.apply(sg)
            found[j.JointType] = search.getPaths().getLength()
        self.assertEqual(found, {"Revolute": 3, "Gears": 2})
        self.view().viewIsometric()
        Gui.SendMsgToActiveView("ViewFit")
        path = shot("gear-train")
        self.assertGreater(orange_pixels(path), 30, "no orange marker drawn in %s" % path)

    def test_the_planetary_set_and_the_vice_as_the_docs_show_them(self):
        # docs/images/wb-sample-planetary.png and wb-sample-vice.png: the samples solved, seen
        # whole, the tree open on their assembly, each marker drawn (orange) once laid out.
        from dispcon_fc import operations
        import couplings

        if not engine_couples():
            self.skipTest("this build's engine has no coupling rows")
        for name, build, count in (("planetary", couplings.planetary, 12), ("vice", couplings.vice, 3)):
            doc = App.newDocument(name)  # a document of the sample's name, as the tab shows it
            self.addCleanup(lambda n=doc.Name: n in App.listDocuments() and App.closeDocument(n))
            activate(doc)
            asm, _ = build(doc)
            self.assertTrue(operations.solve(asm).converged, name)
            self.assertEqual(len(operations.joints(asm)), count, name)
            view = self.view()
            view.viewIsometric()
            Gui.SendMsgToActiveView("ViewFit")
            laid_out()
            tabs = mw().findChild(QtWidgets.QTabWidget, "combiTab")  # the Combo View's
            if tabs is not None:
                tabs.setCurrentIndex(0)  # the tree
            path = shot("sample-" + name)
            self.assertGreater(orange_pixels(path), 10 * count, "%s: too few orange marker pixels in %s" % (name, path))
            Gui.Selection.clearSelection()
            App.closeDocument(doc.Name)
            settle()


def orange_pixels(path):
    """The markers' orange pixels of the image at `path`, one pixel in 3 x 3 counted."""
    image = QtGui.QImage(path)
    return sum(1 for x in range(0, image.width(), 3) for y in range(0, image.height(), 3)
               if (lambda c: c.red() > 200 and 80 < c.green() < 160 and c.blue() < 60)(QtGui.QColor(image.pixel(x, y))))


def selection_green(view):
    """The rendered view's selection-green pixels (FreeCAD draws a selected edge so)."""
    image = rendered(view, os.path.join(OUT, "_selected.png"))
    mask = (image[:, :, 1] > 150) & (image[:, :, 0] < 110) & (image[:, :, 2] < 110)
    return int(mask.sum())


def selected_refs():
    """{(object name, sub-element)} of the selection now."""
    return {(s.Object.Name, name) for s in Gui.Selection.getSelectionEx() for name in s.SubElementNames}


class TestPanelFixes(Documents):
    """What the first designer's audit left as found in the joint and Drive panels: joints named
    from their parts, the picked references highlighted while the panel is open, the fields
    greyed out until the joint is made, the units following the type, the Drive's box clamped."""

    def pick(self, e1, e2, kind="Revolute"):
        """The joint command with nothing selected, then the two references picked in it."""
        panel = picking_panel(kind)
        self.assertTrue(panel.picking)
        Gui.Selection.addSelection(*e1)
        settle()
        Gui.Selection.addSelection(*e2)
        settle()
        self.assertFalse(panel.picking)
        self.assertIsNotNone(panel.joint)
        return panel

    open = TestJointPanel.open

    def test_joints_named_from_their_parts_in_the_tree_and_the_drive_list(self):
        from dispcon_fc import operations
        from dispcon_fc.panels import drive

        asm, base, arm, e1, e2 = self.arm()
        panel = self.pick(e1, e2)
        self.assertEqual(panel.joint.Label, "Base-Arm")
        self.assertIn("Base-Arm holds", panel.message.text())
        panel.ok_button().click()
        settle()
        joint = operations.joints(asm)[0]
        self.assertEqual(joint.Label, "Base-Arm")
        self.assertIsNotNone(tree_icon("Base-Arm"), "the tree does not list Base-Arm")
        # A second joint between the same parts: numbered, unique.
        panel = self.pick(e1, e2, "Slider")
        self.assertEqual(panel.joint.Label, "Base-Arm001")
        panel.ok_button().click()
        settle()
        d = drive.open_panel(asm, joint)
        settle()
        items = [d.joint_box.itemText(k) for k in range(d.joint_box.count())]
        self.assertEqual(items, ["Base-Arm (Revolute)", "Base-Arm001 (Slider)"])
        self.assertIn("Base-Arm", d.message.text())
        d.reject()
        settle()
        # A label typed by a person stays through Pick again; one its parts gave follows them.
        joint.Label = "Main pin"
        panel = jp_edit(joint)
        QtCore.QTimer.singleShot(0, panel.pick_button.click)
        settle()
        Gui.Selection.addSelection(*e1)
        Gui.Selection.addSelection(*e2)
        settle()
        self.assertEqual(panel.joint.Label, "Main pin")
        panel.reject()
        settle()
        self.assertEqual(sorted(j.Label for j in operations.joints(asm)), ["Base-Arm001", "Main pin"])

    def test_a_joint_made_on_two_picks_is_previewed_once_and_its_fields_outlive_the_shown_dialog(self):
        # The panel on two picks: its joint made and previewed as it opens, once (a second
        # preview after the dialog was shown built the model and solved the assembly again, to
        # move nothing). The OK's state was then set from a timer that searched the task view's
        # widgets, which took PySide's hold of the panel's quantity boxes with it: the next read
        # of a box, at a value changed or at OK, raised "Internal C++ object (QAbstractSpinBox)
        # already deleted".
        from dispcon_fc import operations
        from dispcon_fc.panels import joint as jp
        from dispcon_fc.qt import is_alive

        asm, base, arm, e1, e2 = self.arm()
        solve, solves = operations.solve, []

        def counted(*args, **kw):  # the real solve, called through
            solves.append(args[0].Name)
            return solve(*args, **kw)

        operations.solve = counted
        try:
            panel = jp.open_panel(asm=asm, joint_type="Revolute", refs=[e1, e2])
        finally:
            operations.solve = solve
        self.assertEqual(solves, [asm.Name])
        for _ in range(5):  # the dialog shown, its timers run
            settle()
        self.assertTrue(panel.ok_button().isEnabled())
        for box, _, what in panel.quantities:
            self.assertTrue(is_alive(box), "%s's box was let go of while the panel is open" % what)
        panel.offset.setProperty("rawValue", 2.5)
        settle()
        self.assertAlmostEqual(panel.joint.Offset.Value, 2.5, places=9)
        self.assertIn("Base-Arm holds", panel.message.text())
        panel.ok_button().click()
        settle()
        self.assertFalse(Gui.Control.activeDialog())
        joint = operations.joints(asm)[0]
        self.assertAlmostEqual(joint.Offset.Value, 2.5, places=9)
        self.assertEqual(self.doc.UndoNames[0], "Add joint")
        # A panel that opens refusing OK (nothing picked yet) is shown so.
        panel = jp.open_panel(asm=asm, joint_type="Revolute")
        settle()
        self.assertFalse(panel.ok_button().isEnabled())
        panel.reject()
        settle()

    def test_the_picked_references_stay_highlighted_until_ok_or_cancel(self):
        asm, base, arm, e1, e2 = self.arm()
        view = self.view()
        view.viewIsometric()
        Gui.SendMsgToActiveView("ViewFit")
        Gui.Selection.clearSelection()
        settle()
        self.assertEqual(selection_green(view), 0, "green before anything is picked")
        for close in ("ok", "cancel"):
            panel = self.pick(e1, e2)
            refs = {(o.Name, sub) for o, sub in panel.refs}
            self.assertEqual(refs, {(e1[0].Name, e1[1]), (e2[0].Name, e2[1])})
            settle()
            self.assertEqual(selected_refs(), refs, "the picked references are not selected")
            self.assertGreater(selection_green(view), 50, "the picked references are not drawn highlighted")
            # Still so after a field's change moved the parts (the preview's solve).
            panel.offset.setProperty("rawValue", 0.6)
            settle()
            self.assertEqual(selected_refs(), refs)
            self.assertGreater(selection_green(view), 50)
            if close == "ok":
                shot("panel-references-highlighted")
                panel.ok_button().click()
            else:
                panel.reject()
            settle()
            self.assertFalse(Gui.Control.activeDialog())
            self.assertEqual(Gui.Selection.getSelectionEx(), [], "a selection left behind at %s" % close)
            self.assertEqual(selection_green(view), 0, "green left behind at %s" % close)
        # A joint opened for editing shows its references too, and lets go of them at Cancel.
        from dispcon_fc import operations

        joint = operations.joints(asm)[0]
        self.assertTrue(joint.ViewObject.Proxy.doubleClicked(joint.ViewObject))
        settle()
        self.assertEqual(selected_refs(), {(e1[0].Name, e1[1]), (e2[0].Name, e2[1])})
        close_dialog()
        self.assertEqual(Gui.Selection.getSelectionEx(), [])

    def test_fields_greyed_out_with_a_reason_until_the_joint_is_made(self):
        asm, base, arm, e1, e2 = self.arm()
        panel = picking_panel()
        fields = [panel.reverse, panel.offset, *panel.frame, *panel.shift, panel.has_rotation, panel.rot_min,
                  panel.rot_max]

        def greyed(why):
            for w in fields:
                self.assertFalse(w.isEnabled(), "%s is editable %s" % (w.objectName() or w.text(), why))
                self.assertIn("Pick both references first", w.toolTip(), w.objectName())
            self.assertTrue(panel.type_box.isEnabled())

        greyed("before anything is picked")
        shot("panel-greyed-while-picking")
        Gui.Selection.addSelection(*e1)
        settle()
        greyed("with one reference")
        Gui.Selection.addSelection(*e2)
        settle()
        self.assertIsNotNone(panel.joint)
        for w in (panel.reverse, panel.offset, *panel.frame, *panel.shift, panel.has_rotation):
            self.assertTrue(w.isEnabled(), w.objectName() or w.text())
            self.assertNotIn("Pick both references first", w.toolTip())
            self.assertTrue(w.toolTip().strip())
        # Min and max follow their tick box.
        self.assertFalse(panel.rot_min.isEnabled())
        panel.has_rotation.setChecked(True)
        settle()
        self.assertTrue(panel.rot_min.isEnabled() and panel.rot_max.isEnabled())
        QtCore.QTimer.singleShot(0, panel.pick_button.click)
        settle()
        greyed("while picking again")
        panel.reject()

    def test_each_fields_unit_follows_the_type(self):
        panel, asm, base, arm = self.open("Revolute")

        def unit_of(box):
            return box.property("unit") if isinstance(box.property("unit"), str) else str(box.text())

        for kind, checks in (("Screw", ((panel.pitch, "mm"), (panel.phase, "mm"))),
                             ("Gears", ((panel.phase, "°"),)),
                             ("Belt", ((panel.phase, "°"),)),
                             ("Revolute", ((panel.rot_min, "°"), (panel.offset, "mm"))),
                             ("Screw", ((panel.pitch, "mm"), (panel.phase, "mm"), (panel.tr_min, "mm")))):
            seen = panel.type_box.currentText()
            panel.type_box.setCurrentText(kind)
            settle()
            self.assertIsNotNone(panel.joint, "%s after %s: %s" % (kind, seen, panel.message.text()))
            for box, unit in checks:
                text = box.text()
                self.assertTrue(text.endswith(unit), "%s: %s reads %r, not in %s" % (kind, box.objectName(), text, unit))
                other = {"mm": "°", "°": "mm"}[unit]
                self.assertNotIn(other, text, "%s: %s reads %r" % (kind, box.objectName(), text))
            if kind == "Screw":
                self.assertIn("per turn", panel.groups["pitch"].findChildren(QtWidgets.QLabel)[0].text())
                self.assertIn("Engine's phase", panel.engine_phase.text())
                self.assertIn("mm", panel.engine_phase.text(), "%s after %s (%s, its Phase a %s)" % (
                    kind, seen, panel.joint.JointType, panel.joint.getTypeIdOfProperty("Phase")))
            if kind in ("Gears", "Belt"):
                self.assertIn("°", panel.engine_phase.text())
                self.assertNotIn("mm", panel.engine_phase.text())
        shot("panel-screw-units")
        # A type the references cannot make (a rack needs a straight edge): back to picking, and
        # nothing in the previous type's unit is left (the gears' phase was in degrees).
        panel.type_box.setCurrentText("Gears")
        settle()
        self.assertIn("°", panel.engine_phase.text())
        panel.type_box.setCurrentText("RackPinion")
        settle()
        self.assertIsNone(panel.joint)
        self.assertIn("straight edge", panel.message.text())
        self.assertNotIn("°", panel.engine_phase.text())
        self.assertTrue(panel.phase.text().endswith("mm"), panel.phase.text())
        self.assertTrue(panel.radius.text().endswith("mm"), panel.radius.text())
        panel.reject()


class TestTypedAndPicked(Documents):
    """The second audit's findings in the panels: a text in another unit (or past a range) said by
    its field's name and refused, not taken as the last number the box could read; a flexible
    sub-assembly's part picked in the joint panel as a script names it."""

    open = TestJointPanel.open

    def finish_typing(self, box):
        """Editing done, as Tab or a click elsewhere ends it."""
        box.editingFinished.emit()
        settle()

    def test_a_text_in_another_unit_is_said_by_name_and_refused(self):
        panel, asm, base, arm = self.open("Revolute")
        type_into(panel.offset, "3 kg", finish=False)
        # (the box takes no "g" after "3 k": the text it holds is what is said)
        self.assertRegex(panel.message.text(), r"^Offset: '3 kg?' is not a length \(mm\)\.$")
        self.assertIn("cc0000", panel.message.styleSheet())
        self.assertFalse(panel.ok_button().isEnabled(), "OK enabled with '3 kg' in a length")
        self.assertFalse(panel.accept())
        shot("panel-offset-in-kg")
        self.finish_typing(panel.offset)  # the box back at what it could read, and said so
        self.assertIn("It stays at 3 mm.", panel.message.text())
        self.assertTrue(panel.ok_button().isEnabled())
        type_into(panel.offset, "1/4 in")
        self.finish_typing(panel.offset)
        self.assertAlmostEqual(raw_of(panel.offset), 6.35, places=9)
        self.assertIn("holds", panel.message.text())
        self.assertTrue(panel.ok_button().isEnabled())
        self.assertAlmostEqual(panel.joint.Offset.Value, 6.35, places=9)
        panel.reject()

    def test_a_text_in_another_unit_typed_key_by_key_moves_nothing_and_cancel_restores_to_the_bit(self):
        from dispcon_fc.panels import joint as jp

        asm, base, arm, e1, e2 = self.arm()
        bits = lambda: [tuple(o.Placement.Base) + tuple(o.Placement.Rotation.Q) for o in (base, arm)]
        before = bits()
        panel = picking_panel("Revolute", (e1, e2))
        snapped = bits()
        self.assertNotEqual(snapped, before)
        box = panel.offset
        box.setFocus()
        box.selectAll()
        seen = []
        for char in "3 kg":  # as a person types: each key's press and release, the GUI's events run
            for kind in (QtCore.QEvent.KeyPress, QtCore.QEvent.KeyRelease):
                QtWidgets.QApplication.sendEvent(box, QtGui.QKeyEvent(kind, 0, QtCore.Qt.NoModifier, char))
            settle()
            seen.append((box.text(), bits() == snapped))
        # No prefix ("3", "3 ", "3 k") moved the arm: the preview waits for typing to pause.
        self.assertEqual([moved for _, moved in seen], [True] * 4, seen)
        self.assertRegex(panel.message.text(), r"^Offset: '3 kg?' is not a length \(mm\)\.$")
        self.assertFalse(panel.ok_button().isEnabled())
        pause(3 * jp.TYPING_PAUSE_MS)  # a pause with an unreadable text: still nothing moves
        self.assertEqual(bits(), snapped)
        self.assertFalse(panel.ok_button().isEnabled())
        shot("panel-offset-kg-typed")
        # Cancel (its button, as clicked) puts both parts back where they were, to the bit.
        buttons = [b for b in mw().findChildren(QtWidgets.QDialogButtonBox) if b.isVisible()]
        cancel = [b.button(QtWidgets.QDialogButtonBox.Cancel) for b in buttons if b.button(QtWidgets.QDialogButtonBox.Cancel)]
        self.assertTrue(cancel)
        cancel[0].click()
        settle()
        self.assertFalse(Gui.Control.activeDialog())
        self.assertEqual(bits(), before)
        self.assertFalse([o for o in asm.Group if hasattr(o, "JointType")])

    def test_a_typed_offset_is_previewed_once_typing_pauses(self):
        from dispcon_fc.panels import joint as jp

        panel, asm, base, arm = self.open("Revolute")
        z0 = arm.Placement.Base.z
        type_into(panel.offset, "2.5", finish=False)
        self.assertEqual(arm.Placement.Base.z, z0, "moved through a prefix of 2.5")
        pause(3 * jp.TYPING_PAUSE_MS)
        self.assertAlmostEqual(arm.Placement.Base.z, 2.5, places=6)
        self.assertTrue(panel.ok_button().isEnabled())
        for kind in (QtCore.QEvent.KeyPress, QtCore.QEvent.KeyRelease):  # an arrow's step: at once
            QtWidgets.QApplication.sendEvent(panel.offset, QtGui.QKeyEvent(kind, QtCore.Qt.Key_Up, QtCore.Qt.NoModifier))
        settle()
        self.assertGreater(raw_of(panel.offset), 2.5)
        self.assertAlmostEqual(arm.Placement.Base.z, raw_of(panel.offset), places=6)
        panel.offset.clearFocus()
        panel.offset.setProperty("rawValue", 1.0)  # a script's value: at once
        settle()
        self.assertAlmostEqual(arm.Placement.Base.z, 1.0, places=6)
        type_into(panel.offset, "4", finish=False)
        self.assertTrue(panel.accept())  # OK before the pause: the value typed is taken
        settle()
        self.assertAlmostEqual(arm.Placement.Base.z, 4.0, places=6)

    def test_the_drive_says_a_text_in_another_unit_or_past_the_limits(self):
        from dispcon_fc import operations
        from dispcon_fc.panels import drive

        asm, base, arm, pin, slider = slider_on_a_pin(self)
        panel = drive.open_panel(asm, slider)
        settle()
        type_into(panel.target, "5 deg", finish=False)
        self.assertRegex(panel.message.text(), r"^Drive to: '.*' is not a length \(mm\)\.$")
        self.assertFalse(panel.ok_button().isEnabled())
        self.assertFalse(panel.accept())
        type_into(panel.target, "0.01 in")
        self.finish_typing(panel.target)
        self.assertAlmostEqual(operations.drive_value(slider), 0.254, places=6)
        self.assertTrue(panel.ok_button().isEnabled(), panel.message.text())
        type_into(panel.target, "2", finish=False)  # past the travel: said, nothing moved
        pause(2 * drive.TYPING_PAUSE_MS)
        self.assertEqual(raw_of(panel.target), 2.0)
        self.assertIn("outside", panel.message.text())
        self.assertFalse(panel.ok_button().isEnabled())
        self.assertAlmostEqual(operations.drive_value(slider), 0.254, places=6)
        shot("panel-drive-typed-past")
        panel.reject()

    def test_a_flexible_legs_part_is_picked_in_the_joint_panel(self):
        import parts
        os.environ["DISPCON_SUB_IMPORT_ONLY"] = "1"
        import test_subassembly as ts

        tmp = tempfile.mkdtemp()
        leg = ts.make_leg(tmp)
        doc, asm, frame, subs = ts.make_walker(tmp, leg, rigid=False, hip_joints=("Revolute",) * 4)
        self.addCleanup(lambda: "walker" in App.listDocuments() and App.closeDocument("walker"))
        self.addCleanup(lambda: "leg" in App.listDocuments() and App.closeDocument("leg"))
        activate(doc)
        coupler = ts.part(subs[1], "Coupler")
        pin = parts.circle_edge(coupler.LinkedObject.Shape, App.Vector(th_B(), 0, 0))
        post = parts.circle_edge(frame.Shape, App.Vector(ts.LEGS[1][0], ts.LEGS[1][1], 0.1))
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(asm)
        panel = picking_panel("Slider")
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(doc.Name, frame.Name, post)
        settle()
        Gui.Selection.addSelection(doc.Name, coupler.Name, pin)
        settle()
        self.assertNotIn("not a part", panel.message.text())
        self.assertIsNotNone(panel.joint, panel.message.text())
        self.assertEqual({panel.joint.Reference1[0], panel.joint.Reference2[0]}, {frame, coupler})
        self.assertEqual(panel.joint.Label, "Frame-Leg2.Coupler")
        panel.reject()
        settle()
        self.assertEqual(len([o for o in asm.Group if hasattr(o, "JointType")]), 4)


def report_view_text():
    """The Report view's text as a person reads it."""
    for w in mw().findChildren(QtWidgets.QTextEdit):
        if "ReportOutput" in w.metaObject().className():
            return w.toPlainText()
    raise AssertionError("no Report view")


@contextlib.contextmanager
def answering_questions(answer=QtWidgets.QMessageBox.Yes):
    """Any question FreeCAD asks meanwhile (a QMessageBox: "delete its content as well?")
    answered by a click on `answer`, as the designer who chose to delete answers it."""
    asked = []

    def answer_it():
        box = QtWidgets.QApplication.activeModalWidget()
        if isinstance(box, QtWidgets.QMessageBox) and box.button(answer) is not None:
            asked.append(box.text())
            box.button(answer).click()

    timer = QtCore.QTimer()
    timer.timeout.connect(answer_it)
    timer.start(100)
    try:
        yield asked
    finally:
        timer.stop()


class TestPanelsGone(unittest.TestCase):
    """Every panel (a new joint, a joint edited, the Drive, an exploded view, the bill of
    materials, the Check) when what it edits goes from under it while it is open: the object
    deleted in the tree, its document closed, an undo. The panel closes itself at once, saying
    why in the Report view, with no traceback; an edit's undo leaves every placement as it was
    before the panel opened, to the bit. (It stayed open over a closed document, its Cancel
    doing nothing; the exploded view's Cancel raised "Object has been removed from document"
    after an undo.)"""

    KINDS = ("joint-new", "joint-edit", "drive", "exploded", "bom", "check")
    TITLES = {"joint-new": "joint panel", "joint-edit": "joint panel", "drive": "Drive panel",
              "exploded": "Exploded view panel", "bom": "Bill of materials panel", "check": "Check panel"}

    def tearDown(self):
        close_dialog()
        close_documents()

    def setup(self, kind):
        """A new document with a base and an arm on a revolute, the panel of `kind` open: (doc,
        asm, the object whose deletion ends the panel, the panel, the placements before)."""
        from dispcon_fc import operations
        from dispcon_fc.panels import bom as bp, check as cp, drive, exploded as ep
        import parts

        close_dialog()
        doc = App.newDocument("gone")
        activate(doc)
        asm = operations.create_assembly(doc)
        base, arm = base_and_arm(asm)
        e1 = (base, parts.circle_edge(base.Shape, App.Vector(0, 0, 0)))
        e2 = (arm, parts.circle_edge(arm.Shape, App.Vector(0, 0, 0)))
        joint = operations.add_joint(asm, "Revolute", e1, e2)
        self.assertTrue(operations.solve(asm).converged)
        Gui.SendMsgToActiveView("ViewFit")
        before = [tuple(o.Placement.Base) + tuple(o.Placement.Rotation.Q) for o in (base, arm)]
        if kind == "joint-new":
            panel = picking_panel("Revolute", (e1, e2))
            target = panel.joint
        elif kind == "joint-edit":
            panel, target = jp_edit(joint), joint
            panel.offset.setProperty("rawValue", 0.5)  # the preview moves the arm up
            settle()
            self.assertAlmostEqual(arm.Placement.Base.z, 0.5, places=6)
        elif kind == "drive":
            panel, target = drive.open_panel(asm, joint), joint
            panel.target.setProperty("rawValue", 30.0)
            pause(500)
        elif kind == "exploded":
            panel = ep.open_panel(asm)
            target = panel.view
        elif kind == "bom":
            panel, target = bp.open_panel(asm), asm
        else:
            panel, target = panels_show(cp.CheckPanel(asm)), asm
        settle()
        self.assertTrue(Gui.Control.activeDialog(), kind)
        return doc, asm, target, panel, before, (base, arm)

    def gone(self, kind, how):
        doc, asm, target, panel, before, objs = self.setup(kind)
        start = len(report_view_text())
        if how == "deleted" and kind == "joint-edit":
            # FreeCAD's Delete leaves an object in edit; a macro deletes it, inside the panel's
            # transaction: taken back with the rest, as Cancel does.
            label = target.Label
            doc.removeObject(target.Name)
            pause(200)
            said = report_view_text()[start:]
            self.assertIn("The joint panel closed: %s was deleted. Everything since it opened is taken back, "
                          "as Cancel does." % label, said)
            self.assertNotIn("Traceback", said)
            self.assertFalse(Gui.Control.activeDialog())
            self.assertEqual([tuple(o.Placement.Base) + tuple(o.Placement.Rotation.Q) for o in objs], before)
            self.assertEqual([j.Label for j in asm.Group if hasattr(j, "JointType")], [label])
            return said
        if how == "deleted":
            # Its label read before: a deleted object's attributes may raise ReferenceError
            # (seen under load, in the assertion's message).
            label = target.Label
            Gui.Selection.clearSelection()
            Gui.Selection.addSelection(target)
            with answering_questions():
                Gui.runCommand("Std_Delete")
                pause(300)
            self.assertFalse(target in doc.Objects, "%s not deleted" % label)
            reason = "%s was deleted" % label
        elif how == "closed":
            App.closeDocument(doc.Name)
            reason = "its document was closed"
        else:
            Gui.runCommand("Std_Undo")
            reason = "an undo changed its document"
        pause(200)
        said = report_view_text()[start:]
        self.assertNotIn("Traceback", said)
        self.assertNotIn("Error", said)
        if kind == "check" and how == "undo":  # a report of a moment: it stays, Close closes it
            self.assertTrue(Gui.Control.activeDialog())
            panel.reject()
            settle()
        else:
            self.assertIn("The %s closed: %s." % (self.TITLES[kind], reason), said)
        self.assertFalse(Gui.Control.activeDialog(), "the %s stayed open after %s" % (kind, how))
        if how == "undo" and kind in ("joint-edit", "drive"):
            after = [tuple(o.Placement.Base) + tuple(o.Placement.Rotation.Q) for o in objs]
            self.assertEqual(after, before, "the undo left a part where the panel put it")
        shot("panel-gone-%s-%s" % (kind, how))
        return said

    def test_check_run_with_another_panel_open_shows_its_report(self):
        from dispcon_fc import panels
        from dispcon_fc.panels import check

        doc, asm, target, panel, before, objs = self.setup("drive")  # the arm driven to 30 degrees
        self.assertNotEqual([tuple(o.Placement.Base) + tuple(o.Placement.Rotation.Q) for o in objs], before)
        start = len(report_view_text())
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(asm)
        Gui.runCommand("Dispcon_Check")
        settle()
        said = report_view_text()[start:]
        self.assertNotIn("Active task dialog found", said)
        self.assertIsInstance(panels.last_panel, check.CheckPanel)
        self.assertTrue(Gui.Control.activeDialog())
        self.assertTrue(panel.closed)  # the Drive cancelled as its Cancel does: the arm back
        self.assertEqual([tuple(o.Placement.Base) + tuple(o.Placement.Rotation.Q) for o in objs], before)
        shot("panel-check-over-drive")
        panels.last_panel.accept()
        settle()
        self.assertFalse(Gui.Control.activeDialog())

    def gone_for_every_kind(self, how):
        for kind in self.KINDS:
            with self.subTest(kind=kind):
                self.gone(kind, how)
                close_documents()

    def test_deleted(self):
        self.gone_for_every_kind("deleted")

    def test_document_closed(self):
        self.gone_for_every_kind("closed")

    def test_undo(self):
        self.gone_for_every_kind("undo")


def panels_show(panel):
    from dispcon_fc import panels

    return panels.show(panel)


def th_B():
    from test_headless import B

    return B


def jp_edit(joint):
    """The joint panel opened on `joint` (as a double-click in the tree opens it)."""
    from dispcon_fc.panels import joint as jp

    joint.ViewObject.Proxy.doubleClicked(joint.ViewObject)
    settle()
    return jp.current()


def run_in_gui(classes, status_name):
    """Starts the workbench in this FreeCAD at 1280x900, runs the unittest classes, writes 0 to
    <out>/<status_name> when every test passed (1 otherwise) and quits FreeCAD."""
    status = 1
    try:
        exec(open(os.path.join(WB, "InitGui.py")).read(), {"__file__": os.path.join(WB, "InitGui.py")})
        Gui.activateWorkbench("DispconWorkbench")
        mw().setGeometry(0, 0, 1280, 900)
        settle()
        suite = unittest.TestSuite()
        loader = unittest.TestLoader()
        for cls in classes:
            suite.addTests(loader.loadTestsFromTestCase(cls))
        result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
        failed = len(result.failures) + len(result.errors)
        print("%d passed, %d failed" % (result.testsRun - failed, failed))
        status = 0 if result.wasSuccessful() else 1
    except Exception:
        traceback.print_exc()
        print("0 passed, 1 failed")
    finally:
        os.makedirs(OUT, exist_ok=True)
        with open(os.path.join(OUT, status_name), "w") as f:
            f.write(str(status))
        QtWidgets.QApplication.instance().quit()


def main():
    only = os.environ.get("DISPCON_GUI_ONLY")
    run_in_gui([cls for cls in (TestCommands, TestMarkers, TestMarkerFixes, TestTreeIcons, TestRestored, TestJointPanel, TestDrivePanel, TestCheckPanel, TestErrors, TestDragMode, TestDragAtALimit, TestBodies, TestActiveAssembly, TestCouplings,
                                    TestPanelFixes, TestTypedAndPicked, TestPanelsGone)
                if not only or any(o in cls.__name__ for o in only.split(","))], "status-workbench")


if not os.environ.get("DISPCON_GUI_IMPORT_ONLY"):  # scripts/walkthrough.py imports the helpers only
    main()
