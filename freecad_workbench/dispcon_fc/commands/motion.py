"""Commands that move the parts: Solve (snap), Drag mode, Drive."""
import FreeCADGui as Gui

from .. import operations
from ..feedback import highlight, report
from ..objects import joints
from .common import Command, active_assembly


def _solve():
    asm = active_assembly()
    for j in joints(asm):
        highlight([j], colour=(0.1, 0.1, 0.1))
    r = operations.solve(asm)
    report(r.message, error=not r.converged)
    if not r.converged:
        highlight(r.violated)
    return r


def _drag_mode():
    from .. import dragging

    dragging.toggle(active_assembly())


def _drive():
    asm = active_assembly()
    js = [o for o in Gui.Selection.getSelection() if o in joints(asm)] or \
         [j for j in joints(asm) if j.JointType == "Revolute"]
    if not js:
        raise ValueError("select a revolute joint to drive")
    from PySide2 import QtWidgets

    def frame(_):
        Gui.updateGui()

    reached = operations.drive(asm, js[0], [k * 2.0 for k in range(1, 181)], callback=frame)
    report("drove %s by %.1f degrees" % (js[0].Label, reached))
    QtWidgets.QApplication.processEvents()
    return reached


def _motion_study():
    """Drives the selected joint (or the first revolute) through a full turn, or a slider through
    its limits, and exports the animated SVG, the plot and the CSV (dispcon_fc.studies)."""
    from PySide import QtGui

    from .. import studies

    asm = active_assembly()
    js = [o for o in Gui.Selection.getSelection() if o in joints(asm)] or \
         [j for j in joints(asm) if j.JointType == "Revolute"]
    if not js:
        raise ValueError("select a revolute or slider joint for the motion study")
    path, _ = QtGui.QFileDialog.getSaveFileName(None, "Motion study of %s" % js[0].Label,
                                                js[0].Label + ".svg", "SVG (*.svg)")
    if not path:
        return None
    base = path[:-4] if path.lower().endswith(".svg") else path
    study = studies.export_drive_study(asm, js[0], svg_path=base + ".svg", plot_path=base + "-plot.svg",
                                       csv_path=base + ".csv")
    report("%s (written: %s.svg, %s-plot.svg, %s.csv)" % (study.message, base, base, base),
           error=study.exit_code() != 0)
    return study


def commands():
    return [
        ("Dispcon_Solve", Command("Solve", "Snap the parts into place (grounded parts stay)", _solve)),
        ("Dispcon_Drag", Command("Drag", "Toggle drag mode: grab a part with the mouse, the linkage follows", _drag_mode)),
        ("Dispcon_Drive", Command("Drive", "Turn the selected revolute, as an animation", _drive)),
        ("Dispcon_MotionStudy", Command("Motion study", "Sweep the selected joint: lock-ups, interference "
                                        "along the motion, and an animated SVG with the plot", _motion_study)),
    ]
