"""Exploded views: an assembly drawn with its parts moved apart, as a designer shows how it goes
together, without moving a part.

An exploded view is its own object of the document (a Part::FeaturePython, as FreeCAD 1.x's
Assembly keeps its exploded views as objects): its shape is a compound of copies of the parts,
each moved by its offset, with lines along the way each part was drawn. The parts' Placements
are never written: the joints, a solve, a drag and a saved file all see the assembled pose
whether the view is shown or not, so showing the assembled parts again restores every placement
to the bit (there is nothing to restore), and a document saved while the exploded view is shown
reopens assembled, with its exploded view beside it. (A tool that moved the parts would have to
refuse to save, or save the exploded pose as the assembly's; neither is what a designer expects
of a view.) Showing the view hides the parts and the joints' markers, hiding it shows them again
(ViewProviderExplodedView).

A view is a list of steps, as FreeCAD 1.x's exploded views are, applied in order, each from where
the ones before it left the parts. A step moves the parts it names (a part of the assembly; a
placed sub-assembly, which moves as one unit, its parts and those of the sub-assemblies nested in
it by one offset; or a part inside a sub-assembly, alone). Where a unit is: the centre of its
bounding box (its exact geometry's, not a mesh's) as the steps before have drawn it. How a step
moves its units:
- Radial: away from the assembly's centre (the centre of the box around every part as the steps
  before have drawn it), along the line from that centre to the unit's own, in proportion to its
  distance from it, the farthest of the step's units by Distance:
  offset = Distance x (c - C) / max |c - C|;
- Direction: every unit by Distance along Direction;
- Stack: the units in order of their centres along Direction (ties, within a millionth of the
  assembly's size, sharing a place), the first staying and each next one Distance further than
  the one before: offset = Distance x rank x Direction (unit). (A view made by the workbench
  before steps, "Direction", is one such step.)

The steps are the view's properties (StepModes, StepDistances in mm, StepDirections, and the parts
of all steps in StepParts, StepSizes saying how many each takes), so a FreeCAD without the
workbench keeps them (Nothing lost, docs/workbench.md). Every setting enters through
check_steps, whoever gives it (a script, the panel, the property editor at the next recompute)."""
import math

import FreeCAD as App

from . import objects
from .objects import is_sub_assembly, parts, shape_of

MODES = ("Radial", "Direction", "Stack")
# How the panel and the messages say each mode.
MODE_WORDS = {"Radial": "away from the centre", "Direction": "along a direction", "Stack": "stacked along a direction"}


class Step:
    """One step of an exploded view: `mode` (MODES), `distance` (mm), `direction` (an
    App.Vector, for Direction and Stack) and `parts`, the objects it moves (parts, sub-assembly
    instances moving as one, or parts inside them moving alone)."""

    def __init__(self, parts, mode="Radial", distance=0.0, direction=None):
        self.parts = list(parts)
        self.mode = mode
        self.distance = distance
        self.direction = App.Vector(0, 0, 1) if direction is None else App.Vector(direction)

    def copy(self):
        return Step(self.parts, self.mode, self.distance, self.direction)

    def __eq__(self, other):
        return (isinstance(other, Step) and [p.Name for p in self.parts] == [p.Name for p in other.parts]
                and (self.mode, self.distance, tuple(self.direction)) == (other.mode, other.distance,
                                                                         tuple(other.direction)))

    def __repr__(self):
        along = "" if self.mode == "Radial" else ", (%g, %g, %g)" % tuple(self.direction)
        return "Step(%s, %s, %g mm%s)" % ([p.Label for p in self.parts], self.mode, self.distance, along)


