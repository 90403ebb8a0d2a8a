"""Finds and imports the dispcon Python module (the engine) built for FreeCAD's interpreter."""
import glob
import importlib.machinery
import importlib.util
import os
import sys

_HERE = os.path.dirname(os.path.abspath(__file__))
_REPO = os.path.dirname(os.path.dirname(_HERE))


def _from_folder(path):
    """The module from a build folder (put on sys.path), or None."""
    if not os.path.isdir(path) or not glob.glob(os.path.join(path, "dispcon*")):
        return None
    if path not in sys.path:
        sys.path.insert(0, path)
    try:
        import dispcon
        return dispcon
    except ImportError:
        sys.path.remove(path)
        return None


def _beside_me():
    """The module that scripts/install-freecad copied beside this file, or None."""
    for path in sorted(glob.glob(os.path.join(_HERE, "dispcon*.so"))):
        loader = importlib.machinery.ExtensionFileLoader("dispcon", path)
        spec = importlib.util.spec_from_file_location("dispcon", path, loader=loader)
        module = importlib.util.module_from_spec(spec)
        loader.exec_module(module)
        sys.modules["dispcon"] = module
        return module
    return None


def load():
    """Returns the dispcon module: one already importable, else from DISPCON_PYTHONPATH, else the
    one installed beside this file, else <repo>/build/python."""
    try:
        import dispcon  # already importable (on sys.path, or loaded before)
        return dispcon
    except ImportError:
        pass
    env = os.environ.get("DISPCON_PYTHONPATH")
    finders = [lambda p=p: _from_folder(p) for p in (env.split(os.pathsep) if env else [])]
    finders.append(_beside_me)
    finders += [lambda p=p: _from_folder(os.path.join(_REPO, p, "python")) for p in ("build", "build-core")]
    for find in finders:
        module = find()
        if module is not None:
            return module
    raise ImportError("the dispcon module was not found: install the workbench with "
                      "scripts/install-freecad, or set DISPCON_PYTHONPATH to the folder that "
                      "holds dispcon*.so")
