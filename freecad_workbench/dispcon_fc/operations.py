"""The operations on an assembly: what a command or a script does to the document. Each is one
undo step (one transaction); each validates its input first, so a refused operation leaves the
document as it was."""
import os

import FreeCAD as App

from . import engine, geometry, objects
from .adapter import Adapter, Result, _vec
from .objects import joints, parts, shape_of


def create_assembly(doc, name="Assembly"):
    """An empty assembly in `doc`."""
    doc.openTransaction("Create assembly")
    obj = objects.new_assembly(doc, name)
    doc.commitTransaction()
    return obj


def add_part(asm, obj, grounded=False):
    """Adds an existing object of the document (anything with a Shape) to the assembly."""
    doc = asm.Document
    doc.openTransaction("Add part")
    objects.part_properties(obj)
    obj.Grounded = grounded
    asm.addObject(obj)
    doc.commitTransaction()
    return obj


def import_part(asm, path, name=None, grounded=False):
    """Imports a STEP, IGES or BREP file as a part of the assembly."""
    import Part

    ext = os.path.splitext(path)[1].lower()
    if ext not in (".step", ".stp", ".iges", ".igs", ".brep", ".brp"):
        raise ValueError("%s: expected a STEP, IGES or BREP file" % path)
    if not os.path.isfile(path):
        raise ValueError("%s: no such file" % path)
    shape = Part.Shape()
    shape.read(path)
    name = name or os.path.splitext(os.path.basename(path))[0]
    return _new_part(asm, "Import part", "Part::Feature", name, grounded, Shape=shape)


def link_part(asm, path, object_name, grounded=False):
    """Links an object of another .FCStd file (App::Link) as a part. FreeCAD links across
    documents only from a saved document: save the assembly's document first."""
    if not asm.Document.FileName:
        raise ValueError("save %s before linking parts from other files" % asm.Document.Label)
    other = App.openDocument(path)
    source = other.getObject(object_name)
    if source is None:
        raise ValueError("%s has no object %s" % (path, object_name))
    return _new_part(asm, "Link part", "App::Link", object_name, grounded, LinkedObject=source)


def _new_part(asm, action, type_id, name, grounded, **values):
    """A new object of the document made a part of the assembly, in one undo step."""
    doc = asm.Document
    doc.openTransaction(action)
    try:
        obj = doc.addObject(type_id, name)
        for key, value in values.items():
            setattr(obj, key, value)
        objects.part_properties(obj)
        obj.Grounded = grounded
        asm.addObject(obj)
    except Exception:
        # A command that fails leaves the document as it was.
        doc.abortTransaction()
        raise
    doc.commitTransaction()
    return obj


def _perpendicular(v):
    other = App.Vector(1, 0, 0) if abs(v.x) < 0.9 else App.Vector(0, 1, 0)
    return v.cross(other).normalize()


def _sampled_curve(obj, sub, count=64):
    edge = shape_of(obj).getElement(sub)
    return [geometry.to_local(obj.Placement, point=p) for p in edge.discretize(count)]


def add_joint(asm, joint_type, ref1, ref2, **limits):
    """A joint between two parts from geometry references in FreeCAD's form, (obj, "Edge3").
    Part 1 carries the guide (the slider's line, the plane, the curve). Limits: rotation=(min, max)
    in degrees, travel=(min, max) in length units, cone=degrees, angle=(min, max) degrees, move=mu."""
    if joint_type not in objects.JOINT_TYPES:
        raise ValueError("unknown joint type %r (expected one of %s)" % (joint_type, ", ".join(objects.JOINT_TYPES)))
    (o1, s1), (o2, s2) = ref1, ref2
    if o1 == o2:
        raise ValueError("a joint needs two different parts")
    for o in (o1, o2):
        if o not in asm.Group:
            raise ValueError("%s is not a part of %s" % (o.Label, asm.Label))
    f1, f2 = geometry.feature(o1, s1), geometry.feature(o2, s2)
    doc = asm.Document
    doc.openTransaction("Add joint")
    try:
        j = objects.new_joint(doc, joint_type)
        j.JointType = joint_type
        j.Reference1 = (o1, [s1])
        j.Reference2 = (o2, [s2])
        j.Point1 = geometry.to_local(o1.Placement, point=f1.point)
        j.Axis1 = geometry.to_local(o1.Placement, axis=f1.axis)
        j.Point2 = geometry.to_local(o2.Placement, point=f2.point)
        j.Axis2 = geometry.to_local(o2.Placement, axis=f2.axis)
        # Axes that the user picked pointing apart are taken as the same line.
        if f1.axis.dot(f2.axis) < 0:
            j.Axis2 = j.Axis2 * -1
        # The twist reference: a vector across axis 1, and the same world vector in part 2's frame
        # at the creation pose, so the turn is measured from where the parts were.
        perp_world = _perpendicular(f1.axis)
        j.Perp1 = geometry.to_local(o1.Placement, axis=perp_world)
        j.Perp2 = geometry.to_local(o2.Placement, axis=perp_world)
        if joint_type == "PointOnCurve":
            j.Curve1 = _sampled_curve(o1, s1)
        _set_limits(j, **limits)
        asm.addObject(j)
    except Exception:
        doc.abortTransaction()
        raise
    doc.commitTransaction()
    return j


