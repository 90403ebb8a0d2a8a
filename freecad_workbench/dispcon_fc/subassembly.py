"""Sub-assemblies: an assembly placed inside another, from this document or linked from another
.FCStd, as FreeCAD 1.x's AssemblyLink.

An instance is a group in the parent assembly (objects.SubAssemblyProxy) with one App::Link per
part of the assembly it places. Each link's placement in the instance's frame (LocalPlacement)
and in the world (Placement) are stored in the parent's document, so the same leg used four
times keeps four sets of poses and solving the parent never changes the linked file.

- Rigid (the default, as in FreeCAD 1.x): the placed assembly's own joints are solved once, in
  its own frame, from its parts' placements in its document; the instance enters the parent's
  solve as one body (its Placement) whose parts carry the parent's joints.
- Flexible: every link is a body of the parent's solve, and the placed assembly's joints join it
  between this instance's links (each instance has its own copies). A part grounded in the placed
  assembly is not grounded here: the parent's joints hold the instance (as in FreeCAD 1.x).

One level: an assembly that has sub-assemblies of its own cannot be placed yet."""
import os

import FreeCAD as App

from . import objects


def same(a, b):
    """Whether two placements are the same to the bit (FreeCAD 0.20's Placement has no isSame):
    an unchanged placement is not written, so an instance nothing moved is not touched."""
    return tuple(a.Base) == tuple(b.Base) and tuple(a.Rotation.Q) == tuple(b.Rotation.Q)


def source_of(sub):
    """The assembly an instance places, refusing one that is gone (its file moved away)."""
    src = sub.Assembly if "Assembly" in sub.PropertiesList else None
    if src is None or not objects.is_assembly(src):
        raise ValueError("%s: the assembly it places is gone (its file was moved or deleted)" % sub.Label)
    return src


def _source_part(link):
    return link.getLinkedObject(False) if link.LinkedObject is not None else None


def links_by_source(sub):
    """{source part Name: link} of an instance."""
    out = {}
    for link in objects.instance_parts(sub):
        src = link.LinkedObject
        if src is not None:
            out[src.Name] = link
    return out


def resolve(asm, obj, sub):
    """A reference in FreeCAD's forms as (object, element): (part, "Edge3"); (instance,
    "Crank.Edge3") or (assembly, "Leg1.Crank.Edge3"), the part named by its Name or Label in the
    placed assembly (or the instance by its Name or Label in `asm`). Returns (part, "Edge3")."""
    if objects.is_assembly(obj) and "." in sub:
        head, rest = sub.split(".", 1)
        inst = next((s for s in objects.sub_assemblies(obj) if head in (s.Name, s.Label)), None)
        if inst is None:
            raise ValueError("%s has no sub-assembly %s" % (obj.Label, head))
        return resolve(asm, inst, rest)
    if objects.is_sub_assembly(obj):
        if "." not in sub:
            raise ValueError("%s.%s: name a part of the sub-assembly and its element (Crank.Edge3)"
                             % (obj.Label, sub))
        head, rest = sub.split(".", 1)
        for link in objects.instance_parts(obj):
            src = link.LinkedObject
            if head in (link.Name, link.Label) or (src is not None and head in (src.Name, src.Label)):
                return link, rest
        raise ValueError("%s has no part %s (parts: %s)"
                         % (obj.Label, head, ", ".join(l.LinkedObject.Label for l in objects.instance_parts(obj)
                                                       if l.LinkedObject is not None)))
    return obj, sub


def _places(src, asm):
    """Whether placing `src` would place `asm` inside itself."""
    if src == asm:
        return True
    return any(_places(s.Assembly, asm) for s in objects.sub_assemblies(src) if s.Assembly is not None)


def _open_assembly(path, label):
    from .operations import _doc_name

    # Absolute: FreeCAD stores the link relative to the parent's file, from the path it is given.
    path = os.path.abspath(path)
    if os.path.splitext(path)[1].lower() != ".fcstd":
        raise ValueError("%s: expected a FreeCAD document (.FCStd)" % path)
    if not os.path.isfile(path):
        raise ValueError("%s: no such file" % path)
    name = _doc_name(path)
    doc = App.getDocument(name) if name else App.openDocument(path)
    found = objects.top_assemblies(doc)
    if label is not None:
        found = [o for o in found if label in (o.Label, o.Name)]
    if len(found) != 1:
        raise ValueError("%s: %s (name one of: %s)" % (
            path, "no assembly" + (" labelled %s" % label if label else "") if not found else "several assemblies",
            ", ".join(o.Label for o in doc.Objects if objects.is_assembly(o)) or "none"))
    return found[0]


