"""The joint task panel: pick two references, choose the type, set limits, reverse and offset,
and watch the parts move while you do.

The panel holds one transaction open from the moment it opens: the joint it creates, every
preview solve and every change of a field are inside it, so OK is one undo step and Cancel
aborts it, which removes a new joint or gives an edited one (and the parts) back as they were.

Only the fields that apply to the chosen type are shown; lengths and angles are FreeCAD quantity
spin boxes (mm, deg): among them the rotation offset of part 2's joint frame (yaw, pitch, roll).
A min above its max is said in the panel and disables OK."""
import FreeCAD as App
import FreeCADGui as Gui

from .. import engine, geometry, markers, operations, panels
from ..guide import PICK
from ..adapter import ALREADY_HELD, offered_types, refused_bounds
from ..objects import COUPLINGS, LENGTH_PHASE, POSE_WHEN_MADE, TWIST_FROM, mesh_offset, phase_value, placed_parts

from ..qt import QtCore, QtGui, QtWidgets
from .base import TransactionPanel, full_pick

# Which groups of fields each type shows.
FIELDS = {
    "Fixed": ("reverse", "offset", "frame", "twist"),
    "Revolute": ("reverse", "offset", "frame", "rotation", "twist"),
    "Slider": ("reverse", "frame", "travel", "twist"),
    "Cylindrical": ("reverse", "frame", "rotation", "travel", "twist"),
    "Ball": ("offset", "cone"),
    "Planar": ("reverse", "offset", "frame"),
    "PointOnLine": ("travel",),
    "PointOnPlane": ("offset",),
    "PointOnCurve": (),
    "Distance": ("reverse", "distance"),
    "Parallel": ("reverse",),
    "Perpendicular": (),
    "Angle": ("reverse", "angle"),
    "Gears": ("reverse", "ratio", "phase"),
    "Belt": ("reverse", "ratio", "phase"),
    "RackPinion": ("reverse", "radius", "phase"),
    "Screw": ("reverse", "pitch", "phase", "travel"),
}
# Types whose joint is made from the picked geometry in a way of their own (which reference
# carries the guide, a coupling's ratio or radius from the picked circles): changing to or from
# one makes the joint again from the references.
REMADE = ("Distance", "Parallel", "Perpendicular") + COUPLINGS

# A value typed key by key is previewed (the joint's panel) or driven (the Drive's) once the keys
# pause this long, or editing ends (Enter, Tab, OK): not through its prefixes, "3" of "3 kg" or 1
# of 12, which moved the parts and left them so.
TYPING_PAUSE_MS = 400
STEP_KEYS = (QtCore.Qt.Key_Up, QtCore.Qt.Key_Down, QtCore.Qt.Key_PageUp, QtCore.Qt.Key_PageDown)

# The Twist from field's tooltip (the property's, TwistFrom, in the panel's words).
TWIST_TIP = ("Where part 2's turn about the joint's axis is held from (a Fixed, a Slider), or where the turn "
             "limits count from (a Revolute, a Cylindrical: their Min and Max). Picked frames: the picked edges' or "
             "faces' own frames lined up (a circle's or a face's x; a line's: the part's z, x or y most across "
             "it), the same whatever pose the parts are in now. Pose when made: the turn part 2 had when the joint "
             "was made here (a joint opened again: the turn it has when this is chosen); joints saved before "
             "this choice existed keep the turn they were made with")

# What a greyed-out field's tooltip says while the references are picked.
WAITING = "Pick both references first: the joint is made on them, then its fields apply to it"


def quantity_box(unit, minimum, maximum, value=0.0):
    """A Gui::QuantitySpinBox in `unit` (mm, deg) between minimum and maximum."""
    box = Gui.UiLoader().createWidget("Gui::QuantitySpinBox")
    set_unit(box, unit)
    box.setProperty("minimum", minimum)
    box.setProperty("maximum", maximum)
    box.setProperty("rawValue", value)
    return box


def set_unit(box, unit):
    box.setProperty("unit", unit)
    box.setProperty("dispconUnit", unit)  # read back as it was given (typed_problem)


UNIT_WORDS = {"mm": "a length", "deg": "an angle"}
UNIT_SIGNS = {"mm": " mm", "deg": "°"}


class StepOrKey(QtCore.QObject):
    """Tells the panel whether a box's next change is typed (a key that edits its text) or a
    step (an arrow key, the wheel, a click on its arrows)."""

    def __init__(self, panel, parent):
        super().__init__(parent)
        self.panel = panel

    def eventFilter(self, obj, event):
        kind = event.type()
        if kind == QtCore.QEvent.KeyPress:
            self.panel.keyed = event.key() not in STEP_KEYS
        elif kind in (QtCore.QEvent.Wheel, QtCore.QEvent.MouseButtonPress):
            self.panel.keyed = False
        return False


