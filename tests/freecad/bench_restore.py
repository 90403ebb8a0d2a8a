"""What the workbench's Python costs when a document is opened, headless (freecadcmd), without
FreeCAD's own restore around it (docs/performance.md, "Issue 14, fifteenth round: opening and the
joint panel"): tests/freecad/chains.py's 100-part crank chain (148 revolutes) saved and opened
once, then its joints' and its assembly's onDocumentRestored run again PASSES times, each pass's
CPU time printed (speed is reported, never asserted). An open of a file saved by the current
workbench runs the same path: every property is there, each is checked and given its tooltip.
DISPCON_BENCH_WB: another tree's workbench (to compare with it).

    DISPCON_PYTHONPATH=build/python freecadcmd tests/freecad/bench_restore.py"""
import os
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
WB = os.environ.get("DISPCON_BENCH_WB", os.path.join(REPO, "freecad_workbench"))
sys.path.insert(0, WB)
sys.path.insert(0, os.path.join(REPO, "samples", "freecad"))
sys.path.insert(0, HERE)

import FreeCAD as App  # noqa: E402

from chains import crank_chain  # noqa: E402
from dispcon_fc import objects  # noqa: E402

PASSES = int(os.environ.get("DISPCON_BENCH_PASSES", "7"))

path = os.path.join(tempfile.mkdtemp(), "restore-100.FCStd")
doc = App.newDocument("restore100")
crank_chain(doc, 50)
doc.recompute()
doc.saveAs(path)
App.closeDocument(doc.Name)
doc = App.openDocument(path)
restored = [o for o in doc.Objects if isinstance(getattr(o, "Proxy", None), (objects.JointProxy, objects.AssemblyProxy))]
assert len(restored) == 3 * 50 - 2 + 1, len(restored)  # the revolutes and the assembly
times = []
for _ in range(PASSES):
    t = time.process_time()
    for o in restored:
        o.Proxy.onDocumentRestored(o)
    times.append(time.process_time() - t)
assert not doc.isTouched(), "the restore's path touched the document"
print("RESTORE %s: %d objects, CPU ms a pass: %s; load %.1f" % (
    WB, len(restored), " ".join("%.1f" % (1000 * t) for t in times), os.getloadavg()[0]))
App.closeDocument(doc.Name)
