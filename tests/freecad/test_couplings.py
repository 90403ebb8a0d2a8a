"""Distance, Parallel, Perpendicular and the couplings (Gears, Belt, RackPinion, Screw) of the
workbench in real FreeCAD (freecadcmd): joints made from picked vertices, edges and faces of real
parts, solved, and measured again on the parts' geometry against analytic answers. Each class
opens and closes its own documents.

    freecadcmd tests/freecad/test_couplings.py"""
import math
import os
import shutil
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(REPO, "freecad_workbench"))
sys.path.insert(0, os.path.join(REPO, "samples", "freecad"))

import FreeCAD as App  # noqa: E402
import Part  # noqa: E402

import couplings  # noqa: E402
import dispcon_fc.assembly as da  # noqa: E402
from dispcon_fc import geometry  # noqa: E402

TOL = 1e-9


def element(obj, test):
    """The name of the first sub-element of `obj`'s shape (faces, edges, vertices in the part's
    own frame) that `test(kind, shape)` accepts: what a designer would click."""
    inverse = obj.Placement.inverse()
    for kind, items in (("Face", obj.Shape.Faces), ("Edge", obj.Shape.Edges), ("Vertex", obj.Shape.Vertexes)):
        for i, e in enumerate(items):
            local = e.copy()
            local.transformShape(inverse.toMatrix())
            if test(kind, local):
                return "%s%d" % (kind, i + 1)
    raise ValueError("%s has no such element" % obj.Label)


def vertex_at(obj, x, y, z):
    return element(obj, lambda k, e: k == "Vertex" and (e.Point - App.Vector(x, y, z)).Length < 1e-9)


def face_normal(obj, n, at):
    """The planar face whose outward normal is `n` and whose plane passes through `at`."""
    n, at = App.Vector(*n), App.Vector(*at)

    def fits(kind, e):
        if kind != "Face" or e.Surface.TypeId != "Part::GeomPlane":
            return False
        u0, u1, v0, v1 = e.ParameterRange
        normal = e.normalAt(0.5 * (u0 + u1), 0.5 * (v0 + v1))
        return (normal - n).Length < 1e-9 and abs((e.CenterOfMass - at).dot(n)) < 1e-9
    return element(obj, fits)


def edge_between(obj, a, b):
    a, b = App.Vector(*a), App.Vector(*b)
    return element(obj, lambda k, e: k == "Edge" and e.Curve.TypeId == "Part::GeomLine" and {
        tuple(round(c, 9) for c in v.Point) for v in e.Vertexes} == {tuple(round(c, 9) for c in p) for p in (a, b)})


def world(obj, sub):
    """The feature of a picked element as the part stands now."""
    return geometry.feature(obj, sub)


def line_distance(point, line_point, direction):
    d = point - line_point
    return (d - direction * d.dot(direction)).Length


class Parts(unittest.TestCase):
    """A grounded block A (10 x 10 x 2 at the origin) and a free block B (4 x 3 x 1) placed off
    anything the joints ask for, in a document of the test's own."""

    def setUp(self):
        self.doc = App.newDocument("dpp")
        self.asm = da.create_assembly(self.doc)
        self.a = self.doc.addObject("Part::Feature", "A")
        self.a.Shape = Part.makeBox(10, 10, 2)
        self.b = self.doc.addObject("Part::Feature", "B")
        self.b.Shape = Part.makeBox(4, 3, 1)
        self.b.Placement = App.Placement(App.Vector(3, 2, 5), App.Rotation(App.Vector(1, 2, 3), 17))
        da.add_part(self.asm, self.a, grounded=True)
        da.add_part(self.asm, self.b)

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def solved(self, joint_type, ref1, ref2, **kw):
        j = da.add_joint(self.asm, joint_type, ref1, ref2, **kw)
        r = da.solve(self.asm)
        self.assertTrue(r.converged, r.message)
        return j


