"""A smile on the built-in head, written as smile.obj in the current folder (docs/python.md).

Run with the module on the path: PYTHONPATH=build/python /usr/bin/python3 examples/python/quickstart.py
"""
import os

import numpy as np

import myoshell

# The skin's basis is kept where the command line keeps it: a second run skips the basis computation.
cache = os.environ.get("MYOSHELL_CACHE") or os.path.expanduser("~/.cache/myoshell")
head = myoshell.load_head()                      # the built-in head, cm
face = myoshell.Face(head, cache=cache)          # the anatomical face with the whole face's 40 muscles
print("muscles:", ", ".join(face.muscle_names))

# Both zygomatici at 0.8 (activations lie in [0, 1]); the settled shape is an (n, 3) array in cm.
smile = face.pose({"zygomaticus_major_left": 0.8, "zygomaticus_major_right": 0.8})
moved = np.linalg.norm(smile - face.rest_positions(), axis=1)
print(f"max displacement {moved.max():.3f} cm at vertex {moved.argmax()}")

face.write_obj("smile.obj", smile)
print("wrote smile.obj")
