"""The workbench's commands, one module per group (build, joints, motion, analysis): thin
shells over dispcon_fc.operations. `register()` adds them to FreeCAD and returns their names."""
import FreeCADGui as Gui

from .. import panels
from . import analysis, build, joints, motion
from .common import Command, active_assembly  # noqa: F401
from .motion import _drive, _solve  # noqa: F401  (scripts and tests run them directly)

GROUPS = (build, joints, motion, analysis)


def __getattr__(name):
    # `commands.last_panel`: the panel a command opened last, kept by the panels package.
    if name == "last_panel":
        return panels.last_panel
    raise AttributeError(name)


def register():
    names = []
    for group in GROUPS:
        for name, cmd in group.commands():
            Gui.addCommand(name, cmd)
            names.append(name)
    return names
