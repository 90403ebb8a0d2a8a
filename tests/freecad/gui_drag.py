"""GUI test in real FreeCAD under Xvfb: activate the workbench, build the four-bar from parts,
run its Solve command, turn drag mode on and drag the coupler with Coin3D mouse events, check that
the linkage followed; then time drags of a 20-part and a 100-part assembly, each in its own window
(the split per frame printed; the 100-part drag's end result, its Esc and its undo asserted), save
screenshots. Quits FreeCAD itself."""
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
from dispcon_fc.qt import QtWidgets  # noqa: E402

os.environ["DISPCON_GUI_IMPORT_ONLY"] = "1"
import gui_workbench as gw  # noqa: E402  (its helpers only)
from chains import crank_chain  # noqa: E402


def same_placement(p, q, tol=1e-12):
    """Equal positions and rotations (a quaternion or its negative) to `tol`."""
    a, b = p.Rotation.Q, q.Rotation.Q
    turn = min(sum((u - v) ** 2 for u, v in zip(a, b)), sum((u + v) ** 2 for u, v in zip(a, b))) ** 0.5
    return (p.Base - q.Base).Length <= tol and turn <= tol


def drawn(view, marker):
    """Where a joint marker's glyph is drawn: the point and z axis of the transforms on the path
    from the marker's root to its glyph, whichever node holds them."""
    from pivy import coin

    path = coin.SoPath(marker.root)
    path.append(marker.visible)
    path.append(marker.annotation)
    action = coin.SoGetMatrixAction(view.getViewer().getSoRenderManager().getViewportRegion())
    action.apply(path)
    m = action.getMatrix()
    at, axis = m.multVecMatrix(coin.SbVec3f(0, 0, 0)), m.multDirMatrix(coin.SbVec3f(0, 0, 1))
    return App.Vector(*at.getValue()), App.Vector(*axis.getValue())


def drawings(view, asm):
    """Where and how each part is drawn, as the scene graph has it: {name: [(Placement, mode),
    ...]}, one entry per drawing, by its own view (its root's transform and the child its
    display-mode switch shows) or by a copy of an SoMultipleCopy in the scene (copy k drawing
    the k-th child of a switch that picks its child by the copy's index, which holds a node of
    the part's view, placed by matrix k). The mode is named by what the drawing holds ("Flat
    Lines": faces and edges, "Shaded": faces only, "Wireframe": edges only, "Other")."""
    from pivy import coin

    def holds(node, kind):
        search = coin.SoSearchAction()
        search.setType(coin.SoType.fromName(kind))
        search.apply(node)
        return search.getPath() is not None

    def mode(node):
        faces, edges = holds(node, "SoBrepFaceSet"), holds(node, "SoBrepEdgeSet")
        return "Flat Lines" if faces and edges else "Shaded" if faces else "Wireframe" if edges else "Other"

    def placed(rows):  # Coin's matrix (a point is a row, times it) as a Placement
        return App.Placement(App.Matrix(*[rows[j][i] for i in range(4) for j in range(4)]))

    out, owner = {}, {}  # owner: a node of a part's view (by address) -> the part's name
    for p in da.parts(asm):
        root = p.ViewObject.RootNode
        out[p.Name] = []
        for k in range(1, root.getNumChildren()):
            child = root.getChild(k)
            owner[int(child.this)] = p.Name
            if isinstance(child, coin.SoSwitch):
                for i in range(child.getNumChildren()):
                    owner[int(child.getChild(i).this)] = p.Name
                if child.whichChild.getValue() >= 0:
                    t = root.getChild(0)
                    out[p.Name].append((App.Placement(App.Vector(*t.translation.getValue().getValue()),
                                                      App.Rotation(*t.rotation.getValue().getValue())),
                                        mode(child.getChild(child.whichChild.getValue()))))
    search = coin.SoSearchAction()
    search.setType(coin.SoMultipleCopy.getClassTypeId())
    search.setInterest(coin.SoSearchAction.ALL)
    search.apply(view.getViewer().getSoRenderManager().getSceneGraph())
    for n in range(search.getPaths().getLength()):
        copies = search.getPaths()[n].getTail()
        for c in range(copies.getNumChildren()):
            pick = copies.getChild(c)
            if not (isinstance(pick, coin.SoSwitch) and pick.whichChild.getValue() == coin.SO_SWITCH_INHERIT):
                continue
            for k in range(min(pick.getNumChildren(), copies.matrix.getNum())):
                group = pick.getChild(k)
                names = {owner.get(int(group.getChild(i).this)) for i in range(group.getNumChildren())} - {None}
                for name in names:
                    out[name].append((placed(copies.matrix[k].getValue()), mode(group)))
    return out


