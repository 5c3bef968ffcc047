// Numpy arrays in and out of the Python module: checked conversions that name the argument and
// the shape and dtype expected, and the mesh layout V, F, N (NI) of the Python API.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <xmmintrin.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "quadtri/math/vec.h"
#include "quadtri/mesh/triangle_mesh.h"

namespace quadtri::python {

namespace py = pybind11;

using FloatArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using IndexArray = py::array_t<int64_t, py::array::c_style | py::array::forcecast>;

/// `obj` as a C-contiguous float64 array of shape (rows, cols), `rows` any count; `rowName` is
/// how messages call the row count ("n", "m", "k"). Any floating or integer dtype is accepted and
/// converted; anything else (bool, complex, str, object) raises TypeError, a wrong shape
/// ValueError, both naming `name`.
FloatArray floatRows(py::handle obj, const char* name, const char* rowName, py::ssize_t cols);

/// Same for an integer dtype (signed or unsigned), as int64; every entry must lie in
/// [0, bound) (ValueError naming the entry otherwise).
IndexArray indexRows(py::handle obj, const char* name, const char* rowName, py::ssize_t cols,
                     int64_t bound, const char* boundName);

/// A floating array of any shape (for broadcasting), checked as floatRows checks its dtype;
/// `what` is what a TypeError says was expected.
FloatArray floatArray(py::handle obj, const char* name, const std::string& what = "float array");

/// "(4, 2)": an array's shape as numpy prints it.
std::string shapeOf(const py::array& a);
/// An integer array of any shape, checked as indexRows checks its dtype (not its range).
IndexArray indexArray(py::handle obj, const char* name);

/// (n, 3) float64 / int64 copies of C++ rows.
py::array_t<double> rowsOf(const std::vector<Vec3>& rows);
py::array_t<int64_t> trianglesOf(const std::vector<Tri>& triangles);

/// A TriangleMesh from V (n, 3), F (m, 3) and either nothing (normals computed by thesis eq. 2.8,
/// as for a file without normals), per-vertex N (n, 3), or N (k, 3) with corner indices NI
/// (m, 3). Rows of N that no corner uses are ignored; the others must be finite unit vectors.
TriangleMesh meshFromArrays(py::handle V, py::handle F, py::handle N, py::handle NI);

/// The mesh as (V, F, N) with one normal per vertex, or with `split` as (V, F, N, NI) with the
/// mesh's own per-corner layout. Without `split`, a vertex whose corners carry different normals
/// gets the normalised mean of those distinct normals and a quadtri.SplitNormalsWarning says how
/// many vertices did; a vertex no triangle uses gets a zero normal.
py::tuple meshArrays(const TriangleMesh& mesh, bool split, const std::string& what);

/// Keeps the calling thread's floating-point mode (MXCSR) as it was: the library sets
/// flush-to-zero on the threads that trace rays, the calling thread among them, and Python's
/// thread must not be left computing with denormals flushed.
class FloatModeGuard {
 public:
  FloatModeGuard() : csr_(_mm_getcsr()) {}
  ~FloatModeGuard() { _mm_setcsr(csr_); }
  FloatModeGuard(const FloatModeGuard&) = delete;
  FloatModeGuard& operator=(const FloatModeGuard&) = delete;

 private:
  unsigned csr_;
};

/// The calls the library's work runs under: the GIL released, the float mode kept.
struct LibraryCall {
  py::gil_scoped_release release;
  FloatModeGuard guard;
};

/// The path `obj` names (str, bytes or os.PathLike).
std::string pathOf(py::handle obj);

/// `obj` as a whole number of 0 or more that fits 64 bits: TypeError for anything but an int,
/// ValueError naming `name` for a negative or too large one (pybind11's own conversion of an
/// unsigned argument only says the arguments are incompatible).
uint64_t wholeNumber(py::handle obj, const char* name);

/// The warning category of meshArrays, created by the module.
extern PyObject* splitNormalsWarning;

/// Issues a Python warning of `category` (raises if warnings are errors).
void warn(PyObject* category, const std::string& message);

}  // namespace quadtri::python
