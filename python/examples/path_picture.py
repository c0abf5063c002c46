"""A geodesic path over a distance field, as a picture.

    PYTHONPATH=python python3 python/examples/path_picture.py [MESH] [OUT.png]

Takes the mesh (default: the bundled Spot), a path between two far-apart surface points
(proven globally shortest), the exact geodesic distance from the first, and draws both.
"""
import os
import sys

import numpy as np

import trigeo

here = os.path.dirname(os.path.abspath(__file__))
mesh_path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "..", "data", "nvd_spot.obj")
out = sys.argv[2] if len(sys.argv) > 2 else "path_picture.png"

mesh = trigeo.load(mesh_path)
v = mesh.vertices
a = mesh.locate(v.min(axis=0))                       # the surface points nearest two bbox corners
b = mesh.locate(v.max(axis=0))
path = mesh.path(a, b, method="exact")               # globally shortest, proven
field = mesh.field([a])                              # exact distance from a to every vertex
print(f"{mesh}: path of length {path.length:.6g} ({path.global_}), {len(path)} points, "
      f"max angle defect {path.max_angle_defect:.2g} rad; farthest vertex at {np.max(field[np.isfinite(field)]):.6g}")
mesh.render(out, path=path, field=field, view=(0.5, -0.3, -1.0))
print(f"wrote {out}")