class DistanceJoints(Parts):
    """Each pair of features FreeCAD 1.x's Distance joint takes, the distance measured after the
    solve on the parts' own geometry."""

    def test_point_point(self):
        va, vb = vertex_at(self.a, 10, 10, 2), vertex_at(self.b, 0, 0, 0)
        self.solved("Distance", (self.a, va), (self.b, vb), distance=3.0)
        self.assertAlmostEqual((world(self.a, va).point - world(self.b, vb).point).Length, 3.0, delta=TOL)

    def test_point_plane_either_order(self):
        top, vb = face_normal(self.a, (0, 0, 1), (0, 0, 2)), vertex_at(self.b, 4, 3, 1)
        # The vertex picked first: the plane is made part 1 (it carries the guide).
        j = self.solved("Distance", (self.b, vb), (self.a, top), distance=4.0)
        self.assertEqual((j.Reference1[0], j.Feature1, j.Feature2), (self.a, "plane", "vertex"))
        plane, p = world(self.a, top), world(self.b, vb).point
        self.assertAlmostEqual((p - plane.point).dot(plane.axis), 4.0, delta=TOL)

    def test_point_plane_below(self):
        # A negative distance is the plane's other side.
        top, vb = face_normal(self.a, (0, 0, 1), (0, 0, 2)), vertex_at(self.b, 4, 3, 1)
        self.solved("Distance", (self.a, top), (self.b, vb), distance=-1.25)
        plane, p = world(self.a, top), world(self.b, vb).point
        self.assertAlmostEqual((p - plane.point).dot(plane.axis), -1.25, delta=TOL)

    def test_plane_plane(self):
        top, bottom = face_normal(self.a, (0, 0, 1), (0, 0, 2)), face_normal(self.b, (0, 0, -1), (0, 0, 0))
        self.solved("Distance", (self.a, top), (self.b, bottom), distance=1.5)
        plane, other = world(self.a, top), world(self.b, bottom)
        self.assertLess(plane.axis.cross(other.axis).Length, TOL)
        # Every corner of B's face at 1.5 above A's top: the planes parallel, 1.5 apart.
        for v in (self.b.Shape.Faces[int(bottom[4:]) - 1]).Vertexes:
            self.assertAlmostEqual((v.Point - plane.point).dot(plane.axis), 1.5, delta=TOL)

    def test_point_line(self):
        edge, vb = edge_between(self.a, (0, 0, 2), (10, 0, 2)), vertex_at(self.b, 4, 3, 1)
        self.solved("Distance", (self.b, vb), (self.a, edge), distance=2.5)
        line = world(self.a, edge)
        self.assertAlmostEqual(line_distance(world(self.b, vb).point, line.point, line.axis), 2.5, delta=TOL)

    def test_line_line(self):
        ea, eb = edge_between(self.a, (0, 0, 2), (10, 0, 2)), edge_between(self.b, (0, 0, 0), (4, 0, 0))
        self.solved("Distance", (self.a, ea), (self.b, eb), distance=2.0)
        la, lb = world(self.a, ea), world(self.b, eb)
        self.assertLess(la.axis.cross(lb.axis).Length, TOL)
        for v in self.b.Shape.Edges[int(eb[4:]) - 1].Vertexes:
            self.assertAlmostEqual(line_distance(v.Point, la.point, la.axis), 2.0, delta=TOL)

    def test_line_plane(self):
        top, eb = face_normal(self.a, (0, 0, 1), (0, 0, 2)), edge_between(self.b, (0, 0, 0), (4, 0, 0))
        self.solved("Distance", (self.b, eb), (self.a, top), distance=3.0)
        plane = world(self.a, top)
        # Both ends of the edge 3 above the plane: the line parallel to it, at 3.
        for v in self.b.Shape.Edges[int(eb[4:]) - 1].Vertexes:
            self.assertAlmostEqual((v.Point - plane.point).dot(plane.axis), 3.0, delta=TOL)

    def test_edit_distance(self):
        va, vb = vertex_at(self.a, 10, 10, 2), vertex_at(self.b, 0, 0, 0)
        j = self.solved("Distance", (self.a, va), (self.b, vb), distance=3.0)
        da.edit_joint(j, distance=7.5)
        self.assertTrue(da.solve(self.asm).converged)
        self.assertAlmostEqual((world(self.a, va).point - world(self.b, vb).point).Length, 7.5, delta=TOL)

    def test_refused(self):
        va, vb = vertex_at(self.a, 10, 10, 2), vertex_at(self.b, 0, 0, 0)
        before = len(self.doc.Objects)
        with self.assertRaisesRegex(ValueError, "distance -1 mm is below 0"):
            da.add_joint(self.asm, "Distance", (self.a, va), (self.b, vb), distance=-1.0)
        self.assertEqual(len(self.doc.Objects), before)


class Orientation(Parts):
    """Parallel and Perpendicular between lines and planes: the angle between the features'
    directions after the solve."""

    def test_parallel_edges(self):
        ea, eb = edge_between(self.a, (0, 0, 2), (10, 0, 2)), edge_between(self.b, (0, 0, 0), (0, 3, 0))
        self.solved("Parallel", (self.a, ea), (self.b, eb))
        self.assertLess(world(self.a, ea).axis.cross(world(self.b, eb).axis).Length, TOL)

    def test_parallel_planes(self):
        top, side = face_normal(self.a, (0, 0, 1), (0, 0, 2)), face_normal(self.b, (1, 0, 0), (4, 0, 0))
        self.solved("Parallel", (self.a, top), (self.b, side))
        self.assertLess(world(self.a, top).axis.cross(world(self.b, side).axis).Length, TOL)

    def test_perpendicular_planes(self):
        top, bottom = face_normal(self.a, (0, 0, 1), (0, 0, 2)), face_normal(self.b, (0, 0, -1), (0, 0, 0))
        self.solved("Perpendicular", (self.a, top), (self.b, bottom))
        self.assertAlmostEqual(world(self.a, top).axis.dot(world(self.b, bottom).axis), 0.0, delta=TOL)

    def test_perpendicular_line_plane(self):
        top, eb = face_normal(self.a, (0, 0, 1), (0, 0, 2)), edge_between(self.b, (0, 0, 0), (4, 0, 0))
        self.solved("Perpendicular", (self.a, top), (self.b, eb))
        self.assertAlmostEqual(world(self.a, top).axis.dot(world(self.b, eb).axis), 0.0, delta=TOL)

    def test_vertex_refused(self):
        va, eb = vertex_at(self.a, 10, 10, 2), edge_between(self.b, (0, 0, 0), (4, 0, 0))
        with self.assertRaisesRegex(ValueError, "Parallel joint needs a straight or circular edge"):
            da.add_joint(self.asm, "Parallel", (self.a, va), (self.b, eb))


