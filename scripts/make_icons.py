#!/usr/bin/env python3
"""Writes the Dispcon workbench's SVG icons into freecad_workbench/Resources/icons/.

The icons follow FreeCAD's own artwork (the Part and Assembly icons): a 64x64 canvas, the Tango
palette, faces filled with linear gradients from light to dark, a 2 px dark outline in the
colour's darkest shade and a lighter inner line. They are drawn from a few shapes here so that the
joint icons and the 3D markers (dispcon_fc/markers.py) speak the same language: blue is part 1
(the guide), yellow part 2, orange a turn about an axis, green the direction of travel.

Run it after changing a shape; the SVG files it writes are committed (FreeCAD reads them).
"""
import math
import os
import sys

OUT = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                   "freecad_workbench", "Resources", "icons")

# Tango shades: light, mid, dark, outline.
PALETTE = {
    "blue": ("#729fcf", "#3465a4", "#204a87", "#0b1521"),
    "yellow": ("#fce94f", "#edd400", "#c4a000", "#302b00"),
    "red": ("#ef2929", "#cc0000", "#a40000", "#280000"),
    "green": ("#8ae234", "#73d216", "#4e9a06", "#172a04"),
    "grey": ("#eeeeec", "#babdb6", "#888a85", "#2e3436"),
    "orange": ("#fcaf3e", "#f57900", "#ce5c00", "#271700"),
    "dark": ("#888a85", "#555753", "#2e3436", "#0b1521"),
}


class Icon:
    def __init__(self, name, title):
        self.name, self.title = name, title
        self.defs, self.body, self.n = [], [], 0

    def grad(self, colour, x1, y1, x2, y2, light=0, dark=2):
        """A linear gradient of `colour` from shade `light` at (x1, y1) to `dark` at (x2, y2)."""
        self.n += 1
        gid = "%s_g%d" % (self.name, self.n)
        c = PALETTE[colour]
        self.defs.append(
            '<linearGradient id="%s" gradientUnits="userSpaceOnUse" x1="%g" y1="%g" x2="%g" y2="%g">'
            '<stop offset="0" style="stop-color:%s"/><stop offset="1" style="stop-color:%s"/>'
            '</linearGradient>' % (gid, x1, y1, x2, y2, c[light], c[dark]))
        return "url(#%s)" % gid

    def radial(self, colour, cx, cy, r):
        self.n += 1
        gid = "%s_g%d" % (self.name, self.n)
        c = PALETTE[colour]
        self.defs.append(
            '<radialGradient id="%s" gradientUnits="userSpaceOnUse" cx="%g" cy="%g" r="%g" fx="%g" fy="%g">'
            '<stop offset="0" style="stop-color:%s"/><stop offset="0.5" style="stop-color:%s"/>'
            '<stop offset="1" style="stop-color:%s"/></radialGradient>'
            % (gid, cx, cy, r, cx - r * 0.35, cy - r * 0.35, c[0], c[1], c[2]))
        return "url(#%s)" % gid

    def add(self, element):
        self.body.append(element)

    def path(self, d, fill, stroke, width=2, extra=""):
        self.add('<path d="%s" style="fill:%s;stroke:%s;stroke-width:%g;stroke-linejoin:round;'
                 'stroke-linecap:round%s"/>' % (d, fill, stroke, width, extra))

    def svg(self):
        return ('<?xml version="1.0" encoding="UTF-8"?>\n'
                '<svg xmlns="http://www.w3.org/2000/svg" width="64" height="64" viewBox="0 0 64 64" version="1.1">\n'
                '<title>%s</title>\n<defs>\n%s\n</defs>\n%s\n</svg>\n'
                % (self.title, "\n".join(self.defs), "\n".join(self.body)))


# ---------------------------------------------------------------------------------------------
# Shapes