def shown_modes(view, asm):
    """Each part's display mode as drawn ("Flat Lines", "Shaded", "Wireframe", "Other"; see
    drawings()), each part drawn once."""
    out = {}
    for name, drawn_as in drawings(view, asm).items():
        assert len(drawn_as) == 1, "%s is drawn %d times" % (name, len(drawn_as))
        out[name] = drawn_as[0][1]
    return out


def save_near(view, point, path, height=8.0):
    """A screenshot of the view's camera moved over `point` and zoomed to `height` units (an
    orthographic camera's field), the camera put back after."""
    camera = view.getCameraNode()
    position, size = tuple(camera.position.getValue().getValue()), camera.height.getValue()
    direction = view.getViewDirection()
    shift = point - App.Vector(*position)
    at = App.Vector(*position) + shift - direction * shift.dot(direction)  # at the same depth
    camera.position.setValue(at.x, at.y, at.z)
    camera.height.setValue(height)
    try:
        view.saveImage(path, 1280, 900, "White")
    finally:
        camera.position.setValue(*position)
        camera.height.setValue(size)


def part_at(view, asm, x, y):
    """The name of the part drawn nearest under pixel (x, y), by its own view or by a copy
    (drawings()), or None: the picked point's path holds a node of the part's view."""
    from pivy import coin

    owner = {}
    for p in da.parts(asm):
        root = p.ViewObject.RootNode
        for k in range(1, root.getNumChildren()):
            child = root.getChild(k)
            owner[int(child.this)] = p.Name
            for i in range(child.getNumChildren() if isinstance(child, coin.SoSwitch) else 0):
                owner[int(child.getChild(i).this)] = p.Name
    manager = view.getViewer().getSoRenderManager()
    pick = coin.SoRayPickAction(manager.getViewportRegion())
    pick.setPoint(coin.SbVec2s(x, y))
    pick.setRadius(2)
    pick.apply(manager.getSceneGraph())
    point = pick.getPickedPoint()
    path = point.getPath() if point is not None else None
    names = [owner.get(int(path.getNode(i).this)) for i in range(path.getLength())] if path else []
    return next((n for n in names if n), None)


def other_part_on_screen(view, asm, part):
    """A pixel where another part than `part` is drawn nearest under the cursor: one of its
    vertices where it is drawn (during a drag the moving parts are drawn by a copy, where the
    engine has them, and FreeCAD's pick does not name them: part_at)."""
    drawn = drawings(view, asm)
    others = sorted((p for p in da.parts(asm) if p is not part),
                    key=lambda p: (p.Placement.Base - part.Placement.Base).Length)
    for p in others[:10]:
        to_drawn = drawn[p.Name][0][0].multiply(p.Placement.inverse())
        for v in p.Shape.Vertexes:
            x, y = (int(round(c)) for c in view.getPointOnScreen(to_drawn.multVec(v.Point)))
            if part_at(view, asm, x, y) == p.Name:
                return x, y
    raise AssertionError("no other part on the screen")


