"""Commands that look at an assembly or take it elsewhere: Check, Export and Import .dcl."""
from .. import operations, panels
from ..panels.check import CheckPanel
from .common import Command, active_assembly, has_joints, has_parts


def _check():
    panels.show(CheckPanel(active_assembly()))


def _export():
    from ..qt import QtWidgets

    path, _ = QtWidgets.QFileDialog.getSaveFileName(None, "Export .dcl", "", "dispcon (*.dcl)")
    if path:
        operations.export_dcl(active_assembly(), path)


def _import_dcl():
    from ..qt import QtWidgets

    path, _ = QtWidgets.QFileDialog.getOpenFileName(None, "Import .dcl placements", "", "dispcon (*.dcl)")
    if path:
        operations.import_dcl(active_assembly(), path)


def commands():
    return [
        ("Dispcon_Check", Command("Check", "Check: degrees of freedom, redundant and conflicting joints (marked red "
                                  "in the 3D view) and parts that overlap.", _check, active=has_joints)),
        ("Dispcon_ExportDcl", Command("Export .dcl", "Export .dcl: write the assembly as a .dcl file for the dispcon "
                                      "command line.", _export, active=lambda: has_parts(1))),
        ("Dispcon_ImportDcl", Command("Import .dcl", "Import .dcl: place the parts as a .dcl file says (one the "
                                      "command line solved).", _import_dcl, active=lambda: has_parts(1))),
    ]
