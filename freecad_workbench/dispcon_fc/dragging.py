"""Drag mode: press on a part in the 3D view, move the mouse, release. The grabbed point follows
the mouse in the plane through it facing the viewer; the rest of the linkage follows through
dispcon, every mouse event; the whole drag is one undo step. Esc during a drag puts every part
back and leaves no undo step.

During the drag only what is drawn moves: each moving part's Coin3D transform (the one FreeCAD
sets from its Placement) takes the solved pose every frame, and the Placements are written once,
at release (the joints' markers, hidden meanwhile, follow them then). Writing a Placement goes through FreeCAD's document
(change signals, the undo record, the tree, the observers): for a hundred parts that cost more
than the solve and the redraw together (docs/performance.md). The view is drawn lighter
meanwhile (Lighter: no navigation cube, no markers, the parts' edges only), as CAD tools draw a
moving model, and whole again at release.

The mode shows: the Drag command's button stays pressed, the status bar says so, and Esc in the 3D
view (or the button again) leaves it. One drag mode at a time in a session, as FreeCAD's own
modal tools: `_active` is that one."""
import FreeCAD as App
import FreeCADGui as Gui
import numpy as np  # (here: an import in a function goes through PySide's import hook each time)

from .objects import picked, placed_parts, preferences
from .operations import PointDrag, at_limits

_active = None


def _transform_of(part):
    """The SoTransform FreeCAD sets from `part`'s Placement (the first child of its view's root),
    or None when the part's view is drawn some other way (then its Placement is written)."""
    from pivy import coin

    vobj = getattr(part, "ViewObject", None)
    root = getattr(vobj, "RootNode", None) if vobj is not None else None
    if root is None or root.getNumChildren() == 0:
        return None
    t = root.getChild(0)
    if not isinstance(t, coin.SoTransform):
        return None
    pl = part.Placement
    x = t.translation.getValue().getValue()
    q = t.rotation.getValue().getValue()  # x, y, z, w as App.Rotation.Q
    same_q = sum((a - b) ** 2 for a, b in zip(q, pl.Rotation.Q)) < 1e-10 or \
        sum((a + b) ** 2 for a, b in zip(q, pl.Rotation.Q)) < 1e-10
    if (App.Vector(*x) - pl.Base).Length > 1e-5 * max(1.0, pl.Base.Length) or not same_q:
        return None
    return t


def _carried(root):
    """The nodes that draw a part as it is shown now, for a Moving copy: its view's root's
    children after its transform (the first, _transform_of), the display-mode switch replaced by the child it shows; and
    that switch. None when the root is not so made (then its transform is set instead)."""
    from pivy import coin

    nodes, switch = [], None
    for k in range(root.getNumChildren()):
        child = root.getChild(k)
        if k == 0:
            continue  # the transform (_transform_of): the copy places the part instead
        if isinstance(child, coin.SoSwitch):
            shown = child.whichChild.getValue()
            if switch is not None or not 0 <= shown < child.getNumChildren():
                return None
            switch = child
            nodes.append(child.getChild(shown))
        else:
            nodes.append(child)
    return (nodes, switch) if switch is not None else None


def _quaternion_product(a, b):
    """Row by row, the quaternions (w, x, y, z) a b: the turn b, then a."""
    wa, va, wb, vb = a[:, :1], a[:, 1:], b[:, :1], b[:, 1:]
    return np.hstack([wa * wb - np.sum(va * vb, axis=1, keepdims=True),
                      wa * vb + wb * va + np.cross(va, vb)])


def _turned(q, v):
    """Row by row, the vectors v turned by the quaternions q (w, x, y, z)."""
    w, u = q[:, :1], q[:, 1:]
    t = 2 * np.cross(u, v)
    return v + w * t + np.cross(u, t)


_Z = np.array([0.0, 0.0, 1.0])


