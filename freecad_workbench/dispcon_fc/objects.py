"""The workbench's document objects: the assembly (a group of parts and joints), the joints, and
the properties that make an object of the document a part. Every value lives in the objects'
properties; the Python proxies hold nothing (FreeCAD saves a proxy's state, and ours is None)."""
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


def _add(obj, type_id, name, group, doc, value=None):
    """Adds a property the object lacks (new objects, and documents saved by an older workbench
    or without it); keeps the value of one it has."""
    if name not in obj.PropertiesList:
        obj.addProperty(type_id, name, group, doc)
        if value is not None:
            setattr(obj, name, value)


def _mark(obj, kind):
    """The stored property that says what the object is, so it is recognised even when its
    Python proxy could not be restored (the workbench missing when the file was opened)."""
    _add(obj, "App::PropertyString", "DispconType", "Dispcon", "what this object is to the Dispcon workbench")
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
        _add(obj, "App::PropertyPrecision", "Tolerance", "Dispcon", "largest violation accepted", tolerance)
        _add(obj, "App::PropertyInteger", "MaxIterations", "Dispcon", "iteration cap", prefs["MaxIterations"])
        _add(obj, "App::PropertyString", "LastSolve", "Dispcon", "what the last solve said")

    def onDocumentRestored(self, obj):
        self.attach(obj)
        _view_restored(obj, "Assembly")


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
        _mark(obj, "Joint")
        if "JointType" not in obj.PropertiesList:
            obj.addProperty("App::PropertyEnumeration", "JointType", "Joint", "the kind of joint")
            obj.JointType = JOINT_TYPES
        elif list(obj.getEnumerationsOfProperty("JointType")) != JOINT_TYPES:
            # Saved by a workbench with fewer types: the full list, the joint's type kept.
            kind = obj.JointType
            obj.JointType = JOINT_TYPES
            obj.JointType = kind
        _add(obj, "App::PropertyLinkSub", "Reference1", "Joint", "part and element 1 (carries the guide)")
        _add(obj, "App::PropertyLinkSub", "Reference2", "Joint", "part and element 2")
        for name, doc in (("Point1", "joint point, part 1's frame"), ("Axis1", "joint axis, part 1's frame"),
                          ("Perp1", "reference across the axis, part 1's frame"),
                          ("Point2", "joint point, part 2's frame"), ("Axis2", "joint axis, part 2's frame"),
                          ("Perp2", "reference across the axis, part 2's frame")):
            _add(obj, "App::PropertyVector", name, "Geometry", doc)
        _add(obj, "App::PropertyBool", "HasRotationLimits", "Limits", "bound the turn about the axis")
        _add(obj, "App::PropertyAngle", "RotationMin", "Limits", "lowest turn from the creation pose")
        _add(obj, "App::PropertyAngle", "RotationMax", "Limits", "highest turn from the creation pose")
        _add(obj, "App::PropertyBool", "HasTravelLimits", "Limits", "bound the travel along the axis")
        _add(obj, "App::PropertyDistance", "TravelMin", "Limits", "lowest travel")
        _add(obj, "App::PropertyDistance", "TravelMax", "Limits", "highest travel")
        _add(obj, "App::PropertyAngle", "ConeAngle", "Limits", "ball joint: largest tilt of axis 2 from axis 1 (0: none)")
        _add(obj, "App::PropertyAngle", "AngleMin", "Limits", "Angle joint: lowest angle between the axes")
        _add(obj, "App::PropertyAngle", "AngleMax", "Limits", "Angle joint: highest angle between the axes", 180)
        _add(obj, "App::PropertyFloat", "Move", "Abilities", MOVE_DOC, -1)
        if obj.getDocumentationOfProperty("Move") != MOVE_DOC:  # saved with the earlier, terser words
            obj.setDocumentationOfProperty("Move", MOVE_DOC)
        _add(obj, "App::PropertyFloat", "Residual", "Solve", "violation after the last solve")
        _add(obj, "App::PropertyBool", "Violated", "Solve", "not satisfied after the last solve")
        joint_extras(obj)

    def onChanged(self, obj, prop):
        # Its type changed in the property editor: that type's properties shown (a document
        # being read gets them from attach, once its objects are restored).
        if prop == "JointType" and "Ratio" in obj.PropertiesList and "Restoring" not in obj.State:
            show_properties(obj)

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
    _add(obj, "App::PropertyXLink", "Assembly", "Sub-assembly", "the assembly placed here (this or another document)")
    _add(obj, "App::PropertyBool", "Rigid", "Sub-assembly",
         "moves as one part (its own joints solved inside it); off: its parts and joints join this assembly's solve",
         True)
    _add(obj, "App::PropertyPlacement", "Placement", "Sub-assembly", "where the instance's frame is")
    _add(obj, "App::PropertyBool", "Grounded", "Dispcon", INSTANCE_GROUNDED)
    if obj.getDocumentationOfProperty("Grounded") != INSTANCE_GROUNDED:  # a part's words, before
        obj.setDocumentationOfProperty("Grounded", INSTANCE_GROUNDED)


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
    _add(obj, "App::PropertyBool", "RigidInFile", "Sub-assembly",
         "whether the placed file had this place rigid when it was last taken (Rigid unlike it: set here)", obj.Rigid)
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