def turn_about(obj, axis):
    """The part's rotation angle about a world axis (z or x), from its across vector."""
    r = obj.Placement.Rotation
    if axis == "z":
        v = r.multVec(App.Vector(1, 0, 0))
        return math.atan2(v.y, v.x)
    v = r.multVec(App.Vector(0, 1, 0))
    return math.atan2(v.z, v.y)


class Turns:
    """Unwrapped turns of some parts about an axis, sampled as a motion goes."""

    def __init__(self, parts, axis="z"):
        self.parts, self.axis = parts, axis
        self.last = {n: turn_about(p, axis) for n, p in parts.items()}
        self.total = {n: 0.0 for n in parts}

    def sample(self, *_):
        for n, p in self.parts.items():
            a = turn_about(p, self.axis)
            d = a - self.last[n]
            d -= 2 * math.pi * round(d / (2 * math.pi))
            self.total[n] += d
            self.last[n] = a


def same_placement(p, q, tol=1e-9):
    return (p.Base - q.Base).Length <= tol and p.Rotation.multiply(q.Rotation.inverted()).Angle <= tol


def joint_between(asm, a, b):
    for j in da.joints(asm):
        if {j.Reference1[0], j.Reference2[0]} == {a, b}:
            return j
    raise KeyError((a.Label, b.Label))


def engine_couples():
    """Whether this build's engine has the couplings' rows (gear, belt, rack, screw): the
    workbench offers them then, and these tests run."""
    from dispcon_fc import adapter, engine

    return set(da.COUPLINGS) <= set(adapter.offered_types(engine.load()))


COUPLINGS_MISSING = "this build's engine has no coupling rows in its joint table"


