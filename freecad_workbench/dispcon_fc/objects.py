"""The workbench's document objects: the assembly (a group of parts and joints), the joints, and
the properties that make an object of the document a part. Every value lives in the objects'
properties; the Python proxies hold nothing FreeCAD saves (a proxy's state is None; an assembly's
keeps its parts' centres of mass while it lives, adapter.centres_of)."""
import contextlib
import math

import FreeCAD as App

from . import engine

# FreeCAD 1.x's names for its joints, in the order of its Assembly workbench. Each is a row of the
# engine's joint table (adapter.kind_of), but a Distance, whose row depends on what was picked.
JOINT_TYPES = ["Fixed", "Revolute", "Slider", "Cylindrical", "Ball", "Planar", "PointOnLine",
               "PointOnPlane", "PointOnCurve", "Distance", "Parallel", "Perpendicular", "Angle",
               "Gears", "Belt", "RackPinion", "Screw"]
# The couplings: one equation between the parts' turns (or a turn and a travel).
COUPLINGS = ("Gears", "Belt", "RackPinion", "Screw")
# The joint types whose part 2 frame can be turned by a rotation offset: those that hold part 2's
# orientation by its axis and the twist reference across it (a coupling measures its turns from
# its axes as picked, a ball or a point holds no orientation).
FRAME_ROTATED = ("Fixed", "Revolute", "Slider", "Cylindrical", "Planar")
# The joint types that hold part 2's turn about the joint's axis (HOLD_TWIST), and those that
# measure it, to hold it or to bound it by their turn limits (TWIST_TYPES: a Revolute's or a
# Cylindrical's Min 0 deg is where that turn is 0); where that turn is measured from (TwistFrom):
# the frames of the picked elements, as FreeCAD 1.x's Assembly aligns a joint's two coordinate
# systems (what the joint means whatever pose the parts were in when it was made), or the turn
# part 2 had when the joint was made (every joint saved before TwistFrom existed).
HOLD_TWIST = ("Fixed", "Slider")
TWIST_TYPES = ("Fixed", "Revolute", "Slider", "Cylindrical")
PICKED_FRAMES, POSE_WHEN_MADE = TWIST_FROM = ("Picked frames", "Pose when made")


class Stateless:
    """What FreeCAD saves of a proxy (an object's or a view provider's): nothing, every value lives
    in the object's properties (__getstate__ and __setstate__ for FreeCAD 0.20, dumps and loads
    for 1.x)."""

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    dumps = __getstate__
    loads = __setstate__


class _Proxy(Stateless):
    """A document object's proxy: the objects compute nothing on recompute."""

    def execute(self, obj):
        pass


PARAMETERS = "User parameter:BaseApp/Preferences/Mod/Dispcon"
DEFAULT_DRAG_STEPS = 20


def preferences():
    """The defaults a person set on the preferences page (Edit > Preferences > Dispcon); a value
    that is missing or not a positive number gives the built-in default."""
    p = App.ParamGet(PARAMETERS)
    # The built-in defaults are the engine's, stated there once.
    dispcon = engine.load()
    default_tolerance, default_iterations = dispcon.DEFAULT_TOLERANCE, dispcon.DEFAULT_MAX_ITERATIONS
    # The page's tolerance field is text ("1e-9": readable, any magnitude).
    try:
        tolerance = float(p.GetString("Tolerance", "") or default_tolerance)
    except ValueError:
        App.Console.PrintWarning("Dispcon preferences: tolerance %r is not a number; using %g\n"
                                 % (p.GetString("Tolerance", ""), default_tolerance))
        tolerance = default_tolerance
    iterations = p.GetInt("MaxIterations", default_iterations)
    steps = p.GetInt("DragSteps", DEFAULT_DRAG_STEPS)
    return {"LighterDrag": p.GetBool("LighterDrag", True),
            "Tolerance": tolerance if 0 < tolerance < math.inf else default_tolerance,
            "MaxIterations": iterations if iterations > 0 else default_iterations,
            "DragSteps": steps if steps > 0 else DEFAULT_DRAG_STEPS}


def _add(obj, kind, type_id, name, group, value=None, props=None):
    """Adds a property the object lacks (new objects, and documents saved by an older workbench
    or without it), its tooltip DOCS[kind][name]; keeps the value of one it has, and gives it the
    tooltip of now (a document saved with older words reads the current ones once reopened).
    `props`: the set of the object's property names, read once by a caller adding many (kept up
    to date here); FreeCAD builds PropertiesList afresh at each read, a joint's 55 names: read
    for each of a joint's 40-odd properties, it was most of a document's restore in Python."""
    if name not in (obj.PropertiesList if props is None else props):
        obj.addProperty(type_id, name, group, DOCS[kind][name])
        if props is not None:
            props.add(name)
        if value is not None:
            setattr(obj, name, value)
    else:
        _document(obj, name, DOCS[kind][name])


def _document(obj, name, doc):
    if obj.getDocumentationOfProperty(name) != doc:
        obj.setDocumentationOfProperty(name, doc)


def refresh_docs(obj, kind):
    """The tooltips of DOCS[kind] on the properties `obj` has (what a reopened document's objects
    without a proxy of their own get: parts, instances' links, the bill of materials' sheet)."""
    props = obj.PropertiesList
    for name, doc in DOCS[kind].items():
        if name in props:
            _document(obj, name, doc)


def _mark(obj, kind, props=None):
    """The stored property that says what the object is, so it is recognised even when its
    Python proxy could not be restored (the workbench missing when the file was opened)."""
    _add(obj, "Any", "App::PropertyString", "DispconType", "Dispcon", props=props)
    if obj.DispconType != kind:
        obj.DispconType = kind
    obj.setEditorMode("DispconType", 2)  # hidden: it is what the object is, not a setting


