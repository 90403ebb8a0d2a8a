"""Joint markers: a small Coin3D glyph at each joint's point, its z along the joint's axis, one
shape per joint type (a ring for a revolute, a double arrow for a slider, a sphere for a ball, a
square for a plane ...), in the colours of the workbench's icons: orange for a turn, green for
travel, blue for part 1's guide, yellow for part 2's point.

A marker has three looks: normal, selected (the joint is selected in the tree or the 3D view) and
error (the joint a failed Solve or Check points at). The look is state of the view only: nothing
here is a document property, so nothing of it is saved into the file.

The glyphs are drawn over the parts (an SoAnnotation), so a joint inside a part stays visible, and
at one size on the screen whatever the zoom. Markers drawn at one place (the coaxial revolutes of a
planetary set's centre, two joints on one pin) are set apart side by side across their axis
(stacks()), and markers that crowd each other on the screen (a planet's axle, its mesh with the
sun and its mesh with the ring, a few pixels apart at fit-all zoom) are pushed apart there
(spread()), so each stays readable at any zoom.

A marker is never picked (an SoPickStyle UNPICKABLE, as FreeCAD 1.x's joint coordinate systems
are): it is drawn over the pin it marks, so a click there meant for the pin's edge or face (the
next joint's reference, a part pressed on in drag mode) went to the marker and was lost. Joints
are selected in the tree, where their markers turn green."""
import math

import FreeCAD as App
import numpy as np

# Which pieces each joint type's glyph has: ring (turn about the axis), arrows (travel along
# it), sphere (turn about the point), square (the plane across the axis), cube (no motion),
# line (the axis), dot (part 2's point), curve, angle (a second axis at an angle), dimension (a
# distance), parallel and perpendicular (a second axis so), gear (a toothed ring about the axis),
# belt (a pulley and its belt), rack (a toothed bar across the axis), helix (a screw's thread).
PIECES = {
    "Fixed": ("cube",),
    "Revolute": ("line", "ring"),
    "Slider": ("arrows", "cube"),
    "Cylindrical": ("arrows", "ring"),
    "Ball": ("sphere",),
    "Planar": ("square", "line"),
    "PointOnLine": ("arrows", "dot"),
    "PointOnPlane": ("square", "dot"),
    "PointOnCurve": ("curve", "dot"),
    "Distance": ("dimension", "dot"),
    "Parallel": ("line", "parallel"),
    "Perpendicular": ("line", "perpendicular"),
    "Angle": ("line", "angle"),
    # Couplings: the glyph sits on part 1's axis (the driving gear, the pinion, the screw).
    "Gears": ("line", "gear"),
    "Belt": ("line", "belt"),
    "RackPinion": ("gear", "rack"),
    "Screw": ("line", "helix"),
}

ORANGE = (0.96, 0.47, 0.0)
GREEN = (0.30, 0.60, 0.02)
BLUE = (0.20, 0.40, 0.64)
YELLOW = (0.93, 0.83, 0.0)
GREY = (0.33, 0.34, 0.33)
SELECTED = (0.11, 0.85, 0.11)   # FreeCAD's default selection green
ERROR = (1.0, 0.0, 0.0)         # and drawn half as large again

LOOKS = ("normal", "selected", "error")


def _coin():
    from pivy import coin

    return coin


def overlay(name, line_width):
    """An unpickable group drawn in the selection's green over everything of the view (a
    highlight of edges): (its root, named `name`, and the group to add what it draws to)."""
    coin = _coin()
    root = coin.SoSeparator()
    root.setName(name)
    style = coin.SoPickStyle()
    style.style = coin.SoPickStyle.UNPICKABLE  # never in the way of a click on a part
    root.addChild(style)
    root.addChild(_material(SELECTED))
    lines = coin.SoDrawStyle()
    lines.lineWidth = line_width
    lines.pointSize = 2 * line_width
    root.addChild(lines)
    on_top = coin.SoAnnotation()
    root.addChild(on_top)
    return root, on_top


def add_edges(group, shapes):
    """Draws the edges of each shape (a part's, an edge, a face's boundary) in `group` as lines,
    each discretized to 1/200 of its shape's size; an edge that cannot be is left out."""
    coin = _coin()
    points, counts = [], []
    for shape in shapes:
        deflection = max(shape.BoundBox.DiagonalLength / 200.0, 1e-6)
        for edge in shape.Edges:
            try:
                pts = edge.discretize(Deflection=deflection)
            except Exception:
                continue
            if len(pts) >= 2:
                points += [(v.x, v.y, v.z) for v in pts]
                counts.append(len(pts))
    if counts:
        coords = coin.SoCoordinate3()
        coords.point.setValues(0, len(points), points)
        group.addChild(coords)
        line = coin.SoLineSet()
        line.numVertices.setValues(0, len(counts), counts)
        group.addChild(line)


