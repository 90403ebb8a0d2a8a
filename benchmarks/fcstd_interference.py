"""Interference along a sweep, timed against its peer: the same sweep (poses computed once), its
collisions found by dispcon_fc.studies.Clearance (boxes in both parts' frames first, unchanged
pairs cached, booleans only where boxes truly overlap) and by the way the workbench's
interference_along worked before it used Clearance (world boxes, then OpenCascade's common() for every pair whose boxes
meet). Both must find the same collisions. Run with freecadcmd; the samples come from
samples/freecad/build_samples.py, the request from the environment (freecadcmd opens its
arguments as documents):

    DISPCON_BENCH_DOC=build/samples/side-rods.FCStd DISPCON_BENCH_JOINT=Revolute \\
    DISPCON_BENCH_RANGE=0,2.9 freecadcmd benchmarks/fcstd_interference.py
"""
import os
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(
    next((a for a in sys.argv if a.endswith("fcstd_interference.py")), sys.argv[-1]))))
sys.path.insert(0, os.path.join(REPO, "freecad_workbench"))

from dispcon_fc import studies  # noqa: E402


def peer(shapes, placements):
    """World boxes, then common() whenever they meet: [(i, k, volume)]."""
    placed = []
    for s, pl in zip(shapes, placements):
        c = s.copy()
        c.Placement = pl.multiply(c.Placement)
        placed.append(c)
    hits, calls = [], 0
    for i in range(len(placed)):
        for k in range(i + 1, len(placed)):
            if not placed[i].BoundBox.intersect(placed[k].BoundBox):
                continue
            calls += 1
            v = placed[i].common(placed[k]).Volume
            if v > 1e-6 * min(placed[i].Volume, placed[k].Volume):
                hits.append((i, k, v))
    return hits, calls


def main():
    path = os.environ["DISPCON_BENCH_DOC"]
    joint = os.environ.get("DISPCON_BENCH_JOINT", "Revolute")
    steps = int(os.environ.get("DISPCON_BENCH_STEPS", "360"))
    rng = os.environ.get("DISPCON_BENCH_RANGE")
    start, stop = (float(x) for x in rng.split(",")) if rng else (None, None)
    doc, asm = studies.open_assembly(path)
    t0 = time.perf_counter()
    study = studies.sweep(asm, joint, start, stop, steps, interference=False)
    t_sweep = time.perf_counter() - t0
    shapes = study.study.local_shapes()
    clearance = studies.clearance_of(study.study)
    t0 = time.perf_counter()
    ours = [clearance.at(s.placements) for s in study.samples]
    t_ours = time.perf_counter() - t0
    t0 = time.perf_counter()
    theirs, calls = [], 0
    for s in study.samples:
        h, c = peer(shapes, s.placements)
        theirs.append(h)
        calls += c
    t_peer = time.perf_counter() - t0
    same = [[(i, k) for i, k, _ in a] for a in ours] == [[(i, k) for i, k, _ in b] for b in theirs]
    print("%s: %d parts, %d samples (%s); sweep %.2f s; interference: Clearance %.2f s (%d booleans), "
          "peer %.2f s (%d booleans), ratio %.1f; same collisions: %s"
          % (os.path.basename(path), len(shapes), len(study.samples), study.message.split(";")[0],
             t_sweep, t_ours, clearance.common_calls, t_peer, calls, t_peer / max(t_ours, 1e-9), same))
    sys.stdout.flush()
    os._exit(0 if same else 1)


main()
