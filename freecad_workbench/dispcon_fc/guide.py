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
    "Distance": "a vertex, a straight or circular edge or a planar face on each part (points, lines, planes)",
    "Parallel": "two straight edges or planar faces (their directions), one on each part",
    "Perpendicular": "two straight edges or planar faces (their directions), one on each part",
    "Angle": "two straight edges or planar faces (their directions), one on each part",
    "Gears": "a circular edge or cylindrical face on each gear (its pitch circle gives the ratio)",
    "Belt": "a circular edge or cylindrical face on each pulley (their radii give the ratio)",
    "RackPinion": "a circular edge on the pinion, then a straight edge or planar face of the rack along its travel",
    "Screw": "a circular edge or cylindrical face on the screw, then one on the nut",
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
    "Distance": "keeps two points, lines or planes at a distance",
    "Parallel": "keeps two edges or faces parallel",
    "Perpendicular": "keeps two edges or faces at right angles",
    "Angle": "bounds the angle between two axes",
    "Gears": "two gears in mesh: part 2 turns the other way, ratio times part 1's turn",
    "Belt": "two pulleys on a belt: part 2 turns the same way, ratio times part 1's turn",
    "RackPinion": "the rack travels the pinion's radius times its turn",
    "Screw": "the nut travels a pitch along the screw per turn (a cylindrical pair and the thread)",
}


def tooltip(kind):
    return ("%s joint: %s. Select %s, then run this; or run it with nothing selected and pick them "
            "in the 3D view." % (kind, MOTION[kind], PICK[kind]))
