"""The workbench's task panels. Their forms are Qt Designer files in ui/ (Resources/ui once installed), loaded when a
panel opens, so the layout can change without touching the code."""
import FreeCADGui as Gui

from ..resources import ui_path

last_panel = None  # the panel shown last (scripts and tests reach its form through it)


def load_ui(name):
    """The form ui/<name> (Resources/ui/<name> once installed)."""
    return Gui.PySideUic.loadUi(ui_path(name))


def show(panel):
    """Opens `panel` in the task view and returns it."""
    global last_panel
    last_panel = panel
    Gui.Control.showDialog(panel)
    return panel
