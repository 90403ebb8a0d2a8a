"""The operations on an assembly: what a command or a script does to the document. Each is one
undo step (one transaction); each checks its input before it changes anything, and one that fails
half-way is rolled back, so a failed operation leaves the document as it was. A task panel that holds its own transaction open (the joint panel's live
preview) passes undo_step=False: the operation is then part of the panel's one undo step, which
Cancel aborts."""
import contextlib
import math
import os
import re
import warnings

import FreeCAD as App

from . import engine, exploded, geometry, objects, subassembly
from .adapter import ALREADY_HELD, Adapter, Result, _vec, plural, references, refused_bounds
from .objects import joints, placed_parts, shape_of


class Transaction:
    """One undo step on a document, rolled back by abort(). A document without undo (freecadcmd's
    default) gets it for the transaction's time: the rollback needs it."""

    def __init__(self, doc, name):
        self.doc = doc
        self.undo_mode = doc.UndoMode
        if not self.undo_mode:
            doc.UndoMode = 1
        doc.openTransaction(name)

    def _close(self):
        if not self.undo_mode:
            self.doc.UndoMode = self.undo_mode

    def commit(self):
        self.doc.commitTransaction()
        self._close()

    def abort(self):
        self.doc.abortTransaction()
        self._close()


@contextlib.contextmanager
def transaction(doc, name):
    """`with transaction(doc, "Add joint"):` one undo step, rolled back when the body raises."""
    t = Transaction(doc, name)
    try:
        yield
    except BaseException:
        t.abort()
        raise
    t.commit()


def _assembly(asm):
    """The assembly, checked, with its and its joints' proxies back if a restore lost them."""
    if asm is None or not objects.is_assembly(asm):
        raise ValueError("%s is not a Dispcon assembly" % getattr(asm, "Label", asm))
    objects.adopt(asm)
    groups = [asm]
    while groups:  # an instance's nested instances and their links too, at any depth
        for o in groups.pop().Group:
            objects.adopt(o)
            if objects.is_sub_assembly(o):
                groups.append(o)
    return asm


def tolerance(asm):
    t = float(asm.Tolerance)
    if not t > 0:
        raise ValueError("%s: Tolerance must be above 0 (it is %g)" % (asm.Label, t))
    return t


def create_assembly(doc, name="Assembly"):
    """An empty assembly in `doc`, with the tolerance and iteration cap of the preferences."""
    with transaction(doc, "Create assembly"):
        obj = objects.new_assembly(doc, name)
    return obj


def add_part(asm, obj, grounded=False):
    """Adds an existing object of the document (anything with a Shape) to the assembly. A
    PartDesign Body's tip (what a click on the body selects) adds the Body: moved into the
    assembly's group, the feature would leave its Body."""
    _assembly(asm)
    obj = objects.picked(obj)[0]
    body = objects.body_of(obj)
    if body is not None:
        raise ValueError("%s is a feature of the body %s, not a part: add %s itself" % (obj.Label, body.Label, body.Label))
    if not (hasattr(obj, "Shape") or obj.TypeId == "App::Link") or objects.is_joint(obj) or obj == asm:
        raise ValueError("%s has no shape: only solids can be parts" % obj.Label)
    if getattr(obj, "DispconType", "") == "ExplodedView":
        raise ValueError("%s draws the assembly's parts apart; it is not a part" % obj.Label)
    with transaction(asm.Document, "Add part"):
        objects.part_properties(obj)
        obj.Grounded = grounded
        asm.addObject(obj)
    return obj


def set_grounded(part, grounded=True):
    """Grounds a part (it never moves) or frees it, in one undo step."""
    if "Grounded" not in part.PropertiesList:
        raise ValueError("%s is not a part of an assembly" % part.Label)
    if objects.is_sub_assembly(part):
        why = objects.why_not_grounded(part)
        if why:
            raise ValueError("%s cannot be grounded: %s" % (part.Label, why))
    touched = "Touched" in part.State
    with transaction(part.Document, "Ground" if grounded else "Unground"):
        part.Grounded = bool(grounded)
    if not touched:  # its shape is as it was: nothing for a recompute to do
        part.purgeTouched()
    return part


def import_part(asm, path, name=None, grounded=False):
    """Imports a STEP, IGES or BREP file as a part of the assembly."""
    import Part

    _assembly(asm)
    ext = os.path.splitext(path)[1].lower()
    if ext not in (".step", ".stp", ".iges", ".igs", ".brep", ".brp"):
        raise ValueError("%s: expected a STEP, IGES or BREP file" % path)
    if not os.path.isfile(path):
        raise ValueError("%s: no such file" % path)
    shape = Part.Shape()
    try:
        shape.read(path)
    except Exception as e:
        raise ValueError("%s: not readable (%s)" % (path, e)) from None
    name = name or os.path.splitext(os.path.basename(path))[0]
    return _new_part(asm, "Import part", "Part::FeaturePython", name, grounded, Shape=shape)


def linkable_objects(path):
    """The objects of an .FCStd file that can be inserted as parts (those with a solid, outermost
    first): what a person chooses from when inserting a part from another file."""
    other = App.getDocument(_doc_name(path)) if _doc_name(path) else App.openDocument(path)
    out = []
    for o in other.Objects:
        shape = getattr(o, "Shape", None)
        if shape is not None and shape.Solids and not any(hasattr(p, "Shape") for p in o.InList):
            out.append(o)
    return out


def _doc_name(path):
    """The name of the open document saved at `path`, or None."""
    target = os.path.realpath(path)
    for name, d in App.listDocuments().items():
        if d.FileName and os.path.realpath(d.FileName) == target:
            return name
    return None


def link_part(asm, path, object_name=None, grounded=False):
    """Inserts an object of another .FCStd file as a part, as a link (App::Link) that follows the
    file's changes: FreeCAD 1.x's "Insert component". Without object_name, the file's only solid
    (or its first, outermost one). FreeCAD links across documents only from a saved document:
    save the assembly's document first."""
    _assembly(asm)
    if not asm.Document.FileName:
        raise ValueError("save %s before linking parts from other files" % asm.Document.Label)
    if os.path.splitext(path)[1].lower() != ".fcstd":
        raise ValueError("%s: expected a FreeCAD document (.FCStd)" % path)
    if not os.path.isfile(path):
        raise ValueError("%s: no such file" % path)
    if object_name is None:
        candidates = linkable_objects(path)
        if not candidates:
            raise ValueError("%s has no solid to insert" % path)
        source = candidates[0]
    else:
        name = _doc_name(path)
        other = App.getDocument(name) if name else App.openDocument(path)
        source = other.getObject(object_name) or next(
            (o for o in other.Objects if o.Label == object_name), None)
        if source is None:
            raise ValueError("%s has no object %s" % (path, object_name))
    return _new_part(asm, "Link part", "App::Link", source.Label, grounded, LinkedObject=source)


def _new_part(asm, action, type_id, name, grounded, **values):
    """A new object of the document made a part of the assembly, in one undo step."""
    with transaction(asm.Document, action):
        obj = asm.Document.addObject(type_id, name)
        if type_id == "Part::FeaturePython":
            objects.new_part(obj)
        obj.Label = name  # the name as given; the object's Name is FreeCAD's identifier for it
        for key, value in values.items():
            setattr(obj, key, value)
        objects.part_properties(obj)
        obj.Grounded = grounded
        asm.addObject(obj)
    # Its shape is given, nothing to compute: not waiting for a recompute (the tree marks such).
    obj.purgeTouched()
    return obj


