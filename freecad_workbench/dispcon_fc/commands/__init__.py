"""The workbench's commands, one module per group (build, joints, motion, analysis): thin
shells over dispcon_fc.operations. `register()` adds them to FreeCAD and returns them by group,
which the workbench makes its toolbars and its menu of.

The toolbars hold the commands a designer reaches for most as buttons of their own and the
others in drop-down buttons (DROP_DOWNS), as FreeCAD 1.x's Assembly groups its Gears and Belt
joints: the five toolbars filled a 1280-pixel row to the last pixel with one button per
command. The menu keeps every command as an entry of its own."""
import FreeCADGui as Gui

from .. import panels
from ..resources import icon_path
from . import analysis, build, joints, motion, presentation
from .common import Command, active_assembly  # noqa: F401
from .motion import _drive, _solve  # noqa: F401  (scripts and tests run them directly)

# (title, module): one toolbar each, and one section of the menu (the joints in a submenu).
GROUPS = (("Assembly", build), ("Joints", joints), ("Motion", motion), ("Analysis", analysis),
          ("Presentation", presentation))


# Drop-down buttons of the toolbars: (its command name, its text, its tooltip, the commands it
# holds). The button shows the command last run from it (the first at the start); its arrow
# lists them all, each with its icon and tooltip.
DROP_DOWNS = {
    "Assembly": (("Dispcon_InsertGroup", "Insert",
                  "Insert a part or a sub-assembly: a STEP, IGES or BREP file, a part of a saved "
                  "FreeCAD document, or an assembly placed in this one (the arrow lists them)",
                  ("Dispcon_ImportPart", "Dispcon_InsertLink", "Dispcon_InsertSubAssembly")),),
    "Joints": (("Dispcon_JointPointOnGroup", "Point on line, plane or curve",
                "A point of part 2 held on a line, a plane or a curve of part 1 (the arrow lists them)",
                ("Dispcon_JointPointOnLine", "Dispcon_JointPointOnPlane", "Dispcon_JointPointOnCurve")),
               ("Dispcon_JointRelationGroup", "Distance, parallel, perpendicular, angle",
                "Two parts held at a distance or an angle, or kept parallel or perpendicular (the arrow "
                "lists them)",
                ("Dispcon_JointDistance", "Dispcon_JointParallel", "Dispcon_JointPerpendicular",
                 "Dispcon_JointAngle")),
               ("Dispcon_JointCouplingGroup", "Couplings: gears, belt, rack and pinion, screw",
                "Two parts whose motions are tied: gears, a belt, a rack and pinion, a screw (the arrow "
                "lists them)",
                ("Dispcon_JointGears", "Dispcon_JointBelt", "Dispcon_JointRackPinion", "Dispcon_JointScrew"))),
    "Analysis": (("Dispcon_DclGroup", "Export or import .dcl",
                  "The assembly to the dispcon command line (.dcl) and back (the arrow lists them)",
                  ("Dispcon_ExportDcl", "Dispcon_ImportDcl")),),
}


class CommandGroup:
    """A drop-down button of a toolbar holding `members` (registered commands, by name), as
    FreeCAD's own command groups are (GetCommands): active when one of them is."""

    def __init__(self, text, tip, members, commands, pixmap):
        self.text, self.tip, self.members, self.commands, self.pixmap = text, tip, members, commands, pixmap

    def GetCommands(self):
        return tuple(self.members)

    def GetDefaultCommand(self):
        return 0

    def GetResources(self):
        return {"MenuText": self.text, "ToolTip": self.tip, "Pixmap": self.pixmap, "DropDownMenu": True,
                "Exclusive": False}

    def IsActive(self):
        return any(c.IsActive() for c in self.commands)


def __getattr__(name):
    # `commands.last_panel`: the panel a command opened last, kept by the panels package.
    if name == "last_panel":
        return panels.last_panel
    raise AttributeError(name)


def register():
    """Adds every command to FreeCAD, and the toolbars' drop-down buttons; returns [(group title,
    [command names], [the toolbar's command names, a drop-down's name in place of its
    commands])]."""
    groups = []
    for title, group in GROUPS:
        names, made = [], {}
        for name, cmd in group.commands():
            cmd.pixmap = icon_path(name + ".svg")
            Gui.addCommand(name, cmd)
            names.append(name)
            made[name] = cmd
        groups.append((title, names, toolbar(title, names, made)))
    return groups


def toolbar(title, names, made=None):
    """The toolbar of group `title` holding `names`: each drop-down of DROP_DOWNS (registered
    here when `made`, the commands by name, is given) where its first command was; a drop-down
    of one command that exists is that command's own button."""
    out = list(names)
    for group_name, text, tip, members in DROP_DOWNS.get(title, ()):
        present = [n for n in members if n in names]
        if len(present) < 2:
            continue
        if made is not None:
            Gui.addCommand(group_name, CommandGroup(text, tip, present, [made[n] for n in present],
                                                    icon_path(present[0] + ".svg")))
        at = out.index(present[0])
        out = [n for n in out if n not in present]
        out.insert(at, group_name)
    return out
