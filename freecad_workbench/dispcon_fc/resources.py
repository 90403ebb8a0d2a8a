"""Where the workbench's resources are: Resources/{icons,ui} beside the dispcon_fc package, both
in the source tree and in an installed Mod folder."""
import os

RESOURCES = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "Resources")


def ui_path(name):
    return os.path.join(RESOURCES, "ui", name)


def icon_path(name):
    return os.path.join(RESOURCES, "icons", name)