def _material(colour, transparency=0.0):
    coin = _coin()
    m = coin.SoMaterial()
    m.diffuseColor.setValue(*colour)
    m.emissiveColor.setValue(*[0.35 * c for c in colour])
    m.transparency.setValue(transparency)
    return m


def _polyline(points, width=3.0):
    coin = _coin()
    sep = coin.SoSeparator()
    style = coin.SoDrawStyle()
    style.lineWidth.setValue(width)
    sep.addChild(style)
    coords = coin.SoCoordinate3()
    coords.point.setValues(0, len(points), [list(p) for p in points])
    sep.addChild(coords)
    line = coin.SoLineSet()
    line.numVertices.setValue(len(points))
    sep.addChild(line)
    return sep


def _at(child, translation=(0, 0, 0), rotation=None):
    """`child` moved by `translation` and turned by rotation=(axis, radians)."""
    coin = _coin()
    sep = coin.SoSeparator()
    t = coin.SoTransform()
    t.translation.setValue(*translation)
    if rotation is not None:
        t.rotation.setValue(coin.SbVec3f(*rotation[0]), rotation[1])
    sep.addChild(t)
    sep.addChild(child)
    return sep


def _cone_along_z(height, radius):
    """A cone whose tip points along +z (SoCone points along +y)."""
    coin = _coin()
    cone = coin.SoCone()
    cone.height.setValue(height)
    cone.bottomRadius.setValue(radius)
    return _at(cone, rotation=((1, 0, 0), math.pi / 2))


