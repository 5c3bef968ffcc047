"""quadtri: curved quadric triangles from triangle meshes, measured, ray traced and rendered.

Arrays follow libigl's conventions: V (n, 3) float64 positions, F (m, 3) int64 triangles, N (n, 3)
float64 unit normals per vertex (or N (k, 3) with per-corner indices NI (m, 3)). See README.md,
section "Python", for the whole interface.
"""

from ._quadtri import (
    Error,
    Model,
    RayScene,
    SplitNormalsWarning,
    __version__,
    Surface,
    load_mesh,
    model_names,
    read_patches,
    render,
    save_mesh,
    shape,
    shape_names,
)

__all__ = [
    "Error",
    "Model",
    "RayScene",
    "SplitNormalsWarning",
    "Surface",
    "load_mesh",
    "model_names",
    "read_patches",
    "render",
    "save_mesh",
    "shape",
    "shape_names",
]
