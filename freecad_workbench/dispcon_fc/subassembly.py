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

Nested, to any depth (as FreeCAD 1.x's AssemblyLinks): an instance of an assembly that has
sub-assemblies of its own holds, beside its links, one nested instance per such sub-assembly
(a group of the same kind, its SourceName the Name of the sub-assembly it mirrors, its
LocalPlacement its frame in the instance's), and so on down. Each level means what it means at
the top: a rigid instance is one body (everything inside it solved once, in its frame, as its
file has it), a flexible one's links are bodies and its placed assembly's joints join the solve.
Rigid is a property of each place, at every level: a nested instance starts as its counterpart
is in the placed file (RigidInFile keeps what the file said), follows the file while it was not
set here (Rigid equal to RigidInFile), and keeps what the designer set here otherwise; inside a
rigid instance it means nothing (the rigid one is its file as it is) and is read only. Every pose
and setting of every level is stored in the parent's document. An assembly placed inside itself,
directly or through files, is refused, naming the chain."""
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


def is_nested(inst):
    """Whether an instance is nested in another (it mirrors a sub-assembly of the assembly that
    one places) rather than placed by the designer in an assembly."""
    return bool(getattr(inst, "SourceName", ""))


def key(obj):
    return (obj.Document.Name, obj.Name)


def tree(inst):
    """{path: object} of everything inside an instance, at any depth: a link by the Name of the
    part it places, a nested instance by the Name of the sub-assembly it mirrors, the insides of
    a nested instance below its path. The same paths name the same things in the placed
    assembly (source_tree), whichever document each is in."""
    out = {}
    for o in inst.Group:
        if objects.is_sub_assembly(o) and is_nested(o):
            out[(o.SourceName,)] = o
            for path, d in tree(o).items():
                out[(o.SourceName,) + path] = d
        elif o.TypeId == "App::Link" and "LocalPlacement" in o.PropertiesList and o.LinkedObject is not None:
            out[(o.LinkedObject.Name,)] = o
    return out


def source_tree(asm):
    """{path: object} of an assembly: its parts, its sub-assemblies and everything inside them
    (tree), as an instance of it names them."""
    out = {(p.Name,): p for p in objects.parts(asm)}
    for s in objects.sub_assemblies(asm):
        out[(s.Name,)] = s
        for path, d in tree(s).items():
            out[(s.Name,) + path] = d
    return out


def _label(inst, head):
    """Whether `head` names the nested instance `inst` (its Name, its Label, the Name of the
    sub-assembly it mirrors, or that sub-assembly's Label after its container's)."""
    return head in (inst.Name, inst.Label, getattr(inst, "SourceName", "")) or inst.Label.endswith("." + head)


def resolve(asm, obj, sub):
    """A reference in FreeCAD's forms as (object, element): (part, "Edge3"); (instance,
    "Crank.Edge3") or (assembly, "Leg1.Crank.Edge3"), the part named by its Name or Label in the
    placed assembly (or the instance by its Name or Label in `asm`); nested instances the same
    way, to any depth: (assembly, "Walk2.Leg1.Crank.Edge3"), (instance, "Leg1.Crank.Edge3").
    Returns (part, "Edge3")."""
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
        for inst in objects.sub_assemblies(obj):
            if _label(inst, head):
                return resolve(asm, inst, rest)
        raise ValueError("%s has no part %s (parts: %s)"
                         % (obj.Label, head, ", ".join([l.LinkedObject.Label for l in objects.instance_parts(obj)
                                                        if l.LinkedObject is not None]
                                                       + [n.Label.rsplit(".", 1)[-1] + " (a sub-assembly)"
                                                          for n in objects.sub_assemblies(obj)])))
    return obj, sub


def _where(doc):
    return os.path.basename(doc.FileName) if doc.FileName else doc.Label


def _chain(src, asm, seen=()):
    """The places by which placing `src` would place `asm` inside itself: ["Walker", "Leg1 (Leg
    in leg.FCStd)", ...] ending at `asm`, or None when it would not."""
    if key(src) == key(asm):
        return ["%s (%s)" % (src.Label, _where(src.Document))]
    if key(src) in seen:
        return None
    for s in objects.sub_assemblies(src):
        inner = s.Assembly if "Assembly" in s.PropertiesList else None
        if inner is None:
            continue
        rest = _chain(inner, asm, seen + (key(src),))
        if rest is not None:
            return ["%s > %s" % (src.Label, s.Label)] + rest
    return None


def _places(src, asm):
    """Whether placing `src` would place `asm` inside itself."""
    return _chain(src, asm) is not None


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
    makes its parts and joints join the parent's solve. An assembly with sub-assemblies of its
    own is placed with them (nested instances, each rigid or flexible as it is there). One undo
    step; returns the instance."""
    from .operations import _assembly, transaction

    _assembly(asm)
    if isinstance(source, str):
        if not asm.Document.FileName:
            raise ValueError("save %s before placing assemblies from other files" % asm.Document.Label)
        source = _open_assembly(source, label)
    if not objects.is_assembly(source):
        raise ValueError("%s is not a Dispcon assembly" % getattr(source, "Label", source))
    chain = _chain(source, asm)
    if chain is not None:
        raise ValueError("%s cannot be placed inside %s: it would contain itself (%s)"
                         % (source.Label, asm.Label, " > ".join(chain)))
    if source.Document != asm.Document and not (asm.Document.FileName and source.Document.FileName):
        raise ValueError("save %s and %s before linking one into the other"
                         % (asm.Document.Label, source.Document.Label))
    if not objects.parts(source) and not objects.sub_assemblies(source):
        raise ValueError("%s has no part to place" % source.Label)
    for s in objects.sub_assemblies(source):
        source_of(s)  # one that is gone is named before anything is made
    placement = placement or App.Placement()
    doc = asm.Document
    with transaction(doc, "Insert sub-assembly"):
        sub = objects.new_sub_assembly(doc, name or source.Label)
        sub.Label = name or source.Label
        sub.Assembly = source
        sub.Rigid = bool(rigid)
        sub.Placement = placement
        for p in objects.parts(source):
            _new_link(sub, p, p.Placement)
        for s in objects.sub_assemblies(source):
            _new_nested(sub, s, s.Name, s.Label, s.Placement)
        asm.addObject(sub)
        _as_in_file(sub)
    return sub


def _new_link(sub, part, local):
    """The instance's link to `part` of the placed assembly, at `local` in the instance's frame."""
    doc = sub.Document
    link = doc.addObject("App::Link", "%s_%s" % (sub.Name, part.Name))
    link.Label = "%s.%s" % (sub.Label, part.Label)
    link.LinkedObject = part
    instance_link_properties(link)
    link.LocalPlacement = local
    link.Placement = sub.Placement.multiply(local)
    sub.addObject(link)
    return link


def nested_properties(inst):
    objects._add(inst, "NestedInstance", "App::PropertyString", "SourceName", "Sub-assembly")
    objects._add(inst, "NestedInstance", "App::PropertyPlacement", "LocalPlacement", "Sub-assembly")
    objects.nested_rigidity_property(inst)
    inst.setEditorMode("SourceName", 1)


def _new_nested(container, like, source_name, label, local):
    """A nested instance in `container` mirroring the sub-assembly named `source_name` of the
    assembly `container` places, made like `like` (that sub-assembly, or an instance mirroring
    it: its assembly, rigidity, links' and nested instances' poses), at `local`."""
    doc = container.Document
    inst = objects.new_sub_assembly(doc, "%s_%s" % (container.Name, source_name))
    nested_properties(inst)
    inst.Label = "%s.%s" % (container.Label, label)
    inst.SourceName = source_name
    inst.Assembly = source_of(like)
    inst.Rigid = inst.RigidInFile = rigid_of(like)
    inst.LocalPlacement = local
    inst.Placement = container.Placement.multiply(local)
    for link in objects.instance_parts(like):
        if link.LinkedObject is not None:
            _new_link(inst, link.LinkedObject, link.LocalPlacement)
    for n in objects.sub_assemblies(like):
        _new_nested(inst, n, n.SourceName, _mirror_label(n), n.LocalPlacement)
    container.addObject(inst)
    return inst


def _as_in_file(new):
    """New nested instances (`new` and those inside it, in their containers by now) rigid or
    flexible as the placed file has their places (`like` may have been another place's copy),
    their Rigid editable or not; then returns `new`."""
    for o in [new] + [d for d in tree(new).values() if objects.is_sub_assembly(d)]:
        f = file_rigid(o)
        if f is not None and (f != bool(o.Rigid) or f != _held(o)):
            o.Rigid = o.RigidInFile = f
    rigid_modes(new)
    return new


def _top(inst):
    """(the instance placed by the designer that holds `inst`, the SourceNames from it down to
    `inst`): (Walk2, ["Leg3"]) for Walk2.Leg3; (inst, []) for a top one; (None, path) when a
    container is gone."""
    path = []
    while inst is not None and is_nested(inst):
        path.insert(0, inst.SourceName)
        inst = container_of(inst)
    return inst, path


def counterpart(inst):
    """What a nested instance is in the file its top instance places: the instance at the same
    path there (Walk2.Leg3 of a festival's P1: the parade's Walk2.Leg3), or None when gone."""
    top, path = _top(inst)
    if top is None or not path:
        return None
    try:
        src = source_of(top)
    except ValueError:
        return None
    return source_tree(src).get(tuple(path))


def file_rigid(inst):
    """Whether the placed file has a nested instance's place rigid (None: not nested, or gone)."""
    c = counterpart(inst) if is_nested(inst) else None
    return rigid_of(c) if c is not None and objects.is_sub_assembly(c) else None


def _held(inst):
    return bool(inst.RigidInFile) if "RigidInFile" in inst.PropertiesList else bool(inst.Rigid)


def rigid_of(inst):
    """Whether an instance moves as one part here: its Rigid; a nested one not set here (Rigid
    as its file had it when it took it, RigidInFile) follows its file as it is now."""
    if not is_nested(inst):
        return bool(inst.Rigid)
    if bool(inst.Rigid) != _held(inst):
        return bool(inst.Rigid)  # set in this place
    f = file_rigid(inst)
    return bool(inst.Rigid) if f is None else f


def locked_by(inst):
    """The rigid instance `inst` is inside (the nearest), or None: inside a rigid one, a nested
    instance is as that one's file has it, whatever it says."""
    c = container_of(inst) if is_nested(inst) else None
    while c is not None and objects.is_sub_assembly(c):
        if rigid_of(c):
            return c
        c = container_of(c) if is_nested(c) else None
    return None


def rigid_modes(inst):
    """The property editor shows each nested instance's Rigid inside `inst` (and its own) editable,
    or read only where a rigid instance holds it."""
    for o in [inst] + [d for d in tree(inst).values() if objects.is_sub_assembly(d)]:
        if is_nested(o):
            mode = 1 if locked_by(o) is not None else 0
            if o.getEditorMode("Rigid") != ([] if mode == 0 else ["ReadOnly"]):
                o.setEditorMode("Rigid", mode)


def _mirror_label(nested):
    """The Label of the sub-assembly a nested instance mirrors."""
    m = mirror_of(nested)
    return m.Label if m is not None else nested.Label.rsplit(".", 1)[-1]


def container_of(inst):
    return next((o for o in inst.InList if objects.is_assembly(o) or objects.is_sub_assembly(o)), None)


def mirror_of(inst, container=None):
    """The sub-assembly a nested instance mirrors, in the assembly its container places; None
    when that assembly no longer has it."""
    container = container or container_of(inst)
    if container is None:
        return None
    return next((s for s in objects.sub_assemblies(source_of(container)) if s.Name == inst.SourceName), None)


def _lacks(inst):
    """What an instance lacks of the assembly it places, or has that it lost (this level only):
    (labels lacking, objects to remove)."""
    src = source_of(inst)
    parts_now = {p.Name: p for p in objects.parts(src)}
    subs_now = {s.Name: s for s in objects.sub_assemblies(src)}
    have = set()
    extra = []
    for o in inst.Group:
        if objects.is_sub_assembly(o):
            if o.SourceName in subs_now:
                have.add(o.SourceName)
            else:
                extra.append(o)
        elif o.TypeId == "App::Link" and "LocalPlacement" in o.PropertiesList:
            if o.LinkedObject is not None and o.LinkedObject.Name in parts_now:
                have.add(o.LinkedObject.Name)
            else:
                extra.append(o)
    lacking = [o.Label for n, o in list(parts_now.items()) + list(subs_now.items()) if n not in have]
    return lacking, extra


def _same_source(nested, mirror):
    """Whether a nested instance places the assembly the sub-assembly it mirrors places."""
    a = nested.Assembly if "Assembly" in nested.PropertiesList else None
    b = mirror.Assembly if "Assembly" in mirror.PropertiesList else None
    return a is not None and b is not None and key(a) == key(b)


def _in_step(inst):
    if "Assembly" not in inst.PropertiesList or inst.Assembly is None or not objects.is_assembly(inst.Assembly):
        return True  # gone: source_of says so where it matters
    lacking, extra = _lacks(inst)
    if lacking or extra:
        return False
    for n in objects.sub_assemblies(inst):
        m = mirror_of(n, inst)
        if m is None or _file_changed(n) or not _same_source(n, m) or not _in_step(n):
            return False
    return True


def _file_changed(n):
    """Whether the placed file now has a nested instance's place rigid where it had it flexible,
    or the other way round (RigidInFile)."""
    f = file_rigid(n)
    return f is not None and f != _held(n)


def out_of_step(asm):
    """The instances of `asm` whose placed assembly (or one nested in it) gained or lost parts or
    sub-assemblies since they were made, or whose nested instances' rigidity changed in their
    placed file."""
    return [sub for sub in objects.sub_assemblies(asm) if not _in_step(sub)]


def _remove(obj):
    for o in list(getattr(obj, "Group", [])) if objects.is_sub_assembly(obj) else []:
        _remove(o)
    container = container_of(obj)
    if container is not None:
        container.removeObject(obj)
    obj.Document.removeObject(obj.Name)


def _bring(inst, chain):
    src = source_of(inst)
    _refuse_cycle(inst, src, chain)  # before anything is made: a cycle's copies would never end
    lacking, extra = _lacks(inst)
    for o in extra:
        _remove(o)
    have = tree(inst)
    for p in objects.parts(src):
        if (p.Name,) not in have:
            _new_link(inst, p, p.Placement)
    for s in objects.sub_assemblies(src):
        if (s.Name,) not in have:
            like = s
            if is_nested(inst):  # like the container's mirror's own nested instance, where it has one
                m = mirror_of(inst)
                like = next((n for n in objects.sub_assemblies(m) if n.SourceName == s.Name), s) if m else s
            _as_in_file(_new_nested(inst, like, s.Name, s.Label, like.LocalPlacement if like is not s else s.Placement))
    for n in objects.sub_assemblies(inst):
        m = mirror_of(n, inst)
        if m is not None and not _same_source(n, m):  # it places another assembly now: made again
            _remove(n)
            n = _as_in_file(_new_nested(inst, m, m.Name, m.Label, m.Placement))
        if _file_changed(n):  # the file's new word, unless this place was set otherwise
            f = file_rigid(n)
            if bool(n.Rigid) == _held(n):
                n.Rigid = f
            n.RigidInFile = f
        _bring(n, chain + [src])


def bring_in_step(asm):
    """Each instance of `asm` (and each nested one) gets a link for a part its placed assembly
    gained and a nested instance for a sub-assembly it gained, loses those of what it lost (a
    joint of the parent on one is then skipped and named), and its nested instances not set
    rigid or flexible in their place take the rigidity their placed file now gives them."""
    for sub in out_of_step(asm):
        _bring(sub, [asm])


def instance_link_properties(link):
    """A link's own part properties. An App::Link reads a property it lacks from the object it
    links (hasattr would see the placed part's Grounded): each is added by name, and a part
    grounded in the placed assembly is free here (the parent's joints hold the instance)."""
    objects._add(link, "InstanceLink", "App::PropertyPlacement", "LocalPlacement", "Sub-assembly")
    objects._add(link, "InstanceLink", "App::PropertyBool", "Grounded", "Dispcon", False)
    objects._add(link, "InstanceLink", "App::PropertyFloat", "AbilityToRotate", "Dispcon")
    objects._add(link, "InstanceLink", "App::PropertyFloat", "Density", "Dispcon",
                 getattr(link.LinkedObject, "Density", 1.0))


def set_rigid(sub, rigid=True):
    """Makes an instance, at any level, move as one part (True) or join its parts' joints to the
    parent's solve (False) in this place, in one undo step; None (a nested instance): as its
    placed file has it again. Refused, changing nothing, inside a rigid instance (that one is
    its file as it is: make it flexible first)."""
    from .operations import transaction

    if not objects.is_sub_assembly(sub):
        raise ValueError("%s is not a sub-assembly" % getattr(sub, "Label", sub))
    if rigid is None and not is_nested(sub):
        raise ValueError("%s: rigid is True or False (None, as its file has it, is for a nested instance)"
                         % sub.Label)
    if rigid is not None and not isinstance(rigid, (bool, int)):
        raise ValueError("%s: rigid is True or False, not %r" % (sub.Label, rigid))
    lock = locked_by(sub)
    if lock is not None:
        raise ValueError("%s is inside %s, which is rigid: it moves as %s has it (make %s flexible first)"
                         % (sub.Label, lock.Label, _where(source_of(lock).Document), lock.Label))
    with transaction(sub.Document, "Rigid" if rigid else "Flexible" if rigid is not None else "Rigid as in its file"):
        if rigid is None:
            f = file_rigid(sub)
            if f is None:
                raise ValueError("%s: its placed file no longer has it (Solve brings it in step)" % sub.Label)
            sub.Rigid = sub.RigidInFile = f
        elif bool(sub.Rigid) != bool(rigid):
            sub.Rigid = bool(rigid)
        rigid_modes(sub)
    return sub


class InstanceJoint:
    """A joint of a placed assembly as it holds in one flexible instance: its references are
    the instance's links; everything else is read from the joint in the placed assembly (which
    is never written to). Its Label is the instance's and the joint's: Leg1.Revolute (nested:
    Walk2.Leg1.Revolute)."""

    def __init__(self, joint, instance, ref1, ref2):
        self.source, self.instance = joint, instance
        self.Label = "%s.%s" % (instance.Label, joint.Label)
        self.Reference1, self.Reference2 = ref1, ref2

    def __getattr__(self, name):
        return getattr(self.source, name)


# The placed assemblies being solved in their own frames now (solved_locals inside
# solved_locals, for rigid instances nested in rigid ones): one met again is a cycle.
_SOLVING = []


def _refuse_cycle(where, src, chain):
    if key(src) in [key(a) for a in chain]:
        names = [a.Label for a in chain[[key(a) for a in chain].index(key(src)):]] + [src.Label]
        raise ValueError("%s: %s would contain itself (%s): an assembly cannot be placed inside itself"
                         % (where.Label, src.Label, " > ".join(names)))


def solved_locals(src, where):
    """The placed assembly `src` solved in its own frame (its joints, its grounded parts, its own
    instances as they are there), from its document, which is not changed: {path (source_tree):
    placement in its frame} of everything in it. `where`: the instance asking (named in errors)."""
    from .adapter import Adapter
    from .operations import tolerance

    _refuse_cycle(where, src, _SOLVING)
    _SOLVING.append(src)
    try:
        inner = Adapter(src)
        with inner.engine_errors():
            r = inner.model.assemble(tolerance=tolerance(src), max_iterations=src.MaxIterations)
    finally:
        _SOLVING.pop()
    if not r.converged:
        raise ValueError("%s: the joints of %s do not hold (%s)" % (where.Label, src.Label, inner.labelled(r.message)))
    return {path: inner.placement_of(o) if o.Name in inner.frames else o.Placement
            for path, o in source_tree(src).items()}


def add_instances(adapter, physics):
    """The parent's adapter gets the bodies of `adapter.asm`'s sub-assemblies, at any depth (one
    per rigid instance, one per link of a flexible one) and returns the flexible instances'
    joints. What does not depend on where an instance is (the placed assembly solved in its
    frame, the mass properties of its parts in their own frames) is computed once per placed
    assembly."""
    chain = list(_SOLVING)
    if not chain or key(chain[-1]) != key(adapter.asm):
        chain.append(adapter.asm)
    return _add_level(adapter, adapter.asm, physics, ({}, {}), chain)


def _add_level(adapter, container, physics, once, chain):
    import Part

    from .adapter import local_mass

    rigid_once, part_once = once
    extra = []
    mirrors = None
    if not objects.is_assembly(container):  # nested instances: each of what they mirror
        mirrors = {s.Name: s for s in objects.sub_assemblies(source_of(container))}
    for sub in objects.sub_assemblies(container):
        src = source_of(sub)
        _refuse_cycle(sub, src, chain)
        lacking, _ = _lacks(sub)
        if lacking:
            raise ValueError("%s: %s has parts this instance lacks (%s): Solve brings them in"
                             % (sub.Label, src.Label, ", ".join(lacking)))
        if mirrors is not None and sub.SourceName not in mirrors:
            raise ValueError("%s: %s no longer has the sub-assembly it mirrors: Solve brings it in step"
                             % (sub.Label, source_of(container).Label))
        rigid = rigid_of(sub)  # this place's (a nested one not set here: as its file has it now)
        inside = tree(sub)
        if rigid:
            if key(src) not in rigid_once:
                local = solved_locals(src, sub)
                shapes = []
                for path, o in inside.items():
                    if path in local and o.TypeId == "App::Link":
                        s = objects.shape_of(o).copy()
                        s.Placement = local[path].multiply(o.Placement.inverse()).multiply(s.Placement)
                        shapes.append(s)
                rigid_once[key(src)] = (local, local_mass(Part.makeCompound(shapes), App.Placement()))
            local, mass = rigid_once[key(src)]
            body = adapter.add_body(sub, None, physics, local=mass)
            placed = {o.Name: local[path] for path, o in inside.items() if path in local}
            for name, pl in placed.items():
                adapter.frames[name] = (body, pl)
            adapter.rigid[sub.Name] = placed
        else:
            links = {}
            for link in objects.instance_parts(sub):
                source = link.LinkedObject
                if source is None:
                    continue
                links[source.Name] = link
                if key(source) not in part_once:
                    part_once[key(source)] = local_mass(objects.shape_of(link), link.Placement)
                adapter.add_body(link, None, physics, local=part_once[key(source)])
            extra += _own_joints(sub, src, inside)
            extra += _add_level(adapter, sub, physics, once, chain + [src])
    return extra


def _own_joints(sub, src, inside):
    """The joints of `src` (the assembly a flexible instance `sub` places) as they hold in `sub`:
    InstanceJoints whose references are its links (`inside`: tree(sub))."""
    paths = {o.Name: path for path, o in source_tree(src).items()}
    out = []
    for j in objects.joints(src):
        refs = []
        for ref in (j.Reference1, j.Reference2):
            o = ref[0] if ref else None
            d = inside.get(paths.get(o.Name)) if o is not None and o.Document == src.Document else None
            refs.append((d, ref[1]) if d is not None else None)
        out.append(InstanceJoint(j, sub, *refs))
    return out


def instance_joints(container):
    """The joints that hold in the flexible instances of `container` (an assembly or an
    instance), at every depth: Walk2.Leg3.Revolute of a parade whose walkers and legs are
    flexible (none inside a rigid instance: it moves as one). What the Drive panel offers beside
    the assembly's own joints; the adapter makes the same ones."""
    out = []
    for sub in objects.sub_assemblies(container):
        if rigid_of(sub):
            continue
        out += _own_joints(sub, source_of(sub), tree(sub))
        out += instance_joints(sub)
    return out


def _set_local(adapter, obj, container):
    f, g = adapter.frames.get(obj.Name), adapter.frames.get(container.Name)
    if f is None:
        return  # a flexible nested instance: its frame moves only with its container's
    if f[1] is not None and g is not None and f[0] == g[0]:  # both inside one rigid instance
        local = f[1] if g[1] is None else g[1].inverse().multiply(f[1])
    else:
        local = container.Placement.inverse().multiply(obj.Placement)
    if not same(local, obj.LocalPlacement):
        obj.LocalPlacement = local


def _placed(adapter, obj):
    """An object inside a rigid instance goes where its body's owner (just written) puts it."""
    f = adapter.frames.get(obj.Name)
    if f is not None and f[1] is not None:
        pl = adapter.part_of(f[0]).Placement.multiply(f[1])
        if not same(pl, obj.Placement):
            obj.Placement = pl


def _settle(adapter, inst, container):
    _placed(adapter, inst)
    if container is not None:
        _set_local(adapter, inst, container)
    for link in objects.instance_parts(inst):
        if link.Name in adapter.frames:  # else a part since removed from the placed assembly
            _placed(adapter, link)
            _set_local(adapter, link, inst)
    for n in objects.sub_assemblies(inst):
        _settle(adapter, n, inst)


def write_back(adapter):
    """After the parent's bodies are written: the parts (and nested instances) of a rigid
    instance follow its Placement; every link and nested instance keeps its placement in its
    container's frame up to date, at every level."""
    for sub in objects.sub_assemblies(adapter.asm):
        _settle(adapter, sub, None)


def _everything(inst):
    out = [inst]
    for o in inst.Group:
        if objects.is_sub_assembly(o):
            out += _everything(o)
        elif "LocalPlacement" in o.PropertiesList:
            out.append(o)
    return out


def snapshot(asm):
    """Every placement a motion of `asm` can change (its parts, its instances and everything in
    them, at any depth); calling the result puts them back."""
    saved = [(o, o.Placement) for o in objects.parts(asm)]
    for sub in objects.sub_assemblies(asm):
        for o in _everything(sub):
            saved.append((o, o.Placement, o.LocalPlacement) if "LocalPlacement" in o.PropertiesList
                         else (o, o.Placement))

    def restore():
        for entry in saved:
            if len(entry) == 3 and not same(entry[2], entry[0].LocalPlacement):
                entry[0].LocalPlacement = entry[2]
            if not same(entry[1], entry[0].Placement):
                entry[0].Placement = entry[1]

    return restore