class AssemblyProxy(_Proxy):
    """An App::DocumentObjectGroupPython holding the parts and the joints of one assembly."""

    def __init__(self, obj):
        obj.Proxy = self
        self.attach(obj)

    def attach(self, obj):
        _mark(obj, "Assembly")
        prefs = preferences()
        tolerance = prefs["Tolerance"]
        if "Tolerance" in obj.PropertiesList and obj.getTypeIdOfProperty("Tolerance") == "App::PropertyFloat":
            # Saved by an earlier workbench as a plain float, which the property editor shows
            # as "0.00": the same value in a property that shows its digits.
            tolerance = obj.Tolerance
            obj.removeProperty("Tolerance")
        _add(obj, "Assembly", "App::PropertyPrecision", "Tolerance", "Dispcon", tolerance)
        _add(obj, "Assembly", "App::PropertyInteger", "MaxIterations", "Dispcon", prefs["MaxIterations"])
        _add(obj, "Assembly", "App::PropertyString", "LastSolve", "Dispcon")

    def onDocumentRestored(self, obj):
        self.attach(obj)
        # Its parts and its bill of materials' sheet have no proxy of their own to do it: their
        # properties' tooltips of now.
        for o in parts(obj):
            refresh_docs(o, "Part")
        for o in obj.InList:
            if getattr(o, "DispconType", "") == "BOM":
                refresh_docs(o, "BOM")
                refresh_docs(o, "Any")
        _view_restored(obj, "Assembly")
        # It computes nothing (execute is empty), so a touch saved with it is no recompute
        # waiting: an undo or redo that changed its Group or LastSolve touches it with no
        # recompute after, FreeCAD saves the mark, and the reopened, unmodified document showed
        # its Assembly touched (the third audit). Cleared, as a recompute would.
        obj.purgeTouched()


# The paper's "ability to move" mu_12 of a constraint (section 3.1.4, in place of eq. 19's
# m2 / (m1 + m2)): the share of a correction's translation that part 1 takes, part 2 the rest.
MOVE_DOC = ("Which part gives way when the joint pulls its two parts together (the paper's ability to "
            "move, mu): the share of each correction part 1 takes, part 2 taking the rest. 0: part 1 stays "
            "and part 2 does all the moving; 1: part 1 does it all; 0.5: half each. -1 (the default): the "
            "engine chooses, from the parts' masses where it has them (part 1 takes m2 / (m1 + m2): the "
            "lighter moves more), else half each. A grounded part never moves, whatever this says.")


class JointProxy(_Proxy):
    """An App::FeaturePython: two references, the joint's type, its points and axes in each part's
    frame (taken from the picked geometry) and its limits."""

    def __init__(self, obj):
        obj.Proxy = self
        self.attach(obj)

    def attach(self, obj):
        props = set(obj.PropertiesList)  # (read once: _add)
        _mark(obj, "Joint", props)
        _add(obj, "Joint", "App::PropertyEnumeration", "JointType", "Joint", JOINT_TYPES, props=props)
        if list(obj.getEnumerationsOfProperty("JointType")) != JOINT_TYPES:
            # Saved by a workbench with fewer types: the full list, the joint's type kept.
            kind = obj.JointType
            obj.JointType = JOINT_TYPES
            obj.JointType = kind
        _add(obj, "Joint", "App::PropertyLinkSub", "Reference1", "Joint", props=props)
        _add(obj, "Joint", "App::PropertyLinkSub", "Reference2", "Joint", props=props)
        for name in ("Point1", "Axis1", "Perp1", "Point2", "Axis2", "Perp2"):
            _add(obj, "Joint", "App::PropertyVector", name, "Geometry", props=props)
        _add(obj, "Joint", "App::PropertyBool", "HasRotationLimits", "Limits", props=props)
        _add(obj, "Joint", "App::PropertyAngle", "RotationMin", "Limits", props=props)
        _add(obj, "Joint", "App::PropertyAngle", "RotationMax", "Limits", props=props)
        _add(obj, "Joint", "App::PropertyBool", "HasTravelLimits", "Limits", props=props)
        _add(obj, "Joint", "App::PropertyDistance", "TravelMin", "Limits", props=props)
        _add(obj, "Joint", "App::PropertyDistance", "TravelMax", "Limits", props=props)
        _add(obj, "Joint", "App::PropertyAngle", "ConeAngle", "Limits", props=props)
        _add(obj, "Joint", "App::PropertyAngle", "AngleMin", "Limits", props=props)
        _add(obj, "Joint", "App::PropertyAngle", "AngleMax", "Limits", 180, props=props)
        _add(obj, "Joint", "App::PropertyFloat", "Move", "Abilities", -1, props=props)
        _add(obj, "Joint", "App::PropertyFloat", "Residual", "Solve", props=props)
        _add(obj, "Joint", "App::PropertyBool", "Violated", "Solve", props=props)
        joint_extras(obj, props)

    def onBeforeChange(self, obj, prop):
        # What TwistFrom was before it is set (onChanged: a person's choice takes the twist anew).
        if prop == "TwistFrom" and "TwistFrom" in obj.PropertiesList:
            self.twist_before = obj.TwistFrom

    def onChanged(self, obj, prop):
        # Its type changed in the property editor: that type's properties shown (a document
        # being read gets them from attach, once its objects are restored).
        if prop == "JointType" and "Ratio" in obj.PropertiesList and "Restoring" not in obj.State:
            show_properties(obj)
        # TwistFrom set in the property editor (or by a script) means what the joint panel and
        # edit_joint make it mean: the twist taken again, from the picked frames or from the pose
        # now (operations.twist_from_set); not when the workbench sets it itself (a new joint,
        # an old one given the property), nor by a document being read, nor by an undo or redo,
        # which put the twist references back with it.
        if prop == "TwistFrom":
            before, self.twist_before = getattr(self, "twist_before", None), None
            if (before in TWIST_FROM and before != obj.TwistFrom and not getattr(self, "quiet", False)
                    and not App.isRestoring() and "Restoring" not in obj.State
                    and not obj.Document.Restoring and not obj.Document.Transacting):
                from .operations import twist_from_set

                twist_from_set(obj, before)

    def execute(self, obj):
        """A coupling whose part's geometry moved its axis or centre (the part recomputed: a hole
        moved, a gear made larger) takes the new geometry and has its phase made again at the
        poses the parts have, so a saved document never holds a phase measured about axes that
        are no longer there; the Report view and the status bar say so by label."""
        if getattr(obj, "JointType", "") not in COUPLINGS or not getattr(obj, "PhaseKnown", False):
            return
        from .adapter import live_anchors, moved_anchors

        try:
            anchors = live_anchors(obj)
        except Exception:  # a reference gone: the next solve skips the joint and names it
            return
        moved = moved_anchors(obj, anchors)
        if not moved:
            return
        for name, value in anchors.items():
            if getattr(obj, name) != value:
                setattr(obj, name, value)
        remake_phase(obj, keep_offset=True)
        parts = " and ".join(moved)
        text = ("dispcon: the geometry of %s moved the axis or centre of %s: its phase is made again at the "
                "parts' poses (its mesh offset, %s, kept)" % (parts, obj.Label, offset_text(obj)))
        App.Console.PrintWarning(text + "\n")
        if App.GuiUp:
            from . import feedback

            feedback.status(text[len("dispcon: "):])

    def onDocumentRestored(self, obj):
        self.attach(obj)
        # A document saved by freecadcmd has no view providers' proxies (no GuiDocument.xml):
        # given here, while FreeCAD is still restoring, they neither mark the document modified
        # nor get overwritten by the saved view state (read before this).
        _view_restored(obj, "Joint")


