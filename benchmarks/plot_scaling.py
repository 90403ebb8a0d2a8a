"""Draws how cost grows with size from a Google Benchmark JSON file (scripts/bench writes one):
time per solve against the number of parts (log-log), and optionally the iterations each solve
took against the number of parts, as SVG. Standard library only.

    python3 benchmarks/plot_scaling.py build-bench/bench.json scaling.svg [iterations.svg]"""
import json
import math
import sys

SERIES = [  # (name prefix, label, colour, parts per argument)
    ("BM_FourBars_dispcon/", "dispcon: N four-bars", "#1f77b4", 3),
    ("BM_FourBars_slvs/", "SolveSpace: N four-bars, 2D sketch", "#d62728", 3),
    ("BM_FourBars_slvs_rigid/", "SolveSpace: N four-bars, rigid 3D", "#9467bd", 3),
    ("BM_FourBars_dispcon_1core/", "dispcon: N four-bars, one core", "#17becf", 3),
    ("BM_ClosedChain/", "dispcon: closed chain of N links", "#2ca02c", 1),
    ("BM_FourBarGrid/", "dispcon: grid of coupled four-bars", "#ff7f0e", None),
]


def millis(b):
    return b["real_time"] * {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]


ITERATION_SERIES = [  # solves whose iteration count is a counter of the benchmark
    ("BM_FourBars_dispcon_1core/", "N independent four-bars", "#1f77b4", 3),
    ("BM_ClosedChain/", "closed chain of N links", "#2ca02c", 1),
    ("BM_FourBarGrid/", "grid of coupled four-bars", "#ff7f0e", None),
    ("BM_DragStep_ClosedChain/", "drag step, closed chain", "#8c564b", 1),
    ("BM_DragStep_FourBarGrid/", "drag step, grid", "#e377c2", None),
]


def cases(src):
    """A bench.json's cases, one per case by its plain name: with --benchmark_repetitions, the
    median of the repetitions (the mean, spread and each repetition are left out)."""
    runs = json.load(open(src))["benchmarks"]
    if any(b.get("run_type") == "aggregate" for b in runs):
        runs = [dict(b, name=b["run_name"]) for b in runs if b.get("aggregate_name") == "median"
                or (b.get("error_occurred") and b.get("repetition_index", 0) == 0)]
    return runs


def collect(runs, table, value):
    series = []
    for prefix, label, colour, per in table:
        pts = []
        for b in runs:
            if b["name"].startswith(prefix) and not b.get("error_occurred"):
                arg = int(b["name"][len(prefix):].split("/")[0])
                parts = b.get("bodies", arg * per if per else arg)
                pts.append((parts, value(b)))
        if pts:
            series.append((label, colour, sorted(pts)))
    return series


def draw(series, dst, unit, log_y, title=""):
    xs = [p for _, _, s in series for p, _ in s]
    ys = [t for _, _, s in series for _, t in s]
    # A filtered run (scripts/bench --benchmark_filter=...) may leave one size or none: there is
    # no axis to draw then, and the run's figures are still printed.
    if len(set(xs)) < 2:
        print("plot_scaling: fewer than two sizes in this run, %s not drawn" % dst)
        return
    x0, x1 = math.log10(min(xs)), math.log10(max(xs))
    if log_y:
        y0, y1 = math.floor(math.log10(min(ys))), math.ceil(math.log10(max(ys)))
        ticks = [10 ** e for e in range(int(y0), int(y1) + 1)]
        fy = math.log10
    else:
        y0, y1 = 0, max(ys) + 1
        ticks = list(range(0, int(y1) + 1))
        fy = float
    W, H, L, R, T, B = 720, 420, 70, 250, 20, 50
    X = lambda v: L + (math.log10(v) - x0) / (x1 - x0) * (W - L - R)
    Y = lambda v: T + (y1 - fy(v)) / (y1 - y0) * (H - T - B)
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" font-size="12">' % (W, H),
           '<rect width="100%" height="100%" fill="white"/>',
           '<rect x="%d" y="%d" width="%d" height="%d" fill="none" stroke="#888"/>' % (L, T, W - L - R, H - T - B)]
    for v in ticks:
        out.append('<text x="%d" y="%.1f" text-anchor="end">%g%s</text>' % (L - 4, Y(v) + 4, v, unit))
    for e in range(int(math.floor(x0)), int(math.ceil(x1)) + 1):
        if x0 <= e <= x1:
            out.append('<text x="%.1f" y="%d" text-anchor="middle">%d</text>' % (X(10 ** e), H - B + 16, 10 ** e))
    out.append('<text x="%d" y="%d" text-anchor="middle">parts (log scale)</text>' % ((W - R + L) / 2, H - 12))
    if title:
        out.append('<text x="%d" y="%d" fill="#444">%s</text>' % (L + 8, T + 16, title))
    for k, (label, colour, pts) in enumerate(series):
        out.append('<polyline fill="none" stroke="%s" stroke-width="2" points="%s"/>' % (colour, " ".join("%.1f,%.1f" % (X(p), Y(t)) for p, t in pts)))
        for p, t in pts:
            out.append('<circle cx="%.1f" cy="%.1f" r="3" fill="%s"/>' % (X(p), Y(t), colour))
        out.append('<text x="%d" y="%d" fill="%s">%s</text>' % (W - R + 10, T + 16 + 16 * k, colour, label))
    out.append("</svg>")
    open(dst, "w").write("\n".join(out) + "\n")


def main(src, dst, iterations_dst=None):
    runs = cases(src)
    draw(collect(runs, SERIES, millis), dst, " ms", True)
    if iterations_dst:
        # The benchmarks' "iterations" counter follows Google Benchmark's own "iterations" (the
        # repetitions) in the JSON, and the later of two equal keys wins.
        draw(collect(runs, ITERATION_SERIES, lambda b: float(b["iterations"])), iterations_dst, "",
             False, "iterations to reach 1e-9")


if __name__ == "__main__":
    main(*sys.argv[1:4])
