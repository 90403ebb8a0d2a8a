"""The Exploded view panel: the view's steps in order (add, remove, move up and down), and the step
chosen: how it moves its parts (away from the centre, along a direction, stacked along it), how far
(a distance with its unit, and a slider that previews it live) and which parts (ticked in a list
of the assembly's parts and sub-assemblies, or taken from the selection). The exploded view is its
own object (exploded.py): the parts never move, so nothing here can lose the assembled placements.
The panel only translates: every setting goes to exploded.set_steps, which checks it and says what
is wrong (the panel shows that, OK disabled until it is fixed).

Like the Drive panel it holds one transaction open: OK keeps the view (a new one, or the steps
changed) as one undo step; Cancel puts its steps back, or removes the view it made."""
import FreeCADGui as Gui

from .. import exploded, panels
from ..qt import QtCore, QtGui, QtWidgets
from ..resources import icon_path
from .base import TransactionPanel, exists
from .joint import quantity_box, raw

# The direction box's choices: a label and the vector.
DIRECTIONS = (("+Z", (0, 0, 1)), ("-Z", (0, 0, -1)), ("+X", (1, 0, 0)), ("-X", (-1, 0, 0)),
              ("+Y", (0, 1, 0)), ("-Y", (0, -1, 0)))
SLIDER_STEPS = 1000
NAME_ROLE = QtCore.Qt.UserRole