def _step(doc, name, undo_step):
    """An undo step of its own, or (undo_step=False) part of the one the caller holds open:
    FreeCAD would commit the caller's when another opens."""
    return transaction(doc, name) if undo_step else contextlib.nullcontext()


def _perpendicular(v):
    other = App.Vector(1, 0, 0) if abs(v.x) < 0.9 else App.Vector(0, 1, 0)
    return v.cross(other).normalize()


# What each joint type takes of the picked geometry (geometry.Feature.kind), and which of the two
# references carries the guide: a Distance's plane or line, a rack's pinion.
_AXES = ("line", "plane", "circle", "cylinder")
_ROUND = ("circle", "cylinder")
_NEEDS = {
    "Distance": ("a vertex, a straight or circular edge, a planar, cylindrical or spherical face on each part",
                 lambda f1, f2: f1.shape is not None and f2.shape is not None),
    "Parallel": ("a straight or circular edge, a planar or cylindrical face on each part",
                 lambda f1, f2: f1.kind in _AXES and f2.kind in _AXES),
    "Perpendicular": ("a straight or circular edge, a planar or cylindrical face on each part",
                      lambda f1, f2: f1.kind in _AXES and f2.kind in _AXES),
    "Gears": ("a circular edge or cylindrical face on each gear", lambda f1, f2: f1.kind in _ROUND and f2.kind in _ROUND),
    "Belt": ("a circular edge or cylindrical face on each pulley", lambda f1, f2: f1.kind in _ROUND and f2.kind in _ROUND),
    "Screw": ("a circular edge or cylindrical face on the screw and on the nut",
              lambda f1, f2: f1.kind in _ROUND and f2.kind in _ROUND),
    "RackPinion": ("a circular edge or cylindrical face on the pinion and a straight edge or planar face on the rack",
                   lambda f1, f2: f1.kind in _ROUND and f2.kind in ("line", "plane")),
}
_RANK = {"plane": 2, "line": 1, "point": 0}


def _guide_first(joint_type, a, b):
    """The two (part, element, feature) in the order the joint needs: a Distance's plane or line
    first (it carries the guide), a rack's pinion first; otherwise as picked."""
    (_, _, f1), (_, _, f2) = a, b
    if joint_type == "Distance" and f1.shape and f2.shape and _RANK[f2.shape] > _RANK[f1.shape]:
        return b, a
    if joint_type == "RackPinion" and f2.kind in _ROUND and f1.kind not in _ROUND:
        return b, a
    return a, b


def _check_features(joint_type, a, b):
    """Refuses geometry the joint type cannot use, naming what was picked and what it needs."""
    if joint_type not in _NEEDS:
        return
    (o1, s1, f1), (o2, s2, f2) = a, b
    what, fits = _NEEDS[joint_type]
    if not fits(f1, f2):
        raise ValueError("a %s joint needs %s, not %s.%s (%s) and %s.%s (%s)"
                         % (joint_type, what, o1.Label, s1, f1.kind, o2.Label, s2, f2.kind))


def _defaults(joint_type, f1, f2):
    """A coupling's values from the picked circles: the gears' ratio r1/r2 (part 2's turn per turn
    of part 1, the pitch circles rolling), the pinion's radius."""
    if joint_type in ("Gears", "Belt") and f1.radius and f2.radius:
        return {"ratio": f1.radius / f2.radius}
    if joint_type == "RackPinion":
        return {"radius": f1.radius}
    return {}


def _parts_base(part1, part2):
    """A joint's label from its parts before any numbering: part 1's first, "Ground-Crank"."""
    return "%s-%s" % (part1.Label, part2.Label)


def parts_label(doc, part1, part2, joint=None):
    """The label a joint between `part1` and `part2` gets from them (the joint panel's): their
    labels, part 1 (the guide's) first, "Ground-Crank"; made unique in `doc` (whatever FreeCAD's
    duplicate-labels preference says) by FreeCAD's numbering, "Ground-Crank001". `joint`: the
    joint to be so named (its own label is no clash)."""
    base = _parts_base(part1, part2)
    taken = {o.Label for o in doc.Objects if o != joint}
    label, k = base, 0
    while label in taken:
        k += 1
        label = "%s%03d" % (base, k)
    return label


def named_from_parts(joint):
    """Whether the joint's label is the one its parts give it (parts_label's, numbered or not),
    not one a person typed nor a type's name from an earlier workbench (Revolute001)."""
    r1, r2 = joint.Reference1, joint.Reference2
    if not r1 or not r2:
        return False
    base = _parts_base(r1[0], r2[0])
    rest = joint.Label[len(base):] if joint.Label.startswith(base) else None
    return rest is not None and (rest == "" or (len(rest) == 3 and rest.isdigit()))


def add_joint(asm, joint_type, ref1, ref2, undo_step=True, named_by_parts=False, **limits):
    """A joint between two parts from geometry references in FreeCAD's form, (obj, "Edge3").
    Part 1 carries the guide (the slider's line, the plane, the curve; a Distance's plane or line
    and a rack's pinion are made part 1 whichever was picked first). Limits: rotation=(min, max)
    in degrees, travel=(min, max) in length units, cone=degrees, angle=(min, max) degrees, move=mu;
    reverse=True flips part 2's axis, offset=length puts part 2's point that far from part 1's
    along part 1's axis; rotation=False and travel=False (edit_joint) take such limits off.
    Distance: distance=length. Couplings: ratio= (Gears, Belt: part 2's turn per turn of part 1;
    by default the picked radii's r1 / r2), radius= (RackPinion: by default the picked circle's),
    pitch= (Screw: travel per turn), left=True (a left-handed screw), mesh_offset=degrees (mm for a
    rack or a screw: part 2 turned, or moved, that far against part 1 from the pose the coupling is
    made in), phase= (the engine's constant itself, degrees or mm). Fixed, Revolute, Slider,
    Cylindrical and Planar: frame=(yaw, pitch, roll) in degrees turns part 2's joint frame, so that
    part 2 stands so turned against part 1 (yaw about the joint's axis, then pitch and roll);
    shift=(x, y) in mm moves it along the frame's x and y (across the axis; along it: offset), so
    that part 2 stands that far off part 1's point in the joint's frame. Fixed and Slider:
    twist_from="Picked frames" (the default) holds part 2's turn about the axis where the picked
    elements' own frames line up, whatever the pose now; "Pose when made" holds the turn it has
    now (objects.TWIST_FROM; every joint saved before the choice existed). Revolute and
    Cylindrical: the same choice says where their turn limits count from (Min 0 deg: the picked
    frames' x's lined up, or part 2 turned as it stands now). The joint's label is its
    type's, numbered (Revolute001) as FreeCAD 1.x names joints and as scripts and `--joint` name
    them; named_by_parts=True (the joint panel) labels it from its parts (parts_label)."""
    _assembly(asm)
    if joint_type not in objects.JOINT_TYPES:
        raise ValueError("unknown joint type %r (expected one of %s)" % (joint_type, ", ".join(objects.JOINT_TYPES)))
    # A part inside a sub-assembly: (instance, "Crank.Edge3") or (asm, "Leg1.Crank.Edge3").
    # A PartDesign Body's tip named (Pad, "Face1"), or by its path (Body or link, "Pad.Face1"):
    # the Body, or the link, is the part (objects.picked).
    (o1, s1), (o2, s2) = (subassembly.resolve(asm, *objects.picked(*ref)) for ref in (ref1, ref2))
    if o1 == o2:
        raise ValueError("a joint needs two different parts (both references are on %s)" % o1.Label)
    for o in (o1, o2):
        if o not in placed_parts(asm):
            raise ValueError("%s is not a part of %s" % (o.Label, asm.Label))
    if joint_type == "PointOnCurve" and not s1.startswith("Edge"):
        raise ValueError("a PointOnCurve joint needs an edge of %s as its first reference, not %s"
                         % (o1.Label, s1 or "the whole part"))
    a, b = (o1, s1, geometry.feature(o1, s1)), (o2, s2, geometry.feature(o2, s2))
    a, b = _guide_first(joint_type, a, b)
    _check_features(joint_type, a, b)
    (o1, s1, f1), (o2, s2, f2) = a, b
    limits = dict(_defaults(joint_type, f1, f2), **limits)
    _check_limits(joint_type, **limits)
    _check_distance(joint_type, joint_type, f1, limits.get("distance"))
    _check_twist_type(joint_type, joint_type, limits.get("twist_from"))
    with _step(asm.Document, "Add joint", undo_step):
        j = objects.new_joint(asm.Document, joint_type)
        j.JointType = joint_type
        if limits.get("twist_from") is not None:
            with objects.quiet(j):  # before _place, which takes the twist reference by it
                j.TwistFrom = limits["twist_from"]
        _place(j, joint_type, a, b)
        _set_limits(j, **limits)
        if named_by_parts:
            j.Label = parts_label(asm.Document, o1, o2, j)
        asm.addObject(j)
        if limits.get("frame") is not None or limits.get("shift") is not None:
            if joint_type not in objects.FRAME_ROTATED:
                raise ValueError("%s: a %s joint's frame takes no %s offset (only %s)"
                                 % (j.Label, joint_type, "rotation" if limits.get("frame") is not None
                                    else "translation", ", ".join(objects.FRAME_ROTATED)))
            Adapter(asm)  # the engine checks the turned axis, the moved point (its door); an error undoes the joint
        given = limits.get("phase") is not None or limits.get("mesh_offset") is not None
        if given and joint_type not in objects.COUPLINGS:
            raise ValueError("%s: only a coupling (%s) has a phase" % (j.Label, ", ".join(objects.COUPLINGS)))
        if joint_type in objects.COUPLINGS and limits.get("phase") is None:
            _record_phases(asm)
        if limits.get("mesh_offset") is not None:
            _offset_mesh(asm, j, limits["mesh_offset"])
        if given:
            Adapter(asm)  # the engine checks the phase given (its door); an error undoes the joint
    return j


