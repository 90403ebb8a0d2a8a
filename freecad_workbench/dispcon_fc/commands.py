"""The workbench's commands: thin shells over dispcon_fc.assembly."""
import math
import os

import FreeCAD as App
import FreeCADGui as Gui

from . import assembly as da

_UI = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "ui")


def active_assembly():
    doc = App.ActiveDocument
    if doc is None:
        return None
    for sel in Gui.Selection.getSelection():
        if hasattr(sel, "Proxy") and isinstance(sel.Proxy, da.AssemblyProxy):
            return sel
        for parent in sel.InList:
            if hasattr(parent, "Proxy") and isinstance(parent.Proxy, da.AssemblyProxy):
                return parent
    for o in doc.Objects:
        if hasattr(o, "Proxy") and isinstance(o.Proxy, da.AssemblyProxy):
            return o
    return None


def report(text, error=False):
    (App.Console.PrintError if error else App.Console.PrintMessage)("dispcon: %s\n" % text)


def highlight(objects, colour=(1.0, 0.0, 0.0)):
    """Colours the parts of the violated joints in the 3D view (cleared by the next solve)."""
    for o in objects:
        for ref in (o.Reference1, o.Reference2):
            vo = ref[0].ViewObject if ref and ref[0] and ref[0].ViewObject else None
            if vo is not None:
                vo.LineColor = colour
                vo.LineWidth = 4.0


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


def _create():
    da.create_assembly(App.ActiveDocument)


def _add_parts():
    asm = active_assembly()
    for o in Gui.Selection.getSelection():
        if hasattr(o, "Shape") and o is not asm and o not in asm.Group:
            da.add_part(asm, o)


def _import():
    from PySide2 import QtWidgets

    path, _ = QtWidgets.QFileDialog.getOpenFileName(None, "Import a part", "", "CAD (*.step *.stp *.iges *.igs *.brep *.brp)")
    if path:
        da.import_part(active_assembly(), path)


def _ground():
    for o in Gui.Selection.getSelection():
        if hasattr(o, "Grounded"):
            o.Grounded = not o.Grounded


def _solve():
    asm = active_assembly()
    for j in da.joints(asm):
        highlight([j], colour=(0.1, 0.1, 0.1))
    r = da.solve(asm)
    report(r.message, error=not r.converged)
    if not r.converged:
        highlight(r.violated)
    return r


class CheckPanel:
    """The check's report (ui/check.ui); the conflicting and redundant joints' parts are
    outlined in the 3D view (red and orange)."""

    def __init__(self, asm):
        c = da.check(asm)
        lines = ["degrees of freedom: %d" % c["dof"]]
        lines += ["  %s: %d" % (name, dof) for name, dof in c["part_dof"].items()]
        for what, joints in (("conflicting", c["conflicting"]), ("redundant", c["redundant"]),
                             ("limits in contact", c["limits_active"])):
            if joints:
                lines.append("%s: %s" % (what, ", ".join(j.Label for j in joints)))
        lines += c["advice"]
        for a, b, v in da.interference(asm):
            lines.append("%s and %s overlap by %.4g" % (a.Label, b.Label, v))
        self.result = c
        self.form = Gui.PySideUic.loadUi(os.path.join(_UI, "check.ui"))
        self.form.summary.setText(c["message"])
        self.form.report.setPlainText("\n".join(lines))
        highlight(c["redundant"], colour=(1.0, 0.6, 0.0))
        highlight(c["conflicting"])
        report(c["message"], error=not c["converged"])

    def accept(self):
        Gui.Control.closeDialog()
        return True

    def reject(self):
        return self.accept()


def _check():
    global last_panel
    last_panel = CheckPanel(active_assembly())
    Gui.Control.showDialog(last_panel)


def joint_command(kind):
    def run():
        sel = Gui.Selection.getSelectionEx()
        refs = [(s.Object, name) for s in sel for name in s.SubElementNames]
        if len(refs) != 2:
            raise ValueError("select two edges, faces or vertices on two parts for a %s joint" % kind)
        j = da.add_joint(active_assembly(), kind, refs[0], refs[1])
        global last_panel
        last_panel = JointPanel(j)
        Gui.Control.showDialog(last_panel)
    return run


last_panel = None  # the joint panel shown last (scripts and tests reach its form through it)