def _piece(kind, s):
    """One piece of a glyph of size `s` (model units), z along the joint axis."""
    coin = _coin()
    sep = coin.SoSeparator()
    sep.setName("dispcon_" + kind)
    if kind == "line":
        sep.addChild(_material(ORANGE))
        sep.addChild(_polyline([(0, 0, -1.6 * s), (0, 0, 1.6 * s)], 2.0))
    elif kind == "ring":
        sep.addChild(_material(ORANGE))
        pts = [(s * math.cos(a), s * math.sin(a), 0) for a in
               (math.radians(d) for d in range(0, 300, 10))]
        sep.addChild(_polyline(pts, 4.0))
        # The arrow head at the ring's end says which way is positive (right hand about z).
        end = math.radians(300)
        head = _cone_along_z(0.45 * s, 0.18 * s)
        sep.addChild(_at(head, (s * math.cos(end), s * math.sin(end), 0),
                         _turn_z_to((-math.sin(end), math.cos(end), 0))))
    elif kind == "arrows":
        sep.addChild(_material(GREEN))
        sep.addChild(_polyline([(0, 0, -1.4 * s), (0, 0, 1.4 * s)], 4.0))
        sep.addChild(_at(_cone_along_z(0.45 * s, 0.18 * s), (0, 0, 1.4 * s)))
        sep.addChild(_at(_cone_along_z(0.45 * s, 0.18 * s), (0, 0, -1.4 * s), ((1, 0, 0), math.pi)))
    elif kind == "sphere":
        sep.addChild(_material(YELLOW))
        ball = coin.SoSphere()
        ball.radius.setValue(0.55 * s)
        sep.addChild(ball)
    elif kind == "dot":
        sep.addChild(_material(YELLOW))
        ball = coin.SoSphere()
        ball.radius.setValue(0.3 * s)
        sep.addChild(ball)
    elif kind == "cube":
        sep.addChild(_material(GREY))
        cube = coin.SoCube()
        cube.width.setValue(0.7 * s)
        cube.height.setValue(0.7 * s)
        cube.depth.setValue(0.7 * s)
        sep.addChild(cube)
    elif kind == "square":
        sep.addChild(_material(BLUE, 0.4))
        h = 1.2 * s
        coords = coin.SoCoordinate3()
        coords.point.setValues(0, 4, [[-h, -h, 0], [h, -h, 0], [h, h, 0], [-h, h, 0]])
        sep.addChild(coords)
        face = coin.SoFaceSet()
        face.numVertices.setValue(4)
        sep.addChild(face)
        sep.addChild(_polyline([(-h, -h, 0), (h, -h, 0), (h, h, 0), (-h, h, 0), (-h, -h, 0)], 2.0))
    elif kind == "curve":
        sep.addChild(_material(BLUE))
        pts = [(x * s * 0.4, 0, 0.6 * s * math.sin(x * 1.2)) for x in range(-4, 5)]
        sep.addChild(_polyline(pts, 4.0))
    elif kind == "angle":
        sep.addChild(_material(ORANGE))
        tilt = math.radians(40)
        sep.addChild(_polyline([(0, 0, 0), (1.6 * s * math.sin(tilt), 0, 1.6 * s * math.cos(tilt))], 2.0))
        pts = [(s * math.sin(a), 0, s * math.cos(a)) for a in (tilt * k / 8 for k in range(9))]
        sep.addChild(_polyline(pts, 4.0))
    elif kind == "dimension":
        sep.addChild(_material(GREEN))
        sep.addChild(_polyline([(0, 0, 0), (0, 0, 1.4 * s)], 3.0))
        sep.addChild(_polyline([(-0.5 * s, 0, 1.4 * s), (0.5 * s, 0, 1.4 * s)], 3.0))
        sep.addChild(_at(_cone_along_z(0.4 * s, 0.16 * s), (0, 0, 1.2 * s)))
        sep.addChild(_polyline([(-0.8 * s, 0, 0), (0.8 * s, 0, 0)], 3.0))
    elif kind == "parallel":
        sep.addChild(_material(ORANGE))
        sep.addChild(_polyline([(0.6 * s, 0, -1.2 * s), (0.6 * s, 0, 1.2 * s)], 4.0))
    elif kind == "perpendicular":
        sep.addChild(_material(ORANGE))
        sep.addChild(_polyline([(0, 0, 0), (1.6 * s, 0, 0)], 4.0))
        sep.addChild(_polyline([(0, 0, 0.45 * s), (0.45 * s, 0, 0.45 * s), (0.45 * s, 0, 0)], 2.0))
    elif kind == "gear":
        sep.addChild(_material(ORANGE))
        teeth, pts = 12, []
        for k in range(teeth):
            a, w = 2 * math.pi * k / teeth, math.pi / teeth
            for da, r in ((-0.5 * w, 0.85), (-0.25 * w, 1.15), (0.25 * w, 1.15), (0.5 * w, 0.85)):
                pts.append((r * s * math.cos(a + da), r * s * math.sin(a + da), 0))
        sep.addChild(_polyline(pts + pts[:1], 3.0))
    elif kind == "belt":
        # Two pulleys and the belt round them, within a ring's size (a glyph reaching further
        # would cross the markers beside it: a planet's mesh and axle).
        sep.addChild(_material(ORANGE))
        pts = [(-0.5 * s + 0.55 * s * math.cos(a), 0.55 * s * math.sin(a), 0)
               for a in (math.radians(d) for d in range(90, 271, 15))]
        pts += [(0.75 * s + 0.35 * s * math.cos(a), 0.35 * s * math.sin(a), 0)
                for a in (math.radians(d) for d in range(-90, 91, 15))]
        sep.addChild(_polyline(pts + pts[:1], 3.0))
    elif kind == "rack":
        sep.addChild(_material(GREEN))
        pts, y = [], -1.15 * s
        for k in range(-4, 4):
            x = k * 0.5 * s
            pts += [(x, y, 0), (x + 0.1 * s, y + 0.25 * s, 0), (x + 0.25 * s, y + 0.25 * s, 0), (x + 0.35 * s, y, 0)]
        sep.addChild(_polyline(pts, 3.0))
        sep.addChild(_at(_cone_along_z(0.4 * s, 0.16 * s), (2.1 * s, y - 0.3 * s, 0), ((0, 1, 0), math.pi / 2)))
    elif kind == "helix":
        sep.addChild(_material(ORANGE))
        pts = [(0.7 * s * math.cos(t), 0.7 * s * math.sin(t), -1.4 * s + 2.8 * s * t / (8 * math.pi))
               for t in (k * math.pi / 12 for k in range(97))]
        sep.addChild(_polyline(pts, 3.0))
    else:
        raise ValueError("unknown marker piece %r" % kind)
    return sep


def _turn_z_to(direction):
    """(axis, angle) that turns +z onto `direction`."""
    d = App.Vector(*direction)
    if d.Length < 1e-12:
        return ((0, 0, 1), 0.0)
    d.normalize()
    z = App.Vector(0, 0, 1)
    axis = z.cross(d)
    angle = math.acos(max(-1.0, min(1.0, z.dot(d))))
    if axis.Length < 1e-9:
        return ((1, 0, 0), angle)
    axis.normalize()
    return ((axis.x, axis.y, axis.z), angle)


def glyph(joint_type, size):
    """The glyph of `joint_type`, `size` units across (its ring's radius), z along the joint axis."""
    coin = _coin()
    sep = coin.SoSeparator()
    sep.setName("dispcon_glyph_" + joint_type)
    for kind in PIECES[joint_type]:
        sep.addChild(_piece(kind, size))
    return sep


# The unit glyph of each joint type, made once and drawn by every marker of that type (a Coin
# node may have many parents; nothing changes a glyph once made: a marker's look overrides its
# colours from above it). Making them anew was most of what a hundred markers cost to open.
_GLYPHS = {}