@unittest.skipUnless(engine_couples(), COUPLINGS_MISSING)
class Samples(unittest.TestCase):
    """The coupling samples as build_samples.py makes them (STEP parts imported, joints from
    picked edges), each in a document of the test's own."""

    def build(self, name, **kw):
        self.doc = App.newDocument(name.replace("-", "_"))
        asm, named = dict(couplings.SAMPLES)[name](self.doc, **kw)
        r = da.solve(asm)
        self.assertTrue(r.converged, r.message)
        return asm, named

    def tearDown(self):
        if getattr(self, "doc", None) is not None:
            App.closeDocument(self.doc.Name)
            self.doc = None

    def test_three_gears_hold_their_ratios_through_a_full_turn(self):
        asm, p = self.build("three-gears")
        meshes = [j for j in da.joints(asm) if j.JointType == "Gears"]
        # The ratios from the picked pitch circles: r1 / r2.
        self.assertEqual([round(j.Ratio, 12) for j in meshes], [0.5, round(4 / 3, 12)])
        self.assertEqual(da.check(asm)["dof"], 1)
        turns = Turns({n: p[n] for n in ("G1", "G2", "G3")})
        da.drive(asm, joint_between(asm, p["Plate"], p["G1"]), range(10, 361, 10), callback=turns.sample)
        t = turns.total
        self.assertAlmostEqual(t["G1"], 2 * math.pi, delta=TOL)
        self.assertAlmostEqual(t["G2"], -0.5 * t["G1"], delta=TOL)
        self.assertAlmostEqual(t["G3"], 2 / 3 * t["G1"], delta=TOL)

    def test_planetary_obeys_willis(self):
        asm, p = self.build("planetary")
        self.assertEqual(da.check(asm)["dof"], 2)
        turns = Turns({n: p[n] for n in ("Sun", "Carrier", "Ring")})
        da.drive(asm, joint_between(asm, p["Base"], p["Sun"]), range(5, 95, 5), callback=turns.sample)
        s, c, r = turns.total["Sun"], turns.total["Carrier"], turns.total["Ring"]
        self.assertAlmostEqual(s, math.pi / 2, delta=TOL)
        # (w_sun - w_carrier) / (w_ring - w_carrier) = -z_ring / z_sun = -2, as differences.
        self.assertGreater(abs(r - c), 1e-3, "the ring and the carrier turned together: Willis untested")
        self.assertAlmostEqual(s - c, -2 * (r - c), delta=TOL)

    def test_steering_rack_travels_radius_times_the_turn(self):
        asm, p = self.build("steering")
        self.assertEqual(da.check(asm)["dof"], 1)
        coupling = next(j for j in da.joints(asm) if j.JointType == "RackPinion")
        self.assertAlmostEqual(coupling.Radius.Value, 0.3, delta=1e-12)
        rack = p["Rack"]
        u = rack.Placement.Rotation.multVec(coupling.Axis2)
        start, knuckle = rack.Placement.Base, turn_about(p["KnuckleL"], "z")
        turns = Turns({"Pinion": p["Pinion"]})
        da.drive(asm, joint_between(asm, p["Frame"], p["Pinion"]), range(5, 45, 5), callback=turns.sample)
        theta = turns.total["Pinion"]
        self.assertAlmostEqual(theta, math.radians(40), delta=TOL)
        self.assertAlmostEqual((rack.Placement.Base - start).dot(u), 0.3 * theta, delta=TOL)
        self.assertGreater(abs(turn_about(p["KnuckleL"], "z") - knuckle), 0.05, "the wheels did not steer")

    def vice_turn(self, left):
        asm, p = self.build("vice", left=left)
        self.assertEqual(da.check(asm)["dof"], 1)
        jaw, screw = p["Jaw"], p["Screw"]
        start, screw_start = jaw.Placement, screw.Placement.Base
        turns = Turns({"Screw": screw}, "x")
        d = da.Drag(asm, jaw)
        for k in range(1, 21):
            r = d.move(App.Placement(start.Base + App.Vector(0.2 * k / 20, 0, 0), start.Rotation))
            self.assertTrue(r.converged, r.message)
            turns.sample()
        d.finish()
        self.assertAlmostEqual(jaw.Placement.Base.x - start.Base.x, 0.2, delta=TOL)
        self.assertAlmostEqual(screw.Placement.Base.x - screw_start.x, 0.2, delta=TOL)
        # A pitch per turn: the screw's travel is pitch / (2 pi) times its turn (to 1e-9 in
        # length, the solver's tolerance, which is 3e-8 in the turn at a pitch of 0.2).
        self.assertAlmostEqual(0.2 * abs(turns.total["Screw"]) / (2 * math.pi), 0.2, delta=TOL)
        return turns.total["Screw"]

    def test_vice_advances_a_pitch_per_turn(self):
        right = self.vice_turn(False)
        self.tearDown()
        left = self.vice_turn(True)
        self.assertAlmostEqual(0.2 * (left + right) / (2 * math.pi), 0.0, delta=2 * TOL)

    def mesh_value(self, mesh, p):
        """The engine's gear equation on the parts as they stand: ratio turn1 + turn2 about the
        joint's axes (both about world z here, each signed by its axis), in radians."""
        s1 = math.copysign(1, p["G1"].Placement.Rotation.multVec(mesh.Axis1).z)
        s2 = math.copysign(1, p["G2"].Placement.Rotation.multVec(mesh.Axis2).z)
        return mesh.Ratio * s1 * turn_about(p["G1"], "z") + s2 * turn_about(p["G2"], "z")

    def test_phase_is_the_engines_and_holds_the_mesh(self):
        # The Phase is the engine's constant, taken when the coupling was made and passed to the
        # engine at every solve: a gear turned by hand goes back into mesh at the next Solve
        # (before, the coupling was made again at whatever poses the parts had).
        asm, p = self.build("three-gears")
        mesh = joint_between(asm, p["G1"], p["G2"])
        self.assertTrue(mesh.PhaseKnown)
        self.assertEqual(mesh.getTypeIdOfProperty("Phase"), "App::PropertyAngle")
        held = self.mesh_value(mesh, p)
        g2 = p["G2"].Placement
        p["G2"].Placement = App.Placement(g2.Base, App.Rotation(App.Vector(0, 0, 1), 30).multiply(g2.Rotation))
        self.assertGreater(abs(math.remainder(self.mesh_value(mesh, p) - held, 2 * math.pi)), 0.5)
        r = da.solve(asm)
        self.assertTrue(r.converged, r.message)
        self.assertAlmostEqual(math.remainder(self.mesh_value(mesh, p) - held, 2 * math.pi), 0.0, delta=1e-8)
        rack = next(j for j in da.joints(self.build_other("steering")) if j.JointType == "RackPinion")
        self.assertEqual(rack.getTypeIdOfProperty("Phase"), "App::PropertyDistance")
        self.assertTrue(rack.PhaseKnown)

    def build_other(self, name):
        """A second sample in a document of its own, closed with the test."""
        doc = App.newDocument(name.replace("-", "_"))
        self.addCleanup(App.closeDocument, doc.Name)
        asm, _ = dict(couplings.SAMPLES)[name](doc)
        self.assertTrue(da.solve(asm).converged)
        return asm

    def test_a_new_phase_turns_part_2_against_part_1_and_the_ratio_holds(self):
        asm, p = self.build("three-gears")
        mesh = joint_between(asm, p["G1"], p["G2"])
        before = self.mesh_value(mesh, p)
        da.edit_joint(mesh, phase=da.phase_value(mesh) + 12.0)
        self.assertTrue(da.solve(asm).converged)
        self.assertAlmostEqual(math.remainder(self.mesh_value(mesh, p) - before, 2 * math.pi), math.radians(12),
                               delta=1e-8)
        turns = Turns({n: p[n] for n in ("G1", "G2")})
        da.drive(asm, joint_between(asm, p["Plate"], p["G1"]), range(10, 100, 10), callback=turns.sample)
        self.assertAlmostEqual(turns.total["G2"], -0.5 * turns.total["G1"], delta=TOL)

    def test_the_mesh_offset_reads_from_the_pose_made_and_keeps_through_turns(self):
        # The designer's reading of the phase: 0 where the coupling was made, in degrees of part
        # 2 (part 1 held); the engine's phase underneath moves with it, and moves on by whole
        # wrapped turns as the gears go round, which the offset does not.
        asm, p = self.build("three-gears")
        mesh = joint_between(asm, p["G1"], p["G2"])
        self.assertEqual(mesh.getTypeIdOfProperty("MeshOffset"), "App::PropertyAngle")
        self.assertEqual((da.mesh_offset(mesh), mesh.PhaseKnown), (0.0, True))
        before, phase = self.mesh_value(mesh, p), da.phase_value(mesh)
        da.edit_joint(mesh, mesh_offset=12.0)
        self.assertEqual(da.mesh_offset(mesh), 12.0)
        self.assertAlmostEqual(da.phase_value(mesh), phase + 12.0, delta=1e-12)
        self.assertTrue(da.solve(asm).converged)
        # Part 2 stands 12 degrees on against part 1: the equation's ratio turn1 + turn2 by 12.
        self.assertAlmostEqual(math.remainder(self.mesh_value(mesh, p) - before, 2 * math.pi), math.radians(12),
                               delta=1e-8)
        turns = Turns({n: p[n] for n in ("G1", "G2")})
        da.drive(asm, joint_between(asm, p["Plate"], p["G1"]), range(10, 371, 10), callback=turns.sample)
        self.assertAlmostEqual(turns.total["G2"], -0.5 * turns.total["G1"], delta=TOL)
        wrapped = da.phase_value(mesh)
        self.assertGreater(abs(wrapped - phase - 12.0), 1.0)  # the engine's moved on with the turns ...
        self.assertEqual(da.mesh_offset(mesh), 12.0)  # ... the offset did not
        # Set again from there: the engine's phase moves by the change only.
        da.edit_joint(mesh, mesh_offset=-5.0)
        self.assertAlmostEqual(da.phase_value(mesh), wrapped - 17.0, delta=1e-9)
        # A whole turn of part 2 is the same mesh: shown within -180..180 degrees.
        da.edit_joint(mesh, mesh_offset=370.0)
        self.assertAlmostEqual(da.mesh_offset(mesh), 10.0, delta=1e-12)
        self.assertAlmostEqual(da.phase_value(mesh), wrapped - 17.0 + 375.0, delta=1e-9)
        # Refused at the engine's door, nothing changed.
        for bad in (float("nan"), 1e300):
            with self.assertRaisesRegex(ValueError, "phase"):
                da.edit_joint(mesh, mesh_offset=bad)
            self.assertEqual(da.mesh_offset(mesh), 10.0)
        # Made again (a new ratio): the mesh as it stands is the one made, offset 0.
        da.edit_joint(mesh, ratio=0.4)
        self.assertEqual((da.mesh_offset(mesh), mesh.PhaseKnown), (0.0, False))
        self.assertTrue(da.solve(asm).converged)
        self.assertEqual((da.mesh_offset(mesh), mesh.PhaseKnown), (0.0, True))
        # A rack's offset is a length: the rack moved along its travel against the pinion.
        rack = next(j for j in da.joints(self.build_other("steering")) if j.JointType == "RackPinion")
        self.assertEqual(rack.getTypeIdOfProperty("MeshOffset"), "App::PropertyDistance")
        phase = da.phase_value(rack)
        da.edit_joint(rack, mesh_offset=0.05)
        self.assertAlmostEqual(da.phase_value(rack), phase + 0.05, delta=1e-12)

    def test_a_mesh_offset_typed_in_the_property_editor_is_taken_at_the_next_solve(self):
        asm, p = self.build("three-gears")
        mesh = joint_between(asm, p["G1"], p["G2"])
        self.assertEqual(mesh.getEditorMode("MeshOffset"), [])  # editable there
        self.assertEqual(mesh.getEditorMode("Phase"), ["ReadOnly"])
        before, phase = self.mesh_value(mesh, p), da.phase_value(mesh)
        mesh.MeshOffset = 12.0  # as the property editor sets it: nothing else changes now
        self.assertAlmostEqual(da.phase_value(mesh), phase + 12.0, delta=1e-12)  # the engine's to be
        r = da.solve(asm)
        self.assertTrue(r.converged, r.message)
        self.assertAlmostEqual(math.remainder(self.mesh_value(mesh, p) - before, 2 * math.pi), math.radians(12),
                               delta=1e-8)
        self.assertEqual((mesh.MeshOffset.Value, mesh.MeshOffsetHeld.Value), (12.0, 12.0))
        self.assertAlmostEqual(da.phase_value(mesh), phase + 12.0, delta=1e-9)
        placed = {n: o.Placement for n, o in p.items()}
        self.assertTrue(da.solve(asm).converged)
        for n, pl in placed.items():
            self.assertTrue(same_placement(p[n].Placement, pl), "%s moved at the second solve" % n)

    def moved_gear(self, gear, by):
        """`gear`'s shape with its geometry moved by `by` in its own frame (a hole moved in the
        part): its Placement stays, its edges keep their names."""
        shape = gear.Shape.copy()
        shape.Placement = App.Placement()
        m = App.Matrix()
        m.move(App.Vector(*by))
        shape.transformShape(m, True)
        shape.Placement = gear.Placement
        return shape

    def test_a_coupling_whose_geometry_moved_is_made_again_and_said(self):
        # G2's geometry moved 0.3 in its own frame (its bore and its pitch circle): its revolute
        # follows the bore; the mesh's phase, taken about the old centre, would hold the gears
        # by a centre that is no longer the axle's. Solve makes it again at the poses and says so,
        # keeping the designer's mesh offset (how far G2 stands against G1 from where it was made).
        asm, p = self.build("three-gears")
        mesh = joint_between(asm, p["G1"], p["G2"])
        da.edit_joint(mesh, mesh_offset=7.0)
        self.assertTrue(da.solve(asm).converged)
        p["G2"].Shape = self.moved_gear(p["G2"], (0.3, 0, 0))
        r = da.solve(asm)
        self.assertTrue(r.converged, r.message)
        self.assertIn("made the phase of %s again" % mesh.Label, r.message)
        self.assertIn("G2", r.message)
        self.assertIn("its mesh offset, 7\u00b0, kept", r.message)
        self.assertTrue(mesh.PhaseKnown)
        self.assertEqual((da.mesh_offset(mesh), mesh.MeshOffsetHeld.Value), (7.0, 7.0))
        self.assertAlmostEqual((mesh.Point2 - App.Vector(0.3, 0, 0)).Length, 0.0, delta=1e-9)
        placed = {n: o.Placement for n, o in p.items()}
        again = da.solve(asm)
        self.assertNotIn("made the phase", again.message)  # made once
        for n, pl in placed.items():
            self.assertTrue(same_placement(p[n].Placement, pl), "%s moved at the second solve" % n)
        # The ratio holds about the axles as they are now, and the offset through the turns.
        turns = Turns({n: p[n] for n in ("G1", "G2")})
        da.drive(asm, joint_between(asm, p["Plate"], p["G1"]), range(10, 100, 10), callback=turns.sample)
        self.assertAlmostEqual(turns.total["G1"], math.radians(90), delta=TOL)
        self.assertAlmostEqual(turns.total["G2"], -0.5 * turns.total["G1"], delta=TOL)
        self.assertEqual(da.mesh_offset(mesh), 7.0)
        # The offset still means "from where it was made": back to 0, G2 turns 7 degrees back
        # against G1 (the equation ratio turn1 + turn2 by -7 degrees), into the mesh as made.
        before = self.mesh_value(mesh, p)
        da.edit_joint(mesh, mesh_offset=0.0)
        self.assertTrue(da.solve(asm).converged)
        self.assertAlmostEqual(math.remainder(self.mesh_value(mesh, p) - before, 2 * math.pi), math.radians(-7),
                               delta=1e-8)

    def remade_with(self, typed):
        """The three gears with an offset of 7 degrees, G2's geometry moved, `typed` set in the
        property editor (None: nothing typed), solved: (the mesh's equation after it, the joint)."""
        asm, p = self.build("three-gears")
        mesh = joint_between(asm, p["G1"], p["G2"])
        da.edit_joint(mesh, mesh_offset=7.0)
        self.assertTrue(da.solve(asm).converged)
        p["G2"].Shape = self.moved_gear(p["G2"], (0.3, 0, 0))
        if typed is not None:
            mesh.MeshOffset = typed
        r = da.solve(asm)
        self.assertTrue(r.converged, r.message)
        self.assertIn("made the phase of %s again" % mesh.Label, r.message)
        placed = {n: o.Placement for n, o in p.items()}
        self.assertTrue(da.solve(asm).converged)
        for n, pl in placed.items():
            self.assertTrue(same_placement(p[n].Placement, pl), "%s moved at the second solve" % n)
        return self.mesh_value(mesh, p), mesh

    def test_an_offset_typed_before_a_remade_phase_is_taken_at_that_solve(self):
        # 10 degrees typed where 7 was held, then the Solve that makes the phase again at the
        # poses (which stand at 7): G2 stands 3 degrees on against G1 from where the same Solve
        # leaves it with nothing typed, and a second Solve moves nothing.
        kept, mesh = self.remade_with(None)
        self.assertEqual((da.mesh_offset(mesh), mesh.MeshOffsetHeld.Value, mesh.PhaseKnown), (7.0, 7.0, True))
        self.tearDown()
        typed, mesh = self.remade_with(10.0)
        self.assertEqual((da.mesh_offset(mesh), mesh.MeshOffsetHeld.Value, mesh.PhaseKnown), (10.0, 10.0, True))
        self.assertAlmostEqual(math.remainder(typed - kept, 2 * math.pi), math.radians(3), delta=1e-8)

    def test_a_recompute_remakes_a_moved_coupling_before_it_is_saved(self):
        # The part recomputed (as a Pad changed in the GUI): the joint takes the new geometry and
        # its phase is to be made again at the poses, before any solve, so the saved file holds
        # no phase measured about the old axes.
        tmp = tempfile.mkdtemp()
        try:
            asm, p = self.build("three-gears")
            mesh = joint_between(asm, p["G1"], p["G2"])
            da.edit_joint(mesh, mesh_offset=-4.5)
            self.assertTrue(da.solve(asm).converged)
            p["G1"].Shape = self.moved_gear(p["G1"], (0, 0.2, 0))
            self.doc.recompute()
            self.assertFalse(mesh.PhaseKnown)
            self.assertEqual(da.mesh_offset(mesh), -4.5)  # the designer's offset kept
            self.assertAlmostEqual((mesh.Point1 - App.Vector(0, 0.2, 0)).Length, 0.0, delta=1e-9)
            path = os.path.join(tmp, "moved.FCStd")
            self.doc.saveAs(path)
            self.tearDown()
            self.doc = App.openDocument(path)
            asm = next(o for o in self.doc.Objects if da.is_assembly(o))
            p = {o.Label: o for o in self.doc.Objects}
            mesh = joint_between(asm, p["G1"], p["G2"])
            self.assertFalse(mesh.PhaseKnown)
            self.assertAlmostEqual((mesh.Point1 - App.Vector(0, 0.2, 0)).Length, 0.0, delta=1e-9)
            self.assertEqual(da.mesh_offset(mesh), -4.5)
            r = da.solve(asm)
            self.assertTrue(r.converged, r.message)
            self.assertTrue(mesh.PhaseKnown)
            self.assertEqual((da.mesh_offset(mesh), mesh.MeshOffsetHeld.Value), (-4.5, -4.5))
            turns = Turns({n: p[n] for n in ("G1", "G2")})
            da.drive(asm, joint_between(asm, p["Plate"], p["G1"]), range(10, 100, 10), callback=turns.sample)
            self.assertAlmostEqual(turns.total["G2"], -0.5 * turns.total["G1"], delta=TOL)
            self.assertEqual(da.mesh_offset(mesh), -4.5)
        finally:
            shutil.rmtree(tmp)

    def test_bad_values_refused_changing_nothing(self):
        asm, p = self.build("three-gears")
        before = len(self.doc.Objects)
        with self.assertRaisesRegex(ValueError, "ratio 0 must be above 0"):
            da.add_joint(asm, "Gears", couplings.circle(p["G1"], (0, 0, 0), 1.0),
                         couplings.circle(p["G3"], (0, 0, 0), 1.5), ratio=0)
        mesh = joint_between(asm, p["G1"], p["G2"])
        with self.assertRaisesRegex(ValueError, "ratio -2 must be above 0"):
            da.edit_joint(mesh, ratio=-2)
        self.assertEqual((len(self.doc.Objects), mesh.Ratio), (before, 0.5))
        # The phase is checked by the engine's door (the model's), before anything changes.
        phase = da.phase_value(mesh)
        for bad in (float("nan"), 1e300):
            with self.assertRaisesRegex(ValueError, "phase"):
                da.edit_joint(mesh, phase=bad)
            self.assertEqual((da.phase_value(mesh), mesh.PhaseKnown), (phase, True))
        # A rack needs a straight edge or a planar face on the rack.
        with self.assertRaisesRegex(ValueError, "RackPinion joint needs a circular edge"):
            da.add_joint(asm, "RackPinion", couplings.circle(p["G1"], (0, 0, 0), 1.0),
                         couplings.circle(p["G3"], (0, 0, 0), 1.5))

    def test_the_phase_round_trips_after_full_turns(self):
        # Driven through more than a turn, the engine's phase moves on with the wrapped turns;
        # saved and reopened, the gears are where they were and Solve moves nothing.
        tmp = tempfile.mkdtemp()
        try:
            asm, p = self.build("three-gears")
            mesh = joint_between(asm, p["G1"], p["G2"])
            made = da.phase_value(mesh)
            da.drive(asm, joint_between(asm, p["Plate"], p["G1"]), range(10, 371, 10))
            phase = da.phase_value(mesh)
            self.assertNotAlmostEqual(phase, made, delta=1.0)  # the wrapped turns moved it on
            placements = {n: o.Placement for n, o in p.items()}
            labels = {n: o.Label for n, o in p.items()}
            path = os.path.join(tmp, "gears.FCStd")
            self.doc.saveAs(path)
            self.tearDown()
            self.doc = App.openDocument(path)
            asm = next(o for o in self.doc.Objects if da.is_assembly(o))
            p = {n: self.doc.getObjectsByLabel(label)[0] for n, label in labels.items()}
            mesh = joint_between(asm, p["G1"], p["G2"])
            self.assertTrue(mesh.PhaseKnown)
            self.assertAlmostEqual(da.phase_value(mesh), phase, delta=1e-12 * max(1.0, abs(phase)))
            r = da.solve(asm)
            self.assertTrue(r.converged, r.message)
            for n, pl in placements.items():
                self.assertTrue(same_placement(p[n].Placement, pl), "%s moved after reopening" % n)
        finally:
            shutil.rmtree(tmp)

    def test_save_and_reopen_keep_every_coupling(self):
        tmp = tempfile.mkdtemp()
        try:
            for name in ("three-gears", "planetary", "steering", "vice"):
                asm, _ = self.build(name)
                path = os.path.join(tmp, name + ".FCStd")
                keys = ("Label", "JointType", "Ratio", "Radius", "Pitch", "LeftHanded", "PhaseTurns", "PhaseKnown",
                        "MeshOffset", "Feature1", "Feature2")
                saved = [tuple(str(getattr(j, k)) for k in keys) for j in da.joints(asm)]
                phases = [da.phase_value(j) for j in da.joints(asm)]
                self.doc.saveAs(path)
                self.tearDown()
                self.doc = App.openDocument(path)
                asm = next(o for o in self.doc.Objects if da.is_assembly(o))
                self.assertEqual([tuple(str(getattr(j, k)) for k in keys) for j in da.joints(asm)], saved)
                # FreeCAD writes a quantity with 16 significant digits: the phase to 1e-15 of itself.
                for j, phase in zip(da.joints(asm), phases):
                    self.assertAlmostEqual(da.phase_value(j), phase, delta=1e-12 * max(1.0, abs(phase)), msg=j.Label)
                self.assertTrue(any(j.JointType in da.COUPLINGS for j in da.joints(asm)))
                r = da.solve(asm)
                self.assertTrue(r.converged, r.message)
                self.assertEqual(da.check(asm)["dof"], {"planetary": 2}.get(name, 1))
                self.tearDown()
        finally:
            shutil.rmtree(tmp)


