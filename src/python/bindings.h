// The Python module's parts, each registering its functions and classes on the module.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>

#include "quadtri/surface/model.h"
#include "quadtri/surface/tessellate.h"

namespace quadtri::python {

namespace py = pybind11;

/// A converted model as Python holds it: shared, so a RayScene keeps it alive.
struct PyModel {
  std::shared_ptr<const SurfaceModel> model;
  Tessellation tessellation;  ///< of its render geometry (Tessellated models)
  double convertSeconds = 0;  ///< wall time of makeModel
};

/// "thesis", a lattice level (int or its text), as --tessellation takes it.
Tessellation tessellationOf(py::handle value);

void bindMesh(py::module_& m);
void bindModel(py::module_& m);
void bindRays(py::module_& m);
void bindRender(py::module_& m);

}  // namespace quadtri::python
