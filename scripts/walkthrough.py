"""The screenshots of docs/workbench.md's walkthrough, made by the real workbench in real FreeCAD:
a four-bar built from scratch through the commands and the joint panel (import, ground, four
revolutes picked edge by edge, solve, drag, a limit, check), then the samples. Run by
scripts/screenshots under Xvfb (1280x900); writes docs/images/wt-*.png. Quits FreeCAD itself."""
import os
import sys
import tempfile
import traceback

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WB = os.path.join(REPO, "freecad_workbench")
OUT = os.environ.get("DISPCON_SHOTS_OUT", os.path.join(REPO, "docs", "images"))
for p in (WB, os.path.join(REPO, "samples", "freecad"), os.path.join(REPO, "tests", "freecad")):
    sys.path.insert(0, p)

import FreeCAD as App  # noqa: E402
import FreeCADGui as Gui  # noqa: E402
from PySide2 import QtWidgets  # noqa: E402

os.environ["DISPCON_GUI_IMPORT_ONLY"] = "1"
import gui_workbench as gw  # noqa: E402  (the GUI test's screenshot and event helpers)

PARTS = os.path.join(REPO, "samples", "freecad", "parts")


def shot(name):
    path = gw.shot(name)
    os.replace(path, os.path.join(OUT, name + ".png"))
    print("wrote", os.path.join(OUT, name + ".png"))


def tree_expanded():
    """The Model tab in front, every item of the tree open."""
    combo = gw.mw().findChild(QtWidgets.QTabWidget, "combiTab")
    if combo is not None:
        combo.setCurrentIndex(0)
    for tree in gw.mw().findChildren(QtWidgets.QTreeWidget):
        tree.expandAll()
    gw.settle()


def pick(obj, local, top=False):
    import parts

    x, y, z = local
    return (obj, parts.circle_edge(obj.Shape, App.Vector(x, y, z + (0.1 if top else 0.0))))


def import_with_the_command(path):
    """Runs Import part as a person would, the file dialog answered with `path`."""
    dialog = QtWidgets.QFileDialog.getOpenFileName
    QtWidgets.QFileDialog.getOpenFileName = staticmethod(lambda *a, **k: (path, ""))
    try:
        Gui.runCommand("Dispcon_ImportPart")
    finally:
        QtWidgets.QFileDialog.getOpenFileName = dialog
    return App.ActiveDocument.Objects[-1]


def fit():
    view = Gui.ActiveDocument.ActiveView
    view.viewTop()
    Gui.SendMsgToActiveView("ViewFit")
    gw.settle()


def joint_by_picking(ref1, ref2, screenshot=None):
    """The Revolute command with nothing selected, then the two edges picked in the 3D view (the
    cursor resting on the first one shows its marker first); OK."""
    from dispcon_fc.panels import joint as jp

    Gui.Selection.clearSelection()
    Gui.runCommand("Dispcon_JointRevolute")
    panel = jp.current()
    Gui.Selection.setPreselection(*ref1)
    gw.settle()
    if screenshot:
        shot(screenshot + "-picking")
    Gui.Selection.clearPreselection()
    Gui.Selection.addSelection(*ref1)
    Gui.Selection.addSelection(*ref2)
    gw.settle()
    if screenshot:
        shot(screenshot)
    panel.ok_button().click()
    gw.settle()
    return panel.joint


