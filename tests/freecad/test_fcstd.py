"""`dispcon check|sweep|drag|assemble FILE.FCStd`, run for real: the command line hands the
documents to freecadcmd. On the FreeCAD samples (STEP parts, samples/freecad/build_samples.py)
and on documents with known answers made by make_fcstd_docs.py: degrees of freedom, a
conflicting joint named by its label, the lock-up of a double rocker against the closure
formula, a collision placed at a known angle found within one sweep step, a slider driven to
where its rod stretches, written documents, and bad documents refused with exit 2.

Environment: DISPCON_BIN (the dispcon program), DISPCON_FCSTD_DOCS (what make_fcstd_docs.py
and build_samples.py wrote)."""
import json
import math
import os
import shutil
import subprocess
import tempfile
import unittest
import xml.etree.ElementTree as ET
import zipfile

BIN = os.environ["DISPCON_BIN"]
DOCS = os.environ["DISPCON_FCSTD_DOCS"]
with open(os.path.join(DOCS, "facts.json")) as f:
    FACTS = json.load(f)


def doc(name):
    return os.path.join(DOCS, name + ".FCStd")


def run(*args):
    p = subprocess.run([BIN] + [str(a) for a in args], capture_output=True, text=True, timeout=600)
    return p.returncode, p.stdout, p.stderr


def run_json(*args):
    code, out, err = run(*args, "--json")
    try:
        return code, json.loads(out), err
    except ValueError:
        raise AssertionError("not one JSON document (exit %d): %r\n%s" % (code, out[:500], err))


def near_angle(a, b):
    return abs(math.remainder(a - b, 2 * math.pi))


class Check(unittest.TestCase):
    def test_samples_dof_per_part_and_clearance(self):
        expected = {"fourbar": (1, {"Ground": 0, "Crank": 1, "Coupler": 1, "Rocker": 1}),
                    "slider-crank": (1, {"Ground": 0, "Crank": 1, "Rod": 1, "Piston": 1}),
                    "side-rods": (1, {"Ground": 0, "SideRod": 1, "Crank7": 1})}
        for name, (dof, parts) in expected.items():
            code, r, err = run_json("check", doc(name))
            self.assertEqual(code, 0, (name, err, r.get("interference")))
            self.assertTrue(r["converged"])
            self.assertEqual(r["dof"], dof, name)
            for label, d in parts.items():
                self.assertEqual(r["bodies"][label]["dof"], d, (name, label))
            self.assertEqual(r["conflicting"], [])
            self.assertEqual(r["interference"], [], name)
            # The .dcl check's keys, joints named by label.
            for key in ("iterations", "max_residual", "message", "constraints", "redundant",
                        "limits_active", "advice", "diagnosis"):
                self.assertIn(key, r)
            self.assertTrue(all(c["satisfied"] for c in r["constraints"]))
            self.assertEqual(r["constraints"][0]["label"], "Revolute")
        # The leg used four times, linked from leg.FCStd: each flexible leg a four-bar (1 DOF
        # each), each rigid one bolted on (6 - 6 = 0); the legs touch the frame, not each other.
        for name, dof, parts in (("walker", 4, {"Frame": 0, "Leg1.Hip": 0, "Leg1.Crank": 1, "Leg4.Rocker": 1}),
                                 ("walker-rigid", 0, {"Frame": 0, "Leg1": 0, "Leg4": 0})):
            code, r, err = run_json("check", doc(name))
            self.assertEqual((code, r["dof"], r["interference"]), (0, dof, []), (name, err))
            for label, d in parts.items():
                self.assertEqual(r["bodies"][label]["dof"], d, (name, label))
            self.assertEqual(r["constraints"][-1]["label"], "Leg4.Revolute003" if dof else "Fixed003")
        # The side rods repeat the first crank's constraints: every further crank's second pin.
        code, r, _ = run_json("check", doc("side-rods"))
        self.assertEqual(len(r["redundant"]), 17)

    def test_conflicting_joint_named_by_label(self):
        code, r, err = run_json("check", doc("conflicting"))
        self.assertEqual(code, 3)
        self.assertFalse(r["converged"])
        self.assertEqual(r["conflicting"], ["Unreachable pin"])
        self.assertTrue(any("'Unreachable pin'" in a for a in r["advice"]), r["advice"])
        code, out, err = run("check", doc("conflicting"))
        self.assertEqual(code, 3)
        self.assertIn("conflicting: 'Unreachable pin'", out)

    def test_overlap_at_the_assembled_pose_with_volume(self):
        # RSSR's flat links meet at their ball joints: the tilted rod's bosses dip into the crank's
        # and the rocker's, and the check says by how much; the ground, far below, is clear.
        code, r, _ = run_json("check", doc("rssr"))
        self.assertEqual(code, 3)
        pairs = {tuple(h["parts"]): h["volume"] for h in r["interference"]}
        self.assertIn(("Crank", "Rod"), pairs)
        self.assertIn(("Rod", "Rocker"), pairs)
        self.assertTrue(all(0 < v < 0.01 for v in pairs.values()), pairs)
        self.assertFalse([p for p in pairs if "Ground" in p])
        code, r, _ = run_json("check", doc("rssr"), "--no-interference")
        self.assertEqual((code, r["interference"], r["dof"]), (0, [], 2))


