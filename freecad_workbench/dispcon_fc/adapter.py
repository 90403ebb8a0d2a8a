"""The adapter between FreeCAD and the engine: an assembly's parts (their Placements are the
poses, their solids give centres of mass, masses and inertias) and joints (points and axes in each
part's frame) become a dispcon.Model; the solved poses come back as Placements."""
import contextlib
import math
import re

import FreeCAD as App

from . import engine, geometry, subassembly
from .objects import (COUPLINGS, HOLD_TWIST, JOINT_TYPES, LENGTH_PHASE, PICKED_FRAMES, frame_rotation,
                      frame_shift, joints, parts, phase_value, offset_text, remake_phase, set_phase, shape_of, twist_from_picks)


def _vec(v):
    return (v.x, v.y, v.z)


def _rotvec(rotation):
    axis, angle = rotation.Axis, rotation.Angle
    return (axis.x * angle, axis.y * angle, axis.z * angle)


def live_curve(j, count=64):
    """The curve of a PointOnCurve joint, sampled now from part 1's picked edge, in part 1's
    frame: the geometry as it is, whenever the joint was made or its type changed."""
    (part, sub, _), _ = references(j)
    if not sub.startswith("Edge"):
        raise ValueError("%s: a PointOnCurve joint needs an edge of %s as its first reference, not %s"
                         % (j.Label, part.Label, sub or "the whole part"))
    edge = shape_of(part).getElement(sub)  # (references read it: it is there)
    return [geometry.to_local(part.Placement, point=p) for p in edge.discretize(count)]


class LostReference(ValueError):
    """A joint's reference that cannot be read as the document stands: its part deleted, its part
    not in the assembly, or its picked element gone. str() is the one sentence every path says
    (Solve's and Check's skipped joints, the Drive, an edit of the joint's type or TwistFrom):
    the joint's label, what happened, what to do; `why` is that sentence after the label."""

    def __init__(self, joint, why):
        super().__init__("%s: %s" % (joint.Label, why))
        self.joint, self.why = joint, why


# What to do about a lost reference, the same in every sentence: the joint panel (opened by a
# double-click) picks references again.
_PICK_AGAIN = "pick that reference again (double-click the joint)"


class Reference:
    """One of a joint's references as read now: the part, the picked element's name ("" for the
    whole part) and its geometry.Feature in world coordinates (None when not read, or the whole
    part)."""

    __slots__ = ("part", "sub", "feature")

    def __init__(self, part, sub, feature):
        self.part, self.sub, self.feature = part, sub, feature

    def __iter__(self):
        return iter((self.part, self.sub, self.feature))


def references(j, parts=None, features=True):
    """The joint's two references, (Reference, Reference), read by the one reader every caller
    uses; LostReference (one sentence per case, naming the joint) when one of its parts was
    deleted, when a part is not among `parts` (the names of the assembly's parts, with those of
    its sub-assemblies; None: not checked), or, with `features`, when a picked element is gone
    (FreeCAD renumbers the edges and faces of a changed shape, and its errors for a name it no
    longer has vary: no such element, an edge with no curve)."""
    refs = (j.Reference1, j.Reference2)
    if not all(ref and ref[0] is not None for ref in refs):
        raise LostReference(j, "one of its parts was deleted: pick its two references again (double-click "
                               "the joint) or delete the joint")
    if parts is not None:
        for ref in refs:
            if ref[0].Name not in parts:
                raise LostReference(j, "%s is not a part of the assembly: add it to the assembly, or %s"
                                       % (ref[0].Label, _PICK_AGAIN))
    out = []
    for part, subs in refs:
        sub = subs[0] if subs else ""
        f = None
        if features and sub:
            try:
                f = geometry.feature(part, sub)
            except Exception:
                raise LostReference(j, "%s has no %s any more, its shape changed: %s"
                                       % (part.Label, sub, _PICK_AGAIN)) from None
        out.append(Reference(part, sub, f))
    return tuple(out)


# Features whose axis belongs to the geometry (a circle's, a line's, a plane's normal ...), read
# again at every solve. A vertex's (the part's own z) and a sphere's (its own axis) are kept as
# stored: a joint made before the fifteenth round took the world's z at the pose it was made in
# there, and keeps that meaning; another face gives the world's z, which says nothing of the part.
OWN_AXIS = ("circle", "line", "curve", "cylinder", "plane")
ANCHORS = ("Point1", "Axis1", "Perp1", "Point2", "Axis2", "Perp2")
LIVE_TYPES = ("Fixed", "Revolute", "Slider", "Cylindrical", "Ball", "Planar", "PointOnLine", "PointOnPlane",
              "PointOnCurve", "Angle") + COUPLINGS


