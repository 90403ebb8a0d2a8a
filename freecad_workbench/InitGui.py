# dispcon workbench: lists the commands; the work is in dispcon_fc.
import FreeCADGui as Gui


class DispconWorkbench(Gui.Workbench):
    MenuText = "Dispcon"
    ToolTip = "Mechanism assembly with displacement constraints (Gascuel & Gascuel 1994)"

    def Initialize(self):
        from dispcon_fc import commands

        names = commands.register()
        self.appendToolbar("Dispcon", names)
        self.appendMenu("Dispcon", names)

    def GetClassName(self):
        return "Gui::PythonWorkbench"


Gui.addWorkbench(DispconWorkbench())
