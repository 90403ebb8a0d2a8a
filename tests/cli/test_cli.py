"""The dispcon command line against cli.md: exit codes, JSON, CSV, --write."""
import csv
import json
import math
import os
import random
import subprocess
import tempfile
import unittest

BIN = os.environ.get("DISPCON_BIN", "dispcon")
SRC = os.environ.get("DISPCON_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")


def run(*args):
    return subprocess.run([BIN, *args], capture_output=True, text=True, timeout=120)


class Assemble(unittest.TestCase):
    def test_json_has_the_documented_fields(self):
        r = run("assemble", os.path.join(DATA, "pendulum.dcl"), "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        doc = json.loads(r.stdout)
        for key in ("converged", "iterations", "max_residual", "bodies", "constraints"):
            self.assertIn(key, doc)
        self.assertTrue(doc["converged"])
        self.assertLessEqual(doc["max_residual"], 1e-9)
        bar = doc["bodies"]["bar"]
        self.assertEqual(len(bar["position"]), 3)
        self.assertEqual(len(bar["rotation"]), 3)
        self.assertEqual(len(bar["quaternion"]), 4)
        # The hinge holds: the bar's origin is at the world's origin.
        self.assertLess(math.dist(bar["position"], [0, 0, 0]), 1e-9)
        c = doc["constraints"][0]
        self.assertEqual((c["index"], c["line"], c["object1"], c["object2"]), (0, 3, "world", "bar"))
        self.assertTrue(c["satisfied"])

    def test_over_constrained_exits_3_and_names_the_constraints(self):
        r = run("assemble", os.path.join(DATA, "overconstrained.dcl"), "--json", "--max-iterations", "300")
        self.assertEqual(r.returncode, 3)
        doc = json.loads(r.stdout)
        self.assertFalse(doc["converged"])
        violated = [c["line"] for c in doc["constraints"] if not c["satisfied"]]
        self.assertEqual(violated, [3, 4])
        text = run("assemble", os.path.join(DATA, "overconstrained.dcl"), "--max-iterations", "300")
        self.assertIn("line 3", text.stdout)

    def test_bad_file_exits_2_with_file_line_col(self):
        r = run("assemble", os.path.join(DATA, "bad.dcl"))
        self.assertEqual(r.returncode, 2)
        self.assertIn("bad.dcl:4:1: error: expected ';' after hinge", r.stderr)
        self.assertEqual(r.stdout, "")

    def test_warnings_are_printed_and_the_file_still_solves(self):
        r = run("assemble", os.path.join(DATA, "warning.dcl"))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("warning.dcl:3:44: warning: angle max 9 is outside", r.stderr)
        self.assertIn("converged", r.stdout)

    def test_errors_are_capped_with_a_count_of_the_rest(self):
        with tempfile.TemporaryDirectory() as tmp:
            noise = os.path.join(tmp, "noise.dcl")
            with open(noise, "wb") as f:
                f.write(random.Random(5).randbytes(1 << 20))
            dup = os.path.join(tmp, "dup.dcl")
            with open(dup, "w") as f:
                f.write("object a; end\n" * 200000)
            for path, more in ((noise, None), (dup, "199899 more errors")):
                r = subprocess.run([BIN, "check", path], capture_output=True, timeout=120)
                self.assertEqual(r.returncode, 2)
                lines = r.stderr.decode("utf-8", "replace").splitlines()
                self.assertLessEqual(len(lines), 101)
                self.assertRegex(lines[-1], r": error: [0-9]+ more errors \(only the first 100 are listed\)$")
                if more:
                    self.assertIn(more, lines[-1])

    def test_a_huge_direction_is_a_direction_and_a_zero_one_is_placed(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "big.dcl")
            with open(path, "w") as f:
                f.write("object a; end\nconstraint object2 a;\n  axial 1e200 1e200 0; end\n")
            self.assertEqual(run("assemble", path).returncode, 0)
            with open(path, "w") as f:
                f.write("object a; end\nconstraint object2 a;\n  axial 0 0 0; end\n")
            r = run("assemble", path)
            self.assertEqual(r.returncode, 2)
            self.assertIn("big.dcl:3:9: error: axial u is a zero vector", r.stderr)

    def test_the_listing_is_printfs_fixed_point_to_the_last_digit(self):
        # Fixed bodies keep their positions bit for bit: ties at the seventh decimal (1/128 and
        # its negative, dyadic, so exactly halfway: to even), negative zero and a negative value
        # that rounds to zero, a number that rounds up past the column's width, and one in
        # exponent form (its name longer than the name's column); each line as C's
        # printf("%11.6f") writes it (Python's % rounds alike).
        xs = [0.0078125, -0.0078125, -0.0, -4e-7, 999999.9999996, 123456.5000005, 2.0 ** -20]
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "places.dcl")
            with open(path, "w") as f:
                for i, x in enumerate(xs):
                    f.write(f"object b{i}; fixed; position {x!r} {-x!r} 1e-9; end\n")
                f.write("object far_from_the_origin; fixed; position 2e6 0 0; end\n")
            r = run("assemble", path)
            self.assertEqual(r.returncode, 0, r.stderr)
            lines = r.stdout.splitlines()
            self.assertEqual(lines[1], "  body            position                                rotation vector")
            rot = "       %10.6f %10.6f %10.6f" % (0.0, 0.0, 0.0)
            for i, x in enumerate(xs):
                want = "  %-16s%11.6f %11.6f %11.6f" % (f"b{i}", x, -x, 1e-9) + rot
                self.assertEqual(lines[2 + i], want)
            self.assertEqual(lines[2 + len(xs)], "  %-16s%11.5g %11.5g %11.5g" % ("far_from_the_origin", 2e6, 0, 0) + rot)

    def test_defaults_are_the_engines(self):
        r = run("assemble", "--help")
        self.assertRegex(r.stdout, r"--tolerance \S*=1e-0?9\b")
        self.assertRegex(r.stdout, r"--max-iterations \S*=10000\b")

    def test_bad_usage_exits_2(self):
        self.assertEqual(run("assemble", os.path.join(DATA, "pendulum.dcl"), "--bogus").returncode, 2)
        self.assertEqual(run("frobnicate").returncode, 2)
        self.assertEqual(run().returncode, 2)
        r = run("drag", os.path.join(DATA, "pendulum.dcl"), "--body", "nobody", "--to", "0", "0", "0")
        self.assertEqual(r.returncode, 2)
        self.assertIn("unknown body 'nobody'", r.stderr)

    def test_write_round_trips(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "assembled.dcl")
            r = run("assemble", os.path.join(SRC, "samples", "monocycle.dcl"), "--write", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            again = json.loads(run("assemble", out, "--json").stdout)
            self.assertTrue(again["converged"])
            self.assertEqual(again["iterations"], 0)


class Drag(unittest.TestCase):
    def test_csv_has_a_row_per_body_per_step_and_the_bar_turns(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "steps.csv")
            r = run("drag", os.path.join(DATA, "pendulum.dcl"), "--body", "bar", "--to", "0", "0", "0",
                    "--rotation", "0", "0", "1.2", "--steps", "12", "--csv", path, "--json")
            self.assertEqual(r.returncode, 0, r.stderr)
            doc = json.loads(r.stdout)
            self.assertEqual(len(doc["steps"]), 12)
            with open(path) as f:
                rows = list(csv.reader(f))
            self.assertEqual(rows[0], ["step", "body", "px", "py", "pz", "qw", "qx", "qy", "qz"])
            self.assertEqual(len(rows), 1 + 12)
            qw, qz = float(rows[-1][5]), float(rows[-1][8])
            self.assertAlmostEqual(2 * math.atan2(qz, qw), 1.2, places=9)

    def test_text_summary_agrees_with_the_steps(self):
        args = ("drag", os.path.join(DATA, "pendulum.dcl"), "--body", "bar", "--to", "0", "0", "0",
                "--rotation", "0", "0", "2", "--steps", "8")
        steps = json.loads(run(*args, "--json").stdout)["steps"]
        text = run(*args).stdout
        line = next(l for l in text.splitlines() if l.startswith("iterations per step"))
        mean = float(line.split("mean ")[1].split(",")[0])
        worst = int(line.split("worst ")[1])
        self.assertAlmostEqual(mean, sum(s["iterations"] for s in steps) / len(steps), places=4)
        self.assertEqual(worst, max(s["iterations"] for s in steps))

    def test_unreachable_target_exits_3(self):
        r = run("drag", os.path.join(DATA, "pendulum.dcl"), "--body", "bar", "--to", "5", "0", "0",
                "--steps", "2", "--max-iterations", "200", "--json")
        self.assertEqual(r.returncode, 3)
        self.assertFalse(json.loads(r.stdout)["converged"])

    def test_drag_a_gear_train(self):
        r = run("drag", os.path.join(SRC, "samples", "three-gears.dcl"), "--body", "g1",
                "--to", "0", "0", "0", "--rotation", "0", "0", "3", "--steps", "30",
                "--tolerance", "1e-12", "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        bodies = json.loads(r.stdout)["bodies"]
        turn = {name: math.atan2(bodies[name]["rotation"][1][0], bodies[name]["rotation"][0][0])
                for name in ("g2", "g3")}
        self.assertAlmostEqual(turn["g2"], -1.5, delta=1e-11)  # -1/2 of g1's 3 rad
        self.assertAlmostEqual(turn["g3"], 2.0, delta=1e-11)  # 2/3 of it


    def test_drag_out_of_reach_tells_the_distance_left(self):
        # The robot arm's hand is at most 2.5 from the base's pivot (0.5 + 1 + 1 along its
        # links), so (5, 0.5, 0) is out of reach; its elbow never quite straightens (0.2 rad at
        # least), so the stretched arm breaks a limit and the hand is pulled, within a few dozen
        # iterations, to the nearest pose: 2 cos(0.1) from the shoulder at (0, 0.5, 0).
        r = run("drag", os.path.join(SRC, "samples", "robot-arm.dcl"), "--body", "hand",
                "--to", "5", "0.5", "0", "--steps", "1", "--json")
        self.assertEqual(r.returncode, 3, r.stderr)
        doc = json.loads(r.stdout)
        self.assertFalse(doc["converged"])
        self.assertEqual(doc["failed_step"], 0)
        step = doc["steps"][0]
        self.assertFalse(step["converged"])
        self.assertLessEqual(step["iterations"], 40)
        self.assertEqual(step["out_of_reach"]["body"], "hand")
        self.assertAlmostEqual(step["out_of_reach"]["distance_left"], 5 - 2 * math.cos(0.1),
                               delta=1e-9)
        self.assertIn("out of reach: 'hand'", doc["message"])
        self.assertIn("nearest pose", doc["message"])


class Check(unittest.TestCase):
    def test_pendulum_has_one_degree_of_freedom(self):
        r = run("check", os.path.join(DATA, "pendulum.dcl"), "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        doc = json.loads(r.stdout)
        self.assertEqual(doc["dof"], 1)
        self.assertEqual(doc["bodies"]["bar"]["dof"], 1)
        self.assertEqual(doc["redundant"], [])
        self.assertEqual(doc["conflicting"], [])

    def test_two_pins_one_unit_apart_conflict_and_exit_3(self):
        r = run("check", os.path.join(DATA, "overconstrained.dcl"), "--json", "--max-iterations", "300")
        self.assertEqual(r.returncode, 3)
        doc = json.loads(r.stdout)
        self.assertFalse(doc["converged"])
        self.assertEqual(len(doc["conflicting"]), 1)
        self.assertIn(doc["conflicting"][0], (0, 1))

    def test_planetary_set_has_two_degrees_of_freedom(self):
        r = run("check", os.path.join(SRC, "samples", "planetary.dcl"), "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        doc = json.loads(r.stdout)
        self.assertEqual(doc["dof"], 2)
        self.assertEqual(doc["locking"], [])

    def test_four_flexible_legs_have_four_degrees_of_freedom(self):
        r = run("check", os.path.join(SRC, "samples", "legs.dcl"), "--json")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(json.loads(r.stdout)["dof"], 4)


class Animate(unittest.TestCase):
    def test_frames_carry_their_time_and_the_csv_a_row_per_body_per_frame(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "frames.csv")
            svg = os.path.join(tmp, "frames.svg")
            r = run("animate", os.path.join(DATA, "pendulum.dcl"), "--duration", "0.1", "--dt", "0.02",
                    "--gravity", "0", "-9.81", "0", "--csv", path, "--svg", svg, "--json")
            self.assertEqual(r.returncode, 0, r.stderr)
            doc = json.loads(r.stdout)
            for key in ("converged", "iterations", "max_residual", "bodies", "constraints", "frames"):
                self.assertIn(key, doc)
            times = [f["time"] for f in doc["frames"]]
            self.assertAlmostEqual(times[-1], 0.1, places=12)
            self.assertTrue(all(b > a for a, b in zip(times, times[1:])))
            with open(path) as f:
                rows = list(csv.reader(f))
            self.assertEqual(rows[0], ["time", "body", "px", "py", "pz", "qw", "qx", "qy", "qz"])
            self.assertEqual(len(rows) - 1, len({row[0] for row in rows[1:]}))
            self.assertAlmostEqual(float(rows[-1][0]), 0.1, places=9)
            # The hinge holds in every frame: the bar's origin stays at the world's origin.
            for row in rows[1:]:
                self.assertLess(math.dist([float(v) for v in row[2:5]], [0, 0, 0]), 1e-9)
            with open(svg) as f:
                self.assertIn("<svg", f.read())

    def test_missing_time_step_is_bad_usage(self):
        r = run("animate", os.path.join(DATA, "pendulum.dcl"), "--duration", "1")
        self.assertEqual(r.returncode, 2)
        self.assertIn("--dt", r.stderr)


class Sweep(unittest.TestCase):
    def test_the_hinge_follows_the_driven_angle(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "sweep.csv")
            plot = os.path.join(tmp, "sweep.svg")
            r = run("sweep", os.path.join(DATA, "pendulum.dcl"), "--body", "bar", "--axis", "0", "0", "1",
                    "--from", "0", "--to", "1", "--steps", "4", "--csv", path, "--plot", plot)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(path) as f:
                rows = list(csv.reader(f))
            self.assertEqual(rows[0], ["value", "converged", "max_residual", "joint0"])
            self.assertEqual(len(rows), 1 + 5)
            for row in rows[1:]:
                self.assertEqual(row[1], "1")
                self.assertAlmostEqual(float(row[3]), float(row[0]), places=5)
            with open(plot) as f:
                self.assertIn("<svg", f.read())

    def test_turning_across_the_hinge_locks_and_exits_3(self):
        r = run("sweep", os.path.join(DATA, "pendulum.dcl"), "--body", "bar", "--axis", "1", "0", "0",
                "--from", "0", "--to", "1", "--steps", "4", "--json")
        self.assertEqual(r.returncode, 3)
        doc = json.loads(r.stdout)
        self.assertTrue(doc["locked"])
        self.assertLess(doc["lock_value"], 0.25)

    def test_unknown_body_is_bad_usage(self):
        r = run("sweep", os.path.join(DATA, "pendulum.dcl"), "--body", "world")
        self.assertEqual(r.returncode, 2)
        self.assertIn("unknown body 'world'", r.stderr)


if __name__ == "__main__":
    unittest.main()


class JsonLayout(unittest.TestCase):
    """Every subcommand's --json on every sample, byte for byte as nlohmann::json's dump(2) writes
    the same document (the command line built its documents with it before it wrote them as
    streams): keys sorted, the same indents, the same digits for every double."""

    def test_every_document_is_laid_out_as_nlohmann_writes_it(self):
        redump = os.environ.get("DISPCON_JSON_REDUMP")
        if not redump:
            self.skipTest("json_redump is built with the tests (DISPCON_JSON_REDUMP)")
        files = sorted(
            [os.path.join(SRC, "samples", f) for f in os.listdir(os.path.join(SRC, "samples")) if f.endswith(".dcl")]
            + [os.path.join(DATA, f) for f in os.listdir(DATA) if f.endswith(".dcl")])
        checked = 0
        for path in files:
            first = run("assemble", path, "--json")
            if not first.stdout:
                continue  # a file with errors prints no document
            bodies = json.loads(first.stdout)["bodies"]
            commands = [["assemble", path, "--json"], ["check", path, "--json"],
                        ["animate", path, "--json", "--duration", "0.05", "--dt", "0.01"]]
            if bodies:
                name, body = sorted(bodies.items())[-1]
                x, y, z = body["position"]
                commands.append(["drag", path, "--json", "--body", name, "--to", str(x + 0.01), str(y), str(z),
                                 "--steps", "3"])
                commands.append(["sweep", path, "--json", "--body", name, "--steps", "12"])
            for args in commands:
                out = run(*args).stdout
                again = subprocess.run([redump], input=out, capture_output=True, text=True, timeout=60)
                self.assertEqual(again.returncode, 0, (args, again.stderr))
                self.assertEqual(out, again.stdout, args)
                checked += 1
        self.assertGreater(checked, 50)