def live_anchors(j, refs=None):
    """The joint's points and axes in each part's frame, read again from the referenced edges and
    faces as the parts' shapes are now (a Pad made longer, a hole moved): {"Point1": ..., ...}.
    What did not change keeps its stored value exactly; an axis keeps the sense it was given
    (part 2's flipped when the picked axes pointed apart) and the twist reference stays across
    it; a Fixed or Slider whose twist comes from the picked frames (TwistFrom) reads that too
    (picked_across). A joint on the whole part keeps what it has. `refs`: references(j) when the
    caller read them. LostReference, naming the joint, when a reference is lost."""
    out = {name: App.Vector(getattr(j, name)) for name in ANCHORS}
    if j.JointType not in LIVE_TYPES:  # a Distance keeps what it was made with
        return out
    picked = twist_from_picks(j)
    axis1 = None
    for k, (part, sub, f) in zip("12", refs or references(j)):
        if not sub:
            continue
        if k == "1":
            axis1 = f.axis
        elif j.JointType == "RackPinion" and f.kind == "plane" and axis1 is not None:
            # A rack picked by its face travels in it, across the pinion's axis (as made).
            travel = axis1.cross(f.axis)
            if travel.Length > 1e-9:
                f = geometry.Feature(f.point, travel, f.kind)
        point = geometry.to_local(part.Placement, point=f.point)
        stored = out["Point" + k]
        if (point - stored).Length > 1e-9 * max(1.0, stored.Length):
            out["Point" + k] = point
        if f.kind in OWN_AXIS:
            axis = geometry.to_local(part.Placement, axis=f.axis)
            stored = out["Axis" + k]
            if axis.dot(stored) < 0:
                axis = axis * -1
            if (axis - stored).Length > 1e-9:
                out["Axis" + k] = axis
                perp = out["Perp" + k]
                perp = perp - axis * perp.dot(axis)
                out["Perp" + k] = perp.normalize() if perp.Length > 1e-9 else _across(axis)
        if picked:
            perp = picked_across(part.Placement, f, out["Axis" + k])
            if (perp - out["Perp" + k]).Length > 1e-9:
                out["Perp" + k] = perp
    return out


# The part's own axes in the order picked_across prefers them on a tie: z first (parts drawn on
# the xy plane stand up along it), then x, then y.
_PART_AXES = (App.Vector(0, 0, 1), App.Vector(1, 0, 0), App.Vector(0, 1, 0))


def picked_across(placement, f, axis):
    """The twist reference a picked element gives, in its part's frame (`placement`: the part's),
    square to `axis` (the joint's axis there): the x of the element's own frame where it has one
    (f.across: a circle's, a planar or cylindrical face's), else, by a rule of the part's frame
    alone, that one of the part's own z, x and y which lies most across the axis (z first, then
    x, on a tie: a line along x gives z, a line along z gives x), made square to it. Either way a
    function of the part and its geometry, never of the pose it stands in; the same for the axis
    either way round, so a flipped part 2 (Reversed, picked axes pointing apart) turns over about
    it."""
    a = App.Vector(axis).normalize()
    if f is not None and f.across is not None:
        x = geometry.to_local(placement, axis=f.across)
        x = x - a * x.dot(a)
        if x.Length > 1e-9:
            return x.normalize()
    best = _PART_AXES[0]
    for e in _PART_AXES[1:]:
        if abs(e.dot(a)) < abs(best.dot(a)) - 1e-9:
            best = e
    x = best - a * best.dot(a)
    return x.normalize()


def _across(v):
    """A unit vector across `v`."""
    other = App.Vector(1, 0, 0) if abs(v.x) < 0.9 else App.Vector(0, 1, 0)
    return v.cross(other).normalize()


def kind_of(dispcon, joint_type, rows=None):
    """The row of the engine's joint table (dispcon.joint_kinds(), or `rows` read from it once
    by the caller: the table is built anew at each call, 1.3 ms) for a workbench joint type:
    "PointOnLine" is the kind "point_on_line", "Gears" the kind "gear", "RackPinion" the kind
    "rack" (FreeCAD's names are the engine's, in words run together, or plural, or cut short)."""
    want = joint_type.lower()
    rows = rows if rows is not None else dispcon.joint_kinds()
    for same in (lambda name: name == want, lambda name: name + "s" == want,
                 lambda name: len(name) >= 4 and want.startswith(name)):
        for row in rows:
            if same(row["name"].replace("_", "")):
                return row
    raise ValueError("joint type %r is not a kind of joint the engine knows (%s)"
                     % (joint_type, ", ".join(r["name"] for r in rows)))


def offered_types(dispcon):
    """The workbench's joint types the engine can solve, each a row of its joint table (a
    Distance: rows and statements chosen by what is picked): what the commands and the panel
    offer."""
    out = []
    for joint_type in JOINT_TYPES:
        try:
            joint_type == "Distance" or kind_of(dispcon, joint_type)
        except ValueError:
            continue
        out.append(joint_type)
    return out