class SubAssemblyProxy(_Proxy):
    """An App::DocumentObjectGroupPython in a parent assembly: an assembly placed inside it (of
    this document or, through an XLink, of another .FCStd), as FreeCAD 1.x's AssemblyLink. Its
    Group holds one App::Link per part of that assembly, each with its placement in the instance's
    frame (LocalPlacement) stored here, in the parent's document: the linked file is never
    changed. Rigid: the instance moves as one part; flexible: its parts and joints join the
    parent's solve (subassembly.py)."""

    def __init__(self, obj):
        obj.Proxy = self
        self.attach(obj)

    def attach(self, obj):
        _mark(obj, "SubAssembly")
        sub_assembly_properties(obj)
        if getattr(obj, "SourceName", ""):
            nested_rigidity_property(obj)

    def onDocumentRestored(self, obj):
        self.attach(obj)
        refresh_docs(obj, "NestedInstance")  # (those it has: a nested instance's)
        for link in instance_parts(obj):
            refresh_docs(link, "InstanceLink")
        _view_restored(obj, "SubAssembly")
        grounding_modes(obj)
        if getattr(obj, "SourceName", ""):
            from .subassembly import rigid_modes

            rigid_modes(obj)

    def onChanged(self, obj, prop):
        # Made rigid or flexible (the property editor too): the nested instances inside it say
        # whether their own Rigid means anything now (read only inside a rigid one), and it and
        # they whether Grounded does.
        if prop == "Rigid" and "Restoring" not in obj.State and getattr(obj, "Group", None):
            from .subassembly import rigid_modes

            rigid_modes(obj)
        if prop in ("Rigid", "Group") and "Restoring" not in obj.State:
            grounding_modes(obj)
        # Moving the instance carries its parts along (their placements in its frame stay).
        if prop == "Placement":
            for link in getattr(obj, "Group", []):
                if "LocalPlacement" in link.PropertiesList:
                    placed = obj.Placement.multiply(link.LocalPlacement)
                    if (tuple(placed.Base), tuple(placed.Rotation.Q)) != (tuple(link.Placement.Base),
                                                                          tuple(link.Placement.Rotation.Q)):
                        link.Placement = placed


def sub_assembly_properties(obj):
    """The stored properties of a sub-assembly (kept when the file is opened without the
    workbench): the assembly it places, Rigid, its Placement and Grounded."""
    _add(obj, "SubAssembly", "App::PropertyXLink", "Assembly", "Sub-assembly")
    _add(obj, "SubAssembly", "App::PropertyBool", "Rigid", "Sub-assembly", True)
    _add(obj, "SubAssembly", "App::PropertyPlacement", "Placement", "Sub-assembly")
    _add(obj, "SubAssembly", "App::PropertyBool", "Grounded", "Dispcon")


# An instance's Grounded means something only where the instance is one body of the solve:
# rigid, and not inside a rigid instance (which moves it as its own part). A flexible one has no
# one place to hold (its parts join the solve each on its own): there it is hidden.
INSTANCE_GROUNDED = "the whole instance never moves (a rigid instance only; a flexible one's parts move each on its own)"


def why_not_grounded(inst):
    """Why grounding instance `inst` would mean nothing, or None when it means holding it."""
    from .subassembly import locked_by, rigid_of

    holder = locked_by(inst)
    if holder is not None:
        return "it moves as a part of the rigid %s: ground that" % holder.Label
    if not rigid_of(inst):
        return "it is flexible, its parts moving each on its own: make it rigid to hold it whole"
    return None