def _offset_mesh(asm, j, offset):
    """Sets the coupling's mesh offset (deg, or mm) and the engine's phase by as much: made at
    the poses first when it is not known yet."""
    if not j.PhaseKnown:
        _record_phases(asm)
    if not j.PhaseKnown:
        raise ValueError("%s: its assembly does not hold yet, so its mesh has no place to offset from: "
                         "solve it first" % j.Label)
    phase = objects.phase_value(j) + offset - objects.mesh_offset(j)
    j.MeshOffset = objects.normal_offset(j.JointType, offset)
    objects.set_phase(j, phase)  # holding the offset


def _place(j, joint_type, a, b):
    """The joint's references and their points and axes, each in its part's frame as the parts
    stand now."""
    (o1, s1, f1), (o2, s2, f2) = a, b
    if joint_type == "RackPinion" and f2.kind == "plane":
        # The rack travels in its face's plane, across the pinion's axis.
        travel = f1.axis.cross(f2.axis)
        if travel.Length < 1e-9:
            raise ValueError("%s.%s is a face across the pinion's axis: pick the rack's face or edge "
                             "along which it travels" % (o2.Label, s2))
        f2 = geometry.Feature(f2.point, travel, f2.kind)
    objects.joint_extras(j)
    j.Reference1 = (o1, [s1])
    j.Reference2 = (o2, [s2])
    j.Feature1, j.Feature2 = f1.kind, f2.kind
    j.Point1 = geometry.to_local(o1.Placement, point=f1.point)
    j.Axis1 = geometry.to_local(o1.Placement, axis=f1.axis)
    j.Point2 = geometry.to_local(o2.Placement, point=f2.point)
    j.Axis2 = geometry.to_local(o2.Placement, axis=f2.axis)
    # Axes that the user picked pointing apart are taken as the same line (a rack's travel
    # stays as picked: it lies across the pinion's axis).
    if f1.axis.dot(f2.axis) < 0 and joint_type != "RackPinion":
        j.Axis2 = j.Axis2 * -1
    j.Perp1, j.Perp2 = twist_reference(j, (o1, f1), (o2, f2), axis1=f1.axis)


def twist_reference(j, side1, side2, picked=None, axis1=None):
    """The joint's twist references (Perp1, Perp2), each in its part's frame, from its parts and
    picked features ((part, geometry.Feature) each) and its axes as stored: from the picked
    elements' own frames (adapter.picked_across) for a Fixed, Slider, Revolute or Cylindrical
    whose TwistFrom says so (`picked`: that choice instead of the joint's), else a vector across
    axis 1 and the same world vector in part 2's frame at the pose the parts have now, so the turn
    is measured from where the parts are (a Revolute's turn limits "Pose when made" count from
    there, and every type's without TwistFrom); `axis1`: axis 1
    in world coordinates when known (the picked feature's), else from the stored one."""
    (o1, f1), (o2, f2) = side1, side2
    if picked is None:
        picked = objects.twist_from_picks(j)
    if picked:
        from .adapter import picked_across

        return picked_across(o1.Placement, f1, j.Axis1), picked_across(o2.Placement, f2, j.Axis2)
    perp_world = _perpendicular(axis1 if axis1 is not None else o1.Placement.Rotation.multVec(j.Axis1))
    return geometry.to_local(o1.Placement, axis=perp_world), geometry.to_local(o2.Placement, axis=perp_world)


def _read_references(joint, features=True):
    """adapter.references of the joint, its parts checked against those of its assembly (when it
    is in one): a lost reference refused in the words Solve and Check skip the joint with. A
    joint as it holds in a flexible instance (the Drive's Walk2.Leg3.Revolute) holds the
    instance's links, which its placed assembly's parts are not: read without that check."""
    own = not isinstance(joint, subassembly.InstanceJoint)
    asm = next((p for p in joint.InList if objects.is_assembly(p)), None) if own else None
    return references(joint, {p.Name for p in placed_parts(asm)} if asm is not None else None, features)


def _referenced_features(joint):
    """((part, feature), (part, feature)) of the joint's two references as the parts stand now."""
    return tuple((part, f) for part, _, f in _read_references(joint))


def _check_twist_type(label, kind, twist_from):
    """A TwistFrom that is one of objects.TWIST_FROM, on a type that holds a turn: else refused,
    naming the joint and the choices."""
    if twist_from is None:
        return
    if twist_from not in objects.TWIST_FROM:
        raise ValueError("%s: twist from %r is not one of %s" % (label, twist_from,
                                                                 ", ".join(repr(t) for t in objects.TWIST_FROM)))
    if kind not in objects.TWIST_TYPES:
        raise ValueError("%s: a %s joint measures no turn about its axis to take from anywhere (only %s)"
                         % (label, kind, ", ".join(objects.TWIST_TYPES)))


