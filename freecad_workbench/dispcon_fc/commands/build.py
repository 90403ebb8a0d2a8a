"""Commands that build an assembly: new assembly, add parts, import a part, ground."""
import FreeCAD as App
import FreeCADGui as Gui

from .. import operations
from ..objects import picked
from .common import Command, active_assembly


def _create():
    operations.create_assembly(App.ActiveDocument)


def _add_parts():
    asm = active_assembly()
    for o in _selected_solids():
        if o is not asm and o not in asm.Group:
            operations.add_part(asm, o)


def _selected_solids():
    """The objects selected that can be parts, a PartDesign Body's for its tip (a click on the
    body in the 3D view selects its tip feature), each once."""
    out = []
    for o in Gui.Selection.getSelection():
        o = picked(o)[0]
        if hasattr(o, "Shape") and o not in out:
            out.append(o)
    return out


def _import():
    from ..qt import QtWidgets

    path, _ = QtWidgets.QFileDialog.getOpenFileName(None, "Import a part", "", "CAD (*.step *.stp *.iges *.igs *.brep *.brp)")
    if path:
        operations.import_part(active_assembly(), path)


def _insert_link():
    """A part from another .FCStd file, linked (App::Link): the file's solid, or the one chosen."""
    from ..qt import QtWidgets

    asm = active_assembly()
    path, _ = QtWidgets.QFileDialog.getOpenFileName(None, "Insert a part from a FreeCAD file", "", "FreeCAD (*.FCStd)")
    if not path:
        return
    choices = operations.linkable_objects(path)
    if not choices:
        raise ValueError("%s has no solid to insert" % path)
    name = choices[0].Name
    if len(choices) > 1:
        labels = [o.Label for o in choices]
        label, ok = QtWidgets.QInputDialog.getItem(None, "Insert a part", "Part of %s:" % path, labels, 0, False)
        if not ok:
            return
        name = choices[labels.index(label)].Name
    operations.link_part(asm, path, name)


def _insert_sub_assembly():
    """An assembly placed in the active one: the second assembly selected (of this document), or
    one of a saved .FCStd file chosen in a dialog (linked, as FreeCAD 1.x's Insert component)."""
    from ..qt import QtWidgets

    from .. import subassembly
    from ..objects import is_assembly, top_assemblies

    asm = active_assembly()
    chosen = [o for o in Gui.Selection.getSelection() if is_assembly(o) and o is not asm]
    if chosen:
        subassembly.insert_sub_assembly(asm, chosen[0])
        return
    path, _ = QtWidgets.QFileDialog.getOpenFileName(None, "Insert a sub-assembly", "", "FreeCAD (*.FCStd)")
    if not path:
        return
    name = operations._doc_name(path)
    doc = App.getDocument(name) if name else App.openDocument(path)
    found = top_assemblies(doc)
    label = None
    if len(found) > 1:
        labels = [o.Label for o in found]
        label, ok = QtWidgets.QInputDialog.getItem(None, "Insert a sub-assembly", "Assembly of %s:" % path,
                                                   labels, 0, False)
        if not ok:
            return
    subassembly.insert_sub_assembly(asm, path, label)


def _ground():
    for o in Gui.Selection.getSelection():
        o = picked(o)[0]
        if hasattr(o, "Grounded"):
            operations.set_grounded(o, not o.Grounded)


def _can_add():
    asm = active_assembly()
    return asm is not None and any(o is not asm and o not in asm.Group for o in _selected_solids())


def _can_ground():
    return any(hasattr(picked(o)[0], "Grounded") for o in Gui.Selection.getSelection())


def commands():
    return [
        ("Dispcon_CreateAssembly", Command("New assembly", "New assembly: an empty assembly in the active document. "
                                           "Then add or import its parts.", _create, False)),
        ("Dispcon_AddParts", Command("Add parts", "Add parts: select solids of the document in the tree or the "
                                     "3D view, then run this to make them parts of the assembly.", _add_parts,
                                     active=_can_add)),
        ("Dispcon_ImportPart", Command("Import part", "Import part: choose a STEP, IGES or BREP file; its solid "
                                       "becomes a part of the assembly.", _import)),
        ("Dispcon_InsertLink", Command("Insert part from file", "Insert part from file: choose a saved FreeCAD "
                                       "document (.FCStd) and one of its solids; it is linked into the assembly "
                                       "(App::Link) and follows that file's changes. Save this document first.",
                                       _insert_link)),
        ("Dispcon_InsertSubAssembly", Command(
            "Insert sub-assembly", "Insert sub-assembly: select the assembly to insert into, then (Ctrl+click) "
            "another assembly of this document to place in it; or select only the first and choose a saved "
            "FreeCAD document (.FCStd) whose assembly is linked in. It comes in rigid (it moves as one part): "
            "untick Rigid in its properties to let its own joints move in this assembly.", _insert_sub_assembly)),
        ("Dispcon_Ground", Command("Ground", "Ground: select one or more parts; they never move (run again "
                                   "to free them).", _ground, active=_can_ground)),
    ]