def grounding_modes(inst):
    """Shows an instance's Grounded (and its nested instances') in the property editor where it
    means holding the instance, hides it where it means nothing (why_not_grounded)."""
    from .subassembly import tree

    try:
        inside = [d for d in tree(inst).values() if is_sub_assembly(d)]
    except Exception:  # a link not restored yet: the instance alone, the rest at their own restore
        inside = []
    for o in [inst] + inside:
        if "Grounded" not in o.PropertiesList:
            continue
        try:
            hidden = why_not_grounded(o) is not None
        except Exception:  # its placed file not there: as it was
            continue
        if o.getEditorMode("Grounded") != (["Hidden"] if hidden else []):
            o.setEditorMode("Grounded", 2 if hidden else 0)


def nested_rigidity_property(obj):
    """A nested instance's Rigid is its place's (editable) and RigidInFile what its placed file
    said when it took it (hidden): equal, the place follows the file; different, it was set here.
    A nested instance saved before either was editable took its file's rigidity: it follows."""
    _add(obj, "NestedInstance", "App::PropertyBool", "RigidInFile", "Sub-assembly", obj.Rigid)
    obj.setEditorMode("RigidInFile", 2)


class PartProxy(_Proxy):
    """A part the workbench made (imported from a file): a Part::FeaturePython holding the shape
    it was given, so that its view provider can show the part's icon, or the grounded part's.
    Where the workbench is missing it is still a plain shape with its properties (FreeCAD keeps a
    Part::FeaturePython's Shape without its proxy); parts made before (Part::Feature) and any
    other object with a shape stay parts too, with FreeCAD's icons."""

    def __init__(self, obj):
        obj.Proxy = self

    def onDocumentRestored(self, obj):
        _view_restored(obj, "Part")
        # It computes nothing (its shape is given): a touch saved with it, by a redo of its import
        # with no recompute after, is no recompute waiting (the fourth audit's reopened document
        # showed its four parts so). Cleared, as the assembly's is.
        obj.purgeTouched()


def joint_extras(obj, props=None):
    """Reversed, Offset and the frame's rotation offset (the joint panel's), the features picked, a
    Distance's value and the couplings' values, which joints made before them lack: a joint
    without them reads as not reversed, offset 0, not turned, a coupling of ratio 1. `props`: the
    set of the object's property names, when the caller read it (_add)."""
    props = set(obj.PropertiesList) if props is None else props
    _add(obj, "Joint", "App::PropertyBool", "Reversed", "Joint", props=props)
    _add(obj, "Joint", "App::PropertyDistance", "Offset", "Joint", props=props)
    # The rotation offset of part 2's joint frame (FreeCAD 1.x's Assembly has an offset
    # placement on each joint's frames): yaw about the joint's axis, then pitch and roll.
    for name in ("FrameYaw", "FramePitch", "FrameRoll"):
        _add(obj, "Joint", "App::PropertyAngle", name, "Joint", props=props)
    # Its translation offset across the axis (along the axis: Offset): part 2's joint frame moved
    # in its own x and y, so part 2 stands that far off part 1's point in the joint's frame.
    for name in ("FrameX", "FrameY"):
        _add(obj, "Joint", "App::PropertyDistance", name, "Joint", props=props)
    _add(obj, "Joint", "App::PropertyString", "Feature1", "Geometry", props=props)
    _add(obj, "Joint", "App::PropertyString", "Feature2", "Geometry", props=props)
    _add(obj, "Joint", "App::PropertyDistance", "Distance", "Joint", props=props)
    _add(obj, "Joint", "App::PropertyFloat", "Ratio", "Coupling", 1.0, props=props)
    _add(obj, "Joint", "App::PropertyDistance", "Radius", "Coupling", props=props)
    _add(obj, "Joint", "App::PropertyDistance", "Pitch", "Coupling", 1.0, props=props)
    _add(obj, "Joint", "App::PropertyBool", "LeftHanded", "Coupling", props=props)
    phase_property(obj, props)
    twist_property(obj, props)
    show_properties(obj, props)
    read_only_derived(obj, props)


def twist_property(obj, props=None):
    """TwistFrom: a joint without it (saved before it existed, or one whose proxy was lost) was
    made holding the turn its parts had then, and keeps doing so; new_joint gives a new joint
    the picked frames."""
    if "TwistFrom" not in (obj.PropertiesList if props is None else props):
        obj.addProperty("App::PropertyEnumeration", "TwistFrom", "Joint", DOCS["Joint"]["TwistFrom"])
        if props is not None:
            props.add("TwistFrom")
        with quiet(obj):  # what the joint always held: nothing to take anew
            obj.TwistFrom = list(TWIST_FROM)
            obj.TwistFrom = POSE_WHEN_MADE
    else:
        _document(obj, "TwistFrom", DOCS["Joint"]["TwistFrom"])


@contextlib.contextmanager
def quiet(obj):
    """Values the workbench sets on a joint itself, which its proxy does not take as a person's
    choice (JointProxy.onChanged)."""
    proxy = getattr(obj, "Proxy", None)
    if proxy is None or isinstance(proxy, str):
        yield
        return
    proxy.quiet = True
    try:
        yield
    finally:
        proxy.quiet = False


def twist_from_picks(joint):
    """Whether the joint's twist reference is read from its picked elements' frames (a Fixed or
    a Slider, a Revolute or a Cylindrical whose TwistFrom says so), not kept as recorded when it was
    made."""
    return (getattr(joint, "JointType", "") in TWIST_TYPES
            and getattr(joint, "TwistFrom", POSE_WHEN_MADE) == PICKED_FRAMES)


# What the workbench derives and a person reads but never types: the picked geometry in each
# part's frame (made again from the references at every solve) and the last solve's outcome.
# Editable, a typed Axis1 or Feature2 silently broke the joint until the next solve remade it.
DERIVED = ("Point1", "Axis1", "Perp1", "Point2", "Axis2", "Perp2", "Feature1", "Feature2", "Residual", "Violated")


def read_only_derived(obj, props=None):
    """The DERIVED properties read only in the property editor (scripts still write them)."""
    props = obj.PropertiesList if props is None else props
    for name in DERIVED:
        if name in props and "ReadOnly" not in obj.getEditorMode(name):
            obj.setEditorMode(name, 1)


