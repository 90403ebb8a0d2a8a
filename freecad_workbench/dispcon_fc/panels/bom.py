"""The Bill of materials panel: the bill of the assembly as it will be written (a table), how its
sub-assemblies are listed, and Export CSV. OK writes it into the assembly's BOM spreadsheet (made
the first time, rewritten afterwards) as one undo step; Cancel writes nothing."""
import FreeCADGui as Gui

from .. import bom, panels
from ..adapter import plural
from ..feedback import report, status
from ..qt import QtGui, QtWidgets
from ..resources import icon_path

CHOICES = (("rows", "One row each"), ("indented", "A row, its parts below"), ("expanded", "Only their parts"))


class BomPanel:
    def __init__(self, asm):
        self.asm, self.doc = asm, asm.Document
        self.closed = False
        self.bill = []
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
        self.table.setEditTriggers(QtWidgets.QAbstractItemView.NoEditTriggers)
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
        cells = bom.table(self.bill)
        self.table.clear()
        self.table.setColumnCount(len(bom.COLUMNS))
        self.table.setRowCount(len(cells) - 1)
        self.table.setHorizontalHeaderLabels(list(bom.COLUMNS))
        for r, values in enumerate(cells[1:]):
            for c, value in enumerate(values):
                text = "%.6g" % value if isinstance(value, float) else str(value)
                item = QtWidgets.QTableWidgetItem(text)
                if self.bill[r].kind == "sub-assembly":
                    font = item.font()
                    font.setBold(True)
                    item.setFont(font)
                self.table.setItem(r, c, item)
        self.table.resizeColumnsToContents()
        self.message.setStyleSheet("")
        self.message.setText("%s. OK writes %s into the spreadsheet 'BOM of %s' (again: updates it)."
                             % (plural(len(self.bill), "row"), "it" if len(self.bill) == 1 else "them",
                                self.asm.Label))

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
            sheet, bill = bom.write_sheet(self.asm, self.sub_assemblies())
        except Exception as e:  # written nothing (one transaction, aborted)
            self.message.setText(str(e))
            self.message.setStyleSheet("color: #cc0000;")
            return False
        self.closed = True
        report("%s: %d rows written into '%s'" % (self.asm.Label, len(bill), sheet.Label))
        status("Bill of materials: %d rows in '%s'" % (len(bill), sheet.Label), 8000)
        Gui.Control.closeDialog()
        return True

    def reject(self):
        self.closed = True
        Gui.Control.closeDialog()
        return True


def open_panel(asm):
    if Gui.Control.activeDialog():
        Gui.Control.closeDialog()
    return panels.show(BomPanel(asm))
