"""View providers: how the assembly, its joints and its parts look in the tree and the 3D view.

A joint is drawn as its marker (markers.py) at its point and axis; the marker follows the parts as
they move (a document observer), turns green when the joint is selected (a selection observer) and
red while it is the joint a failed Solve or Check points at. All of that is state of the view:
the proxies save nothing (Stateless; no property of the document changes), so a saved file never
carries a highlight; objects.adopt() gives them back to objects whose view proxy a restore lost.
Double-clicking a joint opens its task panel."""
import math

import FreeCAD as App
import FreeCADGui as Gui

from . import markers
from .objects import Stateless, is_joint, is_sub_assembly, nested_parts
from .resources import icon_path


def icon(name):
    """The path of the workbench's icon `name` (Dispcon_<name>.svg)."""
    return icon_path("Dispcon_%s.svg" % name)


class _ViewProxy(Stateless):
    def __init__(self, vobj):
        vobj.Proxy = self


class ViewProviderAssembly(_ViewProxy):
    CAMERA_REST_MS = 150  # the markers are laid out again this long after the camera stopped

    def attach(self, vobj):
        self.Object = vobj.Object
        self.restack_pending = False
        # Joints' markers wait for the layout after a restore (place_later); a group is restored
        # after the objects it holds, so its joints may be waiting already.
        self.placing = vobj.Object.Document.Restoring
        if self.placing:
            self.restack_later()

    def place_later(self):
        """Has the next layout place the markers of this assembly's joints that wait for it:
        FreeCAD restoring a document calls a joint's updateData for each of its properties, seven
        of which moved its marker (1,226 placements for a 100-part chain's 147 joints, each
        asking for a layout, run while the restore went on), where one layout once the restore is
        over places each marker once."""
        self.placing = True
        self.restack_later()

    def restack_later(self):
        """Sets apart the markers of this assembly's joints drawn at one place, once the GUI is
        idle: each marker's follow() asks, and one pass over the joints serves them all (a solve
        moves every part, and each part's joints follow)."""
        self.frames_dirty = True  # a part or a joint moved: the next layout reads the frames again
        if getattr(self, "restack_pending", False):
            return
        self.restack_pending = True
        from .qt import QtCore

        QtCore.QTimer.singleShot(0, self.restack)

    def restack(self):
        """Sets the markers apart: those at one place side by side across their axis (stacks),
        then, on the screen of the document's 3D view, every two nearer than a gap pushed apart
        (spread) as the camera sees them now; the camera moving (a zoom, a turn, a fit) lays them
        out again."""
        self.restack_pending = False
        try:
            group = list(self.Object.Group)
            doc = self.Object.Document
            names = tuple(o.Name for o in group)
            restoring = doc.Restoring
        except Exception:  # the assembly (or its document) is gone meanwhile
            return
        if restoring:  # the restore runs the event loop (its progress bar): laid out once it ends
            from .qt import QtCore

            self.restack_pending = True
            QtCore.QTimer.singleShot(0, self.restack)
            return
        try:
            self._lay_out(group, doc, names)
        finally:
            if getattr(self, "placing", False):
                # The markers of a restored document the layout did not move, placed now.
                self.placing = False
                for o in group:
                    view = _joint_view(o) if o.TypeId == "App::FeaturePython" else None
                    if view is not None and view.waiting:
                        view.follow(o, restack=False)

    def _lay_out(self, group, doc, names):
        # The joints' frames and their stacks hold until a part or a joint moves (restack_later
        # says so) or the group changes: a camera coming to rest lays the markers out on the
        # screen again from them, without reading hundreds of joints from FreeCAD.
        laid = getattr(self, "laid", None)
        if laid is None or getattr(self, "frames_dirty", True) or laid[0] != names:
            laid = self.laid = (names,) + self._frames(group)
            self.frames_dirty = False
        _, frames, views, stacked, points = laid
        if not frames:
            return
        # Each shift is a world vector in glyph units (PIXELS pixels each on the screen).
        shifts = {name: across * (k * markers.STACK_SPACING) for name, (k, across) in stacked.items()}
        screen = _screen(doc)
        if screen is not None:
            self._watch(screen)
            gap = markers.SCREEN_GAP * markers.PIXELS
            anchors = screen.pixels_of(points)
            seeds = [screen.across(shifts[name]) if name in shifts else (0.0, 0.0) for name, _, _ in frames]
            offsets = markers.spread(anchors, gap, seeds, box=screen.box)
            shifts = {name: screen.world(offset) for (name, _, _), offset in zip(frames, offsets)}
        for name, view in views.items():
            view.set_shift(shifts.get(name))

    def _frames(self, group):
        """What a layout reads from FreeCAD: ([(joint name, world point, axis)] of the joints with
        a marker, {name: its view provider}, their stacks (markers.stacks), the points as an
        n x 3 array)."""
        import numpy

        frames, views = [], {}
        for j in group:
            if j.TypeId != "App::FeaturePython":  # a part: no marker (read at once, not its view's proxy)
                continue
            view = _joint_view(j)
            # (a joint whose part was deleted is not drawn: it takes no room)
            frame = markers.joint_frame(j) if view is not None and not getattr(view, "broken", False) else None
            if frame is not None:
                frames.append((j.Name, frame[0], frame[1]))
                views[j.Name] = view
        if not frames:
            return frames, views, {}, None
        points = numpy.array([(p.x, p.y, p.z) for _, p, _ in frames])
        # One place: within a millionth of the spread of the joints' points (the same pin or
        # axle picked twice gives the same point up to rounding).
        spread = max(float((points.max(axis=0) - points.min(axis=0)).max()), 1e-9)
        return frames, views, markers.stacks(frames, 1e-6 * spread), points

    def _watch(self, screen):
        """Lays the markers out again whenever the camera of `screen` (the 3D view's) moves, and
        when the view is drawn at another size or through another kind of camera than the layout
        counted with (a resize, a switch between orthographic and perspective), which move no
        camera: a probe at the top of the view's scene graph compares at each redraw."""
        from pivy import coin

        self.laid_for = screen.drawn
        if getattr(self, "camera_timer", None) is None:
            from .qt import QtCore

            # Once the camera rests (a turn or a zoom with the mouse moves it at every frame):
            # the layout of hundreds of markers takes tens of ms (docs/performance.md).
            self.camera_timer = QtCore.QTimer()
            self.camera_timer.setSingleShot(True)
            self.camera_timer.setInterval(self.CAMERA_REST_MS)
            self.camera_timer.timeout.connect(self.restack)
        probe = getattr(self, "probe", None)
        if probe is None or probe.graph != int(screen.view.getSceneGraph().this):
            if probe is not None:
                probe.remove()
            self.probe = _Probe(screen.view, self)
        sensor = getattr(self, "camera_sensor", None)
        if sensor is not None and getattr(self, "camera", None) is screen.camera:
            return
        if sensor is not None:
            sensor.detach()
        self.camera = screen.camera
        self.camera_sensor = coin.SoNodeSensor(lambda *_: self.camera_timer.start(), None)
        self.camera_sensor.attach(screen.camera)

    def seen_otherwise(self, drawn):
        """The probe's word: the view was drawn as `drawn` ((width, height, orthographic) of its
        viewport and camera), not as the layout counted: laid out again once that rests (a
        resize sends a redraw at every step)."""
        if drawn != getattr(self, "laid_for", None) and getattr(self, "camera_timer", None) is not None:
            self.camera_timer.start()

    def onDelete(self, vobj, subelements):
        probe, self.probe = getattr(self, "probe", None), None
        if probe is not None:
            probe.remove()
        return True

    def getIcon(self):
        return icon("Assembly")

    def onChanged(self, vobj, prop):
        # Hiding the assembly hides its joints' markers with it (and shows them again).
        if prop == "Visibility" and not vobj.Object.Document.Restoring:
            for o in getattr(vobj.Object, "Group", []):
                if is_joint(o) and o.ViewObject is not None:
                    o.ViewObject.Visibility = vobj.Visibility