# The properties only some joint types use, with those types: the property editor shows a joint
# what its type takes (a revolute no ratio, no phase), as the joint's panel does.
_USED_BY = {"Ratio": ("Gears", "Belt"), "Radius": ("RackPinion",), "Pitch": ("Screw",), "LeftHanded": ("Screw",),
            "MeshOffset": COUPLINGS, "Phase": COUPLINGS, "PhaseTurns": ("Gears", "Belt"),
            "Distance": ("Distance",), "FrameYaw": FRAME_ROTATED, "FramePitch": FRAME_ROTATED,
            "FrameRoll": FRAME_ROTATED, "FrameX": FRAME_ROTATED, "FrameY": FRAME_ROTATED, "TwistFrom": TWIST_TYPES}
_READ_ONLY = ("Phase", "PhaseTurns")  # the engine's: the mesh offset sets them


def show_properties(obj, props=None):
    """Shows in the property editor the properties the joint's type uses (the engine's phase read
    only) and hides the others; nothing of a hidden one is lost."""
    kind = getattr(obj, "JointType", "")
    props = obj.PropertiesList if props is None else props
    for name, types in _USED_BY.items():
        if name in props:
            mode = (1 if name in _READ_ONLY else 0) if kind in types else 2
            if obj.getEditorMode(name) != {0: [], 1: ["ReadOnly"], 2: ["Hidden"]}[mode]:
                obj.setEditorMode(name, mode)


def frame_shift(joint):
    """The translation offset of part 2's joint frame across the joint's axis, (x, y) in mm from
    FrameX and FrameY, or None when there is none (or the type takes none)."""
    if getattr(joint, "JointType", "") not in FRAME_ROTATED or "FrameX" not in joint.PropertiesList:
        return None
    shift = (joint.FrameX.Value, joint.FrameY.Value)
    return shift if any(shift) else None


def frame_rotation(joint):
    """The rotation offset of part 2's joint frame (App.Rotation from FrameYaw, FramePitch,
    FrameRoll in degrees), or None when there is none (or the type takes none)."""
    if getattr(joint, "JointType", "") not in FRAME_ROTATED or "FrameYaw" not in joint.PropertiesList:
        return None
    angles = (joint.FrameYaw.Value, joint.FramePitch.Value, joint.FrameRoll.Value)
    return App.Rotation(*angles) if any(angles) else None


# A coupling's phase is the engine's: the constant of its equation (docs/format.md, "Couplings"),
# an angle for Gears and Belt (ratio turn1 + turn2, or -ratio turn1 + turn2), a length for
# RackPinion and Screw (the travel less radius, or pitch / 2 pi, times the turn).
LENGTH_PHASE = ("RackPinion", "Screw")


def phase_property(obj, props=None):
    """Phase in the unit of the joint's type (deg, or mm for a rack or a screw), and PhaseKnown:
    whether it is the engine's (False: the engine makes it at the poses the parts have, as for a
    coupling just made or changed, or one saved by an earlier workbench, whose Phase was a turn of
    its own part). MeshOffset, the designer's reading of it (mesh_offset), and MeshOffsetHeld, the
    offset the stored Phase holds (an offset typed in the property editor reaches the engine at
    the next model). A value of the other unit (the joint's type changed) goes, unknown."""
    want = "App::PropertyDistance" if getattr(obj, "JointType", "") in LENGTH_PHASE else "App::PropertyAngle"
    props = set(obj.PropertiesList) if props is None else props
    known = "PhaseKnown" in props
    for name in ("Phase", "MeshOffset", "MeshOffsetHeld"):
        if name in props and obj.getTypeIdOfProperty(name) != want:
            obj.removeProperty(name)
            props.discard(name)
            if known:
                obj.PhaseKnown = False
    _add(obj, "Joint", want, "MeshOffset", "Coupling", props=props)
    _add(obj, "Joint", want, "Phase", "Coupling", props=props)
    # FreeCAD holds an angle property within +-360 deg, and a gear's phase goes round with the
    # turns: the whole turns of part 2 are kept beside it (the engine's phase is Phase + 360 deg
    # x PhaseTurns; a turn of part 2 is the same pose, so Phase alone says where its teeth are).
    _add(obj, "Joint", "App::PropertyInteger", "PhaseTurns", "Coupling", props=props)
    _add(obj, "Joint", "App::PropertyBool", "PhaseKnown", "Coupling", props=props)
    # A joint saved before it: its Phase holds the offset it has.
    _add(obj, "Joint", want, "MeshOffsetHeld", "Coupling", obj.MeshOffset.Value, props=props)
    # Hidden: the workbench's bookkeeping (the engine's value is read only: show_properties).
    for name in ("PhaseKnown", "MeshOffsetHeld"):
        obj.setEditorMode(name, 2)


def phase_value(joint):
    """The coupling's phase as the engine is to have it, in the joint's unit (deg, or mm for a
    rack or a screw): Phase with its whole turns, and the mesh offset set since it was stored (in
    the property editor: MeshOffset less MeshOffsetHeld; part 2's turn or travel enters the
    coupling's equation with a factor 1)."""
    own = _held_change(joint)
    if getattr(joint, "JointType", "") in LENGTH_PHASE:
        return joint.Phase.Value + own
    return joint.Phase.Value + 360.0 * getattr(joint, "PhaseTurns", 0) + own


def _held_change(joint):
    props = joint.PropertiesList
    if "MeshOffset" not in props or "MeshOffsetHeld" not in props:
        return 0.0
    return joint.MeshOffset.Value - joint.MeshOffsetHeld.Value