def shared_glyph(joint_type):
    """The unit glyph of `joint_type` (glyph(joint_type, 1.0)), shared by the markers."""
    node = _GLYPHS.get(joint_type)
    if node is None:
        node = _GLYPHS[joint_type] = glyph(joint_type, 1.0)
    return node


# The nodes every marker draws alike, made once like the glyphs: its pick style, its two looks'
# overrides and the error look's growth (a marker's own switches choose among them). Made for each
# marker, they were a third of what a hundred markers cost to open (docs/performance.md).
_SHARED = {}


def _shared_node(name, make):
    node = _SHARED.get(name)
    if node is None:
        node = _SHARED[name] = make(name)
    return node


def _unpickable(_):
    style = _coin().SoPickStyle()
    style.style.setValue(_coin().SoPickStyle.UNPICKABLE)
    return style


def _look_override(look):
    """The selected or error look: its colour and a wide line over the pieces' own."""
    coin = _coin()
    g = coin.SoGroup()
    m = _material(SELECTED if look == "selected" else ERROR)
    m.setOverride(True)
    g.addChild(m)
    style = coin.SoDrawStyle()
    style.lineWidth.setValue(6.0)
    style.setOverride(True)
    g.addChild(style)
    return g


def _half_again(_):
    grow = _coin().SoScale()
    grow.scaleFactor.setValue(1.5, 1.5, 1.5)
    return grow


# A glyph's size on the screen, in pixels (its ring's radius): markers keep it whatever the zoom,
# as FreeCAD's own draggers and axis crosses do, so they neither swamp a small part nor vanish
# beside a large one.
PIXELS = 14.0
# The k-th marker of a stack at one place sits this many glyph units (PIXELS pixels each) from
# the first, across the axis: a ring (radius 1) or a gear (1.15) beside the next with a gap.
STACK_SPACING = 2.8
# Markers near each other on the screen are set this many glyph units apart, centre to centre: a
# gear (1.15) and a ring (1) with their lines' widths and a gap a person sees.
SCREEN_GAP = 3.3


def stacks(frames, tolerance):
    """The markers drawn at one place: `frames` is [(key, point, axis)] in the assembly's order;
    returns {key: (k, direction)} for each marker that is the k-th (k >= 1) of a stack whose first
    marker is at the same point (within `tolerance`), with the world direction across the first
    one's axis along which the stack is set apart. The first of each stack stays where it is.
    The firsts are found through a grid of tolerance-sized cells (a point looks in its cell and
    the 26 around it), not by a walk over every stack (quadratic with hundreds of joints)."""
    firsts, out, cells = [], {}, {}
    size = tolerance if tolerance > 0 else 1.0

    def cell(p):
        return (math.floor(p.x / size), math.floor(p.y / size), math.floor(p.z / size))

    for key, point, axis in frames:
        cx, cy, cz = cell(point)
        near = [f for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)
                for f in cells.get((cx + dx, cy + dy, cz + dz), ())]
        # The earliest stack within reach, as a walk over them in order would find.
        hit = min((f for f in near if (point - firsts[f][0]).Length <= tolerance), default=None)
        if hit is not None:
            first = firsts[hit]
            first[2] += 1
            out[key] = (first[2], first[1])
            continue
        a = App.Vector(axis).normalize() if axis.Length > 1e-12 else App.Vector(0, 0, 1)
        across = a.cross(App.Vector(0, 0, 1))
        if across.Length < 1e-6:  # an axis along z: the stack goes along -x
            across = a.cross(App.Vector(0, 1, 0))
        cells.setdefault((cx, cy, cz), []).append(len(firsts))
        firsts.append([point, across.normalize(), 0])
    return out


def _pairs_within(pos, radius):
    """The pairs (i, k), i < k, of rows of `pos` (an n x 2 array of pixels) nearer than `radius`
    (a number, or an n x n-free rule: an array of each point's reach, a pair kept when nearer than
    the sum of their reaches and `radius`'s largest twice over is the sweep's): two index arrays.
    Sweep and prune along the longer side of their box, in numpy: each point is paired with those
    after it along it within reach, and those pairs measured at once (a few hundred markers spread
    over the screen are each within reach of a few dozen)."""
    n = len(pos)
    if n < 2:
        return np.empty(0, dtype=np.intp), np.empty(0, dtype=np.intp)
    reach = np.broadcast_to(np.asarray(radius, dtype=float), (n,))
    sweep = float(reach.max()) if reach.ndim else float(reach)
    sweep = 2 * sweep if np.ndim(radius) else sweep
    axis = 0 if np.ptp(pos[:, 0]) >= np.ptp(pos[:, 1]) else 1
    order = np.argsort(pos[:, axis], kind="stable")
    xs = pos[order, axis]
    ends = np.searchsorted(xs, xs + sweep, side="left")
    starts = np.arange(1, n + 1)
    counts = np.maximum(ends - starts, 0)
    total = int(counts.sum())
    if total == 0:
        return np.empty(0, dtype=np.intp), np.empty(0, dtype=np.intp)
    a = np.repeat(np.arange(n), counts)
    b = np.arange(total) - np.repeat(np.cumsum(counts) - counts, counts) + np.repeat(starts, counts)
    i, k = order[a], order[b]
    d = np.hypot(pos[k, 0] - pos[i, 0], pos[k, 1] - pos[i, 1])
    near = d < (reach[i] + reach[k] if np.ndim(radius) else radius)
    i, k = i[near], k[near]
    return np.minimum(i, k), np.maximum(i, k)


