"""Makes tests/freecad/data/cylindrical-before.FCStd and cylindrical-before.json: two Cylindrical
joints with turn and travel limits, made with their parts turned and lifted, by the workbench of
the fifteenth round's start (main 3d84d20, where a Cylindrical already had TwistFrom); test_twist.py
reopens the file with the workbench of now to find each keeps its meaning to 1e-9. Run once, with
that workbench and its dispcon module (kept as it was made; not part of the tests):

    DISPCON_WORKBENCH=/path/to/old/freecad_workbench DISPCON_PYTHONPATH=/path/to/old/build/python \
        DISPCON_MADE_WITH="main 3d84d20" freecadcmd tests/freecad/make_cylindrical_fixture.py

One assembly, "Sleeves": a grounded link (1 long) and two links (2 long) held by Cylindricals on
the bosses' circles, each limited to a turn of 0..90 degrees and a travel of 0..0.5 along the
axis, made with the link turned 40 degrees about z and lifted 0.2: Picked, its joint "Picked
sleeve" (TwistFrom "Picked frames": its turn counts from the circles' x's), and Posed, its joint
"Posed sleeve" ("Pose when made": from the 40 degrees it was made at). Then Picked is turned to
150 degrees and lifted 0.9, Posed turned to 10 and sunk 0.3, past their limits. The file is saved
before the solve; the JSON holds what that workbench's solve then gave."""
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


doc = App.newDocument("cylindrical_before")
asm = da.create_assembly(doc, "Sleeves")
asm.Label = "Sleeves"
base = doc.addObject("Part::Feature", "Base")
base.Shape = parts.link(1)
da.add_part(asm, base, grounded=True)
links = {}
for name, x, twist_from, turn, lift in (("Picked", 1, "Picked frames", 150, 0.9), ("Posed", 0, "Pose when made", 10, -0.3)):
    link = doc.addObject("Part::Feature", name)
    link.Shape = parts.link(2)
    da.add_part(asm, link)
    z = 0.1 if x else -0.1  # the one on the base's top, the other under it
    link.Placement = App.Placement(App.Vector(x, 0, z + 0.2), App.Rotation(Z, 40))
    j = da.add_joint(asm, "Cylindrical", pin(base, x, 0.1 if x else 0.0), pin(link, 0, 0.0 if x else 0.1),
                     rotation=(0, 90), travel=(0, 0.5), twist_from=twist_from)
    j.Label = name + " sleeve"
    link.Placement = App.Placement(App.Vector(x, 0, z + lift), App.Rotation(Z, turn))  # past the limits made
    links[name] = link
path = os.path.join(OUT, "cylindrical-before.FCStd")
os.makedirs(OUT, exist_ok=True)
doc.saveAs(path)
facts = {"made_with": os.environ.get("DISPCON_MADE_WITH", "")}
r = da.solve(asm)
facts["Sleeves"] = {"converged": r.converged, "message": r.message,
                    **{name: placement(o.Placement) for name, o in links.items()},
                    "TwistFrom": {j.Label: j.TwistFrom for j in da.joints(asm)}}
with open(os.path.join(OUT, "cylindrical-before.json"), "w") as f:
    json.dump(facts, f, indent=1, sort_keys=True)
    f.write("\n")
print("wrote", path, facts)
App.closeDocument(doc.Name)
sys.exit(0)