class ExplodedViewProxy(objects.Stateless):
    """The exploded view's proxy: its shape is made from its steps and the parts' shapes at every
    recompute (it holds nothing of its own)."""

    def __init__(self, obj):
        obj.Proxy = self
        self.attach(obj)

    def attach(self, obj):
        objects._mark(obj, "ExplodedView")
        add = objects._add
        old = "StepModes" not in obj.PropertiesList and "Mode" in obj.PropertiesList
        for type_id, name, group, value in (
                ("App::PropertyLink", "Assembly", "Exploded view", None),
                ("App::PropertyStringList", "StepModes", "Exploded view", None),
                ("App::PropertyFloatList", "StepDistances", "Exploded view", None),
                ("App::PropertyVectorList", "StepDirections", "Exploded view", None),
                ("App::PropertyLinkList", "StepParts", "Exploded view", None),
                ("App::PropertyIntegerList", "StepSizes", "Exploded view", None),
                ("App::PropertyBool", "Lines", "Exploded view", True),
                ("App::PropertyLinkList", "Parts", "Result", None),
                ("App::PropertyVectorList", "Offsets", "Result", None)):
            add(obj, "ExplodedView", type_id, name, group, value)
        for name in ("Parts", "Offsets"):
            obj.setEditorMode(name, 1)  # read only: made from the steps
        if old:
            _migrate(obj)

    def onDocumentRestored(self, obj):
        self.attach(obj)
        if App.GuiUp and obj.ViewObject is not None and obj.ViewObject.Proxy in (None, 0):
            ViewProviderExplodedView(obj.ViewObject)
        _under_the_view(obj)

    def execute(self, obj):
        asm = obj.Assembly
        if asm is None or not objects.is_assembly(asm):
            raise ValueError("%s: its assembly is gone" % obj.Label)
        moved, trails = explode(asm, check_steps(asm, steps(obj)))
        names = [p for p, _ in moved]
        if list(obj.Parts) != names:
            obj.Parts = names
        vectors = [v for _, v in moved]
        if [tuple(v) for v in obj.Offsets] != [tuple(v) for v in vectors]:
            obj.Offsets = vectors
        obj.Shape = exploded_shape(moved, trails if obj.Lines else {})  # last: the view colours it by Parts


def _migrate(obj):
    """A view made before steps (Mode, Direction, Distance, ExpandSubAssemblies): the same
    explosion as one step (its Direction mode stacked: Stack), those properties removed."""
    asm = obj.Assembly
    mode = {"Radial": "Radial", "Direction": "Stack"}.get(getattr(obj, "Mode", "Radial"), "Radial")
    expand = bool(getattr(obj, "ExpandSubAssemblies", False))
    moving = all_units(asm, expand) if asm is not None and objects.is_assembly(asm) else []
    _write(obj, [Step(moving, mode, obj.Distance.Value, obj.Direction)])
    for name in ("Mode", "Direction", "Distance", "ExpandSubAssemblies"):
        if name in obj.PropertiesList:
            obj.removeProperty(name)


def steps(view):
    """The view's steps as Step objects, in order (as stored: check_steps says what is wrong)."""
    modes, distances = list(view.StepModes), list(view.StepDistances)
    directions, sizes, moving = list(view.StepDirections), list(view.StepSizes), list(view.StepParts)
    out, at = [], 0
    for k, mode in enumerate(modes):
        size = sizes[k] if k < len(sizes) else 0
        out.append(Step(moving[at:at + size], mode, distances[k] if k < len(distances) else float("nan"),
                        directions[k] if k < len(directions) else App.Vector()))
        at += size
    if at != len(moving) or len(sizes) != len(modes) or len(distances) != len(modes) or len(directions) != len(modes):
        raise ValueError("%s: its step lists disagree (%d modes, %d distances, %d directions, %d sizes for %d parts)"
                         % (view.Label, len(modes), len(distances), len(directions), len(sizes), len(moving)))
    return out


def _write(view, checked):
    """Stores checked steps in the view's properties (only those that changed)."""
    values = {"StepModes": [s.mode for s in checked], "StepDistances": [float(s.distance) for s in checked],
              "StepDirections": [App.Vector(s.direction) for s in checked],
              "StepSizes": [len(s.parts) for s in checked]}
    if [p.Name for p in view.StepParts] != [p.Name for s in checked for p in s.parts]:
        view.StepParts = [p for s in checked for p in s.parts]
    for name, value in values.items():
        have = getattr(view, name)
        if name == "StepDirections":
            same = [tuple(v) for v in have] == [tuple(v) for v in value]
        else:
            same = list(have) == value
        if not same:
            setattr(view, name, value)


