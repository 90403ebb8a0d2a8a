"""The bill of materials of an assembly: each distinct part once, with how many the assembly holds,
written into a FreeCAD Spreadsheet of the document (one undo step, the same sheet updated when
run again) and exportable as CSV.

Which parts are the same part:
- links (App::Link, a part inserted from a file, each part of a placed sub-assembly) to one
  object are one part, named by that object's label;
- other parts are one part when their labels differ only by FreeCAD's numbering ("Bolt",
  "Bolt001", "Bolt002") and their shapes are the same in their own frames (volume, area, faces,
  edges and box within a millionth of their size): a "link-1" and a "link-3" stay two parts, and
  two different shapes labelled "Pin" and "Pin001" stay two parts, each under its own label.

Sub-assemblies, as the designer chooses (SUB_ASSEMBLIES):
- "rows": one row per distinct placed assembly (the same leg placed four times: 4), its parts
  not listed;
- "indented": that row followed by its parts (indices 3.1, 3.2, ...), their quantities per one
  sub-assembly, as a drawing's parts list of a sub-assembly, and a sub-assembly nested in it the
  same way a level down (3.3, then 3.3.1, ...);
- "expanded": no sub-assembly rows; their parts (and those of the sub-assemblies nested in them)
  are counted with the assembly's own (a leg's crank placed four times: 4 more cranks).

Part number and description are the part's own, where it is defined (a link's: the object it
links, in its file): its PartNumber property (set_part_info adds it; the workbench's parts have
it) and FreeCAD's Description (Label2, the tree's Description column); a placed sub-assembly's are
its assembly's. Two parts of one shape and label but another part number or description are two
rows. A part defined in another file takes them from that file, which is never written to here:
set them there.

Material and mass come only from what the document says: a part's Material (a map with Name and
Density, a link to a material object, or a name) or a material object (FEM's MaterialSolid,
App::MaterialObject) whose References name the part. The workbench's own Density property is the
solver's weight of a part, not a material's, and is not used: without a material density the Mass
cell stays empty."""
import csv
import os
import re

import FreeCAD as App

from . import objects
from .objects import instance_parts, is_sub_assembly, parts, shape_of

SUB_ASSEMBLIES = ("rows", "indented", "expanded")
COLUMNS = ("Index", "Name", "Part number", "Description", "Quantity", "Material", "Volume (mm³)", "Mass (g)",
           "Source")
QUANTITY = COLUMNS.index("Quantity")
# FreeCAD numbers a label that is taken already: "Bolt" then "Bolt001", "Bolt002".
_NUMBERED = re.compile(r"(?<=\D)\d{3,}$")


def label_base(label):
    """A label without FreeCAD's numbering: "Bolt001" -> "Bolt" ("link-1" stays as it is)."""
    return _NUMBERED.sub("", label)


class Row:
    """One line of the bill: `index` ("3", or "3.1" under a sub-assembly), `name`, `part_number`
    and `description` ("" when none), `quantity`,
    `material` ("" when unknown), `volume` (mm³ of one piece) and `mass` (g of one piece, None
    when a density is unknown), `source` (the file a linked part comes from, else ""), `kind`
    ("part" or "sub-assembly") and `members`, the document's objects it counts."""

    def __init__(self, name, kind, key, material="", volume=None, mass=None, source="", info=("", ""), defined=None):
        self.index, self.name, self.kind, self.key = "", name, kind, key
        self.part_number, self.description = info
        self.defined = defined  # the object its part number and description live on
        self.quantity, self.members = 0, []
        self.material, self.volume, self.mass, self.source = material, volume, mass, source

    def cells(self):
        """The row's values in COLUMNS' order (numbers as numbers, unknowns as "")."""
        return (self.index, self.name, self.part_number, self.description, self.quantity, self.material,
                "" if self.volume is None else self.volume, "" if self.mass is None else self.mass, self.source)

    def __repr__(self):
        return "Row(%s, %r, %d)" % (self.index, self.name, self.quantity)


# -- what a part is ------------------------------------------------------------------------------

