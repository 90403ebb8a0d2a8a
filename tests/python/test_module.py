"""The dispcon Python module against python.md, mirroring the C++ tests."""
import math
import os
import random
import tempfile
import unittest
import warnings

import numpy as np

import dispcon

SRC = os.environ.get("DISPCON_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
Z = (0, 0, 1)


def fourbar(a=1.0, b=3.0, c=2.5, d=3.0):
    """A crank-rocker of revolute joints, built in code at rough positions."""
    m = dispcon.Model()
    m.add_body("crank", position=(0.1, -0.1, 0.05), rotation=(0, 0, 0.4))
    m.add_body("coupler", position=(1.2, 0.6, -0.1), rotation=(0, 0, 0.2))
    m.add_body("rocker", position=(2.9, 0.2, 0.1), rotation=(0, 0, 1.9))
    revolute = dict(angle=(Z, Z, 0, 0))
    m.add_joint("crank", hinge=((0, 0, 0), (0, 0, 0)), **revolute)
    m.add_joint("coupler", object1="crank", hinge=((a, 0, 0), (0, 0, 0)), **revolute)
    m.add_joint("rocker", object1="coupler", hinge=((b, 0, 0), (c, 0, 0)), **revolute)
    m.add_joint("rocker", hinge=((d, 0, 0), (0, 0, 0)), **revolute)
    return m


def angle_of(m, name):
    x = m.body(name).rotation[:, 0]
    return math.atan2(x[1], x[0])


def freudenstein(t, a=1.0, b=3.0, c=2.5, d=3.0):
    """Rocker angle for crank angle t, the branch with the coupler-rocker pin above A-D."""
    A = np.array([a * math.cos(t), a * math.sin(t)])
    D = np.array([d, 0.0])
    L = np.linalg.norm(D - A)
    x = (b * b - c * c + L * L) / (2 * L)
    h = math.sqrt(b * b - x * x)
    u = (D - A) / L
    B = A + x * u + h * np.array([-u[1], u[0]])
    return math.atan2(B[1] - D[1], B[0] - D[0])


def quat_matrix(q):
    """The rotation matrix of a unit quaternion (w, x, y, z)."""
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


class Load(unittest.TestCase):
    def test_load_sample_and_assemble(self):
        m = dispcon.load(os.path.join(SRC, "samples", "monocycle.dcl"))
        r = m.assemble(tolerance=1e-9, max_iterations=10000)
        self.assertTrue(r.converged, r.message)
        self.assertLessEqual(r.max_residual, 1e-9)
        self.assertEqual(r.violated, [])
        self.assertEqual(m.body("wheel").position.shape, (3,))
        R = m.body("wheel").rotation
        self.assertEqual(R.shape, (3, 3))
        np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-12)

    def test_bad_text_raises_value_error_with_the_place(self):
        with self.assertRaises(ValueError) as e:
            dispcon.loads("object a; end\nconstraint object2 a; hinge 0 0 0 0 0; end", "t.dcl")
        self.assertIn("t.dcl:2:38: error: expected a number", str(e.exception))

    def test_bad_joint_in_code_raises_value_error(self):
        m = dispcon.Model()
        m.add_body("a")
        with self.assertRaises(ValueError):
            m.add_joint("a", object1="a", hinge=((0, 0, 0), (0, 0, 0)))
        with self.assertRaises(ValueError):
            m.add_joint("nobody", hinge=((0, 0, 0), (0, 0, 0)))
        with self.assertRaises(ValueError):
            m.add_body("a")
        with self.assertRaises(ValueError):
            m.assemble(bogus=1)


