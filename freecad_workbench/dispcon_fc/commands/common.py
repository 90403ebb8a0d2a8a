"""What every command shares: the Command class (a thin shell over one operation, reporting its
errors instead of raising into the GUI) and how a command finds the assembly it works on."""
import FreeCAD as App
import FreeCADGui as Gui

from ..feedback import report
from ..feedback import status as feedback_status
from ..objects import is_assembly, is_joint, is_sub_assembly, is_top_assembly, nested_parts, picked


def active_assembly():
    doc = App.ActiveDocument
    if doc is None:
        return None
    for sel in Gui.Selection.getSelection():
        sel = picked(sel)[0]  # a Body clicked in the 3D view selects its tip
        if is_assembly(sel):
            return sel
        for parent in sel.InList:
            if is_assembly(parent):
                return parent
    # Nothing of an assembly selected: the first not placed in another, then any (the leg placed
    # in a walker, made first, is not what a designer means by the document's assembly).
    # Asked by every command's IsActive whenever FreeCAD updates its toolbars (53 times as a joint
    # panel closes on the 100-part chain): one pass that stops at the first top assembly.
    first = None
    for o in doc.Objects:
        if is_top_assembly(o, doc):
            return o
        if first is None and is_assembly(o):
            first = o
    return first


class Command:
    """A command: its menu text, its tooltip (what to select), what it runs, and when it can run.

    `active` says whether it can run now (FreeCAD greys it out otherwise); by default, when a
    document is open and, if `needs_assembly`, it has an assembly. The icon is
    Resources/icons/<command name>.svg, set by register(). A `checkable` command (drag mode) gets
    its new state as run's argument."""

    def __init__(self, text, tip, run, needs_assembly=True, active=None, checkable=False):
        self.text, self.tip, self.run, self.needs = text, tip, run, needs_assembly
        self.active, self.checkable = active, checkable
        self.pixmap = ""

    def GetResources(self):
        res = {"MenuText": self.text, "ToolTip": self.tip, "Pixmap": self.pixmap}
        if self.checkable:
            res["Checkable"] = False
        return res

    def IsActive(self):
        doc = App.ActiveDocument
        # (FreeCAD asks while it restores a document, from the restore's progress bar: 212 times,
        # each looking through every object for an assembly and its parts, for the 100-part chain)
        if doc is None or doc.Restoring:
            return False
        try:
            if self.active is not None:
                return bool(self.active())
            return not self.needs or active_assembly() is not None
        except Exception:  # a document half-way through a change: not now
            return False

    def Activated(self, *checked):
        try:
            self.run(*checked)
        except Exception as e:  # a command reports, never crashes the GUI
            report(str(e), error=True)
            status(str(e))


def status(text, msecs=8000):
    """A message in the main window's status bar, for 8 s."""
    feedback_status(text, msecs)


# When commands can run (FreeCAD asks often: these stay cheap).

def has_parts(n=1):
    """Whether the assembly has `n` parts, counting those of its sub-assemblies (a joint may
    hold a leg's hip to the frame). Counted until there are `n`: FreeCAD asks each command after
    every event, and counting a hundred parts for each took seconds of a document's opening."""
    asm = active_assembly()
    if asm is None:
        return False
    count = 0
    for o in asm.Group:
        if is_sub_assembly(o):
            count += len(nested_parts(o))
        elif not is_joint(o) and (hasattr(o, "Shape") or o.TypeId == "App::Link"):  # objects.parts'
            count += 1
        if count >= n:
            return True
    return False


def has_joints():
    """Whether the assembly has a joint to solve: its own, or a sub-assembly's. Looked for from
    the end of its group, where joints are added after their parts."""
    asm = active_assembly()
    return asm is not None and any(is_joint(o) or is_sub_assembly(o) for o in reversed(asm.Group))


def no_task_dialog():
    return not Gui.Control.activeDialog()