def _check_twist(joint, kind, twist_from):
    """A new TwistFrom of the joint, checked before anything changes: its value, then the twist
    references it gives, by the engine (the model's door): the joint added again with them to a
    model of its assembly as it stands."""
    _check_twist_type(joint.Label, kind, twist_from)
    features = _referenced_features(joint)  # a lost reference refused before the engine skips the joint
    adapter = _door(joint, kind)
    if adapter is None:
        return
    from .adapter import joint_kwargs

    a = adapter.anchors[joint.Name, joint.Document.Name]
    perp1, perp2 = twist_reference(joint, *features, picked=twist_from == objects.PICKED_FRAMES)
    kw = joint_kwargs(adapter.dispcon, joint, dict(a, Perp1=perp1, Perp2=perp2), kinds=adapter.kinds)
    try:
        with adapter.engine_errors():
            adapter.add_joint(joint, **kw)
    except ValueError as e:
        raise ValueError("%s: its twist taken from the %s: %s" % (joint.Label, twist_from.lower(), e)) from None


def _retwist(joint, twist_from):
    """The joint's twist references made again for a new TwistFrom, then TwistFrom set: from the
    picked frames, or from the pose the parts have now (in that order, so that the proxy, which
    takes a TwistFrom set in the property editor as this, finds the twist already taken)."""
    picked = twist_from == objects.PICKED_FRAMES
    joint.Perp1, joint.Perp2 = twist_reference(joint, *_referenced_features(joint), picked=picked)
    joint.TwistFrom = twist_from


def twist_from_set(joint, before):
    """TwistFrom just set in the property editor (or by a script), from `before`: taken as the
    joint panel and edit_joint take it, the twist references made again from the picked frames
    or from the pose the parts have now (a Revolute's limits then count from that turn), checked
    at the engine's door first. Refused (a lost reference, a twist the joints cannot hold),
    TwistFrom goes back to `before`, nothing else changed, and the Report view and the status bar
    say why in the words edit_joint raises."""
    now = joint.TwistFrom
    try:
        perps = twist_reference(joint, *_referenced_features(joint))
        if all((p - getattr(joint, name)).Length < 1e-12 for p, name in zip(perps, ("Perp1", "Perp2"))):
            return  # taken already (edit_joint, the panel), or the same either way
        _check_twist(joint, joint.JointType, now)
    except ValueError as e:
        with objects.quiet(joint):
            joint.TwistFrom = before
        text = "%s (Twist from back to %r)" % (e, before)
        from . import feedback

        feedback.report(text, error=True)
        feedback.status(text)
        return
    joint.Perp1, joint.Perp2 = perps


def _check_distance(label, joint_type, f1, distance):
    """A Distance below 0 is a side of a plane: refused from a point or a line."""
    if joint_type == "Distance" and distance is not None and distance < 0 and f1.shape != "plane":
        raise ValueError("%s: distance %g mm is below 0 (only a plane has sides: pick the plane first)"
                         % (label, distance))


# add_joint's limits, each as the engine's kind that takes it and its name there, and the unit
# it is given in (degrees or mm) into the engine's.
_LIMIT_KINDS = (("rotation", "revolute", "turn", math.radians), ("travel", "slider", "travel", float),
                ("angle", "angle", "angle", math.radians))


def crossed_limit(rotation=None, travel=None, angle=None, **_):
    """The first of these limits (add_joint's keywords: degrees, mm) whose Min the engine finds
    above its Max, as (keyword, dispcon.LimitError), or None: asked of the engine (the model's
    door) on a model of its own, whatever the joint's type, since a limit its type does not take
    stays in its properties to hold when the type changes. Only that is asked: the range of a
    cone or an angle, which the engine clamps, is _check_limits' own."""
    dispcon = engine.load()
    model = dispcon.Model()
    model.add_body("probe")
    for key, kind, name, to_engine in _LIMIT_KINDS:
        pair = {"rotation": rotation, "travel": travel, "angle": angle}[key]
        if pair in (None, False):
            continue
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", dispcon.ModelWarning)
                model.add_joint("probe", kind=kind, **{name: (to_engine(pair[0]), to_engine(pair[1]))})
        except dispcon.LimitError as e:
            return key, e
    return None


def _check_limits(label, rotation=None, travel=None, cone=None, angle=None, move=None, reverse=None,
                  offset=None, distance=None, ratio=None, radius=None, pitch=None, left=None, phase=None,
                  mesh_offset=None, frame=None, shift=None, twist_from=None):
    """Refuses limits that cannot hold, before anything changes; names the joint and the limit."""
    crossed = crossed_limit(rotation=rotation, travel=travel, angle=angle)
    if crossed:
        what, refusal = crossed
        lo, hi, unit = refused_bounds(refusal)
        unit = " deg" if refusal.unit == "angle" else unit
        raise ValueError("%s: %s min %g%s is above max %g%s" % (label, what, lo, unit, hi, unit))
    if cone is not None and not 0 <= cone <= 180:
        raise ValueError("%s: cone angle %g deg is outside 0..180" % (label, cone))
    if angle is not None and not (0 <= angle[0] and angle[1] <= 180):
        raise ValueError("%s: angle limits %g..%g deg are outside 0..180" % (label, angle[0], angle[1]))
    if move is not None and not (move == -1 or 0 <= move <= 1):
        raise ValueError("%s: move %g is outside 0..1 (or -1: from the masses)" % (label, move))
    for what, value, unit in (("ratio", ratio, ""), ("radius", radius, " mm"), ("pitch", pitch, " mm")):
        if value is not None and not value > 0:
            raise ValueError("%s: %s %g%s must be above 0" % (label, what, value, unit))


def _set_limits(j, rotation=None, travel=None, cone=None, angle=None, move=None, reverse=None, offset=None,
                distance=None, ratio=None, radius=None, pitch=None, left=None, phase=None, mesh_offset=None,
                frame=None, shift=None, twist_from=None):
    # rotation=False, travel=False: no such limits any more.
    if rotation is not None:
        j.HasRotationLimits = rotation is not False
        if rotation is not False:
            j.RotationMin, j.RotationMax = rotation
    if travel is not None:
        j.HasTravelLimits = travel is not False
        if travel is not False:
            j.TravelMin, j.TravelMax = travel
    if cone is not None:
        j.ConeAngle = cone
    if angle is not None:
        j.AngleMin, j.AngleMax = angle
    if move is not None:
        j.Move = move
    objects.joint_extras(j)
    if frame is not None:
        j.FrameYaw, j.FramePitch, j.FrameRoll = (float(a) for a in frame)
    if shift is not None:
        j.FrameX, j.FrameY = (float(d) for d in shift)
    if twist_from is not None and twist_from != j.TwistFrom:
        _retwist(j, twist_from)
    # What the coupling's phase is measured with changed: the engine makes it again at the
    # poses the parts have (record_phases keeps it), so the parts stay where they are.
    remade = False
    for name, value in (("Reversed", reverse), ("Offset", offset), ("Distance", distance), ("Ratio", ratio),
                        ("Radius", radius), ("Pitch", pitch), ("LeftHanded", left)):
        if value is not None:
            value = bool(value) if name in ("Reversed", "LeftHanded") else value
            old = getattr(j, name)
            remade |= name in _PHASE_MEASURE and getattr(old, "Value", old) != value
            setattr(j, name, value)
    if phase is not None:
        # The engine's value given: the mesh offset moves with it (when the old one was known).
        if getattr(j, "PhaseKnown", False):
            j.MeshOffset = objects.normal_offset(j.JointType, objects.mesh_offset(j) + phase - objects.phase_value(j))
        objects.set_phase(j, phase)
    elif remade:
        objects.remake_phase(j)