def _feature_shape(kind):
    from .geometry import Feature

    return Feature((0, 0, 0), (0, 0, 1), kind).shape


def distance_kwargs(j, p1, a1, p2, a2):
    """A Distance joint on the engine's parts, by what was picked (part 1 the plane or the line):
    two points at a distance (a sphere bound), a point at a signed distance from a plane (the
    plane moved along its normal), two planes at a distance (a planar pair so moved), a point at
    a distance from a line (a cylinder about it), two parallel lines at a distance (that cylinder
    and the axes held parallel), a line parallel to a plane at a distance (the moved plane and the
    line held across the normal)."""
    d = j.Distance.Value
    shapes = (_feature_shape(j.Feature1), _feature_shape(j.Feature2))
    shifted = _vec(App.Vector(*p1) + App.Vector(*a1) * d)
    if shapes == ("point", "point"):
        return dict(kind="distance", point1=p1, point2=p2, distance=(d, d))
    if shapes == ("plane", "point"):
        return dict(kind="point_on_plane", point1=shifted, point2=p2, axis1=a1, axis2=a2)
    if shapes == ("plane", "plane"):
        return dict(kind="planar", point1=shifted, point2=p2, axis1=a1, axis2=a2)
    if shapes == ("plane", "line"):
        return dict(hinge=(shifted, p2), planar=(a1,), angle=(a1, a2, math.pi / 2, math.pi / 2))
    if shapes == ("line", "point"):
        return dict(hinge=(p1, p2), cylinder=(a1, d))
    if shapes == ("line", "line"):
        return dict(hinge=(p1, p2), cylinder=(a1, d), angle=(a1, a2, 0.0, 0.0))
    raise ValueError("%s: a Distance joint between %s and %s is not known (pick vertices, edges or "
                     "faces again)" % (j.Label, j.Feature1 or "?", j.Feature2 or "?"))


def coupling_kwargs(row, j, remake=False):
    """A coupling's value under the name its row of the engine's table gives it (coupling_args:
    ratio, radius or pitch first), a screw's hand, and its phase when it is known (PhaseKnown:
    the engine's, in radians or mm; the engine checks it) and still measured with the geometry it
    was made with (not `remake`). Without one, the engine makes the coupling at the poses the
    parts have, and record_phases keeps what it made."""
    takes = row["coupling_args"]
    values = {"ratio": j.Ratio, "radius": j.Radius.Value, "pitch": j.Pitch.Value}
    kw = {takes[0]: values[takes[0]]}
    if "left" in takes:
        kw["left"] = bool(j.LeftHanded)
    if "phase" in takes and getattr(j, "PhaseKnown", False) and not remake:
        kw["phase"] = phase_to_engine(j, phase_value(j))
    return kw


def phase_to_engine(j, value):
    """A Phase of the joint (deg, or mm for a rack or a screw) in the engine's unit."""
    return value if j.JointType in LENGTH_PHASE else math.radians(value)


def phase_from_engine(j, value):
    return value if j.JointType in LENGTH_PHASE else math.degrees(value)


def joint_kwargs(dispcon, j, anchors=None, remake=False, kinds=None):
    """The joint as add_joint's arguments: its kind, its anchors in each part's frame (`anchors`,
    from live_anchors, or those stored), and those of its limits the kind takes (a revolute keeps
    no travel set while it was a slider); a coupling's phase left to the engine when `remake`.
    `kinds`: the engine's joint table when the caller read it once (kind_of)."""
    a = anchors or {name: getattr(j, name) for name in ANCHORS}
    # Offset: part 2's point sits that far along part 1's axis; Reversed: part 2's axis flipped
    # (part 2 turned over about the twist reference, which stays put).
    offset = j.Offset.Value if "Offset" in j.PropertiesList else 0.0
    flip = -1 if "Reversed" in j.PropertiesList and j.Reversed else 1
    if j.JointType == "Distance":
        kw = distance_kwargs(j, _vec(j.Point1), _vec(j.Axis1), _vec(j.Point2), _vec(j.Axis2 * flip))
        if j.Move >= 0:
            kw["move"] = j.Move
        return kw
    row = kind_of(dispcon, j.JointType, kinds)
    rad = math.radians
    axis2, across2 = turned_frame(a["Axis2"] * flip, a["Perp2"], frame_rotation(j))
    point2 = moved_point(a["Point2"], axis2, across2, frame_shift(j))
    kw = dict(kind=row["name"], point1=_vec(a["Point1"] + a["Axis1"] * offset), point2=_vec(point2),
              axis1=_vec(a["Axis1"]), axis2=_vec(axis2), across1=_vec(a["Perp1"]), across2=_vec(across2))
    limits = {"angle": (rad(j.AngleMin.Value), rad(j.AngleMax.Value))}
    if j.HasRotationLimits:
        limits["turn"] = (rad(j.RotationMin.Value), rad(j.RotationMax.Value))
    if j.HasTravelLimits:
        limits["travel"] = (j.TravelMin.Value, j.TravelMax.Value)
    if j.ConeAngle.Value > 0:
        limits["cone"] = rad(j.ConeAngle.Value)
    kw.update({name: value for name, value in limits.items() if name in row["limits"]})
    if row.get("coupling"):
        kw.update(coupling_kwargs(row, j, remake))
    if row["needs_curve"]:
        kw["curve"] = [_vec(p) for p in live_curve(j)]
    if j.Move >= 0:
        kw["move"] = j.Move
    return kw


