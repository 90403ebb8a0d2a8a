"""The check panel: the report of `operations.check` and of interference (ui/check.ui),
also shown by a Solve that failed, headed by what went wrong."""
import html

import FreeCADGui as Gui

from .. import operations
from ..adapter import plural
from ..feedback import labels, mark, report, status, study_message
from ..commands.motion import export_motion_study, save_path, study_joint
from ..objects import joints as joints_of
from ..qt import QtGui, QtWidgets
from ..resources import icon_path
from . import load_ui
from .base import Watched


class CheckPanel(Watched):
    """The check's report (ui/check.ui), by the joints' and parts' labels; the conflicting joints'
    markers turn red in the 3D view (the next Solve or Check that finds none clears them). It
    closes itself when its assembly is deleted or its document closed (an undo leaves it: a
    report of the moment it was made)."""

    title = "Check panel"
    ends_on_undo = False
    closed = False

    def watched(self):
        return [self.asm]

    def __init__(self, asm, headline=None, result=None):
        c = result if result is not None else operations.check(asm)
        self.result = c
        self.form = load_ui("check.ui")
        # The task box's header shows the form's icon: without one, FreeCAD's own logo.
        self.form.setWindowIcon(QtGui.QIcon(icon_path("Dispcon_Check.svg")))
        self.form.summary.setWordWrap(True)
        self.form.summary.setText(_summary(c))
        fit_to_content(self.form.report)
        self.form.report.setHtml(report_html(c, operations.interference(asm)))
        if headline:
            self.form.summary.setText(headline)
            self.form.summary.setStyleSheet("color: #cc0000; font-weight: bold;")
        self.asm, self.doc = asm, asm.Document
        self.watch()
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
        self.form.report.append("<p>%s</p>" % html.escape(text))
        status(text)

    def getStandardButtons(self):
        # A report, not an edit: one Close button (FreeCAD's own report panels have the same), not
        # an OK and a Cancel that would both only close it.
        return int(QtWidgets.QDialogButtonBox.Close)

    def accept(self):
        self.closed = True
        self.unwatch()
        Gui.Control.closeDialog()
        return True

    def reject(self):
        return self.accept()


# The report box grows with its text up to this many pixels (then it scrolls), and is never
# smaller than a few lines.
REPORT_MAX_HEIGHT = 560
REPORT_MIN_HEIGHT = 80


def fit_to_content(box):
    """Keeps the QTextEdit `box` as tall as its text (wrapped at its width), between
    REPORT_MIN_HEIGHT and REPORT_MAX_HEIGHT pixels; beyond that it scrolls."""
    def fit(*_):
        frame = 2 * box.frameWidth() + box.contentsMargins().top() + box.contentsMargins().bottom()
        height = int(box.document().size().height()) + frame + 2
        box.setFixedHeight(max(REPORT_MIN_HEIGHT, min(REPORT_MAX_HEIGHT, height)))

    box.document().documentLayout().documentSizeChanged.connect(fit)
    return fit


def report_html(c, overlaps):
    """The check's report as rich text: the degrees of freedom with each part's in a monospace
    table, the joints that conflict, repeat or touch a limit by label, the engine's advice as
    paragraphs, and the overlapping parts in a monospace table with their volumes."""
    e = html.escape
    mono = "font-family: monospace;"
    out = ["<p><b>degrees of freedom: %d</b></p>" % c["dof"]]
    if c["part_dof"]:
        rows = "".join('<tr><td style="%s">%s</td><td align="right" style="%s">%d</td></tr>' % (mono, e(name), mono, dof)
                       for name, dof in c["part_dof"].items())
        out.append('<table cellspacing="0" cellpadding="2" style="margin-left: 8px;">'
                   '<tr><th align="left" style="%s">part</th><th align="right" style="%s">DOF</th></tr>%s</table>'
                   % (mono, mono, rows))
    for what, joints in (("conflicting", c["conflicting"]), ("redundant", c["redundant"]),
                         ("limits in contact", c["limits_active"])):
        if joints:
            out.append("<p><b>%s:</b> %s</p>" % (what, e(", ".join(j.Label for j in joints))))
    if c.get("skipped"):  # (the message says them; the panel showed nothing of them)
        out.append("<p><b>left out:</b> %s: a part each holds was deleted, or an edge or face it was picked on "
                   "is gone. Double-click each to pick its references again, or delete it.</p>"
                   % e(", ".join(j.Label for j in c["skipped"])))
    out += ["<p>%s</p>" % e(line) for line in c["advice"]]
    if overlaps:
        rows = "".join('<tr><td style="%s">%s</td><td style="%s">%s</td><td align="right" style="%s">%.4g</td></tr>'
                       % (mono, e(a.Label), mono, e(b.Label), mono, v) for a, b, v in overlaps)
        out.append('<p><b>overlapping parts:</b></p><table cellspacing="0" cellpadding="2" style="margin-left: 8px;">'
                   '<tr><th align="left" style="%s">part</th><th align="left" style="%s">part</th>'
                   '<th align="right" style="%s">volume (mm³)</th></tr>%s</table>' % (mono, mono, mono, rows))
    return "".join(out)


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