# The values a coupling's phase is measured with (its equation's coefficients and axes).
_PHASE_MEASURE = ("Reversed", "Ratio", "Radius", "Pitch", "LeftHanded")


def _door(joint, kind):
    """The adapter of the joint's assembly as it stands, to check a new value of the joint at the
    engine (the model's door) before anything changes; None when there is nothing to check yet (a
    joint changing its type to `kind` meets the door at its first solve). A joint the adapter
    leaves out (a reference lost) is refused in the words its Solve says."""
    asm = next((p for p in joint.InList if objects.is_assembly(p)), None)
    if asm is None or joint.JointType != kind:
        return None
    adapter = Adapter(asm)
    said = next((said for j, said in adapter.skipped if j == joint), None)
    if said is not None:
        raise ValueError(said)
    return adapter if joint in adapter.joints else None


def _check_phase(joint, kind, phase):
    """A coupling's new phase, checked by the engine (the model's door) before anything changes:
    the joint added again with it to a model of its assembly as it stands (a joint changing its
    type to a coupling meets the door at its first solve)."""
    if kind not in objects.COUPLINGS:
        raise ValueError("%s: only a coupling (%s) has a phase" % (joint.Label, ", ".join(objects.COUPLINGS)))
    adapter = _door(joint, kind)
    if adapter is None:
        return
    from .adapter import phase_to_engine

    with adapter.engine_errors():
        adapter.add_joint(joint, phase=phase_to_engine(joint, phase))


def _check_shift(joint, kind, shift, frame=None):
    """A translation offset of part 2's joint frame, (x, y) in mm across the joint's axis, checked
    by the engine (the model's door) before anything changes: the joint added again with part 2's
    point moved so (and its frame turned by `frame` when that changes too), to a model of its
    assembly as it stands."""
    if kind not in objects.FRAME_ROTATED:
        raise ValueError("%s: a %s joint's frame takes no translation offset (only %s)"
                         % (joint.Label, kind, ", ".join(objects.FRAME_ROTATED)))
    try:
        x, y = (float(d) for d in shift)
    except (TypeError, ValueError):
        raise ValueError("%s: a frame's translation offset is (x, y) in mm, not %r" % (joint.Label, shift)) from None
    adapter = _door(joint, kind)
    if adapter is None:
        return
    from .adapter import moved_point, turned_frame

    a = adapter.anchors[joint.Name, joint.Document.Name]
    flip = -1 if getattr(joint, "Reversed", False) else 1
    turn = App.Rotation(*(float(v) for v in frame)) if frame is not None else objects.frame_rotation(joint)
    axis, across = turned_frame(a["Axis2"] * flip, a["Perp2"], turn)
    try:
        with adapter.engine_errors():
            adapter.add_joint(joint, axis2=_vec(axis), across2=_vec(across),
                              point2=_vec(moved_point(a["Point2"], axis, across, (x, y))))
    except ValueError as e:
        raise ValueError("%s: its frame moved by %r mm: %s" % (joint.Label, tuple(shift), e)) from None


def _check_frame(joint, kind, frame):
    """A rotation offset of part 2's joint frame, (yaw, pitch, roll) in degrees, checked by the
    engine (the model's door) before anything changes: the joint added again with the axis and
    twist reference it turns to, to a model of its assembly as it stands."""
    if kind not in objects.FRAME_ROTATED:
        raise ValueError("%s: a %s joint's frame takes no rotation offset (only %s)"
                         % (joint.Label, kind, ", ".join(objects.FRAME_ROTATED)))
    if len(frame) != 3:
        raise ValueError("%s: a frame's rotation offset is (yaw, pitch, roll) in degrees, not %r" % (joint.Label, frame))
    adapter = _door(joint, kind)
    if adapter is None:
        return
    from .adapter import turned_frame

    a = adapter.anchors[joint.Name, joint.Document.Name]
    flip = -1 if getattr(joint, "Reversed", False) else 1
    try:
        turn = App.Rotation(*(float(v) for v in frame))
    except (TypeError, ValueError):
        raise ValueError("%s: the frame's rotation offset %r is not three angles" % (joint.Label, frame)) from None
    axis, across = turned_frame(a["Axis2"] * flip, a["Perp2"], turn)
    try:
        with adapter.engine_errors():
            adapter.add_joint(joint, axis2=_vec(axis), across2=_vec(across))
    except ValueError as e:
        raise ValueError("%s: its frame turned by %r deg: %s" % (joint.Label, tuple(frame), e)) from None


def _record_phases(asm):
    """The phases of the couplings without one, as the engine makes them at the poses now (a
    coupling just made: held where it was made). An assembly the engine cannot model yet keeps
    them unknown: its first solve makes them."""
    try:
        Adapter(asm).record_phases()
    except ValueError:
        pass


def set_limits(joint, **limits):
    """Changes a joint's limits (same keywords as add_joint) in one undo step."""
    return edit_joint(joint, **limits)


def edit_joint(joint, joint_type=None, undo_step=True, **limits):
    """Changes a joint's type and limits (same keywords as add_joint) in one undo step; limits
    that cannot hold are refused before anything changes."""
    if not objects.is_joint(joint):
        raise ValueError("%s is not a Dispcon joint" % joint.Label)
    objects.adopt(joint)
    if joint_type is not None and joint_type not in objects.JOINT_TYPES:
        raise ValueError("%s: unknown joint type %r (expected one of %s)"
                         % (joint.Label, joint_type, ", ".join(objects.JOINT_TYPES)))
    kind = joint_type or joint.JointType
    retype = joint_type is not None and joint_type != joint.JointType
    # A new type reads the picked geometry (its anchors at the next solve, a Distance's or a
    # coupling's features now): its references read first, a lost one refused in their words.
    refs = _read_references(joint) if retype else None
    if kind == "PointOnCurve" and refs and not refs[0].sub.startswith("Edge"):
        raise ValueError("%s: a PointOnCurve joint needs an edge of %s as its first reference"
                         % (joint.Label, refs[0].part.Label))
    _check_limits(joint.Label, **limits)
    # A type that reads the picked geometry (a Distance, a coupling) takes it from the references
    # again: the features, which one carries the guide, a rack's direction of travel.
    replace = None
    if retype and (joint_type in _NEEDS or joint.JointType in _NEEDS):
        whole = next((r.part for r in refs if r.feature is None), None)
        if whole is not None:
            raise ValueError("%s: it holds %s whole, with no vertex, edge or face picked, which a %s joint "
                             "reads: pick its references again (double-click the joint)"
                             % (joint.Label, whole.Label, joint_type))
        a, b = _guide_first(joint_type, *[tuple(r) for r in refs])
        _check_features(joint_type, a, b)
        replace = (a, b)
    f1 = replace[0][2] if replace else geometry.Feature((0, 0, 0), (0, 0, 1), getattr(joint, "Feature1", ""))
    _check_distance(joint.Label, kind, f1, limits.get("distance"))
    if limits.get("phase") is not None:
        _check_phase(joint, kind, limits["phase"])
    frame = limits.get("frame")
    if frame is not None and tuple(frame) != tuple(getattr(joint, name).Value if name in joint.PropertiesList else 0.0
                                               for name in ("FrameYaw", "FramePitch", "FrameRoll")):
        _check_frame(joint, kind, frame)
    shift = limits.get("shift")
    if shift is not None and tuple(shift) != tuple(getattr(joint, name).Value if name in joint.PropertiesList else 0.0
                                               for name in ("FrameX", "FrameY")):
        _check_shift(joint, kind, shift, frame)
    twist_from = limits.get("twist_from")
    if twist_from is not None and twist_from != getattr(joint, "TwistFrom", objects.POSE_WHEN_MADE):
        _check_twist(joint, kind, twist_from)
    offset = limits.pop("mesh_offset", None)
    if offset is not None:
        if kind not in objects.COUPLINGS:
            raise ValueError("%s: only a coupling (%s) has a mesh offset" % (joint.Label, ", ".join(objects.COUPLINGS)))
        # The engine's phase it makes, checked at the model's door before anything changes (a
        # phase still to be made: the offset alone, which the door checks the same way).
        known = getattr(joint, "PhaseKnown", False) and limits.get("phase") is None
        probe = objects.phase_value(joint) - objects.mesh_offset(joint) if known else 0.0
        _check_phase(joint, kind, probe + offset)
    with _step(joint.Document, "Edit joint", undo_step):
        retyped = joint_type is not None and joint_type != joint.JointType
        if joint_type is not None:
            joint.JointType = joint_type
        if replace:
            _place(joint, joint_type, *replace)
        _set_limits(joint, **limits)
        if (retyped or replace) and limits.get("phase") is None:
            objects.remake_phase(joint)  # measured otherwise now: made again at the poses
        if offset is not None:
            asm = next((p for p in joint.InList if objects.is_assembly(p)), None)
            if asm is None:
                raise ValueError("%s is in no assembly" % joint.Label)
            _offset_mesh(asm, joint, offset)
    return joint


