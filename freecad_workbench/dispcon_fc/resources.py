"""Where the workbench's resources are. Icons live in Resources/icons beside the dispcon_fc
package. The Qt Designer forms live in the repository's top-level ui/ folder (the project's layout
keeps them apart from the code); an installed Mod folder carries them as Resources/ui."""
import os

_WORKBENCH = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RESOURCES = os.path.join(_WORKBENCH, "Resources")
# Installed: Mod/Dispcon/Resources/ui. Source tree: <repo>/ui, beside freecad_workbench/.
_UI_DIRS = (os.path.join(RESOURCES, "ui"), os.path.join(os.path.dirname(_WORKBENCH), "ui"))


def ui_path(name):
    for folder in _UI_DIRS:
        path = os.path.join(folder, name)
        if os.path.isfile(path):
            return path
    raise FileNotFoundError("the form %s is in none of %s" % (name, ", ".join(_UI_DIRS)))


def icon_path(name):
    return os.path.join(RESOURCES, "icons", name)