def set_phase(joint, value):
    """Stores the engine's phase `value` (deg, or mm) in the joint, its whole turns apart for an
    angle, as holding the mesh offset the joint has now; the phase is then known."""
    turns = 0 if joint.JointType in LENGTH_PHASE else int(round(value / 360.0))
    joint.Phase = value - 360.0 * turns
    joint.PhaseTurns = turns
    if "MeshOffsetHeld" in joint.PropertiesList and joint.MeshOffsetHeld.Value != mesh_offset(joint):
        joint.MeshOffsetHeld = mesh_offset(joint)
    joint.PhaseKnown = True


def mesh_offset(joint):
    """The coupling's mesh offset (deg, or mm for a rack or a screw): how far part 2 stands
    against part 1, part 1 held, from where the coupling was made (0: as made). The engine's
    phase moves by as much (its equation is ratio x turn1 + turn2, or travel - radius x turn: part
    2's turn or travel enters it with a factor 1), but it also moves on by whole wrapped turns as
    the parts go round, which the offset does not: it changes only when the designer sets it."""
    return joint.MeshOffset.Value if "MeshOffset" in joint.PropertiesList else 0.0


def offset_text(joint):
    """The coupling's mesh offset as the messages say it: "7 deg" (°), "0.05 mm"."""
    unit = "mm" if getattr(joint, "JointType", "") in LENGTH_PHASE else "\u00b0"
    return "%g%s%s" % (round(mesh_offset(joint), 9), " " if unit == "mm" else "", unit)


def normal_offset(joint_type, value):
    """A mesh offset as shown: an angle within -180..180 deg (a whole turn of part 2 is the same
    pose, the same mesh), a length as it is."""
    return value if joint_type in LENGTH_PHASE else math.remainder(value, 360.0)


def remake_phase(joint, keep_offset=False):
    """The coupling's phase made again at the poses the parts have at the next model (what it
    is measured with changed: a ratio, the type, the references): its mesh offset starts at 0.
    `keep_offset` (its part's geometry moved an axis or a centre: the coupling is the same, its
    phase only measured about new axes): the designer's offset is kept, the poses the parts
    have standing at the offset the stored phase held (MeshOffsetHeld), so an offset typed since
    is still to be taken (Adapter.pending_offsets) and setting it to 0 later turns part 2 back by
    as much as it was offset."""
    joint.PhaseKnown = False
    if keep_offset:
        return
    for name in ("MeshOffset", "MeshOffsetHeld"):
        if name in joint.PropertiesList:
            setattr(joint, name, 0.0)


def part_properties(obj):
    """The properties that make `obj` a part: Grounded, AbilityToRotate, Density."""
    for type_id, name, value in (("App::PropertyBool", "Grounded", None),
                                 ("App::PropertyFloat", "AbilityToRotate", None), ("App::PropertyFloat", "Density", 1.0)):
        if not hasattr(obj, name):  # (a link reads one it lacks from its linked part)
            _add(obj, "Part", type_id, name, "Dispcon", value)
        elif name in obj.PropertiesList:
            _document(obj, name, DOCS["Part"][name])
    if obj.TypeId != "App::Link":  # a link's part number is its linked object's, in its file
        part_number_property(obj)


def part_number_property(obj):
    """PartNumber, the bill of materials' part number of a part defined here (its description is
    FreeCAD's own Label2)."""
    _add(obj, "Part", "App::PropertyString", "PartNumber", "Bill of materials")


def _kind(obj):
    """"Assembly", "Joint" or None: from the proxy when it was restored, else from the stored
    properties (a document saved where the workbench was missing keeps those, not the proxy)."""
    proxy = getattr(obj, "Proxy", None)
    if isinstance(proxy, AssemblyProxy):
        return "Assembly"
    if isinstance(proxy, JointProxy):
        return "Joint"
    if isinstance(proxy, SubAssemblyProxy):
        return "SubAssembly"
    props = getattr(obj, "PropertiesList", ())
    if "DispconType" in props:
        return obj.DispconType or None
    # Saved before DispconType existed, and the proxy lost since.
    if obj.TypeId == "App::FeaturePython" and {"JointType", "Reference1", "Reference2", "Point1"} <= set(props):
        return "Joint"
    if obj.TypeId == "App::DocumentObjectGroupPython" and {"Tolerance", "MaxIterations", "LastSolve"} <= set(props):
        return "Assembly"
    return None


def is_joint(obj):
    return _kind(obj) == "Joint"


def is_assembly(obj):
    return _kind(obj) == "Assembly"


def is_sub_assembly(obj):
    return _kind(obj) == "SubAssembly"


def adopt(obj):
    """Gives a recognised assembly or joint whose Python proxy was lost (opened where the
    workbench was missing) its proxy back, with any property it lacks; returns whether it did."""
    kind = _kind(obj)
    if kind is None and obj.TypeId == "Part::FeaturePython" and "Grounded" in obj.PropertiesList:
        kind = "Part"  # one of the workbench's parts (the parts carry no DispconType)
    if kind == "ExplodedView":
        from .exploded import adopt_view

        return adopt_view(obj)
    proxy = {"Assembly": AssemblyProxy, "Joint": JointProxy, "SubAssembly": SubAssemblyProxy,
             "Part": PartProxy}.get(kind)
    if proxy is None:
        return False
    _view(obj, kind)
    if isinstance(getattr(obj, "Proxy", None), proxy):
        return False
    proxy(obj)
    return True


def _view(obj, kind):
    """The object's view provider, when the GUI is up."""
    if App.GuiUp:
        from . import viewproviders

        viewproviders.attach(obj, kind)


