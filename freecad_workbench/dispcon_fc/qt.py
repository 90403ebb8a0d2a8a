"""Qt for the workbench, through FreeCAD's own `PySide` shim (never PySide2 directly), so that the
workbench follows whichever Qt binding FreeCAD was built with.

FreeCAD 0.20's shim puts the widgets in `PySide.QtGui` (it has no `QtWidgets` module); FreeCAD 1.x's
shim has `PySide.QtWidgets`. `is_alive` asks whether a widget's C++ side still exists (a task
dialog's form is deleted by FreeCAD when the dialog closes)."""
from PySide import QtCore, QtGui  # FreeCAD's shim

try:
    from PySide import QtWidgets  # FreeCAD 1.x's shim
except ImportError:  # FreeCAD 0.20: the widgets are in QtGui
    QtWidgets = QtGui

try:
    import shiboken2 as _shiboken
except ImportError:  # a FreeCAD built with Qt 6
    import shiboken6 as _shiboken

__all__ = ["QtCore", "QtGui", "QtWidgets", "is_alive"]


def is_alive(obj):
    """Whether `obj`'s C++ object still exists."""
    return obj is not None and _shiboken.isValid(obj)