def solve(asm, undo_step=True):
    """Snap: moves the parts from wherever they are until every joint holds (the seed's automatic
    assembly), grounded parts still. One undo step; a failed solve writes nothing to the
    document (no undo step: its result names the joints still violated, which the GUI marks in
    the view). A joint that lost a part is skipped and named in the message."""
    _assembly(asm)
    if subassembly.out_of_step(asm):  # a placed assembly gained or lost parts since
        with _step(asm.Document, "Update sub-assemblies", undo_step):
            subassembly.bring_in_step(asm)
    adapter = Adapter(asm)
    with adapter.engine_errors():
        r = adapter.model.assemble(tolerance=tolerance(asm), max_iterations=asm.MaxIterations)
    if not r.converged:
        # A failure writes nothing (no Residual, Violated, LastSolve, stored geometry): no undo
        # step, the document not modified, so the first undo takes back what the designer did
        # last. What it says is the result's; the GUI marks its joints in the view (feedback).
        return Result(adapter, r)
    with _step(asm.Document, "Solve assembly", undo_step):
        adapter.write_back(moved=r.iterations > 0)
        adapter.update_joints()
        adapter.mark(r)
        result = Result(adapter, r)
        if _new_news(asm.LastSolve, result.message):
            asm.LastSolve = result.message
        if r.iterations > 0:
            exploded.follow(asm)  # in this undo step: undo takes the view back with the parts
    asm.Document.recompute()
    return result


_HELD = re.compile(r"solved in \d+ iterations?")


def _new_news(last, message):
    """Whether a solve's message is news to the assembly's LastSolve: a Solve that moved nothing
    (ALREADY_HELD) after one that made every joint hold says nothing new, so it leaves LastSolve
    and the document unmodified (opening a solved document and pressing Solve changes nothing)."""
    if message == ALREADY_HELD and (last == ALREADY_HELD or _HELD.fullmatch(last)):
        return False
    return last != message


def _holding(asm, adapter):
    """Refuses to move an assembly whose joints do not hold yet."""
    with adapter.engine_errors():
        first = adapter.model.assemble(tolerance=tolerance(asm))
    if not first.converged:
        raise ValueError("%s does not hold yet: solve it first (%s)" % (asm.Label, adapter.labelled(first.message)))


def _movable(adapter, part):
    """The body that moves when `part` is dragged (a rigid sub-assembly for one of its parts)
    and `part`'s placement in it (None: the part is the body)."""
    if part.Name not in adapter.frames:
        raise ValueError("%s is not a part of %s" % (part.Label, adapter.asm.Label))
    name, local = adapter.body_of(part)
    owner = adapter.part_of(name)
    if getattr(owner, "Grounded", False):
        raise ValueError("%s is grounded: it cannot be moved" % owner.Label)
    return name, local


class _Motion:
    """What the drags share: one undo step from the start to finish(), or cancel() to put every
    part back where it was. A live motion writes the Placements at every step; one that is not
    (live=False: the GUI's drag, which moves what is drawn instead) leaves the document alone
    until finish() writes the last solved poses, once, in an undo step of its own (opened
    there: FreeCAD may close a transaction left open across the GUI's events); its cancel()
    has nothing to undo. Writing a hundred Placements costs FreeCAD far more than the solve
    (each change goes through the document, the undo record, the tree and the observers)."""

    def _begin(self, asm, part, live=True, undo_step=True):
        self.doc = asm.Document
        self.live = live
        self.name = "Drag %s" % part.Label
        self.unwritten = False
        # undo_step=False: part of the transaction a task panel holds open (the Drive panel).
        self.transaction = Transaction(self.doc, self.name) if live and undo_step else None

    def _solved(self):
        """A step converged: its poses go to the document now, or at finish()."""
        if self.live:
            self.adapter.write_back()
        else:
            self.unwritten = True

    def finish(self):
        if self.live:
            exploded.follow(self.asm)  # in the drag's undo step (or the panel's it is part of)
            if self.transaction is not None:
                self.transaction.commit()
        elif self.unwritten:
            with transaction(self.doc, self.name):
                self.adapter.write_back()
                exploded.follow(self.asm)
            self.unwritten = False
        else:
            return
        self.doc.recompute()

    def cancel(self):
        if self.live and self.transaction is not None:
            self.transaction.abort()
            self.doc.recompute()
        self.unwritten = False


class Drag(_Motion):
    """A live drag of one part: `move(placement)` per mouse event, `finish()` on release (or
    `cancel()` to put everything back). The solver's state is built once; a move that cannot be
    made leaves everything where it was. The whole drag is one undo step."""

    def __init__(self, asm, part, undo_step=True):
        self.asm = _assembly(asm)
        self.adapter = Adapter(asm)
        self.part = part
        self.name, self.local = _movable(self.adapter, part)
        _holding(asm, self.adapter)
        with self.adapter.engine_errors():
            self.dragger = self.adapter.model.dragger(self.name, tolerance=tolerance(asm))
        self._begin(asm, part, undo_step=undo_step)
        self.last = None

    def move(self, placement):
        if self.local is not None:  # a part of a rigid sub-assembly: the instance goes where it takes the part
            placement = placement.multiply(self.local.inverse())
        rot = placement.Rotation.toMatrix()
        R = [[rot.A[4 * i + j] for j in range(3)] for i in range(3)]
        with self.adapter.engine_errors():
            r = self.dragger.move_to(position=_vec(placement.Base), rotation=R)
        if r.converged:
            self._solved()
        self.last = r
        return r