class TypedText(QtCore.QObject):
    """Reads what is typed into a panel's quantity boxes as it is typed (typed_problem): a text
    the box cannot take is said by its field's name, and the panel's problem() is that message
    (OK disabled) while it stays in the box. When editing ends the box goes back to the last
    value it could read, and the message says so."""

    def __init__(self, panel, boxes, form):
        super().__init__(form)
        self.panel, self.names, self.bad, self.box = panel, {}, None, None
        for box, what in boxes:
            self.names[box.objectName() or what] = (box, what)
            box.installEventFilter(self)
            box.editingFinished.connect(lambda b=box: self.finished(b))

    def eventFilter(self, obj, event):
        if event.type() == QtCore.QEvent.KeyRelease:
            for box, what in self.names.values():
                if box is obj:  # (a key's press has changed the text by its release)
                    self.read(box, what)
        return False

    def read(self, box, what):
        if self.panel.closed or self.panel._gone():
            return
        bad = typed_problem(box, what)
        was, self.bad, self.box = self.bad, bad, box if bad else None
        if bad:
            self.panel._say(bad, True)
            self.panel._set_ok(False)
        elif was:
            self.panel._edited()

    def finished(self, box):
        # (a panel closing takes the focus from its box: editing ends then too)
        if self.panel.closed or self.panel._gone() or box is not self.box:
            return
        said, self.bad, self.box = self.bad, None, None
        self.panel._changed()
        unit = box.property("dispconUnit")
        self.panel._say("%s It stays at %g%s." % (said, raw(box), UNIT_SIGNS[unit]), True)


def typed_problem(box, what):
    """What is wrong with the text typed in quantity box `box` (its field `what`), or None. The
    box keeps the last value it could read: "3 kg" typed in a length leaves it at 3 mm, and a
    value past its range leaves it where it was; the text is read here so that neither is taken
    without a word."""
    import FreeCAD as App

    text = box.text().strip()
    unit = box.property("dispconUnit")
    try:
        q = App.Units.Quantity(text)
    except Exception:  # FreeCAD's parser: not a quantity at all
        return "%s: '%s' is not %s (%s)." % (what, text, UNIT_WORDS[unit], unit)
    if q.Unit != App.Units.Unit() and q.Unit != App.Units.Quantity("1 " + unit).Unit:
        return "%s: '%s' is not %s (%s)." % (what, text, UNIT_WORDS[unit], unit)
    value = q.getValueAs(unit).Value if q.Unit != App.Units.Unit() else q.Value
    decimals = box.property("decimals")
    shown = 0.5 * 10.0 ** -(decimals if isinstance(decimals, int) else 2)
    if abs(value - raw(box)) > shown + 1e-9 * max(1.0, abs(value)):
        lo, hi = (float(getattr(v, "Value", v)) for v in (box.property("minimum"), box.property("maximum")))
        sign = UNIT_SIGNS[unit]
        return "%s: %g%s is outside %g%s .. %g%s." % (what, value, sign, lo, sign, hi, sign)
    return None


def raw(box):
    return float(box.property("rawValue"))