def units(asm, expand_sub_assemblies=False):
    """The groups of parts that move together: [[part], ...] in the assembly's order."""
    own = set(o.Name for o in parts(asm))
    out = []
    for o in asm.Group:
        if o.Name in own:
            out.append([o])
        elif is_sub_assembly(o):
            links = objects.nested_parts(o)  # those of the instances nested in it too
            if expand_sub_assemblies:
                out += [[link] for link in links]
            elif links:
                out.append(links)
    return out


def all_units(asm, expand_sub_assemblies=False):
    """What a step moving everything names: the assembly's parts and its sub-assemblies (each as
    one), or their parts each alone."""
    own = set(o.Name for o in parts(asm))
    out = []
    for o in asm.Group:
        if o.Name in own:
            out.append(o)
        elif is_sub_assembly(o):
            out += objects.nested_parts(o) if expand_sub_assemblies else [o]
    return out


def choices(asm):
    """[(object, depth)] a step can move, in the tree's order: the assembly's parts (depth 0), each
    placed sub-assembly (0) with its parts and nested sub-assemblies below it (1, 2, ...)."""
    out = []

    def inside(inst, depth):
        for o in inst.Group:
            if is_sub_assembly(o):
                out.append((o, depth))
                inside(o, depth + 1)
            elif o.TypeId == "App::Link" and "LocalPlacement" in o.PropertiesList:
                out.append((o, depth))

    own = set(o.Name for o in parts(asm))
    for o in asm.Group:
        if o.Name in own:
            out.append((o, 0))
        elif is_sub_assembly(o):
            out.append((o, 0))
            inside(o, 1)
    return out


def part_at(view, element):
    """The part whose copy in `view`'s shape holds `element` (a sub-element name picked in the 3D
    view: "Face12", "Edge3", "Vertex7"), or None (a line along a part's way, or no such element).
    The view's compound holds each part's copy in the order of its Parts, then the lines."""
    import re

    m = re.match(r"^(Face|Edge|Vertex)(\d+)$", element or "")
    if m is None:
        return None
    try:
        picked = view.Shape.getElement(element)
    except Exception:  # an element the shape no longer has
        return None
    kind = {"Face": "Faces", "Edge": "Edges", "Vertex": "Vertexes"}[m.group(1)]
    pieces = view.Shape.childShapes()
    for part, piece in zip(view.Parts, pieces):
        if any(e.isSame(picked) for e in getattr(piece, kind)):
            return part
    return None


def unit_of(asm, part):
    """What a step of `asm` names to move `part` with what moves with it: the part itself when it
    is the assembly's, else the sub-assembly placed in `asm` that holds it (at any depth), which
    moves as one; None when it is neither."""
    own = {o.Name for o in parts(asm)}
    if part.Name in own:
        return part
    for o in asm.Group:
        if is_sub_assembly(o) and any(p.Name == part.Name for p in objects.nested_parts(o)):
            return o
    return None


def _members(obj):
    """The parts that move when a step names `obj`."""
    return objects.nested_parts(obj) if is_sub_assembly(obj) else [obj]


