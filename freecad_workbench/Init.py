# dispcon workbench: registered without the GUI too, so freecadcmd scripts can import dispcon_fc.
import os
import sys

import FreeCAD

_here = os.path.dirname(os.path.abspath(__file__)) if "__file__" in dir() else None
if _here and _here not in sys.path:
    sys.path.append(_here)
