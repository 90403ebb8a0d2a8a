"""A macro that activates the Dispcon workbench (scripts/freecad passes it on FreeCAD's command
line). Without an installed workbench (scripts/install-freecad) it loads the one beside it."""
import os
import sys

import FreeCADGui as Gui

if "DispconWorkbench" not in Gui.listWorkbenches():
    _here = os.path.dirname(os.path.abspath(__file__))
    if _here not in sys.path:
        sys.path.insert(0, _here)
    exec(open(os.path.join(_here, "InitGui.py")).read())
Gui.activateWorkbench("DispconWorkbench")