def _definition(obj):
    """The object a part shows: a link's linked object (followed to the end), else the part."""
    if obj.TypeId == "App::Link" or hasattr(obj, "LinkedObject"):
        target = obj.getLinkedObject(True)
        if target is not None and target is not obj:
            return target
    return obj


def _signature(shape):
    """What identical shapes share, in their own frame: volume, area, faces, edges, the box."""
    local = shape.copy()
    local.Placement = App.Placement()
    box = local.BoundBox
    return (local.Volume, local.Area, len(local.Faces), len(local.Edges), box.XLength, box.YLength, box.ZLength)


def _same_shape(a, b):
    if a[2:4] != b[2:4]:
        return False
    size = max(abs(v) for v in a[4:] + b[4:]) or 1.0
    tolerance = 1e-6
    return (abs(a[0] - b[0]) <= tolerance * size ** 3 and abs(a[1] - b[1]) <= tolerance * size ** 2
            and all(abs(x - y) <= tolerance * size for x, y in zip(a[4:], b[4:])))


def part_info(obj):
    """(part number, description) of a part (of its definition: a link's linked object) or of a
    placed assembly: its PartNumber and its Label2, "" where none."""
    target = _definition(obj)
    number = target.PartNumber if "PartNumber" in target.PropertiesList else ""
    return (number if isinstance(number, str) else "", target.Label2 or "")


def _checked_text(what, value, label):
    """The one door of a part number or a description: text on one line, its ends' blanks
    dropped; None (leave it) passes."""
    if value is None:
        return None
    if not isinstance(value, str):
        raise ValueError("%s: the %s is text, not %r" % (label, what, value))
    if any(ord(c) < 32 or ord(c) == 127 for c in value):
        raise ValueError("%s: the %s is one line of text (it holds a line break or a control character)"
                         % (label, what))
    return value.strip()


def check_part_info(obj, part_number=None, description=None):
    """The object set_part_info writes on (the part's definition, or the placed assembly of a
    sub-assembly instance) and the checked values; refused (a ValueError by label) when that
    object is in another file (a placed file is never written to here) or a value is not one
    line of text."""
    from .subassembly import source_of

    target = source_of(obj) if is_sub_assembly(obj) else _definition(obj)
    number = _checked_text("part number", part_number, obj.Label)
    text = _checked_text("description", description, obj.Label)
    if target.Document is not obj.Document:
        raise ValueError("%s is defined in %s: set its part number and description there (a placed file is never "
                         "written to from here)" % (target.Label, _source(target, obj)))
    return target, number, text


def set_part_info(obj, part_number=None, description=None, undo_step=True):
    """Sets the part number (its PartNumber, added if missing) and the description (Label2) of
    a part where it is defined, or of the assembly a sub-assembly instance places; None leaves
    one as it is. One undo step; refused, nothing changes. Returns the object written on."""
    from .operations import _step

    target, number, text = check_part_info(obj, part_number, description)
    with _step(obj.Document, "Part number", undo_step):
        if number is not None:
            objects.part_number_property(target)
            if target.PartNumber != number:
                target.PartNumber = number
        if text is not None and target.Label2 != text:
            target.Label2 = text
    return target


def _source(obj, asm):
    """The file a linked part comes from (its document's file name), or "" for this document's."""
    if obj.Document is asm.Document:
        return ""
    return os.path.basename(obj.Document.FileName) if obj.Document.FileName else obj.Document.Name


def material(obj):
    """(name, density in g/mm³ or None) of a part, from what the document says, or ("", None)."""
    for o in (obj, _definition(obj)):
        found = _own_material(o)
        if found is not None:
            return found
    for o in obj.Document.Objects:
        if "References" in o.PropertiesList and isinstance(getattr(o, "Material", None), dict):
            refs = o.References or []
            if any(r[0] in (obj, _definition(obj)) for r in refs):
                return _card(o.Material)
    return "", None


