// load_mesh, save_mesh, shape, Surface, model_names, shape_names.
#include <pybind11/stl.h>

#include <cmath>

#include "arrays.h"
#include "bindings.h"
#include "quadtri/math/error.h"
#include "quadtri/math/parallel.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/normals.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/model.h"

namespace quadtri::python {

namespace {

const char* kindName(AnalyticSurface::Kind kind) {
  switch (kind) {
    case AnalyticSurface::Kind::Sphere:
      return "sphere";
    case AnalyticSurface::Kind::Ellipsoid:
      return "ellipsoid";
    case AnalyticSurface::Kind::Torus:
      return "torus";
    case AnalyticSurface::Kind::Genus2:
      return "genus2";
    case AnalyticSurface::Kind::Box:
      return "box";
    case AnalyticSurface::Kind::Cylinder:
      return "cylinder";
  }
  return "?";
}

AnalyticSurface makeSurface(const std::string& kind, double a, double b, double c) {
  AnalyticSurface s;
  if (kind == "sphere")
    s.kind = AnalyticSurface::Kind::Sphere;
  else if (kind == "ellipsoid")
    s.kind = AnalyticSurface::Kind::Ellipsoid;
  else if (kind == "torus")
    s.kind = AnalyticSurface::Kind::Torus;
  else if (kind == "genus2")
    s.kind = AnalyticSurface::Kind::Genus2;
  else if (kind == "box")
    s.kind = AnalyticSurface::Kind::Box;
  else if (kind == "cylinder")
    s.kind = AnalyticSurface::Kind::Cylinder;
  else
    throw py::value_error(
        fmt::format("kind '{}': expected sphere, ellipsoid, torus, genus2, box or cylinder", kind));
  for (const auto& [name, value] : {std::pair{"a", a}, {"b", b}, {"c", c}})
    if (!(value > 0.0) || !std::isfinite(value))
      throw py::value_error(fmt::format("{} = {}: expected a finite positive size", name, value));
  s.a = a;
  s.b = b;
  s.c = c;
  return s;
}

// (k, 3) points → f(point) for each, in parallel without the GIL.
template <typename Out, typename F>
void forEachPoint(const FloatArray& points, Out* out, F f) {
  const double* p = points.data();
  const size_t n = size_t(points.shape(0));
  LibraryCall call;
  parallelForRange(tbb::blocked_range<size_t>(0, n), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i)
      f(Vec3(p[3 * i], p[3 * i + 1], p[3 * i + 2]), out, i);
  });
}

py::tuple withTruth(py::tuple arrays, const std::optional<AnalyticSurface>& truth) {
  py::list items(arrays);
  items.append(truth ? py::cast(*truth) : py::none());
  return py::tuple(items);
}

}  // namespace

