"""Finds and imports the dispcon Python module (the engine) built for FreeCAD's interpreter."""
import os
import sys

_HERE = os.path.dirname(os.path.abspath(__file__))
_REPO = os.path.dirname(os.path.dirname(_HERE))


def _candidates():
    env = os.environ.get("DISPCON_PYTHONPATH")
    if env:
        yield from env.split(os.pathsep)
    for build in ("build", "build-core"):
        yield os.path.join(_REPO, build, "python")


def load():
    """Returns the dispcon module: DISPCON_PYTHONPATH first, then <repo>/build/python."""
    try:
        import dispcon  # noqa: F401  already importable
        return sys.modules["dispcon"]
    except ImportError:
        pass
    for path in _candidates():
        if os.path.isdir(path) and path not in sys.path:
            sys.path.insert(0, path)
            try:
                import dispcon
                return dispcon
            except ImportError:
                sys.path.remove(path)
    raise ImportError("the dispcon module was not found: build it with scripts/demo, or set "
                      "DISPCON_PYTHONPATH to the folder that holds dispcon*.so")