def check_steps(asm, given):
    """The one door of a view's settings: each step's mode, distance (a finite number of mm),
    direction (with a length, where the mode uses one) and parts (each a part of `asm` or inside
    one of its sub-assemblies, none twice in a step) checked; returns them as Steps (the
    direction a unit vector). Refused: a ValueError naming the step; nothing is written."""
    placed = {p.Name for p in objects.placed_parts(asm)}
    out = []
    for k, step in enumerate(given, 1):
        if not isinstance(step, Step):
            step = Step(**step) if isinstance(step, dict) else Step(*step)
        where = "step %d" % k
        if step.mode not in MODES:
            raise ValueError("%s: the way is one of %s, not %r" % (where, ", ".join(MODES), step.mode))
        try:
            distance = float(step.distance)
        except (TypeError, ValueError):
            raise ValueError("%s: the distance must be a number of mm (it is %r)" % (where, step.distance))
        if not (math.isfinite(distance) and abs(distance) < 1e12):
            raise ValueError("%s: the distance must be a number of mm (it is %r)" % (where, step.distance))
        direction = App.Vector(step.direction)
        if step.mode != "Radial":
            if not (all(math.isfinite(x) for x in direction) and direction.Length > 1e-12):
                raise ValueError("%s: the direction has no length" % where)
            direction.normalize()
        if not step.parts:
            raise ValueError("%s moves no part: choose the parts it moves" % where)
        seen = {}
        for obj in step.parts:
            if obj is None:
                raise ValueError("%s: one of its parts is gone (deleted)" % where)
            members = _members(obj)
            if not (is_sub_assembly(obj) and _inside(obj, asm)) and not (obj.Name in placed and not is_sub_assembly(obj)):
                raise ValueError("%s: %s is not a part of %s" % (where, obj.Label, asm.Label))
            for m in members:
                if m.Name in seen:
                    raise ValueError("%s moves %s twice (%s and %s)" % (where, m.Label, seen[m.Name], obj.Label))
                seen[m.Name] = obj.Label
        out.append(Step(step.parts, step.mode, distance, direction))
    return out


def _inside(inst, asm):
    """Whether a sub-assembly instance is placed in `asm`, at any depth."""
    for s in objects.sub_assemblies(asm):
        if s.Name == inst.Name or _nested_in(inst, s):
            return True
    return False


def _nested_in(inst, container):
    return any(n.Name == inst.Name or _nested_in(inst, n) for n in objects.sub_assemblies(container))


def _box(shapes, moves=None):
    box = App.BoundBox()
    for k, s in enumerate(shapes):
        b = s.BoundBox
        if moves is not None and moves[k].Length > 0:
            b = App.BoundBox(b)
            b.move(moves[k])
        box.add(b)
    return box


def explode(asm, checked):
    """([(part, offset)] for every part of `asm` in the order of its units, {part Name: [the
    offsets it was drawn at, step after step]}) after the checked steps, applied in order."""
    every = [p for g in units(asm, True) for p in g]
    # Copies, without the meshes a 3D view made of them: OpenCASCADE bounds a meshed shape by its
    # mesh (a tilted torus' box 3% smaller), so the same parts would be drawn elsewhere once shown.
    shapes = {p.Name: shape_of(p).copy() for p in every}
    offset = {p.Name: App.Vector() for p in every}
    trails = {p.Name: [App.Vector()] for p in every}
    size = max(_box(list(shapes.values())).DiagonalLength, 1e-12)
    for step in checked:
        groups = [[m for m in _members(o) if m.Name in shapes] for o in step.parts]
        groups = [g for g in groups if g]
        if not groups:
            continue
        centres = [_box([shapes[m.Name] for m in g], [offset[m.Name] for m in g]).Center for g in groups]
        if step.mode == "Radial":
            centre = _box([shapes[n] for n in shapes], [offset[n] for n in shapes]).Center
            reach = max((c - centre).Length for c in centres)
            scale = step.distance / reach if reach > 1e-9 * size else 0.0
            moves = [(c - centre) * scale for c in centres]
        elif step.mode == "Direction":
            moves = [step.direction * step.distance for _ in groups]
        else:
            along = [c.dot(step.direction) for c in centres]
            levels = []
            for a in sorted(along):
                if not levels or a - levels[-1] > 1e-6 * size:
                    levels.append(a)
            rank = [next(k for k, level in enumerate(levels) if abs(a - level) <= 1e-6 * size) for a in along]
            moves = [step.direction * (step.distance * k) for k in rank]
        for g, move in zip(groups, moves):
            for m in g:
                offset[m.Name] = offset[m.Name] + move
                if move.Length > 0:
                    trails[m.Name].append(App.Vector(offset[m.Name]))
    return [(p, App.Vector(offset[p.Name])) for p in every], trails


