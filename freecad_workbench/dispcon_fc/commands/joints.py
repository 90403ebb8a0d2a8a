"""One command per joint type: its panel, with the references already selected or picked in it."""
import FreeCADGui as Gui

from .. import engine
from ..adapter import offered_types
from ..panels.joint import open_panel
from ..guide import tooltip
from ..objects import picked
from .common import Command, active_assembly, has_parts


def joint_command(kind):
    def run():
        # The references selected already (up to two); the panel asks for the rest.
        # With their paths from what the view draws: a Body's, or a link's to one, not its tip's.
        sel = Gui.Selection.getSelectionEx("", 0)
        refs = [picked(s.Object, name) for s in sel for name in s.SubElementNames][:2]
        open_panel(asm=active_assembly(), joint_type=kind, refs=refs)
    return run


def commands():
    return [("Dispcon_Joint" + kind,
             Command(kind + " joint", tooltip(kind), joint_command(kind), active=lambda: has_parts(2)))
            for kind in offered_types(engine.load())]