class Solve(unittest.TestCase):
    def test_fourbar_in_code_matches_freudenstein(self):
        m = fourbar()
        r = m.assemble(tolerance=1e-10)
        self.assertTrue(r.converged, r.message)
        t = angle_of(m, "crank")
        self.assertAlmostEqual(angle_of(m, "rocker"), freudenstein(t), delta=1e-9)

    def test_drag_is_continuous_and_follows_freudenstein(self):
        m = fourbar()
        m.assemble()
        t0 = angle_of(m, "crank")
        d = m.drag("crank", position=(0, 0, 0), rotation=(0, 0, t0 + 1.0), steps=20,
                   tolerance=1e-10)
        self.assertTrue(d.converged, d.message)
        self.assertEqual(len(d.steps), 20)
        self.assertAlmostEqual(angle_of(m, "rocker"), freudenstein(t0 + 1.0), delta=1e-9)

    def test_solver_options_as_keywords(self):
        for scheme in ("jacobi", "gauss-seidel"):
            m = fourbar()
            r = m.assemble(tolerance=1e-10, scheme=scheme, newton_polish=False,
                           max_iterations=100000)
            self.assertTrue(r.converged, r.message)
            self.assertAlmostEqual(angle_of(m, "rocker"), freudenstein(angle_of(m, "crank")),
                                   delta=1e-8)
        with self.assertRaises(ValueError):
            fourbar().assemble(scheme="newton")

    def test_held_bodies_do_not_move(self):
        m = fourbar()
        m.assemble()
        before = m.body("coupler").position.copy()
        m.set_pose("rocker", position=m.body("rocker").position + 0.05)
        m.set_pose("crank", rotation=(0, 0, angle_of(m, "crank") + 0.02))
        r = m.solve(held=["coupler"])
        self.assertTrue(r.converged, r.message)
        np.testing.assert_array_equal(m.body("coupler").position, before)

    def test_failed_solve_leaves_poses_unchanged(self):
        m = dispcon.Model()
        m.add_body("bar", position=(0.3, 0, 0))
        m.add_joint("bar", hinge=((0, 0, 0), (0, 0, 0)))
        m.add_joint("bar", hinge=((1, 0, 0), (0, 0, 0)))
        r = m.assemble(max_iterations=200)
        self.assertFalse(r.converged)
        self.assertEqual(sorted(r.violated), [0, 1])
        np.testing.assert_array_equal(m.body("bar").position, [0.3, 0, 0])

    def test_drag_to_an_unreachable_pose_fails_and_keeps_the_poses(self):
        m = dispcon.Model()
        m.add_body("bar", position=(0.5, 0, 0))
        m.add_joint("bar", hinge=((0, 0, 0), (-0.5, 0, 0)), angle=(Z, Z, 0, 0))
        self.assertTrue(m.assemble().converged)
        # Turning the bar about its own centre moves its pinned end off the pivot.
        d = m.drag("bar", position=(0.5, 0, 0), rotation=(0, 0, 1.0), steps=10)
        self.assertFalse(d.converged)
        self.assertEqual(d.failed_step, 0)
        self.assertGreater(d.max_residual, 1e-3)
        np.testing.assert_array_equal(m.body("bar").position, [0.5, 0, 0])
        np.testing.assert_array_equal(m.body("bar").rotation_vector, [0, 0, 0])

    def test_dragger_out_of_reach_tells_the_body_and_the_distance_left(self):
        # A 2-link arm (2 and 1.5) with a hand at its tip, the hand held 3.905 from the shoulder.
        m = dispcon.Model()
        m.add_body("upper", position=(0, 0, 0))
        m.add_body("fore", position=(2, 0, 0))
        m.add_body("hand", position=(3.5, 0, 0))
        m.add_joint("upper", hinge=((0, 0, 0), (0, 0, 0)))
        m.add_joint("fore", object1="upper", hinge=((2, 0, 0), (0, 0, 0)))
        m.add_joint("hand", object1="fore", hinge=((1.5, 0, 0), (0, 0, 0)))
        self.assertTrue(m.assemble().converged)
        drag = m.dragger("hand")
        self.assertTrue(drag.move_to(position=(2, 2, 0)).converged)
        before = m.body("fore").position.copy()
        r = drag.move_to(position=(3, 2.5, 0))
        self.assertFalse(r.converged)
        self.assertEqual(r.status, "out-of-reach")
        self.assertEqual(r.out_of_reach, "hand")
        self.assertAlmostEqual(r.distance_left, math.sqrt(15.25) - 3.5, delta=1e-12)
        np.testing.assert_array_equal(m.body("fore").position, before)
        self.assertIsNone(drag.move_to(position=(2, 2.1, 0)).out_of_reach)

    def test_puller_moves_the_model_to_the_nearest_pose(self):
        # The same arm pulled by its hand's point: past the links' reach the arm stretches toward
        # the target and the model takes that pose, joints exact; a reachable point is met.
        m = dispcon.Model()
        m.add_body("upper", position=(0, 0, 0))
        m.add_body("fore", position=(2, 0, 0), rotation=(0, 0, 0.5))
        m.add_body("hand", position=(2 + 1.5 * math.cos(0.5), 1.5 * math.sin(0.5), 0))
        m.add_joint("upper", hinge=((0, 0, 0), (0, 0, 0)))
        m.add_joint("fore", object1="upper", hinge=((2, 0, 0), (0, 0, 0)))
        m.add_joint("hand", object1="fore", hinge=((1.5, 0, 0), (0, 0, 0)))
        self.assertTrue(m.assemble().converged)
        pull = m.puller("hand", point=(0, 0, 0))
        r = pull.pull_to((3, 2.5, 0))
        self.assertFalse(r.converged)
        self.assertEqual(r.status, "out-of-reach")
        self.assertEqual(r.out_of_reach, "hand")
        # Beyond the links' 3.5 the arm stretched toward the target is the nearest pose there
        # is (nothing bends it off the line): found without iterating.
        self.assertEqual(r.iterations, 0)
        self.assertAlmostEqual(r.distance_left, math.sqrt(15.25) - 3.5, delta=1e-12)
        self.assertEqual(r.violated, [])
        t = np.array([3, 2.5, 0]) / math.sqrt(15.25)
        np.testing.assert_allclose(m.body("fore").position, 2 * t, atol=1e-12)
        np.testing.assert_allclose(m.body("hand").position, 3.5 * t, atol=1e-12)
        self.assertLess(max(c.residual for c in m.residuals()), 1e-9)
        back = pull.pull_to((2, 2, 0))
        self.assertTrue(back.converged, back.message)
        np.testing.assert_allclose(m.body("hand").position, [2, 2, 0], atol=1e-9)
        with self.assertRaises(ValueError):
            pull.pull_to((math.nan, 0, 0))

    def test_live_dragger(self):
        m = fourbar()
        m.assemble()
        t0 = angle_of(m, "crank")
        drag = m.dragger("crank")
        for k in range(1, 11):
            r = drag.move_to(rotation=(0, 0, t0 + 0.05 * k))
            self.assertTrue(r.converged, r.message)
            self.assertAlmostEqual(angle_of(m, "rocker"), freudenstein(t0 + 0.05 * k), delta=1e-8)


