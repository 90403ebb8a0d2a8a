"""Every number enters through the engine's door: the command line only translates its refusal
(exit 2, the message on standard error). The reproducers of issue 13."""
import os
import subprocess
import tempfile
import unittest

BIN = os.environ.get("DISPCON_BIN", "dispcon")
SRC = os.environ.get("DISPCON_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")
PENDULUM = os.path.join(DATA, "pendulum.dcl")
MONOCYCLE = os.path.join(SRC, "samples", "monocycle.dcl")


def run(*args):
    return subprocess.run([BIN, *args], capture_output=True, text=True, timeout=120)


def dcl(text):
    f = tempfile.NamedTemporaryFile("w", suffix=".dcl", delete=False)
    f.write(text)
    f.close()
    return f.name


class Door(unittest.TestCase):
    def refused(self, args, *words):
        r = run(*args)
        self.assertEqual(r.returncode, 2, (args, r.stdout, r.stderr))
        self.assertNotIn("converged", r.stdout)
        for w in words:
            self.assertIn(w, r.stderr, args)
        return r

    def test_drag_targets(self):
        self.refused(["drag", PENDULUM, "--body", "bar", "--to", "nan", "0", "0"], "target", "nan")
        self.refused(["drag", PENDULUM, "--body", "bar", "--to", "0", "0", "0",
                      "--rotation", "nan", "0", "0"], "rotation")
        self.refused(["drag", PENDULUM, "--body", "bar", "--to", "0", "0", "0",
                      "--rotation", "1e300", "0", "0"], "1e+300")

    def test_solve_options(self):
        self.refused(["assemble", PENDULUM, "--tolerance", "nan"], "tolerance")
        self.refused(["assemble", PENDULUM, "--tolerance", "0"], "tolerance")
        self.refused(["assemble", PENDULUM, "--max-iterations", "0"], "max_iterations")

    def test_animate_options(self):
        self.refused(["animate", MONOCYCLE, "--duration", "1", "--dt", "0.1",
                      "--gravity", "nan", "0", "0"], "gravity")
        self.refused(["animate", MONOCYCLE, "--duration", "nan", "--dt", "0.1"], "duration")
        self.refused(["animate", MONOCYCLE, "--duration", "1", "--dt", "1e-300"], "frames")
        # UBSan used to flag the frame count's cast to int ("0 frames", exit 0).
        self.refused(["animate", MONOCYCLE, "--duration", "1e12", "--dt", "1"], "1e+12 frames")

    def test_sweep_range(self):
        self.refused(["sweep", os.path.join(SRC, "samples", "fourbar.dcl"), "--body", "crank",
                      "--from", "nan"], "from")

    def test_file_values_are_placed(self):
        for text, place in [
            ("object a; end\nconstraint object2 a;\n hinge 1e155 0 0 0 0 0; end\n", ":3:8:"),
            ("object a;\n rotate 1e300; end\n", ":2:2:"),
            ("object a;\n mass 1; inertia 1e-150 1e-150 1e-150; end\n", ":2:10:"),
            ("object a;\n mass 1; inertia 1e300 1e300 1e300; end\n", ":2:10:"),
            ("object a; mass 1; inertia 1 1 1;\n velocity 1e300 0 0; end\n", ":2:2:"),
        ]:
            path = dcl(text)
            try:
                r = self.refused(["assemble", path], path + place)
                self.assertNotIn("e+300000", r.stderr)
            finally:
                os.unlink(path)

    def test_numbers_are_readable(self):
        path = dcl("object a;\n rotate 1e300; end\n")
        try:
            r = run("assemble", path)
            self.assertIn("1e+300", r.stderr)
            self.assertLess(max(len(w) for w in r.stderr.split()), 60, r.stderr)
        finally:
            os.unlink(path)
        # A pose far away prints in exponent form, not with 150 digits.
        path = dcl("object a; position 1e14 0 0; end\n")
        try:
            r = run("assemble", path)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertIn("1e+14", r.stdout)
        finally:
            os.unlink(path)

    def test_write_to_a_full_disk_fails(self):
        if not os.path.exists("/dev/full"):
            self.skipTest("no /dev/full")
        self.refused(["assemble", PENDULUM, "--write", "/dev/full"], "/dev/full")

    def test_directory_and_missing_file(self):
        r = self.refused(["assemble", DATA], DATA, "directory")
        r = self.refused(["assemble", "/nonexistent/x.dcl"], "/nonexistent/x.dcl: error: cannot open")
        self.assertNotIn(":0:0:", r.stderr)


if __name__ == "__main__":
    unittest.main()