def drag_timed(doc, asm, part, local_grab, path, check=False, top=False):
    """Drags `part` by its point `local_grab` (or by the first of a list of points that shows
    on the screen: a joint's marker, drawn over the parts, may hide one) along `path` (a
    function of the frame k = 1, 2 ... giving the cursor: pixels from the grab point on the
    screen, or a 3D displacement of the grab point from where it starts; path(None) is the
    number of frames) in the document's own maximised window (seen
    isometric, or from the top), each frame's redraw waited for (the view's frames swapped);
    returns the split per frame. With check: Esc cancels a first drag drawn in full (the
    preference "Simplified view during a drag" unticked; everything back, no undo
    step), the drawn parts follow the engine during the drag in a lighter view (no navigation
    cube, no markers, edges only) while the document stays unchanged; released over another
    part, the drag ends; after release the Placements are the engine's poses, the markers and
    the full view are back, every joint holds to 1e-9 and one undo puts everything back."""
    from dispcon_fc import objects, viewproviders

    Gui.updateGui()
    Gui.setActiveDocument(doc.Name)
    mdi = Gui.getMainWindow().findChild(QtWidgets.QMdiArea)
    for sub in mdi.subWindowList():
        if sub.windowTitle().startswith(doc.Label):
            mdi.setActiveSubWindow(sub)
            sub.showMaximized()
    Gui.updateGui()
    view = Gui.getDocument(doc.Name).ActiveView
    view.viewTop() if top else view.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    Gui.updateGui()
    swapped = [0]
    view.graphicsView().viewport().frameSwapped.connect(lambda: swapped.__setitem__(0, swapped[0] + 1))

    cpu = [0.0]

    def redraw():
        """Processes events until the view has shown a new frame; its time, or None. Adds the
        process's CPU time (OpenGL's rendering threads included) to cpu[0]."""
        before, t0, c0 = swapped[0], time.perf_counter(), time.process_time()
        while swapped[0] == before:
            if time.perf_counter() - t0 > 2:
                return None
            Gui.updateGui()
        cpu[0] += time.process_time() - c0
        return time.perf_counter() - t0

    # What a redraw of these parts costs with nothing moving.
    idle = []
    for _ in range(10):
        view.getViewer().getSoRenderManager().getSceneGraph().touch()
        idle.append(redraw())
    assert None not in idle, "the view did not redraw"
    idle_cpu, cpu[0] = cpu[0] / len(idle), 0.0
    Gui.runCommand("Dispcon_Drag", 1)
    mode = dragging._active
    for grab in local_grab if isinstance(local_grab, list) else [local_grab]:
        grab = part.Placement.multVec(grab)
        x, y = (int(c) for c in view.getPointOnScreen(grab))
        info = view.getObjectInfo((x, y))
        if info and info["Object"] == part.Name:
            break
    assert info and info["Object"] == part.Name, "%s is not under the cursor: %s" % (part.Label, info)
    moving = [p for p in da.parts(asm) if not p.Grounded]
    start = {p.Name: p.Placement for p in moving}
    undo = doc.UndoNames  # (FreeCAD keeps the last 20 steps: compare the names)
    frames = path(None)

    def cursor(k):
        to = path(k)
        if isinstance(to, App.Vector):
            return tuple(int(round(c)) for c in view.getPointOnScreen(grab + to))
        return x + to[0], y + to[1]

    viewer = view.getViewer()
    modes = [viewer.getSceneGraph().getField(f) for f in ("highlightMode", "selectionMode")]
    full = dict(modes=[m.getValue() for m in modes], cube=viewer.isEnabledNaviCube(), parts=shown_modes(view, asm))
    assert full["cube"] and "Flat Lines" in full["parts"].values(), "not the view a drag makes lighter: %s" % full

    def markers_in_place(after):
        """After a drag: every marker drawn, where the Placements put its joint, and the view
        drawn and picked as before (the drag made it lighter: Lighter)."""
        for j in da.joints(asm):
            marker = viewproviders.joint_view(j).marker
            assert marker.is_visible(), "%s's marker is hidden after %s" % (j.Label, after)
            at, axis = drawn(view, marker)
            pl = j.Reference1[0].Placement
            assert (at - pl.multVec(j.Point1)).Length < 1e-5 and (axis - pl.Rotation.multVec(j.Axis1)).Length < 1e-5, \
                "%s's marker is not in place after %s" % (j.Label, after)
        now = dict(modes=[m.getValue() for m in modes], cube=viewer.isEnabledNaviCube(), parts=shown_modes(view, asm))
        assert now == full, "the view is not put back after %s: %s, before the drag %s" % (after, now, full)

    if check:
        # Esc during a drag: everything drawn goes back, the document never changed. This one
        # is drawn in full (the preference "Simplified view during a drag" unticked): the cube
        # and the markers stay, only selection is off.
        prefs = App.ParamGet(objects.PARAMETERS)
        prefs.SetBool("LighterDrag", False)
        try:
            gw.mouse(view, "press", x, y)
            for k in range(1, 6):
                gw.mouse(view, "move", *cursor(k))
            assert viewer.isEnabledNaviCube(), "the navigation cube went with the simplified view unticked"
            assert shown_modes(view, asm) == full["parts"], "the parts were drawn lighter with the simplified view unticked"
            assert [m.get() for m in modes] == ["OFF", "SEL_OFF"], "selection on during a full-view drag"
            gw.mouse(view, "esc", 0, 0)
        finally:
            prefs.RemBool("LighterDrag")
        assert dragging._active is mode and mode.drag is None, "Esc did not cancel the drag alone"
        assert doc.UndoNames == undo, "a cancelled drag left an undo step: %s" % doc.UndoNames[:2]
        for p in moving:
            assert same_placement(p.Placement, start[p.Name], 0), "%s moved" % p.Label
            t = p.ViewObject.RootNode.getChild(0)
            shown = App.Placement(App.Vector(*t.translation.getValue().getValue()),
                                  App.Rotation(*t.rotation.getValue().getValue()))
            assert same_placement(shown, p.Placement, 1e-5), "%s is not drawn back in place" % p.Label
        markers_in_place("Esc")
        mode.frames, mode.solver_seconds, mode.write_seconds, mode.release_seconds = 0, 0.0, 0.0, 0.0
        mode.unmoved = 0
        mode.solver_cpu = mode.write_cpu = cpu[0] = 0.0
    t0 = time.perf_counter()
    gw.mouse(view, "press", x, y)
    press = time.perf_counter() - t0
    assert mode.drag is not None, "pressing on %s did not start a drag" % part.Label
    redraws = []
    # Every event of the path moves the cursor by a pixel or more (a real drag): each one is
    # solved, written and drawn, and the split below is over all of them. (Drag mode still
    # skips an event at the last one's pixel, which a real mouse seldom sends.)
    handled = 0.0
    for k in range(1, frames + 1):
        t0 = time.perf_counter()
        gw.mouse(view, "move", *cursor(k))
        handled += time.perf_counter() - t0
        redraws.append(redraw())
    assert None not in redraws, "a frame of the drag was not drawn"
    assert mode.unmoved == 0 and mode.frames == frames, \
        "%d of %d events were not solved (the cursor at the last one's pixel)" % (mode.unmoved, frames)
    redraw_cpu = cpu[0] / frames
    drag = mode.drag
    if check:
        # During the drag the document is unchanged; what is drawn is the engine's poses.
        drawn_now = drawings(view, asm)
        for p in moving:
            assert same_placement(p.Placement, start[p.Name], 0), "%s was written during the drag" % p.Label
            assert len(drawn_now[p.Name]) == 1, "%s is drawn %d times" % (p.Label, len(drawn_now[p.Name]))
            # (Coin3D holds single precision: 4e-6 apart at 40 units)
            assert same_placement(drawn_now[p.Name][0][0], drag.adapter.placement_of(p), 1e-5), \
                "%s is not drawn where solved" % p.Label
        # The view is lighter: no navigation cube, no markers (they stay where they were, and
        # the Placements place them at release), the parts' edges without their faces, no
        # preselection nor selection.
        assert not viewer.isEnabledNaviCube(), "the navigation cube is drawn during the drag"
        hidden = [j.Label for j in da.joints(asm) if viewproviders.joint_view(j).marker.is_visible()]
        assert not hidden, "markers drawn during the drag: %s" % hidden[:3]
        solid = [n for n, m in shown_modes(view, asm).items() if m != "Wireframe"]
        assert not solid, "parts drawn with their faces during the drag: %s" % solid[:3]
        assert [m.get() for m in modes] == ["OFF", "SEL_OFF"], \
            "preselection or selection on during the drag: %s" % [m.get() for m in modes]
        view.saveImage(os.path.join(OUT, "hundred-during.png"), 1280, 900, "White")
        save_near(view, part.Placement.Base, os.path.join(OUT, "hundred-during-near.png"))
        # Released over another part (the linkage lags the cursor): the drag ends all the same,
        # and nothing is selected (FreeCAD's selection node took that release before).
        Gui.Selection.clearSelection()
        release = other_part_on_screen(view, asm, part)
    else:
        release = cursor(frames)
    gw.mouse(view, "release", *release)
    assert mode.drag is None, "the release at %s did not end the drag" % (release,)
    release_redraw = redraw() or 0.0
    Gui.runCommand("Dispcon_Drag", 0)
    moved = max((p.Placement.Base - start[p.Name].Base).Length for p in moving)
    assert moved > 0.05, "the parts did not move (%.4f)" % moved
    if check:
        for p in da.parts(asm):
            assert same_placement(p.Placement, drag.adapter.placement_of(p)), "%s is not where solved" % p.Label
        markers_in_place("release")
        save_near(view, part.Placement.Base, os.path.join(OUT, "hundred-near.png"))
        assert not Gui.Selection.getSelection(), "the release selected %s" % Gui.Selection.getSelection()[0].Label
        # Every joint holds to 1e-9 as the document now stands (the chain's are revolutes: the
        # pins' points meet and their axes are parallel).
        for j in da.joints(asm):
            assert j.JointType == "Revolute", j.JointType
            o1, o2 = j.Reference1[0], j.Reference2[0]
            gap = (o1.Placement.multVec(j.Point1 + j.Axis1 * j.Offset.Value) - o2.Placement.multVec(j.Point2)).Length
            tilt = o1.Placement.Rotation.multVec(j.Axis1).cross(o2.Placement.Rotation.multVec(j.Axis2)).Length
            assert gap <= 1e-9 and tilt <= 1e-9, "%s does not hold: %.3g apart, axes %.3g" % (j.Label, gap, tilt)
        assert doc.UndoNames[0] == "Drag %s" % part.Label and doc.UndoNames[1:] == undo[:len(doc.UndoNames) - 1], \
            "the drag did not make one undo step: %s" % doc.UndoNames[:3]
        doc.undo()
        for p in moving:
            assert same_placement(p.Placement, start[p.Name], 1e-12), "undo left %s moved" % p.Label
        doc.redo()
    n = mode.frames
    return dict(parts=len(da.parts(asm)), moving=len(moving), frames=n, press=press,
                solver=mode.solver_seconds / n, writes=mode.write_seconds / n,
                event=(handled - mode.solver_seconds - mode.write_seconds) / n,
                redraw=sum(redraws) / n, idle=sorted(idle)[len(idle) // 2],
                solver_cpu=mode.solver_cpu / n, writes_cpu=mode.write_cpu / n, redraw_cpu=redraw_cpu,
                idle_cpu=idle_cpu,
                release=mode.release_seconds, release_redraw=release_redraw,
                fps=n / (handled + sum(redraws)))


def report(name, t):
    print("%s drag (%d parts, %d moving), %d frames, the cursor moved every one: %.1f frames/s; per frame, "
          "wall (CPU): solver %.2f (%.2f) ms; writes %.2f (%.2f) ms (transforms); rest of the event %.2f ms; "
          "redraw %.1f (%.1f) ms; a redraw with nothing moving %.1f (%.1f) ms; press %.0f ms; "
          "release %.0f ms (Placements, recompute) and its redraw %.0f ms; load %.1f"
          % (name, t["parts"], t["moving"], t["frames"], t["fps"], 1000 * t["solver"], 1000 * t["solver_cpu"],
             1000 * t["writes"], 1000 * t["writes_cpu"], 1000 * t["event"], 1000 * t["redraw"],
             1000 * t["redraw_cpu"], 1000 * t["idle"], 1000 * t["idle_cpu"], 1000 * t["press"],
             1000 * t["release"], 1000 * t["release_redraw"], os.getloadavg()[0]))


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
    mid = coupler.Placement.multVec(App.Vector(1.5, 0, 0.1))

    def screen(p):
        x, y = view.getPointOnScreen(p)
        return int(x), int(y)

    x0, y0 = screen(mid)
    info = view.getObjectInfo((x0, y0))
    assert info and info["Object"] == coupler.Name, "the coupler is not under the cursor: %s" % info
    crank_before = angle_of(crank)
    gw.mouse(view, "press", x0, y0)
    assert mode.drag is not None, "pressing on the coupler did not start a drag"
    for k in range(1, 31):
        gw.mouse(view, "move", x0 - 2 * k, y0 + 3 * k)
        Gui.updateGui()
    gw.mouse(view, "release", x0 - 60, y0 + 90)
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
    from dispcon_fc.qt import QtGui

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

    # Frame rates, each assembly in its own window: the 20-part one (five four-bars side by
    # side, 15 moving parts and 5 grounds; one four-bar moves) and the 100-part chain (all 99
    # moving parts move), dragged with mouse events through drag mode. Timing is reported,
    # not asserted (the machine is shared); the end result is asserted.
    doc2 = App.newDocument("twenty")
    asm2 = da.create_assembly(doc2)
    couplers2 = []
    for k in range(5):
        a, g2, c2, cp2, r2 = fourbar(doc2, OUT)
        for o in (g2, c2, cp2, r2):
            o.Placement = App.Placement(o.Placement.Base + App.Vector(0, 0, 2 * k), o.Placement.Rotation)
            asm2.addObject(o)
        for j in da.joints(a):
            asm2.addObject(j)
        couplers2.append(cp2)
    assert da.solve(asm2).converged
    twenty = drag_timed(doc2, asm2, couplers2[4], App.Vector(1.5, 0, 0.1), lambda k: 60 if k is None else (-2 * k, 3 * k))
    report("20-part", twenty)
    Gui.getDocument(doc2.Name).ActiveView.saveImage(os.path.join(OUT, "twenty.png"), 1280, 900, "White")

    doc4 = App.newDocument("hundred")
    asm4, cranks4, couplers4 = crank_chain(doc4, 50)
    assert len(da.parts(asm4)) == 100, len(da.parts(asm4))
    assert da.solve(asm4).converged
    grabbed = couplers4[25]  # a coupler of the upper layer: nothing above it
    # The cursor where the grabbed point goes when the cranks turn from 60 to 150 degrees and
    # back, twice (the coupler translates on a circle), away from the chain's change point at
    # 180 degrees, where the parallelograms could fold into crossed ones: the circle's pixels
    # in turn, as a mouse sends them, so that every event moves the cursor by a pixel or more.
    # Seen from the top with the whole chain in the window, the circle is a dozen pixels across.
    pixels = []  # the path, made once the view is set up (drag_timed)

    def along(k):
        if not pixels:
            view = Gui.getDocument(doc4.Name).ActiveView
            at = grabbed.Placement.multVec(on_coupler[0])
            x0, y0 = (int(c) for c in view.getPointOnScreen(at))
            leg, a0 = [(x0, y0)], math.radians(60)
            for i in range(1, 1801):
                a = math.radians(60 + 0.05 * i)
                p = at + App.Vector(math.cos(a) - math.cos(a0), math.sin(a) - math.sin(a0), 0)
                px = tuple(int(round(c)) for c in view.getPointOnScreen(p))
                if px != leg[-1]:
                    leg.append(px)
            back = leg[-2::-1]
            pixels.extend(leg[1:] + back[1:] + leg[1:])  # 60 -> 150 -> 60 -> 150 degrees
            pixels[:] = [(px - x0, py - y0) for px, py in pixels]
            assert len(pixels) >= 40 and all(a != b for a, b in zip([(0, 0)] + pixels, pixels)), pixels
        return len(pixels) if k is None else pixels[k - 1]

    # Seen from the top, the cursor's plane is the chain's; pressed on the coupler's middle, or
    # beside it where the markers' rings at its ends cross the middle.
    on_coupler = [App.Vector(0.75 + d, 0, 0.1) for d in (0, 0.1, -0.1, 0.2, -0.2, 0.3, -0.3)]
    hundred = drag_timed(doc4, asm4, grabbed, on_coupler, along, check=True, top=True)
    # One degree of freedom: every crank turned with the first, by about the cursor's 90.
    turned = [math.degrees(angle_of(c)) for c in cranks4]
    assert all(abs(t - turned[0]) < 1e-6 for t in turned), "the cranks did not turn together"
    assert abs(turned[0] - 150) < 20, "the cranks did not follow the cursor: %.1f degrees" % turned[0]
    report("100-part", hundred)
    Gui.getDocument(doc4.Name).ActiveView.saveImage(os.path.join(OUT, "hundred.png"), 1280, 900, "White")
    print("1 passed, 0 failed")
    status = 0
except Exception:
    traceback.print_exc()
    print("0 passed, 1 failed")
finally:
    with open(os.path.join(OUT, "status"), "w") as f:
        f.write(str(status))
    QtWidgets.QApplication.instance().quit()