class Poses(unittest.TestCase):
    def test_set_pose_takes_a_rotation_matrix_or_vector(self):
        m = dispcon.Model()
        m.add_body("bar")
        t = 0.7
        R = np.array([[math.cos(t), -math.sin(t), 0], [math.sin(t), math.cos(t), 0], [0, 0, 1]])
        m.set_pose("bar", position=[1, 2, 3], rotation=R)
        b = m.body("bar")
        np.testing.assert_allclose(b.rotation, R, atol=1e-12)
        np.testing.assert_allclose(b.rotation_vector, [0, 0, t], atol=1e-12)
        np.testing.assert_allclose(b.quaternion, [math.cos(t / 2), 0, 0, math.sin(t / 2)],
                                   atol=1e-12)
        np.testing.assert_array_equal(b.position, [1, 2, 3])
        m.set_pose("bar", rotation=(t, 0, 0))
        np.testing.assert_allclose(m.body("bar").rotation[1:, 1],
                                   [math.cos(t), math.sin(t)], atol=1e-12)

    def test_set_pose_refuses_a_matrix_that_is_no_rotation(self):
        m = dispcon.Model()
        m.add_body("bar", position=(0.5, 0, 0))
        with self.assertRaises(ValueError) as e:
            m.set_pose("bar", rotation=2 * np.eye(3))
        self.assertIn("not a rotation", str(e.exception))
        with self.assertRaises(ValueError):
            m.set_pose("bar", rotation=np.diag([1.0, 1.0, -1.0]))
        with self.assertRaises(ValueError):
            m.set_pose("nobody", position=(0, 0, 0))
        np.testing.assert_array_equal(m.body("bar").rotation, np.eye(3))

    def test_poses_in_one_array_and_back(self):
        m = fourbar()
        self.assertTrue(m.assemble().converged)
        a = m.poses()
        self.assertEqual(a.shape, (3, 7))
        for row, name in zip(a, m.body_names()):
            b = m.body(name)
            np.testing.assert_array_equal(row[:3], b.position)
            q = row[3:] if row[3] >= 0 else -row[3:]  # quaternion keeps w >= 0
            np.testing.assert_array_equal(q, b.quaternion)
        moved = a.copy()
        moved[:, 0] += 1.0
        m.set_poses(moved)
        np.testing.assert_array_equal(m.poses()[:, 0], a[:, 0] + 1.0)
        m.set_poses(a)
        np.testing.assert_array_equal(m.poses(), a)  # back bit for bit
        for bad in (a[:2], a[:, :6], np.full((3, 7), np.nan)):
            with self.assertRaises(ValueError):
                m.set_poses(bad)
        np.testing.assert_array_equal(m.poses(), a)  # a refused array changes nothing
        m.body("crank").fixed = True
        moved = a.copy()
        moved[0, :3] += 5.0
        m.set_poses(moved)
        np.testing.assert_array_equal(m.body("crank").position, a[0, :3])  # fixed: kept

    def test_joint_info_names_the_bodies(self):
        m = fourbar()
        self.assertEqual(m.joint_count(), 4)
        j = m.joint(1)
        self.assertEqual((j.index, j.object1, j.object2, j.line), (1, "crank", "coupler", 0))
        self.assertEqual(j["object2"], "coupler")
        loaded = dispcon.loads(m.to_dcl())
        lines = [loaded.joint(i).line for i in range(loaded.joint_count())]
        self.assertTrue(all(line > 0 for line in lines), lines)
        self.assertEqual(lines, sorted(lines))
        with self.assertRaises(ValueError):
            m.joint(4)

    def test_residuals_measure_without_moving(self):
        m = dispcon.Model()
        m.add_body("bar", position=(0.3, 0.4, 0))
        m.add_joint("bar", hinge=((0, 0, 0), (0, 0, 0)))
        reports = m.residuals()
        self.assertEqual(len(reports), 1)
        self.assertFalse(reports[0].satisfied)
        self.assertGreater(reports[0].residual, 0)
        np.testing.assert_array_equal(m.body("bar").position, [0.3, 0.4, 0])
        self.assertTrue(m.assemble().converged)
        self.assertTrue(all(r.satisfied for r in m.residuals()))


