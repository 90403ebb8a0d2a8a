"""How assemblies and joints show in the tree and the 3D view (GUI only): the hooks the GUI side
builds on (icons, joint markers, double-click to edit). Like the objects' proxies they save
nothing (Stateless); objects.adopt() gives them back to objects whose view proxy a restore lost."""
import os

from .objects import Stateless
from .resources import icon_path


class _ViewProvider(Stateless):
    icon = "dispcon.svg"

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.ViewObject = vobj
        self.Object = vobj.Object

    def getIcon(self):
        path = icon_path(self.icon)
        return path if os.path.isfile(path) else icon_path("dispcon.svg")



class ViewProviderAssembly(_ViewProvider):
    icon = "assembly.svg"


class ViewProviderJoint(_ViewProvider):
    def getIcon(self):
        kind = getattr(getattr(self, "Object", None), "JointType", "")
        path = icon_path("joint-%s.svg" % kind.lower()) if kind else ""
        return path if path and os.path.isfile(path) else super().getIcon()


def attach(obj, kind):
    """Gives `obj` (an "Assembly" or a "Joint") its view provider when the GUI is up and it has none."""
    vobj = getattr(obj, "ViewObject", None)
    if vobj is None:
        return
    cls = {"Assembly": ViewProviderAssembly, "Joint": ViewProviderJoint}[kind]
    if not isinstance(getattr(vobj, "Proxy", None), cls):
        cls(vobj)
