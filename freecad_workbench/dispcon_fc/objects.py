"""The workbench's document objects: the assembly (a group of parts and joints), the joints, and
the properties that make an object of the document a part. Every value lives in the objects'
properties; the Python proxies hold nothing (FreeCAD saves a proxy's state, and ours is None)."""
import FreeCAD as App

JOINT_TYPES = ["Fixed", "Revolute", "Slider", "Cylindrical", "Ball", "Planar", "PointOnLine",
               "PointOnPlane", "PointOnCurve", "Angle"]


class _Proxy:
    """What FreeCAD saves of a proxy: nothing, every value lives in the object's properties
    (__getstate__ and __setstate__ for FreeCAD 0.20, dumps and loads for 1.x)."""

    def execute(self, obj):
        pass

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    dumps = __getstate__
    loads = __setstate__


class AssemblyProxy(_Proxy):
    """An App::DocumentObjectGroupPython holding the parts and the joints of one assembly."""

    def __init__(self, obj):
        obj.Proxy = self
        self.attach(obj)

    def attach(self, obj):
        if not hasattr(obj, "Tolerance"):
            obj.addProperty("App::PropertyFloat", "Tolerance", "Dispcon", "largest violation accepted").Tolerance = 1e-9
        if not hasattr(obj, "MaxIterations"):
            obj.addProperty("App::PropertyInteger", "MaxIterations", "Dispcon", "iteration cap").MaxIterations = 10000
        if not hasattr(obj, "LastSolve"):
            obj.addProperty("App::PropertyString", "LastSolve", "Dispcon", "what the last solve said")

    def onDocumentRestored(self, obj):
        self.attach(obj)


class JointProxy(_Proxy):
    """An App::FeaturePython: two references, the joint's type, its points and axes in each part's
    frame (taken from the picked geometry) and its limits."""

    def __init__(self, obj):
        obj.Proxy = self
        obj.addProperty("App::PropertyEnumeration", "JointType", "Joint", "the kind of joint")
        obj.JointType = JOINT_TYPES
        obj.addProperty("App::PropertyLinkSub", "Reference1", "Joint", "part and element 1 (carries the guide)")
        obj.addProperty("App::PropertyLinkSub", "Reference2", "Joint", "part and element 2")
        for name, doc in (("Point1", "joint point, part 1's frame"), ("Axis1", "joint axis, part 1's frame"),
                          ("Perp1", "reference across the axis, part 1's frame"),
                          ("Point2", "joint point, part 2's frame"), ("Axis2", "joint axis, part 2's frame"),
                          ("Perp2", "reference across the axis, part 2's frame")):
            obj.addProperty("App::PropertyVector", name, "Geometry", doc)
        obj.addProperty("App::PropertyVectorList", "Curve1", "Geometry", "sampled curve, part 1's frame (PointOnCurve)")
        obj.addProperty("App::PropertyBool", "HasRotationLimits", "Limits", "bound the turn about the axis")
        obj.addProperty("App::PropertyAngle", "RotationMin", "Limits", "lowest turn from the creation pose")
        obj.addProperty("App::PropertyAngle", "RotationMax", "Limits", "highest turn from the creation pose")
        obj.addProperty("App::PropertyBool", "HasTravelLimits", "Limits", "bound the travel along the axis")
        obj.addProperty("App::PropertyDistance", "TravelMin", "Limits", "lowest travel")
        obj.addProperty("App::PropertyDistance", "TravelMax", "Limits", "highest travel")
        obj.addProperty("App::PropertyAngle", "ConeAngle", "Limits", "ball joint: largest tilt of axis 2 from axis 1 (0: none)")
        obj.addProperty("App::PropertyAngle", "AngleMin", "Limits", "Angle joint: lowest angle between the axes")
        obj.addProperty("App::PropertyAngle", "AngleMax", "Limits", "Angle joint: highest angle between the axes")
        obj.AngleMax = 180
        obj.addProperty("App::PropertyFloat", "Move", "Abilities", "part 1's share of a correction (-1: from the masses)")
        obj.Move = -1
        obj.addProperty("App::PropertyFloat", "Residual", "Solve", "violation after the last solve")
        obj.addProperty("App::PropertyBool", "Violated", "Solve", "not satisfied after the last solve")


def part_properties(obj):
    """The properties that make `obj` a part: Grounded, AbilityToRotate, Density."""
    if not hasattr(obj, "Grounded"):
        obj.addProperty("App::PropertyBool", "Grounded", "Dispcon", "never moves")
    if not hasattr(obj, "AbilityToRotate"):
        obj.addProperty("App::PropertyFloat", "AbilityToRotate", "Dispcon",
                        "no-physics ability to rotate (0: from the part's size)")
    if not hasattr(obj, "Density"):
        obj.addProperty("App::PropertyFloat", "Density", "Dispcon", "mass per unit volume").Density = 1.0


def is_joint(obj):
    return hasattr(obj, "Proxy") and isinstance(getattr(obj, "Proxy", None), JointProxy)


def is_assembly(obj):
    return hasattr(obj, "Proxy") and isinstance(getattr(obj, "Proxy", None), AssemblyProxy)


def shape_of(obj):
    """The placed shape of a part: its Shape, or, for an App::Link, the linked shape."""
    if hasattr(obj, "Shape"):
        return obj.Shape
    import Part

    return Part.getShape(obj)


def parts(asm):
    return [o for o in asm.Group
            if not is_joint(o) and (hasattr(o, "Shape") or o.TypeId == "App::Link")]


def joints(asm):
    return [o for o in asm.Group if is_joint(o)]


def new_assembly(doc, name):
    obj = doc.addObject("App::DocumentObjectGroupPython", name)
    AssemblyProxy(obj)
    return obj


def new_joint(doc, name):
    obj = doc.addObject("App::FeaturePython", name)
    JointProxy(obj)
    return obj
