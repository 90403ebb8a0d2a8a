"""Studies of an assembly as a whole, headless: the check of a document (does it assemble, degrees
of freedom, redundant and conflicting joints, parts that overlap), a sweep of one joint through a
range (lock-ups, limits, every joint's value, interference along the motion) and what a person
looks at afterwards (a plot of the joint values, an animated SVG of the parts moving).

Built on the scripting API of `dispcon_fc.assembly`; every name in a result is a FreeCAD Label.

    import dispcon_fc.studies as st
    doc, asm = st.open_assembly("fourbar.FCStd")
    report = st.check(asm)                             # a dict, the keys of `dispcon check --json`
    study = st.sweep(asm, "Revolute", 0, 2 * math.pi, 360)
    open("motion.svg", "w").write(st.motion_svg(asm, study, view="xy"))
"""
import math
import os
import re
import zipfile

import FreeCAD as App

from . import assembly as da
from .adapter import LostReference, plural, references


class StudyError(ValueError):
    """Bad input: a file that cannot be read, a document without an assembly, an unknown joint.
    The message names the file and the object, `FILE: error: ...`."""


# ---------------------------------------------------------------------------------------------
# Opening a document


def open_assembly(path, label=None):
    """Opens `path` and returns (document, assembly). Refuses, with StudyError naming the file and
    the object, a missing file, a file that is not a FreeCAD document (or a damaged one), a
    document without an assembly (or several, when no label is given), and parts or joints whose
    shapes or references are gone (a linked file that was moved away)."""
    if not os.path.isfile(path):
        raise StudyError("%s: error: no such file" % path)
    try:
        with zipfile.ZipFile(path) as z:
            bad = z.testzip()
            if bad is not None:
                raise StudyError("%s: error: damaged FreeCAD document (%s is corrupt)" % (path, bad))
            if "Document.xml" not in z.namelist():
                raise StudyError("%s: error: not a FreeCAD document (no Document.xml inside)" % path)
    except (zipfile.BadZipFile, OSError, EOFError, ValueError) as e:
        if isinstance(e, StudyError):
            raise
        raise StudyError("%s: error: not a FreeCAD document, or a damaged one (%s)" % (path, e))
    try:
        doc = App.openDocument(os.path.abspath(path))
    except Exception as e:  # FreeCAD raises plain exceptions for unreadable documents
        raise StudyError("%s: error: FreeCAD cannot open it (%s)" % (path, e))
    # Without a label, the top assemblies: not those placed inside another (sub-assemblies).
    found = da.top_assemblies(doc)
    if label is not None:
        found = [o for o in doc.Objects if da.is_assembly(o) and o.Label == label]
        if not found:
            raise StudyError("%s: error: no assembly labelled '%s' (assemblies: %s)"
                             % (path, label, _labels(o for o in doc.Objects if da.is_assembly(o))))
    if not found:
        raise StudyError("%s: error: not a dispcon assembly: no Dispcon assembly object in the "
                         "document (objects: %s)" % (path, _labels(doc.Objects[:8]) or "none"))
    if len(found) > 1:
        raise StudyError("%s: error: %d assemblies (%s): name one with --assembly"
                         % (path, len(found), _labels(found)))
    asm = found[0]
    _check_references(path, asm)
    return doc, asm


def _labels(objs):
    return ", ".join("'%s'" % o.Label for o in objs)


def _check_references(path, asm):
    for sub in da.sub_assemblies(asm):
        if sub.Assembly is None or not da.is_assembly(sub.Assembly):
            raise StudyError("%s: error: sub-assembly '%s' places an assembly that is gone (its file was moved?)"
                             % (path, sub.Label))
    for p in da.placed_parts(asm):
        if p.TypeId == "App::Link" and p.getLinkedObject(True) in (None, p):
            raise StudyError("%s: error: part '%s' links an object that is gone (%s)"
                             % (path, p.Label, _link_target(p)))
        shape = da.shape_of(p)
        if shape is None or shape.isNull() or not shape.Solids:
            what = (" (its link %s is missing)" % _link_target(p)) if p.TypeId == "App::Link" else ""
            raise StudyError("%s: error: part '%s' has no solid shape%s" % (path, p.Label, what))
    parts = set(p.Name for p in da.placed_parts(asm))
    for j in da.joints(asm):
        try:
            references(j, parts, features=False)  # the workbench's reader, in its words
        except LostReference as e:
            raise StudyError("%s: error: %s" % (path, e)) from None


