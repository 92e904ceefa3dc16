"""Finding and loading the Python module `myoshell` inside Blender (docs/blender.md, "Other Blender
versions").

The zip carries the module built for Debian's Python 3.11 under lib/ (`make blender-addon`); a
folder given in the add-on's preferences (or $MYOSHELL_PYTHONPATH) is tried first, so that a module
built for another Blender's Python can be used without rebuilding the zip.
"""

import importlib
import os
import sys

_HERE = os.path.dirname(os.path.abspath(__file__))
BUNDLED = os.path.join(_HERE, "lib")
# The built-in head's landmark file (assets/default_head/landmarks_multipie68.json), for a mesh
# added by "Add the built-in head" and picked without a landmark file.
DEFAULT_LANDMARKS = os.path.join(_HERE, "data", "default_head_landmarks.json")

_module = None
_error = None


def restore_np_bool():
    """Debian 12's Blender 3.4 ships add-ons (the glTF importer) that still use `np.bool`, an alias
    numpy 1.24 removed: without it the importer fails. Put the alias back (Python's `bool`, as numpy
    before 1.24 had it) when it is missing; nothing else of numpy is touched."""
    try:
        import numpy as np
    except ImportError:
        return False
    if "bool" in np.__dict__:
        return False
    np.bool = bool
    return True


def load(extra_path=""):
    """The module, imported once; raises ImportError with what was tried."""
    global _module, _error
    if _module is not None:
        return _module
    tried = []
    for folder in (extra_path, os.environ.get("MYOSHELL_PYTHONPATH", ""), BUNDLED):
        if folder and os.path.isdir(folder):
            tried.append(folder)
            if folder not in sys.path:
                sys.path.insert(0, folder)
    try:
        _module = importlib.import_module("myoshell")
    except ImportError as e:
        py = "%d.%d" % sys.version_info[:2]
        _error = (
            "cannot import the myoshell module into Blender's Python %s (%s); looked in: %s. "
            "The zip's module is built for Python 3.11 (Debian 12's Blender 3.4): build the module "
            "for this Python and give its folder in the add-on's preferences (docs/blender.md)"
            % (py, e, ", ".join(tried) or "nothing"))
        raise ImportError(_error) from e
    return _module


def error():
    return _error
