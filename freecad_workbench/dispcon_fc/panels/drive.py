"""The Drive panel: a motor on a joint. Choose a Revolute or Cylindrical (its turn, in degrees) or
a Slider or PointOnLine (its travel, in mm), type where it goes, and the linkage follows at once.

Like the joint panel, it holds one transaction open from the moment it opens: every drive it
previews is inside it, so OK is one undo step and Cancel aborts it, which puts every part back.
A step of the box (its arrows, the wheel, the arrow keys) stops at the joint's limits; a value
typed past one is refused in words (the box keeps what was typed, nothing moves, OK disabled)
rather than cut to a prefix: with the box's range the limits, the keystroke that took it past
was dropped, so `40 deg` typed against a limit of 28.65 read `4 deg` and drove there without a
word (the fourth audit). drive_to refuses a script's value outside them too; a drive that locks
on the way stops there and says where.

A value typed key by key is driven once typing pauses (or editing ends: Enter, Tab, OK), not at
each prefix: `12` typed is not driven through 1 first, a prefix that could leave a linkage on
another branch than the value would. The arrows, the wheel and a script's value drive at once."""
import math

import FreeCADGui as Gui

from .. import operations, panels
from .base import TransactionPanel
from ..qt import QtCore, QtGui, QtWidgets
from ..resources import icon_path
from .joint import TYPING_PAUSE_MS, StepOrKey, TypedText, markers_icon, quantity_box, raw, set_unit

UNIT_TEXT = {"deg": "°", "mm": " mm"}
FULL_RANGE = 1e6  # a joint without limits: degrees or mm either way


def drivable_joints(asm):
    """The joints of `asm` a drive can move, in the assembly's order: its own, then its flexible
    sub-assemblies' at every depth (Walk2.Leg3.Revolute)."""
    return operations.drivable_joints(asm)