def _own_material(obj):
    if "Material" not in obj.PropertiesList:
        return None
    value = obj.Material
    if isinstance(value, dict):
        return _card(value)
    if hasattr(value, "Material") and isinstance(value.Material, dict):  # a link to a material object
        return _card(value.Material)
    if isinstance(value, str) and value:
        return value, None
    return None


def _card(card):
    """A material card's name and density (g/mm³), the density None when missing or unreadable."""
    name = card.get("Name") or card.get("CardName") or ""
    density = None
    text = card.get("Density")
    if text:
        try:
            density = 1000.0 * App.Units.Quantity(text).getValueAs("kg/mm^3").Value
        except Exception:  # no unit, or not a density: not guessed
            density = None
        if density is not None and not density > 0:
            density = None
    return name, density


# -- the bill ----------------------------------------------------------------------------------

class _Counter:
    """Rows in their first part's order, each part counted into the row it belongs to."""

    def __init__(self, asm):
        self.asm, self.rows = asm, []

    def add_part(self, obj, times=1):
        target = _definition(obj)
        shape = shape_of(obj)
        sig = _signature(shape)
        linked = target is not obj
        info = part_info(obj)
        for row in self.rows:
            if row.kind != "part":
                continue
            if linked and row.key == ("link", target):
                break
            if not linked and row.key[0] == "shape" and row.key[1] == label_base(obj.Label) \
                    and _same_shape(row.key[2], sig) and row.key[3] == info:
                break
        else:
            name, density = material(obj)
            volume = shape.Volume
            key = ("link", target) if linked else ("shape", label_base(obj.Label), sig, info)
            label = target.Label if linked else label_base(obj.Label)
            if not linked and any(r.kind == "part" and r.name == label for r in self.rows):
                label = obj.Label  # another shape (or part number) under the same name: its own label
            row = Row(label, "part", key, name, volume, None if density is None else volume * density,
                      _source(target, self.asm), info, target)
            self.rows.append(row)
        row.quantity += times
        row.members.append(obj)
        return row

    def add_sub_assembly(self, sub):
        from .subassembly import source_of

        src = source_of(sub)
        for row in self.rows:
            if row.key == ("sub", src):
                break
        else:
            row = Row(src.Label, "sub-assembly", ("sub", src), source=_source(src, self.asm), info=part_info(src),
                      defined=src)
            row.children = _Counter(self.asm)
            links = set(o.Name for o in instance_parts(sub))
            for o in sub.Group:  # its parts, and the sub-assemblies nested in it as rows of their own
                if o.Name in links:
                    row.children.add_part(o)
                elif is_sub_assembly(o):
                    row.children.add_sub_assembly(o)
            pieces = row.children.rows
            row.volume = sum(r.volume * r.quantity for r in pieces)
            if all(r.mass is not None for r in pieces):
                row.mass = sum(r.mass * r.quantity for r in pieces)
            self.rows.append(row)
        row.quantity += 1
        row.members.append(sub)
        return row


def rows(asm, sub_assemblies_as="indented"):
    """The bill of `asm` as a list of Row, numbered: its own parts and its sub-assemblies in the
    tree's order, sub-assemblies as `sub_assemblies_as` says (SUB_ASSEMBLIES)."""
    if sub_assemblies_as not in SUB_ASSEMBLIES:
        raise ValueError("sub-assemblies: one of %s, not %r" % (", ".join(SUB_ASSEMBLIES), sub_assemblies_as))
    if not objects.is_assembly(asm):
        raise ValueError("%s is not a Dispcon assembly" % getattr(asm, "Label", asm))
    own = set(o.Name for o in parts(asm))
    counter = _Counter(asm)
    for o in asm.Group:
        if o.Name in own:
            counter.add_part(o)
        elif is_sub_assembly(o):
            if sub_assemblies_as == "expanded":
                for link in objects.nested_parts(o):
                    counter.add_part(link)
            else:
                counter.add_sub_assembly(o)
    out = []
    _number(counter.rows, "", sub_assemblies_as == "indented", out)
    return out