def _view_restored(obj, kind):
    """The view provider of an object FreeCAD is restoring (onDocumentRestored), when the GUI is
    up and the document has none for it: one saved by freecadcmd has no view providers' proxies
    (no GuiDocument.xml). Given while FreeCAD is still restoring, they do not mark the document
    modified, and no saved view state overwrites them."""
    if not App.GuiUp or obj.ViewObject is None or obj.ViewObject.Proxy not in (None, 0):
        return
    _view(obj, kind)
    if kind in ("Assembly", "SubAssembly"):
        # A group given its view provider while restoring hides its children (FreeCAD's views
        # are all hidden until the restore ends); without a saved view state every object is
        # shown, as FreeCAD shows the objects of any document saved without one.
        for o in [obj] + list(obj.Group):
            if o.ViewObject is not None:
                o.ViewObject.Visibility = True


def adopt_document(doc):
    """adopt() for every object of `doc`; returns how many got their proxy back."""
    return sum(adopt(o) for o in doc.Objects)


def shape_of(obj):
    """The placed shape of a part: its Shape, or, for an App::Link, the linked shape."""
    if hasattr(obj, "Shape"):
        return obj.Shape
    import Part

    return Part.getShape(obj)


def parts(asm):
    """The assembly's own parts (not those inside its sub-assemblies)."""
    return [o for o in asm.Group if not is_joint(o) and not is_sub_assembly(o)
            and (hasattr(o, "Shape") or o.TypeId == "App::Link")]


def sub_assemblies(asm):
    """The instances placed in an assembly (or nested in an instance: one level down)."""
    return [o for o in asm.Group if is_sub_assembly(o)]


def instance_parts(sub):
    """The links of a sub-assembly instance, one per part of the assembly it places."""
    return [o for o in sub.Group if o.TypeId == "App::Link" and "LocalPlacement" in o.PropertiesList]


def is_top_assembly(obj, doc):
    """Whether `obj` is an assembly of `doc` not placed inside another assembly of `doc` (one placed
    in other documents' assemblies still counts: each file has its own top)."""
    return is_assembly(obj) and not any(is_sub_assembly(i) and i.Document == doc for i in obj.InList)


def top_assemblies(doc):
    """The assemblies of `doc` that are not placed inside another assembly of `doc`."""
    return [o for o in doc.Objects if is_top_assembly(o, doc)]


def nested_parts(sub):
    """The links of a sub-assembly instance and of the instances nested in it, at any depth."""
    return instance_parts(sub) + [p for n in sub_assemblies(sub) for p in nested_parts(n)]


def placed_parts(asm):
    """Every part a joint of `asm` can hold: its own and those of its sub-assemblies (and of
    theirs, at any depth)."""
    return parts(asm) + [p for s in sub_assemblies(asm) for p in nested_parts(s)]


def body_of(obj):
    """The PartDesign Body `obj` is a feature of (its Pad, its Sketch...), or None."""
    find = getattr(obj, "getParentGeoFeatureGroup", None)
    body = find() if find is not None else None
    return body if body is not None and body.TypeId == "PartDesign::Body" else None


def picked(obj, sub=""):
    """What a designer means by a pick, as (object, element). A click on a PartDesign Body's
    solid selects its tip feature: FreeCAD names (`Pad`, "Face1"), or with the path from the
    object the 3D view draws, (Body, "Pad.Face1"), or (link, "Pad.Face1") for an App::Link to the
    Body (a sub-assembly's part). The tip's shape and element names are the Body's (Body.Shape
    is its tip's, placed; a link's is the Body's, placed): the Body, or the link, is the part,
    "Face1" its element. Anything else is what was picked."""
    body = body_of(obj)
    if body is not None and body.Tip == obj:
        return body, sub
    if "." in sub:
        head, element = sub.rsplit(".", 1)
        inner = getattr(obj, "LinkedObject", None) if obj.TypeId == "App::Link" else obj
        tip = getattr(inner, "Tip", None) if getattr(inner, "TypeId", "") == "PartDesign::Body" else None
        if tip is not None and head == tip.Name:
            return obj, element
    return obj, sub


def joints(asm):
    return [o for o in asm.Group if is_joint(o)]


def new_assembly(doc, name):
    obj = doc.addObject("App::DocumentObjectGroupPython", name)
    AssemblyProxy(obj)
    _view(obj, "Assembly")
    return obj


def new_sub_assembly(doc, name):
    obj = doc.addObject("App::DocumentObjectGroupPython", name)
    SubAssemblyProxy(obj)
    _view(obj, "SubAssembly")
    return obj


def new_part(obj):
    """Makes a new Part::FeaturePython one of the workbench's parts (its proxy and view)."""
    PartProxy(obj)
    _view(obj, "Part")
    return obj


def new_joint(doc, name):
    obj = doc.addObject("App::FeaturePython", name)
    JointProxy(obj)
    with quiet(obj):
        obj.TwistFrom = PICKED_FRAMES  # a new joint means the same whatever pose its parts are in
    _view(obj, "Joint")
    return obj