WITHOUT_WORKBENCH = """
import sys
import FreeCAD as App
try:
    import dispcon_fc
    raise SystemExit("the workbench was importable: this session must not have it")
except ImportError:
    pass
doc = App.openDocument(sys.argv[-1])
joints = [o for o in doc.Objects if "JointType" in o.PropertiesList]
assert sorted(j.JointType for j in joints) == ["Revolute", "Screw", "Slider"], [j.JointType for j in joints]
assert all(j.Proxy is None for j in joints), [j.Proxy for j in joints]
doc.save()
print("SESSION OK")
sys.exit(0)
"""


@unittest.skipUnless(engine_couples(), COUPLINGS_MISSING)
class NothingLostWithoutTheWorkbench(unittest.TestCase):
    def test_a_left_handed_screw_saved_where_the_workbench_is_missing(self):
        os.environ["DISPCON_IMPORT_ONLY"] = "1"
        import test_headless as th

        with tempfile.TemporaryDirectory() as tmp:
            doc = App.newDocument("vice_kept")
            asm, p = couplings.vice(doc, pitch=0.25, left=True)
            screw = next(j for j in da.joints(asm) if j.JointType == "Screw")
            da.edit_joint(screw, phase=da.phase_value(screw) + 0.05)  # mm: the nut a quarter turn on
            self.assertTrue(da.solve(asm).converged)
            phase = da.phase_value(screw)
            path = os.path.join(tmp, "vice.FCStd")
            doc.saveAs(path)
            values = th.settings_of(doc)
            App.closeDocument(doc.Name)
            th.freecad_session(WITHOUT_WORKBENCH, tmp, path)
            doc = App.openDocument(path)
            try:
                asm = next(o for o in doc.Objects if da.is_assembly(o))
                self.assertEqual(th.settings_of(doc), values)
                screw = next(j for j in da.joints(asm) if j.JointType == "Screw")
                self.assertEqual((screw.Pitch.Value, screw.LeftHanded), (0.25, True))
                self.assertAlmostEqual(da.phase_value(screw), phase, delta=1e-12)
                self.assertEqual(list(screw.getEnumerationsOfProperty("JointType")), da.JOINT_TYPES)
                self.assertTrue(da.solve(asm).converged)
                self.assertEqual(da.check(asm)["dof"], 1)
            finally:
                App.closeDocument(doc.Name)


UNIT_TESTS = [DistanceJoints, Orientation, Samples, NothingLostWithoutTheWorkbench]


if __name__ in ("__main__", "test_couplings") and not os.environ.get("DISPCON_IMPORT_ONLY"):
    suite = unittest.TestSuite(unittest.defaultTestLoader.loadTestsFromTestCase(c) for c in UNIT_TESTS)
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
    failed = len(result.failures) + len(result.errors)
    print("%d passed, %d failed" % (result.testsRun - failed, failed))
    # freecadcmd would open the arguments after this script as documents.
    sys.exit(1 if failed else 0)