class Sweep(unittest.TestCase):
    def test_one_leg_of_the_walker_turns_the_others_stay(self):
        # A joint of a flexible sub-assembly, named as its instance's: leg 3's crank, a full turn.
        code, r, err = run_json("sweep", doc("walker"), "--joint", "Leg3.Revolute", "--steps", 24)
        self.assertEqual(code, 0, err)
        self.assertFalse(r["locked"])
        self.assertTrue(all(sample["converged"] for sample in r["samples"]))
        labels = [j["label"] for j in r["joints"]]
        column = lambda label: [sample["joint_values"][labels.index(label)] for sample in r["samples"]]  # noqa: E731
        self.assertGreater(max(column("Leg3.Revolute")) - min(column("Leg3.Revolute")), 6.0)
        for other in ("Leg1.Revolute", "Leg2.Revolute001", "Leg4.Revolute003"):
            values = column(other)
            self.assertLess(max(values) - min(values), 1e-9, other)

    def test_lock_up_of_a_double_rocker_against_the_closure(self):
        f = FACTS["double-rocker"]
        code, r, err = run_json("sweep", doc("double-rocker"), "--joint", "CrankPivot")
        self.assertEqual(code, 3, err)
        self.assertTrue(r["locked"])
        # The joint's value is the crank's turn from the picked frames (the pins' circles' x's, the
        # parts' x), its angle about z, whatever crank_deg it was placed at.
        crank = r["lock_value"]
        self.assertLess(near_angle(crank, f["stretched"]), 1e-6, (crank, f["stretched"]))
        self.assertIn("locks at", r["message"])
        # And the other way, down to the folded pose.
        code, r, err = run_json("sweep", doc("double-rocker"), "--joint", "CrankPivot",
                                "--from", math.radians(f["crank_deg"]),
                                "--to", math.radians(f["crank_deg"]) - math.pi, "--steps", 90)
        self.assertEqual(code, 3, err)
        crank = r["lock_value"]
        self.assertLess(near_angle(crank, f["folded"]), 1e-6, (crank, f["folded"]))

    def test_collision_at_a_known_angle_within_one_step(self):
        f = FACTS["obstacle"]
        steps = 360
        code, r, err = run_json("sweep", doc("obstacle"), "--joint", "CrankPivot", "--steps", steps)
        self.assertEqual(code, 3, err)
        self.assertFalse(r["locked"])
        hits = {tuple(h["parts"]): h for h in r["interference"]}
        self.assertEqual(list(hits), [("Crank", "Pole")], r["interference"])
        h = hits[("Crank", "Pole")]
        step = 2 * math.pi / steps
        first = math.degrees(h["first"])  # the crank's angle about z: its turn from the picked frames
        last = math.degrees(h["last"])
        self.assertLessEqual(abs(math.remainder(math.radians(first - f["first"]), 2 * math.pi)), step, (first, f))
        self.assertLessEqual(abs(math.remainder(math.radians(last - f["last"]), 2 * math.pi)), step, (last, f))
        self.assertGreater(h["worst_volume"], 0)
        colliding = [s for s in r["samples"] if s["colliding"]]
        self.assertTrue(all(s["colliding"] == [["Crank", "Pole"]] for s in colliding))
        self.assertLessEqual(abs(len(colliding) - (f["last"] - f["first"])), 2)

    def test_every_joint_value_csv_plot_and_animation(self):
        with tempfile.TemporaryDirectory() as tmp:
            csv, plot, svg = (os.path.join(tmp, n) for n in ("s.csv", "plot.svg", "motion.svg"))
            code, r, err = run_json("sweep", doc("fourbar-clash"), "--joint", "Revolute", "--steps", 120,
                                    "--csv", csv, "--plot", plot, "--svg", svg, "--view", "xy")
            self.assertEqual(code, 3, err)
            self.assertEqual([h["parts"] for h in r["interference"]], [["Crank", "Stop"], ["Coupler", "Stop"]]
                             if r["interference"][0]["parts"][0] == "Crank" else
                             [["Coupler", "Stop"], ["Crank", "Stop"]])
            self.assertEqual(len(r["samples"]), 121)
            # The one line counts in words: two pairs collide (one "pair ... collides").
            self.assertIn("; 2 pairs of parts collide: ", r["message"])
            self.assertEqual([j["label"] for j in r["joints"]], ["Revolute", "Revolute001", "Revolute002", "Revolute003"])
            first, last = r["samples"][0], r["samples"][-1]
            # The driven joint reads the driven value; a full turn brings every joint back.
            for s in r["samples"]:
                self.assertAlmostEqual(s["joint_values"][0], s["value"], places=7)
            for a, b in zip(first["joint_values"][1:], last["joint_values"][1:]):
                self.assertLess(near_angle(a, b), 1e-6)
            with open(csv) as f:
                rows = f.read().splitlines()
            self.assertEqual(rows[0], "value,converged,max_residual,colliding,Revolute,Revolute001,Revolute002,Revolute003")
            self.assertEqual(len(rows), 122)
            self.assertEqual(ET.parse(plot).getroot().tag, "{http://www.w3.org/2000/svg}svg")
            root = ET.parse(svg).getroot()
            ns = "{http://www.w3.org/2000/svg}"
            paths = [p for p in root.iter(ns + "path") if p.get("id", "").startswith("part")]
            self.assertEqual([p.get("data-label") for p in paths], ["Ground", "Crank", "Coupler", "Rocker", "Stop"])
            for p in paths:
                # Every moving part's outline changes from frame to frame; the still ones have none.
                moves = [a for a in p.iter(ns + "animate") if a.get("attributeName") == "d"]
                self.assertEqual(len(moves), 0 if p.get("data-label") in ("Ground", "Stop") else 1)
                for m in moves:
                    self.assertEqual(len(m.get("values").split(";")), 121)
                    self.assertGreater(len(set(m.get("values").split(";"))), 100)
            # The colliding parts turn red at some frames; the ground never.
            red = {p.get("data-label") for p in paths for a in p.iter(ns + "animate")
                   if a.get("attributeName") == "stroke" and "#d62728" in a.get("values")}
            self.assertEqual(red, {"Crank", "Coupler", "Stop"})

    def test_slider_driven_to_where_the_rod_stretches(self):
        # The piston's wrist pin runs on y = -0.1; the rod (3) and crank (1) stretch when it is at
        # x = sqrt(4^2 - 0.1^2); the slider's value is the pin's x less the guide's midpoint 3.25.
        code, r, err = run_json("sweep", doc("slider-crank"), "--joint", "Slider", "--from", 0, "--to", 1.2,
                                "--steps", 60)
        self.assertEqual(code, 3, err)
        self.assertTrue(r["locked"])
        self.assertAlmostEqual(r["lock_value"], math.sqrt(16 - 0.01) - 3.25, places=6)
        self.assertEqual(r["kind"], "travel")

    def test_unknown_joint_is_bad_usage(self):
        code, out, err = run("sweep", doc("fourbar"), "--joint", "Nope")
        self.assertEqual(code, 2)
        self.assertIn("no joint labelled 'Nope'", err)
        self.assertIn(doc("fourbar"), err)