class ViewProviderSubAssembly(_ViewProxy):
    """A sub-assembly in the tree: its icon says whether it moves as one part (rigid) or not."""

    def attach(self, vobj):
        self.Object = vobj.Object

    def getIcon(self):
        obj = getattr(self, "Object", None)
        flexible = obj is not None and "Rigid" in obj.PropertiesList and not obj.Rigid
        return icon("SubAssemblyFlexible" if flexible else "SubAssembly")

    def updateData(self, obj, prop):
        if prop == "Rigid" and hasattr(obj.ViewObject, "signalChangeIcon"):
            obj.ViewObject.signalChangeIcon()


class ViewProviderPart(_ViewProxy):
    """A part made by the workbench: the part's icon in the tree, the grounded part's (with the
    ground hatch) when it is grounded. The shape is drawn as any Part's."""

    def attach(self, vobj):
        self.Object = vobj.Object

    def getIcon(self):
        obj = getattr(self, "Object", None)
        return icon("GroundedPart" if getattr(obj, "Grounded", False) else "Part")

    def updateData(self, obj, prop):
        if prop == "Grounded" and hasattr(obj.ViewObject, "signalChangeIcon"):
            obj.ViewObject.signalChangeIcon()


class ViewProviderJoint(_ViewProxy):
    """A joint's marker in the 3D view, its type's icon in the tree, its panel on double-click."""

    def attach(self, vobj):
        self.Object = vobj.Object
        self.selected = False
        self.error = False
        obj = vobj.Object
        self.marker = markers.Marker(obj.JointType, "dispcon_marker_" + obj.Name)
        self.shift = None  # set off its point, apart from markers near it (the assembly's restack)
        self.waiting = False  # for the layout after a restore to place it (follow)
        self.broken = False  # one of its parts deleted: not drawn (follow)
        vobj.addDisplayMode(self.marker.root, "Marker")
        self.follow(obj)

    def getDisplayModes(self, vobj):
        return ["Marker"]

    def getDefaultDisplayMode(self):
        return "Marker"

    def setDisplayMode(self, mode):
        return mode

    def getIcon(self):
        obj = getattr(self, "Object", None)
        kind = obj.JointType if obj is not None and hasattr(obj, "JointType") else "Fixed"
        return icon("Joint" + kind)

    def updateData(self, obj, prop):
        if not hasattr(self, "marker"):
            return
        if prop == "JointType":
            self.marker.set_type(obj.JointType)
            # The tree shows the new type's icon.
            obj.ViewObject.signalChangeIcon() if hasattr(obj.ViewObject, "signalChangeIcon") else None
        if prop in ("JointType", "Point1", "Axis1", "Point2", "Reference1", "Reference2", "Ratio"):
            self.follow(obj)

    def follow(self, obj, restack=True):
        """Puts the marker at the joint's point and axis as the parts now stand (set apart from
        the others near it by its shift; the assembly lays them out again once idle). While
        FreeCAD restores the document, the marker waits, hidden, for the assembly's layout after
        the restore (ViewProviderAssembly.place_later)."""
        if obj.Document.Restoring and self._wait(obj):
            return
        # Either part gone (deleted): the joint joins nothing and is skipped by Solve and Check.
        broken = not all(ref and ref[0] is not None for ref in (obj.Reference1, obj.Reference2))
        placement = None if broken else markers.joint_placement(obj)
        if getattr(self, "waiting", False) or broken != getattr(self, "broken", False):
            # A joint one of whose parts was deleted is drawn nowhere, as FreeCAD 1.x's Assembly
            # hides a joint's frame whose reference is gone (it was left where the part had
            # been, in the air, the joint skipped by Solve and Check, which name it); an undo of
            # the delete gives the part back and the marker is drawn at its place again.
            self.waiting, self.broken = False, broken
            self.marker.set_visible(not broken)
        if placement is not None:
            self.marker.set_placement(placement)
            shift = getattr(self, "shift", None)
            self.marker.set_offset(placement.Rotation.inverted().multVec(shift) if shift else App.Vector())
        if restack:
            view = _assembly_view(obj)
            if view is not None:
                view.restack_later()

    def _wait(self, obj):
        """Leaves the marker, hidden (not drawn at the origin, where it is not), to its assembly's
        layout after the restore; False when the joint is in no assembly (placed at once)."""
        if self.waiting:
            return True
        assembly = next((p for p in obj.InList if obj in getattr(p, "Group", ())), None)
        if assembly is None:
            return False
        self.waiting = True
        self.marker.set_visible(False)
        view = getattr(getattr(assembly, "ViewObject", None), "Proxy", None)
        if isinstance(view, ViewProviderAssembly):
            view.place_later()
        # (else its view, given later in the restore, lays out and places its joints then)
        return True

    def set_shift(self, shift):
        """Sets the marker off its joint's point by `shift`, a world vector in glyph units (None:
        not moved), as the assembly's layout says."""
        if shift is not None and shift.Length < 1e-9:
            shift = None
        was = getattr(self, "shift", None)
        if (shift is None) != (was is None) or (shift is not None and (shift - was).Length > 1e-9):
            self.shift = shift
            self.follow(self.Object, restack=False)

    def set_error(self, on):
        self.error = bool(on)
        self._relook()

    def set_selected(self, on):
        self.selected = bool(on)
        self._relook()

    def _relook(self):
        self.marker.set_look("selected" if self.selected else "error" if self.error else "normal")

    def doubleClicked(self, vobj):
        Gui.ActiveDocument.setEdit(vobj.Object, 0)
        return True

    def setEdit(self, vobj, mode=0):
        if mode != 0:
            return None
        from .panels.joint import open_panel

        open_panel(vobj.Object)
        return True

    def unsetEdit(self, vobj, mode=0):
        if mode != 0:
            return None
        return True