class PointDrag(_Motion):
    """A mouse drag: the grabbed point of `part` is pulled towards a moving world point (the
    cursor on the plane through the grab point), the part free to turn as the linkage needs.
    Each event is one pull of the engine's Puller: every joint stays exact while the point is
    drawn toward the cursor; where the linkage cannot put it there (a 1-DOF linkage's point moves
    on a curve, a limit, a dead point) the linkage goes to the nearest pose it allows, from the
    pose it had (continuity: no jump to another branch). One undo step for the whole drag; with
    live=False the Placements are written once, by finish() (the model holds the poses)."""

    # A frame's pull stops after this many iterations when the point is still getting nearer
    # (the cursor well off a stretched linkage's reach): the model then holds the pose reached,
    # joints exact, and the next frame goes on from it (docs/performance.md).
    MAX_ITERATIONS = 20

    def __init__(self, asm, part, grab_world, live=True):
        self.asm = _assembly(asm)
        self.adapter = Adapter(asm)
        self.part = part
        name, local = _movable(self.adapter, part)
        _holding(asm, self.adapter)
        body = part.Placement if local is None else part.Placement.multiply(local.inverse())
        grab_local = geometry.to_local(body, point=grab_world)
        with self.adapter.engine_errors():
            self.puller = self.adapter.model.puller(name, point=_vec(grab_local),
                                                    tolerance=tolerance(asm),
                                                    max_iterations=self.MAX_ITERATIONS)
        self._begin(asm, part, live)
        self.frames = 0
        self.solver_seconds = 0.0
        # The last frame's target and answer when its pull ended where it can go no nearer (at
        # the target, or at the nearest pose): a pull from there toward the same point ends
        # where it starts. `changed` says whether the last move() moved the model.
        self._settled = None
        self.changed = False

    def move(self, target):
        """Pulls the grabbed point towards `target`; returns whether the linkage holds (the
        engine leaves the model as it was otherwise)."""
        import time

        t0 = time.perf_counter()
        to = _vec(target)
        self.frames += 1
        if self._settled is not None and self._settled[0] == to:
            # The cursor has not moved since a pull that settled (a mouse event at the same
            # pixel): nothing to solve, nothing moves. The engine's pull would take a few
            # iterations to find that it is already at the nearest pose (docs/performance.md).
            self.changed = False
            self.solver_seconds += time.perf_counter() - t0
            return self._settled[1]
        with self.adapter.engine_errors():
            r = self.puller.pull_to(to)
        # Stopped short (the nearest pose, or the cap with the point still getting nearer): the
        # engine moved the model only where every joint holds; a result naming a violated joint
        # left it as it was.
        ok = r.converged or (r.status in ("out-of-reach", "iteration-limit") and not r.violated)
        if ok:
            self._solved()
        self.changed = ok
        # At the cap the point was still getting nearer: the next frame goes on, even unmoved.
        self._settled = (to, ok) if r.converged or r.status == "out-of-reach" else None
        self.solver_seconds += time.perf_counter() - t0
        return ok


def at_limits(asm):
    """Each of the assembly's joints standing at one of its limits, in words ("Frame-Wheel is at
    its limit, 28.6479°"): what held a drag that went no further. Only joints with limits are
    measured (from their parts' placements; nothing is solved)."""
    out = []
    for j in joints(asm):
        limits = drive_limits(j) if drivable(j) else None
        if not limits:
            continue
        try:
            value = drive_value(j)
        except ValueError:  # a part deleted: no value to say
            continue
        unit = "°" if drivable(j) == "angle" else " mm"
        for limit in limits:
            if abs(value - limit) <= 1e-6 * max(1.0, abs(limit)):
                out.append("%s is at its limit, %g%s" % (j.Label, limit, unit))
                break
    return out


class DragResult:
    """What a scripted drag did: `converged` when `part` reached the placement asked, every joint
    holding; else `message` says, with the parts' and joints' labels, how far from that placement
    it stopped (the fifth audit read the engine's "'p2_Platform' stays 40 / 10 / 2 from its
    target" for 1 / 4 / 20 steps: its internal name, measured from the first step's target), after
    how many steps, and what holds it (a joint at its limit, else the engine's reason for the next
    step). `iterations` and `max_residual` are the last step's."""

    def __init__(self, adapter, part, asked, r, made, steps):
        self.converged = r.converged
        self.iterations, self.max_residual = r.iterations, r.max_residual
        self.steps, self.steps_made = steps, made
        if r.converged:
            self.message = "%s moved in %s" % (part.Label, plural(steps, "step"))
            return
        gap = (asked.Base - part.Placement.Base).Length
        turn = math.degrees(part.Placement.Rotation.multiply(asked.Rotation.inverted()).Angle)
        held = at_limits(adapter.asm)
        # (The engine's message measures from the step's own target: said as the next step's.)
        self.message = "%s stops %g mm%s from the placement asked, after %d of %s: %s" % (
            part.Label, round(gap, 9), " and %g\u00b0" % round(turn, 6) if turn > 1e-6 else "", made,
            plural(steps, "step"), "; ".join(held) if held else "the next step: " + adapter.advice(r.message))

    def __bool__(self):
        return self.converged

    def __repr__(self):
        return "<dispcon_fc.DragResult %s>" % self.message


def drag(asm, part, placement, steps=None):
    """Moves `part` to `placement` in `steps` steps (the preferences' drag steps when None), the
    rest following; one undo step. Stops at the last step that could be made (the next one left
    everything as it was). Returns a DragResult."""
    steps = steps or objects.preferences()["DragSteps"]
    d = Drag(asm, part)
    start = part.Placement
    r, made = None, 0
    try:
        for k in range(1, steps + 1):
            t = k / steps
            pl = App.Placement(start.Base + (placement.Base - start.Base) * t,
                               start.Rotation.slerp(placement.Rotation, t))
            r = d.move(pl)
            if not r.converged:
                break
            made = k
    except BaseException:
        d.cancel()
        raise
    d.finish()
    return DragResult(d.adapter, part, placement, r, made, steps)


def driven_side(joint):
    """The part a joint turns, with the joint's point and axis in that part's frame: the second
    part, or the first when the second is grounded (whichever order the references were picked)."""
    (part1, _, _), (part2, _, _) = _read_references(joint)  # its axis is its picked element's: lost, refused
    for part, point, axis in ((part2, joint.Point2, joint.Axis2), (part1, joint.Point1, joint.Axis1)):
        if not getattr(part, "Grounded", False):
            return part, point, axis
    raise ValueError("%s joins two grounded parts (%s, %s): nothing to turn" % (joint.Label, part1.Label, part2.Label))


def _turned(start, pivot, axis_world, degrees):
    turn = App.Rotation(axis_world, degrees)
    return App.Placement(pivot + turn.multVec(start.Base - pivot), turn.multiply(start.Rotation))


def drive(asm, joint, angles_deg, callback=None):
    """Turns a revolute (or a part about a joint's axis) through the given angles, in degrees from
    its current pose: the joint's part that can move turns about the joint's axis while the rest
    follows. Returns the angle reached before a lock, or the last one."""
    part, point, axis = driven_side(joint)
    axis_world = part.Placement.Rotation.multVec(axis)
    pivot = part.Placement.multVec(point)
    start = part.Placement
    d = Drag(asm, part)
    reached = 0.0
    try:
        for a in angles_deg:
            r = d.move(_turned(start, pivot, axis_world, a))
            if not r.converged:
                break
            reached = a
            if callback:
                callback(a)
    except BaseException:
        d.cancel()
        raise
    d.finish()
    return reached


# The joints a drive moves, and the unit of their value.
DRIVE_UNITS = {"angle": "deg", "travel": "mm"}


def drivable(joint):
    """"angle" (a Revolute's or Cylindrical's turn), "travel" (a Slider's or PointOnLine's) or
    None: what a drive sets of `joint`."""
    from .studies import joint_kind

    return joint_kind(joint)


