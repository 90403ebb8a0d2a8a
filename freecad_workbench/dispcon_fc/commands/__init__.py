"""The workbench's commands, one module per group (build, joints, motion, analysis): thin
shells over dispcon_fc.operations. `register()` adds them to FreeCAD and returns them by group,
which the workbench makes its toolbars and its menu of."""
import FreeCADGui as Gui

from .. import panels
from ..resources import icon_path
from . import analysis, build, joints, motion, presentation
from .common import Command, active_assembly  # noqa: F401
from .motion import _drive, _solve  # noqa: F401  (scripts and tests run them directly)

# (title, module): one toolbar each, and one section of the menu (the joints in a submenu).
GROUPS = (("Assembly", build), ("Joints", joints), ("Motion", motion), ("Analysis", analysis),
          ("Presentation", presentation))


def __getattr__(name):
    # `commands.last_panel`: the panel a command opened last, kept by the panels package.
    if name == "last_panel":
        return panels.last_panel
    raise AttributeError(name)


def register():
    """Adds every command to FreeCAD; returns [(group title, [command names])]."""
    groups = []
    for title, group in GROUPS:
        names = []
        for name, cmd in group.commands():
            cmd.pixmap = icon_path(name + ".svg")
            Gui.addCommand(name, cmd)
            names.append(name)
        groups.append((title, names))
    return groups
