# dispcon workbench: its toolbars and menu; the work is in dispcon_fc.
# FreeCAD runs this file inside a function: a name defined at its top level is gone by the time
# the workbench's methods run, so they import what they use and keep constants on the class.
import FreeCADGui as Gui


class DispconWorkbench(Gui.Workbench):
    MenuText = "Dispcon"
    ToolTip = "Mechanism assembly with displacement constraints (Gascuel & Gascuel 1994)"
    # Toolbars are named so: the first of them starts a row of its own (see Activated).
    TOOLBAR = "Dispcon %s"

    def __init__(self):
        # The workbench's own icon, beside this file (here, or in the Mod folder it was installed in).
        import dispcon_fc.resources as resources

        self.__class__.Icon = resources.icon_path("dispcon.svg")

    def Initialize(self):
        from dispcon_fc import commands, viewproviders

        groups = commands.register()
        # The toolbars: the commands used most as buttons, the others in drop-down buttons
        # (commands.DROP_DOWNS), so that the row has room at 1280 px.
        for title, _, bar in groups:
            self.appendToolbar(self.TOOLBAR % title, bar)
        # One menu, every command an entry of its own: the build commands, the joints in a
        # submenu, then motion and analysis, with separators between the groups.
        for k, (title, names, _) in enumerate(groups):
            if title == "Joints":
                self.appendMenu(["Dispcon", "Joints"], names)
            else:
                self.appendMenu("Dispcon", (["Separator"] if k else []) + names)
        # Markers that follow their parts and show the selection.
        self.observer = viewproviders.install()

    def Activated(self):
        # FreeCAD's own toolbars fill the first row at 1280 px: ours start a row of their own, so
        # Solve, Drag and Check never hide behind a toolbar's ">>".
        import FreeCADGui
        from dispcon_fc.qt import QtWidgets

        window = FreeCADGui.getMainWindow()
        bars = [tb for tb in window.findChildren(QtWidgets.QToolBar)
                if tb.objectName().startswith(self.TOOLBAR % "")]
        if bars:
            first = min(bars, key=lambda tb: (tb.y(), tb.x()))
            named = [tb for tb in bars if tb.objectName() == self.TOOLBAR % "Assembly"]
            first = named[0] if named else first
            if not window.toolBarBreak(first):
                window.insertToolBarBreak(first)

    def GetClassName(self):
        return "Gui::PythonWorkbench"


def _preferences_page():
    from dispcon_fc.resources import RESOURCES, ui_path

    # The group's icon is found by name (preferences-dispcon) on the icon path.
    Gui.addIconPath(RESOURCES + "/icons")
    Gui.addPreferencePage(ui_path("preferences.ui"), "Dispcon")


Gui.addWorkbench(DispconWorkbench())
_preferences_page()