def _set_limits(j, rotation=None, travel=None, cone=None, angle=None, move=None):
    if rotation is not None:
        j.HasRotationLimits = True
        j.RotationMin, j.RotationMax = rotation
    if travel is not None:
        j.HasTravelLimits = True
        j.TravelMin, j.TravelMax = travel
    if cone is not None:
        j.ConeAngle = cone
    if angle is not None:
        j.AngleMin, j.AngleMax = angle
    if move is not None:
        j.Move = move


def set_limits(joint, **limits):
    """Changes a joint's limits (same keywords as add_joint) in one undo step."""
    doc = joint.Document
    doc.openTransaction("Joint limits")
    _set_limits(joint, **limits)
    doc.commitTransaction()


def solve(asm):
    """Snap: moves the parts from wherever they are until every joint holds (the seed's automatic
    assembly), grounded parts still. One undo step; a failed solve moves nothing and marks the
    joints still violated."""
    adapter = Adapter(asm)
    r = adapter.model.assemble(tolerance=asm.Tolerance, max_iterations=asm.MaxIterations)
    doc = asm.Document
    doc.openTransaction("Solve assembly")
    if r.converged:
        adapter.write_back()
    adapter.mark(r)
    result = Result(adapter, r)
    asm.LastSolve = result.message
    doc.commitTransaction()
    doc.recompute()
    return result


class Drag:
    """A live drag of one part: `move(placement)` per mouse event, `finish()` on release. The
    solver's state is built once; a move that cannot be made leaves everything where it was."""

    def __init__(self, asm, part):
        self.asm = asm
        self.adapter = Adapter(asm)
        self.part = part
        self.name = self.adapter.names[part.Name]
        first = self.adapter.model.assemble(tolerance=asm.Tolerance)
        if not first.converged:
            raise ValueError("the assembly does not hold yet: solve it first (%s)" % first.message)
        self.dragger = self.adapter.model.dragger(self.name, tolerance=asm.Tolerance)
        self.doc = asm.Document
        self.doc.openTransaction("Drag %s" % part.Label)
        self.last = None

    def move(self, placement):
        rot = placement.Rotation.toMatrix()
        R = [[rot.A[4 * i + j] for j in range(3)] for i in range(3)]
        r = self.dragger.move_to(position=_vec(placement.Base), rotation=R)
        if r.converged:
            self.adapter.write_back()
        self.last = r
        return r

    def finish(self):
        self.doc.commitTransaction()
        self.doc.recompute()


class PointDrag:
    """A mouse drag: the grabbed point of `part` is pulled towards a moving world point (the
    cursor on the plane through the grab point), the part free to turn as the linkage needs.
    Each event: first solve with a joint from the cursor to the grabbed point; when the linkage
    cannot put the point there (a 1-DOF linkage's point moves on a curve), keep the compromise
    that pull reached and solve again without it, so the linkage goes as near as it can, joints
    exact, by continuity (no jump to another branch). One undo step for the whole drag."""

    def __init__(self, asm, part, grab_world):
        self.asm = asm
        self.adapter = Adapter(asm)
        self.part = part
        name = self.adapter.names[part.Name]
        model = self.adapter.model
        first = model.assemble(tolerance=asm.Tolerance)
        if not first.converged:
            raise ValueError("the assembly does not hold yet: solve it first (%s)" % first.message)
        grab_local = geometry.to_local(part.Placement, point=grab_world)
        # The mouse joint is active at time 0 only: `pull` sees it, `settle` does not.
        self.handle = model.add_joint(name, hinge=(_vec(grab_world), _vec(grab_local)),
                                      time=(-1.0, 0.5), label="mouse")
        self.pull = model.session(tolerance=asm.Tolerance, max_iterations=60, time=0.0)
        self.settle = model.session(tolerance=asm.Tolerance, max_iterations=500, time=1.0)
        self.doc = asm.Document
        self.doc.openTransaction("Drag %s" % part.Label)
        self.frames = 0
        self.solver_seconds = 0.0

    def move(self, target):
        """Pulls the grabbed point towards `target`; returns whether the linkage holds."""
        import time

        t0 = time.perf_counter()
        model = self.adapter.model
        model.set_hinge(self.handle, p1=_vec(target))
        before = {n: (model.body(n).position.copy(), model.body(n).rotation_vector.copy())
                  for n in model.body_names()}
        ok = self.pull.solve(keep_best=True).converged or self.settle.solve().converged
        if not ok:  # nothing could be made: back to where it was
            for n, (x, r) in before.items():
                model.set_pose(n, position=x, rotation=r)
        else:
            self.adapter.write_back()
        self.frames += 1
        self.solver_seconds += time.perf_counter() - t0
        return ok

    def finish(self):
        self.doc.commitTransaction()
        self.doc.recompute()