class Diagnostics(unittest.TestCase):
    def test_pendulum_has_one_degree_of_freedom(self):
        m = dispcon.Model()
        m.add_body("bar", position=(0.2, 0, 0))
        m.add_joint("bar", hinge=((0, 0, 0), (0, 0, 0)), angle=(Z, Z, 0, 0))
        c = m.check()
        self.assertEqual(c.dof, 1)
        self.assertEqual(c.body_dof["bar"], 1)

    def test_planar_fourbar_in_3d_has_one_dof_and_redundant_equations(self):
        c = fourbar().check()
        self.assertEqual(c.dof, 1)
        self.assertEqual(c.redundant, [3])


    def test_sweep_turns_a_grashof_crank_fully_and_puts_it_back(self):
        m = fourbar()
        m.assemble()
        before = m.body("rocker").position.copy()
        s = m.sweep("crank", axis=Z, start=0.0, stop=2 * math.pi, steps=36)
        self.assertFalse(s.locked, s.message)
        self.assertEqual(len(s.samples), 37)
        self.assertTrue(all(x.converged for x in s.samples))
        np.testing.assert_array_equal(m.body("rocker").position, before)

    def test_sweep_locks_at_the_twist_limits(self):
        m = dispcon.Model()
        m.add_body("bar", position=(0.5, 0, 0))
        X = (1, 0, 0)
        m.add_joint("bar", hinge=((0, 0, 0), (-0.5, 0, 0)), angle=(Z, Z, 0, 0),
                    twist=(X, X, -0.5, 0.5))
        self.assertTrue(m.assemble().converged)
        for stop, limit in ((1.0, 0.5), (-1.0, -0.5)):
            s = m.sweep("bar", axis=Z, start=0.0, stop=stop, steps=100)
            self.assertTrue(s.locked, s.message)
            self.assertAlmostEqual(s.lock_value, limit, delta=1e-6)
            self.assertLess(len(s.samples), 101)
            self.assertEqual(s.samples[-1].limits_active, [0])

    def test_animated_pendulum_keeps_its_pivot_and_falls(self):
        m = dispcon.Model()
        m.add_body("bar", position=(0.5, 0, 0), mass=1.0, inertia=(0.01, 0.1, 0.1))
        m.add_joint("bar", hinge=((0, 0, 0), (-0.5, 0, 0)), angle=(Z, Z, 0, 0))
        a = m.animate(duration=0.2, dt=0.01, gravity=(0, -9.81, 0))
        self.assertTrue(a.converged, a.message)
        self.assertGreaterEqual(len(a.frames), 20)
        times = [f.time for f in a.frames]
        self.assertEqual(times, sorted(times))
        for f in a.frames:
            x, q = f.poses["bar"]
            pivot = x + quat_matrix(q) @ np.array([-0.5, 0, 0])
            np.testing.assert_allclose(pivot, [0, 0, 0], atol=1e-6)
        self.assertLess(a.frames[-1].poses["bar"][0][1], -1e-3)


class Files(unittest.TestCase):
    def test_to_dcl_round_trip(self):
        m = fourbar()
        m.assemble()
        again = dispcon.loads(m.to_dcl())
        self.assertEqual(again.body_names(), ["crank", "coupler", "rocker"])
        self.assertEqual(again.assemble().iterations, 0)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "m.dcl")
            m.save(path)
            np.testing.assert_allclose(dispcon.load(path).body("rocker").position,
                                       m.body("rocker").position, atol=1e-15)


def same_bits(m):
    """Every body's pose as raw bytes, to compare bit for bit."""
    return {n: (m.body(n).position.tobytes(), m.body(n).quaternion.tobytes()) for n in m.body_names()}