class Observer:
    """One per workbench: moves markers with their parts and shows which joints are selected."""

    # Document observer -------------------------------------------------------------------
    def slotChangedObject(self, obj, prop):
        if prop != "Placement":
            return
        highlight = _HIGHLIGHTS.get(obj.Document.Name)
        if highlight is not None and obj.Name in highlight.parts:
            highlight.redraw_later()
        for o in obj.InList:
            proxy = _joint_view(o)
            if proxy is not None:
                proxy.follow(o)

    # Selection observer ------------------------------------------------------------------
    def addSelection(self, doc, name, sub, pos):
        self._refresh(doc)

    def removeSelection(self, doc, name, sub):
        self._refresh(doc)

    def setSelection(self, doc):
        self._refresh(doc)

    def clearSelection(self, doc):
        self._refresh(doc)

    def slotDeletedDocument(self, doc):
        _highlight(doc, [])

    def _refresh(self, doc_name):
        doc = App.getDocument(doc_name) if doc_name and doc_name in App.listDocuments() else App.ActiveDocument
        if doc is None:
            return
        chosen = Gui.Selection.getSelection(doc.Name)
        selected = {o.Name for o in chosen}
        for o in doc.Objects:
            proxy = _joint_view(o)
            if proxy is not None:
                proxy.set_selected(o.Name in selected)
        # A sub-assembly instance (a group: nothing of its own in the 3D view) selected in the
        # tree: its parts, at any depth, drawn in the selection's green.
        _highlight(doc, [o for o in chosen if is_sub_assembly(o)])