class ExplodedPanel(TransactionPanel):
    """The task panel of `view`, an exploded view of `asm` (a new one when None)."""

    title = "Exploded view panel"

    def watched(self):
        return [self.asm, self.view]

    def __init__(self, asm, view=None):
        import FreeCAD as App

        self.asm, self.doc = asm, asm.Document
        self.new = view is None
        self.transaction = None
        self.closed = False
        self.busy = False
        self.was_shown = None if view is None else bool(view.ViewObject.Visibility)
        self.transaction = _transaction(self.doc)
        try:
            self.view = view or exploded.new_exploded_view(asm, undo_step=False)
            self.steps = [s.copy() for s in exploded.steps(self.view)]
        except Exception:
            self.transaction.abort()
            raise
        exploded.show(self.view, True)
        self.watch()
        # The slider's full travel: twice the assembly's size (a radial step's farthest part
        # that far out; a stack of a few parts that far apart).
        box = App.BoundBox()
        for p in self.view.Parts:
            box.add(exploded.shape_of(p).BoundBox)
        self.size = box.DiagonalLength
        self.reach = max([2.0 * self.size] + [abs(s.distance) for s in self.steps] + [1e-6])
        self.current = 0
        self.form = self._build()
        self._fill_steps()
        self._load_step()
        self._say(self._summary())
        # A part clicked in the 3D view (its copy in the view, or the part itself) is ticked in the
        # chosen step, or unticked when it was: the step's parts picked where they are seen.
        self.observer = _Picks(self)
        Gui.Selection.addObserver(self.observer)

    # -- the form ----------------------------------------------------------------------------
    def _build(self):
        w = QtWidgets.QWidget()
        w.setObjectName("DispconExplodedPanel")
        w.setWindowTitle("Exploded view")
        w.setWindowIcon(QtGui.QIcon(icon_path("Dispcon_ExplodedView.svg")))
        top = QtWidgets.QVBoxLayout(w)
        top.addWidget(QtWidgets.QLabel("Steps, applied in order:"))
        self.step_list = QtWidgets.QListWidget()
        self.step_list.setObjectName("steps")
        self.step_list.setToolTip("Each step moves its parts from where the steps before it left them")
        self.step_list.setMaximumHeight(110)
        top.addWidget(self.step_list)
        buttons = QtWidgets.QGridLayout()
        self.add_button = _button("addStep", "Add", "A new step after the one chosen, moving the parts selected now")
        self.remove_button = _button("removeStep", "Remove", "Remove the chosen step")
        self.up_button = _button("stepUp", "Up", "Apply the chosen step one earlier")
        self.down_button = _button("stepDown", "Down", "Apply the chosen step one later")
        for k, b in enumerate((self.add_button, self.remove_button, self.up_button, self.down_button)):
            buttons.addWidget(b, k // 2, k % 2)
        top.addLayout(buttons)
        self.message = QtWidgets.QLabel()  # under the steps: seen without scrolling the panel
        self.message.setObjectName("message")
        self.message.setWordWrap(True)
        top.addWidget(self.message)
        self.step_box = QtWidgets.QGroupBox("Step")
        self.step_box.setObjectName("stepBox")
        top.addWidget(self.step_box)
        form = QtWidgets.QFormLayout(self.step_box)
        form.setRowWrapPolicy(QtWidgets.QFormLayout.WrapLongRows)
        self.mode = QtWidgets.QComboBox()
        self.mode.setObjectName("mode")
        for mode in exploded.MODES:
            self.mode.addItem(exploded.MODE_WORDS[mode][0].upper() + exploded.MODE_WORDS[mode][1:], mode)
        self.mode.setToolTip("Away from the centre: each part out from the assembly's centre, the farthest by the "
                             "distance. Along a direction: each part the distance along it. Stacked: the parts in "
                             "their order along it, each the distance further than the one before")
        form.addRow("Moves", self.mode)
        self.direction = QtWidgets.QComboBox()
        self.direction.setObjectName("direction")
        self.direction.setToolTip("The direction the step moves its parts along (another one: a script's "
                                  "exploded.set_explosion)")
        form.addRow("Direction", self.direction)
        self.distance = quantity_box("mm", -1e9, 1e9)
        self.distance.setObjectName("distance")
        self.distance.setToolTip("Away from the centre: how far the farthest part moves; along a direction: how far "
                                 "each moves; stacked: the step between two parts")
        form.addRow("Distance", self.distance)
        self.slider = QtWidgets.QSlider(QtCore.Qt.Horizontal)
        self.slider.setObjectName("slider")
        self.slider.setRange(0, SLIDER_STEPS)
        self.slider.setToolTip("Drag to see the parts go apart (0 to twice the assembly's size)")
        form.addRow("", self.slider)
        self.parts = QtWidgets.QListWidget()
        self.parts.setObjectName("parts")
        self.parts.setToolTip("Ticked: the step moves it (a sub-assembly as one; a part inside one alone)")
        self.parts.setMinimumHeight(120)
        form.addRow("Parts", self.parts)
        for wide in (self.step_list, self.parts, self.mode, self.direction):
            # As narrow as the Combo View: the text is cut, the panel does not grow past it.
            wide.setSizePolicy(QtWidgets.QSizePolicy.Ignored, wide.sizePolicy().verticalPolicy())
        self.take = _button("takeSelection", "Take the selection",
                            "The step moves the parts and sub-assemblies selected (in the tree), no others")
        form.addRow("", self.take)
        self.lines = QtWidgets.QCheckBox("Lines along each part's way")
        self.lines.setObjectName("lines")
        top.addWidget(self.lines)
        top.addStretch(1)
        for asm_obj, depth in exploded.choices(self.asm):
            item = QtWidgets.QListWidgetItem("    " * depth + asm_obj.Label)
            item.setData(NAME_ROLE, asm_obj.Name)
            item.setFlags(item.flags() | QtCore.Qt.ItemIsUserCheckable)
            item.setCheckState(QtCore.Qt.Unchecked)
            self.parts.addItem(item)
        self.lines.setChecked(self.view.Lines)
        self.step_list.currentRowChanged.connect(self._chosen)
        self.add_button.clicked.connect(lambda *_: self.add_step())
        self.remove_button.clicked.connect(lambda *_: self.remove_step())
        self.up_button.clicked.connect(lambda *_: self.move_step(-1))
        self.down_button.clicked.connect(lambda *_: self.move_step(1))
        self.mode.currentIndexChanged.connect(self._edited)
        self.direction.currentIndexChanged.connect(self._edited)
        self.distance.valueChanged.connect(self._distance_typed)
        self.slider.valueChanged.connect(self._slid)
        self.parts.itemChanged.connect(self._edited)
        self.take.clicked.connect(lambda *_: self.take_selection())
        self.lines.toggled.connect(self._edited)
        return w

    def _fill_steps(self):
        self.busy = True
        self.step_list.clear()
        for k, s in enumerate(self.steps):
            self.step_list.addItem(_step_text(k, s))
        if self.steps:
            self.step_list.setCurrentRow(self.current)
        self.busy = False

    def _load_step(self):
        """The step box shows the chosen step (no redraw meanwhile)."""
        has = bool(self.steps)
        self.step_box.setEnabled(has)
        self.remove_button.setEnabled(has)
        self.up_button.setEnabled(has and self.current > 0)
        self.down_button.setEnabled(has and self.current < len(self.steps) - 1)
        if not has:
            return
        s = self.steps[self.current]
        self.busy = True
        self.step_box.setTitle("Step %d" % (self.current + 1))
        self.mode.setCurrentIndex(exploded.MODES.index(s.mode) if s.mode in exploded.MODES else 0)
        self.direction.clear()
        for label, _ in DIRECTIONS:
            self.direction.addItem(label)
        d = tuple(s.direction)
        match = [k for k, (_, vec) in enumerate(DIRECTIONS) if _parallel(vec, d)]
        if not match:
            self.direction.addItem("(%g, %g, %g)" % d)
            match = [self.direction.count() - 1]
        self.direction.setCurrentIndex(match[0])
        self.direction.setEnabled(s.mode != "Radial")
        self.distance.setProperty("rawValue", s.distance)
        self.slider.setValue(self._steps(s.distance))
        names = {p.Name for p in s.parts}
        for k in range(self.parts.count()):
            item = self.parts.item(k)
            item.setCheckState(QtCore.Qt.Checked if item.data(NAME_ROLE) in names else QtCore.Qt.Unchecked)
        self.busy = False

    def _steps(self, distance):
        return int(round(min(max(distance / self.reach, 0.0), 1.0) * SLIDER_STEPS))

    def _summary(self):
        moved = sum(1 for v in self.view.Offsets if v.Length > 0)
        return ("%d of %d parts drawn apart in %d step%s. The parts themselves stay assembled: hide the view "
                "(Space) to see them." % (moved, len(self.view.Parts), len(self.steps),
                                          "" if len(self.steps) == 1 else "s"))

    # -- the steps -----------------------------------------------------------------------------
    def _chosen(self, row):
        if self.busy or self._gone() or row < 0:
            return
        self.current = row
        self._load_step()

    def add_step(self):
        """A step after the chosen one: along +Z, a quarter of the assembly's size, moving what is
        selected (nothing selected: the panel asks for its parts)."""
        chosen = {o.Name for o in Gui.Selection.getSelection(self.doc.Name)}
        moving = [o for o, _ in exploded.choices(self.asm) if o.Name in chosen]
        at = self.current + 1 if self.steps else 0
        self.steps.insert(at, exploded.Step(moving, "Direction", round(0.25 * self.size, 1), (0, 0, 1)))
        self.current = at
        self._refresh()

    def remove_step(self):
        if not self.steps:
            return
        del self.steps[self.current]
        self.current = max(0, min(self.current, len(self.steps) - 1))
        self._refresh()

    def move_step(self, by):
        to = self.current + by
        if not self.steps or not 0 <= to < len(self.steps):
            return
        self.steps.insert(to, self.steps.pop(self.current))
        self.current = to
        self._refresh()

    def pick(self, obj_name, element):
        """A click in the 3D view on `obj_name`'s `element`: the unit it belongs to (a part of the
        assembly, or the sub-assembly placed in it that holds the part, moving as one) ticked in
        the chosen step, or unticked; returns that unit, or None when the click hit no part."""
        if self._gone() or not self.steps:
            return None
        obj = self.doc.getObject(obj_name)
        if obj is None:
            return None
        part = exploded.part_at(self.view, element) if obj == self.view else obj
        unit = exploded.unit_of(self.asm, part) if part is not None else None
        if unit is None:
            return None
        for k in range(self.parts.count()):
            item = self.parts.item(k)
            if item.data(NAME_ROLE) == unit.Name:
                on = item.checkState() != QtCore.Qt.Checked
                item.setCheckState(QtCore.Qt.Checked if on else QtCore.Qt.Unchecked)  # _edited redraws
                self._say("%s %s step %d. %s" % (unit.Label, "added to" if on else "taken out of", self.current + 1,
                                                  self.message.text()))
                return unit
        return None

    def _forget(self):
        observer = getattr(self, "observer", None)
        if observer is not None:
            Gui.Selection.removeObserver(observer)
            self.observer = None

    def take_selection(self):
        chosen = {o.Name for o in Gui.Selection.getSelection(self.doc.Name)}
        self.busy = True
        for k in range(self.parts.count()):
            item = self.parts.item(k)
            item.setCheckState(QtCore.Qt.Checked if item.data(NAME_ROLE) in chosen else QtCore.Qt.Unchecked)
        self.busy = False
        self._edited()

    def _refresh(self):
        self._fill_steps()
        self._load_step()
        self._apply()

    # -- the preview -------------------------------------------------------------------------
    def _slid(self, steps):
        if self.busy or self._gone():
            return
        value = self.reach * steps / SLIDER_STEPS
        self.busy = True
        self.distance.setProperty("rawValue", value)
        self.busy = False
        self._edited()

    def _distance_typed(self, *_):
        if self.busy or self._gone():
            return
        self.busy = True
        self.slider.setValue(self._steps(raw(self.distance)))
        self.busy = False
        self._edited()

    def _edited(self, *_):
        """The step box's values into the chosen step, then the preview."""
        if self.busy or self._gone():
            return
        if self.steps:
            s = self.steps[self.current]
            s.mode = self.mode.itemData(self.mode.currentIndex())
            k = self.direction.currentIndex()
            if 0 <= k < len(DIRECTIONS):
                s.direction = exploded.App.Vector(*DIRECTIONS[k][1])
            s.distance = raw(self.distance)
            by_name = {o.Name: o for o, _ in exploded.choices(self.asm)}
            s.parts = [by_name[self.parts.item(k).data(NAME_ROLE)] for k in range(self.parts.count())
                       if self.parts.item(k).checkState() == QtCore.Qt.Checked]
            self.direction.setEnabled(s.mode != "Radial")
            item = self.step_list.item(self.current)
            if item is not None:
                item.setText(_step_text(self.current, s))
        self._apply()

    def _apply(self):
        try:
            exploded.set_steps(self.view, self.steps, lines=self.lines.isChecked(), undo_step=False)
        except ValueError as e:
            self._say(str(e), True)
            self._set_ok(False)
            return
        Gui.updateGui()
        self._say(self._summary())
        self._set_ok(True)

    # -- the task dialog ----------------------------------------------------------------------
    def accept(self):
        self._close(commit=True)
        return True

    def _take_back(self):
        if self.new and exists(self.view):
            exploded.show(self.view, False)  # the parts back before the view goes
        self.transaction.abort()
        if not self.new and self.was_shown is not None and exists(self.view):
            exploded.show(self.view, self.was_shown)

    def _close(self, commit):
        if self.closed or self._gone():
            return
        self.closed = True
        self.unwatch()
        if commit:
            self.transaction.commit()
        else:
            self._take_back()
        self._forget()
        self.doc.recompute()
        Gui.Control.closeDialog()


class _Picks:
    """The panel's selection observer: a click in the 3D view with a sub-element (a face, an edge
    or a vertex under the cursor) picks that part for the chosen step; the selection it made is
    cleared once the click is taken, so the next click on it picks it again."""

    def __init__(self, panel):
        self.panel = panel

    def addSelection(self, doc, obj, sub, pnt):
        panel = self.panel
        if panel.closed or not sub or doc != panel.doc.Name:
            return
        if panel.pick(obj, sub) is not None:
            QtCore.QTimer.singleShot(0, Gui.Selection.clearSelection)


def _button(name, text, tip):
    b = QtWidgets.QPushButton(text)
    b.setObjectName(name)
    b.setToolTip(tip)
    return b


def _step_text(k, s):
    """"2. Along a direction, 20 mm: 3 parts" for the steps' list."""
    words = exploded.MODE_WORDS.get(s.mode, s.mode)
    return "%d. %s%s, %g mm: %d part%s" % (k + 1, words[0].upper(), words[1:], round(s.distance, 6), len(s.parts),
                                            "" if len(s.parts) == 1 else "s")


def _transaction(doc):
    from ..operations import Transaction

    return Transaction(doc, "Exploded view")


def _parallel(a, b):
    """Whether b points the way of the unit axis a."""
    n = sum(x * x for x in b) ** 0.5
    return n > 0 and all(abs(x - y / n) < 1e-12 for x, y in zip(a, b))


def open_panel(asm, view=None):
    """Shows the Exploded view panel of `view` (by default the assembly's first exploded view, or
    a new one); returns it."""
    current = panels.current(ExplodedPanel)
    if current is not None:
        current.reject()
    if Gui.Control.activeDialog():
        Gui.Control.closeDialog()
    if view is None:
        found = exploded.views_of(asm)
        view = found[0] if found else None
    panel = ExplodedPanel(asm, view)
    panels.show(panel)
    panel._set_ok(True)
    return panel
