"""One command per joint type: a joint from the two picked references, then its panel."""
import FreeCADGui as Gui

from .. import operations, panels
from ..objects import JOINT_TYPES
from ..panels.joint import JointPanel
from .common import Command, active_assembly


def joint_command(kind):
    def run():
        sel = Gui.Selection.getSelectionEx()
        refs = [(s.Object, name) for s in sel for name in s.SubElementNames]
        if len(refs) != 2:
            raise ValueError("select two edges, faces or vertices on two parts for a %s joint" % kind)
        j = operations.add_joint(active_assembly(), kind, refs[0], refs[1])
        panels.show(JointPanel(j))
    return run


def commands():
    return [("Dispcon_Joint" + kind,
             Command(kind + " joint", "A %s joint from two picked edges, faces or vertices" % kind,
                     joint_command(kind)))
            for kind in JOINT_TYPES]
