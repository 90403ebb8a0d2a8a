"""What the GUI tells the user about a command's outcome: messages in the Report view, and parts
outlined in the 3D view."""
import FreeCAD as App


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