def joint_extras(obj):
    """Reversed, Offset and the frame's rotation offset (the joint panel's), the features picked, a
    Distance's value and the couplings' values, which joints made before them lack: a joint
    without them reads as not reversed, offset 0, not turned, a coupling of ratio 1."""
    _add(obj, "App::PropertyBool", "Reversed", "Joint", "part 2's axis flipped")
    _add(obj, "App::PropertyDistance", "Offset", "Joint", "part 2's point this far from part 1's, along part 1's axis")
    # The rotation offset of part 2's joint frame (FreeCAD 1.x's Assembly has an offset
    # placement on each joint's frames): yaw about the joint's axis, then pitch and roll.
    for name, doc in (("FrameYaw", "part 2 turned this far about the joint's axis from the picked frame"),
                      ("FramePitch", "part 2's axis tilted this far about the frame's y (after the yaw)"),
                      ("FrameRoll", "part 2's axis tilted this far about the frame's x (after the pitch)")):
        _add(obj, "App::PropertyAngle", name, "Joint", doc)
    # Its translation offset across the axis (along the axis: Offset): part 2's joint frame moved
    # in its own x and y, so part 2 stands that far off part 1's point in the joint's frame.
    for name, doc in (("FrameX", "part 2 moved this far along the joint frame's x (across the axis)"),
                      ("FrameY", "part 2 moved this far along the joint frame's y (across the axis)")):
        _add(obj, "App::PropertyDistance", name, "Joint", doc)
    _add(obj, "App::PropertyString", "Feature1", "Geometry", "what reference 1 is: point, line, plane, circle, ...")
    _add(obj, "App::PropertyString", "Feature2", "Geometry", "what reference 2 is")
    _add(obj, "App::PropertyDistance", "Distance", "Joint", "Distance joint: the distance between the features")
    _add(obj, "App::PropertyFloat", "Ratio", "Coupling", "Gears, Belt: part 2's turn per turn of part 1", 1.0)
    _add(obj, "App::PropertyDistance", "Radius", "Coupling", "RackPinion: the pinion's pitch radius (travel per radian)")
    _add(obj, "App::PropertyDistance", "Pitch", "Coupling", "Screw: travel per turn", 1.0)
    _add(obj, "App::PropertyBool", "LeftHanded", "Coupling", "Screw: a left-handed thread")
    phase_property(obj)
    show_properties(obj)
    read_only_derived(obj)


# What the workbench derives and a person reads but never types: the picked geometry in each
# part's frame (made again from the references at every solve) and the last solve's outcome.
# Editable, a typed Axis1 or Feature2 silently broke the joint until the next solve remade it.
DERIVED = ("Point1", "Axis1", "Perp1", "Point2", "Axis2", "Perp2", "Feature1", "Feature2", "Residual", "Violated")


def read_only_derived(obj):
    """The DERIVED properties read only in the property editor (scripts still write them)."""
    for name in DERIVED:
        if name in obj.PropertiesList and "ReadOnly" not in obj.getEditorMode(name):
            obj.setEditorMode(name, 1)


# The properties only some joint types use, with those types: the property editor shows a joint
# what its type takes (a revolute no ratio, no phase), as the joint's panel does.
_USED_BY = {"Ratio": ("Gears", "Belt"), "Radius": ("RackPinion",), "Pitch": ("Screw",), "LeftHanded": ("Screw",),
            "MeshOffset": COUPLINGS, "Phase": COUPLINGS, "PhaseTurns": ("Gears", "Belt"),
            "Distance": ("Distance",), "FrameYaw": FRAME_ROTATED, "FramePitch": FRAME_ROTATED,
            "FrameRoll": FRAME_ROTATED, "FrameX": FRAME_ROTATED, "FrameY": FRAME_ROTATED}