class Moving:
    """What draws the moving parts during a drag, in one Coin3D node: each part's drawing (the
    nodes under its view's root: its coordinates and the display mode it shows) under one
    SoMultipleCopy, whose copy k draws part k (a switch that picks its child by the copy's
    index), placed by matrix k. The matrices come from two engines fed with every part's
    position and rotation (axis and angle) as three arrays: a frame is three calls, whatever
    the number of parts, and one change notified up the scene graph. The parts' own drawing is
    switched off meanwhile (their display-mode switches show nothing), and `end()` switches it
    back on and takes the copy away.

    Setting each part's own transform cost two pivy calls and a notification up the scene
    graph per part: 0.55-0.75 ms a frame for a hundred parts, of which the notifications
    about 0.35 ms (docs/performance.md)."""

    def __init__(self, view, parts):
        """`parts`: (row in poses(), placement in its body's frame or None, the view's root,
        its transform, the nodes that draw it, its display-mode switch), one per part."""
        from pivy import coin

        self.rows = np.array([row for row, *_ in parts], dtype=np.intp)
        locals_ = [local for _, local, *_ in parts]
        if any(local is not None for local in locals_):
            # Each part's placement in its body's frame: position, quaternion (w, x, y, z).
            ident = (App.Vector(), App.Rotation())
            pls = [(pl.Base, pl.Rotation) if pl is not None else ident for pl in locals_]
            self.local_x = np.array([[b.x, b.y, b.z] for b, _ in pls])
            self.local_q = np.array([[r.Q[3], r.Q[0], r.Q[1], r.Q[2]] for _, r in pls])
        else:
            self.local_x = self.local_q = None
        self.root = coin.SoSeparator()
        self.root.renderCaching = coin.SoSeparator.OFF  # it changes every frame
        copies = coin.SoMultipleCopy()
        pick = coin.SoSwitch()
        pick.whichChild = coin.SO_SWITCH_INHERIT  # copy k draws child k
        for _, _, _, _, nodes, _ in parts:
            group = coin.SoGroup()
            for node in nodes:
                group.addChild(node)
            pick.addChild(group)
        copies.addChild(pick)
        self.root.addChild(copies)
        self.turn = coin.SoComposeRotation()
        self.place = coin.SoComposeMatrix()
        self.place.rotation.connectFrom(self.turn.rotation)
        copies.matrix.connectFrom(self.place.matrix)
        # The fields found once (pivy looks a field up by name at every access: 30 us).
        self.translations, self.axes, self.angles = self.place.translation, self.turn.axis, self.turn.angle
        self.count = len(parts)
        self.switches = [(switch, switch.whichChild.getValue()) for *_, switch in parts]
        self.scene = view.getSceneGraph()
        self.scene.ref()  # held while the copy is in it (the view may close first)
        # Drawn first where the parts' own transforms have them (x, y, z, w, qx, qy, qz).
        at = [t.translation.getValue().getValue() + t.rotation.getValue().getValue() for *_, t, _, _ in parts]
        self.update_from(np.array([(p[0], p[1], p[2], p[6], p[3], p[4], p[5]) for p in at]), rows=False)
        self.scene.addChild(self.root)
        for switch, _ in self.switches:
            switch.whichChild = coin.SO_SWITCH_NONE

    def update_from(self, poses, rows=True):
        """Draws the parts at `poses` (Model.poses(): a row per body, x, y, z, w, qx, qy, qz;
        with rows False, a row per part). Few numpy operations: each runs cold after a
        redraw, several times slower than in a loop."""
        p = poses[self.rows] if rows else poses
        x, q = p[:, :3], p[:, 3:]
        if rows and self.local_x is not None:
            x = x + _turned(q, self.local_x)
            q = _quaternion_product(q, self.local_q)
        v = q[:, 1:]
        sin = np.sqrt(np.einsum("ij,ij->i", v, v))
        angle = 2 * np.arctan2(sin, q[:, 0])  # in [0, 2 pi]: the quaternion's sign kept
        still = sin == 0  # no turn: any axis
        axis = (v + still[:, None] * _Z) / (sin + still)[:, None]
        n = self.count
        self.translations.setValues(0, n, x.tolist())
        self.axes.setValues(0, n, axis.tolist())
        self.angles.setValues(0, n, angle.tolist())

    def end(self):
        """The parts drawn by their own views again."""
        if self.root is None:
            return
        for switch, shown in self.switches:
            switch.whichChild = shown
        self.scene.removeChild(self.root)
        self.scene.unref()
        self.root.getChild(0).matrix.disconnect()
        self.root.removeAllChildren()
        self.root = None