void bindMesh(py::module_& m) {
  py::class_<AnalyticSurface>(m, "Surface", R"doc(
The smooth surface a built-in shape samples, to measure models against (truth_distance).

Surface(kind, a=1, b=1, c=1): kind "sphere" (radius a), "ellipsoid" (semi-axes a, b, c),
"torus" (major radius a, minor radius b, around the z axis), "genus2" (the pretzel
(x^4 - x^2 + y^2)^2 + z^2 = a^2, tube a = 0.2 in shape("genus2")), or, with creases, "box"
(centred at the origin, half extents a, b, c) or "cylinder" (capped, around the z axis, radius
a, z from -b to b).
)doc")
      .def(py::init(&makeSurface), py::arg("kind"), py::arg("a") = 1.0, py::arg("b") = 1.0,
           py::arg("c") = 1.0)
      .def_property_readonly("kind", [](const AnalyticSurface& s) { return kindName(s.kind); })
      .def_readonly("a", &AnalyticSurface::a)
      .def_readonly("b", &AnalyticSurface::b)
      .def_readonly("c", &AnalyticSurface::c)
      .def_property_readonly("size", &AnalyticSurface::size,
                             "The largest extent's half: what truth_distance divides by.")
      .def(
          "distance",
          [](const AnalyticSurface& s, py::handle P) {
            const FloatArray points = floatRows(P, "P", "k", 3);
            py::array_t<double> out(points.shape(0));
            forEachPoint(points, out.mutable_data(),
                         [&](const Vec3& p, double* o, size_t i) { o[i] = s.distance(p); });
            return out;
          },
          py::arg("P"),
          "Unsigned distance (k,) from each point of P (k, 3) to the surface (genus2: an upper "
          "bound, converged near the surface).")
      .def(
          "normal",
          [](const AnalyticSurface& s, py::handle P) {
            const FloatArray points = floatRows(P, "P", "k", 3);
            py::array_t<double> out({points.shape(0), py::ssize_t(3)});
            forEachPoint(points, out.mutable_data(), [&](const Vec3& p, double* o, size_t i) {
              const Vec3 n = s.normal(p);
              for (int k = 0; k < 3; ++k) o[3 * i + k] = n[k];
            });
            return out;
          },
          py::arg("P"),
          "Outward unit normal (k, 3) at the surface point nearest to each point of P (k, 3).")
      .def("__repr__", [](const AnalyticSurface& s) {
        return fmt::format("quadtri.Surface('{}', a={}, b={}, c={})", kindName(s.kind), s.a, s.b,
                           s.c);
      });

  m.def("model_names", &modelNames, "Every model name, in the order `--model all` lists them.");
  m.def("shape_names", &builtinShapeNames, "The built-in shapes' names.");

  m.def(
      "load_mesh",
      [](py::handle path, const std::string& normals, bool split, bool truth, double creaseAngle) {
        const std::string spec = pathOf(path);
        const NormalSource source = parseNormalSource(normals);
        BuiltinMesh input;
        {
          LibraryCall call;
          checkCreaseAngle(creaseAngle);
          input = loadMeshSpec(spec, NormalOptions(source, creaseAngle));
        }
        if (const std::optional<std::string> repaired = repairWarning(input.mesh, spec))
          warn(PyExc_UserWarning, *repaired);
        py::tuple arrays = meshArrays(input.mesh, split, spec);
        return truth ? withTruth(arrays, input.truth) : arrays;
      },
      py::arg("path"), py::arg("normals") = "file", py::arg("split") = false,
      py::arg("truth") = false, py::arg("crease_angle") = kDefaultCreaseAngleDeg, R"doc(
Loads a mesh file (.obj, .ply, .stl, .off) or a built-in shape spec (icosphere:3, torus:1,0.35,
...), exactly as the CLI's `convert` and `analyze` read their MESH argument.

normals: "file" (the file's; angle-weighted and split at crease_angle degrees, default 30, when
it has none; a built-in shape's analytic normals), "average" (eq. 2.8, never split) or "angle"
(angle-weighted, split at crease_angle), as the CLI's --normals and --crease-angle.

Returns V (n, 3) float64, F (m, 3) int64 and N (n, 3) float64, one unit normal per vertex. Positions
are welded, so vertices shared by triangles are shared indices. Where the file gives a vertex
different normals on different corners (split normals at a crease), N holds their normalised mean
and a quadtri.SplitNormalsWarning is issued; with split=True it returns V, F, N (k, 3), NI (m, 3)
instead, corner j of triangle i having normal N[NI[i, j]], exactly as the library holds it. With
truth=True a last item is added: the quadtri.Surface a built-in shape samples, or None.
)doc");

  m.def(
      "save_mesh",
      [](py::handle path, py::handle V, py::handle F, py::handle N, py::handle NI) {
        const std::string file = pathOf(path);
        const TriangleMesh mesh = meshFromArrays(V, F, N, NI);
        LibraryCall call;
        mesh.validate(file);
        saveMesh(mesh, file);
      },
      py::arg("path"), py::arg("V"), py::arg("F"), py::arg("N") = py::none(),
      py::arg("NI") = py::none(),
      "Writes V, F and normals (as Model takes them) to an .obj or a .ply file (atomically).");

  m.def(
      "shape",
      [](const std::string& name, int level, int segments, int rings, std::array<double, 3> radii,
         double major, double minor, int cells, const std::string& normals, bool truth) {
        if (normals != "analytic" && normals != "average" && normals != "angle")
          throw py::value_error(
              fmt::format("normals '{}': expected analytic, average or angle", normals));
        ShapeParams params;
        params.level = level;
        params.segments = segments;
        params.rings = rings;
        params.radii = Vec3(radii[0], radii[1], radii[2]);
        params.major = major;
        params.minor = minor;
        params.cells = cells;
        params.analyticNormals = normals != "average";
        BuiltinMesh shape;
        {
          LibraryCall call;
          shape = makeBuiltin(name, params);
          if (normals == "angle") computeVertexNormals(shape.mesh, NormalSource::Angle);
        }
        py::tuple arrays = meshArrays(shape.mesh, false, name);
        return truth ? withTruth(arrays, shape.truth) : arrays;
      },
      py::arg("name"), py::arg("level") = 2, py::arg("segments") = 32, py::arg("rings") = 16,
      py::arg("radii") = std::array<double, 3>{1.0, 0.7, 0.5}, py::arg("major") = 1.0,
      py::arg("minor") = 0.35, py::arg("cells") = 24, py::arg("normals") = "analytic",
      py::arg("truth") = false, R"doc(
A built-in shape as V (n, 3), F (m, 3), N (n, 3), as `quadtri mesh NAME` makes it: triangle,
tetrahedron, icosahedron, icosphere (level), uv-sphere (segments, rings), ellipsoid (radii,
level), torus (major, minor, segments, rings) or genus2 (cells). normals: "analytic" (the true
surface's), "average" (thesis eq. 2.8) or "angle". With truth=True a last item is added: the
quadtri.Surface the shape samples (the polyhedra sample the unit sphere).
)doc");
}

}  // namespace quadtri::python
