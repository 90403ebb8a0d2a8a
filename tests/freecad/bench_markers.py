"""What one layout of the joint markers costs with hundreds of joints (docs/performance.md, "Issue
14, tenth round: the markers' layout"): real FreeCAD under Xvfb at 1280x900, not a test (speed is
measured, never asserted). Two generated assemblies of real solids (samples/freecad/parts.py):

- `chain`: tests/freecad/chains.py's chain of parallelograms (gui_drag.py's), 134 cranks: 267 parts, 400 revolutes along a
  line (at fit-all zoom a crowd with no room beside its joints);
- `grid`: 30 chains of 5 cranks in 6 rows of 5: 270 parts, 390 revolutes over the screen (crowds
  with room, made readable).

Each is seen whole (fit-all, isometric) and zoomed in four times on its middle, and the assembly's
`ViewProviderAssembly.restack()` (the layout a camera rest runs) timed `RUNS` times, the median
printed with the share of `markers.stacks` and `markers.spread` (DISPCON_BENCH_PROFILE=1: and a
profile of one layout; DISPCON_BENCH_WB: another tree's workbench, to compare). Quits FreeCAD itself.

    XDG_DATA_HOME=$(mktemp -d) DISPCON_PYTHONPATH=build/python \\
        xvfb-run -a -s '-screen 0 1280x900x24' freecad tests/freecad/bench_markers.py"""
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
from chains import chains  # noqa: E402  (the crank chains gui_drag.py drags)

RUNS = int(os.environ.get("DISPCON_BENCH_RUNS", "9"))
OUT = os.environ.get("DISPCON_GUI_OUT", "/tmp/dispcon-bench-markers")


def settle():
    for _ in range(3):
        QtWidgets.QApplication.processEvents()
        Gui.updateGui()


def timed(asm):
    """The median of RUNS layouts (ms) and the medians of stacks' and spread's shares."""
    from dispcon_fc import markers

    proxy = asm.ViewObject.Proxy
    spent = {"stacks": [], "spread": []}
    originals = {name: getattr(markers, name) for name in spent}

    def timing(name):
        def run(*args, **kw):
            t = time.perf_counter()
            try:
                return originals[name](*args, **kw)
            finally:
                spent[name].append(time.perf_counter() - t)
        return run

    totals = []
    try:
        for name in spent:
            setattr(markers, name, timing(name))
        for _ in range(RUNS):
            t = time.perf_counter()
            proxy.restack()
            totals.append(time.perf_counter() - t)
    finally:
        for name, f in originals.items():
            setattr(markers, name, f)

    def median(xs):
        return 1000 * sorted(xs)[len(xs) // 2] if xs else 0.0
    shifts = [getattr(getattr(j.ViewObject, "Proxy", None), "shift", None) for j in asm.Group]
    moved = sum(1 for v in shifts if v is not None)
    # The layout, offset by offset (to 1e-9 glyph units): two workbenches' runs compared by it.
    import hashlib

    text = repr([None if v is None else tuple(round(x, 9) + 0.0 for x in v) for v in shifts])
    layout = int(hashlib.sha1(text.encode()).hexdigest()[:8], 16)
    return median(totals), median(spent["stacks"]), median(spent["spread"]), moved, layout


def timed_cold(asm):
    """The median of RUNS layouts each after a part moved (the frames read from FreeCAD again),
    in ms: what a layout costs when it cannot reuse the frames a camera rest reuses."""
    proxy = asm.ViewObject.Proxy
    totals = []
    for _ in range(RUNS):
        proxy.frames_dirty = True
        t = time.perf_counter()
        proxy.restack()
        totals.append(time.perf_counter() - t)
    return 1000 * sorted(totals)[len(totals) // 2]


status = 1
try:
    exec(open(os.path.join(WB, "InitGui.py")).read())
    Gui.activateWorkbench("DispconWorkbench")
    import dispcon_fc.assembly as da

    os.makedirs(OUT, exist_ok=True)
    for label, rows, cols, cranks in (("chain", 1, 1, 134), ("grid", 6, 5, 5)):
        doc = App.newDocument(label)
        t = time.perf_counter()
        asm = chains(doc, rows, cols, cranks, label.capitalize())
        r = da.solve(asm)
        build = time.perf_counter() - t
        Gui.getDocument(doc.Name).ActiveView.viewIsometric()
        Gui.SendMsgToActiveView("ViewFit")
        settle()
        view = Gui.getDocument(doc.Name).ActiveView
        joints = len(da.joints(asm))
        for zoom in ("fit-all", "zoomed in 4x"):
            if zoom != "fit-all":
                cam = view.getCameraNode()
                cam.height.setValue(cam.height.getValue() / 4.0) if hasattr(cam, "height") else None
                settle()
            total, stacks, spread, moved, layout = timed(asm)
            print("LAYOUT %s (%d parts, %d joints, %s): restack %.1f ms (stacks %.1f, spread %.1f); "
                  "after a part moved %.1f ms; %d markers set off their joints (layout %x); load %.1f; "
                  "built and solved in %.1f s (%s)"
                  % (label, len(da.parts(asm)), joints, zoom, total, stacks, spread, timed_cold(asm), moved,
                     layout & 0xffffffff, os.getloadavg()[0], build, r.message))
            if os.environ.get("DISPCON_BENCH_PROFILE"):
                import cProfile
                import pstats

                profile = cProfile.Profile()
                profile.runcall(asm.ViewObject.Proxy.restack)
                pstats.Stats(profile, stream=sys.stdout).sort_stats("tottime").print_stats(14)
            view.saveImage(os.path.join(OUT, "%s-%s.png" % (label, zoom.split()[0])), 1280, 900, "White")
        App.closeDocument(doc.Name)
    status = 0
except Exception:
    traceback.print_exc()
finally:
    with open(os.path.join(OUT, "status"), "w") as f:
        f.write(str(status))
    QtWidgets.QApplication.instance().quit()
