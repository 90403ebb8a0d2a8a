"""Drag mode: press on a part in the 3D view, move the mouse, release. The grabbed point follows
the mouse in the plane through it facing the viewer; the rest of the linkage follows through
dispcon, every mouse event; the whole drag is one undo step."""
import FreeCAD as App
import FreeCADGui as Gui

from .objects import parts
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
        ]

    def close(self):
        for cb, kind in zip(self.callbacks, (self.coin.SoMouseButtonEvent, self.coin.SoLocation2Event)):
            self.view.removeEventCallbackPivy(kind.getClassTypeId(), cb)
        if self.drag:
            self.drag.finish()
            self.drag = None

    def button(self, event_cb):
        event = event_cb.getEvent()
        if event.getButton() != self.coin.SoMouseButtonEvent.BUTTON1:
            return
        pos = event.getPosition().getValue()
        if event.getState() == self.coin.SoMouseButtonEvent.DOWN:
            info = self.view.getObjectInfo((int(pos[0]), int(pos[1])))
            part = App.ActiveDocument.getObject(info["Object"]) if info else None
            if part is None or part not in parts(self.asm) or getattr(part, "Grounded", False):
                return
            self.grab = App.Vector(info["x"], info["y"], info["z"])
            self.drag = PointDrag(self.asm, part, self.grab)
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


def toggle(asm):
    """Turns drag mode on or off; returns the mode when on."""
    global _active
    if _active is not None:
        _active.close()
        _active = None
        return None
    _active = DragMode(asm)
    return _active
