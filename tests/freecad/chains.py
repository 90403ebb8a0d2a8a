"""Chains of parallelograms from real solids (samples/freecad/parts.py), shared by the GUI drag
test (gui_drag.py) and the markers' benchmark (bench_markers.py). Importing it runs nothing."""
import FreeCAD as App

PITCH, LENGTH = 1.5, 1.0


def crank_chain(doc, cranks, asm=None, at=None, name="Chain"):
    """A 1-DOF chain of parallelograms: `cranks` cranks on one ground plate's bosses, each pair of
    neighbours joined by a coupler (alternate couplers one layer higher, so neighbours touch
    without overlapping): 2 * cranks parts, 3 * cranks - 2 revolutes, in `asm` (a new assembly
    called `name` when None), the plate at `at`. Dragging any moving part turns every crank.
    Returns (asm, cranks, couplers)."""
    import dispcon_fc.assembly as da
    import parts

    at = at if at is not None else App.Vector()
    asm = asm if asm is not None else da.create_assembly(doc, name)
    ground = doc.addObject("Part::Feature", "Ground")
    ground.Shape = parts.ground([(k * PITCH, 0) for k in range(cranks)])
    ground.Placement = App.Placement(at, App.Rotation())
    da.add_part(asm, ground, grounded=True)
    crank_shape, coupler_shape = parts.link(LENGTH), parts.link(PITCH)
    tip = App.Rotation(App.Vector(0, 0, 1), 60).multVec(App.Vector(LENGTH, 0, 0))
    cs, ls = [], []
    for k in range(cranks):
        c = doc.addObject("Part::Feature", "Crank%d" % k)
        c.Shape = crank_shape
        c.Placement = App.Placement(at + App.Vector(k * PITCH, 0, 0.1), App.Rotation(App.Vector(0, 0, 1), 60))
        cs.append(da.add_part(asm, c))
    for k in range(cranks - 1):
        c = doc.addObject("Part::Feature", "Coupler%d" % k)
        c.Shape = coupler_shape
        c.Placement = App.Placement(at + App.Vector(k * PITCH, 0, 0.2 + 0.1 * (k % 2)) + tip, App.Rotation())
        ls.append(da.add_part(asm, c))

    def pin(o, x, top=False):
        return (o, parts.circle_edge(o.Shape, App.Vector(x, 0, 0.1 if top else 0.0)))

    for k in range(cranks):
        da.add_joint(asm, "Revolute", pin(ground, k * PITCH, True), pin(cs[k], 0))
    for k in range(cranks - 1):
        layer = 0.1 * (k % 2)
        da.add_joint(asm, "Revolute", pin(cs[k], LENGTH, True), pin(ls[k], 0), offset=layer)
        da.add_joint(asm, "Revolute", pin(cs[k + 1], LENGTH, True), pin(ls[k], PITCH), offset=layer)
    return asm, cs, ls


def chains(doc, rows, cols, cranks, name="Grid"):
    """`rows` x `cols` crank chains of `cranks` parallelograms, each on a ground plate of its own,
    in one assembly: rows * cols * (2 cranks - 1) parts, (3 cranks - 2) revolutes each."""
    import dispcon_fc.assembly as da

    asm = da.create_assembly(doc, name)
    for r in range(rows):
        for c in range(cols):
            crank_chain(doc, cranks, asm, App.Vector(c * (cranks * PITCH + 2.0), r * 3.0, 0))
    return asm
