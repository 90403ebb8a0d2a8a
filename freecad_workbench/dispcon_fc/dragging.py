"""Drag mode: press on a part in the 3D view, move the mouse, release. The grabbed point follows
the mouse in the plane through it facing the viewer; the rest of the linkage follows through
dispcon, every mouse event; the whole drag is one undo step.

The mode shows: the Drag command's button stays pressed, the status bar says so, and Esc in the 3D
view (or the button again) leaves it. One drag mode at a time in a session, as FreeCAD's own
modal tools: `_active` is that one."""
import FreeCAD as App
import FreeCADGui as Gui

from .objects import placed_parts
from .operations import PointDrag

_active = None


class DragMode:
    def __init__(self, asm):
        from pivy import coin

        self.coin = coin
        self.asm = asm
        self.view = Gui.ActiveDocument.ActiveView
        self.drag = None
        self.frames = 0
        self.solver_seconds = 0.0
        self.callbacks = [
            self.view.addEventCallbackPivy(coin.SoMouseButtonEvent.getClassTypeId(), self.button),
            self.view.addEventCallbackPivy(coin.SoLocation2Event.getClassTypeId(), self.motion),
            self.view.addEventCallbackPivy(coin.SoKeyboardEvent.getClassTypeId(), self.key),
        ]
        self._show_state(True)

    def close(self):
        kinds = (self.coin.SoMouseButtonEvent, self.coin.SoLocation2Event, self.coin.SoKeyboardEvent)
        for cb, kind in zip(self.callbacks, kinds):
            self.view.removeEventCallbackPivy(kind.getClassTypeId(), cb)
        if self.drag:
            self.drag.finish()
            self.drag = None
        self._show_state(False)

    def _show_state(self, on):
        """The status bar's message and label, and the Drag button's pressed state."""
        from PySide2 import QtWidgets

        window = Gui.getMainWindow()
        bar = window.statusBar()
        label = bar.findChild(QtWidgets.QLabel, "DispconDragState")
        if on:
            text = "Drag mode: press on a part and move the mouse; Esc leaves"
            if label is None:
                label = QtWidgets.QLabel(text)
                label.setObjectName("DispconDragState")
                label.setStyleSheet("color: #ffffff; background: #4e9a06; padding: 1px 6px;")
                bar.addPermanentWidget(label)
            label.show()
            bar.showMessage(text)
        else:
            if label is not None:
                bar.removeWidget(label)
                label.deleteLater()
            bar.clearMessage()
        for action in window.findChildren(QtWidgets.QAction, "Dispcon_Drag"):
            if action.isCheckable() and action.isChecked() != on:
                action.blockSignals(True)
                action.setChecked(on)
                action.blockSignals(False)

    def key(self, event_cb):
        event = event_cb.getEvent()
        if event.getKey() == self.coin.SoKeyboardEvent.ESCAPE and event.getState() == self.coin.SoButtonEvent.DOWN:
            event_cb.setHandled()
            stop(self.view)

    def button(self, event_cb):
        event = event_cb.getEvent()
        if event.getButton() != self.coin.SoMouseButtonEvent.BUTTON1:
            return
        pos = event.getPosition().getValue()
        if event.getState() == self.coin.SoMouseButtonEvent.DOWN:
            info = self.view.getObjectInfo((int(pos[0]), int(pos[1])))
            part = App.ActiveDocument.getObject(info["Object"]) if info else None
            # A part of the assembly or of one of its sub-assemblies (a rigid one moves whole).
            if part is None or part not in placed_parts(self.asm) or getattr(part, "Grounded", False):
                return
            self.grab = App.Vector(info["x"], info["y"], info["z"])
            try:
                self.drag = PointDrag(self.asm, part, self.grab)
            except ValueError as e:  # a rigid sub-assembly that is grounded: nothing to drag
                App.Console.PrintMessage("Dispcon: %s\n" % e)
                return
            self.part = part
            self.normal = self.view.getViewDirection()
            event_cb.setHandled()
        elif event.getState() == self.coin.SoMouseButtonEvent.UP and self.drag:
            self.drag.finish()
            self.drag = None
            event_cb.setHandled()

    def motion(self, event_cb):
        if not self.drag:
            return
        import time

        pos = event_cb.getEvent().getPosition().getValue()
        point = self.view.getPoint(int(pos[0]), int(pos[1]))
        direction = self.view.getViewDirection()
        # The cursor's ray meets the plane through the grab point facing the viewer.
        d = direction.dot(self.normal)
        if abs(d) < 1e-12:
            return
        t = (self.grab - point).dot(self.normal) / d
        hit = point + direction * t
        t0 = time.perf_counter()
        self.drag.move(hit)
        self.solver_seconds += time.perf_counter() - t0
        self.frames += 1
        event_cb.setHandled()


def active(view=None):
    """The drag mode that is on, or None (`view` is accepted for the callers' clarity: there is
    one drag mode at a time)."""
    return _active


def start(asm, view=None):
    """Turns drag mode on for `asm` (off first wherever it was on); returns the mode."""
    global _active
    if asm is None:
        raise ValueError("no assembly to drag: create one with New assembly")
    if _active is not None:
        stop()
    _active = DragMode(asm)
    return _active


def stop(view=None):
    """Turns drag mode off."""
    global _active
    mode, _active = _active, None
    if mode is not None:
        mode.close()


def toggle(asm):
    """Turns drag mode on or off; returns the mode when on."""
    if _active is not None:
        stop()
        return None
    return start(asm)