class Write(unittest.TestCase):
    def test_assemble_and_drag_write_a_new_document_only(self):
        with tempfile.TemporaryDirectory() as tmp:
            src = os.path.join(tmp, "fourbar.FCStd")
            shutil.copy(doc("fourbar"), src)
            with open(src, "rb") as f:
                before = f.read()
            out = os.path.join(tmp, "dragged.FCStd")
            svg = os.path.join(tmp, "drag.svg")
            code, r, err = run_json("drag", src, "--body", "Coupler", "--to", 0.5, 1.2, 0.2, "--steps", 20,
                                    "--write", out, "--svg", svg)
            self.assertIn(code, (0, 3), err)
            self.assertEqual(len(r["steps"]), 20 if code == 0 else r["failed_step"])
            with open(src, "rb") as f:
                self.assertEqual(f.read(), before, "the input was changed")
            if code == 0:
                self.assertTrue(zipfile.is_zipfile(out))
                code, c, err = run_json("check", out)
                self.assertEqual(code, 0, err)
                self.assertEqual(c["iterations"], 0)
            self.assertTrue(os.path.exists(svg))
            # Writing over the input needs --in-place.
            code, _, err = run("assemble", src, "--write", src)
            self.assertEqual(code, 2)
            self.assertIn("--in-place", err)
            code, r, err = run_json("assemble", src, "--write", os.path.join(tmp, "a.FCStd"))
            self.assertEqual(code, 0, err)
            self.assertEqual(r["status"], "converged")
            # A document that cannot be written is an error naming it, not a silent success.
            code, out, err = run("assemble", src, "--write", "/proc/a.FCStd")
            self.assertEqual((code, out), (2, ""))
            self.assertIn("/proc/a.FCStd: error: cannot write the document", err)