# spread() stops pushing when the crowding has not shrunk by a hundredth in this many passes.
STALL = 8


def _crowds(n, i, k):
    """The crowd of each of `n` markers joined by the pairs (i, k): an array of one root marker
    per crowd (union-find with path halving)."""
    crowd = list(range(n))

    def top(m):
        while crowd[m] != m:
            crowd[m] = crowd[crowd[m]]
            m = crowd[m]
        return m

    for a, b in zip(i.tolist(), k.tolist()):
        ra, rb = top(a), top(b)
        if ra != rb:
            crowd[ra] = rb
    return np.array([top(m) for m in range(n)])


def _room(points, radii, gap):
    """An upper bound of the area within radii[i] of some points[i] (pixels): the cells of a grid
    a quarter of a gap wide that may hold such a point (a cell whose gap to the point's own cell
    is within its radius), each counted whole. Points of one radius share one stencil."""
    cell = 0.25 * gap
    home = np.floor(points / cell).astype(np.int64)
    steps = np.ceil(np.asarray(radii, dtype=float) / cell).astype(np.int64)
    x0, y0 = home.min(axis=0) - steps.max() - 1
    x1, y1 = home.max(axis=0) + steps.max() + 1
    grid = np.zeros((int(x1 - x0) + 1, int(y1 - y0) + 1), dtype=bool)
    for reach in np.unique(steps).tolist():
        dx, dy = (d.ravel() for d in np.meshgrid(np.arange(-reach - 1, reach + 2), np.arange(-reach - 1, reach + 2)))
        keep = np.hypot(np.maximum(abs(dx) - 1, 0), np.maximum(abs(dy) - 1, 0)) <= reach
        dx, dy = dx[keep], dy[keep]
        own = home[steps == reach]
        grid[(own[:, 0, None] + dx[None, :] - x0).ravel(), (own[:, 1, None] + dy[None, :] - y0).ravel()] = True
    return int(grid.sum()) * cell * cell