class Door(unittest.TestCase):
    """Every number enters through the engine's door: ValueError naming it (issue 13)."""

    def assert_refused(self, f, *words):
        with self.assertRaises(ValueError) as c:
            f()
        for w in words:
            self.assertIn(w, str(c.exception))

    def test_drag_targets(self):
        nan = float("nan")
        m = fourbar()
        before = same_bits(m)
        self.assert_refused(lambda: m.drag("crank", position=(nan, 0, 0)), "target")
        self.assert_refused(lambda: m.drag("crank", rotation=(nan, 0, 0)), "rotation")
        self.assert_refused(lambda: m.drag("crank", rotation=(0, 0, 0, 1)), "rotation")
        for bad in (np.eye(3) * 2, np.diag([1.0, 1.0, -1.0]), np.ones((3, 3))):
            self.assert_refused(lambda: m.drag("crank", rotation=bad), "not a rotation")
        d = m.dragger("crank")
        self.assert_refused(lambda: d.move_to(position=(nan, 0, 0)), "target")
        self.assert_refused(lambda: d.move_to(rotation=np.eye(3) * 2), "not a rotation")
        self.assertEqual(before, same_bits(m))

    def test_poses_and_options(self):
        nan = float("nan")
        m = fourbar()
        self.assert_refused(lambda: m.set_pose("crank", position=(nan, 0, 0)), "nan")
        self.assert_refused(lambda: m.set_pose("crank", rotation=(1e300, 0, 0)), "1e+300")
        self.assert_refused(lambda: m.assemble(relaxation=nan), "relaxation")
        self.assert_refused(lambda: m.assemble(time=nan), "time")
        self.assert_refused(lambda: m.assemble(tolerance=nan), "tolerance")
        self.assert_refused(lambda: m.assemble(max_iterations=2**40), "max_iterations")
        self.assert_refused(lambda: m.animate(1.0, 0.1, (nan, 0, 0)), "gravity")
        self.assert_refused(lambda: m.add_body("x", mass=1e-150), "mass")
        self.assert_refused(lambda: m.add_joint("crank", hinge=((1e155, 0, 0), (0, 0, 0))), "hinge")
        self.assertNotIn("x", m.body_names())

    def test_bodies_change_only_through_checked_setters(self):
        m = fourbar()
        with self.assertRaises((ValueError, AttributeError)):
            m.body("world").fixed = False
        self.assert_refused(lambda: setattr(m.body("crank"), "mass", float("nan")), "mass")
        self.assertIsNone(m.body("crank").mass)

    def test_load_a_directory_or_a_missing_file(self):
        self.assert_refused(lambda: dispcon.load(SRC), "directory")
        self.assert_refused(lambda: dispcon.load("/nonexistent/x.dcl"), "/nonexistent/x.dcl: error")

    def test_failed_drag_changes_nothing(self):
        m = dispcon.load(os.path.join(SRC, "samples", "bricard.dcl"))
        before = same_bits(m)
        r = m.drag("link2", position=(50, 50, 50), steps=1)
        self.assertFalse(r.converged)
        self.assertEqual(before, same_bits(m))

    def test_session_follows_the_model(self):
        m = fourbar()
        s = m.session()
        self.assertTrue(s.solve().converged)
        for _ in range(40):  # enough to move the joints' storage
            m.add_joint("rocker", hinge=((3, 0, 0), (0, 0, 0)), angle=(Z, Z, 0, 0))
        m.add_joint("crank", hinge=((5, 0, 0), (0, 0, 0)))  # cannot hold with the others
        r = s.solve()
        self.assertFalse(r.converged)
        self.assertEqual(len(r.constraints), m.joint_count())
