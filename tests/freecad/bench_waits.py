"""The waits a designer meets in FreeCAD besides the drag's frame rate (docs/performance.md, "Issue
14, thirteenth round: the waits besides the drag"): real FreeCAD under Xvfb at 1280x900, the
20- and 100-part crank chains of tests/freecad/chains.py (gui_drag.py's), each saved with its last
revolute taken out and timed RUNS times, the medians of their wall and CPU times printed (speed is
reported, never asserted):

- open: the saved document read, its views and markers made, until the first frame is drawn;
- Solve: the Solve command on a perturbed pose (every moving part shifted and turned a little),
  until the frame showing the solved parts is drawn;
- Check: the Check command until its panel is shown and the frame drawn;
- drag's first frame: in drag mode, the press on a coupler and the first move, until the frame
  showing it is drawn (the drag then cancelled by Esc);
- add joint: the joint panel opened on the two picked circles (the joint made and previewed),
  then its OK, each until the tree and the view are updated (the joint then undone);
- save: the document written.

What each wait gives is asserted: the document as saved (its parts, its joints, their markers
where the joints are), every joint holding after Solve to 1e-9, the Check's degrees of freedom
(the chain's 1, and 2 more for the coupler and the crank the removed joint set free), the first
move solved and drawn by the drag's moving copy, the joint added holding in one undo step, the saved
file read back with the parts where they were. DISPCON_BENCH_PROFILE=<wait> prints a cProfile of
one more run of that wait; DISPCON_BENCH_SKIP=check leaves the Check out (check100: at 100 parts
only, where main's took minutes), and so any of the waits (solve, drag, panel: with its OK, save;
open: the document opened once, untimed), to time the others alone; DISPCON_BENCH_DUMP=<file> writes the solved Placements (repr of every
float) to compare two trees' answers; DISPCON_BENCH_WB: another tree's workbench. Quits FreeCAD
itself; writes 0 to <out>/status-waits when all held.

    XDG_CONFIG_HOME=$(mktemp -d) XDG_DATA_HOME=$(mktemp -d) DISPCON_PYTHONPATH=build/python \\
        xvfb-run -a -s '-screen 0 1280x900x24' freecad tests/freecad/bench_waits.py"""
import math
import os
import sys
import tempfile
import time
import traceback

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
WB = os.environ.get("DISPCON_BENCH_WB", os.path.join(REPO, "freecad_workbench"))
sys.path.insert(0, WB)
sys.path.insert(0, os.path.join(REPO, "samples", "freecad"))
sys.path.insert(0, HERE)

import FreeCAD as App  # noqa: E402
import FreeCADGui as Gui  # noqa: E402
from dispcon_fc.qt import QtWidgets  # noqa: E402

os.environ["DISPCON_GUI_IMPORT_ONLY"] = "1"
import gui_workbench as gw  # noqa: E402  (its helpers only)
from chains import PITCH, crank_chain  # noqa: E402

RUNS = int(os.environ.get("DISPCON_BENCH_RUNS", "5"))
SIZES = [int(n) for n in os.environ.get("DISPCON_BENCH_SIZES", "20,100").split(",")]
OUT = os.environ.get("DISPCON_GUI_OUT", os.path.join(tempfile.gettempdir(), "dispcon-bench-waits"))
PROFILE = os.environ.get("DISPCON_BENCH_PROFILE", "")
SKIP = os.environ.get("DISPCON_BENCH_SKIP", "").split(",")  # waits not timed (main's Check took minutes)
WAITS = ("open", "solve", "check", "drag", "panel", "ok", "save")