def _link_target(p):
    """Where a link points, read from the document's own file: FreeCAD forgets it when the
    linked file is missing."""
    try:
        with zipfile.ZipFile(p.Document.FileName) as z:
            xml = z.read("Document.xml").decode("utf-8", "replace")
        start = xml.index('<Object name="%s"' % p.Name, xml.index("<ObjectData"))
        m = re.search(r'name="LinkedObject"[^>]*>\s*<XLink file="([^"]*)"[^>]*name="([^"]*)"', xml[start:])
        if m:
            return "%s#%s" % (m.group(1), m.group(2))
    except (OSError, ValueError, KeyError, zipfile.BadZipFile):
        pass
    return "an object of another file"


# ---------------------------------------------------------------------------------------------
# The model of an assembly, named as the user knows it


class Study:
    """An assembly's dispcon model (the document is never changed by a study), its parts'
    shapes in their own frames (computed once), and the translation from the engine's internal
    names to FreeCAD Labels."""

    def __init__(self, asm, tolerance=None, max_iterations=None):
        self.asm = asm
        self.adapter = da.Adapter(asm)
        self.model = self.adapter.model
        self.parts = self.adapter.parts
        self.joints = self.adapter.joints
        self.tolerance = tolerance or asm.Tolerance
        self.max_iterations = max_iterations or asm.MaxIterations
        self._local = None

    def options(self):
        return dict(tolerance=self.tolerance, max_iterations=self.max_iterations)

    def joint(self, label):
        for j in self.joints:
            if j.Label == label:
                return j
        raise StudyError("%s: error: no joint labelled '%s' in '%s' (joints: %s)"
                         % (self.asm.Document.FileName or self.asm.Document.Name, label,
                            self.asm.Label, _labels(self.joints)))

    def part(self, label):
        for p in self.parts:
            if p.Label == label:
                return p
        raise StudyError("%s: error: no part labelled '%s' in '%s' (parts: %s)"
                         % (self.asm.Document.FileName or self.asm.Document.Name, label,
                            self.asm.Label, _labels(self.parts)))

    def placements(self):
        """Every part's placement in the model now (not in the document)."""
        return [self.adapter.placement_of(p) for p in self.parts]

    def placement_in(self, placements, obj):
        """`obj`'s placement among `placements` (the parts', in order): a part of a rigid
        sub-assembly is where its instance's placement puts it."""
        body, local = self.adapter.body_of(obj)
        pl = placements[self.parts.index(self.adapter.part_of(body))]
        return pl if local is None else pl.multiply(local)

    def in_body(self, obj, point):
        """A point in `obj`'s frame, in its body's (a part of a rigid sub-assembly: its instance's)."""
        local = self.adapter.body_of(obj)[1]
        return point if local is None else tuple(local.multVec(App.Vector(*point)))

    def local_shapes(self):
        if self._local is None:
            self._local = local_shapes(self.parts)
        return self._local

    def rename(self, text):
        """An engine message with the internal body names and joint numbers as Labels."""
        def joint(m):
            return "joint '%s'" % self.joints[int(m.group(1))].Label

        text = re.sub(r"joint #?(\d+)(?: \(line \d+\))?(?: [^\s:]+ / [^\s:]+)?", joint, text)
        return self.adapter.labelled(text)

    def bodies_json(self, dof=None):
        out = {}
        for p, pl in zip(self.parts, self.placements()):
            m = pl.Rotation.toMatrix()
            q = pl.Rotation.Q  # x, y, z, w
            out[p.Label] = {"position": [pl.Base.x, pl.Base.y, pl.Base.z],
                            "rotation": [[m.A[4 * i + k] for k in range(3)] for i in range(3)],
                            "quaternion": [q[3], q[0], q[1], q[2]]}
            if dof is not None:
                out[p.Label]["dof"] = dof.get(self.adapter.names[p.Name], 0)
        return out

    def constraints_json(self, reports):
        out = []
        for c, j in zip(reports, self.joints):
            out.append({"index": c.index, "label": j.Label, "line": 0,
                        "object1": j.Reference1[0].Label, "object2": j.Reference2[0].Label,
                        "residual": c.residual, "satisfied": c.satisfied, "active": c.active,
                        "at_limit": c.at_limit})
        return out

    def solve_json(self, r):
        return {"converged": r.converged, "iterations": r.iterations, "max_residual": r.max_residual,
                "message": self.rename(r.message), "bodies": self.bodies_json(),
                "constraints": self.constraints_json(r.constraints)}