def drag(asm, part, placement, steps=20):
    """Moves `part` to `placement` in `steps` steps, the rest following; one undo step. Returns
    the last step's result; stops at the first step that cannot be made."""
    d = Drag(asm, part)
    start = part.Placement
    r = None
    for k in range(1, steps + 1):
        t = k / steps
        pl = App.Placement(start.Base + (placement.Base - start.Base) * t,
                           start.Rotation.slerp(placement.Rotation, t))
        r = d.move(pl)
        if not r.converged:
            break
    d.finish()
    return r


def drive(asm, joint, angles_deg, callback=None):
    """Turns a revolute (or a part about a joint's axis) through the given angles, in degrees from
    its current pose: the second part turns about the joint's axis while the rest follows. Returns
    the angle reached before a lock, or the last one."""
    part = joint.Reference2[0]
    axis_world = part.Placement.Rotation.multVec(joint.Axis2)
    pivot = part.Placement.multVec(joint.Point2)
    start = part.Placement
    d = Drag(asm, part)
    reached = 0.0
    for a in angles_deg:
        turn = App.Rotation(axis_world, a)
        pl = App.Placement(pivot + turn.multVec(start.Base - pivot), turn.multiply(start.Rotation))
        r = d.move(pl)
        if not r.converged:
            break
        reached = a
        if callback:
            callback(a)
    d.finish()
    return reached


def check(asm):
    """Degrees of freedom, redundant and conflicting joints (as joint objects), limits in contact."""
    adapter = Adapter(asm)
    c = adapter.model.check(tolerance=asm.Tolerance)
    return {
        "converged": c.converged,
        "dof": c.dof,
        "part_dof": {adapter.part_of(n).Label: v for n, v in c.body_dof.items()},
        "redundant": [adapter.joints[i] for i in c.redundant],
        "conflicting": [adapter.joints[i] for i in c.conflicting],
        "limits_active": [adapter.joints[i] for i in c.limits_active],
        "advice": list(c.advice),
        "message": c.message,
    }


def interference(asm):
    """Pairs of parts whose solids overlap at the current pose, with the overlap volume."""
    ps = parts(asm)
    out = []
    for i in range(len(ps)):
        for k in range(i + 1, len(ps)):
            a, b = shape_of(ps[i]), shape_of(ps[k])
            if not a.BoundBox.intersect(b.BoundBox):
                continue
            common = a.common(b)
            if common.Volume > 1e-9:
                out.append((ps[i], ps[k], common.Volume))
    return out


def interference_along(asm, joint, angles_deg, ignore=()):
    """Drives `joint` (as `drive` does) through the angles and checks for collisions at each:
    returns [(angle, part_a, part_b, overlap_volume)], then puts every part back where it was.
    Pairs listed in `ignore` (such as parts that touch at their joint by design) are skipped."""
    part = joint.Reference2[0]
    axis_world = part.Placement.Rotation.multVec(joint.Axis2)
    pivot = part.Placement.multVec(joint.Point2)
    start = part.Placement
    before = {p.Name: p.Placement for p in parts(asm)}
    skip = {frozenset((a.Name, b.Name)) for a, b in ignore}
    hits = []
    d = Drag(asm, part)
    try:
        for a in angles_deg:
            turn = App.Rotation(axis_world, a)
            r = d.move(App.Placement(pivot + turn.multVec(start.Base - pivot), turn.multiply(start.Rotation)))
            if not r.converged:
                break
            for pa, pb, volume in interference(asm):
                if frozenset((pa.Name, pb.Name)) not in skip:
                    hits.append((a, pa, pb, volume))
    finally:
        for p in parts(asm):
            p.Placement = before[p.Name]
        d.finish()
    return hits


def export_dcl(asm, path):
    """Writes the assembly as a .dcl file for the command line."""
    adapter = Adapter(asm)
    adapter.model.save(path)


def import_dcl(asm, path):
    """Places the assembly's parts as a .dcl file says (the file's objects named as export_dcl
    names them): the way back from the command line."""
    adapter = Adapter(asm)
    m = engine.load().load(path)
    doc = asm.Document
    doc.openTransaction("Import .dcl placements")
    for p in adapter.parts:
        name = adapter.names[p.Name]
        if name in m.body_names():
            b = m.body(name)
            q = b.quaternion
            p.Placement = App.Placement(App.Vector(*b.position), App.Rotation(q[1], q[2], q[3], q[0]))
    doc.commitTransaction()
    doc.recompute()