# The instances drawn highlighted, by document name.
_HIGHLIGHTS = {}


class _Highlight:
    """The edges of a selected instance's parts (every link at any depth) drawn over the view in
    the selection's green: FreeCAD highlights what a selected object draws, and an instance is a
    group that draws nothing of its own (its links are drawn at the document's root). State of
    the view only: a node of the 3D view's scene graph, never a property."""

    def __init__(self, doc, instances):
        from pivy import coin

        self.doc_name = doc.Name
        self.instances = [o.Name for o in instances]
        self.parts = set()
        self.root = coin.SoSeparator()
        self.root.setName("dispcon_instance_highlight")
        self.pending = False
        view = Gui.getDocument(doc.Name).ActiveView
        self.graph = view.getSceneGraph()
        # Held while the highlight is in it (the view can go first with its document).
        self.graph.ref()
        self.graph.addChild(self.root)
        self.redraw()

    def redraw_later(self):
        if not self.pending:
            self.pending = True
            from .qt import QtCore

            QtCore.QTimer.singleShot(0, self.redraw)

    def redraw(self):
        import Part

        self.pending = False
        if self.graph is None or self.doc_name not in App.listDocuments():
            return
        doc = App.getDocument(self.doc_name)
        links = [p for name in self.instances if doc.getObject(name) is not None
                 for p in nested_parts(doc.getObject(name))]
        self.parts = {p.Name for p in links}
        self.root.removeAllChildren()
        drawn, on_top = markers.overlay("dispcon_instance_edges", 3.0)
        self.root.addChild(drawn)
        shapes = []
        for link in links:
            try:
                shape = Part.getShape(link)
            except Exception:  # a link whose file is gone: nothing to draw
                continue
            if not shape.isNull():
                shapes.append(shape)
        markers.add_edges(on_top, shapes)

    def remove(self):
        graph, self.graph = self.graph, None
        if graph is not None:
            graph.removeChild(self.root)
            graph.unref()