# ---------------------------------------------------------------------------------------------
# Interference


def local_shapes(parts):
    """Every part's shape in its own frame, so a pose is a placement away (no copy of the
    geometry per pose)."""
    out = []
    for p in parts:
        s = da.shape_of(p).copy()
        s.Placement = p.Placement.inverse().multiply(s.Placement)
        out.append(s)
    return out


class Clearance:
    """Which parts overlap at a pose, and by how much. Boxes first: each part's world box, then
    each part's own box carried into the other's frame (a tight test for long, turned links);
    OpenCascade's common() only for pairs whose boxes truly overlap. A pair whose relative
    placement did not change since the last time (parts that move together, or never move) keeps
    its last answer."""

    def __init__(self, shapes, labels, relative=1e-6):
        self.shapes = shapes
        self.labels = labels
        self.boxes = [s.BoundBox for s in shapes]
        self.volumes = [s.Volume for s in shapes]
        size = max((b.DiagonalLength for b in self.boxes), default=1.0) or 1.0
        # Boxes that only touch (parts stacked face to face) do not overlap.
        self.gap = 1e-7 * size
        self.relative = relative
        self.cache = {}
        self.common_calls = 0

    @staticmethod
    def _corners(box):
        return [App.Vector(x, y, z) for x in (box.XMin, box.XMax) for y in (box.YMin, box.YMax)
                for z in (box.ZMin, box.ZMax)]

    def _box_in(self, box, placement):
        pts = [placement.multVec(c) for c in self._corners(box)]
        return (min(p.x for p in pts), max(p.x for p in pts), min(p.y for p in pts),
                max(p.y for p in pts), min(p.z for p in pts), max(p.z for p in pts))

    def _overlap(self, a, b):
        g = self.gap
        return (a[0] < b[1] - g and b[0] < a[1] - g and a[2] < b[3] - g and b[2] < a[3] - g
                and a[4] < b[5] - g and b[4] < a[5] - g)

    @staticmethod
    def _own(box):
        return (box.XMin, box.XMax, box.YMin, box.YMax, box.ZMin, box.ZMax)

    @staticmethod
    def _key(pl):
        q = pl.Rotation.Q
        if q[3] < 0:
            q = tuple(-x for x in q)
        return tuple(round(v, 9) for v in (pl.Base.x, pl.Base.y, pl.Base.z) + tuple(q))

    def at(self, placements):
        """[(i, k, volume)] for the pairs of parts that overlap at these placements (one per
        part, in order)."""
        world = [self._box_in(b, pl) for b, pl in zip(self.boxes, placements)]
        hits = []
        n = len(placements)
        for i in range(n):
            for k in range(i + 1, n):
                if not self._overlap(world[i], world[k]):
                    continue
                rel = placements[i].inverse().multiply(placements[k])
                key = self._key(rel)
                cached = self.cache.get((i, k))
                if cached is not None and cached[0] == key:
                    volume = cached[1]
                else:
                    volume = self._volume(i, k, rel)
                    self.cache[(i, k)] = (key, volume)
                if volume > self.relative * min(self.volumes[i], self.volumes[k]):
                    hits.append((i, k, volume))
        return hits

    def _volume(self, i, k, rel):
        # Part k's box in part i's frame, and the other way round.
        if not self._overlap(self._own(self.boxes[i]), self._box_in(self.boxes[k], rel)):
            return 0.0
        if not self._overlap(self._own(self.boxes[k]), self._box_in(self.boxes[i], rel.inverse())):
            return 0.0
        other = self.shapes[k].copy()
        other.Placement = rel.multiply(other.Placement)
        self.common_calls += 1
        common = self.shapes[i].common(other)
        return common.Volume if not common.isNull() else 0.0

    def report(self, placements):
        return [{"parts": [self.labels[i], self.labels[k]], "volume": v}
                for i, k, v in self.at(placements)]


def clearance_of(study):
    return Clearance(study.local_shapes(), [p.Label for p in study.parts])


# ---------------------------------------------------------------------------------------------
# check