# Every property the workbench gives an object, by the kind of object, with its tooltip: the one
# table read when a property is made (_add) and when a document is opened (_add again, and
# refresh_docs for the objects without a proxy of their own), so a document saved with older
# words shows these once reopened. What the property editor shows, so in a designer's words.
_PART = {
    "Grounded": "never moves: the other parts are placed around it",
    "AbilityToRotate": "how readily the part turns rather than moves when a joint pulls it (the paper's "
                       "no-physics ability to rotate; 0: from the part's size)",
    "Density": "mass per unit volume: the parts' masses say which gives way (a joint's Move), and the "
               "bill of materials lists them",
}
DOCS = {
    "Any": {"DispconType": "what this object is to the Dispcon workbench"},
    "Assembly": {
        "Tolerance": "largest violation of a joint a solve accepts",
        "MaxIterations": "the most iterations a solve takes before it stops and says so",
        "LastSolve": "what the last solve said",
    },
    "Joint": {
        "JointType": "the kind of joint (the joint's panel changes it with its fields)",
        "Reference1": "part and element 1 (carries the guide)",
        "Reference2": "part and element 2",
        "Point1": "joint point, part 1's frame (made from Reference1 at every solve)",
        "Axis1": "joint axis, part 1's frame (made from Reference1 at every solve)",
        "Perp1": "reference across the axis, part 1's frame (made from Reference1 at every solve)",
        "Point2": "joint point, part 2's frame (made from Reference2 at every solve)",
        "Axis2": "joint axis, part 2's frame (made from Reference2 at every solve)",
        "Perp2": "reference across the axis, part 2's frame (made from Reference2 at every solve)",
        "HasRotationLimits": "bound the turn about the axis (between RotationMin and RotationMax)",
        "RotationMin": "lowest turn about the axis: from the picked frames lined up, or from the pose when made "
                       "(TwistFrom)",
        "RotationMax": "highest turn about the axis: from the picked frames lined up, or from the pose when made "
                       "(TwistFrom)",
        "HasTravelLimits": "bound the travel along the axis (between TravelMin and TravelMax)",
        "TravelMin": "lowest travel",
        "TravelMax": "highest travel",
        "ConeAngle": "ball joint: largest tilt of axis 2 from axis 1 (0: none)",
        "AngleMin": "Angle joint: lowest angle between the axes",
        "AngleMax": "Angle joint: highest angle between the axes",
        "Move": MOVE_DOC,
        "Residual": "violation after the last solve",
        "Violated": "not satisfied after the last solve",
        "Reversed": "part 2's axis flipped",
        "Offset": "part 2's point this far from part 1's, along part 1's axis",
        "TwistFrom": "Fixed, Slider: where part 2's turn about the axis is held from; Revolute, Cylindrical: "
                     "where their turn limits count from. Picked frames: the picked elements' own frames lined "
                     "up (a circle's or a face's x, else the part's z, x or y most across the axis): the same "
                     "whatever pose the parts were in when the joint was made. Pose when made: the turn recorded when the joint was made, or when this was last chosen in the "
                     "joint's panel or by edit_joint; joints saved before this existed",
        "FrameYaw": "part 2 turned this far about the joint's axis from the picked frame",
        "FramePitch": "part 2's axis tilted this far about the frame's y (after the yaw)",
        "FrameRoll": "part 2's axis tilted this far about the frame's x (after the pitch)",
        "FrameX": "part 2 moved this far along the joint frame's x (across the axis)",
        "FrameY": "part 2 moved this far along the joint frame's y (across the axis)",
        "Feature1": "what reference 1 is: point, line, plane, circle, ...",
        "Feature2": "what reference 2 is",
        "Distance": "Distance joint: the distance between the features",
        "Ratio": "Gears, Belt: part 2's turn per turn of part 1",
        "Radius": "RackPinion: the pinion's pitch radius (travel per radian)",
        "Pitch": "Screw: travel per turn",
        "LeftHanded": "Screw: a left-handed thread",
        "MeshOffset": "how far part 2 is turned (deg; a rack's or a screw's part 2: moved, mm) against part 1 "
                      "from where the coupling was made, part 1 held (the joint's panel previews it; here, the "
                      "next Solve takes it)",
        "Phase": "the engine's constant of the coupling's equation (kept for it; MeshOffset is its reading): "
                 "ratio x turn1 + turn2 (Gears; Belt: -ratio), or travel - radius x turn (RackPinion; Screw: "
                 "pitch / 2 pi), each turn measured from the line of centres",
        "PhaseTurns": "Gears, Belt: whole turns of part 2 in the phase (the engine's is Phase + 360 deg x PhaseTurns)",
        "PhaseKnown": "Phase is the engine's (else made at the poses)",
        "MeshOffsetHeld": "the mesh offset the stored Phase holds",
    },
    "SubAssembly": {
        "Assembly": "the assembly placed here (this or another document)",
        "Rigid": "moves as one part (its own joints solved inside it); off: its parts and joints join this "
                 "assembly's solve",
        "Placement": "where the instance's frame is",
        "Grounded": INSTANCE_GROUNDED,
    },
    # An instance inside an instance (its place mirrors a sub-assembly of the file placed).
    "NestedInstance": {
        "SourceName": "the Name of the sub-assembly this nested instance mirrors in the assembly its container places",
        "LocalPlacement": "this nested instance's frame in its container's frame (stored here, per instance)",
        "RigidInFile": "whether the placed file had this place rigid when it was last taken (Rigid unlike it: set here)",
    },
    "Part": dict(_PART, PartNumber="the part number the bill of materials lists (its description: the "
                                   "Description, Label2)"),
    # An instance's part: a link to the placed assembly's part, its pose kept per instance.
    "InstanceLink": dict(_PART, LocalPlacement="this part's placement in its instance's frame (stored here, per "
                                               "instance)"),
    "ExplodedView": {
        "Assembly": "the assembly drawn exploded",
        "StepModes": "each step's way: Radial (away from the centre), Direction (along it), Stack (stacked along it)",
        "StepDistances": "each step's distance (mm): Radial, how far its farthest part moves; Direction, how far "
                         "each moves; Stack, the step between two parts",
        "StepDirections": "each step's direction (Direction, Stack)",
        "StepParts": "the parts the steps move, step after step (a sub-assembly moves as one)",
        "StepSizes": "how many of StepParts each step moves",
        "Lines": "lines along the way each part is drawn",
        "Parts": "the parts drawn, in the order of Offsets",
        "Offsets": "how far each part is drawn from its place",
    },
    "BOM": {
        "Assembly": "the assembly this is the bill of",
        "SubAssemblies": "sub-assemblies: one row each, with their parts indented, or expanded into parts",
        "BomRows": "the rows written last (the header's too)",
    },
}
