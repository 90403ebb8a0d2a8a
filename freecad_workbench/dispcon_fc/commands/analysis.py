"""Commands that look at an assembly or take it elsewhere: Check, Export and Import .dcl."""
from .. import operations, panels
from ..panels.check import CheckPanel
from .common import Command, active_assembly


def _check():
    panels.show(CheckPanel(active_assembly()))


def _export():
    from PySide2 import QtWidgets

    path, _ = QtWidgets.QFileDialog.getSaveFileName(None, "Export .dcl", "", "dispcon (*.dcl)")
    if path:
        operations.export_dcl(active_assembly(), path)


def _import_dcl():
    from PySide2 import QtWidgets

    path, _ = QtWidgets.QFileDialog.getOpenFileName(None, "Import .dcl placements", "", "dispcon (*.dcl)")
    if path:
        operations.import_dcl(active_assembly(), path)


def commands():
    return [
        ("Dispcon_Check", Command("Check", "Degrees of freedom, redundant and conflicting joints, collisions", _check)),
        ("Dispcon_ExportDcl", Command("Export .dcl", "Write the assembly for the dispcon command line", _export)),
        ("Dispcon_ImportDcl", Command("Import .dcl", "Place the parts as a .dcl file says", _import_dcl)),
    ]
