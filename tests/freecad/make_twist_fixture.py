"""Makes tests/freecad/data/twist-before.FCStd and twist-before.json: joints made askew by the
workbench as it was before TwistFrom existed (main at e05b94a, the fourteenth round's start),
which test_twist.py reopens with the workbench of now to find they mean what they meant. Run
once, with the old workbench and its dispcon module (kept as it was made; not part of the tests):

    DISPCON_WORKBENCH=/path/to/old/freecad_workbench DISPCON_PYTHONPATH=/path/to/old/build/python \
        DISPCON_MADE_WITH="main e05b94a" freecadcmd tests/freecad/make_twist_fixture.py

Two assemblies. "Askew": a link held to a grounded one by a Fixed joint on their bosses' circles,
made with the link turned 40 degrees about z and tipped 20 degrees about x, then moved off; the
old workbench's solve puts it back turned 40 degrees (its twist recorded at the making pose).
"SliderCrank": samples/freecad's slider-crank made in the sample's order, the Ball's solve
tipping the piston before the Slider is made: that workbench's solve cannot close it. The file
is saved before those last solves; the JSON holds what that workbench's solves then gave."""
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


def pin(o, x, z=0.0):
    return (o, parts.circle_edge(o.Shape, App.Vector(x, 0, z)))


def placement(pl):
    return {"base": list(pl.Base), "q": list(pl.Rotation.Q)}


def askew(doc):
    asm = da.create_assembly(doc, "Askew")
    asm.Label = "Askew"
    g = doc.addObject("Part::Feature", "Base")
    g.Shape = parts.link(1)
    da.add_part(asm, g, grounded=True)
    arm = doc.addObject("Part::Feature", "Arm")
    arm.Shape = parts.link(2)
    da.add_part(asm, arm)
    turned = App.Rotation(App.Vector(0, 0, 1), 40).multiply(App.Rotation(App.Vector(1, 0, 0), 20))
    arm.Placement = App.Placement(App.Vector(1.0, 0.05, 0.1), turned)
    da.add_joint(asm, "Fixed", pin(g, 1, 0.1), pin(arm, 0))
    arm.Placement = App.Placement(App.Vector(1.3, -0.2, 0.3), turned)  # off the joint: the solve brings it back
    return asm, arm


def slider_crank(doc):
    asm = da.create_assembly(doc, "SliderCrank")
    asm.Label = "SliderCrank"
    made = []
    for name, shape in (("Ground", parts.ground_with_rail([(0, 0)], (1.5, 5.0))), ("Crank", parts.link(1)),
                        ("Rod", parts.link(3)), ("Piston", parts.piston())):
        o = doc.addObject("Part::Feature", name)
        o.Shape = shape
        da.add_part(asm, o, grounded=name == "Ground")
        made.append(o)
    g, crank, rod, piston = made
    crank.Placement = App.Placement(App.Vector(0, 0, 0.15), App.Rotation(App.Vector(0, 0, 1), 30))
    rod.Placement = App.Placement(App.Vector(0.8, 0.5, 0.2), App.Rotation(App.Vector(0, 0, 1), -10))
    piston.Placement = App.Placement(App.Vector(3.5, 0.1, 0.1), App.Rotation())
    da.add_joint(asm, "Revolute", pin(g, 0, 0.1), pin(crank, 0))
    da.add_joint(asm, "Revolute", pin(crank, 1, 0.1), pin(rod, 0))
    assert da.solve(asm).converged
    da.add_joint(asm, "Ball", pin(rod, 3), (piston, parts.face_at_height(piston.Shape, 0.1)))
    assert da.solve(asm).converged
    da.add_joint(asm, "Slider", (g, parts.line_edge_along_x(g.Shape, -0.3, 0.1)),
                 (piston, parts.line_edge_along_x(piston.Shape, -0.2)))
    return asm, (crank, rod, piston)


doc = App.newDocument("twist_before")
asm1, arm = askew(doc)
asm2, moving = slider_crank(doc)
path = os.path.join(OUT, "twist-before.FCStd")
os.makedirs(OUT, exist_ok=True)
doc.saveAs(path)
facts = {"made_with": os.environ.get("DISPCON_MADE_WITH", "")}
r = da.solve(asm1)
facts["Askew"] = {"converged": r.converged, "Arm": placement(arm.Placement)}
r = da.solve(asm2)
facts["SliderCrank"] = {"converged": r.converged, "message": r.message,
                        **{o.Label: placement(o.Placement) for o in moving}}
with open(os.path.join(OUT, "twist-before.json"), "w") as f:
    json.dump(facts, f, indent=1, sort_keys=True)
    f.write("\n")
print("wrote", path, facts)
App.closeDocument(doc.Name)
sys.exit(0)
