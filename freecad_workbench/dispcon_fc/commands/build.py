"""Commands that build an assembly: new assembly, add parts, import a part, ground."""
import FreeCAD as App
import FreeCADGui as Gui

from .. import operations
from .common import Command, active_assembly


def _create():
    operations.create_assembly(App.ActiveDocument)


def _add_parts():
    asm = active_assembly()
    for o in Gui.Selection.getSelection():
        if hasattr(o, "Shape") and o is not asm and o not in asm.Group:
            operations.add_part(asm, o)


def _import():
    from PySide2 import QtWidgets

    path, _ = QtWidgets.QFileDialog.getOpenFileName(None, "Import a part", "", "CAD (*.step *.stp *.iges *.igs *.brep *.brp)")
    if path:
        operations.import_part(active_assembly(), path)


def _ground():
    for o in Gui.Selection.getSelection():
        if hasattr(o, "Grounded"):
            o.Grounded = not o.Grounded


def commands():
    return [
        ("Dispcon_CreateAssembly", Command("New assembly", "An empty assembly in the document", _create, False)),
        ("Dispcon_AddParts", Command("Add parts", "Add the selected objects as parts", _add_parts)),
        ("Dispcon_ImportPart", Command("Import part", "Import a STEP, IGES or BREP file as a part", _import)),
        ("Dispcon_Ground", Command("Ground", "Toggle: the selected parts never move", _ground)),
    ]