def check(asm, interference=True, **options):
    """`dispcon check` on an assembly: the keys of the .dcl command's JSON, joints and parts
    named by Label, and "interference" (parts overlapping at the assembled pose, with volumes).
    The document is not changed."""
    s = Study(asm, **options)
    c = s.model.check(**s.options())
    assembled = s.model.assemble(**s.options())
    out = s.solve_json(c.solve)
    out["bodies"] = s.bodies_json(dof=c.body_dof)
    labels = lambda ids: [s.joints[i].Label for i in ids]  # noqa: E731
    out.update({"assembly": asm.Label, "dof": c.dof, "redundant": labels(c.redundant),
                "conflicting": labels(c.conflicting), "limits_active": labels(c.limits_active),
                "advice": [s.rename(a) for a in c.advice], "diagnosis": s.rename(c.message)})
    out["interference"] = (clearance_of(s).report(s.placements())
                           if assembled.converged and interference else [])
    return out


def check_exit(report):
    """0 when the assembly holds, no joint conflicts and no parts overlap; else 3."""
    ok = report["converged"] and not report["conflicting"] and not report["interference"]
    return 0 if ok else 3


# ---------------------------------------------------------------------------------------------
# Joint values and the driver of a sweep


def _world(pl, v):
    return pl.Rotation.multVec(v)


def joint_kind(j):
    """What a sweep drives and a sample reports of a joint: "angle" (its turn, radians),
    "travel" (along its axis, length units) or None."""
    if j.JointType in ("Revolute", "Cylindrical"):
        return "angle"
    if j.JointType in ("Slider", "PointOnLine"):
        return "travel"
    return None


def joint_value(j, pl1, pl2):
    """The turn of part 2 relative to part 1 about the joint's axis (counter-clockwise about axis
    1), counted as the joint's turn limits are: from the picked frames' x's lined up, or from the
    pose when made (TwistFrom); or part 2's travel along axis 1."""
    kind = joint_kind(j)
    a1 = _world(pl1, j.Axis1)
    if kind == "angle":
        b1, b2 = _world(pl1, j.Perp1), _world(pl2, j.Perp2)
        return math.atan2(b1.cross(b2).dot(a1), b1.dot(b2))
    if kind == "travel":
        return (pl2.multVec(j.Point2) - pl1.multVec(j.Point1)).dot(a1)
    return None


class _Driver:
    """Holds one joint at a value: a point-to-point joint between its two parts whose point on
    part 1 is moved to where part 2's point is when the joint has that value (at the joint's
    radius for a turn, along its axis for a travel). The joint's own equations hold the rest."""

    def __init__(self, study, joint):
        self.study, self.j = study, joint
        self.kind = joint_kind(joint)
        if self.kind is None:
            raise StudyError("%s: error: joint '%s' is a %s: sweep drives a Revolute, Cylindrical, "
                             "Slider or PointOnLine joint"
                             % (study.asm.Document.FileName, joint.Label, joint.JointType))
        o1, o2 = self.ends = joint.Reference1[0], joint.Reference2[0]
        box = da.shape_of(o2).BoundBox
        self.radius = max(0.5 * box.DiagonalLength, 1e-6)
        # The hinge's points are in the parts' frames: in their bodies' (a rigid sub-assembly's).
        self.index = study.model.add_joint(study.adapter.body_of(o2)[0], object1=study.adapter.body_of(o1)[0],
                                           hinge=(study.in_body(o1, self._p1(self.value())),
                                                  study.in_body(o2, self._p2())),
                                           label="sweep driver")

    def value(self, placements=None):
        pls = placements or self.study.placements()
        return joint_value(self.j, self.study.placement_in(pls, self.ends[0]), self.study.placement_in(pls, self.ends[1]))

    def _p1(self, v):
        j = self.j
        # The joint's point on part 1 is its Offset along the axis from Point1 (joint_kwargs).
        base = j.Point1 + App.Vector(j.Axis1).normalize() * (j.Offset.Value if "Offset" in j.PropertiesList else 0.0)
        if self.kind == "angle":
            a, b = App.Vector(j.Axis1).normalize(), App.Vector(j.Perp1).normalize()
            c = a.cross(b)
            p = base + (b * math.cos(v) + c * math.sin(v)) * self.radius
        else:
            p = base + App.Vector(j.Axis1).normalize() * v
        return (p.x, p.y, p.z)

    def _p2(self):
        j = self.j
        p = j.Point2 + App.Vector(j.Perp2).normalize() * self.radius if self.kind == "angle" else j.Point2
        return (p.x, p.y, p.z)

    def set(self, v):
        self.study.model.set_hinge(self.index, p1=self.study.in_body(self.ends[0], self._p1(v)))


