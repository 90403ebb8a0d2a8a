"""Points and axes from FreeCAD geometry: what a picked vertex, edge or face means for a joint."""
import FreeCAD as App


class Feature:
    """A point and a unit axis in world coordinates, where they came from, and the radius of a
    circular edge or a cylindrical face (None for others): a gear's pitch circle. `across`: the x
    direction of the element's own frame, in world coordinates, where it has one (a circle's, a
    planar, cylindrical or spherical face's surface frame; FreeCAD's Assembly takes a joint's
    frame from it), else None: a line and a vertex define no direction across their axis."""

    def __init__(self, point, axis, kind, radius=None, across=None):
        self.point = App.Vector(point)
        self.axis = App.Vector(axis).normalize() if App.Vector(axis).Length > 0 else App.Vector(0, 0, 1)
        self.kind = kind
        self.radius = radius
        self.across = App.Vector(across) if across is not None else None

    @property
    def shape(self):
        """What the feature is to a Distance, Parallel or Perpendicular joint: "point" (a vertex,
        a sphere's or a circle's centre), "line" (a straight edge, a cylinder's axis) or "plane"
        (a planar face); None for a curve or a face of another kind."""
        return {"vertex": "point", "sphere": "point", "circle": "point", "line": "line",
                "cylinder": "line", "plane": "plane"}.get(self.kind)


def feature(obj, sub):
    """The joint feature of `obj`'s sub-element `sub` ("Edge3", "Face2", "Vertex1"), in world
    coordinates: a circular edge gives its centre and axis, a straight edge its midpoint and
    direction, a cylindrical face its axis (the point nearest to its centre of mass), a planar face
    its centre and normal, a spherical face its centre and its own axis, a vertex its point and
    the part's own z (FreeCAD 1.x's Assembly gives a vertex the part's own axes: a function of the
    part, never of the pose it stands in); another face its centre of mass and the world's z."""
    if hasattr(obj, "Shape"):
        shape = obj.Shape
    else:  # an App::Link: the linked shape, placed
        import Part

        shape = Part.getShape(obj)
    try:
        element = shape.getElement(sub)
    except Exception:
        raise ValueError("%s has no %s" % (obj.Label, sub or "sub-element: pick an edge, face or vertex")) from None
    curve = getattr(element, "Curve", None)
    surface = getattr(element, "Surface", None)
    if sub.startswith("Vertex"):
        return Feature(element.Point, shape.Placement.Rotation.multVec(App.Vector(0, 0, 1)), "vertex")
    if sub.startswith("Edge"):
        if hasattr(curve, "Radius") and hasattr(curve, "Center"):
            return Feature(curve.Center, curve.Axis, "circle", curve.Radius, getattr(curve, "XAxis", None))
        if curve is not None and curve.TypeId == "Part::GeomLine":
            a, b = element.Vertexes[0].Point, element.Vertexes[-1].Point
            return Feature((a + b) * 0.5, b - a, "line")
        first, last = element.FirstParameter, element.LastParameter
        return Feature(element.valueAt(0.5 * (first + last)), element.tangentAt(first), "curve")
    if sub.startswith("Face"):
        kind = surface.TypeId if surface is not None else ""
        if kind == "Part::GeomCylinder":
            centre = element.CenterOfMass
            base, axis = surface.Center, surface.Axis
            foot = base + axis * (centre - base).dot(axis)
            return Feature(foot, axis, "cylinder", surface.Radius, _surface_x(surface))
        if kind == "Part::GeomPlane":
            u0, u1, v0, v1 = element.ParameterRange
            return Feature(element.CenterOfMass, element.normalAt(0.5 * (u0 + u1), 0.5 * (v0 + v1)), "plane",
                           across=_surface_x(surface))
        if kind == "Part::GeomSphere":
            return Feature(surface.Center, surface.Axis, "sphere", across=_surface_x(surface))
        return Feature(element.CenterOfMass, App.Vector(0, 0, 1), "face")
    raise ValueError("%s.%s: expected a VertexN, EdgeN or FaceN" % (obj.Label, sub))


def _surface_x(surface):
    """The x direction of a surface's own frame (a plane's, a cylinder's, a sphere's), world
    coordinates."""
    rotation = getattr(surface, "Rotation", None)
    return rotation.multVec(App.Vector(1, 0, 0)) if rotation is not None else None


def to_local(placement, point=None, axis=None):
    """World point / direction into the local frame of an object with this placement."""
    inverse = placement.inverse()
    if point is not None:
        return inverse.multVec(point)
    return inverse.Rotation.multVec(axis)


def center_of_mass(shape):
    """The centre of mass of a shape's solids (None when it has none, or no volume): what a
    model without physics needs of a part. One solid, the common part, costs two of
    OpenCascade's integrations instead of mass_properties' six: pressing on a part of a
    100-part assembly to drag it builds the model from every part."""
    solids = shape.Solids
    if len(solids) != 1:
        props = mass_properties(shape)
        return props[1] if props is not None else None
    if not solids[0].Volume > 0:
        return None
    return solids[0].CenterOfMass


def mass_properties(shape):
    """Volume, centre of mass and inertia tensor (about the centre of mass, global axes) of a
    shape's solids, as FreeCAD computes them; None when it has no solid."""
    solids = shape.Solids
    if not solids:
        return None
    volume = sum(s.Volume for s in solids)
    if volume <= 0:
        return None
    com = App.Vector(0, 0, 0)
    for s in solids:
        com += s.CenterOfMass * (s.Volume / volume)
    inertia = [[0.0] * 3 for _ in range(3)]
    for s in solids:
        m = s.MatrixOfInertia  # about the solid's own centre of mass, unit density
        d = s.CenterOfMass - com
        dd = [d.x, d.y, d.z]
        for i in range(3):
            for j in range(3):
                parallel = s.Volume * ((d.dot(d) if i == j else 0.0) - dd[i] * dd[j])
                inertia[i][j] += m.A[4 * i + j] + parallel
    return volume, com, inertia