class BadInput(unittest.TestCase):
    def assertRefused(self, path, *words):
        code, out, err = run("check", path)
        self.assertEqual(code, 2, (out, err))
        self.assertEqual(out, "")
        self.assertIn(path + ": error: ", err)
        for w in words:
            self.assertIn(w, err)

    def test_missing_file(self):
        self.assertRefused(os.path.join(DOCS, "nowhere.FCStd"), "no such file")

    def test_damaged_zip(self):
        with tempfile.TemporaryDirectory() as tmp:
            bad = os.path.join(tmp, "damaged.FCStd")
            with open(doc("fourbar"), "rb") as f:
                data = f.read()
            with open(bad, "wb") as f:
                f.write(data[: len(data) // 2])
            self.assertRefused(bad, "damaged")

    def test_not_an_assembly(self):
        self.assertRefused(doc("not-an-assembly"), "not a dispcon assembly", "'Just a box'")

    def test_linked_file_gone(self):
        self.assertRefused(doc("linked-gone"), "'Borrowed bar'", "library-gone.FCStd#LibraryBar")

    def test_freecad_missing(self):
        env = dict(os.environ, PATH="/nonexistent", DISPCON_FREECADCMD="")
        p = subprocess.run([BIN, "check", doc("fourbar")], capture_output=True, text=True, env=env)
        self.assertEqual(p.returncode, 2)
        self.assertIn("freecadcmd", p.stderr)

    def test_bad_usage_before_freecad_starts(self):
        code, out, err = run("sweep", doc("fourbar"), "--joint", "Revolute", "--view", "sideways")
        self.assertEqual(code, 2)
        code, out, err = run("sweep", doc("fourbar"))
        self.assertEqual(code, 2)
        self.assertIn("--joint", err)


if __name__ == "__main__":
    unittest.main()