class DrivePanel(TransactionPanel):
    """The task panel that drives one joint of `asm` (`joint`, else the first drivable one)."""

    title = "Drive panel"

    def watched(self):
        return [self.asm] + list(self.joints)

    def __init__(self, asm, joint=None):
        self.asm = asm
        self.doc = asm.Document
        self.joints = drivable_joints(asm)
        if not self.joints:
            raise ValueError("%s has no Revolute, Cylindrical, Slider or PointOnLine joint to drive" % asm.Label)
        self.transaction = operations.Transaction(self.doc, "Drive")
        self.closed = False
        self.watch()
        self.busy = False  # a drive is running (its frames process the GUI's events)
        self.pending = False  # the value changed meanwhile: drive again once it ends
        self.keyed = False  # the box's last change was typed (not an arrow's step): not clamped
        self.ends = (-FULL_RANGE, FULL_RANGE)  # where a step stops: the limits, rounded inwards
        self.form = self._build()
        start = joint if joint in self.joints else self.joints[0]
        self.joint_box.setCurrentIndex(self.joints.index(start))
        self._joint_changed(self.joints.index(start))

    # -- the form ----------------------------------------------------------------------------
    def _build(self):
        w = QtWidgets.QWidget()
        w.setObjectName("DispconDrivePanel")
        w.setWindowTitle("Drive")
        w.setWindowIcon(QtGui.QIcon(icon_path("Dispcon_Drive.svg")))
        top = QtWidgets.QVBoxLayout(w)
        form = QtWidgets.QFormLayout()
        form.setRowWrapPolicy(QtWidgets.QFormLayout.WrapLongRows)
        top.addLayout(form)
        self.joint_box = QtWidgets.QComboBox()
        self.joint_box.setObjectName("joint")
        self.joint_box.setToolTip("The joint the motor sits on: a Revolute's or Cylindrical's turn, "
                                  "a Slider's or PointOnLine's travel")
        for j in self.joints:
            self.joint_box.addItem(QtGui.QIcon(markers_icon(j.JointType)), "%s (%s)" % (j.Label, j.JointType))
        form.addRow("Joint", self.joint_box)
        self.now = QtWidgets.QLabel()
        self.now.setObjectName("now")
        form.addRow("Now", self.now)
        self.limits = QtWidgets.QLabel()
        self.limits.setObjectName("limits")
        self.limits.setWordWrap(True)
        form.addRow("Limits", self.limits)
        self.target = quantity_box("deg", -FULL_RANGE, FULL_RANGE)
        self.target.setObjectName("target")
        self.target.setToolTip("Where the joint goes, measured as its limits are (from where it was "
                               "made); the parts follow once you pause typing, or at once with the arrows")
        form.addRow("Drive to", self.target)
        self.message = QtWidgets.QLabel()
        self.message.setObjectName("message")
        self.message.setWordWrap(True)
        top.addWidget(self.message)
        top.addStretch(1)
        self.joint_box.currentIndexChanged.connect(self._joint_changed)
        self.pause = QtCore.QTimer(w)
        self.pause.setSingleShot(True)
        self.pause.setInterval(TYPING_PAUSE_MS)
        self.pause.timeout.connect(self._drive)
        self.target.valueChanged.connect(self._changed)
        self.keys = StepOrKey(self, w)
        self.target.installEventFilter(self.keys)
        self.target.editingFinished.connect(self._flush)
        self.typing = TypedText(self, [(self.target, "Drive to")], w)
        return w

    def _changed(self, *_):
        """Typed: driven once the keys pause; stepped (arrows, wheel) or set: driven now."""
        if self.keyed and self.target.hasFocus() and not self.busy:
            self.pause.start()
            return
        self.pause.stop()
        if not self.keyed and not self.busy and self._clamped():
            return  # (the box set to the limit comes back here as a change of its own)
        self._drive()

    def _clamped(self):
        """A step past a limit stops at it, as the box's end would: the box set to the limit
        (its end rounded inwards, which value() reads as the limit); whether it was set."""
        lo, hi = self.ends
        value = raw(self.target)
        end = lo if value < lo else hi if value > hi else None
        if end is None:
            return False
        self.target.setProperty("rawValue", end)
        return True

    _edited = _changed  # (a text readable again: as any change of the box)

    def _flush(self):
        """Editing ended: what was typed and not yet driven is driven now (or refused: a typed
        value stays typed until a step, never cut to the limit)."""
        if self.pause.isActive():
            self.pause.stop()
            self._drive()

    def joint(self):
        return self.joints[self.joint_box.currentIndex()]

    def unit(self):
        return operations.DRIVE_UNITS[operations.drivable(self.joint())]

    def _joint_changed(self, index):
        """Another joint: the box takes its unit and its value now (the parts stay where the last
        drive left them)."""
        if self._gone():
            return
        j = self.joint()
        unit = UNIT_TEXT[self.unit()]
        self.form.setWindowIcon(QtGui.QIcon(markers_icon(j.JointType)))
        try:
            now = operations.drive_value(j)
        except ValueError as e:
            self._say(str(e), True)
            self._set_ok(False)
            return
        limits = operations.drive_limits(j)
        self.limits.setText("%g%s .. %g%s" % (limits[0], unit, limits[1], unit) if limits else "none")
        self.busy = True  # the box's new unit, range and value are no drive
        set_unit(self.target, self.unit())
        # The box keeps its full range, so whatever is typed is read and a value past a limit
        # is said (problem); its steps stop at the limits (_clamped). The box holds its
        # decimals: a limit between two of its steps (66.736 in a box of two decimals) is the
        # steps' end rounded inwards (66.73), which value() reads as the limit.
        lo, hi = limits if limits else (-FULL_RANGE, FULL_RANGE)
        scale = 1.0 / self.step()
        self.ends = (math.ceil(lo * scale - 1e-6) / scale, math.floor(hi * scale + 1e-6) / scale)
        self.keyed = False
        self.target.setProperty("rawValue", round(now, 9))
        self.busy = False
        self._show_now()
        self._say("Type where %s goes; the parts follow." % j.Label)
        self._set_ok(True)

    def _show_now(self):
        # As the limits and the message write it ("-5.02°"), not "-5.020°" beside "-5.02 °".
        self.now.setText("%g%s" % (operations.drive_value(self.joint()), UNIT_TEXT[self.unit()]))

    def step(self):
        """The smallest change the box shows (its last decimal)."""
        decimals = self.target.property("decimals")
        return 10.0 ** -(decimals if isinstance(decimals, int) else 2)

    def value(self):
        """The value the box asks for: at an end of its range, the joint's limit there itself
        (the box's end is the limit rounded inwards to its decimals)."""
        value = raw(self.target)
        for limit in operations.drive_limits(self.joint()) or ():
            if abs(value - limit) < self.step() * (1 - 1e-6):
                return limit
        return value

    # -- validation and the preview -------------------------------------------------------------
    def problem(self):
        """What is wrong with the value asked for, in the panel's words, or None."""
        j, value, unit = self.joint(), self.value(), UNIT_TEXT[self.unit()]
        if self.typing.bad:
            return self.typing.bad
        limits = operations.drive_limits(j)
        if limits is not None and not limits[0] - 1e-9 <= value <= limits[1] + 1e-9:
            return ("%g%s is outside %s's limits, %g%s .. %g%s: nothing moved. Type a value within them, "
                    "or widen them in its joint panel." % (value, unit, j.Label, limits[0], unit, limits[1], unit))
        return None

    def _drive(self):
        if self.closed or self._gone():  # (closing takes the focus: the box says its value again)
            return
        if self.busy:
            self.pending = True
            return
        bad = self.problem()
        if bad:
            self._say(bad, True)
            self._set_ok(False)
            return
        j, value, unit = self.joint(), self.value(), UNIT_TEXT[self.unit()]
        self.busy = True
        try:
            reached, arrived = operations.drive_to(self.asm, j, value, undo_step=False,
                                                   callback=lambda v: Gui.updateGui())
        except ValueError as e:  # drive_to has put every part back
            self._say(str(e), True)
            self._set_ok(False)
            return
        finally:
            self.busy = False
        if self._gone():
            return
        self._show_now()
        self._set_ok(True)
        if arrived:
            self._say("%s is at %g%s." % (j.Label, value, unit))
        else:
            self._say("%s locks at %.3f%s on the way to %g%s: the parts stay where it locks "
                      "(OK keeps them so)." % (j.Label, reached, unit, value, unit), True)
        if self.pending:  # (a change during the drive to the value it drove to is none)
            self.pending = False
            if self.value() != value:
                self._drive()

    # -- the task dialog ----------------------------------------------------------------------
    def accept(self):
        self._flush()  # (Enter or OK before typing paused: the value typed, then the commit)
        bad = self.problem()
        if bad:
            self._say(bad, True)
            return False
        self._close(commit=True)
        return True

    def _close(self, commit):
        if self.closed or self._gone():  # its document closed: nothing to commit or abort
            return
        self.closed = True
        self.unwatch()
        self.pause.stop()
        if commit:
            self.transaction.commit()
        else:
            self.transaction.abort()
        self.doc.recompute()
        Gui.Control.closeDialog()


def open_panel(asm, joint=None):
    """Shows the Drive panel for `joint` (or the first drivable joint of `asm`); returns it."""
    from . import joint as jp

    previous = jp.current() or current()
    if previous is not None:
        previous.reject()
    if Gui.Control.activeDialog():
        Gui.Control.closeDialog()
    panel = DrivePanel(asm, joint)
    panels.show(panel)
    panel._set_ok(panel.problem() is None)
    return panel


def current():
    """The Drive panel open now, or None."""
    return panels.current(DrivePanel)