def this_tree():
    """Refuses to go on when the workbench FreeCAD runs may not be this tree's: a copy installed in
    the user's Mod folder (loaded at FreeCAD's start, before this script) would be shown instead.
    scripts/screenshots gives FreeCAD a user data folder of its own, so there is none."""
    import dispcon_fc

    mine = os.path.realpath(WB)
    ran = os.path.realpath(os.path.dirname(os.path.dirname(dispcon_fc.__file__)))
    if "DispconWorkbench" in Gui.listWorkbenches():  # registered by FreeCAD from a Mod folder
        ran = ran if ran != mine else "a Mod folder"
    others = sorted({os.path.realpath(p) for p in sys.path if p and os.path.isfile(os.path.join(p, "dispcon_fc", "__init__.py"))}
                    - {mine})
    if ran != mine or others:
        raise RuntimeError("FreeCAD runs the workbench in %s (other copies: %s), not only this tree's (%s): a copy "
                           "installed in the user's Mod folder loads first; run scripts/screenshots, which gives "
                           "FreeCAD a user data folder of its own" % (ran, ", ".join(others) or "none", mine))
    print("the workbench driven: %s" % ran)


def main():
    this_tree()
    os.makedirs(OUT, exist_ok=True)
    # What FreeCAD runs for a workbench installed in its Mod folder: Init.py, then InitGui.py.
    for name in ("Init.py", "InitGui.py"):
        exec(open(os.path.join(WB, name)).read(), {"__file__": os.path.join(WB, name)})
    Gui.activateWorkbench("DispconWorkbench")
    window = gw.mw()
    window.setGeometry(0, 0, 1280, 900)
    from dispcon_fc import dragging, objects

    doc = App.newDocument("FourBar")
    gw.settle()
    shot("wt-1-workbench")

    # 1. An assembly and its parts: four STEP files; the plate is grounded.
    Gui.runCommand("Dispcon_CreateAssembly")
    asm = [o for o in doc.Objects if objects.is_assembly(o)][0]
    Gui.Selection.addSelection(asm)
    ground = import_with_the_command(os.path.join(PARTS, "ground-3.step"))
    crank = import_with_the_command(os.path.join(PARTS, "link-1.step"))
    coupler = import_with_the_command(os.path.join(PARTS, "link-3.step"))
    rocker = import_with_the_command(os.path.join(PARTS, "link-2.5.step"))
    for obj, label in ((ground, "Ground"), (crank, "Crank"), (coupler, "Coupler"), (rocker, "Rocker")):
        obj.Label = label
    # Roughly where they go (a person drags them there, or types a Placement).
    crank.Placement = App.Placement(App.Vector(-0.6, -1.2, 0.15), App.Rotation(App.Vector(0, 0, 1), 40))
    coupler.Placement = App.Placement(App.Vector(0.8, 1.4, 0.2), App.Rotation(App.Vector(0, 0, 1), -5))
    rocker.Placement = App.Placement(App.Vector(4.2, -0.4, 0.1), App.Rotation(App.Vector(0, 0, 1), 80))
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(ground)
    Gui.runCommand("Dispcon_Ground")
    Gui.Selection.clearSelection()
    fit()
    tree_expanded()
    shot("wt-2-parts")

    # 2. Four revolutes, each by picking two circular edges; the parts snap as soon as the second
    # edge is picked.
    j1 = joint_by_picking(pick(ground, (0, 0, 0), top=True), pick(crank, (0, 0, 0)), "wt-3-revolute")
    j2 = joint_by_picking(pick(crank, (1, 0, 0), top=True), pick(coupler, (0, 0, 0)))
    j3 = joint_by_picking(pick(coupler, (3, 0, 0)), pick(rocker, (2.5, 0, 0), top=True))
    j4 = joint_by_picking(pick(ground, (3, 0, 0), top=True), pick(rocker, (0, 0, 0)))
    for j, label in ((j1, "Ground-Crank"), (j2, "Crank-Coupler"), (j3, "Coupler-Rocker"), (j4, "Rocker-Ground")):
        j.Label = label

    # 3. Solve; the joints' markers; one selected in the tree.
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(asm)
    Gui.runCommand("Dispcon_Solve")
    Gui.Selection.clearSelection()
    Gui.ActiveDocument.ActiveView.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    Gui.Selection.addSelection(j2)
    tree_expanded()
    shot("wt-4-solved")
    Gui.Selection.clearSelection()

    # 4. Drag mode: press on the coupler and move the mouse (Coin3D events, as a mouse sends).
    fit()
    Gui.Selection.addSelection(asm)
    gw.action("Dispcon_Drag").trigger()
    view = Gui.ActiveDocument.ActiveView
    x0, y0 = (int(v) for v in view.getPointOnScreen(coupler.Placement.multVec(App.Vector(1.5, 0, 0.1))))
    gw.mouse(view, "press", x0, y0)
    for k in range(1, 25):
        gw.mouse(view, "move", x0 - 3 * k, y0 - 2 * k)
        Gui.updateGui()
    gw.mouse(view, "release", x0 - 72, y0 - 48)
    shot("wt-5-drag")
    dragging.stop()

    # 5. A limit: double-click the crank's joint, limit its turn, try max below min first.
    Gui.Selection.clearSelection()
    j1.ViewObject.Proxy.doubleClicked(j1.ViewObject)
    gw.settle()
    from dispcon_fc.panels import joint as jp

    panel = jp.current()
    panel.has_rotation.setChecked(True)
    panel.rot_min.setProperty("rawValue", 45.0)
    panel.rot_max.setProperty("rawValue", -45.0)
    gw.settle()
    shot("wt-6-limit-refused")
    panel.rot_min.setProperty("rawValue", -150.0)
    panel.rot_max.setProperty("rawValue", 150.0)
    gw.settle()
    shot("wt-7-limit")
    panel.ok_button().click()
    gw.settle()

    # 5b. Drive: the crank's joint to 40 degrees past where it is, then up against its limit
    # (the box's range is the joint's limits: its arrows stop there).
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(j1)
    gw.settle()
    Gui.runCommand("Dispcon_Drive")
    gw.settle()
    from dispcon_fc.panels import drive

    panel = drive.current()
    now = float(panel.target.property("rawValue"))
    panel.target.setProperty("rawValue", now + 40.0)
    gw.settle()
    shot("wt-7b-drive")
    panel.target.stepBy(400)
    gw.settle()
    shot("wt-7c-drive-at-limit")
    panel.target.setProperty("rawValue", now + 40.0)
    gw.settle()
    panel.ok_button().click()
    gw.settle()

    # 6. Check.
    Gui.Selection.addSelection(asm)
    Gui.runCommand("Dispcon_Check")
    gw.settle()
    shot("wt-8-check")
    gw.close_dialog()

    # 7. A joint that cannot hold: Solve says which and marks it.
    import parts

    bad = objects_add_joint(asm, (ground, parts.circle_edge(ground.Shape, App.Vector(3, 0, 0.1))),
                            (crank, parts.circle_edge(crank.Shape, App.Vector(1, 0, 0))))
    bad.Label = "Crank-to-far-pin"
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(asm)
    Gui.runCommand("Dispcon_Solve")
    gw.settle()
    shot("wt-9-solve-failed")
    gw.close_dialog()
    App.closeDocument(doc.Name)

    # The samples.
    samples = os.environ.get("DISPCON_SAMPLES", os.path.join(REPO, "build", "samples"))
    for name in ("slider-crank", "rssr"):
        path = os.path.join(samples, name + ".FCStd")
        if not os.path.isfile(path):
            print("no %s: build the samples first (scripts/screenshots does)" % path)
            continue
        d = App.openDocument(path)
        Gui.ActiveDocument.ActiveView.viewIsometric()
        Gui.SendMsgToActiveView("ViewFit")
        tree_expanded()
        shot("wt-sample-" + name)
        App.closeDocument(d.Name)


def objects_add_joint(asm, ref1, ref2):
    from dispcon_fc import operations

    return operations.add_joint(asm, "Revolute", ref1, ref2)


status = 1
try:
    main()
    status = 0
except Exception:
    traceback.print_exc()
finally:
    with open(os.path.join(tempfile.gettempdir(), "dispcon-walkthrough-status"), "w") as f:
        f.write(str(status))
    QtWidgets.QApplication.instance().quit()