class Vocabulary(unittest.TestCase):
    """The engine's joint table, read by name: kinds build, classify back and round-trip."""

    def test_every_kind_builds_classifies_back_and_round_trips(self):
        limits = {"turn": (-0.5, 0.5), "travel": (-1, 2), "cone": 0.4, "angle": (0.2, 0.3),
                  "distance": (1.5, 1.5)}
        names = [k["name"] for k in dispcon.joint_kinds()]
        self.assertEqual(len(names), len(set(names)))
        for k in ("fixed", "revolute", "slider", "cylindrical", "ball", "planar", "point_on_line",
                  "point_on_plane", "point_on_curve", "parallel", "perpendicular", "angle", "distance",
                  "gear", "belt", "rack", "screw"):
            self.assertIn(k, names)
        for row in dispcon.joint_kinds():
            with self.subTest(kind=row["name"]):
                m = dispcon.Model()
                m.add_body("a", position=(0.2, 0.1, 0))
                kw = {name: limits[name] for name in row["limits"]}
                if row["needs_curve"]:
                    kw["curve"] = [(0, 0, 0), (1, 0, 0), (1, 1, 0)]
                if row["coupling"]:
                    kw[row["coupling_args"][0]] = 0.5  # its ratio, radius or pitch
                # A rack travels across its pinion's axis.
                axis2 = (1, 0, 0) if row["name"] == "rack" else Z
                i = m.add_joint("a", kind=row["name"], point1=(0, 0, 0), point2=(0.1, 0, 0),
                                axis1=(0, 0, 2), axis2=axis2, label=row["title"], **kw)
                self.assertEqual(m.joint(i).kind, row["name"])
                back = dispcon.loads(m.to_dcl())
                self.assertEqual(back.joint(0).kind, row["name"])
                self.assertEqual(back.joint(0).label, row["title"])

    def test_the_pendulum_built_by_kind_solves_like_the_one_built_by_statements(self):
        by_kind = dispcon.Model()
        by_kind.add_body("bar", position=(0.3, 0.2, 0.1))
        by_kind.add_joint("bar", kind="revolute", point2=(-0.5, 0, 0))
        by_text = dispcon.Model()
        by_text.add_body("bar", position=(0.3, 0.2, 0.1))
        by_text.add_joint("bar", hinge=((0, 0, 0), (-0.5, 0, 0)), angle=(Z, Z, 0, 0))
        self.assertEqual(by_kind.to_dcl(), by_text.to_dcl())
        self.assertTrue(by_kind.assemble().converged)
        np.testing.assert_allclose(by_kind.body("bar").rotation @ (-0.5, 0, 0) + by_kind.body("bar").position,
                                   (0, 0, 0), atol=1e-9)

    def test_bad_kinds_and_keywords_raise_value_error(self):
        m = dispcon.Model()
        m.add_body("a")
        with self.assertRaisesRegex(ValueError, "unknown joint kind 'hinge'"):
            m.add_joint("a", kind="hinge")
        with self.assertRaisesRegex(ValueError, "revolute takes no travel limit"):
            m.add_joint("a", kind="revolute", travel=(0, 1))
        with self.assertRaisesRegex(ValueError, "angle needs its angle range"):
            m.add_joint("a", kind="angle")
        with self.assertRaisesRegex(ValueError, "not 'hinge'"):
            m.add_joint("a", kind="ball", hinge=((0, 0, 0), (0, 0, 0)))
        with self.assertRaisesRegex(ValueError, "not 'bogus'"):
            m.add_joint("a", bogus=1)
        with self.assertRaisesRegex(ValueError, "at most one translation guide"):
            m.add_joint("a", axial=(Z,), planar=(Z,))
        self.assertEqual(m.joint_count(), 0)

    def test_couplings_by_kind_and_by_statement_are_the_same_joint(self):
        rows = {r["name"]: r for r in dispcon.joint_kinds()}
        self.assertEqual(rows["gear"]["coupling_args"], ["ratio", "phase"])
        self.assertEqual(rows["rack"]["coupling_args"], ["radius", "phase"])
        self.assertEqual(rows["screw"]["coupling_args"], ["pitch", "left", "phase"])
        self.assertIsNone(rows["revolute"]["coupling"])
        gear = [c for c in dispcon.components() if c["keyword"] == "gear"][0]
        self.assertTrue(gear["coupling"])
        self.assertEqual([a[0] for a in gear["args"]], ["C1", "a1", "C2", "a2", "ratio", "phase"])
        cases = [
            (dict(kind="gear", ratio=2.0, phase=0.25), dict(gear=((0, 0, 0), Z, (1, 0, 0), Z, 2.0, 0.25))),
            (dict(kind="belt", ratio=0.5), dict(belt=((0, 0, 0), Z, (1, 0, 0), Z, 0.5))),
            (dict(kind="rack", radius=0.3, phase=0.0),
             dict(rack=((0, 0, 0), Z, (1, 0, 0), (0, 1, 0), 0.3, 0.0))),
            (dict(kind="screw", pitch=0.2, left=True, phase=0.0),
             dict(hinge=((0, 0, 0), (1, 0, 0)), axial=(Z,), angle=(Z, Z, 0, 0),
                  screw=((0, 0, 0), Z, (1, 0, 0), Z, 0.2, True, 0.0))),
        ]
        for by_kind, by_statement in cases:
            with self.subTest(kind=by_kind["kind"]):
                a, b = dispcon.Model(), dispcon.Model()
                for m in (a, b):
                    m.add_body("g", position=(2, 0, 0))
                axis2 = (0, 1, 0) if by_kind["kind"] == "rack" else Z
                a.add_joint("g", point2=(1, 0, 0), axis1=Z, axis2=axis2, **by_kind)
                b.add_joint("g", **by_statement)
                self.assertEqual(a.to_dcl(), b.to_dcl())
                self.assertEqual(a.joint(0).kind, by_kind["kind"])
                back = dispcon.loads(a.to_dcl())
                self.assertEqual(back.to_dcl(), a.to_dcl())

    def test_a_gear_pair_built_in_python_holds_its_ratio(self):
        # Two gears on the frame, radii 1 and 2 (ratio 2), the first dragged a quarter turn: the
        # second turns back by half as much.
        m = dispcon.Model()
        m.add_body("g1")
        m.add_body("g2", position=(3, 0, 0))
        m.add_joint("g1", kind="revolute")
        m.add_joint("g2", kind="revolute", point1=(3, 0, 0))
        m.add_joint("g2", object1="g1", kind="gear", point2=(0, 0, 0), ratio=0.5)
        self.assertEqual(m.check().dof, 1)
        m.body("g1").fixed = True
        m.set_pose("g1", rotation=(0, 0, math.pi / 2))
        self.assertTrue(m.solve().converged)
        self.assertAlmostEqual(m.body("g2").rotation_vector[2], -math.pi / 4, delta=1e-9)

    def test_a_couplings_phase_reads_back_as_the_model_holds_it(self):
        # JointInfo.phase: the phase given, or the one the model made at its poses, as the .dcl
        # writer records it; moved on with the turns; None for a joint that is no coupling.
        m = dispcon.Model()
        m.add_body("g1")
        m.add_body("g2", position=(3, 0, 0), rotation=(0, 0, 0.4))
        m.add_joint("g1", kind="revolute")
        m.add_joint("g2", kind="revolute", point1=(3, 0, 0))
        m.add_joint("g2", object1="g1", kind="gear", point2=(0, 0, 0), ratio=0.5)
        m.add_joint("g2", object1="g1", kind="belt", point2=(0, 0, 0), ratio=0.5, phase=0.25)
        self.assertIsNone(m.joint(0).phase)
        self.assertIsNone(m.joint(1)["phase"])
        self.assertEqual((m.joint(3).phase, m.joint(3)["phase"]), (0.25, 0.25))
        made = m.joint(2).phase
        self.assertIsInstance(made, float)
        self.assertIn("phase %s;" % format(made, ".17g"), m.to_dcl())
        # g2 taken a whole turn round: its wrapped turn drops 2 pi, which the phase takes up.
        for k in range(1, 9):
            m.set_pose("g2", position=(3, 0, 0), rotation=(0, 0, 0.4 + k * math.pi / 4))
        self.assertAlmostEqual(abs(m.joint(2).phase - made), 2 * math.pi, delta=1e-9)
        self.assertAlmostEqual(abs(m.joint(3).phase - 0.25), 2 * math.pi, delta=1e-9)

    def test_bad_coupling_arguments_raise_value_error_naming_them(self):
        m = dispcon.Model()
        m.add_body("a", position=(1, 0, 0))
        with self.assertRaisesRegex(ValueError, "gear needs its ratio"):
            m.add_joint("a", kind="gear")
        with self.assertRaisesRegex(ValueError, "gear ratio must be positive, found -1"):
            m.add_joint("a", kind="gear", ratio=-1)
        with self.assertRaisesRegex(ValueError, "ratio must be a number"):
            m.add_joint("a", kind="gear", ratio="two")
        with self.assertRaisesRegex(ValueError, "pitch must be a number"):
            m.add_joint("a", kind="screw", pitch=[1])
        with self.assertRaisesRegex(ValueError, "left must be True or False"):
            m.add_joint("a", kind="screw", pitch=1, left=1)
        with self.assertRaisesRegex(ValueError, r"add_joint\(kind='belt'\) takes .*, ratio, phase; not 'left'"):
            m.add_joint("a", kind="belt", ratio=1, left=True)
        with self.assertRaisesRegex(ValueError, "not 'left'"):
            m.add_joint("a", kind="revolute", left=True)
        with self.assertRaisesRegex(ValueError, r"kind='revolute'\) takes .*; not 'ratio'"):
            m.add_joint("a", kind="revolute", ratio=2)
        with self.assertRaisesRegex(ValueError, r"kind='rack'\) takes .*, radius, phase; not 'ratio'"):
            m.add_joint("a", kind="rack", ratio=2)
        with self.assertRaisesRegex(ValueError, "gear a2 is a zero vector"):
            m.add_joint("a", kind="gear", ratio=1, axis2=(0, 0, 0))
        with self.assertRaisesRegex(ValueError, "gear phase is not a number"):
            m.add_joint("a", kind="gear", ratio=1, phase=float("nan"))
        with self.assertRaisesRegex(ValueError, "the turn has no reference"):
            m.add_joint("a", kind="gear", ratio=1, point1=(1, 0, 0))
        with self.assertRaisesRegex(ValueError, "screw left must be True or False"):
            m.add_joint("a", screw=((0, 0, 0), Z, (0, 0, 0), Z, 1, "yes"))
        with self.assertRaisesRegex(ValueError, "gear needs at least 5 items"):
            m.add_joint("a", gear=((0, 0, 0), Z, (0, 0, 0), Z))
        self.assertEqual(m.joint_count(), 0)

    def test_crossed_bounds_say_what_was_refused(self):
        """A LimitError is the ValueError the command line's message is in, and says which
        bounds, as given, in which unit: a shell names them in its own words without checking
        them itself or reading the message."""
        m = dispcon.Model()
        m.add_body("a")
        with self.assertRaises(dispcon.LimitError) as caught:
            m.add_joint("a", kind="revolute", turn=(1.0472, 0.5))
        e = caught.exception
        self.assertIsInstance(e, ValueError)
        self.assertEqual(str(e), "constraint: twist: min 1.0472 is above max 0.5")
        self.assertEqual((e.statement, e.min, e.max, e.unit), ("twist", 1.0472, 0.5, "angle"))
        with self.assertRaises(dispcon.LimitError) as caught:
            m.add_joint("a", axial=(Z, 5, 2), label="rail")
        e = caught.exception
        self.assertEqual((e.statement, e.min, e.max, e.unit), ("axial", 5.0, 2.0, "length"))
        self.assertEqual(m.joint_count(), 0)
        # Other refusals stay plain ValueErrors.
        with self.assertRaises(ValueError) as caught:
            m.add_joint("a", axial=((0, 0, 0), 0, 1))
        self.assertNotIsInstance(caught.exception, dispcon.LimitError)

    def test_clamped_bounds_warn_instead_of_passing_silently(self):
        m = dispcon.Model()
        m.add_body("a")
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            m.add_joint("a", hinge=((0, 0, 0), (0, 0, 0)), angle=(Z, Z, 0, 9))
        self.assertEqual([w.category for w in caught], [dispcon.ModelWarning])
        self.assertIn("joint 0: angle max 9 is outside [0, 3.14159]; clamped to 3.14159",
                      str(caught[0].message))
        with warnings.catch_warnings():
            warnings.simplefilter("error", dispcon.ModelWarning)
            with self.assertRaises(dispcon.ModelWarning):
                dispcon.loads("object a; end\nconstraint object2 a; angle 0 0 1 0 0 1 max 9; end", "w.dcl")

    def test_names_the_format_cannot_hold_are_refused(self):
        m = dispcon.Model()
        with self.assertRaisesRegex(ValueError, "'y; fixed' cannot be written in a .dcl file"):
            m.add_body("y; fixed")
        self.assertEqual(m.body_names(), [])

    def test_labels_round_trip_whatever_they_hold(self):
        rng = random.Random(13)
        pieces = ["\n", '"', "\\", ";", "end", "object evil; fixed; end", "é", "🙂", "\x00", "\t",
                  "label \"", "/*", "//"]
        for _ in range(300):
            label = "".join(rng.choice(pieces) if rng.random() < 0.7 else chr(rng.randrange(1, 0x3000))
                            for _ in range(rng.randrange(0, 10)))
            m = dispcon.Model()
            m.add_body("bar")
            m.add_joint("bar", kind="ball", label=label)
            back = dispcon.loads(m.to_dcl())
            self.assertEqual(back.body_names(), ["bar"])
            self.assertEqual(back.joint(0).label, label)

    def test_defaults_are_the_engines(self):
        self.assertEqual(dispcon.DEFAULT_TOLERANCE, 1e-9)
        self.assertEqual(dispcon.DEFAULT_MAX_ITERATIONS, 10000)
        keywords = [c["keyword"] for c in dispcon.components()]
        self.assertEqual(keywords[:2], ["hinge", "axial"])
        angle = [c for c in dispcon.components() if c["keyword"] == "angle"][0]
        self.assertEqual(angle["bounds"], (0, math.pi))