def drivable_joints(asm):
    """The joints a drive can move in `asm`, in its order: its own, then those of its flexible
    sub-assemblies at every depth (Walk2.Leg3.Revolute; subassembly.instance_joints)."""
    _assembly(asm)
    return [j for j in joints(asm) + subassembly.instance_joints(asm) if drivable(j)]


def drive_value(joint):
    """The joint's value now, as its limits measure it: part 2's turn relative to part 1 in
    degrees since the joint was made, or its travel along part 1's axis in mm."""
    from .studies import joint_value

    kind = drivable(joint)
    if kind is None:
        raise ValueError("%s is a %s: a drive sets a Revolute's or Cylindrical's turn, or a Slider's or "
                         "PointOnLine's travel" % (joint.Label, joint.JointType))
    driven_side(joint)  # a part deleted: said here, by label
    v = joint_value(joint, joint.Reference1[0].Placement, joint.Reference2[0].Placement)
    return math.degrees(v) if kind == "angle" else v


def drive_limits(joint):
    """The (min, max) the joint's own limits allow its drive value, or None when it has none."""
    kind = drivable(joint)
    if kind == "angle" and joint.HasRotationLimits:
        return joint.RotationMin.Value, joint.RotationMax.Value
    if kind == "travel" and joint.HasTravelLimits:
        return joint.TravelMin.Value, joint.TravelMax.Value
    return None


def drive_to(asm, joint, value, undo_step=True, callback=None):
    """Drives `joint` to `value` (drive_value's measure: degrees or mm): the joint's part that can
    move turns about (or slides along) the joint's axis in small steps while the rest follows,
    callback(value) after each, until the value or the first step that cannot be made (a lock, a
    limit). One undo step (undo_step=False: part of the caller's open one). A value outside the
    joint's limits is refused before anything moves; an error half-way puts every part back.
    Returns (value reached, whether it is `value`)."""
    _assembly(asm)
    kind = drivable(joint)
    start_value = drive_value(joint)
    limits = drive_limits(joint)
    unit = "°" if kind == "angle" else " mm"
    if limits is not None and not limits[0] - 1e-9 <= value <= limits[1] + 1e-9:
        raise ValueError("%s: %g%s is outside its limits %g%s .. %g%s"
                         % (joint.Label, value, unit, limits[0], unit, limits[1], unit))
    part, _, _ = driven_side(joint)
    # Part 2 moves by the change, or part 1 by its opposite when part 2 is grounded.
    sign = 1.0 if part == joint.Reference2[0] else -1.0
    pl1 = joint.Reference1[0].Placement
    axis_world = pl1.Rotation.multVec(joint.Axis1).normalize()
    point = joint.Point2 if sign > 0 else joint.Point1
    pivot = part.Placement.multVec(point)
    start = part.Placement
    delta = value - start_value
    # Steps of 2 degrees, or 1/50 of the part's size: the linkage follows without a jump.
    size = max(shape_of(part).BoundBox.DiagonalLength, 1e-6)
    steps = max(1, int(math.ceil(abs(delta) / (2.0 if kind == "angle" else size / 50))))
    put_back = subassembly.snapshot(asm)
    reached = start_value
    d = Drag(asm, part, undo_step=undo_step)
    try:
        for k in range(1, steps + 1):
            v = start_value + delta * k / steps
            if kind == "angle":
                pl = _turned(start, pivot, axis_world, sign * (v - start_value))
            else:
                pl = App.Placement(start.Base + axis_world * (sign * (v - start_value)), start.Rotation)
            if not d.move(pl).converged:
                break
            reached = v
            if callback:
                callback(v)
    except BaseException:
        d.cancel()
        put_back()
        raise
    d.finish()
    return reached, abs(reached - value) <= 1e-9 * max(1.0, abs(value))


def check(asm):
    """Degrees of freedom, redundant and conflicting joints (as joint objects), limits in contact;
    joints that lost a part are listed under "skipped" and left out."""
    _assembly(asm)
    adapter = Adapter(asm)
    with adapter.engine_errors():
        c = adapter.model.check(tolerance=tolerance(asm))
    message = adapter.advice(c.message)
    if adapter.skipped:
        message += "; " + adapter.skipped_message()
    return {
        "converged": c.converged,
        "dof": c.dof,
        "part_dof": {adapter.part_of(n).Label: v for n, v in c.body_dof.items()},
        "redundant": [adapter.joints[i] for i in c.redundant],
        "conflicting": [adapter.joints[i] for i in c.conflicting],
        "limits_active": [adapter.joints[i] for i in c.limits_active],
        "skipped": [j for j, _ in adapter.skipped],
        "advice": [adapter.advice(a) for a in c.advice],
        "message": message,
    }


def interference(asm, clearance=None):
    """Pairs of parts whose solids overlap at the current pose, with the overlap volume (parts
    that only touch do not count). `clearance`, a studies.Clearance of these parts, carries
    what it learnt from one pose to the next."""
    from .studies import Clearance, local_shapes

    ps = placed_parts(asm)
    if clearance is None:
        clearance = Clearance(local_shapes(ps), [p.Label for p in ps])
    return [(ps[i], ps[k], v) for i, k, v in clearance.at([p.Placement for p in ps])]


def interference_along(asm, joint, angles_deg, ignore=()):
    """Drives `joint` (as `drive` does) through the angles and checks for collisions at each:
    returns [(angle, part_a, part_b, overlap_volume)], then puts every part back where it was.
    Pairs listed in `ignore` (such as parts that touch at their joint by design) are skipped."""
    part, point, axis = driven_side(joint)
    axis_world = part.Placement.Rotation.multVec(axis)
    pivot = part.Placement.multVec(point)
    start = part.Placement
    put_back = subassembly.snapshot(asm)
    skip = {frozenset((a.Name, b.Name)) for a, b in ignore}
    hits = []
    from .studies import Clearance, local_shapes

    ps = placed_parts(asm)
    clearance = Clearance(local_shapes(ps), [p.Label for p in ps])
    d = Drag(asm, part)
    try:
        for a in angles_deg:
            r = d.move(_turned(start, pivot, axis_world, a))
            if not r.converged:
                break
            for pa, pb, volume in interference(asm, clearance):
                if frozenset((pa.Name, pb.Name)) not in skip:
                    hits.append((a, pa, pb, volume))
    finally:
        put_back()
        d.finish()
    return hits


def export_dcl(asm, path):
    """Writes the assembly as a .dcl file for the command line."""
    _assembly(asm)
    adapter = Adapter(asm)
    with adapter.engine_errors():
        adapter.model.save(path)


def import_dcl(asm, path):
    """Places the assembly's parts as a .dcl file says (the file's objects named as export_dcl
    names them): the way back from the command line. Joints are never made or edited: a joint
    frame's offsets (FrameX...FrameRoll) travel in the file only as part 2's moved point and
    turned axes (the format has no statement for them), so they stay as the document holds them."""
    _assembly(asm)
    adapter = Adapter(asm)
    with adapter.engine_errors():
        m = engine.load().load(path)
    with transaction(asm.Document, "Import .dcl placements"):
        for p in adapter.parts:
            name = adapter.names[p.Name]
            if name in m.body_names():
                b = m.body(name)
                q = b.quaternion
                p.Placement = App.Placement(App.Vector(*b.position), App.Rotation(q[1], q[2], q[3], q[0]))
        subassembly.write_back(adapter)  # the sub-assemblies' parts follow
    asm.Document.recompute()
