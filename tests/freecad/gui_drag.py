"""GUI test in real FreeCAD under Xvfb: activate the workbench, build the four-bar from parts,
run its Solve command, turn drag mode on and drag the coupler with Coin3D mouse events, check that
the linkage followed, measure a 20-part drag, save a screenshot. Quits FreeCAD itself."""
import math
import os
import sys
import tempfile
import time
import traceback

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
WB = os.path.join(REPO, "freecad_workbench")
OUT = os.environ.get("DISPCON_GUI_OUT", os.path.join(tempfile.gettempdir(), "dispcon-gui"))
sys.path.insert(0, WB)
sys.path.insert(0, os.path.join(REPO, "samples", "freecad"))
sys.path.insert(0, HERE)

import FreeCAD as App  # noqa: E402
import FreeCADGui as Gui  # noqa: E402
from PySide2 import QtWidgets  # noqa: E402
from pivy import coin  # noqa: E402

status = 1
try:
    exec(open(os.path.join(WB, "InitGui.py")).read())
    Gui.activateWorkbench("DispconWorkbench")
    import dispcon_fc.assembly as da
    import dispcon_fc.dragging as dragging
    import parts

    os.environ["DISPCON_IMPORT_ONLY"] = "1"
    from test_headless import angle_of, freudenstein, fourbar

    os.makedirs(OUT, exist_ok=True)
    doc = App.newDocument("gui")
    asm, g, crank, coupler, rocker = fourbar(doc, OUT)
    Gui.SendMsgToActiveView("ViewFit")
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(asm)
    Gui.runCommand("Dispcon_Solve")
    assert abs(angle_of(rocker) - freudenstein(angle_of(crank))) < 1e-8, "Solve did not assemble"
    view = Gui.ActiveDocument.ActiveView
    view.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    Gui.updateGui()

    # Drag mode on; press on the coupler's middle, move the mouse, release.
    Gui.runCommand("Dispcon_Drag", 1)  # a checkable command: 1 turns it on
    mode = dragging._active
    assert mode is not None, "drag mode did not start"
    viewer = view.getViewer()
    region = viewer.getSoRenderManager().getViewportRegion()
    height = region.getWindowSize()[1]
    mid = coupler.Placement.multVec(App.Vector(1.5, 0, 0.1))

    def screen(p):
        x, y = view.getPointOnScreen(p)
        return int(x), int(y)

    def send(event, x, y):
        event.setPosition(coin.SbVec2s(x, y))
        action = coin.SoHandleEventAction(region)
        action.setEvent(event)
        action.apply(viewer.getSoRenderManager().getSceneGraph())

    x0, y0 = screen(mid)
    info = view.getObjectInfo((x0, y0))
    assert info and info["Object"] == coupler.Name, "the coupler is not under the cursor: %s" % info
    crank_before = angle_of(crank)
    press = coin.SoMouseButtonEvent()
    press.setButton(coin.SoMouseButtonEvent.BUTTON1)
    press.setState(coin.SoMouseButtonEvent.DOWN)
    send(press, x0, y0)
    assert mode.drag is not None, "pressing on the coupler did not start a drag"
    for k in range(1, 31):
        move = coin.SoLocation2Event()
        send(move, x0 - 2 * k, y0 + 3 * k)
        Gui.updateGui()
    release = coin.SoMouseButtonEvent()
    release.setButton(coin.SoMouseButtonEvent.BUTTON1)
    release.setState(coin.SoMouseButtonEvent.UP)
    send(release, x0 - 60, y0 + 90)
    Gui.runCommand("Dispcon_Drag", 0)
    moved = abs(angle_of(crank) - crank_before)
    assert moved > 0.05, "the crank did not follow the coupler (turned %.4f rad)" % moved
    err = abs(math.remainder(angle_of(rocker) - freudenstein(angle_of(crank)), 2 * math.pi))
    assert err < 1e-8, "the linkage broke during the drag: %g" % err
    for j in da.joints(asm):
        assert not j.Violated
    print("dragged with %d mouse events: crank turned %.3f rad, closure error %.2e" % (mode.frames, moved, err))
    view.saveImage(os.path.join(OUT, "fourbar-drag.png"), 1280, 900, "White")
    # The session as a person sees it: the main window, with the 3D view's rendering painted
    # where the view is (a widget grab cannot read OpenGL under Xvfb).
    from PySide2 import QtGui

    window = Gui.getMainWindow()
    shot = window.grab()
    mdi = window.findChild(QtWidgets.QMdiArea)
    area = mdi.geometry()
    area.moveTopLeft(mdi.mapTo(window, mdi.rect().topLeft()))
    view.saveImage(os.path.join(OUT, "view.png"), area.width(), area.height() - 30, "White")
    painter = QtGui.QPainter(shot)
    painter.drawImage(area.topLeft(), QtGui.QImage(os.path.join(OUT, "view.png")))
    painter.end()
    shot.save(os.path.join(OUT, "session.png"))

    # A joint from picked edges through the workbench's command and its task panel: a limited
    # revolute (+-30 degrees), then Drive turns it until the limit stops it.
    import dispcon_fc.commands as commands

    doc3 = App.newDocument("panel")
    asm3 = da.create_assembly(doc3)
    base = doc3.addObject("Part::Feature", "Base")
    base.Shape = parts.ground([(0, 0)])
    da.add_part(asm3, base, grounded=True)
    arm = doc3.addObject("Part::Feature", "Arm")
    arm.Shape = parts.link(1.5)
    da.add_part(asm3, arm)
    arm.Placement = App.Placement(App.Vector(0.05, 0.02, 0), App.Rotation())
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(base, parts.circle_edge(base.Shape, App.Vector(0, 0, 0)))
    Gui.Selection.addSelection(arm, parts.circle_edge(arm.Shape, App.Vector(0, 0, 0)))
    Gui.runCommand("Dispcon_JointRevolute")
    panel = commands.last_panel
    assert panel is not None and Gui.Control.activeDialog(), "the joint panel did not open"
    panel.has_rotation.setChecked(True)
    panel.rot_min.setProperty("rawValue", -30.0)
    panel.rot_max.setProperty("rawValue", 30.0)
    assert panel.accept()
    joint = da.joints(asm3)[0]
    assert joint.HasRotationLimits and abs(joint.RotationMax.Value - 30) < 1e-9
    assert da.solve(asm3).converged
    # Check, away from the limits: one degree of freedom (at a limit, the limit holds it too).
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(asm3)
    Gui.runCommand("Dispcon_Check")
    check = commands.last_panel
    assert Gui.Control.activeDialog() and check.result["dof"] == 1, check.result
    assert "degrees of freedom: 1" in check.form.report.toPlainText()
    check.accept()
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(joint)
    start = angle_of(arm)
    reached = commands._drive()
    turned = math.degrees(math.remainder(angle_of(arm) - start, 2 * math.pi))
    assert abs(reached - 30) <= 2 and abs(turned - reached) < 1e-6, (reached, turned)
    print("panel: revolute limited to +-30 degrees; Drive stopped at %.1f degrees" % reached)

    # A 20-part assembly (five four-bars side by side, 15 moving parts and 5 grounds): frames per
    # second of a drag, the solver and FreeCAD's update measured apart.
    doc2 = App.newDocument("twenty")
    asm2 = da.create_assembly(doc2)
    cranks = []
    for k in range(5):
        a, g2, c2, cp2, r2 = fourbar(doc2, OUT)
        for o in (g2, c2, cp2, r2):
            o.Placement = App.Placement(o.Placement.Base + App.Vector(0, 0, 2 * k), o.Placement.Rotation)
            asm2.addObject(o)
        for j in da.joints(a):
            asm2.addObject(j)
        cranks.append(c2)
    assert da.solve(asm2).converged
    # The 20-part document's own view, in front: the update time must be that of its redraw.
    Gui.updateGui()
    Gui.setActiveDocument(doc2.Name)
    mdi = Gui.getMainWindow().findChild(QtWidgets.QMdiArea)
    for sub in mdi.subWindowList():
        if sub.windowTitle().startswith(doc2.Label):
            mdi.setActiveSubWindow(sub)
    Gui.updateGui()
    view2 = Gui.getDocument(doc2.Name).ActiveView
    view2.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    d = da.Drag(asm2, cranks[0])
    solver, update, frames = 0.0, 0.0, 60
    start = cranks[0].Placement
    for k in range(1, frames + 1):
        rot = App.Rotation(App.Vector(0, 0, 1), 2 * k).multiply(start.Rotation)
        t0 = time.perf_counter()
        r = d.move(App.Placement(start.Base, rot))
        t1 = time.perf_counter()
        Gui.updateGui()
        t2 = time.perf_counter()
        assert r.converged, r.message
        solver += t1 - t0
        update += t2 - t1
    d.finish()
    print("20-part drag: %.1f frames/s; solver and placements %.2f ms/frame, FreeCAD update %.2f ms/frame"
          % (frames / (solver + update), 1000 * solver / frames, 1000 * update / frames))
    view2.saveImage(os.path.join(OUT, "twenty.png"), 1280, 900, "White")
    print("1 passed, 0 failed")
    status = 0
except Exception:
    traceback.print_exc()
    print("0 passed, 1 failed")
finally:
    with open(os.path.join(OUT, "status"), "w") as f:
        f.write(str(status))
    QtWidgets.QApplication.instance().quit()