# The engine's statements whose bounds a joint's limits are, as the joint's panel names them.
LIMIT_NAMES = {"twist": "turn", "axial": "travel", "angle": "angle", "sphere": "distance"}


def refused_bounds(refusal):
    """(min, max, unit) of the engine's refusal of crossed bounds (dispcon.LimitError) as the
    panel writes them: degrees and "\u00b0" for an angle, mm and " mm" for a length."""
    if refusal.unit == "angle":
        return math.degrees(refusal.min), math.degrees(refusal.max), "\u00b0"
    return refusal.min, refusal.max, " mm"


def limit_refusal(j, refusal):
    """The engine's refusal of a joint's limits, Min above Max (dispcon.LimitError: which
    statement, the bounds as given, their unit), in the designer's words: the joint by its label,
    the limit as its panel names it, degrees or mm as the panel writes them, and what to do. Its
    Min set above its Max in the property editor (which the panel's check does not see) comes
    here; the engine's own words were "constraint: twist: min 1.0472 is above max 0.5"."""
    what = LIMIT_NAMES.get(refusal.statement, refusal.statement)
    lo, hi, unit = refused_bounds(refusal)
    return ("%s: its %s's Min %g%s is above its Max %g%s: set Min below Max (double-click %s to open its panel)"
            % (j.Label, what, lo, unit, hi, unit, j.Label))


def moved_anchors(j, anchors):
    """The labels of the parts whose live `anchors` (live_anchors) moved a point or an axis of
    `j` from those the joint holds ([] when none did)."""
    return [ref[0].Label for k, ref in (("1", j.Reference1), ("2", j.Reference2))
            if any(getattr(j, name + k) != anchors[name + k] for name in ("Point", "Axis"))]


def moved_point(point, axis, across, shift):
    """Part 2's joint point (in part 2's frame) with the frame's translation offset `shift`, (x, y)
    along the frame's x (the twist reference `across`, square to `axis`) and y (axis x across), or
    as it is when None: the point goes the other way, so that when the joint puts it on part 1's,
    part 2 stands moved by `shift` in the joint's frame."""
    if shift is None:
        return point
    z = App.Vector(axis).normalize()
    x = App.Vector(across) - z * App.Vector(across).dot(z)
    x = x.normalize() if x.Length > 1e-12 else _across(z)
    y = z.cross(x)
    return point - x * shift[0] - y * shift[1]


def turned_frame(axis, across, rotation):
    """Part 2's joint axis and twist reference (its frame's z and x, in part 2's frame) with the
    frame's rotation offset: the frame turned by the inverse of `rotation` about its own axes, so
    that when the joint lines it up with part 1's, part 2 stands turned by `rotation` in the joint's
    frame (a yaw of 30 degrees turns part 2 30 degrees on about the joint's axis). None: as they
    are."""
    if rotation is None:
        return axis, across
    z = App.Vector(axis).normalize()
    x = App.Vector(across) - z * App.Vector(across).dot(z)
    x = x.normalize() if x.Length > 1e-12 else _across(z)
    y = z.cross(x)
    back = rotation.inverted()

    def in_part(v):  # a vector of the joint's frame in part 2's
        return x * v.x + y * v.y + z * v.z

    return in_part(back.multVec(App.Vector(0, 0, 1))) * axis.Length, in_part(back.multVec(App.Vector(1, 0, 0)))


def _in_body(kw, side, local):
    """add_joint's arguments with side 1's or 2's anchors carried from its part's frame into its
    body's (a part of a rigid sub-assembly: `local` is the part's placement in the instance)."""
    if local is None:
        return kw
    for key in ("point", "axis", "across"):
        if key + side in kw:
            v = App.Vector(*kw[key + side])
            kw[key + side] = _vec(local.multVec(v) if key == "point" else local.Rotation.multVec(v))
    if side == "1" and "curve" in kw:
        kw["curve"] = [_vec(local.multVec(App.Vector(*p))) for p in kw["curve"]]
    # A Distance made of statements (distance_kwargs): their points and directions by side.
    for statement, items in _STATEMENT_SIDES.items():
        if statement in kw:
            values = list(kw[statement])
            for k, (s, what) in enumerate(items):
                if s == side:
                    v = App.Vector(*values[k])
                    values[k] = _vec(local.multVec(v) if what == "point" else local.Rotation.multVec(v))
            kw[statement] = tuple(values)
    return kw


