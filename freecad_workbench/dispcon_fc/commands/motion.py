"""Commands that move the parts: Solve (snap), Drag mode, Drive."""
import FreeCADGui as Gui

from .. import operations
from ..feedback import report, solve_outcome, study_message
from ..objects import joints, sub_assemblies
from .common import Command, active_assembly, has_joints


def _solve():
    asm = active_assembly()
    r = operations.solve(asm)
    solve_outcome(asm, r)
    return r


def _drag_mode(checked=None):
    from .. import dragging

    view = Gui.ActiveDocument.ActiveView
    on = dragging.active(view) is None if checked is None else bool(checked)
    if on and dragging.active(view) is None:
        dragging.start(active_assembly(), view)
    elif not on and dragging.active(view) is not None:
        dragging.stop(view)


def _has_revolute():
    asm = active_assembly()
    return asm is not None and any(j.JointType in ("Revolute", "Cylindrical") for j in joints(asm))


def _has_drivable():
    # Cheap (FreeCAD asks often): a joint of its own, or a flexible sub-assembly whose joints the
    # panel lists (operations.drivable_joints).
    asm = active_assembly()
    return asm is not None and (any(operations.drivable(j) for j in joints(asm))
                                or any(not getattr(s, "Rigid", True) for s in sub_assemblies(asm)))


def _drive_panel():
    """The Drive panel on the selected joint (or the assembly's first drivable one)."""
    from ..panels import drive

    asm = active_assembly()
    selected = [o for o in Gui.Selection.getSelection() if o in joints(asm) and operations.drivable(o)]
    return drive.open_panel(asm, selected[0] if selected else None)


def _drive():
    """A whole turn of the selected revolute (or the first), as an animation, stopping where it
    locks: what scripts call (the command opens the Drive panel)."""
    asm = active_assembly()
    js = [o for o in Gui.Selection.getSelection() if o in joints(asm)] or \
         [j for j in joints(asm) if j.JointType == "Revolute"]
    if not js:
        raise ValueError("select a revolute joint to drive")
    from ..qt import QtWidgets

    def frame(_):
        Gui.updateGui()

    reached = operations.drive(asm, js[0], [k * 2.0 for k in range(1, 181)], callback=frame)
    report("drove %s by %.1f degrees" % (js[0].Label, reached))
    QtWidgets.QApplication.processEvents()
    return reached


def study_joint(asm):
    """The joint a motion study sweeps: the selected one, else the assembly's first revolute."""
    js = [o for o in Gui.Selection.getSelection() if o in joints(asm)] or \
         [j for j in joints(asm) if j.JointType == "Revolute"]
    if not js:
        raise ValueError("select a revolute or slider joint for the motion study")
    return js[0]


def save_path(title, suggested, filter_text):
    """A path from a save dialog (Qt's own, the same under any desktop), or "" when cancelled."""
    from ..qt import QtWidgets

    path, _ = QtWidgets.QFileDialog.getSaveFileName(Gui.getMainWindow(), title, suggested, filter_text,
                                                    options=QtWidgets.QFileDialog.DontUseNativeDialog)
    return path


def export_motion_study(asm, joint, path):
    """Sweeps `joint` and writes the animated SVG at `path`, its plot beside it (-plot.svg) and
    the CSV (dispcon_fc.studies); reports what it wrote. Returns the study."""
    from .. import studies

    base = path[:-4] if path.lower().endswith(".svg") else path
    study = studies.export_drive_study(asm, joint, svg_path=base + ".svg", plot_path=base + "-plot.svg",
                                       csv_path=base + ".csv")
    report("%s (written: %s.svg, %s-plot.svg, %s.csv)" % (study_message(study), base, base, base),
           error=study.exit_code() != 0)
    return study


def _motion_study():
    """Drives the selected joint (or the first revolute) through a full turn, or a slider through
    its limits, and exports the animated SVG, the plot and the CSV (dispcon_fc.studies)."""
    asm = active_assembly()
    joint = study_joint(asm)
    path = save_path("Motion study of %s" % joint.Label, joint.Label + ".svg", "SVG (*.svg)")
    return export_motion_study(asm, joint, path) if path else None


def commands():
    return [
        ("Dispcon_Solve", Command("Solve", "Solve: snap the parts into place so that every joint holds; grounded "
                                  "parts stay. Select the assembly (or any of its parts) first when the "
                                  "document has several.", _solve, active=has_joints)),
        ("Dispcon_Drag", Command("Drag", "Drag mode (on/off): press on a part in the 3D view and move the mouse; "
                                 "the linkage follows. Esc leaves it.", _drag_mode, active=has_joints,
                                 checkable=True)),
        ("Dispcon_Drive", Command("Drive", "Drive: a motor on a joint. Select a Revolute or Cylindrical "
                                  "(its turn, deg) or a Slider or PointOnLine (its travel, mm), then type "
                                  "where it goes in the panel; the linkage follows.", _drive_panel,
                                  active=_has_drivable)),
        ("Dispcon_MotionStudy", Command("Motion study", "Motion study: select a revolute or slider joint, then run "
                                        "this to sweep it: lock-ups, interference along the motion, and an "
                                        "animated SVG with its plot and CSV.", _motion_study, active=_has_revolute)),
    ]