def _highlight(doc, instances):
    """Draws the parts of `instances` (sub-assembly instances of `doc`) highlighted in `doc`'s
    3D view, and no other instance's."""
    was = _HIGHLIGHTS.pop(doc.Name, None)
    names = [o.Name for o in instances]
    if was is not None and was.instances == names and was.graph is not None:
        _HIGHLIGHTS[doc.Name] = was
        return
    if was is not None:
        was.remove()
    if not names or not App.GuiUp:
        return
    try:
        gdoc = Gui.getDocument(doc.Name)
        if gdoc is None or not hasattr(gdoc.ActiveView, "getSceneGraph"):
            return
        _HIGHLIGHTS[doc.Name] = _Highlight(doc, instances)
    except Exception:  # no 3D view (another kind of view active): nothing drawn
        return


def highlighted(doc):
    """The names of the instances drawn highlighted in `doc`'s view, and their parts'."""
    h = _HIGHLIGHTS.get(doc.Name)
    return (list(h.instances), set(h.parts)) if h is not None else ([], set())


class _Probe:
    """An SoCallback at the top of a 3D view's scene graph (FreeCAD's selection node, which holds
    every view provider's nodes): traversed at each redraw of the view before anything it draws,
    it tells its assembly's view provider the viewport's size and whether the camera is
    orthographic, so that a resize or a change of projection (neither moves the camera the
    layout watches) lays the markers out again. One Python call a redraw, whatever the number of
    markers; a traversal that is not a redraw (a pick, a bounding box) returns at once."""

    def __init__(self, view, owner):
        from pivy import coin

        graph = view.getSceneGraph()
        # The view, not its scene graph, is held: a closed view raises when asked for its graph,
        # where a graph held past its view would be read after it is freed.
        self.view, self.graph = view, int(graph.this)
        self.node = coin.SoCallback()
        self.node.setName("dispcon_layout_probe")
        self.node.setCallback(_probe, (owner, coin.SoGLRenderAction.getClassTypeId(), coin.SoViewportRegionElement.get,
                                       coin.SoViewVolumeElement.get, coin.SbViewVolume.ORTHOGRAPHIC))
        graph.insertChild(self.node, 0)

    def remove(self):
        view, self.view = self.view, None
        try:
            graph = view.getSceneGraph() if view is not None else None
        except Exception:  # the view is closed: the probe went with its scene graph
            return
        if graph is not None and int(graph.this) == self.graph:
            k = graph.findChild(self.node)
            if k >= 0:
                graph.removeChild(k)


def _probe(data, action):
    """_Probe's callback (`data`: the assembly's view provider, the render action's type and the
    elements' getters, found once)."""
    owner, render, region, volume, orthographic = data
    if not action.isOfType(render):
        return
    state = action.getState()
    width, height = region(state).getViewportSizePixels()
    owner.seen_otherwise((width, height, volume(state).getProjectionType() == orthographic))


class _Screen:
    """How the camera of a 3D view shows the world: pixels(point) the point's place on the screen
    (pixels from the camera's axis, x right, y up), world((dx, dy)) a shift of so many pixels as
    a world vector in glyph units (markers.PIXELS pixels each), across(shift) the other way."""

    def __init__(self, camera, height_pixels, width_pixels=None, view=None):
        from pivy import coin

        self.camera, self.view = camera, view  # (the 3D view, for _Probe)
        # How the view is drawn, as the layout counts it (compared by _Probe at each redraw).
        self.drawn = (width_pixels, height_pixels, camera.isOfType(coin.SoOrthographicCamera.getClassTypeId()))
        # The screen in pixels() (None: unknown, every marker laid out), its longer side both
        # ways: a window taller than wide has its camera's height across its width.
        side = 0.5 * max(width_pixels, height_pixels) if width_pixels else None
        self.box = None if side is None else (-side, -side, side, side)
        rot = camera.orientation.getValue()
        self.right, self.up, self.forward = (App.Vector(*rot.multVec(coin.SbVec3f(*v)).getValue())
                                             for v in ((1, 0, 0), (0, 1, 0), (0, 0, -1)))
        self.eye = App.Vector(*camera.position.getValue().getValue())
        # The camera's height (or angle) spans the viewport's shorter side: Coin widens the view
        # across the longer one (measured: 10 units at height 100 drawn 77.2 px apart in a
        # 1052 x 772 view, 55.2 in a 552 x 772 one, where the height's pixels put them 77.2 apart).
        span = min(width_pixels, height_pixels) if width_pixels else height_pixels
        if camera.isOfType(coin.SoOrthographicCamera.getClassTypeId()):
            self.per_unit, self.angle = span / max(camera.height.getValue(), 1e-12), None
        else:  # perspective: the pixels per unit fall with the depth
            self.per_unit, self.angle = span, camera.heightAngle.getValue()

    def _scale(self, point):
        if self.angle is None:
            return self.per_unit
        depth = max((point - self.eye).dot(self.forward), 1e-9)
        return self.per_unit / (2 * depth * math.tan(0.5 * self.angle))

    def pixels(self, point):
        d, s = point - self.eye, self._scale(point)
        return (d.dot(self.right) * s, d.dot(self.up) * s)

    def pixels_of(self, points):
        """pixels() of each row of an n x 3 array, as an n x 2 array (the same numbers: the same
        products, taken row by row in numpy)."""
        import numpy

        d = points - numpy.array(tuple(self.eye))
        right, up = numpy.array(tuple(self.right)), numpy.array(tuple(self.up))
        if self.angle is None:
            s = self.per_unit
        else:
            depth = numpy.maximum(d @ numpy.array(tuple(self.forward)), 1e-9)
            s = self.per_unit / (2 * depth * math.tan(0.5 * self.angle))
        return numpy.column_stack((d @ right * s, d @ up * s))

    def world(self, offset):
        return (self.right * offset[0] + self.up * offset[1]) * (1.0 / markers.PIXELS)

    def across(self, shift):
        """A world shift in glyph units as pixels on the screen, kept at its length when the
        camera looks along it (a stack seen end on still starts side by side)."""
        x, y = shift.dot(self.right), shift.dot(self.up)
        r = math.hypot(x, y)
        if r < 0.2 * shift.Length:
            x, y, r = 1.0, 0.0, 1.0
        return (x / r * shift.Length * markers.PIXELS, y / r * shift.Length * markers.PIXELS)