def insert_sub_assembly(asm, source, label=None, placement=None, rigid=True, name=None):
    """Places an assembly inside `asm`: `source` is an assembly object (of this document or of
    another open one) or the path of an .FCStd (its top-level assembly, or the one labelled
    `label`). `placement` puts the instance's frame (the placed assembly's origin); rigid=False
    makes its parts and joints join the parent's solve. One undo step; returns the instance."""
    from .operations import _assembly, transaction

    _assembly(asm)
    if isinstance(source, str):
        if not asm.Document.FileName:
            raise ValueError("save %s before placing assemblies from other files" % asm.Document.Label)
        source = _open_assembly(source, label)
    if not objects.is_assembly(source):
        raise ValueError("%s is not a Dispcon assembly" % getattr(source, "Label", source))
    if _places(source, asm):
        raise ValueError("%s cannot be placed inside %s: it would contain itself" % (source.Label, asm.Label))
    if objects.sub_assemblies(source):
        raise ValueError("%s has sub-assemblies of its own: one level of sub-assemblies only (not done yet)"
                         % source.Label)
    if source.Document != asm.Document and not (asm.Document.FileName and source.Document.FileName):
        raise ValueError("save %s and %s before linking one into the other"
                         % (asm.Document.Label, source.Document.Label))
    src_parts = objects.parts(source)
    if not src_parts:
        raise ValueError("%s has no part to place" % source.Label)
    placement = placement or App.Placement()
    doc = asm.Document
    with transaction(doc, "Insert sub-assembly"):
        sub = objects.new_sub_assembly(doc, name or source.Label)
        sub.Label = name or source.Label
        sub.Assembly = source
        sub.Rigid = bool(rigid)
        sub.Placement = placement
        for p in src_parts:
            _new_link(sub, p)
        asm.addObject(sub)
    return sub


def _new_link(sub, part):
    """The instance's link to `part` of the placed assembly, where that assembly has it."""
    doc = sub.Document
    link = doc.addObject("App::Link", "%s_%s" % (sub.Name, part.Name))
    link.Label = "%s.%s" % (sub.Label, part.Label)
    link.LinkedObject = part
    instance_link_properties(link)
    link.LocalPlacement = part.Placement
    link.Placement = sub.Placement.multiply(part.Placement)
    sub.addObject(link)
    return link


def out_of_step(asm):
    """The instances of `asm` whose placed assembly gained or lost parts since they were made."""
    out = []
    for sub in objects.sub_assemblies(asm):
        src = sub.Assembly if "Assembly" in sub.PropertiesList else None
        if src is None or not objects.is_assembly(src):
            continue  # gone: source_of says so where it matters
        linked = set(links_by_source(sub))
        now = {p.Name for p in objects.parts(src)}
        if linked != now or any(l.LinkedObject is None for l in objects.instance_parts(sub)):
            out.append(sub)
    return out


def bring_in_step(asm):
    """Each instance of `asm` gets a link for a part its placed assembly gained, and loses the
    link of a part it lost (a joint of the parent on it is then skipped and named)."""
    for sub in out_of_step(asm):
        src = source_of(sub)
        now = {p.Name: p for p in objects.parts(src)}
        for link in objects.instance_parts(sub):
            if link.LinkedObject is None or link.LinkedObject.Name not in now:
                sub.removeObject(link)
                sub.Document.removeObject(link.Name)
        linked = links_by_source(sub)
        for name, part in now.items():
            if name not in linked:
                _new_link(sub, part)


def instance_link_properties(link):
    """A link's own part properties. An App::Link reads a property it lacks from the object it
    links (hasattr would see the placed part's Grounded): each is added by name, and a part
    grounded in the placed assembly is free here (the parent's joints hold the instance)."""
    objects._add(link, "App::PropertyPlacement", "LocalPlacement", "Sub-assembly",
                 "this part's placement in its instance's frame (stored here, per instance)")
    objects._add(link, "App::PropertyBool", "Grounded", "Dispcon", "never moves", False)
    objects._add(link, "App::PropertyFloat", "AbilityToRotate", "Dispcon",
                 "no-physics ability to rotate (0: from the part's size)")
    objects._add(link, "App::PropertyFloat", "Density", "Dispcon", "mass per unit volume",
                 getattr(link.LinkedObject, "Density", 1.0))


def set_rigid(sub, rigid=True):
    """Makes an instance move as one part (True) or join its parts' joints to the parent's solve
    (False), in one undo step."""
    from .operations import transaction

    if not objects.is_sub_assembly(sub):
        raise ValueError("%s is not a sub-assembly" % sub.Label)
    with transaction(sub.Document, "Rigid" if rigid else "Flexible"):
        sub.Rigid = bool(rigid)
    return sub