class Include(unittest.TestCase):
    """Sub-models: dispcon.load follows `include`, flexible copies drag alone, rigid ones not."""

    def test_load_follows_includes_and_each_flexible_leg_drags_alone(self):
        m = dispcon.load(os.path.join(SRC, "samples", "legs.dcl"))
        names = m.body_names()
        self.assertIn("front_left.crank", names)
        self.assertIn("back_right.rocker", names)
        self.assertEqual(len(names), 1 + 4 * 3)
        self.assertEqual(m.check().dof, 4)
        before = same_bits(m)
        r = m.drag("front_right.crank", position=(0, 0, -1), rotation=(0, 0, math.pi / 2 + 0.5), steps=5)
        self.assertTrue(r.converged, r.message)
        after = same_bits(m)
        moved = sorted(n for n in names if after[n] != before[n])
        self.assertEqual(moved, ["front_right.coupler", "front_right.crank", "front_right.rocker"])

    def test_a_rigid_include_is_one_body_that_does_not_move(self):
        leg = os.path.join(SRC, "samples", "leg.dcl")
        m = dispcon.loads('include "%s" as stiff rigid;' % leg, "walker.dcl")
        self.assertEqual(m.body_names(), ["stiff"])
        self.assertEqual(m.check().dof, 0)
        before = same_bits(m)
        r = m.drag("stiff", rotation=(0, 0, 0.5), steps=3)
        self.assertFalse(r.converged)
        self.assertEqual(same_bits(m), before)
        with self.assertRaisesRegex(ValueError, r"walker.dcl:1:9: error: cannot include 'nowhere.dcl'"):
            dispcon.loads('include "nowhere.dcl" as n;', "walker.dcl")


if __name__ == "__main__":
    unittest.main()