# Which side's frame each leading argument of the statements distance_kwargs writes is in.
_STATEMENT_SIDES = {"hinge": (("1", "point"), ("2", "point")), "planar": (("1", "axis"),),
                    "cylinder": (("1", "axis"),), "angle": (("1", "axis"), ("2", "axis"))}


def local_mass(shape, placement):
    """Volume, centre of mass and inertia (unit density, about the centre of mass) of a shape's
    solids in the frame of `placement`; () when it has no solid."""
    props = geometry.mass_properties(shape)
    if props is None:
        return ()
    volume, com, inertia = props
    # The inertia is in global axes of the shape as placed: to local axes.
    R = placement.Rotation.toMatrix()
    rows = [[R.A[4 * i + j] for j in range(3)] for i in range(3)]
    local = [[sum(rows[i][a] * inertia[i][j] * rows[j][b] for i in range(3) for j in range(3)) for b in range(3)]
             for a in range(3)]
    return volume, geometry.to_local(placement, point=com), local


class Centres:
    """The parts' centres of mass in their own frames, each kept with the shape it was integrated
    from: OpenCascade's integration was most of the time a model of a hundred parts took to build
    (Solve, Check, a drag's press, a joint added each build one). One per assembly, held by its
    proxy and never saved (centres_of): it goes with the assembly, and with its document when that
    closes. A shape is integrated again when it is no longer a partner of the one kept (the same
    geometry, wherever it is placed: a recomputed part, a document read again is integrated anew);
    a part moved keeps its centre, which is in its own frame."""

    def __init__(self):
        self.known = {}  # (document name, object name) -> (shape, centre or None)

    def __len__(self):
        return len(self.known)

    def centre(self, owner, shape, placement):
        """The centre of mass of `owner`'s `shape` (its solids) in the frame of `placement`, the
        owner's; None when it has no solid or no volume."""
        key = (owner.Document.Name, owner.Name)
        # Only a shape placed where its owner is (a Part::Feature's, a link's: to rounding,
        # FreeCAD places it through a matrix) is known by its geometry: the centre in the owner's
        # frame is then the same wherever the owner stands, to rounding (a few units in the last
        # place of the centre integrated anew).
        rel = placement.inverse().multiply(shape.Placement)
        q = rel.Rotation.Q
        placed = rel.Base.Length <= 1e-12 * max(1.0, placement.Base.Length) and math.sqrt(
            q[0] ** 2 + q[1] ** 2 + q[2] ** 2) <= 1e-12
        known = self.known.get(key) if placed else None
        if known is not None and known[0].isPartner(shape):
            return App.Vector(known[1]) if known[1] is not None else None
        com = geometry.center_of_mass(shape)
        centre = geometry.to_local(placement, point=com) if com is not None else None
        if placed:
            self.known[key] = (shape, App.Vector(centre) if centre is not None else None)
        return centre


def centres_of(asm):
    """The Centres kept by `asm`'s proxy, made at the first model built of it (a proxy restored
    from a file or copied is made without one: FreeCAD saves none of it); a fresh one, kept by
    nobody, for an assembly whose proxy was lost (opened where the workbench was missing)."""
    from .objects import AssemblyProxy

    proxy = getattr(asm, "Proxy", None)
    if not isinstance(proxy, AssemblyProxy):
        return Centres()
    centres = getattr(proxy, "centres", None)
    if centres is None:
        centres = proxy.centres = Centres()
    return centres