def median(xs):
    xs = sorted(xs)
    return xs[len(xs) // 2]


class Frames:
    """Counts the frames the active 3D view has drawn (its viewport's frameSwapped)."""

    def __init__(self):
        self.view = None
        self.count = 0

    def watch(self, view):
        if view is not self.view:
            self.view = view
            view.graphicsView().viewport().frameSwapped.connect(self._swapped)

    def _swapped(self):
        self.count += 1

    def drawn(self, timeout=5.0):
        """Processes events until the view has drawn a frame more (asked for: the scene graph
        touched, as any change does); False when none came."""
        before, t0 = self.count, time.perf_counter()
        self.view.getViewer().getSoRenderManager().getSceneGraph().touch()
        while self.count == before:
            if time.perf_counter() - t0 > timeout:
                return False
            Gui.updateGui()
        return True


frames = Frames()


def show(doc):
    """`doc`'s 3D view active and maximised, seen isometric and whole; the view."""
    App.setActiveDocument(doc.Name)
    Gui.ActiveDocument = Gui.getDocument(doc.Name)
    mdi = Gui.getMainWindow().findChild(QtWidgets.QMdiArea)
    for sub in mdi.subWindowList():
        if sub.windowTitle().startswith(doc.Label):
            mdi.setActiveSubWindow(sub)
            sub.showMaximized()
    view = Gui.getDocument(doc.Name).ActiveView
    frames.watch(view)
    return view


def timing(wait, parts_count):
    """Whether `wait` is timed at `parts_count` parts (DISPCON_BENCH_SKIP names it, or it with the
    count: check100)."""
    return not {wait, "%s%d" % (wait, parts_count)} & set(SKIP)


def timed(name, record, fn):
    """Runs fn() (its result returned), adding its seconds to record[name] and the CPU seconds of
    FreeCAD's process to record[name + " cpu"] (on a shared machine less swayed by the others'
    load than the wall time, though not free of it)."""
    t, cpu = time.perf_counter(), time.process_time()
    out = fn()
    record.setdefault(name, []).append(time.perf_counter() - t)
    record.setdefault(name + " cpu", []).append(time.process_time() - cpu)
    return out


def profiled(name, fn):
    """fn() under cProfile when DISPCON_BENCH_PROFILE names this wait (the top printed)."""
    if PROFILE != name:
        return fn()
    import cProfile
    import pstats

    profile = cProfile.Profile()
    out = profile.runcall(fn)
    print("PROFILE of %s:" % name)
    pstats.Stats(profile, stream=sys.stdout).sort_stats("cumulative").print_stats(40)
    pstats.Stats(profile, stream=sys.stdout).sort_stats("tottime").print_stats(20)
    return out


def holds(asm, tol=1e-9):
    """Every revolute of `asm` holds to `tol`: the pins' points meet, their axes parallel."""
    for j in da.joints(asm):
        o1, o2 = j.Reference1[0], j.Reference2[0]
        gap = (o1.Placement.multVec(j.Point1 + j.Axis1 * j.Offset.Value) - o2.Placement.multVec(j.Point2)).Length
        tilt = o1.Placement.Rotation.multVec(j.Axis1).cross(o2.Placement.Rotation.multVec(j.Axis2)).Length
        assert gap <= tol and tilt <= tol, "%s does not hold: %.3g apart, axes %.3g" % (j.Label, gap, tilt)


def poses(asm):
    return {p.Name: App.Placement(p.Placement) for p in da.parts(asm)}


def same_poses(a, b, tol):
    for name, p in a.items():
        q = b[name]
        turn = min(sum((u - v) ** 2 for u, v in zip(p.Rotation.Q, q.Rotation.Q)),
                   sum((u + v) ** 2 for u, v in zip(p.Rotation.Q, q.Rotation.Q))) ** 0.5
        assert (p.Base - q.Base).Length <= tol and turn <= tol, "%s: %s and %s" % (name, p, q)


def perturb(asm, start):
    """Every moving part shifted (up to 0.03) and turned (up to 3 degrees about z) from where
    `start` (poses()) has it, by an amount of its own: the same pose each time."""
    for k, p in enumerate(da.parts(asm)):
        if p.Grounded:
            continue
        pl = start[p.Name]
        shift = App.Vector(0.03 * math.sin(k), 0.03 * math.cos(k), 0)
        p.Placement = App.Placement(pl.Base + shift, App.Rotation(App.Vector(0, 0, 1), 3 * math.sin(2 * k + 1))
                                    .multiply(pl.Rotation))


def build(parts_count, path):
    """The chain of `parts_count` parts solved, its last revolute (the last crank's pin on the
    last coupler) taken out, saved at `path`; returns that joint's references."""
    doc = App.newDocument("waits%d" % parts_count)
    asm, cranks, couplers = crank_chain(doc, parts_count // 2)
    assert len(da.parts(asm)) == parts_count, len(da.parts(asm))
    assert da.solve(asm).converged
    last = da.joints(asm)[-1]
    refs = [(last.Reference1[0].Name, last.Reference1[1][0]), (last.Reference2[0].Name, last.Reference2[1][0])]
    doc.removeObject(last.Name)
    doc.recompute()
    doc.saveAs(path)
    App.closeDocument(doc.Name)
    return refs


def one_size(parts_count, record):
    import dispcon_fc.commands as commands
    from dispcon_fc import dragging, viewproviders
    from dispcon_fc.commands import motion
    from dispcon_fc.panels import joint as jp

    path = os.path.join(OUT, "waits-%d.FCStd" % parts_count)
    refs = build(parts_count, path)
    joints_saved = 3 * (parts_count // 2) - 3
    settle = lambda: [Gui.updateGui() for _ in range(3)]  # noqa: E731

    # Open: until the first frame with the markers laid out.
    def open_doc():
        d = App.openDocument(path)
        show(d)
        assert frames.drawn(), "the opened document was not drawn"
        return d

    doc = None
    for k in range(RUNS if timing("open", parts_count) else 1):
        if doc is not None:
            App.closeDocument(doc.Name)
            settle()
        if not timing("open", parts_count):
            doc = open_doc()
            break
        doc = timed("open", record, open_doc) if k < RUNS - 1 or PROFILE != "open" else profiled("open", open_doc)
    asm = next(o for o in doc.Objects if da.is_assembly(o))
    view = show(doc)
    view.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    settle()
    assert len(da.parts(asm)) == parts_count and len(da.joints(asm)) == joints_saved
    holds(asm)
    for j in da.joints(asm):
        marker = viewproviders.joint_view(j).marker
        assert marker.is_visible(), "%s's marker is not drawn after open" % j.Label
    saved = poses(asm)

    # Solve on a perturbed pose.
    def solve():
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(asm)
        r = motion._solve()  # the Solve command's own function (Gui.runCommand returns nothing)
        assert frames.drawn()
        return r

    solved = None
    for k in range(RUNS + (PROFILE == "solve") if timing("solve", parts_count) else 0):
        perturb(asm, saved)
        doc.recompute()
        settle()
        r = timed("solve", record, solve) if k < RUNS else profiled("solve", solve)
        assert r.converged and r.iterations > 0, r.message
        holds(asm)
        if solved is None:
            solved = poses(asm)
        same_poses(solved, poses(asm), 0.0)  # the same perturbed pose solves to the same bits
    dump = os.environ.get("DISPCON_BENCH_DUMP")
    if dump and solved is not None:
        with open(dump, "a") as f:
            for name in sorted(solved):
                pl = solved[name]
                f.write("%d %s %r %r\n" % (parts_count, name, tuple(pl.Base), tuple(pl.Rotation.Q)))
    for p in da.parts(asm):  # back to the saved poses, which hold
        p.Placement = saved[p.Name]
    doc.recompute()
    settle()

    # Check: the chain's one degree of freedom and, its last pin taken out, the last crank's
    # turn and the last coupler's about its one pin.
    def check():
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(asm)
        Gui.runCommand("Dispcon_Check")
        assert frames.drawn()
        return commands.last_panel

    for k in range(RUNS + (PROFILE == "check") if timing("check", parts_count) else 0):
        panel = timed("check", record, check) if k < RUNS else profiled("check", check)
        assert Gui.Control.activeDialog() and panel.result["dof"] == 3, panel.result["message"]
        assert not panel.result["conflicting"], panel.result["conflicting"]
        panel.accept()
        settle()

    # Add the joint taken out, through the joint panel: made (the preview), then OK.
    undo = doc.UndoNames
    o1, o2 = doc.getObject(refs[0][0]), doc.getObject(refs[1][0])
    for k in range(RUNS + (PROFILE in ("panel", "ok")) if timing("panel", parts_count) else 0):
        Gui.Selection.clearSelection()

        def opened():
            p = jp.open_panel(asm=asm, joint_type="Revolute", refs=[(o1, refs[0][1]), (o2, refs[1][1])])
            assert frames.drawn()
            return p

        def ok():
            assert panel.accept()
            assert frames.drawn()

        panel = timed("panel", record, opened) if k < RUNS or PROFILE != "panel" else profiled("panel", opened)
        assert panel.joint is not None, "the panel made no joint"
        timed("ok", record, ok) if k < RUNS or PROFILE != "ok" else profiled("ok", ok)
        assert len(da.joints(asm)) == joints_saved + 1
        added = da.joints(asm)[-1]
        assert added.Label == "%s-%s" % (o1.Label, o2.Label), added.Label
        holds(asm)
        assert doc.UndoNames[0] == "Add joint" and doc.UndoNames[1:] == undo[:len(doc.UndoNames) - 1], \
            doc.UndoNames[:3]
        doc.undo()
        settle()
        assert len(da.joints(asm)) == joints_saved and doc.UndoNames == undo
    same_poses(saved, poses(asm), 0.0)

    # The drag's first frame: the press on the middle coupler and a move of 3 pixels, until
    # the frame showing it; then Esc.
    couplers = sorted((p for p in da.parts(asm) if p.Label.startswith("Coupler")), key=lambda p: p.Placement.Base.x)
    part = couplers[len(couplers) // 2 | 1]  # of the upper layer: nothing above it
    view.viewTop()
    Gui.SendMsgToActiveView("ViewFit")
    settle()
    Gui.runCommand("Dispcon_Drag", 1)
    mode = dragging._active
    for d in (0, 0.1, -0.1, 0.2, -0.2, 0.3, -0.3):
        grab = part.Placement.multVec(App.Vector(PITCH / 2 + d, 0, 0.1))
        x, y = (int(c) for c in view.getPointOnScreen(grab))
        info = view.getObjectInfo((x, y))
        if info and info["Object"] == part.Name:
            break
    assert info and info["Object"] == part.Name, "%s is not under the cursor: %s" % (part.Label, info)
    for k in range(RUNS + (PROFILE == "drag") if timing("drag", parts_count) else 0):
        def first_frame():
            gw.mouse(view, "press", x, y)
            gw.mouse(view, "move", x + 3, y - 3)
            assert frames.drawn()

        timed("drag", record, first_frame) if k < RUNS else profiled("drag", first_frame)
        assert mode.drag is not None and mode.frames >= 1, "the press did not start a drag"
        drag = mode.drag
        moved = max((drag.adapter.placement_of(p).Base - p.Placement.Base).Length for p in da.parts(asm))
        assert moved > 1e-3, "the first frame moved nothing (%.3g)" % moved
        assert mode.shown is not None and mode.shown.moving is not None, "the moving parts are not drawn moved"
        gw.mouse(view, "esc", 0, 0)
        settle()
        assert mode.drag is None
        same_poses(saved, poses(asm), 0.0)
    Gui.runCommand("Dispcon_Drag", 0)
    view.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
    settle()

    # Save (a part moved first, so each save has something new to write).
    crank = next(p for p in da.parts(asm) if p.Label == "Crank0")
    saves = RUNS + (PROFILE == "save") if timing("save", parts_count) else 0
    for k in range(saves):
        crank.Label2 = "run %d" % k
        timed("save", record, doc.save) if k < RUNS else profiled("save", doc.save)
    App.closeDocument(doc.Name)
    settle()
    doc = App.openDocument(path)
    asm = next(o for o in doc.Objects if da.is_assembly(o))
    same_poses(saved, poses(asm), 1e-12)  # (a saved file rounds a placement's last bits)
    if saves:
        assert next(p for p in da.parts(asm) if p.Label == "Crank0").Label2 == "run %d" % (saves - 1)
    App.closeDocument(doc.Name)
    settle()


status = 1
try:
    exec(open(os.path.join(WB, "InitGui.py")).read())
    Gui.activateWorkbench("DispconWorkbench")
    import dispcon_fc.assembly as da
    os.makedirs(OUT, exist_ok=True)
    results = {}
    for n in SIZES:
        results[n] = {}
        one_size(n, results[n])
    for wait in WAITS:
        print("WAIT %-6s %s; load %.1f" % (wait, ", ".join(
            "%d parts %.0f ms (%s), CPU %.0f ms (%s)" % (
                n, 1000 * median(results[n][wait]), " ".join("%.0f" % (1000 * t) for t in results[n][wait]),
                1000 * median(results[n][wait + " cpu"]), " ".join("%.0f" % (1000 * t) for t in results[n][wait + " cpu"]))
            for n in SIZES if results[n].get(wait)), os.getloadavg()[0]))
    print("%d waits timed and their results held" % sum(len(r[w]) for r in results.values() for w in WAITS if w in r))
    status = 0
except Exception:
    traceback.print_exc()
finally:
    with open(os.path.join(OUT, "status-waits"), "w") as f:
        f.write(str(status))
    QtWidgets.QApplication.instance().quit()