def spread(anchors, gap, seeds=None, iterations=100, box=None):
    """A layout of markers on the screen: `anchors` are the markers' points in pixels [(x, y)],
    `seeds` their first offsets (a stack's side by side, or (0, 0)); returns the offsets [(dx, dy)]
    in pixels that set every two markers at least `gap` apart, each pair that is nearer pushed
    apart along the line between them, half each, all pairs at once from where the markers are
    (so the layout does not depend on their order), until none is (or `iterations` passes). A
    marker that nothing crowds keeps its seed; none goes further than its seed's length and a
    gap from its point. A crowd that cannot be made readable so (a hundred joints along a chain
    seen whole: more markers than the screen has room for beside their joints) keeps its seeds:
    markers scattered about would say less than markers at their joints. `box` (x0, y0, x1, y1),
    the screen in the same pixels: markers whose points are further off it than three gaps and
    their cap are not laid out (they keep their seeds; they cannot be drawn on it, and the camera
    coming to rest over them lays them out then).

    In numpy, each pass over one list of the pairs that can ever come within a gap (a marker
    stays within its cap of its point: those whose points are nearer than a gap and their two
    caps), so a camera rest with hundreds of joints lays them out in milliseconds
    (docs/performance.md)."""
    n = len(anchors)
    if n == 0:
        return []
    seeds = seeds or [(0.0, 0.0)] * n
    anchor = np.array(anchors, dtype=float).reshape(n, 2)
    seed = np.array(seeds, dtype=float).reshape(n, 2)
    caps = np.hypot(seed[:, 0], seed[:, 1]) + gap
    if box is not None:
        reach = caps + 3 * gap
        shown = ((anchor[:, 0] > box[0] - reach) & (anchor[:, 0] < box[2] + reach)
                 & (anchor[:, 1] > box[1] - reach) & (anchor[:, 1] < box[3] + reach))
        if not shown.all():
            inside = np.flatnonzero(shown).tolist()
            laid = spread([anchors[i] for i in inside], gap, [seeds[i] for i in inside], iterations) if inside else []
            out = [tuple(s) for s in seeds]
            for i, offset in zip(inside, laid):
                out[i] = offset
            return out
    pos = anchor + seed
    # The crowds: markers joined by chains of pairs nearer than a gap, as seeded.
    near_i, near_k = _pairs_within(pos, gap - 1e-9)
    tops = _crowds(n, near_i, near_k)
    # A crowd that has not the room for its markers a gap apart (packed as closely as discs can
    # be, 0.87 gap^2 each, in its box grown by a gap all round) is left as seeded at once.
    hopeless = set()
    for c in np.unique(tops[near_i]).tolist() if len(near_i) else ():
        members = pos[tops == c]
        x0, y0 = members.min(axis=0)
        x1, y1 = members.max(axis=0)
        if 0.87 * len(members) * gap * gap > (x1 - x0 + 2 * gap) * (y1 - y0 + 2 * gap):
            hopeless.add(c)
        elif 0.866 * len(members) * gap * gap > _room(anchor[tops == c], caps[tops == c] + 0.5 * gap, gap):
            # The same count against the room its markers can reach: each stays within its cap
            # of its joint, so their discs (a gap across) lie within cap and half a gap of the
            # joints. A chain seen slantwise has a box of room and a strip of it: its passes
            # pushed to and fro until the last one (most of a layout zoomed in on a chain).
            hopeless.add(c)
    free = ~np.isin(tops, list(hopeless)) if hopeless else np.ones(n, dtype=bool)
    # The pairs that can come within a gap, among the markers that may move: each point's reach
    # is its cap and half a gap (a hopeless crowd's markers are not even looked at: a chain seen
    # whole spent most of a layout finding pairs it then threw away).
    movable = np.flatnonzero(free)
    cand_i, cand_k = _pairs_within(anchor[movable], (caps + 0.5 * gap)[movable])
    cand_i, cand_k = movable[cand_i], movable[cand_k]
    # The passes stop once the crowding left no longer shrinks (by a hundredth in STALL passes):
    # a crowd that cannot be made readable went back to its seeds after the last pass anyway,
    # and pushing it on for the remaining passes cost most of a layout zoomed in on a chain.
    best, since = math.inf, 0
    for _ in range(iterations) if len(cand_i) else ():
        # All pairs pushed from the same positions.
        dx = pos[cand_k, 0] - pos[cand_i, 0]
        dy = pos[cand_k, 1] - pos[cand_i, 1]
        d = np.hypot(dx, dy)
        near = d < gap - 1e-9
        if not near.any():
            break
        i, k, dx, dy, d = cand_i[near], cand_k[near], dx[near], dy[near], d[near]
        crowding = float((gap - d).sum())
        if crowding < 0.99 * best:
            best, since = crowding, 0
        else:
            since += 1
            if since >= STALL:
                break
        same = d < 1e-9
        if same.any():  # one point: apart along a direction of their own
            turn = 2.399963 * (i[same] + k[same])  # the golden angle: no two pairs alike
            dx[same], dy[same], d[same] = np.cos(turn), np.sin(turn), 1.0
        push = 0.5 * (gap - d) + 1e-6
        ux, uy = dx / d * push, dy / d * push
        move = np.zeros((n, 2))
        move[:, 0] = np.bincount(k, ux, n) - np.bincount(i, ux, n)
        move[:, 1] = np.bincount(k, uy, n) - np.bincount(i, uy, n)
        pos += move
        # None wanders off its joint.
        off = pos - anchor
        r = np.hypot(off[:, 0], off[:, 1])
        out = r > caps
        if out.any():
            pos[out] = anchor[out] + off[out] * (caps[out] / r[out])[:, None]
    # A crowd still crowded goes back to its seeds; one of those may then crowd a marker of a
    # crowd made readable (whose passes saw it elsewhere), which then goes back too, until none
    # is left nearer than a gap to a marker that moved.
    unreadable = set(hopeless)
    while True:
        back = np.isin(tops, list(unreadable)) if unreadable else np.zeros(n, dtype=bool)
        pos[back] = anchor[back] + seed[back]
        left_i, left_k = _pairs_within(pos, gap * (1 - 1e-3) - 1e-9)
        more = set(tops[left_i].tolist()) | set(tops[left_k].tolist())
        if more <= unreadable:
            break
        unreadable |= more
    offsets = (pos - anchor).tolist()
    return [tuple(seeds[i]) if tops[i] in unreadable else (offsets[i][0], offsets[i][1]) for i in range(n)]