def offsets(asm, mode="Radial", direction=App.Vector(0, 0, 1), distance=0.0, expand_sub_assemblies=False):
    """[(part, offset)] for every part of `asm` after one step moving every unit (the module's
    rules), its parts where they are."""
    checked = check_steps(asm, [Step(all_units(asm, expand_sub_assemblies), mode, distance, direction)])
    return explode(asm, checked)[0]


def exploded_shape(moved, trails=None):
    """A compound of each part's shape moved by its offset, then (trails) lines from each moved
    part's centre at its place along the offsets it was drawn at, step after step. `trails`
    True: one straight line to where it is drawn."""
    import Part

    pieces, lines = [], []
    for part, offset in moved:
        shape = shape_of(part).copy()
        centre = shape.BoundBox.Center
        if offset.Length > 0:
            shape.translate(offset)
            way = [App.Vector(), offset] if trails is True else (trails or {}).get(part.Name, [])
            for a, b in zip(way, way[1:]):
                if (b - a).Length > 0:
                    lines.append(Part.makeLine(centre + a, centre + b))
        pieces.append(shape)
    return Part.makeCompound(pieces + lines)


def views_of(asm):
    """The exploded views of `asm` in its document (with their proxies: a document saved where the
    workbench was missing lost them)."""
    found = [o for o in asm.Document.Objects
             if getattr(o, "DispconType", "") == "ExplodedView" and getattr(o, "Assembly", None) == asm]
    for o in found:
        objects.adopt(o)
    return found


def follow(asm):
    """Redraws every exploded view of `asm` from the parts' placements as they are now, in
    whatever undo step is open: a Solve's or a drag's (operations.solve, _Motion.finish), so the
    view shows the new pose at once, not at the next recompute, and undo takes the view back with
    the parts. Writes no placement."""
    for view in views_of(asm):
        view.recompute()


def adopt_view(obj):
    """An exploded view whose proxies a document saved where the workbench was missing lost: its
    proxy (a view of before the steps migrated to one step) and its view provider back; returns
    whether it got its proxy."""
    if App.GuiUp and obj.ViewObject is not None and not isinstance(obj.ViewObject.Proxy, ViewProviderExplodedView):
        ViewProviderExplodedView(obj.ViewObject)
        _under_the_view(obj)
    if isinstance(getattr(obj, "Proxy", None), ExplodedViewProxy):
        return False
    ExplodedViewProxy(obj)
    return True


def _under_the_view(view):
    """A view restored shown hides the assembled parts and markers under it, as showing it does:
    a FreeCAD without the workbench shows every part of an assembly (the children of a Python
    group whose view provider it cannot make: measured with FreeCAD 0.20.2) and saves them so.
    Nothing is recorded as hidden by the view: hiding it shows them all."""
    vobj = view.ViewObject if App.GuiUp else None
    asm = getattr(view, "Assembly", None)
    if vobj is None or not vobj.Visibility or asm is None or not objects.is_assembly(asm):
        return
    for o in _drawn(asm):
        if o.ViewObject is not None and o.ViewObject.Visibility:
            o.ViewObject.Visibility = False


def is_exploded_view(obj):
    return getattr(obj, "DispconType", "") == "ExplodedView"