_READ_ONLY = ("Phase", "PhaseTurns")  # the engine's: the mesh offset sets them


def show_properties(obj):
    """Shows in the property editor the properties the joint's type uses (the engine's phase read
    only) and hides the others; nothing of a hidden one is lost."""
    kind = getattr(obj, "JointType", "")
    for name, types in _USED_BY.items():
        if name in obj.PropertiesList:
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


def phase_property(obj):
    """Phase in the unit of the joint's type (deg, or mm for a rack or a screw), and PhaseKnown:
    whether it is the engine's (False: the engine makes it at the poses the parts have, as for a
    coupling just made or changed, or one saved by an earlier workbench, whose Phase was a turn of
    its own part). MeshOffset, the designer's reading of it (mesh_offset), and MeshOffsetHeld, the
    offset the stored Phase holds (an offset typed in the property editor reaches the engine at
    the next model). A value of the other unit (the joint's type changed) goes, unknown."""
    want = "App::PropertyDistance" if getattr(obj, "JointType", "") in LENGTH_PHASE else "App::PropertyAngle"
    known = "PhaseKnown" in obj.PropertiesList
    for name in ("Phase", "MeshOffset", "MeshOffsetHeld"):
        if name in obj.PropertiesList and obj.getTypeIdOfProperty(name) != want:
            obj.removeProperty(name)
            if known:
                obj.PhaseKnown = False
    _add(obj, want, "MeshOffset", "Coupling",
         "how far part 2 is turned (deg; a rack's or a screw's part 2: moved, mm) against part 1 from where "
         "the coupling was made, part 1 held (the joint's panel previews it; here, the next Solve takes it)")
    _add(obj, want, "Phase", "Coupling", "the engine's constant of the coupling's equation (kept for it; "
         "MeshOffset is its reading): ratio x turn1 + turn2 (Gears; Belt: -ratio), or travel - radius x turn "
         "(RackPinion; Screw: pitch / 2 pi), each turn measured from the line of centres")
    # FreeCAD holds an angle property within +-360 deg, and a gear's phase goes round with the
    # turns: the whole turns of part 2 are kept beside it (the engine's phase is Phase + 360 deg
    # x PhaseTurns; a turn of part 2 is the same pose, so Phase alone says where its teeth are).
    _add(obj, "App::PropertyInteger", "PhaseTurns", "Coupling",
         "Gears, Belt: whole turns of part 2 in the phase (the engine's is Phase + 360 deg x PhaseTurns)")
    _add(obj, "App::PropertyBool", "PhaseKnown", "Coupling", "Phase is the engine's (else made at the poses)")
    # A joint saved before it: its Phase holds the offset it has.
    _add(obj, want, "MeshOffsetHeld", "Coupling", "the mesh offset the stored Phase holds", obj.MeshOffset.Value)
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
    if not hasattr(obj, "Grounded"):
        obj.addProperty("App::PropertyBool", "Grounded", "Dispcon", "never moves")
    if not hasattr(obj, "AbilityToRotate"):
        obj.addProperty("App::PropertyFloat", "AbilityToRotate", "Dispcon",
                        "no-physics ability to rotate (0: from the part's size)")
    if not hasattr(obj, "Density"):
        obj.addProperty("App::PropertyFloat", "Density", "Dispcon", "mass per unit volume").Density = 1.0
    if obj.TypeId != "App::Link":  # a link's part number is its linked object's, in its file
        part_number_property(obj)


def part_number_property(obj):
    """PartNumber, the bill of materials' part number of a part defined here (its description is
    FreeCAD's own Label2)."""
    _add(obj, "App::PropertyString", "PartNumber", "Bill of materials",
         "the part number the bill of materials lists (its description: the Description, Label2)")


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


def top_assemblies(doc):
    """The assemblies of `doc` that are not placed inside another assembly of `doc` (those placed
    in other documents' assemblies still count: each file has its own top)."""
    return [o for o in doc.Objects if is_assembly(o)
            and not any(is_sub_assembly(i) and i.Document == doc for i in o.InList)]


def nested_parts(sub):
    """The links of a sub-assembly instance and of the instances nested in it, at any depth."""
    return instance_parts(sub) + [p for n in sub_assemblies(sub) for p in nested_parts(n)]


def placed_parts(asm):
    """Every part a joint of `asm` can hold: its own and those of its sub-assemblies (and of
    theirs, at any depth)."""
    return parts(asm) + [p for s in sub_assemblies(asm) for p in nested_parts(s)]


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
    _view(obj, "Joint")
    return obj

