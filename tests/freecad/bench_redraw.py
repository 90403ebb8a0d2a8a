"""What the joint markers cost a redraw (docs/performance.md, "Issue 14, fifteenth round: what the
markers cost a redraw"): real FreeCAD under Xvfb at 1280x900, not a test (speed is measured, never
asserted). gui_drag.py's 100-part chain (tests/freecad/chains.py, 50 cranks: 148 revolutes) in its
own maximised window, seen from the top and whole, redrawn with nothing moving (the scene touched,
each frame waited for until it is shown) in four states, taken in turn ROUNDS times:

- `shown`: the markers drawn, as at rest;
- `hidden`: the markers hidden by their own switch, as during a drag (dragging.Lighter);
- `absent`: the joints' views hidden (their display mode off: no node of a marker traversed), the
  floor that `shown` and `hidden` are measured against;
- `lighter shown` / `lighter hidden` / `lighter absent`: the same in the drag's lighter view
  (dragging.Lighter: no navigation cube, the parts' edges only), what a drag frame redraws.

Each state's REDRAWS redraws give the CPU time of FreeCAD's main thread (time.thread_time: the
traversal, pivy's callbacks, Mesa's vertex work on that thread; not llvmpipe's rasterising threads,
which the markers' few pixels hardly load) and of the whole process, and the wall time; the
medians over the rounds are printed (DISPCON_BENCH_STATES="shown,hidden": those only). DISPCON_BENCH_WB picks another tree's workbench (before/after
with one module). Quits FreeCAD itself.

    XDG_CONFIG_HOME=$(mktemp -d) XDG_DATA_HOME=$(mktemp -d) DISPCON_PYTHONPATH=build/python \\
        xvfb-run -a -s '-screen 0 1280x900x24' freecad tests/freecad/bench_redraw.py"""
import os
import sys
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
from chains import crank_chain  # noqa: E402

ROUNDS = int(os.environ.get("DISPCON_BENCH_ROUNDS", "5"))
REDRAWS = int(os.environ.get("DISPCON_BENCH_REDRAWS", "30"))
OUT = os.environ.get("DISPCON_GUI_OUT", "/tmp/dispcon-bench-redraw")


class _Adapter:
    """What dragging.Lighter reads of a drag's adapter: the joints and the parts' names."""

    def __init__(self, asm, joints, parts):
        self.asm, self.joints, self.skipped = asm, joints, []
        self.frames = {p.Name: None for p in parts}


status = 1
try:
    exec(open(os.path.join(WB, "InitGui.py")).read())
    Gui.activateWorkbench("DispconWorkbench")
    import dispcon_fc.assembly as da
    from dispcon_fc import dragging, viewproviders

    os.makedirs(OUT, exist_ok=True)
    doc = App.newDocument("hundred")
    asm, _, _ = crank_chain(doc, 50)
    assert da.solve(asm).converged, "the chain did not assemble"
    joints, parts = da.joints(asm), da.parts(asm)
    assert len(parts) == 100 and len(joints) == 148, (len(parts), len(joints))
    mdi = Gui.getMainWindow().findChild(QtWidgets.QMdiArea)
    for sub in mdi.subWindowList():
        if sub.windowTitle().startswith(doc.Label):
            mdi.setActiveSubWindow(sub)
            sub.showMaximized()
    Gui.updateGui()
    view = Gui.getDocument(doc.Name).ActiveView
    view.viewTop()
    Gui.SendMsgToActiveView("ViewFit")
    for _ in range(5):
        QtWidgets.QApplication.processEvents()
        Gui.updateGui()
        time.sleep(0.05)
    swapped = [0]
    view.graphicsView().viewport().frameSwapped.connect(lambda: swapped.__setitem__(0, swapped[0] + 1))
    graph = view.getViewer().getSoRenderManager().getSceneGraph()
    markers = [viewproviders.joint_view(j).marker for j in joints]
    assert all(m.is_visible() for m in markers), "a marker is hidden at rest"

    def redraws():
        """REDRAWS redraws with nothing moving: (main thread CPU, process CPU, wall) per redraw."""
        main = cpu = wall = 0.0
        for _ in range(REDRAWS):
            before = swapped[0]
            t0, c0, p0 = time.perf_counter(), time.thread_time(), time.process_time()
            graph.touch()
            while swapped[0] == before:
                if time.perf_counter() - t0 > 5:
                    raise RuntimeError("the view did not redraw")
                Gui.updateGui()
            main += time.thread_time() - c0
            cpu += time.process_time() - p0
            wall += time.perf_counter() - t0
        return main / REDRAWS, cpu / REDRAWS, wall / REDRAWS

    def state(name):
        """Puts the view in state `name`; returns what undoes it."""
        undo = []
        if name.startswith("lighter"):
            lighter = dragging.Lighter(view, _Adapter(asm, [], parts))
            undo.append(lighter.restore)
        if name.endswith("hidden"):
            for m in markers:
                m.set_visible(False)
            undo.append(lambda: [m.set_visible(True) for m in markers])
        elif name.endswith("absent"):
            for j in joints:
                j.ViewObject.Visibility = False
            undo.append(lambda: [setattr(j.ViewObject, "Visibility", True) for j in joints])
        return lambda: [u() for u in reversed(undo)]

    names = ("shown", "hidden", "absent", "lighter shown", "lighter hidden", "lighter absent")
    if os.environ.get("DISPCON_BENCH_STATES"):  # some of them: "shown,lighter hidden"
        names = tuple(n for n in os.environ["DISPCON_BENCH_STATES"].split(",") if n in names)
    got = {n: [] for n in names}
    redraws()  # warm up: the first redraws build the caches and the display lists
    for r in range(ROUNDS):
        for n in names:
            undo = state(n)
            try:
                redraws()  # the state's first redraws (caches made again) not counted
                got[n].append(redraws())
            finally:
                undo()
        print("round %d of %d done, load %.1f" % (r + 1, ROUNDS, os.getloadavg()[0]), flush=True)
    assert all(m.is_visible() for m in markers), "a marker was left hidden"
    view.saveImage(os.path.join(OUT, "hundred-top.png"), 1280, 900, "White")

    def med(xs):
        return 1000 * sorted(xs)[len(xs) // 2]

    for n in names:
        rows = got[n]
        print("REDRAW %-15s main thread %.2f ms (%.2f-%.2f), process %.2f ms, wall %.2f ms; %d rounds of %d"
              % (n, med([r[0] for r in rows]), 1000 * min(r[0] for r in rows), 1000 * max(r[0] for r in rows),
                 med([r[1] for r in rows]), med([r[2] for r in rows]), len(rows), REDRAWS))
    print("REDRAW workbench %s, load %.1f" % (WB, os.getloadavg()[0]))
    status = 0
except Exception:
    traceback.print_exc()
finally:
    with open(os.path.join(OUT, "status"), "w") as f:
        f.write(str(status))
    QtWidgets.QApplication.instance().quit()
