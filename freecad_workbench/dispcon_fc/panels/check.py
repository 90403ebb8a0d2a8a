"""The check panel: the report of `operations.check` and of interference (ui/check.ui),
also shown by a Solve that failed, headed by what went wrong."""
import FreeCADGui as Gui

from .. import operations
from ..adapter import plural
from ..feedback import labels, mark, report, status, study_message
from ..commands.motion import export_motion_study, save_path, study_joint
from ..objects import joints as joints_of
from ..qt import QtWidgets
from . import load_ui


class CheckPanel:
    """The check's report (ui/check.ui), by the joints' and parts' labels; the conflicting joints'
    markers turn red in the 3D view (the next Solve or Check that finds none clears them)."""

    def __init__(self, asm, headline=None, result=None):
        c = result if result is not None else operations.check(asm)
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
        self.form.summary.setWordWrap(True)
        self.form.summary.setText(_summary(c))
        self.form.report.setPlainText("\n".join(lines))
        if headline:
            self.form.summary.setText(headline)
            self.form.summary.setStyleSheet("color: #cc0000; font-weight: bold;")
        self.asm = asm
        # The exports a designer wants next, without another command: the report as JSON, and
        # the motion study (animated SVG, plot, CSV) of the selected joint or the first revolute.
        self.form.exportReport.clicked.connect(lambda *_: self._export_report())
        self.form.motionStudy.clicked.connect(lambda *_: self._motion_study())
        self.form.motionStudy.setEnabled(bool(joints_of(asm)))
        mark(asm, c["conflicting"])
        if headline is None:
            report(c["message"], error=not c["converged"])
            status("Check: %s of freedom%s" % (plural(c["dof"], "degree"), "; conflicting: " + labels(c["conflicting"])
                                                        if c["conflicting"] else ""))

    def _export_report(self):
        path = save_path("Export the check of %s" % self.asm.Label, self.asm.Label + "-check.json", "JSON (*.json)")
        if path:
            self.export_report(path)

    def export_report(self, path):
        """Writes the check as the command line's JSON at `path`; says so in the panel."""
        from .. import studies

        studies.export_check_report(self.asm, path)
        self._said("Written: %s" % path)

    def _motion_study(self):
        try:
            joint = study_joint(self.asm)
            path = save_path("Motion study of %s" % joint.Label, joint.Label + ".svg", "SVG (*.svg)")
            if path:
                study = export_motion_study(self.asm, joint, path)
                self._said("%s; written: %s and its plot and CSV" % (study_message(study), path))
        except ValueError as e:
            self._said(str(e))

    def _said(self, text):
        self.form.report.appendPlainText(text)
        status(text)

    def getStandardButtons(self):
        # A report, not an edit: one Close button (FreeCAD's own report panels have the same), not
        # an OK and a Cancel that would both only close it.
        return int(QtWidgets.QDialogButtonBox.Close)

    def accept(self):
        Gui.Control.closeDialog()
        return True

    def reject(self):
        return self.accept()


def _summary(c):
    """The check's verdict in a person's words (the engine's message names internal objects)."""
    if c["conflicting"]:
        return "Does not assemble: %s conflict%s with the other joints." % (
            labels(c["conflicting"]), "s" if len(c["conflicting"]) == 1 else "")
    if not c["converged"]:
        return "Does not assemble yet: run Solve."
    dof = c["dof"]
    return "Assembles; %d degree%s of freedom left%s." % (
        dof, "" if dof == 1 else "s", "" if not c["redundant"] else
        " (%s repeat%s other joints)" % (labels(c["redundant"]), "s" if len(c["redundant"]) == 1 else ""))
