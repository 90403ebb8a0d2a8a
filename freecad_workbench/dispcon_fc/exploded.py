"""Exploded views: an assembly drawn with its parts moved apart, as a designer shows how it goes
together, without moving a part.

An exploded view is its own object of the document (a Part::FeaturePython, as FreeCAD 1.x's
Assembly keeps its exploded views as objects): its shape is a compound of copies of the parts,
each moved by its offset, with a line from where each part sits to where it is drawn. The parts'
Placements are never written: the joints, a solve, a drag and a saved file all see the assembled
pose whether the view is shown or not, so showing the assembled parts again restores every
placement to the bit (there is nothing to restore), and a document saved while the exploded view
is shown reopens assembled, with its exploded view beside it. (A tool that moved the parts would
have to refuse to save, or save the exploded pose as the assembly's; neither is what a designer
expects of a view.) Showing the view hides the parts and the joints' markers, hiding it shows
them again (viewproviders.ViewProviderExplodedView).

What moves (units): each part of the assembly; each placed sub-assembly as one unit (all its
parts, those of the sub-assemblies nested in it too, by one offset), or each of those parts alone
when ExpandSubAssemblies is on. Where a unit's
centre is: the centre of its bounding box. The offsets:
- Radial: each unit moves away from the assembly's centre (the centre of the box around every
  part) along the line from that centre to its own, in proportion to its distance from it, the
  farthest unit by Distance: offset = Distance x (c - C) / max |c - C|;
- Direction: the units in order of their centres along Direction (ties, within a millionth of
  the assembly's size, sharing a place), the first staying and each next one Distance further
  than the one before: offset = Distance x rank x Direction (unit)."""
import FreeCAD as App

from . import objects
from .objects import is_sub_assembly, parts, shape_of

MODES = ("Radial", "Direction")


class ExplodedViewProxy(objects.Stateless):
    """The exploded view's proxy: its shape is made from its properties and the parts' shapes at
    every recompute (it holds nothing of its own)."""

    def __init__(self, obj):
        obj.Proxy = self
        self.attach(obj)

    def attach(self, obj):
        objects._mark(obj, "ExplodedView")
        add = objects._add
        add(obj, "App::PropertyLink", "Assembly", "Exploded view", "the assembly drawn exploded")
        if "Mode" not in obj.PropertiesList:
            obj.addProperty("App::PropertyEnumeration", "Mode", "Exploded view",
                            "Radial: away from the assembly's centre; Direction: stacked along Direction")
            obj.Mode = list(MODES)
        add(obj, "App::PropertyVector", "Direction", "Exploded view", "the direction of a Direction explosion",
            App.Vector(0, 0, 1))
        add(obj, "App::PropertyDistance", "Distance", "Exploded view",
            "Radial: how far the farthest part moves; Direction: the step between two parts")
        add(obj, "App::PropertyBool", "ExpandSubAssemblies", "Exploded view",
            "each part of a placed sub-assembly moves alone (off: the sub-assembly moves as one)")
        add(obj, "App::PropertyBool", "Lines", "Exploded view", "a line from each part's place to where it is drawn",
            True)
        add(obj, "App::PropertyLinkList", "Parts", "Result", "the parts drawn, in the order of Offsets")
        add(obj, "App::PropertyVectorList", "Offsets", "Result", "how far each part is drawn from its place")
        for name in ("Parts", "Offsets"):
            obj.setEditorMode(name, 1)  # read only: made from the settings

    def onDocumentRestored(self, obj):
        self.attach(obj)
        if App.GuiUp and obj.ViewObject is not None and obj.ViewObject.Proxy in (None, 0):
            ViewProviderExplodedView(obj.ViewObject)

    def execute(self, obj):
        asm = obj.Assembly
        if asm is None or not objects.is_assembly(asm):
            raise ValueError("%s: its assembly is gone" % obj.Label)
        moved = offsets(asm, obj.Mode, obj.Direction, obj.Distance.Value, obj.ExpandSubAssemblies)
        names = [p for p, _ in moved]
        if list(obj.Parts) != names:
            obj.Parts = names
        vectors = [v for _, v in moved]
        if [tuple(v) for v in obj.Offsets] != [tuple(v) for v in vectors]:
            obj.Offsets = vectors
        obj.Shape = exploded_shape(moved, obj.Lines)  # last: the view colours it by Parts


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


def _box(shapes):
    box = App.BoundBox()
    for s in shapes:
        box.add(s.BoundBox)
    return box