# ---------------------------------------------------------------------------------------------
# sweep


class Sample:
    """One pose of a sweep. Turns are unwrapped against the previous sample's (`previous`), so a
    joint turning past half a turn reads on continuously instead of jumping by 2 pi."""

    def __init__(self, value, result, study, placements, n_joints, previous=None):
        self.value = value
        self.converged = result.converged
        self.max_residual = result.max_residual
        self.limits_active = [c.index for c in result.constraints if c.at_limit and c.index < n_joints]
        self.placements = placements
        self.joint_values = [joint_value(j, study.placement_in(placements, j.Reference1[0]),
                                         study.placement_in(placements, j.Reference2[0]))
                             for j in study.joints]
        if previous is not None:
            for n, j in enumerate(study.joints):
                v, before = self.joint_values[n], previous.joint_values[n]
                if joint_kind(j) == "angle" and v is not None and before is not None:
                    self.joint_values[n] = before + math.remainder(v - before, 2 * math.pi)
        self.colliding = []  # [(i, k, volume)]


class SweepStudy:
    """What a sweep found: samples (value, poses, every joint's value, limits, collisions), the
    lock-up if any, and the interference of every pair along the motion."""

    def __init__(self, study, joint, kind):
        self.study, self.joint, self.kind = study, joint, kind
        self.samples = []
        self.locked = False
        self.lock_value = None
        self.start = self.stop = None  # the range swept, once known (radians or length units)
        self.message = ""
        self.clearance = None

    def interference(self):
        """Per pair that collides: the first and last driven value, the worst overlap and where."""
        pairs = {}
        for s in self.samples:
            for i, k, v in s.colliding:
                p = pairs.setdefault((i, k), {"first": s.value, "last": s.value, "worst_volume": v,
                                              "worst_value": s.value})
                p["last"] = s.value
                if v > p["worst_volume"]:
                    p["worst_volume"], p["worst_value"] = v, s.value
        labels = [p.Label for p in self.study.parts]
        return [dict(parts=[labels[i], labels[k]], **v) for (i, k), v in sorted(pairs.items())]

    def limits_reached(self):
        seen = []
        for s in self.samples:
            for i in s.limits_active:
                if i not in seen:
                    seen.append(i)
        return [self.study.joints[i].Label for i in seen]

    def to_json(self):
        js = self.study.joints
        units = {"angle": "rad", "travel": "length"}
        return {
            "converged": not self.locked and all(s.converged for s in self.samples),
            "locked": self.locked, "lock_value": self.lock_value, "message": self.message,
            "joint": self.joint.Label, "kind": self.kind,
            "joints": [{"label": j.Label, "type": j.JointType, "unit": units.get(joint_kind(j))}
                       for j in js],
            "limits_reached": self.limits_reached(),
            "interference": self.interference() if self.clearance else [],
            # How much the interference test cost: OpenCascade booleans run, of the pairs tested.
            "boolean_tests": self.clearance.common_calls if self.clearance else 0,
            "samples": [{"value": s.value, "converged": s.converged, "max_residual": s.max_residual,
                         "limits_active": [js[i].Label for i in s.limits_active],
                         "joint_values": s.joint_values,
                         "colliding": [[self.study.parts[i].Label, self.study.parts[k].Label]
                                       for i, k, _ in s.colliding]}
                        for s in self.samples],
        }

    def exit_code(self):
        return 3 if self.locked or (self.clearance and self.interference()) else 0

    def csv(self):
        labels = [j.Label for j in self.study.joints]
        quote = lambda t: '"%s"' % t.replace('"', '""') if re.search(r'[,"\n]', t) else t  # noqa: E731
        rows = ["value,converged,max_residual,colliding," + ",".join(quote(t) for t in labels)]
        for s in self.samples:
            vals = ["" if v is None else repr(v) for v in s.joint_values]
            rows.append(",".join([repr(s.value), "1" if s.converged else "0", repr(s.max_residual),
                                  str(len(s.colliding))] + vals))
        return "\n".join(rows) + "\n"