def box(ic, x, y, w, h, d, colour):
    """An isometric box like FreeCAD's Part icon: front face at (x, y) w x h, depth d up-right."""
    c = PALETTE[colour]
    top = "M %g,%g %g,%g %g,%g %g,%g z" % (x, y, x + d, y - d * 0.6, x + w + d, y - d * 0.6, x + w, y)
    side = "M %g,%g %g,%g %g,%g %g,%g z" % (x + w, y, x + w + d, y - d * 0.6, x + w + d, y + h - d * 0.6, x + w, y + h)
    front = "M %g,%g %g,%g %g,%g %g,%g z" % (x, y, x + w, y, x + w, y + h, x, y + h)
    ic.path(top, c[0], c[3])
    ic.path(side, ic.grad(colour, x + w, y + h, x + w + d, y, 2, 1), c[3])
    ic.path(front, ic.grad(colour, x, y + h, x + w * 0.3, y, 1, 0), c[3])
    ic.path("M %g,%g %g,%g %g,%g" % (x + 2, y + h - 2, x + 2, y + 2, x + w - 2, y + 2), "none", c[0], 1.5)


def link(ic, x1, y1, x2, y2, r, colour, holes=True):
    """A flat link between two pin centres, rounded ends, with the pins' holes."""
    c = PALETTE[colour]
    a = math.atan2(y2 - y1, x2 - x1)
    nx, ny = -math.sin(a) * r, math.cos(a) * r
    d = ("M %g,%g L %g,%g A %g,%g 0 0 0 %g,%g L %g,%g A %g,%g 0 0 0 %g,%g z"
         % (x1 + nx, y1 + ny, x2 + nx, y2 + ny, r, r, x2 - nx, y2 - ny, x1 - nx, y1 - ny, r, r, x1 + nx, y1 + ny))
    ic.path(d, ic.grad(colour, x1 - nx, y1 - ny, x1 + nx, y1 + ny, 0, 2), c[3])
    if holes:
        for (px, py) in ((x1, y1), (x2, y2)):
            ic.add('<circle cx="%g" cy="%g" r="%g" style="fill:%s;stroke:%s;stroke-width:1.5"/>'
                   % (px, py, r * 0.38, PALETTE["grey"][0], c[3]))


def pin(ic, x, y, r, colour="red"):
    c = PALETTE[colour]
    ic.add('<circle cx="%g" cy="%g" r="%g" style="fill:%s;stroke:%s;stroke-width:2"/>'
           % (x, y, r, ic.radial(colour, x, y, r), c[3]))


def ball(ic, x, y, r, colour):
    pin(ic, x, y, r, colour)


def arrow_head(x, y, angle, size):
    """A filled triangle pointing along `angle` with its tip at (x, y)."""
    a1, a2 = angle + math.radians(150), angle - math.radians(150)
    return "M %g,%g L %g,%g L %g,%g z" % (x, y, x + size * math.cos(a1), y + size * math.sin(a1),
                                            x + size * math.cos(a2), y + size * math.sin(a2))


def straight_arrow(ic, x1, y1, x2, y2, colour, both=False, width=4):
    c = PALETTE[colour]
    a = math.atan2(y2 - y1, x2 - x1)
    inset = 6
    sx, sy = x1 + (inset * math.cos(a) if both else 0), y1 + (inset * math.sin(a) if both else 0)
    ex, ey = x2 - inset * math.cos(a), y2 - inset * math.sin(a)
    ic.path("M %g,%g L %g,%g" % (sx, sy, ex, ey), "none", c[3], width + 3)
    ic.path("M %g,%g L %g,%g" % (sx, sy, ex, ey), "none", c[1], width)
    ic.path(arrow_head(x2, y2, a, 11), c[1], c[3], 1.5)
    if both:
        ic.path(arrow_head(x1, y1, a + math.pi, 11), c[1], c[3], 1.5)


def arc_arrow(ic, cx, cy, rx, ry, a0, a1, colour, width=4):
    """An elliptical arc from angle a0 to a1 (degrees, counter-clockwise on screen when a1 < a0)
    with an arrow head at a1."""
    c = PALETTE[colour]
    p = lambda a: (cx + rx * math.cos(math.radians(a)), cy + ry * math.sin(math.radians(a)))
    step = -8 if a1 < a0 else 8
    end = a1 - step * 0.9
    (x0, y0), (xe, ye) = p(a0), p(end)
    large = 1 if abs(end - a0) > 180 else 0
    sweep = 1 if a1 > a0 else 0
    d = "M %g,%g A %g,%g 0 %d %d %g,%g" % (x0, y0, rx, ry, large, sweep, xe, ye)
    ic.path(d, "none", c[3], width + 3)
    ic.path(d, "none", c[1], width)
    (xt, yt) = p(a1)
    ang = math.atan2(yt - ye, xt - xe)
    ic.path(arrow_head(xt + 2 * math.cos(ang), yt + 2 * math.sin(ang), ang, 11), c[1], c[3], 1.5)


