"""The check panel: the report of `operations.check` and of interference (Resources/ui/check.ui)."""
import FreeCADGui as Gui

from .. import operations
from ..feedback import highlight, report
from . import load_ui


class CheckPanel:
    """The check's report (ui/check.ui); the conflicting and redundant joints' parts are
    outlined in the 3D view (red and orange)."""

    def __init__(self, asm):
        c = operations.check(asm)
        lines = ["degrees of freedom: %d" % c["dof"]]
        lines += ["  %s: %d" % (name, dof) for name, dof in c["part_dof"].items()]
        for what, joints in (("conflicting", c["conflicting"]), ("redundant", c["redundant"]),
                             ("limits in contact", c["limits_active"])):
            if joints:
                lines.append("%s: %s" % (what, ", ".join(j.Label for j in joints)))
        lines += c["advice"]
        for a, b, v in operations.interference(asm):
            lines.append("%s and %s overlap by %.4g" % (a.Label, b.Label, v))
        self.result = c
        self.form = load_ui("check.ui")
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