class JointPanel:
    """Edits a joint's type and limits (ui/joint.ui)."""

    def __init__(self, joint):
        self.joint = joint
        self.form = Gui.PySideUic.loadUi(os.path.join(_UI, "joint.ui"))
        f = self.form
        f.jointType.addItems(da.JOINT_TYPES)
        f.jointType.setCurrentText(joint.JointType)
        f.hasRotation.setChecked(joint.HasRotationLimits)
        f.rotationMin.setValue(joint.RotationMin.Value)
        f.rotationMax.setValue(joint.RotationMax.Value)
        f.hasTravel.setChecked(joint.HasTravelLimits)
        f.travelMin.setValue(joint.TravelMin.Value)
        f.travelMax.setValue(joint.TravelMax.Value)
        f.cone.setValue(joint.ConeAngle.Value)

    def accept(self):
        f, j = self.form, self.joint
        doc = j.Document
        doc.openTransaction("Edit joint")
        j.JointType = f.jointType.currentText()
        j.HasRotationLimits = f.hasRotation.isChecked()
        j.RotationMin, j.RotationMax = f.rotationMin.value(), f.rotationMax.value()
        j.HasTravelLimits = f.hasTravel.isChecked()
        j.TravelMin, j.TravelMax = f.travelMin.value(), f.travelMax.value()
        j.ConeAngle = f.cone.value()
        doc.commitTransaction()
        Gui.Control.closeDialog()
        return True

    def reject(self):
        Gui.Control.closeDialog()
        return True


def _drag_mode():
    from . import dragging

    dragging.toggle(active_assembly())


def _drive():
    asm = active_assembly()
    js = [o for o in Gui.Selection.getSelection() if o in da.joints(asm)] or \
         [j for j in da.joints(asm) if j.JointType == "Revolute"]
    if not js:
        raise ValueError("select a revolute joint to drive")
    from PySide2 import QtWidgets

    def frame(_):
        Gui.updateGui()

    reached = da.drive(asm, js[0], [k * 2.0 for k in range(1, 181)], callback=frame)
    report("drove %s by %.1f degrees" % (js[0].Label, reached))
    QtWidgets.QApplication.processEvents()
    return reached


def _export():
    from PySide2 import QtWidgets

    path, _ = QtWidgets.QFileDialog.getSaveFileName(None, "Export .dcl", "", "dispcon (*.dcl)")
    if path:
        da.export_dcl(active_assembly(), path)


def _import_dcl():
    from PySide2 import QtWidgets

    path, _ = QtWidgets.QFileDialog.getOpenFileName(None, "Import .dcl placements", "", "dispcon (*.dcl)")
    if path:
        da.import_dcl(active_assembly(), path)


def register():
    commands = [
        ("Dispcon_CreateAssembly", Command("New assembly", "An empty assembly in the document", _create, False)),
        ("Dispcon_AddParts", Command("Add parts", "Add the selected objects as parts", _add_parts)),
        ("Dispcon_ImportPart", Command("Import part", "Import a STEP, IGES or BREP file as a part", _import)),
        ("Dispcon_Ground", Command("Ground", "Toggle: the selected parts never move", _ground)),
    ]
    for kind in da.JOINT_TYPES:
        commands.append(("Dispcon_Joint" + kind,
                         Command(kind + " joint", "A %s joint from two picked edges, faces or vertices" % kind,
                                 joint_command(kind))))
    commands += [
        ("Dispcon_Solve", Command("Solve", "Snap the parts into place (grounded parts stay)", _solve)),
        ("Dispcon_Drag", Command("Drag", "Toggle drag mode: grab a part with the mouse, the linkage follows", _drag_mode)),
        ("Dispcon_Drive", Command("Drive", "Turn the selected revolute, as an animation", _drive)),
        ("Dispcon_Check", Command("Check", "Degrees of freedom, redundant and conflicting joints, collisions", _check)),
        ("Dispcon_ExportDcl", Command("Export .dcl", "Write the assembly for the dispcon command line", _export)),
        ("Dispcon_ImportDcl", Command("Import .dcl", "Place the parts as a .dcl file says", _import_dcl)),
    ]
    for name, cmd in commands:
        Gui.addCommand(name, cmd)
    return [name for name, _ in commands]
