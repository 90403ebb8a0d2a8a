"""The Bill of materials panel: the bill of the assembly as it will be written (a table), how its
sub-assemblies are listed, and Export CSV. Part number and Description are typed in the table
(double-click) for parts defined in this document (bom.check_part_info says why not for others:
a placed file's parts are set in that file). OK writes them on the parts and the bill into the
assembly's BOM spreadsheet (made the first time, rewritten afterwards) as one undo step; Cancel
writes nothing."""
import FreeCADGui as Gui

from .. import bom, panels
from ..adapter import plural
from ..feedback import report, status
from ..qt import QtCore, QtGui, QtWidgets
from ..resources import icon_path
from .base import Watched

EDITABLE = (bom.COLUMNS.index("Part number"), bom.COLUMNS.index("Description"))
CHOICES = (("rows", "One row each"), ("indented", "A row, its parts below"), ("expanded", "Only their parts"))


class BomPanel(Watched):
    title = "Bill of materials panel"

    def __init__(self, asm):
        self.asm, self.doc = asm, asm.Document
        self.closed = False
        self.watch()
        self.bill = []
        self.edits = {}  # {Name of the object written on: (a member, part number, description)}
        self.filling = False
        self.form = self._build()
        sheet = bom.sheet_of(asm)
        choice = sheet.SubAssemblies if sheet is not None and "SubAssemblies" in sheet.PropertiesList else "indented"
        self.choice.setCurrentIndex([c for c, _ in CHOICES].index(choice))
        self._fill()

    def _build(self):
        w = QtWidgets.QWidget()
        w.setObjectName("DispconBomPanel")
        w.setWindowTitle("Bill of materials")
        w.setWindowIcon(QtGui.QIcon(icon_path("Dispcon_BillOfMaterials.svg")))
        top = QtWidgets.QVBoxLayout(w)
        form = QtWidgets.QFormLayout()
        form.setRowWrapPolicy(QtWidgets.QFormLayout.WrapLongRows)
        top.addLayout(form)
        self.choice = QtWidgets.QComboBox()
        self.choice.setObjectName("subAssemblies")
        for _, text in CHOICES:
            self.choice.addItem(text)
        self.choice.setToolTip("How a placed sub-assembly is listed: one row (with how many are placed), that "
                               "row with its parts below it (per one sub-assembly), or its parts counted with the "
                               "assembly's own")
        form.addRow("Sub-assemblies", self.choice)
        self.table = QtWidgets.QTableWidget()
        self.table.setObjectName("table")
        self.table.setEditTriggers(QtWidgets.QAbstractItemView.DoubleClicked
                                   | QtWidgets.QAbstractItemView.EditKeyPressed)
        self.table.verticalHeader().setVisible(False)
        # As narrow as the Combo View: the columns scroll, the panel does not grow past it.
        self.table.setSizePolicy(QtWidgets.QSizePolicy.Ignored, QtWidgets.QSizePolicy.Expanding)
        self.table.setMinimumHeight(220)
        top.addWidget(self.table, 1)
        self.export = QtWidgets.QPushButton("Export CSV...")
        self.export.setObjectName("exportCsv")
        self.export.setToolTip("Write this bill as a CSV file (the spreadsheet's columns)")
        top.addWidget(self.export)
        self.message = QtWidgets.QLabel()
        self.message.setObjectName("message")
        self.message.setWordWrap(True)
        top.addWidget(self.message)
        self.choice.currentIndexChanged.connect(lambda *_: self._fill())
        self.table.itemChanged.connect(self._typed)
        self.export.clicked.connect(lambda *_: self._export())
        return w

    def sub_assemblies(self):
        return CHOICES[self.choice.currentIndex()][0]

    def _fill(self):
        try:
            self.bill = bom.rows(self.asm, self.sub_assemblies())
        except Exception as e:  # a part whose shape cannot be read: said, nothing written
            self.bill = []
            self.message.setText(str(e))
            self.message.setStyleSheet("color: #cc0000;")
            return
        for row in self.bill:  # what was typed and not written yet
            if row.defined is not None and row.defined.Name in self.edits:
                _, row.part_number, row.description = self.edits[row.defined.Name]
        cells = bom.table(self.bill)
        self.filling = True
        self.table.clear()
        self.table.setColumnCount(len(bom.COLUMNS))
        self.table.setRowCount(len(cells) - 1)
        self.table.setHorizontalHeaderLabels(list(bom.COLUMNS))
        for r, values in enumerate(cells[1:]):
            row = self.bill[r]
            why = self._not_here(row)
            for c, value in enumerate(values):
                text = "%.6g" % value if isinstance(value, float) else str(value)
                item = QtWidgets.QTableWidgetItem(text)
                if c in EDITABLE and why is None:
                    item.setToolTip("Double-click to type the %s (written on %s at OK)"
                                    % (bom.COLUMNS[c].lower(), row.defined.Label))
                else:
                    item.setFlags(item.flags() & ~QtCore.Qt.ItemIsEditable)
                    if c in EDITABLE:
                        item.setToolTip(why)
                if row.kind == "sub-assembly":
                    font = item.font()
                    font.setBold(True)
                    item.setFont(font)
                self.table.setItem(r, c, item)
        self.table.resizeColumnsToContents()
        self.filling = False
        self.message.setStyleSheet("")
        self.message.setText("%s. OK writes %s into the spreadsheet 'BOM of %s' (again: updates it)."
                             % (plural(len(self.bill), "row"), "it" if len(self.bill) == 1 else "them",
                                self.asm.Label))

    def _not_here(self, row):
        """Why a row's part number and description cannot be typed here (None: they can)."""
        if not row.members:
            return "nothing to write it on"
        try:
            bom.check_part_info(row.members[0])
        except ValueError as e:
            return str(e)
        return None

    def _typed(self, item):
        """A part number or description typed: checked by the bill's door, kept for OK and the
        CSV; refused, said in red and put back."""
        if self.filling or item.column() not in EDITABLE:
            return
        row = self.bill[item.row()]
        number, text = row.part_number, row.description
        if item.column() == bom.COLUMNS.index("Part number"):
            number = item.text()
        else:
            text = item.text()
        try:
            target, number, text = bom.check_part_info(row.members[0], number, text)
        except ValueError as e:
            self.message.setText(str(e))
            self.message.setStyleSheet("color: #cc0000;")
            self.filling = True
            item.setText(row.part_number if item.column() == bom.COLUMNS.index("Part number") else row.description)
            self.filling = False
            return
        self.edits[target.Name] = (row.members[0], number, text)
        self._fill()

    def part_info(self):
        """The edits for bom.write_sheet: {member: (part number, description)}."""
        return {member: (number, text) for member, number, text in self.edits.values()}

    def _export(self):
        from ..commands.motion import save_path

        path = save_path("Export the bill of materials of %s" % self.asm.Label, self.asm.Label + "-bom.csv",
                         "CSV (*.csv)")
        if path:
            self.export_csv(path)

    def export_csv(self, path):
        bom.write_csv(self.bill, path)
        self.message.setText("Written: %s" % path)
        status("Bill of materials written: %s" % path)

    def getStandardButtons(self):
        return int(QtWidgets.QDialogButtonBox.Ok | QtWidgets.QDialogButtonBox.Cancel)

    def accept(self):
        try:
            sheet, bill = bom.write_sheet(self.asm, self.sub_assemblies(), self.part_info())
        except Exception as e:  # written nothing (one transaction, aborted)
            self.message.setText(str(e))
            self.message.setStyleSheet("color: #cc0000;")
            return False
        self.closed = True
        self.unwatch()
        report("%s: %d rows written into '%s'" % (self.asm.Label, len(bill), sheet.Label))
        status("Bill of materials: %d rows in '%s'" % (len(bill), sheet.Label), 8000)
        Gui.Control.closeDialog()
        return True

    def watched(self):
        return [self.asm]

    def reject(self):
        self.closed = True
        self.unwatch()
        Gui.Control.closeDialog()
        return True


def open_panel(asm):
    if Gui.Control.activeDialog():
        Gui.Control.closeDialog()
    return panels.show(BomPanel(asm))