def plate(ic, x, y, w, h, skew, colour):
    """A plane seen in perspective: a parallelogram."""
    c = PALETTE[colour]
    d = "M %g,%g %g,%g %g,%g %g,%g z" % (x + skew, y, x + w + skew, y, x + w, y + h, x, y + h)
    ic.path(d, ic.grad(colour, x, y + h, x + w * 0.4, y, 1, 0), c[3])


def dot(ic, x, y, r=5, colour="yellow"):
    pin(ic, x, y, r, colour)


def plus(ic, x, y, colour="green"):
    c = PALETTE[colour]
    d = ("M %g,%g h6 v6 h6 v6 h-6 v6 h-6 v-6 h-6 v-6 h6 z" % (x - 3, y - 9))
    ic.path(d, ic.grad(colour, x, y - 9, x, y + 9, 0, 2), c[3])


def ground_hatch(ic, x, y, w):
    c = PALETTE["dark"]
    ic.path("M %g,%g h%g v6 h%g z" % (x, y, w, -w), ic.grad("dark", x, y, x, y + 6, 0, 2), c[3])
    for k in range(int(w // 7)):
        xs = x + 4 + 7 * k
        ic.path("M %g,%g l-5,7" % (xs, y + 8), "none", c[2], 2)


def document(ic, x, y, w, h, text=None):
    c = PALETTE["grey"]
    fold = 10
    d = "M %g,%g h%g l%g,%g v%g h%g z" % (x, y, w - fold, fold, fold, h - fold, -w)
    ic.path(d, ic.grad("grey", x, y, x + w, y + h, 0, 1), c[3])
    ic.path("M %g,%g v%g h%g" % (x + w - fold, y, fold, fold), c[1], c[3], 1.5)
    if text:
        ic.add('<text x="%g" y="%g" style="font-family:sans-serif;font-weight:bold;font-size:11px;'
               'fill:%s">%s</text>' % (x + 3, y + h - 6, PALETTE["dark"][2], text))


def gear(ic, cx, cy, r, teeth, colour, phase=0.0):
    """A spur gear seen along its axis: `teeth` trapezoid teeth round a pitch circle of radius r,
    a hub hole in the middle."""
    c = PALETTE[colour]
    pts = []
    depth = max(2.5, r * 0.22)
    for k in range(teeth):
        a = phase + 2 * math.pi * k / teeth
        w = math.pi / teeth
        for da, rr in ((-0.5 * w, r - depth / 2), (-0.25 * w, r + depth / 2), (0.25 * w, r + depth / 2),
                       (0.5 * w, r - depth / 2)):
            pts.append((cx + rr * math.cos(a + da), cy + rr * math.sin(a + da)))
    d = "M " + " L ".join("%.2f,%.2f" % p for p in pts) + " z"
    ic.path(d, ic.grad(colour, cx - r, cy - r, cx + r, cy + r, 0, 2), c[3], 1.5)
    ic.add('<circle cx="%g" cy="%g" r="%g" style="fill:%s;stroke:%s;stroke-width:1.5"/>'
           % (cx, cy, max(2.0, r * 0.3), PALETTE["grey"][0], c[3]))


def rack(ic, x, y, w, h, pitch, colour):
    """A rack: a bar along x with teeth on its top side."""
    c = PALETTE[colour]
    d = "M %g,%g" % (x, y)
    k = x
    while k + pitch <= x + w + 1e-9:
        d += " L %g,%g L %g,%g L %g,%g L %g,%g" % (k + pitch * 0.2, y, k + pitch * 0.35, y - 4,
                                                  k + pitch * 0.65, y - 4, k + pitch * 0.8, y)
        k += pitch
    d += " L %g,%g L %g,%g L %g,%g z" % (x + w, y, x + w, y + h, x, y + h)
    ic.path(d, ic.grad(colour, x, y - 4, x, y + h, 0, 2), c[3], 1.5)


def thread(ic, x1, x2, y, r, turns, colour):
    """A threaded rod along x seen from the side: its body and slanted thread lines."""
    c = PALETTE[colour]
    ic.path("M %g,%g H %g V %g H %g z" % (x1, y - r, x2, y + r, x1), ic.grad(colour, x1, y - r, x1, y + r, 0, 2), c[3], 2)
    step = (x2 - x1) / turns
    for k in range(turns):
        xs = x1 + step * (k + 0.25)
        ic.path("M %g,%g L %g,%g" % (xs, y + r, xs + step * 0.5, y - r), "none", c[3], 1.5)


# ---------------------------------------------------------------------------------------------
# The icons


def two_links(ic):
    """Part 1 (blue) and part 2 (yellow) meeting at the icon's middle: most joints' backdrop."""
    link(ic, 8, 50, 32, 32, 7, "blue")
    link(ic, 32, 32, 56, 44, 7, "yellow")


def icons():
    out = {}

    def icon(name, title):
        ic = Icon(name, title)
        out[name] = ic
        return ic

    # The workbench's icon (package.xml and the workbench selector name it dispcon.svg).
    ic = icon("dispcon", "Dispcon workbench: a four-bar linkage")
    ground_hatch(ic, 4, 52, 56)
    link(ic, 14, 46, 18, 20, 5, "blue")
    link(ic, 18, 20, 46, 12, 5, "yellow")
    link(ic, 46, 12, 50, 46, 5, "blue")
    for x, y in ((14, 46), (50, 46), (18, 20), (46, 12)):
        pin(ic, x, y, 4)

    ic = icon("Dispcon_Assembly", "Assembly: parts held by joints")
    box(ic, 4, 30, 22, 22, 10, "blue")
    box(ic, 30, 24, 20, 28, 10, "yellow")
    pin(ic, 28, 40, 6)

    ic = icon("Dispcon_CreateAssembly", "New assembly")
    box(ic, 4, 30, 22, 22, 10, "blue")
    box(ic, 30, 24, 20, 28, 10, "yellow")
    plus(ic, 50, 14)

    ic = icon("Dispcon_Part", "A part of the assembly")
    box(ic, 10, 26, 30, 30, 16, "blue")

    ic = icon("Dispcon_GroundedPart", "A grounded part: it never moves")
    box(ic, 12, 22, 28, 26, 14, "blue")
    ground_hatch(ic, 4, 50, 56)

    ic = icon("Dispcon_AddParts", "Add the selected objects as parts")
    box(ic, 6, 28, 28, 28, 14, "blue")
    plus(ic, 50, 14)

    ic = icon("Dispcon_ImportPart", "Import a STEP, IGES or BREP file as a part")
    document(ic, 4, 4, 28, 36, "STP")
    box(ic, 28, 34, 20, 20, 10, "blue")
    straight_arrow(ic, 22, 46, 28, 46, "green")

    ic = icon("Dispcon_InsertLink", "Insert a part from another FreeCAD file as a link")
    document(ic, 4, 4, 28, 36, "FC")
    box(ic, 28, 34, 20, 20, 10, "blue")
    straight_arrow(ic, 22, 46, 28, 46, "orange")

    # Sub-assemblies: a small assembly (two links on a pin) inside a frame; rigid has a padlock
    # (it moves as one part), flexible an orange turn arrow (its parts still move).
    def sub_assembly(ic):
        c = PALETTE["grey"]
        ic.add('<rect x="4" y="10" width="50" height="44" rx="4" style="fill:%s;stroke:%s;stroke-width:2;'
               'stroke-dasharray:5,3"/>' % (ic.grad("grey", 4, 10, 54, 54, 0, 1), c[3]))
        link(ic, 12, 44, 28, 26, 5, "blue")
        link(ic, 28, 26, 46, 36, 5, "yellow")
        pin(ic, 28, 26, 4)

    ic = icon("Dispcon_SubAssembly", "Rigid sub-assembly: an assembly placed here, moving as one part")
    sub_assembly(ic)
    # A padlock: locked together.
    ic.path("M 45,46 v-5 a6,6 0 0 1 12,0 v5", "none", PALETTE["dark"][3], 5)
    ic.path("M 45,46 v-5 a6,6 0 0 1 12,0 v5", "none", PALETTE["grey"][1], 2.5)
    ic.add('<rect x="41" y="45" width="20" height="15" rx="2" style="fill:%s;stroke:%s;stroke-width:2"/>'
           % (ic.grad("yellow", 41, 45, 61, 60, 0, 2), PALETTE["yellow"][3]))

    ic = icon("Dispcon_SubAssemblyFlexible", "Flexible sub-assembly: its parts and joints join this assembly's solve")
    sub_assembly(ic)
    arc_arrow(ic, 28, 26, 14, 14, 200, 320, "orange", width=3)

    ic = icon("Dispcon_InsertSubAssembly", "Insert an assembly (of this or another file) as a sub-assembly")
    sub_assembly(ic)
    plus(ic, 52, 12)

    ic = icon("Dispcon_Ground", "Ground: the selected parts never move")
    box(ic, 16, 24, 24, 22, 12, "yellow")
    ground_hatch(ic, 4, 48, 56)
    pin(ic, 28, 14, 5, "red")
    ic.path("M 28,19 V 34", "none", PALETTE["red"][3], 3)

    # Joints: the same backdrop, and the glyph the 3D marker draws.
    ic = icon("Dispcon_JointFixed", "Fixed joint: no motion between the parts")
    two_links(ic)
    c = PALETTE["dark"]
    ic.add('<rect x="24" y="24" width="16" height="16" rx="2" style="fill:%s;stroke:%s;stroke-width:2"/>'
           % (ic.grad("dark", 24, 24, 40, 40, 0, 2), c[3]))
    ic.path("M 28,28 l8,8 M 36,28 l-8,8", "none", PALETTE["grey"][0], 2.5)

    ic = icon("Dispcon_JointRevolute", "Revolute joint: a turn about one axis")
    two_links(ic)
    pin(ic, 32, 32, 6)
    arc_arrow(ic, 32, 32, 22, 12, 200, -20, "orange")

    ic = icon("Dispcon_JointSlider", "Slider joint: travel along one axis")
    link(ic, 4, 48, 60, 20, 5, "blue", holes=False)
    box(ic, 20, 30, 18, 12, 7, "yellow")
    straight_arrow(ic, 10, 62, 54, 40, "green", both=True, width=3)

    ic = icon("Dispcon_JointCylindrical", "Cylindrical joint: a turn about an axis and travel along it")
    link(ic, 4, 48, 60, 20, 4, "blue", holes=False)
    c = PALETTE["yellow"]
    ic.add('<ellipse cx="32" cy="34" rx="9" ry="13" transform="rotate(-27 32 34)" style="fill:%s;stroke:%s;stroke-width:2"/>'
           % (ic.grad("yellow", 24, 24, 40, 44, 0, 2), c[3]))
    arc_arrow(ic, 32, 34, 16, 20, 140, -60, "orange", width=3)
    straight_arrow(ic, 36, 58, 60, 46, "green", width=3)

    ic = icon("Dispcon_JointBall", "Ball joint: turns about a point")
    link(ic, 6, 54, 28, 36, 7, "blue", holes=False)
    c = PALETTE["blue"]
    ic.path("M 16,30 A 16,16 0 0 0 44,42", "none", c[3], 7)
    ic.path("M 16,30 A 16,16 0 0 0 44,42", "none", c[1], 4)
    link(ic, 32, 32, 56, 10, 5, "yellow", holes=False)
    ball(ic, 30, 34, 11, "yellow")

    ic = icon("Dispcon_JointPlanar", "Planar joint: slides and turns on a plane")
    plate(ic, 2, 36, 46, 22, 14, "blue")
    box(ic, 18, 30, 18, 12, 8, "yellow")
    straight_arrow(ic, 40, 30, 60, 30, "green", width=3)
    straight_arrow(ic, 20, 20, 28, 6, "green", width=3)

    ic = icon("Dispcon_JointPointOnLine", "Point on line: a point of part 2 stays on a line of part 1")
    link(ic, 4, 52, 60, 20, 4, "blue", holes=False)
    dot(ic, 32, 36, 8)
    straight_arrow(ic, 14, 28, 42, 12, "green", width=3)

    ic = icon("Dispcon_JointPointOnPlane", "Point on plane: a point of part 2 stays on a plane of part 1")
    plate(ic, 2, 30, 46, 26, 14, "blue")
    dot(ic, 30, 42, 8)
    ic.path("M 30,34 V 10", "none", PALETTE["red"][1], 3, ";stroke-dasharray:4,3")

    ic = icon("Dispcon_JointPointOnCurve", "Point on curve: a point of part 2 stays on a curve of part 1")
    d = "M 4,50 C 16,10 36,60 60,16"
    ic.path(d, "none", PALETTE["blue"][3], 9)
    ic.path(d, "none", PALETTE["blue"][1], 5)
    dot(ic, 33, 36, 8)

    ic = icon("Dispcon_JointAngle", "Angle joint: bounds the angle between two axes")
    link(ic, 10, 54, 58, 54, 4, "blue", holes=False)
    link(ic, 10, 54, 44, 14, 4, "yellow", holes=False)
    arc_arrow(ic, 10, 54, 34, 34, 0, -44, "orange", width=3)
    pin(ic, 10, 54, 5, "dark")

    ic = icon("Dispcon_JointDistance", "Distance joint: points, lines or planes at a set distance")
    plate(ic, 2, 40, 44, 18, 12, "blue")
    box(ic, 30, 10, 16, 10, 7, "yellow")
    c = PALETTE["green"]
    ic.path("M 22,47 V 22", "none", c[3], 5)
    ic.path("M 22,47 V 22", "none", c[1], 2.5)
    ic.path(arrow_head(22, 16, -math.pi / 2, 10), c[1], c[3], 1.5)
    ic.path(arrow_head(22, 52, math.pi / 2, 10), c[1], c[3], 1.5)

    ic = icon("Dispcon_JointParallel", "Parallel joint: two edges or faces kept parallel")
    link(ic, 6, 50, 46, 30, 5, "blue", holes=False)
    link(ic, 18, 30, 58, 10, 5, "yellow", holes=False)
    c = PALETTE["orange"]
    ic.path("M 28,50 L 40,26 M 36,52 L 48,28", "none", c[3], 5)
    ic.path("M 28,50 L 40,26 M 36,52 L 48,28", "none", c[1], 2.5)

    ic = icon("Dispcon_JointPerpendicular", "Perpendicular joint: two edges or faces kept at right angles")
    link(ic, 6, 54, 58, 54, 5, "blue", holes=False)
    link(ic, 14, 54, 14, 6, 5, "yellow", holes=False)
    c = PALETTE["orange"]
    ic.path("M 14,40 H 28 V 54", "none", c[3], 5)
    ic.path("M 14,40 H 28 V 54", "none", c[1], 2.5)

    ic = icon("Dispcon_JointGears", "Gears joint: two gears in mesh turn opposite ways")
    gear(ic, 20, 36, 14, 10, "blue")
    gear(ic, 46, 24, 10, 8, "yellow", phase=math.pi / 8)
    arc_arrow(ic, 20, 36, 18, 18, 150, 60, "orange", width=3)
    arc_arrow(ic, 46, 24, 14, 14, 250, 340, "orange", width=3)

    ic = icon("Dispcon_JointBelt", "Belt joint: two pulleys on a belt turn the same way")
    c = PALETTE["dark"]
    ic.path("M 16,22 L 48,30 M 16,54 L 48,46", "none", c[3], 5)
    ic.path("M 16,22 L 48,30 M 16,54 L 48,46", "none", c[1], 2.5)
    pin(ic, 16, 38, 15, "blue")
    pin(ic, 48, 38, 8, "yellow")
    arc_arrow(ic, 16, 38, 20, 20, 120, 40, "orange", width=3)
    arc_arrow(ic, 48, 38, 13, 13, 120, 40, "orange", width=3)

    ic = icon("Dispcon_JointRackPinion", "Rack and pinion joint: the rack travels as the pinion turns")
    rack(ic, 2, 44, 60, 10, 8, "yellow")
    gear(ic, 30, 26, 12, 10, "blue")
    straight_arrow(ic, 8, 60, 56, 60, "green", width=2)

    ic = icon("Dispcon_JointScrew", "Screw joint: the nut travels a pitch per turn of the screw")
    thread(ic, 4, 60, 34, 7, 7, "blue")
    box(ic, 26, 22, 12, 22, 6, "yellow")
    arc_arrow(ic, 12, 34, 8, 16, 250, 120, "orange", width=3)
    straight_arrow(ic, 40, 56, 60, 56, "green", width=2)

    ic = icon("Dispcon_Solve", "Solve: snap the parts into place")
    link(ic, 6, 52, 26, 36, 6, "blue")
    link(ic, 38, 28, 58, 14, 6, "yellow")
    straight_arrow(ic, 44, 40, 30, 40, "green", width=3)
    c = PALETTE["green"]
    ic.path("M 8,16 l8,8 l14,-16", "none", c[3], 8)
    ic.path("M 8,16 l8,8 l14,-16", "none", c[0], 4)

    ic = icon("Dispcon_Drag", "Drag mode: move a part with the mouse, the linkage follows")
    two_links(ic)
    c = PALETTE["grey"]
    ic.path("M 30,4 V 30 L 36,24 L 41,35 L 45,33 L 40,22 L 48,22 z", "#ffffff", PALETTE["dark"][3], 2)
    straight_arrow(ic, 6, 18, 22, 10, "green", width=3)

    ic = icon("Dispcon_Drive", "Drive: turn a revolute, as an animation")
    link(ic, 18, 44, 50, 22, 7, "yellow")
    pin(ic, 18, 44, 7)
    arc_arrow(ic, 18, 44, 14, 14, 180, -150, "green")
    c = PALETTE["dark"]
    ic.add('<rect x="4" y="54" width="28" height="8" rx="2" style="fill:%s;stroke:%s;stroke-width:2"/>'
           % (ic.grad("dark", 4, 54, 4, 62, 0, 2), c[3]))

    ic = icon("Dispcon_MotionStudy", "Motion study: sweep a joint, plot and animate it")
    document(ic, 6, 4, 44, 52)
    c = PALETTE["dark"]
    ic.path("M 12,48 H 44 M 12,48 V 14", "none", c[2], 2)
    d = "M 12,36 C 18,14 24,14 28,30 C 32,46 38,46 44,24"
    ic.path(d, "none", PALETTE["orange"][3], 6)
    ic.path(d, "none", PALETTE["orange"][1], 3)
    link(ic, 34, 58, 58, 40, 5, "yellow")
    pin(ic, 34, 58, 4)

    ic = icon("Dispcon_Check", "Check: degrees of freedom, redundant and conflicting joints")
    two_links(ic)
    c = PALETTE["grey"]
    ic.add('<circle cx="26" cy="24" r="14" style="fill:%s;fill-opacity:0.75;stroke:%s;stroke-width:4"/>'
           % (c[0], PALETTE["dark"][2]))
    ic.path("M 36,34 L 50,48", "none", PALETTE["dark"][3], 9)
    ic.path("M 36,34 L 50,48", "none", PALETTE["orange"][1], 5)
    ic.add('<text x="17" y="30" style="font-family:sans-serif;font-weight:bold;font-size:16px;fill:%s">?</text>'
           % PALETTE["blue"][2])

    ic = icon("Dispcon_ExportDcl", "Export the assembly as a .dcl file")
    box(ic, 4, 30, 18, 18, 9, "blue")
    document(ic, 30, 6, 28, 40, "dcl")
    straight_arrow(ic, 16, 56, 44, 56, "green", width=3)

    ic = icon("Dispcon_ImportDcl", "Place the parts as a .dcl file says")
    document(ic, 4, 6, 28, 40, "dcl")
    box(ic, 38, 30, 18, 18, 9, "blue")
    straight_arrow(ic, 18, 56, 46, 56, "green", width=3)

    ic = icon("Dispcon_Interference", "Interference: parts that overlap")
    box(ic, 4, 28, 26, 26, 12, "blue")
    box(ic, 24, 20, 26, 26, 12, "yellow")
    ic.path("M 24,28 h6 v18 h-6 z", PALETTE["red"][0], PALETTE["red"][3])
    return out


def main(argv):
    out = argv[1] if len(argv) > 1 else OUT
    os.makedirs(out, exist_ok=True)
    for name, ic in icons().items():
        with open(os.path.join(out, name + ".svg"), "w") as f:
            f.write(ic.svg())
    print("%d icons in %s" % (len(icons()), out))


if __name__ == "__main__":
    main(sys.argv)
