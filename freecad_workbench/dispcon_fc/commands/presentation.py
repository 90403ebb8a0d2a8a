"""Commands that present an assembly to others: its bill of materials and its exploded view."""
from ..objects import placed_parts
from .common import Command, active_assembly, no_task_dialog


def _bill_of_materials():
    from ..panels.bom import open_panel

    return open_panel(active_assembly())


def _exploded_view():
    """The panel of the selected exploded view, else of the assembly's first one, else a new one."""
    import FreeCADGui as Gui

    from .. import exploded
    from ..panels.exploded import open_panel

    chosen = [o for o in Gui.Selection.getSelection() if exploded.is_exploded_view(o)]
    if chosen:
        return open_panel(chosen[0].Assembly, chosen[0])
    return open_panel(active_assembly())


def _has_parts():
    asm = active_assembly()
    return asm is not None and bool(placed_parts(asm)) and no_task_dialog()


def commands():
    return [
        ("Dispcon_BillOfMaterials", Command(
            "Bill of materials", "Bill of materials: every distinct part with how many the assembly holds, its "
            "part number, description, material and mass where the document knows them (type a part number or "
            "description in the table); OK writes it into a spreadsheet (run again to update it), Export CSV "
            "into a file.", _bill_of_materials, active=_has_parts)),
        ("Dispcon_ExplodedView", Command(
            "Exploded view", "Exploded view: the parts drawn apart in steps applied in order, each moving the "
            "parts it names away from the centre or along a direction, with a live slider; the assembly itself "
            "never moves. Its object in the tree shows it (Space: the assembled parts again).", _exploded_view,
            active=_has_parts)),
    ]
