"""What to pick for each joint type, in the words the joint commands' tooltips and the joint
panel use. Part 1 (picked first) carries the guide: the slider's line, the plane, the curve."""

PICK = {
    "Fixed": "two faces, edges or vertices, one on each part",
    "Revolute": "two circular edges or cylindrical faces, one on each part (the pin and its hole)",
    "Slider": "a straight edge or planar face of the guide, then a straight edge or face of the slider",
    "Cylindrical": "two circular edges or cylindrical faces (the shaft and its bore)",
    "Ball": "two spherical faces, or a vertex or circular edge at the ball's centre on each part",
    "Planar": "a planar face on each part (they stay on one plane)",
    "PointOnLine": "a straight edge of the guide, then a vertex or circular edge of the other part",
    "PointOnPlane": "a planar face of the guide, then a vertex or circular edge of the other part",
    "PointOnCurve": "an edge (the curve) of the guide, then a vertex or circular edge of the other part",
    "Angle": "two straight edges or planar faces (their directions), one on each part",
}

MOTION = {
    "Fixed": "no motion between the parts",
    "Revolute": "a turn about one axis",
    "Slider": "travel along one axis, no turn",
    "Cylindrical": "a turn about an axis and travel along it",
    "Ball": "turns about a point",
    "Planar": "slides and turns on a plane",
    "PointOnLine": "a point of part 2 stays on a line of part 1",
    "PointOnPlane": "a point of part 2 stays on a plane of part 1",
    "PointOnCurve": "a point of part 2 stays on a curve of part 1",
    "Angle": "bounds the angle between two axes",
}


def tooltip(kind):
    return ("%s joint: %s. Select %s, then run this; or run it with nothing selected and pick them "
            "in the 3D view." % (kind, MOTION[kind], PICK[kind]))