class JointPanel(TransactionPanel):
    """The task panel of a new joint (asm, joint_type, refs) or of an existing one (joint)."""

    title = "joint panel"

    def __init__(self, asm, joint_type=None, refs=(), joint=None):
        self.asm = asm
        self.joint = joint
        self.new = joint is None
        self.doc = asm.Document
        self.refs = list(refs)
        self.transaction = operations.Transaction(self.doc, "Edit joint" if joint else "Add joint")
        self.closed = False
        self.watch()
        self.preview = None  # the marker under the cursor while picking
        self.picked = None  # the references' edges drawn highlighted once the joint is made
        self.form = self._build(joint.JointType if joint else joint_type)
        self._load()
        self.picking = False
        Gui.Selection.addObserver(self)
        if self.joint is None and len(self.refs) == 2:
            self._create()
        elif self.joint is None:
            self._start_picking(keep=self.refs)
        elif len(self.refs) < 2:  # a part it held was deleted: made again on two new picks
            self._start_picking()
            self._say("%s lost a part (deleted): pick %s to make it again, or Cancel and delete it." % (
                joint.Label, PICK[joint.JointType]), True)
        self._show_fields()

    # -- the form ----------------------------------------------------------------------------
    def _build(self, joint_type):
        w = QtWidgets.QWidget()
        w.setObjectName("DispconJointPanel")
        w.setWindowTitle("Joint")
        w.setWindowIcon(QtGui.QIcon(markers_icon(joint_type)))
        top = QtWidgets.QVBoxLayout(w)
        form = QtWidgets.QFormLayout()
        form.setRowWrapPolicy(QtWidgets.QFormLayout.WrapLongRows)
        top.addLayout(form)
        self.type_box = QtWidgets.QComboBox()
        for t in offered_types(engine.load()):
            self.type_box.addItem(QtGui.QIcon(markers_icon(t)), t)
        self.type_box.setCurrentText(joint_type)
        self.type_box.setToolTip("The kind of joint: changing it keeps the references and moves the parts at once")
        form.addRow("Type", self.type_box)
        # What to pick next, or what is wrong, right under the type: at the panel's foot it was
        # below the fold of the Combo View (a Cylindrical's or a Screw's fields) at 1280x900.
        self.message = QtWidgets.QLabel()
        self.message.setObjectName("message")
        self.message.setWordWrap(True)
        top.addWidget(self.message)

        refs = QtWidgets.QGroupBox("References")
        rl = QtWidgets.QVBoxLayout(refs)
        self.ref_list = QtWidgets.QListWidget()
        self.ref_list.setMaximumHeight(52)
        rl.addWidget(self.ref_list)
        self.pick_button = QtWidgets.QPushButton("Pick again")
        self.pick_button.setToolTip("Forget the two references and pick two new ones in the 3D view")
        rl.addWidget(self.pick_button)
        top.addWidget(refs)

        self.groups = {}
        g = self._group(top, "reverse", None)
        self.reverse = QtWidgets.QCheckBox("Reverse (flip part 2's axis)")
        self.reverse.setToolTip("Part 2 faces the other way along the joint's axis (its picked axis flipped)")
        g.layout().addWidget(self.reverse)
        # Where a Fixed's or a Slider's hold on part 2's turn about the axis comes from, and
        # where a Revolute's or a Cylindrical's turn limits count from.
        g = self._group(top, "twist", None)
        gl = QtWidgets.QFormLayout()
        g.layout().addLayout(gl)
        self.twist = QtWidgets.QComboBox()
        self.twist.setObjectName("twistFrom")
        self.twist.addItems(list(TWIST_FROM))
        self.twist.setToolTip(TWIST_TIP)
        gl.addRow("Twist from", self.twist)
        g = self._group(top, "offset", None)
        gl = QtWidgets.QFormLayout()
        g.layout().addLayout(gl)
        self.offset = quantity_box("mm", -1e6, 1e6)
        self.offset.setToolTip("Gap between the two points along part 1's axis")
        gl.addRow("Offset", self.offset)
        # The rotation offset of part 2's joint frame, as FreeCAD's placement dialog spells a
        # rotation: yaw about the joint's axis, then pitch and roll.
        g = self._group(top, "frame", "Part 2's frame offset")
        gl = QtWidgets.QFormLayout()
        g.layout().addLayout(gl)
        self.frame = []
        for name, label, tip in (("frameYaw", "Yaw", "Part 2 turned this far about the joint's axis"),
                                 ("framePitch", "Pitch", "Part 2's axis tilted this far about the frame's y"),
                                 ("frameRoll", "Roll", "Part 2's axis tilted this far about the frame's x")):
            box = quantity_box("deg", -360, 360)
            box.setObjectName(name)
            box.setToolTip(tip)
            gl.addRow(label, box)
            self.frame.append(box)
        # Its translation offset across the axis (along it: Offset), in the frame's x and y.
        self.shift = []
        for name, label, tip in (("frameX", "Moved x", "Part 2 moved this far along the joint frame's x"),
                                 ("frameY", "Moved y", "Part 2 moved this far along the joint frame's y")):
            box = quantity_box("mm", -1e6, 1e6)
            box.setObjectName(name)
            box.setToolTip(tip)
            gl.addRow(label, box)
            self.shift.append(box)
        self.rot_min, self.rot_max, self.has_rotation = self._range(top, "rotation", "Limit the turn", "deg", -360, 360)
        self.tr_min, self.tr_max, self.has_travel = self._range(top, "travel", "Limit the travel", "mm", -1e6, 1e6)
        g = self._group(top, "cone", None)
        gl = QtWidgets.QFormLayout()
        g.layout().addLayout(gl)
        self.cone = quantity_box("deg", 0, 180)
        self.cone.setToolTip("Largest tilt of part 2's axis from part 1's (0: none)")
        gl.addRow("Cone", self.cone)
        self.ang_min, self.ang_max, _ = self._range(top, "angle", None, "deg", 0, 180)
        self.distance = self._value(top, "distance", "Distance", quantity_box("mm", -1e6, 1e6),
                                    "Distance between the two features (a plane's other side below 0)")
        ratio = QtWidgets.QDoubleSpinBox()
        ratio.setDecimals(6)
        ratio.setRange(0.0, 1e6)
        ratio.setValue(1.0)
        self.ratio = self._value(top, "ratio", "Ratio", ratio,
                                 "Part 2's turn per turn of part 1 (pitch radii r1 / r2, or teeth z1 / z2)")
        self.radius = self._value(top, "radius", "Pinion radius", quantity_box("mm", 0, 1e6, 1.0),
                                  "The rack's travel per radian of the pinion's turn (its pitch radius)")
        self.pitch = self._value(top, "pitch", "Pitch (per turn)", quantity_box("mm", 0, 1e6, 1.0),
                                 "The nut's travel along the screw per turn, in mm")
        self.left = QtWidgets.QCheckBox("Left-handed thread")
        self.left.setToolTip("The nut travels the other way for the same turn")
        self.groups["pitch"].layout().addWidget(self.left)
        # The mesh offset (an angle, or a length for a rack or a screw): 0 where the coupling
        # was made; a new one turns part 2 against part 1 at the preview's solve. The engine's
        # phase underneath is shown beside it, read only.
        self.phase = self._value(top, "phase", "Mesh offset", quantity_box("deg", -1e7, 1e7),
                                 "How far part 2 is turned against part 1 (part 1 held) from where the "
                                 "coupling was made; a rack's or a screw's part 2: how far it is moved")
        self.engine_phase = QtWidgets.QLabel()
        self.engine_phase.setObjectName("enginePhase")
        self.engine_phase.setWordWrap(True)  # unwrapped, it widened the panel past the Combo View
        self.engine_phase.setToolTip("The engine's constant of the coupling's equation (ratio x turn 1 + turn 2; "
                                     "a rack's or a screw's travel less its turns), kept in the joint: it moves "
                                     "by the offset, and by whole turns as the parts go round")
        self.engine_phase.setStyleSheet("color: gray;")
        self.groups["phase"].layout().addWidget(self.engine_phase)
        self.phase_edited = False  # only an offset typed in the panel goes to the joint
        self.phase.valueChanged.connect(self._phase_edited)

        top.addStretch(1)
        # Each quantity box by the name the panel shows it with, for what is wrong with its text.
        self.quantities = [(self.offset, "offset", "Offset")] + [
            (b, "frame", n) for b, n in zip(self.frame + self.shift, ("Yaw", "Pitch", "Roll", "Moved x", "Moved y"))] + [
            (self.rot_min, "rotation", "Turn min"), (self.rot_max, "rotation", "Turn max"),
            (self.tr_min, "travel", "Travel min"), (self.tr_max, "travel", "Travel max"), (self.cone, "cone", "Cone"),
            (self.ang_min, "angle", "Angle min"), (self.ang_max, "angle", "Angle max"),
            (self.distance, "distance", "Distance"), (self.radius, "radius", "Pinion radius"),
            (self.pitch, "pitch", "Pitch"), (self.phase, "phase", "Mesh offset")]
        self.typing = TypedText(self, [(box, what) for box, _, what in self.quantities], w)

        self.type_box.currentTextChanged.connect(self._type_changed)
        # (clicked passes its checked state, which is no list of references to keep)
        self.pick_button.clicked.connect(lambda *_: self._start_picking())
        self.reverse.toggled.connect(self._changed)
        # A value typed is previewed once the keys pause (or editing ends); a step, at once.
        self.keyed = False
        self.pause = QtCore.QTimer(w)
        self.pause.setSingleShot(True)
        self.pause.setInterval(TYPING_PAUSE_MS)
        self.pause.timeout.connect(self._changed)
        self.keys = StepOrKey(self, w)
        self.boxes = (self.offset, self.rot_min, self.rot_max, self.tr_min, self.tr_max, self.cone, self.ang_min,
                      self.ang_max, self.distance, self.ratio, self.radius, self.pitch, self.phase, *self.frame,
                      *self.shift)
        for box in self.boxes:
            box.valueChanged.connect(self._edited)
            box.installEventFilter(self.keys)
            box.editingFinished.connect(self._flush)
        for check in (self.has_rotation, self.has_travel, self.left):
            check.toggled.connect(self._changed)
        self.twist.currentTextChanged.connect(self._changed)
        return w

    def _phase_edited(self, *_):
        if not self.loading:
            self.phase_edited = True

    def _phase_unit(self):
        set_unit(self.phase, "mm" if self.type_box.currentText() in LENGTH_PHASE else "deg")

    def _group(self, top, name, title):
        g = QtWidgets.QGroupBox(title) if title else QtWidgets.QWidget()
        g.setObjectName(name)
        layout = QtWidgets.QVBoxLayout(g)
        if not title:
            layout.setContentsMargins(0, 0, 0, 0)
        top.addWidget(g)
        self.groups[name] = g
        return g

    def _value(self, top, name, label, box, tip):
        """A group of one value: its label and its box (a quantity spin box with its unit)."""
        g = self._group(top, name, None)
        gl = QtWidgets.QFormLayout()
        g.layout().addLayout(gl)
        box.setObjectName(name)
        box.setToolTip(tip)
        gl.addRow(label, box)
        return box

    def _range(self, top, name, check_text, unit, lo, hi):
        g = self._group(top, name, {"rotation": "Turn", "travel": "Travel", "angle": "Angle between axes"}[name])
        what = {"rotation": "turn about the axis", "travel": "travel along the axis",
                "angle": "angle between the two axes"}[name]
        check = None
        if check_text:
            check = QtWidgets.QCheckBox(check_text)
            check.setToolTip("Bound part 2's %s between Min and Max (untick: free)" % what)
            g.layout().addWidget(check)
        gl = QtWidgets.QFormLayout()
        g.layout().addLayout(gl)
        a, b = quantity_box(unit, lo, hi), quantity_box(unit, lo, hi)
        a.setObjectName(name + "Min")
        b.setObjectName(name + "Max")
        since = {"angle": "", "travel": ", measured from where the joint was made",
                 "rotation": ", counted as Twist from says (Picked frames: 0 where the picked frames' x's "
                             "line up; Pose when made: 0 as part 2 stood)"}[name]
        a.setToolTip("The lowest %s%s" % (what, since))
        b.setToolTip("The highest %s%s" % (what, since))
        gl.addRow("Min", a)
        gl.addRow("Max", b)
        return a, b, check

    def _load(self):
        """The fields from the joint (or the defaults of a new one)."""
        j = self.joint
        self.loading = True
        if j is not None:
            # (a reference whose part was deleted is None: the fourth audit's double-click on
            # such a joint raised here, leaving its transaction open and no panel)
            self.refs = [(r[0], r[1][0] if r[1] else "") for r in (j.Reference1, j.Reference2) if r and r[0]]
            self.reverse.setChecked(bool(getattr(j, "Reversed", False)))
            self.offset.setProperty("rawValue", float(getattr(j, "Offset", 0) and j.Offset.Value))
            self.has_rotation.setChecked(j.HasRotationLimits)
            self.rot_min.setProperty("rawValue", j.RotationMin.Value)
            self.rot_max.setProperty("rawValue", j.RotationMax.Value)
            self.has_travel.setChecked(j.HasTravelLimits)
            self.tr_min.setProperty("rawValue", j.TravelMin.Value)
            self.tr_max.setProperty("rawValue", j.TravelMax.Value)
            self.cone.setProperty("rawValue", j.ConeAngle.Value)
            self.ang_min.setProperty("rawValue", j.AngleMin.Value)
            self.ang_max.setProperty("rawValue", j.AngleMax.Value)
            for box, name in zip(self.frame + self.shift, ("FrameYaw", "FramePitch", "FrameRoll", "FrameX", "FrameY")):
                box.setProperty("rawValue", getattr(j, name).Value if name in j.PropertiesList else 0.0)
            self.twist.setCurrentText(getattr(j, "TwistFrom", POSE_WHEN_MADE))
            self._load_values()
        else:
            self.ang_max.setProperty("rawValue", 180.0)
        self._list_refs()
        self.loading = False

    def _load_values(self):
        """The Distance's and the couplings' fields from the joint (a joint made before them has
        none: the defaults stay)."""
        j = self.joint
        props = j.PropertiesList
        was, self.loading = self.loading, True
        self._phase_unit()
        for box, name in ((self.distance, "Distance"), (self.radius, "Radius"), (self.pitch, "Pitch")):
            if name in props:
                box.setProperty("rawValue", getattr(j, name).Value)
        if "Phase" in props:
            self.phase.setProperty("rawValue", mesh_offset(j))
            unit = " mm" if j.JointType in LENGTH_PHASE else "°"
            self.engine_phase.setText("Engine's phase: %.6g%s%s" % (phase_value(j), unit, "" if j.PhaseKnown
                                                                      else " (made at the poses at the next solve)"))
        self.phase_edited = False
        if "Ratio" in props:
            self.ratio.setValue(j.Ratio)
        if "LeftHanded" in props:
            self.left.setChecked(j.LeftHanded)
        self.loading = was

    def _list_refs(self):
        self.ref_list.clear()
        for k, (o, sub) in enumerate(self.refs):
            self.ref_list.addItem("%d. %s: %s" % (k + 1, o.Label, sub or "(whole part)"))
        self.pick_button.setEnabled(bool(self.refs))  # nothing picked yet: nothing to pick again

    def _show_fields(self):
        kind = self.type_box.currentText()
        shown = FIELDS[kind]
        was, self.loading = self.loading, True
        self._phase_unit()
        self.loading = was
        for name, g in self.groups.items():
            g.setVisible(name in shown)
        self._editable()

    def _editable(self):
        """The fields editable once the joint is made on both references; while picking each is
        greyed out, its tooltip saying why (they set a joint there is not yet)."""
        ready = self.joint is not None and not self.picking
        for g in self.groups.values():
            g.setEnabled(ready)
            for w in g.findChildren(QtWidgets.QWidget):
                if not isinstance(w, (QtWidgets.QAbstractSpinBox, QtWidgets.QCheckBox)):
                    continue
                tip = w.property("dispconTip")
                if tip is None:
                    tip = w.toolTip()
                    w.setProperty("dispconTip", tip)
                w.setToolTip(tip if ready else "%s\n(%s)" % (WAITING, tip) if tip else WAITING)
        for box, check in ((self.rot_min, self.has_rotation), (self.rot_max, self.has_rotation),
                           (self.tr_min, self.has_travel), (self.tr_max, self.has_travel)):
            box.setEnabled(ready and check.isChecked())

    # -- the picked references, highlighted ---------------------------------------------------
    def _highlight(self):
        """The joint's two references selected, and drawn in the selection's green over the 3D
        view, while the panel is open, as FreeCAD 1.x's joint panel keeps them (the panel's list
        names them; the view shows where they are). The drawing follows the parts as the preview
        moves them; both go at OK or Cancel."""
        if self.closed or self._gone() or self.joint is None:
            return
        Gui.Selection.clearSelection()
        for obj, sub in self.refs:
            Gui.Selection.addSelection(self.doc.Name, obj.Name, sub)
        self._draw_picked()

    def _draw_picked(self):
        self._hide_picked()
        view = Gui.ActiveDocument.ActiveView if Gui.ActiveDocument else None
        if self.joint is None or view is None or not hasattr(view, "getSceneGraph"):
            return
        self.picked = picked_edges(self.refs)
        self.picked_graph = view.getSceneGraph()
        self.picked_graph.ref()  # held while the drawing is in it (as the preview marker)
        self.picked_graph.addChild(self.picked)

    def _hide_picked(self):
        if self.picked is not None:
            graph, self.picked_graph = self.picked_graph, None
            graph.removeChild(self.picked)
            graph.unref()
            self.picked = None

    # -- picking -----------------------------------------------------------------------------
    def _start_picking(self, keep=()):
        """New references from the 3D view (after those in `keep`)."""
        self.picking = True
        self.refs = list(keep)
        self._list_refs()
        self._hide_picked()
        # No joint now: no engine's phase (it was the joint's, in its type's unit).
        self.engine_phase.setText("")
        if not keep:
            Gui.Selection.clearSelection()
        self._editable()
        self._say("Pick %s." % PICK[self.type_box.currentText()])
        self._set_ok(False)

    def watched(self):
        return [self.asm] + ([self.joint] if self.joint is not None else [])

    def _forget(self):
        """A panel whose document or form is gone stops listening and drops its drawings."""
        self._hide_preview()
        self._hide_picked()
        Gui.Selection.removeObserver(self)

    def addSelection(self, doc, name, sub, pos):
        if self._gone() or not self.picking or not sub or doc != self.doc.Name:
            return
        obj, sub = full_pick(doc, name, sub)  # a Body, or a link to one, for its tip's name
        # Its own parts and those of its sub-assemblies at any depth (a flexible leg's coupler is
        # a link in the instance's group, not the assembly's): what add_joint takes.
        if obj is None or obj not in placed_parts(self.asm):
            self._say("%s is not a part of %s: pick on one of its parts." % (obj.Label if obj else name, self.asm.Label), True)
            return
        if self.refs and self.refs[0][0] == obj:
            self._say("Pick the second reference on another part than %s." % obj.Label, True)
            return
        self.refs.append((obj, sub))
        self._list_refs()
        if len(self.refs) == 2:
            self.picking = False
            # Made once FreeCAD has finished with this selection event.
            QtCore.QTimer.singleShot(0, self._replace)
        else:
            self._say("Now %s's partner: pick on another part." % obj.Label)

    def setPreselection(self, doc, name, sub):
        """While picking, the feature under the cursor shows the marker the joint would get."""
        if self._gone() or not self.picking or not sub or doc != self.doc.Name:
            return
        obj, sub = full_pick(doc, name, sub)  # a Body, or a link to one, for its tip's name
        if obj is None or obj not in placed_parts(self.asm):
            return
        try:
            f = geometry.feature(obj, sub)
        except Exception:  # an element that gives no joint feature: no preview
            self._hide_preview()
            return
        if self.preview is None:
            view = Gui.ActiveDocument.ActiveView if Gui.ActiveDocument else None
            if view is None:
                return
            self.preview = markers.Marker(self.type_box.currentText(), "dispcon_preview")
            self.preview_graph = view.getSceneGraph()
            # Held while the preview is in it: the view and its scene graph can go first (with
            # their document), and taking the preview out of a freed node corrupts the heap.
            self.preview_graph.ref()
            self.preview_graph.addChild(self.preview.root)
        self.preview.set_type(self.type_box.currentText())
        self.preview.place(f.point, f.axis)
        self.preview.root.setName("dispcon_preview")

    def removePreselection(self, doc, name, sub):
        if not self._gone():
            self._hide_preview()

    def _hide_preview(self):
        if self.preview is not None:
            graph, self.preview_graph = self.preview_graph, None
            graph.removeChild(self.preview.root)
            graph.unref()  # freed here when its view has gone meanwhile
            self.preview = None

    # -- changes and the preview --------------------------------------------------------------
    def _replace(self):
        """The joint on the new references: the old one (if any) goes, inside the panel's
        transaction, so Cancel brings it back. (It runs from a timer: by then the panel may be
        closed, its widgets deleted.)"""
        if self.closed or self._gone():
            return
        self._hide_preview()
        if self.joint is not None:
            # A label its parts gave it follows the new parts; one typed, or a type's name from
            # an earlier workbench (Revolute001), stays.
            label = None if operations.named_from_parts(self.joint) else self.joint.Label
            self.changing = True  # (its own deletion: not one that ends the panel)
            try:
                self.doc.removeObject(self.joint.Name)
            finally:
                self.changing = False
            self.joint = None
            self._create()
            if self.joint is not None and label is not None:
                self.joint.Label = label
        else:
            self._create()

    def _create(self):
        try:
            kind = self.type_box.currentText()
            # (the twist chosen for the joint on the earlier references: taken at the pose now)
            twist = {"twist_from": self.twist.currentText()} if "twist" in FIELDS[kind] else {}
            self.joint = operations.add_joint(self.asm, kind, self.refs[0], self.refs[1], undo_step=False,
                                              named_by_parts=True, **twist)
        except ValueError as e:
            self._start_picking()
            self._say(str(e), True)
            return
        # add_joint may have put the guide's reference first (a Distance's plane, a pinion).
        self.refs = [(r[0], r[1][0] if r[1] else "") for r in (self.joint.Reference1, self.joint.Reference2)]
        # Its parts' poses as it is made, before its preview moves them: "Pose when made" chosen
        # later in this panel means these (_changed).
        self.made_at = [(o, App.Placement(o.Placement)) for o, _ in self.refs]
        self._list_refs()
        self._load_values()
        self._editable()
        self._changed()
        self._highlight()

    def _type_changed(self, kind):
        self._show_fields()
        self.form.setWindowIcon(QtGui.QIcon(markers_icon(kind)))
        if self.picking:
            self._say("Pick %s." % PICK[kind])
        elif self.joint is not None and (kind in REMADE or self.joint.JointType in REMADE):
            self._replace()
        else:
            self._changed()

    def values(self):
        """The edit the fields ask for, as operations.edit_joint's keywords."""
        kind = self.type_box.currentText()
        shown = FIELDS[kind]
        kw = {"joint_type": kind}
        if "rotation" in shown:
            kw["rotation"] = (raw(self.rot_min), raw(self.rot_max)) if self.has_rotation.isChecked() else False
        if "travel" in shown:
            kw["travel"] = (raw(self.tr_min), raw(self.tr_max)) if self.has_travel.isChecked() else False
        if "cone" in shown:
            kw["cone"] = raw(self.cone)
        if "angle" in shown:
            kw["angle"] = (raw(self.ang_min), raw(self.ang_max))
        kw["reverse"] = "reverse" in shown and self.reverse.isChecked()
        kw["offset"] = raw(self.offset) if "offset" in shown else 0.0
        if "frame" in shown:
            kw["frame"] = tuple(raw(box) for box in self.frame)
            kw["shift"] = tuple(raw(box) for box in self.shift)
        if "twist" in shown:
            kw["twist_from"] = self.twist.currentText()
        if "distance" in shown:
            kw["distance"] = raw(self.distance)
        if "ratio" in shown:
            kw["ratio"] = self.ratio.value()
        if "radius" in shown:
            kw["radius"] = raw(self.radius)
        if "pitch" in shown:
            kw["pitch"], kw["left"] = raw(self.pitch), self.left.isChecked()
        if "phase" in shown and self.phase_edited:
            kw["mesh_offset"] = raw(self.phase)
        return kw

    def problem(self):
        """What is wrong with the fields, in the panel's words, or None."""
        kw = self.values()
        if self.typing.bad:
            return self.typing.bad
        crossed = operations.crossed_limit(**kw)  # the engine's rule, asked while typing
        if crossed:
            key, refusal = crossed
            lo, hi, unit = refused_bounds(refusal)
            what = {"rotation": "Turn", "travel": "Travel", "angle": "Angle"}[key]
            return "%s: min %g%s is above max %g%s." % (what, lo, unit, hi, unit)
        for key, what, unit in (("ratio", "Ratio", ""), ("radius", "Pinion radius", " mm"), ("pitch", "Pitch", " mm")):
            if key in kw and not kw[key] > 0:
                return "%s %g%s: it must be above 0." % (what, kw[key], unit)
        return None

    def _edited(self, *_):
        """A box's value changed: typed, previewed once the keys pause; stepped (arrows, wheel)
        or set by a script, at once."""
        if self.keyed and not self.loading and any(box.hasFocus() for box in self.boxes):
            self.pause.start()
            return
        self._changed()

    def _flush(self):
        """Editing ended: what was typed and not yet previewed is previewed now."""
        self.keyed = False
        if self.pause.isActive():
            self._changed()

    def _changed(self, *_):
        if self.loading or self.closed or self._gone():
            return
        self.pause.stop()
        self._show_fields()
        bad = self.problem()
        if bad:
            self._say(bad, True)
            self._set_ok(False)
            return
        if self.joint is None:
            self._set_ok(False)
            return
        try:
            values = self.values()
            if values.get("twist_from") == POSE_WHEN_MADE and self.joint.TwistFrom != POSE_WHEN_MADE:
                self._back_to_made()
            operations.edit_joint(self.joint, undo_step=False, **values)
            r = operations.solve(self.asm, undo_step=False)
        except ValueError as e:
            self._say(str(e), True)
            self._set_ok(False)
            return
        self._set_ok(True)
        self._draw_picked()  # where the preview moved the parts
        self._load_values()  # the offset and phase the solve kept (made at the poses, or the one typed)
        if r.converged:
            self._say("%s holds%s." % (self.joint.Label, "" if r.message == ALREADY_HELD else " (%s)" % r.message))
        else:
            self._say("The parts cannot be placed so: %s. OK keeps the joint anyway." % r.message, True)
        Gui.updateGui()

    def _back_to_made(self):
        """"Pose when made" chosen for a joint this panel made: its parts back where they stood
        when it was made (its preview has lined their picked frames up since), so the turn it
        holds is the one part 2 had then, as the choice says; the solve that follows moves the
        rest. A joint the panel opened on is taken at the pose its parts have now."""
        for part, placement in getattr(self, "made_at", ()):
            if not getattr(part, "Grounded", False) and part.Placement != placement:
                part.Placement = placement

    # -- the task dialog ----------------------------------------------------------------------
    def accept(self):
        self._flush()  # (Enter or OK before typing paused: the value typed, then the commit)
        bad = self.problem()
        if bad or self.joint is None:
            self._say(bad or "Pick two references first.", True)
            return False
        self._close(commit=True)
        return True

    def _close(self, commit):
        if self.closed or self._gone():  # its document closed: nothing to commit or abort
            return
        self.closed = True
        self.unwatch()
        self.pause.stop()
        self._hide_preview()
        self._hide_picked()
        Gui.Selection.removeObserver(self)
        Gui.Selection.clearSelection()  # the references highlighted while it was open
        if commit:
            self.transaction.commit()
        else:
            self.transaction.abort()
        self.doc.recompute()
        Gui.Control.closeDialog()
        if Gui.ActiveDocument is not None and Gui.ActiveDocument.getInEdit() is not None:
            Gui.ActiveDocument.resetEdit()


