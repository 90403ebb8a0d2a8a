"""The script `dispcon` runs in freecadcmd for .FCStd files (dispcon_fc/headless.py). freecadcmd
takes every argument for a file to open, so the request comes in the environment:
DISPCON_FC_REQUEST names a JSON file, DISPCON_FC_WORKBENCH the folder holding dispcon_fc."""
import os
import sys

sys.path.insert(0, os.environ.get("DISPCON_FC_WORKBENCH") or os.path.dirname(os.path.abspath(sys.argv[-1])))

from dispcon_fc import headless  # noqa: E402

headless.main()
# Leave at once: the answer is written, and FreeCAD's shutdown has nothing to add.
os._exit(0)
