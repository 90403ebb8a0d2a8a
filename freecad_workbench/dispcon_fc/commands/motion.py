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


def commands():
    return [
        ("Dispcon_Solve", Command("Solve", "Snap the parts into place (grounded parts stay)", _solve)),
        ("Dispcon_Drag", Command("Drag", "Toggle drag mode: grab a part with the mouse, the linkage follows", _drag_mode)),
        ("Dispcon_Drive", Command("Drive", "Turn the selected revolute, as an animation", _drive)),
    ]
