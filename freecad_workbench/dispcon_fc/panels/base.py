"""What the task panels that hold one transaction share: the message line, the OK button, the
dialog's buttons, Cancel, and knowing when their document or form is gone."""
from . import ok_button
from ..qt import QtCore, QtWidgets, is_alive


class TransactionPanel:
    """A task panel with a form (`self.form`), a message label (`self.message`), its document
    (`self.doc`) and the transaction it holds open (`self.transaction`). A subclass writes
    `_close(commit)`, and `_forget()` if it holds something to let go of when its document goes."""

    closed = False

    def _say(self, text, error=False):
        self.message.setText(text)
        self.message.setStyleSheet("color: #cc0000;" if error else "")

    def ok_button(self):
        return ok_button(self.form)

    def _set_ok(self, enabled, tries=5):
        self.ok_enabled = enabled
        button = self.ok_button()
        if button is not None:
            button.setEnabled(enabled)
        elif tries > 0 and not self.closed:
            # The task view shows its buttons only once the event loop has run after
            # showDialog: a panel that opens refusing OK (a joint still to pick) says so then,
            # or the OK of a joint not made yet stayed enabled.
            QtCore.QTimer.singleShot(0, lambda: self._gone() or self._set_ok(self.ok_enabled, tries - 1))

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
        self._forget()
        return True

    def _forget(self):
        """Lets go of what the panel holds outside itself (nothing here)."""

    # -- the task dialog ----------------------------------------------------------------------
    def getStandardButtons(self):
        return int(QtWidgets.QDialogButtonBox.Ok | QtWidgets.QDialogButtonBox.Cancel)

    def reject(self):
        self._close(commit=False)
        return True