def _screen_scaled(child, pixels):
    """`child` (drawn at unit size) scaled at each redraw so that one unit is `pixels` pixels on
    the screen: FreeCAD's SoShapeScale node (a Coin node of FreeCAD's GUI, made by its type
    name since pivy has no class for it), behind a callback that sets its scaleFactor for the
    viewport drawn.

    SoShapeScale (FreeCAD 0.20's src/Gui/SoAxisCrossKit.cpp) divides its scaleFactor by the
    viewport's height in pixels and passes that to Coin's getWorldToScreenScale, which takes it
    as a share of the view volume's width: one unit was drawn scaleFactor * width / height pixels
    (measured on a ring of radius 1 seen face on: 19.0 px for 14 in a 1052 x 772 view, 10.5 in a
    656 x 876 one, 7.1 in a 400 x 800 image; the same at every zoom). The callback, traversed just
    before it at every redraw, sets scaleFactor to `pixels` * height / width of the viewport being
    drawn (the view's, or the image's that saveImage renders), so a unit is `pixels` pixels in
    each, as the layout (PIXELS) counts it."""
    coin = _coin()
    kind = coin.SoType.fromName("SoShapeScale")
    if kind.isBad():  # not FreeCAD's GUI: the glyph at unit size
        return child
    node = coin.cast(kind.createInstance(), "SoBaseKit")
    factor = coin.cast(node.getField("scaleFactor"), "SoSFFloat")
    factor.setValue(pixels)
    node.setPart("shape", child)
    fit = coin.SoCallback()
    fit.setCallback(_fit_to_viewport, (factor, float(pixels), coin.SoGLRenderAction.getClassTypeId(),
                                       coin.SoViewportRegionElement.get))
    group = coin.SoGroup()
    group.addChild(fit)
    group.addChild(node)
    return group


def _fit_to_viewport(data, action):
    """An SoCallback's function: SoShapeScale's scaleFactor (`data`: the field, the pixels a unit
    is drawn, the render action's type and SoViewportRegionElement.get, found once) made pixels *
    height / width of the viewport a render draws. Set without notifying: two views of one
    document of different shapes (or a view and an image saved at another size) draw the same
    marker, each render setting its own value; a notification would have each render ask the
    other view for a redraw, and so on forever. The field is read by the SoShapeScale right after,
    in the same traversal. 5-7 us a marker and a redraw (docs/workbench.md, "Measured")."""
    factor, pixels, render, region = data
    if not action.isOfType(render):
        return
    width, height = region(action.getState()).getViewportSizePixels()
    value = pixels * height / width if width > 0 else pixels
    if abs(factor.getValue() - value) > 1e-6 * value:
        factor.enableNotify(False)
        factor.setValue(value)
        factor.enableNotify(True)


class Marker:
    """A glyph placed at a world point with its z along a world axis, the same size on the screen
    at any zoom, with the three looks. Its `root` goes into a view provider's display mode or
    straight into a view's scene graph."""

    def __init__(self, joint_type, name="dispcon_marker", pixels=PIXELS):
        coin = _coin()
        self.root = coin.SoSeparator()
        self.root.setName(name)
        # Never picked: a click on the edge under a marker (the marker to come of the edge under
        # the cursor, a joint's marker on the pin to pick next) reaches that edge.
        self.root.addChild(_shared_node("unpickable", _unpickable))
        self.transform = coin.SoTransform()
        self.root.addChild(self.transform)
        # The fields, found once: pivy looks a field up by name at every access (tens of
        # microseconds), and a drag places the markers at every frame.
        self._translation = self.transform.translation
        self._rotation = self.transform.rotation
        self._vec = coin.SbVec3f
        # The look: an override material and line width (ignoring the pieces' own colours)
        # when selected or in error; nothing overridden when normal (a switch shows no child
        # until told).
        self.look_switch = coin.SoSwitch()
        self._look = self.look_switch.whichChild
        for look in LOOKS[1:]:
            self.look_switch.addChild(_shared_node(look, _look_override))
        # The error look's glyph half as large again, about its own centre: in the holder after
        # the layout's shift (offset), so the shift stays the layout's. Before the screen scale, it
        # grew the shift too and more than half again (the third audit: a stacked marker in error
        # 142 px from its joint where the layout put it 43 px away, its ring 3.3 times as large).
        self.grow = coin.SoSwitch()
        self._grown = self.grow.whichChild
        self.grow.addChild(_shared_node("grow", _half_again))
        # Drawn or not, as a view's own state (a drag hides the markers: docs/performance.md);
        # above the annotation, so a hidden marker costs no delayed-render path.
        self.visible = coin.SoSwitch()
        self._shown = self.visible.whichChild
        self._shown.setValue(coin.SO_SWITCH_ALL)
        self.root.addChild(self.visible)
        self.annotation = coin.SoAnnotation()
        self.visible.addChild(self.annotation)
        self.annotation.addChild(self.look_switch)
        # The glyph goes into `holder`, which the screen scale draws at `pixels` per unit.
        self.holder = coin.SoSeparator()
        self.holder.setName("dispcon_glyph_holder")
        # The glyph's shift off its point in glyph units (a stacked marker's), before the glyph.
        self.offset = coin.SoTranslation()
        self._offset = self.offset.translation
        self.scaled = _screen_scaled(self.holder, pixels)
        self.annotation.addChild(self.scaled)
        self.joint_type = None
        self.look = "normal"
        self.set_type(joint_type)

    def set_type(self, joint_type):
        if joint_type == self.joint_type:
            return
        self.holder.removeAllChildren()
        self.holder.addChild(self.offset)
        self.holder.addChild(self.grow)
        self.holder.addChild(shared_glyph(joint_type))
        self.joint_type = joint_type

    def place(self, point, axis):
        self._translation.setValue(point.x, point.y, point.z)
        (a, angle) = _turn_z_to((axis.x, axis.y, axis.z))
        self._rotation.setValue(self._vec(*a), angle)

    def set_placement(self, placement):
        """The glyph at `placement` (its z along the joint's axis), as joint_placement() gives."""
        b = placement.Base
        self._translation.setValue(b.x, b.y, b.z)
        self._rotation.setValue(*placement.Rotation.Q)

    def set_offset(self, local):
        """Shifts the glyph off its point by `local`, a vector in the marker's own frame in glyph
        units (PIXELS pixels each on the screen): a marker set apart from others at one place."""
        self._offset.setValue(local.x, local.y, local.z)

    def offset_units(self):
        return App.Vector(*self._offset.getValue().getValue())

    def set_visible(self, on):
        """Draws the marker or not (nothing else changes: it still follows its placement)."""
        self._shown.setValue(_coin().SO_SWITCH_ALL if on else _coin().SO_SWITCH_NONE)

    def is_visible(self):
        return self._shown.getValue() != _coin().SO_SWITCH_NONE

    def set_look(self, look):
        if look not in LOOKS:
            raise ValueError("unknown marker look %r (expected one of %s)" % (look, ", ".join(LOOKS)))
        self.look = look
        self._look.setValue(LOOKS.index(look) - 1 if look != "normal" else _coin().SO_SWITCH_NONE)
        self._grown.setValue(_coin().SO_SWITCH_ALL if look == "error" else _coin().SO_SWITCH_NONE)


