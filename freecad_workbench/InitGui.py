# dispcon workbench: lists the commands; the work is in dispcon_fc.
import FreeCADGui as Gui


class DispconWorkbench(Gui.Workbench):
    MenuText = "Dispcon"
    ToolTip = "Mechanism assembly with displacement constraints (Gascuel & Gascuel 1994)"

    def __init__(self):
        from dispcon_fc.resources import icon_path

        self.__class__.Icon = icon_path("dispcon.svg")

    def Initialize(self):
        from dispcon_fc import commands

        names = commands.register()
        self.appendToolbar("Dispcon", names)
        self.appendMenu("Dispcon", names)

    def GetClassName(self):
        return "Gui::PythonWorkbench"


def _preferences_page():
    from dispcon_fc.resources import RESOURCES, ui_path

    # The group's icon is found by name (preferences-dispcon) on the icon path.
    Gui.addIconPath(RESOURCES + "/icons")
    Gui.addPreferencePage(ui_path("preferences.ui"), "Dispcon")


Gui.addWorkbench(DispconWorkbench())
_preferences_page()
