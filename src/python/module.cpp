// The Python module quadtri._quadtri (README "Python"); quadtri/__init__.py re-exports it.
#include <pybind11/pybind11.h>

#include "arrays.h"
#include "bindings.h"
#include "quadtri/math/error.h"

PYBIND11_MODULE(_quadtri, m) {
  namespace py = pybind11;
  m.doc() =
      "quadtri: curved quadric triangles from triangle meshes, their metrics, ray tracing and "
      "rendering (README, \"Python\").";
  m.attr("__version__") = QUADTRI_VERSION;
  // quadtri::Error carries the message the CLI prints after "quadtri: error: ".
  py::register_exception<quadtri::Error>(m, "Error", PyExc_RuntimeError);
  quadtri::python::splitNormalsWarning = PyErr_NewExceptionWithDoc(
      "quadtri.SplitNormalsWarning",
      "A mesh's split (per-corner) normals were averaged per vertex.", PyExc_UserWarning, nullptr);
  if (!quadtri::python::splitNormalsWarning) throw py::error_already_set();
  m.add_object("SplitNormalsWarning", py::handle(quadtri::python::splitNormalsWarning));
  quadtri::python::bindMesh(m);
  quadtri::python::bindModel(m);
  quadtri::python::bindRays(m);
  quadtri::python::bindRender(m);
}