def _number(rows, prefix, indented, out):
    """Numbers rows (1, 2, ...; under a sub-assembly 2.1, 2.2, a nested one's 2.3.1) into out."""
    for k, row in enumerate(rows, 1):
        row.index = prefix + str(k)
        out.append(row)
        if row.kind == "sub-assembly" and indented:
            _number(row.children.rows, row.index + ".", indented, out)  # quantities in one of it


def table(bill):
    """The header and the rows' cells: what the sheet and the CSV hold."""
    return [list(COLUMNS)] + [list(r.cells()) for r in bill]


# -- the spreadsheet -----------------------------------------------------------------------------

def sheet_of(asm):
    """The BOM spreadsheet made for `asm` before, or None."""
    for o in asm.Document.Objects:
        if getattr(o, "DispconType", "") == "BOM" and getattr(o, "Assembly", None) == asm:
            return o
    return None


def _column(k):
    return chr(ord("A") + k)


def _cell_text(value):
    """A cell's content as the spreadsheet reads it: numbers as numbers, text always as text
    (a leading ' keeps "1.2" an index and "=..." a name, not a formula)."""
    if isinstance(value, bool):
        value = str(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value)
    return "'" + value if value else ""


def write_sheet(asm, sub_assemblies_as="indented", part_info=None):
    """Writes the bill of `asm` into its BOM spreadsheet (made the first time, emptied and written
    again afterwards) in one undo step; returns (sheet, rows). `part_info` ({part: (part number,
    description)}, the BOM panel's edits) is set on the parts first, in the same undo step (each
    checked before anything is written)."""
    from .operations import transaction

    edits = [(obj, number, text) for obj, (number, text) in (part_info or {}).items()]
    for obj, number, text in edits:
        check_part_info(obj, number, text)
    rows(asm, sub_assemblies_as)  # a refused choice, before anything is written
    doc = asm.Document
    with transaction(doc, "Bill of materials"):
        for obj, number, text in edits:
            set_part_info(obj, number, text, undo_step=False)
        bill = rows(asm, sub_assemblies_as)
        cells = table(bill)
        sheet = sheet_of(asm)
        if sheet is None:
            sheet = doc.addObject("Spreadsheet::Sheet", "BOM")
            objects._mark(sheet, "BOM")
            objects._add(sheet, "BOM", "App::PropertyLink", "Assembly", "Dispcon", asm)
            objects._add(sheet, "BOM", "App::PropertyEnumeration", "SubAssemblies", "Dispcon", list(SUB_ASSEMBLIES))
            objects._add(sheet, "BOM", "App::PropertyInteger", "BomRows", "Dispcon")
            sheet.setEditorMode("BomRows", 2)
        if sheet.getContents("C1") != COLUMNS[2]:  # new, or written before the part number's column
            for k, width in enumerate((60, 180, 110, 200, 70, 140, 110, 90, 140)):
                sheet.setColumnWidth(_column(k), width)
        sheet.Label = "BOM of %s" % asm.Label
        sheet.SubAssemblies = sub_assemblies_as
        last = _column(len(COLUMNS) - 1)
        if sheet.BomRows:
            # The last bill's cells and their styles (clearAll would take the sheet's own
            # properties with them); any cell a designer added beside the bill stays.
            sheet.clear("A1:%s%d" % (last, sheet.BomRows))
        sheet.BomRows = len(cells)
        for r, values in enumerate(cells, 1):
            for c, value in enumerate(values):
                text = _cell_text(value)
                if text:
                    sheet.set("%s%d" % (_column(c), r), text)
        sheet.setStyle("A1:%s1" % last, "bold")
        for r, row in enumerate(bill, 2):
            if row.kind == "sub-assembly":
                sheet.setStyle("A%d:%s%d" % (r, last, r), "bold")
        sheet.recompute()
    return sheet, bill


def write_csv(bill, path):
    """Writes the bill (rows()) as CSV at `path`: the sheet's header and cells, comma-separated,
    numbers in full precision."""
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        for values in table(bill):
            w.writerow(["" if v is None else (repr(v) if isinstance(v, float) else v) for v in values])
    return path