class Adapter:
    """One assembly as a dispcon.Model: bodies are the parts (their Placement is the pose), with
    mass and inertia from their shapes; joints are the joint objects, in order."""

    def __init__(self, asm, physics=False, made=None):
        # made: {joint name: engine phase} for couplings whose phase is to be made at the poses
        # with an offset typed since (pending_offsets): the model is built again with them.
        self.made = made or {}
        self.dispcon = engine.load()
        self.kinds = self.dispcon.joint_kinds()  # read once a model, not once a joint (kind_of)
        self.asm = asm
        self.centres = centres_of(asm)
        self.model = self.dispcon.Model()
        # names: the objects that are bodies (parts, rigid sub-assemblies, the parts of flexible
        # ones) -> body name; frames: every object a joint can hold -> (body name, its placement
        # in the body's frame, None when it is the body); rigid: instance -> {link: that placement}.
        self.names, self.frames, self.rigid = {}, {}, {}
        self.parts = []
        for p in parts(asm):
            self.add_body(p, shape_of(p), physics)
        instance_joints = subassembly.add_instances(self, physics)
        # A joint that lost a part is left out of the model and reported, by its label.
        # So is one whose picked edge or face is gone; the others take their geometry as the
        # parts' shapes are now (anchors).
        self.skipped = []
        self.anchors = {}
        active = []
        for j in joints(asm) + instance_joints:
            try:
                refs = references(j, self.frames, features=j.JointType in LIVE_TYPES)
                self.anchors[j.Name, j.Document.Name] = live_anchors(j, refs)
            except LostReference as e:
                self.skipped.append((j, str(e)))
                continue
            active.append(j)
        self.joints = active
        # Couplings whose parts' geometry moved an axis or a centre since their phase was taken
        # (a hole moved, a gear made larger): the phase, measured about the old axes, would hold
        # the parts in a mesh nobody made, so the engine makes it again at the poses the parts
        # have, and the solve says so by label.
        self.remade = [j for j in active if j.JointType in COUPLINGS and getattr(j, "PhaseKnown", False)
                       and not isinstance(j, subassembly.InstanceJoint)  # a placed file's: never written
                       and j.Document == asm.Document and moved_anchors(j, self.anchors[j.Name, j.Document.Name])]
        self.moved = {j.Name: moved_anchors(j, self.anchors[j.Name, j.Document.Name]) for j in self.remade}
        with self.engine_errors():
            for j in self.joints:
                self.add_joint(j)
        pending = {} if made is not None else self.pending_offsets()
        if pending:
            self.__init__(asm, physics, pending)

    def pending_offsets(self):
        """{joint name: engine phase} for the couplings of this document whose phase the engine
        made at the poses (new, changed, or their geometry moved) while their mesh offset differs
        from the one those poses stand at (MeshOffsetHeld: what the stored phase held; 0 for a
        coupling made or changed): the phase made, moved on by the difference (part 2's turn or
        travel enters the equation with a factor 1), so a kept or typed offset is held now."""
        pending = {}
        for i, j in enumerate(self.joints):
            if (isinstance(j, subassembly.InstanceJoint) or j.Document != self.asm.Document
                    or j.JointType not in COUPLINGS or "MeshOffsetHeld" not in j.PropertiesList
                    or (getattr(j, "PhaseKnown", False) and j not in self.remade)):
                continue
            change = j.MeshOffset.Value - j.MeshOffsetHeld.Value
            made = self.model.joint(i).phase
            if change != 0.0 and made is not None:
                pending[j.Name] = made + phase_to_engine(j, change)
        return pending

    def add_joint(self, j, **changed):
        """Adds joint `j` to the model (with the arguments in `changed` in place of its own:
        what an edit would give the engine, which checks them); returns its index."""
        (b1, l1), (b2, l2) = self.frames[j.Reference1[0].Name], self.frames[j.Reference2[0].Name]
        made = {"phase": self.made[j.Name]} if j.Name in self.made and j.Document == self.asm.Document else {}
        kw = dict(joint_kwargs(self.dispcon, j, self.anchors[j.Name, j.Document.Name], j in self.remade, self.kinds),
                  **made)
        kw.update(changed)
        kw = _in_body(_in_body(kw, "1", l1), "2", l2)
        try:
            return self.model.add_joint(b2, object1=b1, label=j.Label, **kw)
        except self.dispcon.LimitError as e:
            raise ValueError(limit_refusal(j, e)) from None

    def add_body(self, owner, shape, physics, local=None):
        """A body for `owner` (a part, or a rigid sub-assembly with the compound of its parts
        placed): its Placement is the pose; returns the body's name. `local`: the shape's mass
        properties in the owner's frame when known (local_mass; the same leg placed four times
        is measured once)."""
        name = "p%d_%s" % (len(self.parts), "".join(c if c.isalnum() else "_" for c in owner.Name))
        self.names[owner.Name] = name
        self.frames[owner.Name] = (name, None)
        self.parts.append(owner)
        pl = owner.Placement
        kw = dict(position=_vec(pl.Base), rotation=_rotvec(pl.Rotation),
                  fixed=bool(getattr(owner, "Grounded", False)))
        if local is None and not physics:
            # The centre only: the integrations for the mass and inertia were most of the time
            # a drag's press took (it builds the model from every part).
            centre = self.centres.centre(owner, shape, pl)
            props = (None, centre, None) if centre is not None else ()
        else:
            props = local if local is not None else local_mass(shape, pl)
        if props:
            volume, centre, inertia = props
            density = getattr(owner, "Density", 1.0) or 1.0
            kw["center"] = _vec(centre)
            if physics:
                kw["mass"] = density * volume
                kw["inertia"] = [[density * v for v in row] for row in inertia]
        if getattr(owner, "AbilityToRotate", 0) > 0:
            kw["rotate"] = owner.AbilityToRotate
        self.model.add_body(name, **kw)
        return name

    def body_of(self, obj):
        """(body name, `obj`'s placement in the body's frame or None) of a part or a part of a
        sub-assembly; KeyError when the assembly has no such part."""
        return self.frames[obj.Name]

    def labelled(self, text):
        """`text` with the model's internal body names (p0_Base) as the parts' labels."""
        labels = {self.names[p.Name]: p.Label for p in self.parts if p.Name in self.names}
        if not labels:
            return text
        pattern = re.compile(r"\b(%s)\b" % "|".join(re.escape(n) for n in sorted(labels, key=len, reverse=True)))
        return pattern.sub(lambda m: labels[m.group(1)], text)

    # How the engine's diagnostics name a joint: "joint #4 (line 12) p0_Base / p3_Crank", its
    # index in the model (the adapter's joints, in order), its .dcl line when read from one.
    JOINT_REF = re.compile(r"joint #(\d+)(?: \(line \d+\))? (\w+) / (\w+)")

    def joint_named(self, index):
        """A joint as the person knows it: "'Crank pin' (joint between 'Ground' and 'Crank')"."""
        j = self.joints[index]
        return "'%s' (joint between '%s' and '%s')" % (j.Label, j.Reference1[0].Label, j.Reference2[0].Label)

    def advice(self, text):
        """One of the engine's diagnostics in the workbench's words: joints and parts by their
        labels, and "removing <joint> makes the model consistent" as what to do about it."""
        def joint(m):
            k = int(m.group(1))
            return self.joint_named(k) if 0 <= k < len(self.joints) else m.group(0)

        fix = re.match(r"removing (joint #\d+.*?) makes the model consistent$", text)
        if fix:
            text = "remove or loosen %s: the other joints then hold" % fix.group(1)
        return self.labelled(self.JOINT_REF.sub(joint, text))

    @contextlib.contextmanager
    def engine_errors(self):
        """The engine's errors as ValueErrors that name the parts by their labels."""
        try:
            yield
        except (RuntimeError, ValueError, IndexError, KeyError) as e:
            raise ValueError(self.labelled(str(e))) from None

    def skipped_message(self):
        return "; ".join("skipped %s" % said for _, said in self.skipped)

    def part_of(self, name):
        for p in self.parts:
            if self.names[p.Name] == name:
                return p
        raise KeyError(name)

    def placement_of(self, part):
        """Where the model has `part` now (a part of a rigid sub-assembly: where its body puts it)."""
        body, local = self.frames[part.Name]
        b = self.model.body(body)
        q = b.quaternion  # w, x, y, z
        pl = App.Placement(App.Vector(*b.position), App.Rotation(q[1], q[2], q[3], q[0]))
        return pl if local is None else pl.multiply(local)

    def write_back(self, moved=True):
        """The model's poses into the document; a placement the model left where it was is not
        written (an unchanged write still marks the document modified). moved=False: the model
        moved nothing (a solve of no iteration), so no part's placement is written at all (read
        from a saved file, a placement comes back from the model a few bits apart)."""
        for p in self.parts:
            if getattr(p, "Grounded", False) or not moved:
                continue
            pl = self.placement_of(p)
            if not subassembly.same(pl, p.Placement):
                p.Placement = pl
        subassembly.write_back(self)
        self.record_phases()

    def record_phases(self):
        """Stores each coupling's phase as the model holds it now in its joint (made at the poses
        where it had none; followed through the turns as the parts moved), so the next model
        holds the coupling where this one did: a gear turned by hand goes back into mesh at the
        next Solve, and the ratio holds across sessions."""
        for i, j in enumerate(self.joints):
            if (isinstance(j, subassembly.InstanceJoint) or j.Document != self.asm.Document
                    or j.JointType not in COUPLINGS):
                continue
            phase = self.model.joint(i).phase
            if phase is None:
                continue
            value = phase_from_engine(j, phase)
            if j in self.remade:  # made at these poses: its geometry goes with it
                self.store_anchors(j)
                j.PhaseKnown = False
            # A phase made at the poses holds the mesh offset the joint has: 0 for a coupling
            # made or changed, the designer's own for one whose geometry moved (pending_offsets).
            held = "MeshOffsetHeld" in j.PropertiesList and j.MeshOffsetHeld.Value == j.MeshOffset.Value
            if not getattr(j, "PhaseKnown", False) or abs(phase_value(j) - value) > 1e-12 or not held:
                set_phase(j, value)
        self.recorded = True

    def remade_message(self):
        """The couplings whose phase this model made again, by label ("" when none)."""
        if not self.remade:
            return ""
        return "; ".join("made the phase of %s again at the parts' poses (the geometry of %s moved its axis or "
                         "centre; its mesh offset, %s, kept)"
                         % (j.Label, " and ".join(self.moved[j.Name]), offset_text(j))
                         for j in self.remade)

    def store_anchors(self, j):
        for name, value in self.anchors[j.Name, j.Document.Name].items():
            if getattr(j, name) != value:
                setattr(j, name, value)

    def update_joints(self):
        """Stores the geometry the joints were solved with (read from the live shapes) in the
        joints of this document whose parts' shapes changed, so their markers follow (the joints
        of a linked file are never changed)."""
        for j in self.joints:
            if j.Document != self.asm.Document:
                continue
            self.store_anchors(j)
            if j in self.remade and not getattr(self, "recorded", False):
                remake_phase(j, keep_offset=True)  # the solve failed: made at the poses by the next model

    def mark(self, result):
        """Each joint's residual and whether it is violated, written only where they changed
        (a Solve that moved nothing leaves the document unmodified)."""
        for report, j in zip(result.constraints, self.joints):
            if isinstance(j, subassembly.InstanceJoint):
                continue  # a joint of the placed assembly: its document is not written to
            if not same_residual(j.Residual, report.residual, self.asm.Tolerance):
                j.Residual = report.residual
            if j.Violated != (not report.satisfied):
                j.Violated = not report.satisfied