class Shown:
    """What a drag moves on screen: the objects that can move (parts, and the parts of
    sub-assemblies: every object the adapter has a body frame for), drawn at the engine's poses
    (`update()`, each frame) while the document is not touched; `end()` (the drag released:
    the Placements then place them) and `restore()` (a cancelled drag) draw them by their own
    views again. A part whose view is made as FreeCAD makes a part's (a transform that mirrors
    its Placement, a display-mode switch) is drawn by one Moving copy for all; one whose view
    is made otherwise but has such a transform gets that transform set each frame (its
    translation's notification off, its rotation's on: one notification per part); one with
    neither gets its Placement written, outside any undo step, and put back before the drag's
    one undo step writes them all (`put_back()`), so that undo returns it where it was.

    The joints' markers are hidden during a drag (Lighter) and stay where they are: the
    Placements written at release (or put back after Esc) place them, as at rest."""

    def __init__(self, adapter, view):
        model = adapter.model
        self.adapter = adapter
        doc = adapter.asm.Document
        rows = {n: k for k, n in enumerate(model.body_names())}  # poses() has a row per body
        moving = {adapter.names[p.Name] for p in adapter.parts if not getattr(p, "Grounded", False)}
        carried = []  # drawn by the Moving copy: (row, local, root, transform, nodes, switch)
        # Set one by one: (row of its body, its placement in the body's frame or None,
        # translation, rotation, object); the fields found once (pivy looks a field up by name
        # at every access).
        self.transforms = []
        self.written = []  # (part, its Placement before the drag): written each frame
        for name, (body, local) in adapter.frames.items():
            obj = doc.getObject(name)
            if body not in moving or obj is None:
                continue
            t = _transform_of(obj)
            drawing = _carried(obj.ViewObject.RootNode) if t is not None else None
            if drawing is not None:
                carried.append((rows[body], local, obj.ViewObject.RootNode, t) + drawing)
            elif t is not None:
                self.transforms.append((rows[body], local, t.translation, t.rotation, obj))
            elif hasattr(obj, "Shape") or obj.TypeId == "App::Link":  # drawn some other way
                self.written.append((obj, obj.Placement))
        self.moving = Moving(view, carried) if carried else None
        for _, _, translation, _, _ in self.transforms:
            translation.enableNotify(False)

    @staticmethod
    def _pose(row, local):
        pl = App.Placement(App.Vector(row[0], row[1], row[2]), App.Rotation(row[4], row[5], row[6], row[3]))
        return pl if local is None else pl.multiply(local)

    def update(self):
        poses = self.adapter.model.poses()  # every body in one call
        if self.moving is not None:
            self.moving.update_from(poses)
        if self.transforms:
            rows = poses.tolist()
            for k, local, translation, rotation, _ in self.transforms:
                p = rows[k]
                if local is None:  # a body's own part: straight from the engine
                    translation.setValue(p[0], p[1], p[2])
                    rotation.setValue(p[4], p[5], p[6], p[3])  # x, y, z, w; notifies for both
                else:
                    pl = self._pose(p, local)
                    translation.setValue(pl.Base.x, pl.Base.y, pl.Base.z)
                    rotation.setValue(*pl.Rotation.Q)
        for p, _ in self.written:
            p.Placement = self.adapter.placement_of(p)

    def put_back(self):
        for p, start in self.written:
            p.Placement = start

    def end(self):
        """The drag is over: the parts drawn by their own views, the transforms notify again."""
        if self.moving is not None:
            self.moving.end()
        for _, _, translation, _, _ in self.transforms:
            translation.enableNotify(True)
            translation.touch()

    def restore(self):
        """Everything drawn back where the document has it (the Placements were never written)."""
        self.end()
        self.put_back()
        for _, _, translation, rotation, obj in self.transforms:
            pl = obj.Placement
            translation.setValue(pl.Base.x, pl.Base.y, pl.Base.z)
            rotation.setValue(*pl.Rotation.Q)


