#include "arrays.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>

#include "quadtri/mesh/normals.h"

namespace quadtri::python {

PyObject* splitNormalsWarning = nullptr;

std::string shapeOf(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

namespace {

std::string expected(std::string_view what, const char* rowName, py::ssize_t cols) {
  return rowName ? fmt::format("{} array of shape ({}, {})", what, rowName, cols)
                 : fmt::format("{} array", what);
}

// "a float array", "an integer array": `what` with its indefinite article.
static std::string withArticle(const std::string& what) {
  const bool vowel =
      !what.empty() && std::string_view("aeiou").find(what[0]) != std::string_view::npos;
  return (vowel ? "an " : "a ") + what;
}

// `obj` as an array whose dtype kind is one of `kinds`, or TypeError.
py::array checkedArray(py::handle obj, const char* name, std::string_view kinds,
                       const std::string& what) {
  py::array a = py::array::ensure(obj);
  const bool isArray = py::isinstance<py::array>(obj);
  if (!a) {
    throw py::type_error(fmt::format("{}: expected {}, got a {} that numpy cannot convert", name,
                                     withArticle(what),
                                     std::string(py::str(py::type::of(obj).attr("__name__")))));
  }
  const char kind = a.dtype().kind();
  if (kinds.find(kind) == std::string_view::npos) {
    const std::string got =
        !isArray && kind == 'O'
            ? fmt::format("a {}", std::string(py::str(py::type::of(obj).attr("__name__"))))
            : fmt::format("dtype {}", std::string(py::str(a.dtype())));
    throw py::type_error(fmt::format("{}: expected {}, got {}", name, withArticle(what), got));
  }
  return a;
}

void checkShape(const py::array& a, const char* name, const std::string& what, py::ssize_t cols) {
  if (a.ndim() != 2 || a.shape(1) != cols)
    throw py::value_error(
        fmt::format("{}: expected {}, got shape {}", name, withArticle(what), shapeOf(a)));
}

}  // namespace

FloatArray floatRows(py::handle obj, const char* name, const char* rowName, py::ssize_t cols) {
  const std::string what = expected("float", rowName, cols);
  py::array a = checkedArray(obj, name, "fiu", what);
  checkShape(a, name, what, cols);
  return FloatArray::ensure(a);
}

IndexArray indexRows(py::handle obj, const char* name, const char* rowName, py::ssize_t cols,
                     int64_t bound, const char* boundName) {
  const std::string what = expected("integer", rowName, cols);
  py::array a = checkedArray(obj, name, "iu", what);
  checkShape(a, name, what, cols);
  // Unsigned values above int64's range wrap to negatives and are caught below.
  IndexArray out = IndexArray::ensure(a);
  const int64_t* p = out.data();
  for (py::ssize_t i = 0; i < out.shape(0); ++i)
    for (py::ssize_t j = 0; j < cols; ++j) {
      const int64_t v = p[i * cols + j];
      if (v < 0 || v >= bound)
        throw py::value_error(fmt::format("{}[{}, {}] = {}: expected {} index in [0, {})", name, i,
                                          j, v, boundName, bound));
    }
  return out;
}

FloatArray floatArray(py::handle obj, const char* name, const std::string& what) {
  return FloatArray::ensure(checkedArray(obj, name, "fiu", what));
}

IndexArray indexArray(py::handle obj, const char* name) {
  return IndexArray::ensure(checkedArray(obj, name, "iu", expected("integer", nullptr, 0)));
}

py::array_t<double> rowsOf(const std::vector<Vec3>& rows) {
  py::array_t<double> out({py::ssize_t(rows.size()), py::ssize_t(3)});
  double* p = out.mutable_data();
  for (size_t i = 0; i < rows.size(); ++i)
    for (int k = 0; k < 3; ++k) p[3 * i + k] = rows[i][k];
  return out;
}

py::array_t<int64_t> trianglesOf(const std::vector<Tri>& triangles) {
  py::array_t<int64_t> out({py::ssize_t(triangles.size()), py::ssize_t(3)});
  int64_t* p = out.mutable_data();
  for (size_t i = 0; i < triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) p[3 * i + k] = triangles[i][k];
  return out;
}

namespace {

std::vector<Vec3> vec3Rows(const FloatArray& a) {
  std::vector<Vec3> out(size_t(a.shape(0)));
  const double* p = a.data();
  for (size_t i = 0; i < out.size(); ++i) out[i] = Vec3(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  return out;
}

std::vector<Tri> triRows(const IndexArray& a) {
  std::vector<Tri> out(size_t(a.shape(0)));
  const int64_t* p = a.data();
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = {uint32_t(p[3 * i]), uint32_t(p[3 * i + 1]), uint32_t(p[3 * i + 2])};
  return out;
}

}  // namespace

TriangleMesh meshFromArrays(py::handle V, py::handle F, py::handle N, py::handle NI) {
  TriangleMesh mesh;
  const FloatArray v = floatRows(V, "V", "n", 3);
  if (v.shape(0) > py::ssize_t(UINT32_MAX))
    throw py::value_error("V: more vertices than 32-bit indices address");
  mesh.positions = vec3Rows(v);
  mesh.triangles = triRows(indexRows(F, "F", "m", 3, v.shape(0), "a vertex"));
  if (N.is_none()) {
    if (!NI.is_none()) throw py::value_error("NI: given without N");
    computeVertexNormals(mesh, NormalSource::Average);
    return mesh;
  }
  const FloatArray n = floatRows(N, "N", NI.is_none() ? "n" : "k", 3);
  mesh.normals = vec3Rows(n);
  if (NI.is_none()) {
    if (n.shape(0) != v.shape(0))
      throw py::value_error(fmt::format(
          "N: expected one normal per vertex, shape ({}, 3), got shape ({}, 3) (per-corner "
          "normals need NI)",
          v.shape(0), n.shape(0)));
    mesh.normalIndices = mesh.triangles;
  } else {
    mesh.normalIndices = triRows(indexRows(NI, "NI", "m", 3, n.shape(0), "a normal"));
    if (mesh.normalIndices.size() != mesh.triangles.size())
      throw py::value_error(
          fmt::format("NI: expected one row per triangle, shape ({}, 3), got ({}, 3)",
                      mesh.triangles.size(), mesh.normalIndices.size()));
  }
  std::vector<bool> used(mesh.normals.size(), false);
  for (const Tri& t : mesh.normalIndices)
    for (uint32_t i : t) used[i] = true;
  for (size_t i = 0; i < mesh.normals.size(); ++i) {
    const Vec3& nrm = mesh.normals[i];
    if (!used[i]) {
      mesh.normals[i] = Vec3(0, 0, 1);  // unused: any unit vector passes validation
    } else if (!allFinite(nrm) || std::abs(nrm.norm() - 1.0) > 1e-6) {
      throw py::value_error(fmt::format(
          "N[{}] = ({}, {}, {}): expected a finite unit normal (length 1 to within 1e-6)", i,
          nrm.x(), nrm.y(), nrm.z()));
    }
  }
  return mesh;
}

py::tuple meshArrays(const TriangleMesh& mesh, bool split, const std::string& what) {
  py::array_t<double> V = rowsOf(mesh.positions);
  py::array_t<int64_t> F = trianglesOf(mesh.triangles);
  if (split) {
    if (mesh.hasNormals())
      return py::make_tuple(V, F, rowsOf(mesh.normals), trianglesOf(mesh.normalIndices));
    std::vector<Vec3> faces(mesh.triangleCount());
    std::vector<Tri> indices(mesh.triangleCount());
    for (size_t t = 0; t < faces.size(); ++t) {
      faces[t] = mesh.faceNormal(t);
      indices[t] = {uint32_t(t), uint32_t(t), uint32_t(t)};
    }
    return py::make_tuple(V, F, rowsOf(faces), trianglesOf(indices));
  }
  std::vector<Vec3> first(mesh.positions.size(), Vec3::Zero());
  std::vector<uint8_t> state(mesh.positions.size(), 0);  // 0 unused, 1 one normal, 2 split
  for (size_t t = 0; t < mesh.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.triangles[t][k];
      const Vec3 n = mesh.cornerNormal(t, k);
      if (state[v] == 0) {
        first[v] = n;
        state[v] = 1;
      } else if (state[v] == 1 && n != first[v]) {
        state[v] = 2;
      }
    }
  // A split vertex: the mean of the distinct normals on its corners (on a cube's corner, of its
  // three faces', however the faces are triangulated).
  std::vector<std::vector<Vec3>> distinct(mesh.positions.size());
  for (size_t t = 0; t < mesh.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.triangles[t][k];
      if (state[v] != 2) continue;
      const Vec3 n = mesh.cornerNormal(t, k);
      if (std::find(distinct[v].begin(), distinct[v].end(), n) == distinct[v].end())
        distinct[v].push_back(n);
    }
  size_t splitCount = 0;
  for (size_t v = 0; v < first.size(); ++v)
    if (state[v] == 2) {
      Vec3 sum = Vec3::Zero();
      for (const Vec3& n : distinct[v]) sum += n;
      first[v] = safeNormalized(sum, first[v]);
      ++splitCount;
    }
  py::tuple result = py::make_tuple(V, F, rowsOf(first));
  if (splitCount)
    warn(splitNormalsWarning,
         fmt::format("{}: {} of {} vertices have split normals (different normals on their "
                     "corners); N holds the normalised mean of each one's distinct normals. "
                     "split=True returns the corner normals as N, NI",
                     what, splitCount, mesh.positions.size()));
  return result;
}

uint64_t wholeNumber(py::handle obj, const char* name) {
  // Whatever has __index__ (an int, a numpy integer), but not a bool.
  const bool isBool = py::isinstance<py::bool_>(obj) ||
                      std::string(py::str(py::type::of(obj).attr("__name__"))) == "bool_";
  if (!PyIndex_Check(obj.ptr()) || isBool)
    throw py::type_error(fmt::format("{}: expected an int, got a {}", name,
                                     std::string(py::str(py::type::of(obj).attr("__name__")))));
  const py::int_ value = py::reinterpret_steal<py::int_>(PyNumber_Index(obj.ptr()));
  if (!value) throw py::error_already_set();
  if (value < py::int_(0) || value > py::int_(std::numeric_limits<uint64_t>::max()))
    throw py::value_error(fmt::format("{} = {}: expected a whole number from 0 to 2^64 - 1", name,
                                      std::string(py::str(obj))));
  return value.cast<uint64_t>();
}

std::string pathOf(py::handle obj) {
  return py::str(py::module_::import("os").attr("fsdecode")(obj));
}

void warn(PyObject* category, const std::string& message) {
  if (PyErr_WarnEx(category, message.c_str(), 1) != 0) throw py::error_already_set();
}

}  // namespace quadtri::python