class InstanceJoint:
    """A joint of a placed assembly as it holds in one flexible instance: its references are
    the instance's links; everything else is read from the joint in the placed assembly (which
    is never written to). Its Label is the instance's and the joint's: Leg1.Revolute."""

    def __init__(self, joint, instance, ref1, ref2):
        self.source, self.instance = joint, instance
        self.Label = "%s.%s" % (instance.Label, joint.Label)
        self.Reference1, self.Reference2 = ref1, ref2

    def __getattr__(self, name):
        return getattr(self.source, name)


def solved_locals(sub):
    """The placed assembly's parts solved in its own frame (its joints, its grounded parts),
    from their placements in its document, which is not changed: {source part Name: Placement}."""
    from .adapter import Adapter
    from .operations import tolerance

    src = source_of(sub)
    inner = Adapter(src)
    with inner.engine_errors():
        r = inner.model.assemble(tolerance=tolerance(src), max_iterations=src.MaxIterations)
    if not r.converged:
        raise ValueError("%s: the joints of %s do not hold (%s)" % (sub.Label, src.Label, inner.labelled(r.message)))
    return {p.Name: inner.placement_of(p) for p in inner.parts}


def add_instances(adapter, physics):
    """The parent's adapter gets the bodies of `adapter.asm`'s sub-assemblies (one per rigid
    instance, one per part of a flexible one) and returns the flexible instances' joints. What
    does not depend on where an instance is (the placed assembly solved in its frame, the mass
    properties of its parts in their own frames) is computed once per placed assembly."""
    import Part

    from .adapter import local_mass

    def key(obj):
        return (obj.Document.Name, obj.Name)

    rigid_once, part_once = {}, {}
    extra = []
    for sub in objects.sub_assemblies(adapter.asm):
        src = source_of(sub)
        links = links_by_source(sub)
        missing = [p.Label for p in objects.parts(src) if p.Name not in links]
        if missing:
            raise ValueError("%s: %s has parts this instance lacks (%s): Solve brings them in"
                             % (sub.Label, src.Label, ", ".join(missing)))
        if sub.Rigid:
            if key(src) not in rigid_once:
                local = solved_locals(sub)
                shapes = []
                for name, link in links.items():
                    if name in local:  # else a part since removed from the placed assembly
                        s = objects.shape_of(link).copy()
                        s.Placement = local[name].multiply(link.Placement.inverse()).multiply(s.Placement)
                        shapes.append(s)
                rigid_once[key(src)] = (local, local_mass(Part.makeCompound(shapes), App.Placement()))
            local, mass = rigid_once[key(src)]
            placed = {link.Name: local[name] for name, link in links.items() if name in local}
            body = adapter.add_body(sub, None, physics, local=mass)
            for link_name, pl in placed.items():
                adapter.frames[link_name] = (body, pl)
            adapter.rigid[sub.Name] = placed
        else:
            for link in links.values():
                source = link.LinkedObject
                if key(source) not in part_once:
                    part_once[key(source)] = local_mass(objects.shape_of(link), link.Placement)
                adapter.add_body(link, None, physics, local=part_once[key(source)])
            for j in objects.joints(src):
                refs = []
                for ref in (j.Reference1, j.Reference2):
                    link = links.get(ref[0].Name) if ref and ref[0] is not None else None
                    refs.append((link, ref[1]) if link is not None else None)
                extra.append(InstanceJoint(j, sub, *refs))
    return extra


def write_back(adapter):
    """After the parent's bodies are written: a rigid instance's parts follow its Placement; a
    flexible instance's parts keep their placements in its frame up to date."""
    for sub in objects.sub_assemblies(adapter.asm):
        if sub.Name in adapter.rigid:
            for link in objects.instance_parts(sub):
                local = adapter.rigid[sub.Name].get(link.Name)
                if local is None:
                    continue
                if not same(local, link.LocalPlacement):
                    link.LocalPlacement = local
                placed = sub.Placement.multiply(local)
                if not same(placed, link.Placement):
                    link.Placement = placed
        else:
            inverse = sub.Placement.inverse()
            for link in objects.instance_parts(sub):
                if link.Name in adapter.names:
                    local = inverse.multiply(link.Placement)
                    if not same(local, link.LocalPlacement):
                        link.LocalPlacement = local


def snapshot(asm):
    """Every placement a motion of `asm` can change (its parts, its instances and their parts);
    calling the result puts them back."""
    saved = [(o, o.Placement) for o in objects.parts(asm)]
    for sub in objects.sub_assemblies(asm):
        saved.append((sub, sub.Placement))
        saved += [(link, link.Placement, link.LocalPlacement) for link in objects.instance_parts(sub)]

    def restore():
        for entry in saved:
            if len(entry) == 3 and not same(entry[2], entry[0].LocalPlacement):
                entry[0].LocalPlacement = entry[2]
            if not same(entry[1], entry[0].Placement):
                entry[0].Placement = entry[1]

    return restore