def new_exploded_view(asm, mode="Radial", distance=None, direction=None, expand_sub_assemblies=False,
                      lines=True, undo_step=True, steps=None):
    """An exploded view of `asm` (a new object of its document, the parts untouched), in one undo
    step: `steps` (Step objects, or (parts, mode, distance, direction) tuples, applied in order),
    or one step moving every part (`mode`, `distance` in mm, by default half the assembly's size,
    `direction`; a sub-assembly as one unless `expand_sub_assemblies`). Returns it."""
    from .operations import _assembly, transaction

    _assembly(asm)
    if not parts(asm) and not any(is_sub_assembly(o) for o in asm.Group):
        raise ValueError("%s has no part to explode" % asm.Label)
    if steps is None:
        if distance is None:
            groups = units(asm, expand_sub_assemblies)
            distance = 0.5 * _box([shape_of(p) for g in groups for p in g]).DiagonalLength
        steps = [Step(all_units(asm, expand_sub_assemblies), mode, distance,
                      App.Vector(0, 0, 1) if direction is None else direction)]
    checked = check_steps(asm, steps)
    doc = asm.Document

    def make():
        obj = doc.addObject("Part::FeaturePython", "ExplodedView")
        ExplodedViewProxy(obj)
        obj.Label = "Exploded view of %s" % asm.Label
        obj.Assembly = asm
        _write(obj, checked)
        obj.Lines = bool(lines)
        if App.GuiUp and obj.ViewObject is not None:
            ViewProviderExplodedView(obj.ViewObject)
        obj.recompute()
        show(obj, True)
        return obj

    if not undo_step:
        return make()
    with transaction(doc, "Exploded view"):
        return make()


def _view(view):
    if not is_exploded_view(view):
        raise ValueError("%s is not an exploded view" % getattr(view, "Label", view))
    objects.adopt(view)
    asm = view.Assembly
    if asm is None or not objects.is_assembly(asm):
        raise ValueError("%s: its assembly is gone" % view.Label)
    return asm


def set_steps(view, new_steps, lines=None, undo_step=True):
    """Replaces the view's steps (checked first: a refused one changes nothing) and redraws it, in
    one undo step."""
    from .operations import transaction

    asm = _view(view)
    checked = check_steps(asm, new_steps)

    def write():
        _write(view, checked)
        if lines is not None and view.Lines != bool(lines):
            view.Lines = bool(lines)
        view.recompute()
        return view

    if not undo_step:
        return write()
    with transaction(view.Document, "Exploded view"):
        return write()


def add_step(view, moving, mode="Direction", distance=10.0, direction=(0, 0, 1), index=None, undo_step=True):
    """Adds a step moving `moving` (at the end, or before step `index`, counted from 0)."""
    now = steps(view)
    now.insert(len(now) if index is None else index, Step(moving, mode, distance, App.Vector(*direction)
                                                          if isinstance(direction, tuple) else direction))
    return set_steps(view, now, undo_step=undo_step)


def remove_step(view, index, undo_step=True):
    now = steps(view)
    if not 0 <= index < len(now):
        raise ValueError("%s has no step %d (it has %d)" % (view.Label, index + 1, len(now)))
    if len(now) == 1:
        raise ValueError("%s: its only step cannot go (delete the view instead)" % view.Label)
    del now[index]
    return set_steps(view, now, undo_step=undo_step)


def move_step(view, index, to, undo_step=True):
    """Moves step `index` to place `to` (counted from 0): the steps after apply from where it
    leaves the parts."""
    now = steps(view)
    if not (0 <= index < len(now) and 0 <= to < len(now)):
        raise ValueError("%s has steps 1 to %d" % (view.Label, len(now)))
    now.insert(to, now.pop(index))
    return set_steps(view, now, undo_step=undo_step)


def set_explosion(view, undo_step=True, step=0, lines=None, expand_sub_assemblies=None, mode=None, distance=None,
                  direction=None, parts=None):
    """Changes one step (the first by default: a view of one step is one explosion) and redraws the
    view, in one undo step; refused settings change nothing. `expand_sub_assemblies` makes the
    step move every part of the assembly, each sub-assembly as one (False) or each of its parts
    alone (True)."""
    asm = _view(view)
    now = steps(view)
    if not 0 <= step < len(now):
        raise ValueError("%s has no step %d (it has %d)" % (view.Label, step + 1, len(now)))
    s = now[step].copy()
    if mode is not None:
        s.mode = mode
    if distance is not None:
        s.distance = distance
    if direction is not None:
        s.direction = App.Vector(direction)
    if expand_sub_assemblies is not None:
        s.parts = all_units(asm, expand_sub_assemblies)
    if parts is not None:
        s.parts = list(parts)
    now[step] = s
    return set_steps(view, now, lines=lines, undo_step=undo_step)