def joint_frame(joint):
    """The joint's point and axis in world coordinates, from part 1 (the guide's part), or None
    when a reference is missing. A Gears joint's marker sits where the pitch circles touch (the
    centres' distance split as r1 : r2, that is ratio : 1), a Belt's half-way between the
    pulleys, or, a planet in its ring, where they mesh; so it stands apart from the gears' own
    revolutes."""
    ref = joint.Reference1
    if not ref or ref[0] is None:
        return None
    pl = ref[0].Placement
    point, axis = pl.multVec(joint.Point1), pl.Rotation.multVec(joint.Axis1)
    other = joint.Reference2
    if joint.JointType in ("Gears", "Belt") and other and other[0] is not None and "Ratio" in joint.PropertiesList:
        centre2 = other[0].Placement.multVec(joint.Point2)
        inside = _internal_mesh(joint, point, centre2) if joint.JointType == "Belt" else None
        if inside is not None:
            return inside, axis
        share = joint.Ratio / (1.0 + joint.Ratio) if joint.JointType == "Gears" and joint.Ratio > 0 else 0.5
        point = point + (centre2 - point) * share
    return point, axis


def _internal_mesh(joint, centre1, centre2):
    """Where a Belt that is an internal mesh (a planet in its ring: one picked circle's centre
    inside the other circle) meshes: on the larger circle, on the side of the smaller one; None
    for a belt between pulleys apart (or circles no longer there)."""
    from . import geometry

    try:
        r1, r2 = (geometry.feature(ref[0], ref[1][0]).radius for ref in (joint.Reference1, joint.Reference2))
    except Exception:  # an element gone, or not a circle: the solve names it
        return None
    if not r1 or not r2:
        return None
    d = centre2 - centre1
    if not 1e-12 < d.Length < max(r1, r2):
        return None
    big, small, r = (centre2, centre1, r2) if r2 > r1 else (centre1, centre2, r1)
    return big + (small - big) * (r / d.Length)


def joint_placement(joint):
    """Where the joint's marker is drawn: at joint_frame()'s point with its z along the axis,
    turned about the axis with part 1. The glyph is fixed on part 1, so it looks the same
    whether a drag carries it on the part's transform or it is placed from the Placements; None
    when a reference is missing."""
    frame = joint_frame(joint)
    if frame is None:
        return None
    point, axis = frame
    # A copy: FreeCAD writes a property's Placement back after any call that may change it
    # (multiply() among them), which would move the part and call this again.
    turn = App.Rotation(joint.Reference1[0].Placement.Rotation)
    a, angle = _turn_z_to(turn.inverted().multVec(axis))
    return App.Placement(point, turn.multiply(App.Rotation(App.Vector(*a), math.degrees(angle))))
