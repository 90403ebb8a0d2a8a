"""The Exploded view panel: how the assembly's parts are drawn apart (away from its centre, or
stacked along a direction), how far (a distance with its unit, and a slider that previews it
live), whether a sub-assembly moves as one. The exploded view is its own object (exploded.py):
the parts never move, so nothing here can lose the assembled placements.

Like the Drive panel it holds one transaction open: OK keeps the view (a new one, or the settings
changed) as one undo step; Cancel puts its settings back, or removes the view it made."""
import FreeCADGui as Gui

from .. import exploded, panels
from ..qt import QtCore, QtGui, QtWidgets
from ..resources import icon_path
from .base import TransactionPanel
from .joint import quantity_box, raw

# The direction box's choices: a label and the vector.
DIRECTIONS = (("+Z", (0, 0, 1)), ("-Z", (0, 0, -1)), ("+X", (1, 0, 0)), ("-X", (-1, 0, 0)),
              ("+Y", (0, 1, 0)), ("-Y", (0, -1, 0)))
SLIDER_STEPS = 1000


class ExplodedPanel(TransactionPanel):
    """The task panel of `view`, an exploded view of `asm` (a new one when None)."""

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
        except Exception:
            self.transaction.abort()
            raise
        exploded.show(self.view, True)
        # The slider's full travel: twice the assembly's size (a radial view's farthest part
        # that far out; a stack of a few parts that far apart).
        box = App.BoundBox()
        for p in self.view.Parts:
            box.add(exploded.shape_of(p).BoundBox)
        self.reach = max(2.0 * box.DiagonalLength, abs(self.view.Distance.Value), 1e-6)
        self.form = self._build()
        self._load()

    # -- the form ----------------------------------------------------------------------------
    def _build(self):
        w = QtWidgets.QWidget()
        w.setObjectName("DispconExplodedPanel")
        w.setWindowTitle("Exploded view")
        w.setWindowIcon(QtGui.QIcon(icon_path("Dispcon_ExplodedView.svg")))
        top = QtWidgets.QVBoxLayout(w)
        form = QtWidgets.QFormLayout()
        form.setRowWrapPolicy(QtWidgets.QFormLayout.WrapLongRows)
        top.addLayout(form)
        self.mode = QtWidgets.QComboBox()
        self.mode.setObjectName("mode")
        self.mode.addItem("Away from the centre", "Radial")
        self.mode.addItem("Along a direction", "Direction")
        self.mode.setToolTip("Away from the centre: each part moves out from the assembly's centre, the farthest "
                             "by the distance. Along a direction: the parts in their order along it, each "
                             "the distance further than the one before")
        form.addRow("Explode", self.mode)
        self.direction = QtWidgets.QComboBox()
        self.direction.setObjectName("direction")
        for label, _ in DIRECTIONS:
            self.direction.addItem(label)
        self.direction.setToolTip("The direction the parts are stacked along (another one: the view's "
                                  "Direction property)")
        form.addRow("Direction", self.direction)
        self.distance = quantity_box("mm", 0.0, 1e9)
        self.distance.setObjectName("distance")
        self.distance.setToolTip("Away from the centre: how far the farthest part moves; along a direction: "
                                 "the step between two parts")
        form.addRow("Distance", self.distance)
        self.slider = QtWidgets.QSlider(QtCore.Qt.Horizontal)
        self.slider.setObjectName("slider")
        self.slider.setRange(0, SLIDER_STEPS)
        self.slider.setToolTip("Drag to see the parts go apart (0 to twice the assembly's size)")
        form.addRow("", self.slider)
        self.expand = QtWidgets.QCheckBox("Each part of a sub-assembly alone")
        self.expand.setObjectName("expand")
        self.expand.setToolTip("Off: a placed sub-assembly moves as one")
        form.addRow(self.expand)
        self.lines = QtWidgets.QCheckBox("Lines from each part's place")
        self.lines.setObjectName("lines")
        form.addRow(self.lines)
        self.message = QtWidgets.QLabel()
        self.message.setObjectName("message")
        self.message.setWordWrap(True)
        top.addWidget(self.message)
        top.addStretch(1)
        self.mode.currentIndexChanged.connect(self._changed)
        self.direction.currentIndexChanged.connect(self._changed)
        self.distance.valueChanged.connect(self._distance_typed)
        self.slider.valueChanged.connect(self._slid)
        self.expand.toggled.connect(self._changed)
        self.lines.toggled.connect(self._changed)
        return w

    def _load(self):
        """The form shows the view's settings (no redraw meanwhile)."""
        v = self.view
        self.busy = True
        self.mode.setCurrentIndex(exploded.MODES.index(v.Mode))
        d = tuple(v.Direction)
        match = [k for k, (_, vec) in enumerate(DIRECTIONS) if _parallel(vec, d)]
        if not match:
            self.direction.addItem("(%g, %g, %g)" % d)
            match = [self.direction.count() - 1]
        self.direction.setCurrentIndex(match[0])
        self.distance.setProperty("rawValue", v.Distance.Value)
        self.slider.setValue(self._steps(v.Distance.Value))
        self.expand.setChecked(v.ExpandSubAssemblies)
        self.lines.setChecked(v.Lines)
        self.direction.setEnabled(v.Mode == "Direction")
        self.busy = False
        self._say(self._summary())

    def _steps(self, distance):
        return int(round(min(max(distance / self.reach, 0.0), 1.0) * SLIDER_STEPS))

    def _direction(self):
        k = self.direction.currentIndex()
        return DIRECTIONS[k][1] if k < len(DIRECTIONS) else tuple(self.view.Direction)

    def _summary(self):
        v = self.view
        how = ("away from the centre, the farthest part %g mm" % v.Distance.Value if v.Mode == "Radial" else
               "along %s, %g mm apart" % (self.direction.currentText(), v.Distance.Value))
        return ("%d parts drawn apart %s. The parts themselves stay assembled: hide the view (Space) to see "
                "them." % (len(v.Parts), how))

    # -- the preview -------------------------------------------------------------------------
    def _slid(self, steps):
        if self.busy or self._gone():
            return
        value = self.reach * steps / SLIDER_STEPS
        self.busy = True
        self.distance.setProperty("rawValue", value)
        self.busy = False
        self._apply()

    def _distance_typed(self, *_):
        if self.busy or self._gone():
            return
        self.busy = True
        self.slider.setValue(self._steps(raw(self.distance)))
        self.busy = False
        self._apply()

    def _changed(self, *_):
        if self.busy or self._gone():
            return
        self._apply()

    def _apply(self):
        mode = self.mode.itemData(self.mode.currentIndex())
        self.direction.setEnabled(mode == "Direction")
        try:
            exploded.set_explosion(self.view, undo_step=False, mode=mode, direction=self._direction(),
                                   distance=raw(self.distance), expand_sub_assemblies=self.expand.isChecked(),
                                   lines=self.lines.isChecked())
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

    def _close(self, commit):
        if self.closed or self._gone():
            return
        self.closed = True
        if commit:
            self.transaction.commit()
        else:
            if self.new:
                exploded.show(self.view, False)  # the parts back before the view goes
            self.transaction.abort()
            if not self.new and self.was_shown is not None:
                exploded.show(self.view, self.was_shown)
        self.doc.recompute()
        Gui.Control.closeDialog()


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