def same_residual(old, new, tolerance):
    """Two residuals within a ten-thousandth of each other, or a thousandth of the solve's
    tolerance apart: the same for a designer. A saved file keeps a float's first five digits and
    rounds the poses, so the same assembly read again gives residuals that far apart (a joint
    holding at 2.2985e-12 came back at 2.3010e-12, the tolerance 1e-9). A NaN is never the same."""
    return math.isclose(old, new, rel_tol=1e-4, abs_tol=1e-3 * float(tolerance))


ALREADY_HELD = "every joint already holds; nothing moved"


def plural(n, word):
    """`n` and `word`, with an s unless n is one ("1 iteration", "3 iterations", "0 joints")."""
    return "%d %s%s" % (n, word, "" if n == 1 else "s")


def made_askew(j):
    """How far apart (degrees, at least) the two parts' axes of a joint holding the turn as it
    was when made (HOLD_TWIST, TwistFrom "Pose when made") were then, from its stored twist
    reference: made lined up, part 2's reference is square to its axis; made with part 2 tipped
    by t away from part 1's axis, their dot product is up to sin(t). 0 for a joint that holds no
    turn, or takes it from the picked frames (made in any pose, it means the same)."""
    if j.JointType not in HOLD_TWIST or "Perp2" not in j.PropertiesList or twist_from_picks(j):
        return 0.0
    axis, perp = App.Vector(j.Axis2), App.Vector(j.Perp2)
    if axis.Length < 1e-12 or perp.Length < 1e-12:
        return 0.0
    return math.degrees(math.asin(min(1.0, abs(axis.dot(perp)) / (axis.Length * perp.Length))))