# -- in the GUI ----------------------------------------------------------------------------------

def _drawn(asm):
    """What showing an exploded view of `asm` hides: its parts (a sub-assembly's too) and its
    joints (their markers)."""
    return objects.placed_parts(asm) + objects.joints(asm)


class ViewProviderExplodedView(objects.Stateless):
    """The exploded view in the tree (its icon) and the 3D view: drawn in its parts' colours;
    shown, it hides the assembly's parts and markers, hidden, shows them again. Double-click opens
    its panel. What it hid is state of the view (a reopened document shows what was saved)."""

    def __init__(self, vobj):
        vobj.Proxy = self
        self.attach(vobj)

    def attach(self, vobj):
        self.Object = vobj.Object
        self.hidden = None  # the names of what this view hid, when it did

    def getIcon(self):
        from .resources import icon_path

        return icon_path("Dispcon_ExplodedView.svg")

    def onChanged(self, vobj, prop):
        if prop == "Visibility" and not vobj.Object.Document.Restoring:
            self.swap(vobj.Visibility)

    def updateData(self, obj, prop):
        if prop == "Shape":
            self.colour(obj)

    def swap(self, exploded):
        """Hides the assembly's parts and markers (exploded) or shows again what it hid (all of
        them when it does not know: a reopened document)."""
        asm = getattr(self.Object, "Assembly", None)
        if asm is None:
            return
        if exploded:
            shown = [o for o in _drawn(asm) if o.ViewObject is not None and o.ViewObject.Visibility]
            self.hidden = (self.hidden or set()) | {o.Name for o in shown}
            for o in shown:
                o.ViewObject.Visibility = False
        else:
            for o in _drawn(asm):
                if o.ViewObject is not None and (self.hidden is None or o.Name in self.hidden):
                    o.ViewObject.Visibility = True
            self.hidden = None

    def colour(self, obj):
        """Each part's faces in the exploded view in that part's colours."""
        vobj = obj.ViewObject
        if vobj is None or "DiffuseColor" not in vobj.PropertiesList:
            return
        colours = []
        for part in obj.Parts:
            n = len(shape_of(part).Faces)
            source = part.ViewObject
            if source is None or "DiffuseColor" not in source.PropertiesList:
                target = part.getLinkedObject(True) if hasattr(part, "getLinkedObject") else part
                source = target.ViewObject if target is not None else None
            own = list(source.DiffuseColor) if source is not None and "DiffuseColor" in source.PropertiesList else []
            if len(own) != n:
                base = source.ShapeColor if source is not None and "ShapeColor" in source.PropertiesList \
                    else (0.8, 0.8, 0.8, 0.0)
                own = [base] * n
            colours += own
        if len(colours) == len(obj.Shape.Faces) and colours:
            vobj.DiffuseColor = colours

    def onDelete(self, vobj, subelements):
        # Deleted while shown (the Delete key): the assembled parts come back with it gone.
        if vobj.Visibility:
            self.swap(False)
        return True

    def doubleClicked(self, vobj):
        from .panels.exploded import open_panel

        open_panel(vobj.Object.Assembly, vobj.Object)
        return True


def show(view, exploded=True):
    """Shows the exploded view (the assembly's parts hidden) or the assembly (the view hidden).
    Without the GUI it sets what the document stores of it (each object's Visibility), so a
    document saved by freecadcmd opens in a GUI, with the workbench or without it, showing the
    view or the parts, not both on top of each other."""
    vobj = view.ViewObject
    if vobj is None:
        asm = getattr(view, "Assembly", None)
        for o, on in [(view, bool(exploded))] + [(o, not exploded) for o in (_drawn(asm) if asm is not None else [])]:
            if o.Visibility != on:
                o.Visibility = on
        return
    proxy = vobj.Proxy
    if vobj.Visibility != bool(exploded):
        vobj.Visibility = bool(exploded)  # onChanged swaps
    elif isinstance(proxy, ViewProviderExplodedView):
        proxy.swap(bool(exploded))
