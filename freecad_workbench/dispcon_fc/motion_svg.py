"""Pictures of a motion study, headless: the plot of every joint's value against the driving one,
and an animated SVG (SMIL, played by any browser) of the parts' outlines moving, projected from
their shapes onto a view plane, the parts that collide drawn in red at the poses where they do,
beside the plot with a cursor that follows the animation."""
import math

import FreeCAD as App

VIEWS = ("xy", "xz", "yz", "iso")
COLOURS = ["#1f77b4", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22",
           "#17becf", "#ff7f0e", "#393b79", "#637939", "#8c6d31"]
RED = "#d62728"


def project(view):
    """(x, y, z) -> (u, v) on the screen, v downwards."""
    if view == "xy":
        return lambda p: (p.x, -p.y)
    if view == "xz":
        return lambda p: (p.x, -p.z)
    if view == "yz":
        return lambda p: (p.y, -p.z)
    if view == "iso":
        c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
        return lambda p: ((p.x - p.y) * c, (p.x + p.y) * s - p.z)
    raise ValueError("unknown view %r (expected one of %s)" % (view, ", ".join(VIEWS)))


def outlines(shape, segments=16):
    """The edges of a shape (in its own frame) as polylines: straight edges by their ends, curves
    by `segments` points (fewer for short arcs)."""
    box = shape.BoundBox
    size = box.DiagonalLength or 1.0
    lines = []
    for e in shape.Edges:
        if e.Length < 1e-9 * size:
            continue
        if e.Curve.TypeId == "Part::GeomLine":
            pts = [e.Vertexes[0].Point, e.Vertexes[-1].Point]
        else:
            n = max(3, min(segments, int(segments * e.Length / (0.5 * size)) + 3))
            pts = e.discretize(n)
        lines.append(pts)
    return _dedupe(lines)