def offsets(asm, mode="Radial", direction=App.Vector(0, 0, 1), distance=0.0, expand_sub_assemblies=False):
    """[(part, offset)] for every part of `asm` (the module's rules), its parts where they are."""
    if mode not in MODES:
        raise ValueError("exploded view: mode is one of %s, not %r" % (", ".join(MODES), mode))
    groups = units(asm, expand_sub_assemblies)
    if not groups:
        return []
    shapes = [[shape_of(p) for p in g] for g in groups]
    centres = [_box(s).Center for s in shapes]
    whole = _box([s for g in shapes for s in g])
    size = max(whole.DiagonalLength, 1e-12)
    if mode == "Radial":
        centre = whole.Center
        reach = max((c - centre).Length for c in centres)
        scale = distance / reach if reach > 1e-9 * size else 0.0
        moves = [(c - centre) * scale for c in centres]
    else:
        if direction.Length < 1e-12:
            raise ValueError("exploded view: the direction has no length")
        d = App.Vector(direction)
        d.normalize()
        along = [c.dot(d) for c in centres]
        levels = []
        for a in sorted(along):
            if not levels or a - levels[-1] > 1e-6 * size:
                levels.append(a)
        rank = [next(k for k, level in enumerate(levels) if abs(a - level) <= 1e-6 * size) for a in along]
        moves = [d * (distance * k) for k in rank]
    return [(p, App.Vector(move)) for g, move in zip(groups, moves) for p in g]


def exploded_shape(moved, lines=True):
    """A compound of each part's shape moved by its offset, then (lines) a line from each moved
    part's centre at its place to where it is drawn."""
    import Part

    pieces, trails = [], []
    for part, offset in moved:
        shape = shape_of(part).copy()
        centre = shape.BoundBox.Center
        if offset.Length > 0:
            shape.translate(offset)
            if lines:
                trails.append(Part.makeLine(centre, centre + offset))
        pieces.append(shape)
    return Part.makeCompound(pieces + trails)


def views_of(asm):
    """The exploded views of `asm` in its document."""
    return [o for o in asm.Document.Objects
            if getattr(o, "DispconType", "") == "ExplodedView" and getattr(o, "Assembly", None) == asm]


def follow(asm):
    """Redraws every exploded view of `asm` from the parts' placements as they are now, in
    whatever undo step is open: a Solve's or a drag's (operations.solve, _Motion.finish), so the
    view shows the new pose at once, not at the next recompute, and undo takes the view back with
    the parts. Writes no placement."""
    for view in views_of(asm):
        view.recompute()


def is_exploded_view(obj):
    return getattr(obj, "DispconType", "") == "ExplodedView"


def new_exploded_view(asm, mode="Radial", distance=None, direction=None, expand_sub_assemblies=False,
                      lines=True, undo_step=True):
    """An exploded view of `asm` (a new object of its document, the parts untouched), in one undo
    step; `distance` in mm (by default half the assembly's size). Returns it."""
    from .operations import _assembly, transaction

    _assembly(asm)
    if not parts(asm) and not any(is_sub_assembly(o) for o in asm.Group):
        raise ValueError("%s has no part to explode" % asm.Label)
    if distance is None:
        groups = units(asm, expand_sub_assemblies)
        distance = 0.5 * _box([shape_of(p) for g in groups for p in g]).DiagonalLength
    doc = asm.Document

    def make():
        obj = doc.addObject("Part::FeaturePython", "ExplodedView")
        ExplodedViewProxy(obj)
        obj.Label = "Exploded view of %s" % asm.Label
        obj.Assembly = asm
        _set(obj, mode=mode, distance=distance, direction=direction,
             expand_sub_assemblies=expand_sub_assemblies, lines=lines)
        if App.GuiUp and obj.ViewObject is not None:
            ViewProviderExplodedView(obj.ViewObject)
        obj.recompute()
        if App.GuiUp:
            show(obj, True)
        return obj

    if not undo_step:
        return make()
    with transaction(doc, "Exploded view"):
        return make()


def _set(obj, mode=None, distance=None, direction=None, expand_sub_assemblies=None, lines=None):
    if mode is not None:
        if mode not in MODES:
            raise ValueError("exploded view: mode is one of %s, not %r" % (", ".join(MODES), mode))
        obj.Mode = mode
    if direction is not None:
        direction = App.Vector(direction)
        if direction.Length < 1e-12:
            raise ValueError("exploded view: the direction has no length")
        obj.Direction = direction
    if distance is not None:
        if not (distance == distance and abs(distance) < 1e12):
            raise ValueError("exploded view: the distance must be a number (it is %r)" % distance)
        obj.Distance = distance
    if expand_sub_assemblies is not None:
        obj.ExpandSubAssemblies = bool(expand_sub_assemblies)
    if lines is not None:
        obj.Lines = bool(lines)


def set_explosion(view, undo_step=True, **settings):
    """Changes an exploded view's settings (mode, distance, direction, expand_sub_assemblies,
    lines) and redraws it, in one undo step; refused settings change nothing."""
    from .operations import transaction

    if not is_exploded_view(view):
        raise ValueError("%s is not an exploded view" % getattr(view, "Label", view))
    if not undo_step:
        _set(view, **settings)
        view.recompute()
        return view
    with transaction(view.Document, "Exploded view"):
        _set(view, **settings)
        view.recompute()
    return view


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
    """Shows the exploded view (the assembly's parts hidden) or the assembly (the view hidden)."""
    vobj = view.ViewObject
    if vobj is None:
        return
    proxy = vobj.Proxy
    if vobj.Visibility != bool(exploded):
        vobj.Visibility = bool(exploded)  # onChanged swaps
    elif isinstance(proxy, ViewProviderExplodedView):
        proxy.swap(bool(exploded))
