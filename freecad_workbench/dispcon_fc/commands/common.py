"""What every command shares: the Command class (a thin shell over one operation, reporting its
errors instead of raising into the GUI) and how a command finds the assembly it works on."""
import FreeCAD as App
import FreeCADGui as Gui

from ..feedback import report
from ..objects import is_assembly


def active_assembly():
    doc = App.ActiveDocument
    if doc is None:
        return None
    for sel in Gui.Selection.getSelection():
        if is_assembly(sel):
            return sel
        for parent in sel.InList:
            if is_assembly(parent):
                return parent
    for o in doc.Objects:
        if is_assembly(o):
            return o
    return None


class Command:
    def __init__(self, text, tip, run, needs_assembly=True):
        self.text, self.tip, self.run, self.needs = text, tip, run, needs_assembly

    def GetResources(self):
        return {"MenuText": self.text, "ToolTip": self.tip}

    def IsActive(self):
        return App.ActiveDocument is not None and (not self.needs or active_assembly() is not None)

    def Activated(self):
        try:
            self.run()
        except Exception as e:  # a command reports, never crashes the GUI
            report(str(e), error=True)