def sweep(asm, joint_label, start=None, stop=None, steps=360, interference=True, **options):
    """Drives the joint labelled `joint_label` (a turn in radians or a travel in length units,
    the joint's own value as `joint_value` measures it) from `start` to `stop` in `steps` equal
    steps, each from the last pose (continuity), the rest following. Where a step cannot be
    made, bisects to 1e-9 for the lock-up and stops. Default range: a full turn from the
    assembled value; a slider's travel limits. The document is not changed."""
    s = Study(asm, **options)
    j = s.joint(joint_label)
    kind = joint_kind(j)
    out = SweepStudy(s, j, kind)
    first = s.model.assemble(**s.options())
    if not first.converged:
        out.locked, out.message = True, "does not assemble: " + s.rename(first.message)
        return out
    driver = _Driver(s, j)
    v0 = driver.value()
    if start is None:
        start = v0 if kind == "angle" else (j.TravelMin.Value if j.HasTravelLimits else None)
    if stop is None:
        stop = start + 2 * math.pi if kind == "angle" else (j.TravelMax.Value if j.HasTravelLimits else None)
    if start is None or stop is None:
        raise StudyError("%s: error: joint '%s' has no travel limits: give --from and --to"
                         % (asm.Document.FileName, j.Label))
    if kind == "angle":
        # Turn to the start the short way round from where the joint is.
        start = v0 + math.remainder(start - v0, 2 * math.pi) if stop - start <= 2 * math.pi + 1e-12 else start
    out.start, out.stop = start, stop
    session = s.model.session(**s.options())
    n = len(s.joints)
    out.clearance = clearance_of(s) if interference else None

    def drive(v):
        driver.set(v)
        return session.solve()

    # Reach the start by small steps from the assembled value (continuity), unrecorded.
    approach = max(1, int(abs(start - v0) / (math.pi / 90 if kind == "angle" else driver.radius / 50)))
    for k in range(1, approach + 1):
        r = drive(v0 + (start - v0) * k / approach)
        if not r.converged:
            out.locked, out.lock_value = True, v0 + (start - v0) * (k - 1) / approach
            out.message = "cannot reach the start %.9g: locks at %.9g" % (start, out.lock_value)
            return out
    last_good = start
    for k in range(steps + 1):
        v = start + (stop - start) * k / steps
        r = drive(v)
        if not r.converged:
            lo, hi = last_good, v
            for _ in range(60):
                if abs(hi - lo) <= 1e-9:
                    break
                mid = 0.5 * (lo + hi)
                if drive(mid).converged:
                    lo = mid
                else:
                    hi = mid
            out.locked, out.lock_value = True, lo
            sample = Sample(v, r, s, s.placements(), n, out.samples[-1] if out.samples else None)
            out.samples.append(sample)
            break
        last_good = v
        sample = Sample(v, r, s, s.placements(), n, out.samples[-1] if out.samples else None)
        if k == 0 and kind == "angle":
            # The driven joint reads the driven value from the start (the start may lie beyond
            # half a turn).
            d = s.joints.index(j)
            sample.joint_values[d] = v + math.remainder(sample.joint_values[d] - v, 2 * math.pi)
        if out.clearance:
            sample.colliding = out.clearance.at(sample.placements)
        out.samples.append(sample)
    unit = " rad" if kind == "angle" else ""
    if out.locked:
        deg = " (%.6g deg)" % math.degrees(out.lock_value) if kind == "angle" else ""
        out.message = "'%s' locks at %.9g%s%s: no position reachable by continuity beyond it" % (
            j.Label, out.lock_value, unit, deg)
    else:
        out.message = "'%s' moves freely from %.9g to %.9g%s" % (j.Label, start, stop, unit)
    hits = out.interference() if out.clearance else []
    if hits:
        out.message += "; %s of parts %s: %s" % (plural(len(hits), "pair"), "collides" if len(hits) == 1 else "collide", ", ".join(
            "'%s'/'%s' from %.6g to %.6g" % (h["parts"][0], h["parts"][1], h["first"], h["last"])
            for h in hits))
    return out


# ---------------------------------------------------------------------------------------------
# drag and assemble (on the model, then written to the document)


def assemble(asm, **options):
    """The automatic assembly; the document's placements change only when it converged.
    Returns the JSON of `dispcon assemble`."""
    s = Study(asm, **options)
    r = s.model.assemble(**s.options())
    out = s.solve_json(r)
    out.update({"status": r.status, "seed_iterations": r.seed_iterations,
                "newton_iterations": r.newton_iterations})
    if r.converged:
        s.adapter.write_back()
        asm.Document.recompute()
    return out