def picked_edges(refs):
    """A Coin3D node drawing the edges of the references [(object, sub-element)] (a face's
    boundary, a vertex as a dot) in the selection's green over the view, unpickable: FreeCAD's
    own highlight of a selected edge is drawn by the view's renderer only, so this one is what
    an image of the view (and a test) sees as well."""
    from pivy import coin

    root, on_top = markers.overlay("dispcon_picked", 4.0)
    elements, dots = [], []
    for obj, sub in refs:
        try:
            element = obj.getSubObject(sub) if sub else obj.Shape
        except Exception:  # an element gone: nothing to draw for it
            continue
        if element is None or element.isNull():
            continue
        elements.append(element)
        dots += [(v.X, v.Y, v.Z) for v in element.Vertexes] if element.ShapeType == "Vertex" else []
    markers.add_edges(on_top, elements)
    if dots:
        coords = coin.SoCoordinate3()
        coords.point.setValues(0, len(dots), dots)
        on_top.addChild(coords)
        on_top.addChild(coin.SoPointSet())
    return root


def markers_icon(kind):
    from ..viewproviders import icon

    return icon("Joint" + kind)


def open_panel(joint=None, asm=None, joint_type=None, refs=()):
    """Shows the panel for `joint`, or for a new joint of `asm` on `refs` (picked in the 3D view
    when fewer than two); returns it."""
    # Another joint panel open: cancelled as its Cancel would (its transaction aborted, its
    # observer and timers stopped). Closing only the dialog left that panel alive with its
    # widgets deleted: its pending _replace then ran inside this call and read a deleted spin
    # box ("Internal C++ object (QAbstractSpinBox) already deleted", seen under load).
    previous = current()
    if previous is not None:
        previous.reject()
    if Gui.Control.activeDialog():
        Gui.Control.closeDialog()
    if joint is not None:
        asm = next(p for p in joint.InList if joint in getattr(p, "Group", []))
    panel = JointPanel(asm, joint_type=joint_type, refs=refs, joint=joint)
    panels.show(panel)
    if panel.joint is None or panel.picking:  # (an edited joint that lost a part: picked again)
        panel._set_ok(False)
    elif not panel.new:
        panel._changed()
        panel._highlight()
    return panel


def current():
    """The joint panel open now, or None."""
    return panels.current(JointPanel)