def made_askew_hints(joints, least=10.0):
    """What to do about each joint whose TwistFrom is "Pose when made" and that was made with its
    parts' axes `least` degrees apart or more: it holds part 2 turned about the axis as it stood
    then, a turn with which the other joints may have no pose (the slider-crank's Slider made
    after its Ball's solve had tipped the piston over, the third workbench audit); its TwistFrom
    set to "Picked frames" takes the turn from the picked elements instead."""
    hints = []
    for j in joints:
        t = made_askew(j)
        if t >= least:
            part1, part2 = j.Reference1[0].Label, j.Reference2[0].Label
            hints.append("%s was made with %s's axis %.0f degrees or more off %s's and, its TwistFrom being "
                         "'Pose when made', holds %s turned about it as it stood then: if the joints cannot "
                         "hold so, set its TwistFrom to '%s' (the joint panel's Twist from), which lines up "
                         "the picked elements' frames whatever the pose"
                         % (j.Label, part2, t, part1, part2, PICKED_FRAMES))
    return hints


class Result:
    """What a solve said, with the joints still violated named as the user knows them."""

    def __init__(self, adapter, r):
        self.converged = r.converged
        self.iterations = r.iterations
        self.max_residual = r.max_residual
        self.violated = [adapter.joints[i] for i in r.violated]
        names = ", ".join("%s (residual %.3g)" % (adapter.joints[i].Label, r.constraints[i].residual) for i in r.violated)
        self.skipped = [j for j, _ in adapter.skipped]
        if not r.converged:
            self.message = "could not make every joint hold; still violated: " + names
            self.message += "".join("; " + hint for hint in made_askew_hints(adapter.joints))
        elif r.iterations == 0:
            self.message = ALREADY_HELD
        else:
            self.message = "solved in %s" % plural(r.iterations, "iteration")
        if not adapter.joints:
            self.message = "nothing to solve: %s has no joint" % adapter.asm.Label
        if adapter.skipped:
            self.message += "; " + adapter.skipped_message()
        if adapter.remade:
            self.message += "; " + adapter.remade_message()

    def __bool__(self):
        return self.converged

    def __repr__(self):
        return "<dispcon_fc.Result %s>" % self.message
