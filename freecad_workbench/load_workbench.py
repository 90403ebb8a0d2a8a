"""A macro that loads the Dispcon workbench from this folder and activates it, for a FreeCAD
whose Mod folder does not hold it (scripts/freecad passes it on FreeCAD's command line)."""
import os
import sys

import FreeCADGui as Gui

_here = os.path.dirname(os.path.abspath(__file__))
if _here not in sys.path:
    sys.path.insert(0, _here)
if "DispconWorkbench" not in Gui.listWorkbenches():
    exec(open(os.path.join(_here, "InitGui.py")).read())
Gui.activateWorkbench("DispconWorkbench")