def _dedupe(lines):
    seen, out = set(), []
    for pts in lines:
        key = tuple(round(c, 9) for p in (pts[0], pts[-1], pts[len(pts) // 2]) for c in (p.x, p.y, p.z))
        if key not in seen:
            seen.add(key)
            out.append(pts)
    return out


def _fmt(x):
    return ("%.1f" % x).rstrip("0").rstrip(".") if abs(x) < 1e6 else "0"


class _Frame:
    """A box on the page that maps world (u, v) into itself, keeping the aspect ratio."""

    def __init__(self, umin, umax, vmin, vmax, x, y, w, h, margin=10):
        du, dv = (umax - umin) or 1.0, (vmax - vmin) or 1.0
        self.k = min((w - 2 * margin) / du, (h - 2 * margin) / dv)
        self.x0 = x + margin + 0.5 * ((w - 2 * margin) - self.k * du) - self.k * umin
        self.y0 = y + margin + 0.5 * ((h - 2 * margin) - self.k * dv) - self.k * vmin

    def __call__(self, u, v):
        return self.x0 + self.k * u, self.y0 + self.k * v


def _paths(series, frame):
    """One path's "d" per frame, from the part's projected polylines in each frame; a polyline
    drawn over another in every frame (a disc's top and bottom circles seen from above) once."""
    lines = [["M" + " L".join("%s %s" % tuple(map(_fmt, frame(*uv))) for uv in pl) for pl in uv_lines]
             for uv_lines in series]
    seen, keep = set(), []
    for k in range(len(lines[0]) if lines else 0):
        key = tuple(frame_lines[k] for frame_lines in lines)
        if key not in seen:
            seen.add(key)
            keep.append(k)
    return [" ".join(frame_lines[k] for k in keep) for frame_lines in lines]


def plot_svg(values, series, xlabel, width=520, height=380, x=0, y=0, bands=(), cursor=None,
             standalone=True):
    """A plot of series [(label, unit, [value or None per sample])] against `values`; `bands` are
    [(first, last)] shaded red (collisions); `cursor` = (dur, key_times, xs) animates a vertical
    line. Returns SVG text (a whole document when standalone, else a <g>)."""
    left, right, top, bottom = 60, 130, 20, 40
    pw, ph = width - left - right, height - top - bottom
    xs = [v for v in values]
    ys = [v for _, _, vals in series for v in vals if v is not None and math.isfinite(v)]
    xmin, xmax = (min(xs), max(xs)) if xs else (0.0, 1.0)
    ymin, ymax = (min(ys), max(ys)) if ys else (0.0, 1.0)
    if xmax - xmin < 1e-12:
        xmax = xmin + 1
    if ymax - ymin < 1e-12:
        ymin, ymax = ymin - 1, ymax + 1
    pad = 0.05 * (ymax - ymin)
    ymin, ymax = ymin - pad, ymax + pad
    X = lambda v: x + left + pw * (v - xmin) / (xmax - xmin)  # noqa: E731
    Y = lambda v: y + top + ph * (1 - (v - ymin) / (ymax - ymin))  # noqa: E731
    out = ['<g font-family="sans-serif" font-size="11">',
           '<rect x="%s" y="%s" width="%d" height="%d" fill="white" stroke="#444"/>'
           % (_fmt(x + left), _fmt(y + top), pw, ph)]
    for a, b in bands:
        out.append('<rect x="%s" y="%s" width="%s" height="%d" fill="%s" fill-opacity="0.15"/>'
                   % (_fmt(X(a)), _fmt(y + top), _fmt(max(1.0, X(b) - X(a))), ph, RED))
    for k in range(5):
        tx, ty = xmin + (xmax - xmin) * k / 4, ymin + (ymax - ymin) * k / 4
        out.append('<text x="%s" y="%s" text-anchor="middle">%.3g</text>' % (_fmt(X(tx)), _fmt(y + top + ph + 14), tx))
        out.append('<text x="%s" y="%s" text-anchor="end">%.3g</text>' % (_fmt(x + left - 4), _fmt(Y(ty) + 4), ty))
    out.append('<text x="%s" y="%s" text-anchor="middle">%s</text>' % (_fmt(x + left + pw / 2), _fmt(y + height - 6), _esc(xlabel)))
    for n, (label, unit, vals) in enumerate(series):
        colour = COLOURS[n % len(COLOURS)]
        pts = ["%s,%s" % (_fmt(X(a)), _fmt(Y(b))) for a, b in zip(xs, vals) if b is not None and math.isfinite(b)]
        if pts:
            out.append('<polyline fill="none" stroke="%s" stroke-width="1.5" points="%s"/>' % (colour, " ".join(pts)))
        out.append('<text x="%s" y="%s" fill="%s">%s%s</text>' % (_fmt(x + left + pw + 6), _fmt(y + top + 12 + 14 * n), colour,
                                                               _esc(label), " (%s)" % unit if unit else ""))
    if cursor:
        dur, key_times, cx = cursor
        xs_ = ";".join(_fmt(X(v)) for v in cx)
        out.append('<line y1="%s" y2="%s" stroke="black" stroke-width="1">'
                   '<animate attributeName="x1" dur="%ss" repeatCount="indefinite" keyTimes="%s" values="%s"/>'
                   '<animate attributeName="x2" dur="%ss" repeatCount="indefinite" keyTimes="%s" values="%s"/></line>'
                   % (_fmt(y + top), _fmt(y + top + ph), dur, key_times, xs_, dur, key_times, xs_))
    out.append("</g>")
    body = "\n".join(out)
    if not standalone:
        return body
    return ('<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" viewBox="0 0 %d %d">\n%s\n</svg>\n'
            % (width, height, width, height, body))


def _esc(t):
    return str(t).replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def animation_svg(shapes, labels, frames, view="iso", title="", plot=None, seconds=None,
                  max_frames=180, size=520):
    """An animated SVG of parts moving. `shapes`: each part's shape in its own frame; `frames`:
    [(placements, set of colliding part indices)]; `plot`: (values, series, xlabel, colliding) drawn
    on the right, values and colliding one per frame, with a cursor at each frame's value and the
    runs of collisions shaded. At most `max_frames`
    frames are kept (evenly, the first and last always, and every frame where a collision starts
    or ends); `seconds` is the loop's length (default 1/30 s a frame, at least 3 s)."""
    proj = project(view)
    keep = _pick(frames, max_frames)
    frames = [frames[i] for i in keep]
    local = [outlines(s) for s in shapes]
    # Every frame's projected polylines, per part.
    per_part = []
    umin = vmin = float("inf")
    umax = vmax = float("-inf")
    for n, lines in enumerate(local):
        series = []
        for pls, _ in frames:
            pl = pls[n]
            uv = [[proj(pl.multVec(p)) for p in line] for line in lines]
            for line in uv:
                for u, v in line:
                    umin, umax, vmin, vmax = min(umin, u), max(umax, u), min(vmin, v), max(vmax, v)
            series.append(uv)
        per_part.append(series)
    width = size + (size if plot else 0)
    frame = _Frame(umin, umax, vmin, vmax, 0, 24, size, size - 40 - 14 * (len(labels) // 5))
    count = len(frames)
    dur = seconds or max(3.0, count / 30.0)
    key_times = ";".join("%.5g" % (k / (count - 1)) for k in range(count)) if count > 1 else "0"
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" viewBox="0 0 %d %d">'
           % (width, size, width, size),
           '<rect width="100%" height="100%" fill="white"/>',
           '<text x="8" y="16" font-family="sans-serif" font-size="13">%s (view %s)</text>' % (_esc(title), view)]
    for n, series in enumerate(per_part):
        colour = COLOURS[n % len(COLOURS)]
        ds = _paths(series, frame)
        hit = [n in coll for _, coll in frames]
        attrs = 'fill="none" stroke="%s" stroke-width="%s" stroke-linejoin="round"' % (
            RED if hit[0] else colour, 2.5 if hit[0] else 1.2)
        out.append('<path id="part%d" data-label="%s" d="%s" %s>' % (n, _esc(labels[n]), ds[0], attrs))
        if count > 1 and any(d != ds[0] for d in ds):
            out.append('<animate attributeName="d" dur="%ss" repeatCount="indefinite" keyTimes="%s" values="%s"/>'
                       % (_fmt3(dur), key_times, ";".join(ds)))
        if count > 1 and any(hit):
            # A static part too (an obstacle) turns red while something runs into it.
            out.append('<animate attributeName="stroke" dur="%ss" repeatCount="indefinite" calcMode="discrete" '
                       'keyTimes="%s" values="%s"/>' % (_fmt3(dur), key_times,
                                                       ";".join(RED if h else colour for h in hit)))
            out.append('<animate attributeName="stroke-width" dur="%ss" repeatCount="indefinite" calcMode="discrete" '
                       'keyTimes="%s" values="%s"/>' % (_fmt3(dur), key_times,
                                                       ";".join("2.5" if h else "1.2" for h in hit)))
        out.append("</path>")
    for n, label in enumerate(labels):
        out.append('<text x="%d" y="%d" font-family="sans-serif" font-size="11" fill="%s">%s</text>'
                   % (8 + 90 * (n % 5), size - 8 - 14 * (len(labels) // 5 - n // 5), COLOURS[n % len(COLOURS)],
                      _esc(label)))
    if plot:
        values, series, xlabel, colliding = plot
        cursor_x = [values[i] for i in keep]
        bands = _bands(values, [bool(c) for c in colliding])
        out.append(plot_svg(values, series, xlabel, width=size, height=int(size * 0.75), x=size, y=40,
                            bands=bands, cursor=(_fmt3(dur), key_times, cursor_x), standalone=False))
    out.append("</svg>")
    return "\n".join(out) + "\n"


def _fmt3(x):
    return "%.3f" % x


def _pick(frames, max_frames):
    n = len(frames)
    if n <= max_frames:
        return list(range(n))
    keep = {0, n - 1}
    for k in range(1, n):
        if bool(frames[k][1]) != bool(frames[k - 1][1]) or frames[k][1] != frames[k - 1][1]:
            keep.update((k - 1, k))
    step = max(1, math.ceil(n / max(2, max_frames - len(keep))))
    keep.update(range(0, n, step))
    return sorted(keep)


def _bands(values, flags):
    """[(first, last)] runs of values where flags hold."""
    out, start = [], None
    for v, f in zip(values, flags):
        if f and start is None:
            start = v
        if f:
            end = v
        if not f and start is not None:
            out.append((start, end))
            start = None
    if start is not None:
        out.append((start, end))
    return out


def sweep_plot(study):
    """(values, series, xlabel, colliding flags) of a SweepStudy for plot_svg/animation_svg."""
    values = [s.value for s in study.samples]
    units = {"angle": "rad", "travel": "length"}
    from .studies import joint_kind

    series = [(j.Label, units.get(joint_kind(j)), [s.joint_values[n] for s in study.samples])
              for n, j in enumerate(study.study.joints) if joint_kind(j)]
    xlabel = "%s (%s)" % (study.joint.Label, units[study.kind])
    return values, series, xlabel, [s.colliding for s in study.samples]


def sweep_svg(study, view="iso"):
    """The animated SVG of a SweepStudy: the parts at every sample, the plot beside."""
    shapes = study.study.local_shapes()
    labels = [p.Label for p in study.study.parts]
    frames = [(s.placements, {i for a, b, _ in s.colliding for i in (a, b)}) for s in study.samples]
    return animation_svg(shapes, labels, frames, view=view,
                         title="%s: sweep of '%s'" % (study.study.asm.Label, study.joint.Label),
                         plot=sweep_plot(study))


def sweep_plot_svg(study):
    values, series, xlabel, colliding = sweep_plot(study)
    return plot_svg(values, series, xlabel, bands=_bands(values, [bool(c) for c in colliding]))


def drag_svg(drag_study, colliding, view="iso"):
    """The animated SVG of a DragStudy: the parts at every step (colliding: per step the
    [(i, k, volume)] overlaps), the plot of every joint's value against the step."""
    from .studies import joint_kind, joint_value

    st = drag_study.study
    shapes = st.local_shapes()
    labels = [p.Label for p in st.parts]
    frames = [(pls, {i for a, b, _ in c for i in (a, b)}) for pls, c in zip(drag_study.placements, colliding)]
    units = {"angle": "rad", "travel": "length"}
    series = []
    for j in st.joints:
        if joint_kind(j):
            i1, i2 = st.parts.index(j.Reference1[0]), st.parts.index(j.Reference2[0])
            series.append((j.Label, units[joint_kind(j)],
                           [joint_value(j, pls[i1], pls[i2]) for pls in drag_study.placements]))
    values = list(range(len(drag_study.placements)))
    return animation_svg(shapes, labels, frames, view=view,
                         title="%s: drag of '%s'" % (st.asm.Label, drag_study.part.Label),
                         plot=(values, series, "step", colliding))
