# dispcon workbench, started with FreeCAD with or without the GUI: puts dispcon_fc on the path, and
# gives assemblies and joints whose Python proxy a restore lost (a document saved where the
# workbench was missing) their proxy back, recognised by their stored properties.
import os
import sys

import FreeCAD

_here = os.path.dirname(os.path.abspath(__file__)) if "__file__" in dir() else None
if _here and _here not in sys.path:
    sys.path.append(_here)


class _DispconRestoreObserver:
    # FreeCAD 0.20's App has no "restore finished" signal; a document opened is made the active
    # one once its objects are read, so activation is where the proxies are given back.
    # (FreeCAD runs this file inside a function: methods import what they use.)
    def slotActivateDocument(self, doc):
        if any("DispconType" in o.PropertiesList or "JointType" in o.PropertiesList for o in doc.Objects):
            from dispcon_fc import objects

            # (Only a document saved where the workbench was missing gets anything here, which
            # FreeCAD counts as a modification: it is one. A document saved by freecadcmd has
            # its proxies; their onDocumentRestored gives the views theirs, unmodified.)
            objects.adopt_document(doc)


FreeCAD.addDocumentObserver(_DispconRestoreObserver())
