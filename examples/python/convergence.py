"""Convergence of truth_distance under refinement, with quadtri's Python module and matplotlib.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/convergence.py convergence.png
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import quadtri

models = ["flat", "phong", "quadric-param", "nagata", "quadric-implicit-robust"]
levels = range(0, 5)
fig, ax = plt.subplots(figsize=(6, 4))
for name in models:
    triangles, distances = [], []
    for level in levels:
        V, F, N, truth = quadtri.shape("ellipsoid", radii=(1, 0.7, 0.5), level=level, truth=True)
        distances.append(quadtri.Model(name, V, F, N).truth_distance(truth))
        triangles.append(len(F))
    ax.loglog(triangles, distances, "o-", label=name)
    slope = np.polyfit(np.log(triangles[-3:]), np.log(distances[-3:]), 1)[0]
    print(f"{name:24s} truth_distance {distances[-1]:.3g} at {triangles[-1]} triangles, "
          f"order {-2 * slope:.2f} in the edge length")
ax.set_xlabel("triangles")
ax.set_ylabel("truth_distance (relative)")
ax.set_title("ellipsoid 1 × 0.7 × 0.5")
ax.legend()
fig.tight_layout()
fig.savefig(sys.argv[1] if len(sys.argv) > 1 else "convergence.png", dpi=120)
