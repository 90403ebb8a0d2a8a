"""What the GUI tells the user about a command's outcome: a message in the Report view and the
status bar, and the joints to look at marked in the 3D view (their markers turn red). The marks
are state of the view, never of the document: nothing a command shows is saved into the file."""
import math

import FreeCAD as App


def report(text, error=False):
    (App.Console.PrintError if error else App.Console.PrintMessage)("dispcon: %s\n" % text)


def status(text, msecs=0):
    """The text in the main window's status bar (until the next message when msecs is 0).

    FreeCAD echoes a Report view message in the status bar by an event it posts, which would
    overwrite this text when it is processed (unless an earlier error's is still shown: so it did
    or did not, by the clock). The text is shown now and once more when the events already
    posted have been processed, so what the command says last is what stays."""
    if App.GuiUp:
        import FreeCADGui as Gui
        from .qt import QtCore, is_alive

        bar = Gui.getMainWindow().statusBar()
        bar.showMessage(text, msecs)
        QtCore.QTimer.singleShot(0, lambda: is_alive(bar) and bar.showMessage(text, msecs))


def mark(asm, culprits):
    """Marks the joints in `culprits` red in the 3D view and clears the mark of every other joint
    of the assembly."""
    if not App.GuiUp:
        return
    from .objects import joints
    from .viewproviders import joint_view

    names = {j.Name for j in culprits}
    for j in joints(asm):
        view = joint_view(j)
        if view is not None:
            view.set_error(j.Name in names)


def labels(joints):
    return ", ".join("'%s'" % j.Label for j in joints)


def solve_outcome(asm, result):
    """After a Solve: on success, clears the marks and says so; on failure, finds the joint to fix
    as Check does (the conflicting one, else those still violated), marks it, and says so in the
    status bar and in a task panel. Returns the panel shown, or None."""
    if result.converged:
        mark(asm, [])
        status("%s: %s" % (asm.Label, result.message), 8000)
        report("%s: %s" % (asm.Label, result.message))
        return None
    from . import operations, panels
    from .panels.check import CheckPanel

    c = operations.check(asm)
    culprits = c["conflicting"] or result.violated
    what = "conflicts with the other joints" if c["conflicting"] else "cannot hold"
    if len(culprits) > 1:
        what = what.replace("conflicts", "conflict")
    text = "Solve failed: %s %s; nothing moved. Fix or delete %s." % (
        labels(culprits), what, "it" if len(culprits) == 1 else "them")
    report(text, error=True)
    status(text)
    panel = panels.show(CheckPanel(asm, headline=text, result=c))
    mark(asm, culprits)
    return panel


def swept_value(study, value):
    """A value of a swept joint as the Drive panel writes it: a turn in degrees to the hundredth
    ("46.73°", from the study's radians), a travel in mm to the ten-thousandth ("0.25 mm")."""
    if study.kind == "angle":
        return "%g°" % round(math.degrees(value), 2)
    return "%g mm" % round(value, 4)


def study_message(study):
    """A motion study's outcome in the workbench's words: angles in degrees with their unit and
    counts in words ("1 pair of parts collides", "5 pairs of parts collide"). The study's own
    .message is the command line's (`dispcon sweep`, in radians), so it is not reworded but
    composed again from what the study found."""
    from .adapter import plural

    label = "'%s'" % study.joint.Label
    if study.start is None:  # it did not assemble: nothing was swept
        return study.message
    if study.locked and not study.samples:
        text = "%s cannot reach the start %s: it locks at %s" % (
            label, swept_value(study, study.start), swept_value(study, study.lock_value))
    elif study.locked:
        text = "%s locks at %s: it cannot %s past it" % (
            label, swept_value(study, study.lock_value), "turn" if study.kind == "angle" else "slide")
    else:
        text = "%s moves freely from %s to %s" % (label, swept_value(study, study.start),
                                                  swept_value(study, study.stop))
    hits = study.interference() if study.clearance else []
    if hits:
        text += "; %s of parts %s: %s" % (plural(len(hits), "pair"), "collides" if len(hits) == 1 else "collide",
                                          ", ".join("'%s' and '%s' from %s to %s" % (
                                              h["parts"][0], h["parts"][1], swept_value(study, h["first"]),
                                              swept_value(study, h["last"])) for h in hits))
    return text
