"""The workbench's task panels. Their forms are Qt Designer files in ui/ (Resources/ui once installed), loaded when a
panel opens, so the layout can change without touching the code."""
import FreeCADGui as Gui

from ..resources import ui_path

last_panel = None  # the panel shown last (scripts and tests reach its form through it)


def load_ui(name):
    """The form ui/<name> (Resources/ui/<name> once installed)."""
    return Gui.PySideUic.loadUi(ui_path(name))


def show(panel):
    """Opens `panel` in the task view and returns it. A panel open already is cancelled first, as
    its Cancel would (FreeCAD shows one task dialog at a time: Check run with the Drive panel
    open said only "Active task dialog found", and showed nothing)."""
    global last_panel
    previous = last_panel
    if previous is not None and previous is not panel and not previous.closed and Gui.Control.activeDialog():
        previous.reject()
    if Gui.Control.activeDialog():
        Gui.Control.closeDialog()
    last_panel = panel
    Gui.Control.showDialog(panel)
    return panel


def current(kind):
    """The panel of class `kind` open now, or None."""
    panel = last_panel
    if isinstance(panel, kind) and not panel.closed and Gui.Control.activeDialog():
        return panel
    return None