def _holding(node, type_name):
    """Whether the Coin subgraph `node` holds a node of the type named `type_name`."""
    from pivy import coin

    kind = coin.SoType.fromName(type_name)
    if kind.isBad():
        return False
    search = coin.SoSearchAction()
    search.setType(kind)
    search.apply(node)
    return search.getPath() is not None


def _wireframe_child(switch):
    """For a part's display-mode switch showing faces and edges (FreeCAD's "Flat Lines"), the
    index of its child that shows the same edges without the faces ("Wireframe"); else None."""
    shown = switch.whichChild.getValue()
    if not 0 <= shown < switch.getNumChildren():
        return None
    child = switch.getChild(shown)
    if not (_holding(child, "SoBrepFaceSet") and _holding(child, "SoBrepEdgeSet")):
        return None
    for k in range(switch.getNumChildren()):
        other = switch.getChild(k)
        if k != shown and _holding(other, "SoBrepEdgeSet") and not _holding(other, "SoBrepFaceSet"):
            return k
    return None


class Lighter:
    """What the view leaves out during a drag, put back as it was by `restore()`: the
    navigation cube and the joints' markers are not drawn, the parts are drawn as their edges
    without their faces (FreeCAD's "Wireframe": the links stay told apart, where shaded faces
    without edges merge into one grey band), and FreeCAD's selection node neither preselects
    (its pick through the whole scene at every mouse move) nor selects (it took the button's
    release over another part, which then never reached drag mode and left the drag on).

    Under software OpenGL a frame of a hundred parts spent more on these than on anything
    else: the navigation cube, the 148 markers and the faces with their edges about 6-10,
    9-13 and 4-5 ms of CPU a frame (docs/performance.md). Everything here is state of the
    view: no document property, no preference changes. With `simplified` False (the
    preference "Simplified view during a drag" unticked) only the selection node is turned off:
    the drag is drawn in full, slower."""

    def __init__(self, view, adapter, simplified=True):
        from pivy import coin

        from . import viewproviders

        self.viewer = view.getViewer()
        self.cube = simplified and self.viewer.isEnabledNaviCube()
        if self.cube:
            self.viewer.setEnabledNaviCube(False)
        # The selection node's modes, by name (the enums' values are FreeCAD's business).
        self.modes = []
        selection = self.viewer.getSceneGraph()
        for name, off in (("highlightMode", "OFF"), ("selectionMode", "SEL_OFF")):
            field = selection.getField(name)
            if field is not None:  # FreeCAD's selection node: its mode, then off
                self.modes.append((field, field.getValue()))
                field.set(off)
        self.markers = []
        self.switches = []  # (a part's display-mode switch, the child it showed)
        if not simplified:
            return
        for j in adapter.joints + [j for j, _ in adapter.skipped]:
            proxy = viewproviders.joint_view(j)
            if proxy is not None and proxy.marker.is_visible():
                proxy.marker.set_visible(False)
                self.markers.append(proxy.marker)
        doc = adapter.asm.Document
        for name in adapter.frames:
            root = getattr(getattr(doc.getObject(name), "ViewObject", None), "RootNode", None)
            for k in range(root.getNumChildren() if root is not None else 0):
                switch = root.getChild(k)
                lines = _wireframe_child(switch) if isinstance(switch, coin.SoSwitch) else None
                if lines is not None:
                    self.switches.append((switch, switch.whichChild.getValue()))
                    switch.whichChild.setValue(lines)

    def restore(self):
        for switch, shown in self.switches:
            switch.whichChild.setValue(shown)
        for marker in self.markers:
            marker.set_visible(True)
        for field, value in self.modes:
            field.setValue(value)
        if self.cube:
            self.viewer.setEnabledNaviCube(True)
        self.switches, self.markers, self.modes, self.cube = [], [], [], False