def _screen(doc):
    """The _Screen of `doc`'s active 3D view, or None (no GUI document, or another kind of view)."""
    try:
        gdoc = Gui.getDocument(doc.Name)
        view = gdoc.ActiveView if gdoc is not None else None
        if view is None or not hasattr(view, "getCameraNode"):
            return None
        width, height = view.getViewer().getSoRenderManager().getViewportRegion().getViewportSizePixels()
        return _Screen(view.getCameraNode(), height, width, view)
    except Exception:  # a view closing meanwhile: the world's stacks only
        return None


def _assembly_parts(joint):
    """The parts of the joint's assembly (its two parts when it is in none yet)."""
    for parent in joint.InList:
        group = getattr(parent, "Group", None)
        if group and joint in group:
            return [o for o in group if not is_joint(o)]
    return [r[0] for r in (joint.Reference1, joint.Reference2) if r and r[0] is not None]


def _assembly_view(joint):
    """The view provider proxy of the assembly holding `joint`, or None."""
    for parent in joint.InList:
        if joint in getattr(parent, "Group", []):
            vobj = getattr(parent, "ViewObject", None)
            proxy = getattr(vobj, "Proxy", None) if vobj is not None else None
            return proxy if isinstance(proxy, ViewProviderAssembly) else None
    return None


def _joint_view(obj):
    vobj = getattr(obj, "ViewObject", None)
    proxy = getattr(vobj, "Proxy", None) if vobj is not None else None
    return proxy if isinstance(proxy, ViewProviderJoint) and hasattr(proxy, "marker") else None


def joint_view(obj):
    """The joint's view provider proxy (its marker's looks), or None without the GUI."""
    return _joint_view(obj)


def install():
    """Registers the observers; returns a handle for uninstall."""
    observer = Observer()
    App.addDocumentObserver(observer)
    Gui.Selection.addObserver(observer)
    return observer


def uninstall(observer):
    App.removeDocumentObserver(observer)
    Gui.Selection.removeObserver(observer)


def attach(obj, kind=None):
    """Gives a joint or an assembly its view provider (new objects, or objects of a document
    saved before the view providers existed); `kind` ("Assembly", "Joint") when known."""
    if not App.GuiUp or obj.ViewObject is None:
        return
    if isinstance(getattr(obj.ViewObject, "Proxy", None),
                  (ViewProviderJoint, ViewProviderAssembly, ViewProviderSubAssembly, ViewProviderPart)):
        return
    if kind == "Part":
        ViewProviderPart(obj.ViewObject)
    elif kind == "Joint" or (kind is None and is_joint(obj)):
        ViewProviderJoint(obj.ViewObject)
    elif kind == "SubAssembly":
        ViewProviderSubAssembly(obj.ViewObject)
    elif kind == "Assembly" or (kind is None and hasattr(obj, "Group")):
        ViewProviderAssembly(obj.ViewObject)