class DragStudy:
    def __init__(self, study, part):
        self.study, self.part = study, part
        self.steps = []       # solve results
        self.placements = []  # per step, every part's placement
        self.converged = True
        self.failed_step = -1


def drag(asm, part_label, position, rotation=None, steps=50, **options):
    """`dispcon drag` on an assembly: assembles, then moves the part labelled `part_label` in
    `steps` equal steps to `position` (and `rotation`, a rotation vector in radians, kept when
    None) while the rest follows. Stops at the first step that fails. The document's placements
    change only when every step was made. Returns (json, DragStudy)."""
    s = Study(asm, **options)
    part = s.part(part_label)
    if getattr(part, "Grounded", False):
        raise StudyError("%s: error: part '%s' is grounded: it cannot be dragged"
                         % (asm.Document.FileName, part.Label))
    first = s.model.assemble(**s.options())
    study = DragStudy(s, part)
    if not first.converged:
        out = s.solve_json(first)
        out.update({"steps": [], "failed_step": 0,
                    "message": "does not assemble: " + s.rename(first.message)})
        study.converged, study.failed_step = False, 0
        return out, study
    name = s.adapter.names[part.Name]
    start = s.adapter.placement_of(part)
    if rotation is not None:
        axis = App.Vector(*rotation)
        angle = axis.Length
        target_rot = App.Rotation(axis if angle > 0 else App.Vector(0, 0, 1), math.degrees(angle))
    else:
        target_rot = start.Rotation
    target = App.Vector(*position)
    dragger = s.model.dragger(name, **s.options())
    total, worst, last = first.iterations, first.max_residual, first
    study.placements.append(s.placements())
    for k in range(1, steps + 1):
        t = k / steps
        rot = start.Rotation.slerp(target_rot, t)
        m = rot.toMatrix()
        r = dragger.move_to(position=tuple(start.Base + (target - start.Base) * t),
                            rotation=[[m.A[4 * i + c] for c in range(3)] for i in range(3)])
        study.steps.append(r)
        total += r.iterations
        worst = max(worst, r.max_residual)
        last = r
        if not r.converged:
            study.converged, study.failed_step = False, k
            break
        study.placements.append(s.placements())
    out = s.solve_json(last)
    out["iterations"], out["max_residual"] = total, worst
    out["steps"] = [{"iterations": r.iterations, "max_residual": r.max_residual,
                     "converged": r.converged} for r in study.steps]
    out["failed_step"] = study.failed_step
    if study.converged:
        out["message"] = "dragged '%s' in %s, %s" % (part.Label, plural(steps, "step"), plural(total, "iteration"))
        s.adapter.write_back()
        asm.Document.recompute()
    else:
        out["message"] = "step %d of %d cannot be made: %s" % (
            study.failed_step, steps, s.rename(last.message))
    return out, study


def drag_csv(study):
    rows = ["step,body,px,py,pz,qw,qx,qy,qz"]
    for k, pls in enumerate(study.placements):
        for p, pl in zip(study.study.parts, pls):
            q = pl.Rotation.Q
            rows.append(",".join([str(k), p.Label] + [repr(v) for v in (pl.Base.x, pl.Base.y, pl.Base.z,
                                                                          q[3], q[0], q[1], q[2])]))
    return "\n".join(rows) + "\n"


# ---------------------------------------------------------------------------------------------
# For the workbench's Drive and Check commands (their panels call these)


def export_drive_study(asm, joint, svg_path=None, plot_path=None, csv_path=None, start=None,
                       stop=None, steps=360, view="iso"):
    """The Drive command's exports: sweeps `joint` (a joint object or its Label) as `sweep` does,
    and writes the animated SVG, the plot and the CSV that are asked for. Returns the
    SweepStudy (its .message, .interference(), .to_json()); the document is not changed."""
    from . import motion_svg

    label = joint if isinstance(joint, str) else joint.Label
    study = sweep(asm, label, start, stop, steps)
    for path, text in ((svg_path, lambda: motion_svg.sweep_svg(study, view)),
                       (plot_path, lambda: motion_svg.sweep_plot_svg(study)),
                       (csv_path, study.csv)):
        if path:
            with open(path, "w") as f:
                f.write(text())
    return study


def export_check_report(asm, json_path):
    """The Check command's export: the report of `check` as the command line's JSON."""
    import json

    report = check(asm)
    with open(json_path, "w") as f:
        json.dump(report, f, indent=2, default=lambda x: None)
    return report
