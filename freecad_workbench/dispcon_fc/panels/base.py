"""What the task panels that hold one transaction share: the message line, the OK button, the
dialog's buttons, Cancel, and knowing when their document or form is gone; and what every panel
shares: closing itself when what it edits goes from under it."""
import FreeCAD as App
import FreeCADGui as Gui

from ..objects import picked
from ..qt import QtCore, QtWidgets, is_alive


def exists(obj):
    """Whether `obj` is still an object of its document (not deleted, nor taken away by an undo;
    its document not closed)."""
    try:
        return obj.Document.getObject(obj.Name) is obj
    except (ReferenceError, RuntimeError):
        return False


def full_pick(doc_name, name, sub):
    """The part and element of the pick a selection observer was just told of as (name, sub):
    FreeCAD names the object it resolved, a PartDesign Body's tip feature for a click on the
    Body, or on a sub-assembly's link to one (the link is then lost); the path from the object
    the 3D view draws keeps the Body or the link (objects.picked)."""
    doc = App.getDocument(doc_name)
    for chosen in reversed(Gui.Selection.getSelectionEx(doc_name, 0)):
        for path in reversed(chosen.SubElementNames):
            if (path == sub and chosen.Object.Name == name) or path.endswith(name + "." + sub):
                return picked(chosen.Object, path)
    obj = doc.getObject(name)
    return picked(obj, sub) if obj is not None else (None, sub)


class _Watch:
    """A document observer that tells its panel when the panel's document closes, an undo or a
    redo changes it, or one of the objects the panel edits (panel.watched()) is deleted. It says
    so from a timer: FreeCAD is still in the middle of that change when it calls."""

    def __init__(self, panel):
        self.panel = panel

    def _tell(self, why):
        panel = self.panel
        if not getattr(panel, "changing", False):
            QtCore.QTimer.singleShot(0, lambda: panel._went_away(why))

    def _ours(self, doc):
        try:
            return doc is self.panel.doc or doc.Name == self.panel.doc.Name
        except (ReferenceError, RuntimeError):
            return True  # its document gone meanwhile

    def slotDeletedDocument(self, doc):
        if self._ours(doc):
            self._tell("its document was closed")

    def slotUndoDocument(self, doc):
        if self.panel.ends_on_undo and self._ours(doc):
            self._tell("an undo changed its document")

    def slotRedoDocument(self, doc):
        if self.panel.ends_on_undo and self._ours(doc):
            self._tell("a redo changed its document")

    def slotDeletedObject(self, obj):
        try:
            mine = any(obj is o for o in self.panel.watched())
            label = obj.Label
            if getattr(obj.Document, "Transacting", False):
                return  # an undo or a redo taking it away: that one says so
        except (ReferenceError, RuntimeError):
            return
        if mine:
            self._tell("%s was deleted" % label)


class Watched:
    """A panel (`self.doc`, `self.closed`, `self.form`) that closes itself, once, when its
    document closes, an undo or a redo changes it, or an object it edits is deleted: it then
    lets go of what it holds, takes back what it did where its transaction is still open (as
    Cancel), and says in the status bar and the Report view why it closed. Its Cancel, its OK
    and anything later find it closed and do nothing (no deleted object read, no traceback)."""

    title = "panel"
    ends_on_undo = True  # (a report of a moment, as the Check's, stays)
    changing = False  # the panel itself is deleting or replacing an object it edits

    def watch(self):
        self._watch = _Watch(self)
        App.addDocumentObserver(self._watch)

    def unwatch(self):
        watch = getattr(self, "_watch", None)
        if watch is not None:
            self._watch = None
            App.removeDocumentObserver(watch)

    def watched(self):
        """The objects whose deletion ends the panel."""
        return []

    def _went_away(self, why):
        if getattr(self, "_watch", None) is None:
            return  # closed by its OK or Cancel meanwhile, or ended already
        self.closed = True
        self.unwatch()
        try:
            self._forget()
        except (ReferenceError, RuntimeError):
            pass
        from . import last_panel

        if last_panel is not self or not Gui.Control.activeDialog():
            return  # its dialog closed already (by another panel opening): nothing to say
        transaction = getattr(self, "transaction", None)
        try:
            alive = bool(self.doc.Name)
        except (ReferenceError, RuntimeError):
            alive = False
        text = "The %s closed: %s." % (self.title, why)
        if alive and transaction is not None and self.doc.HasPendingTransaction:
            # Its transaction still open (a script deleted the object inside it): everything
            # since the panel opened is taken back, as Cancel does, that deletion too.
            self._take_back()
            text += " Everything since it opened is taken back, as Cancel does."
        from .. import feedback

        feedback.report(text)
        feedback.status(text, 8000)
        Gui.Control.closeDialog()

    def _take_back(self):
        self.transaction.abort()

    def _forget(self):
        """Lets go of what the panel holds outside itself (nothing here)."""


class TransactionPanel(Watched):
    """A task panel with a form (`self.form`), a message label (`self.message`), its document
    (`self.doc`) and the transaction it holds open (`self.transaction`). A subclass writes
    `_close(commit)`, and `_forget()` if it holds something to let go of when its document goes."""

    closed = False

    def _say(self, text, error=False):
        self.message.setText(text)
        self.message.setStyleSheet("color: #cc0000;" if error else "")

    # The dialog's buttons, as FreeCAD hands them to the panel when it shows it
    # (modifyStandardButtons). They were found by walking up from the form and searching each
    # ancestor's children: PySide wraps every widget such a search meets, and when the wrapper of
    # the ancestor searched went, the wrappers of the form's Gui::QuantitySpinBoxes (made by
    # FreeCAD's UiLoader) were invalidated with it, the widgets themselves alive: the joint panel's
    # next read of a box ("Internal C++ object (QAbstractSpinBox) already deleted") raised, at its
    # OK or at a value changed, whenever that search had run after the dialog was shown.
    _buttons = None

    def modifyStandardButtons(self, box):
        self._buttons = box
        button = self.ok_button()
        if button is not None and hasattr(self, "ok_enabled"):
            button.setEnabled(self.ok_enabled)  # (a panel that opens refusing OK: a joint still to pick)

    def ok_button(self):
        """The dialog's OK button, or None before the panel is shown or once its dialog is gone."""
        box = self._buttons
        if not is_alive(box):
            return None
        button = box.button(QtWidgets.QDialogButtonBox.Ok)
        return button if is_alive(button) else None

    def _set_ok(self, enabled):
        self.ok_enabled = enabled  # (taken by the buttons when FreeCAD gives them: modifyStandardButtons)
        button = self.ok_button()
        if button is not None:
            button.setEnabled(enabled)

    def _gone(self):
        """True, and the panel lets go of what it holds, once its document or its form is gone
        (FreeCAD closes a task dialog without asking it when the document closes)."""
        try:
            self.doc.Name
            if is_alive(self.form):
                return False
        except ReferenceError:
            pass
        self.closed = True
        self.unwatch()
        self._forget()
        return True

    # -- the task dialog ----------------------------------------------------------------------
    def getStandardButtons(self):
        return int(QtWidgets.QDialogButtonBox.Ok | QtWidgets.QDialogButtonBox.Cancel)

    def reject(self):
        self._close(commit=False)
        return True
