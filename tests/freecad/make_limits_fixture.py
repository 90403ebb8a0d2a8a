"""Makes tests/freecad/data/limits-before.FCStd and limits-before.json: Revolute joints with turn
limits made with their part turned, by the workbench as it was before TwistFrom existed (main at
e05b94a, the fourteenth round's start), whose limits counted from the pose when made; test_twist.py
reopens the file with the workbench of now to find they count from there still. Run once, with the
old workbench and a dispcon module (kept as it was made; not part of the tests):

    DISPCON_WORKBENCH=/path/to/old/freecad_workbench DISPCON_PYTHONPATH=/path/to/old/build/python \
        DISPCON_MADE_WITH="main e05b94a" freecadcmd tests/freecad/make_limits_fixture.py

One assembly, "Limited": a grounded link (1 long) and two links (2 long) held by Revolutes on
the bosses' circles, each with its turn limited to 0..90 degrees, made with the link turned 40
degrees about z (so the old workbench's limits are 40..130 degrees of the link's turn); then
Below is turned to 10 degrees and Above to 150, past those limits. The file is saved before the
solve; the JSON holds what that workbench's solve then gave (each link at its nearer limit)."""
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.environ.get("DISPCON_WORKBENCH", os.path.join(REPO, "freecad_workbench")))
sys.path.insert(0, os.path.join(REPO, "samples", "freecad"))

import FreeCAD as App  # noqa: E402

import dispcon_fc.assembly as da  # noqa: E402
import parts  # noqa: E402

OUT = os.path.join(HERE, "data")
Z = App.Vector(0, 0, 1)


def pin(o, x, z=0.0):
    return (o, parts.circle_edge(o.Shape, App.Vector(x, 0, z)))


def placement(pl):
    return {"base": list(pl.Base), "q": list(pl.Rotation.Q)}


doc = App.newDocument("limits_before")
asm = da.create_assembly(doc, "Limited")
asm.Label = "Limited"
base = doc.addObject("Part::Feature", "Base")
base.Shape = parts.link(1)
da.add_part(asm, base, grounded=True)
arms = {}
for name, x, then in (("Below", 0, 10), ("Above", 1, 150)):
    arm = doc.addObject("Part::Feature", name)
    arm.Shape = parts.link(2)
    da.add_part(asm, arm)
    z = 0.1 if x else -0.1  # the one on the base's top, the other under it
    arm.Placement = App.Placement(App.Vector(x, 0, z), App.Rotation(Z, 40))
    da.add_joint(asm, "Revolute", pin(base, x, 0.1 if x else 0.0), pin(arm, 0, 0.0 if x else 0.1),
                 rotation=(0, 90))
    arm.Placement = App.Placement(App.Vector(x, 0, z), App.Rotation(Z, then))  # past the limits made
    arms[name] = arm
path = os.path.join(OUT, "limits-before.FCStd")
os.makedirs(OUT, exist_ok=True)
doc.saveAs(path)
facts = {"made_with": os.environ.get("DISPCON_MADE_WITH", "")}
r = da.solve(asm)
facts["Limited"] = {"converged": r.converged, "message": r.message,
                    **{name: placement(o.Placement) for name, o in arms.items()}}
with open(os.path.join(OUT, "limits-before.json"), "w") as f:
    json.dump(facts, f, indent=1, sort_keys=True)
    f.write("\n")
print("wrote", path, facts)
App.closeDocument(doc.Name)
sys.exit(0)