class DragMode:
    def __init__(self, asm):
        from pivy import coin

        self.coin = coin
        self.asm = asm
        self.view = Gui.ActiveDocument.ActiveView
        self.drag = None
        self.shown = None
        # What the frames cost, from the first drag of this mode (a test reads them): the
        # solver, the writes (the transforms; the Placements at release) and how many;
        # wall time, and this thread's CPU time (what they cost when the machine is shared).
        self.frames = 0
        self.solver_seconds = self.solver_cpu = 0.0
        self.write_seconds = self.write_cpu = 0.0
        self.release_seconds = 0.0
        self.unmoved = 0  # frames whose cursor had not moved since the last (no solve, no writes)
        self.lighter = None  # what the view leaves out during a drag (Lighter)
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
            self.release()
        self._show_state(False)

    def _show_state(self, on):
        """The status bar's message and label, and the Drag button's pressed state."""
        from .qt import QtWidgets

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
            if self.drag:  # Esc during a drag: everything back, no undo step; the mode stays
                self.cancel()
            else:
                stop(self.view)

    def release(self):
        """The drag ends: the last solved poses become the parts' Placements, one undo step."""
        import time

        t0 = time.perf_counter()
        drag, shown, self.drag, self.shown = self.drag, self.shown, None, None
        shown.put_back()
        try:
            drag.finish()
        finally:
            # After the Placements are written: the parts' own views then draw them where the
            # drag left them, never for a frame where it began.
            shown.end()
            self._full_view()
        self.release_seconds += time.perf_counter() - t0
        held = at_limits(self.asm)
        if held:  # (the fourth audit's wheel, pulled round past its limit, stopped without a word)
            from .feedback import status

            status("%s: it holds the drag there" % "; ".join(held))

    def cancel(self):
        """The drag is given up: the document was never written; what is drawn goes back."""
        drag, shown, self.drag, self.shown = self.drag, self.shown, None, None
        drag.cancel()
        shown.restore()
        self._full_view()

    def _full_view(self):
        """The view drawn and picked as before the drag (Lighter)."""
        lighter, self.lighter = self.lighter, None
        if lighter is not None:
            lighter.restore()

    def button(self, event_cb):
        event = event_cb.getEvent()
        if event.getButton() != self.coin.SoMouseButtonEvent.BUTTON1:
            return
        pos = event.getPosition().getValue()
        if event.getState() == self.coin.SoMouseButtonEvent.DOWN:
            info = self.view.getObjectInfo((int(pos[0]), int(pos[1])))
            part = App.ActiveDocument.getObject(info["Object"]) if info else None
            if info and info.get("ParentObject") is not None:  # a Body, or a link to one: its tip drawn
                part = picked(info["ParentObject"], info.get("SubName", ""))[0]
            # A part of the assembly or of one of its sub-assemblies (a rigid one moves whole).
            if part is None or part not in placed_parts(self.asm) or getattr(part, "Grounded", False):
                return
            self.grab = App.Vector(info["x"], info["y"], info["z"])
            try:
                self.drag = PointDrag(self.asm, part, self.grab, live=False)
            except ValueError as e:  # a rigid sub-assembly that is grounded: nothing to drag
                App.Console.PrintMessage("Dispcon: %s\n" % e)
                return
            # The view made lighter first: the parts' drawings then moved are the lighter ones.
            self.lighter = Lighter(self.view, self.drag.adapter,
                                   simplified=preferences()["LighterDrag"])
            self.shown = Shown(self.drag.adapter, self.view)
            self.part = part
            self.normal = self.view.getViewDirection()
            event_cb.setHandled()
        elif event.getState() == self.coin.SoMouseButtonEvent.UP and self.drag:
            self.release()
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
        t0, c0 = time.perf_counter(), time.thread_time()
        moved = self.drag.move(hit)
        t1, c1 = time.perf_counter(), time.thread_time()
        if moved and self.drag.changed:
            self.shown.update()
        elif moved:
            self.unmoved += 1  # the cursor at the pixel of the last frame: nothing was solved
        self.solver_seconds += t1 - t0
        self.solver_cpu += c1 - c0
        self.write_seconds += time.perf_counter() - t1
        self.write_cpu += time.thread_time() - c1
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
