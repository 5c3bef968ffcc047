// Model: a mesh converted by one model, its evaluation, tessellation, patches and metrics.
#include <pybind11/stl.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "arrays.h"
#include "bindings.h"
#include "patch_records.h"
#include "quadtri/analysis/metrics.h"
#include "quadtri/math/error.h"
#include "quadtri/surface/convert_output.h"
#include "quadtri/surface/patch_table.h"

namespace quadtri::python {

Tessellation tessellationOf(py::handle value) {
  if (py::isinstance<py::bool_>(value))
    throw py::type_error(
        "tessellation: expected a lattice level (int), 'thesis' or 'auto', got a bool");
  if (py::isinstance<py::int_>(value))
    return Tessellation::parse(std::to_string(value.cast<long long>()));
  if (py::isinstance<py::str>(value)) return Tessellation::parse(value.cast<std::string>());
  throw py::type_error(
      fmt::format("tessellation: expected a lattice level (int), 'thesis' or 'auto', got a {}",
                  std::string(py::str(py::type::of(value).attr("__name__")))));
}

namespace {

py::object tessellationValue(const Tessellation& t) {
  if (t.kind != Tessellation::Kind::Lattice) return py::str(tessellationName(t));
  return py::int_(t.level);
}

const char* representationName(Representation r) {
  switch (r) {
    case Representation::InputTriangles:
      return "input-triangles";
    case Representation::Tessellated:
      return "tessellated";
    case Representation::Implicit:
      return "implicit";
    case Representation::Bezier:
      return "bezier";
  }
  return "?";
}

nlohmann::json conversion(const PyModel& m) {
  LibraryCall call;
  return conversionJson(*m.model, m.tessellation);
}

}  // namespace

void bindModel(py::module_& m) {
  m.def(
      "read_patches",
      [](py::handle path) {
        const std::string file = pathOf(path);
        PatchTable table;
        {
          LibraryCall call;
          table = readPatchTable(file);
        }
        py::dict out;
        out["model"] = table.model;
        out["tessellation"] = table.tessellation;
        out["triangles"] = table.triangles;
        out["patches"] =
            recordsFromBytes(table.patchLayout, table.patches.data(), size_t(table.patchCount));
        out["bridges"] =
            recordsFromBytes(table.bridgeLayout, table.bridges.data(), size_t(table.bridgeCount));
        return out;
      },
      py::arg("path"), R"doc(
Reads a binary patch table, what `quadtri convert MESH --model NAME -o OUT.qtp` writes (README,
"Binary patch table"): a dict with "model", "tessellation" (as --tessellation takes it),
"triangles" (input triangles), "patches" and "bridges", the structured arrays Model.patches()
and Model.bridges() return for the same conversion. Raises quadtri.Error naming the file and
the byte offset of what is wrong in it.
)doc");

  py::class_<PyModel>(m, "Model", R"doc(
A triangle mesh converted by one model (quadtri.model_names()), as `quadtri convert` and
`quadtri analyze` convert it.

Model(name, V, F, N=None, NI=None, tessellation=8): V (n, 3) float, F (m, 3) integer indices
into V (welded: triangles that share a vertex share its index, which is how the models find
neighbours); N (n, 3) one unit normal per vertex, or N (k, 3) with NI (m, 3) per-corner normal
indices (split normals, as load_mesh(..., split=True) returns them); without N, thesis eq. 2.8
computes them, as the CLI does for a file without normals. tessellation: the lattice level
(1 to 256), "thesis", or "auto" / "auto:TOLERANCE" (the lowest level up to 8 whose triangles
stay within TOLERANCE, default 1e-4, of the bounding-box diagonal from the surface; for a
tessellated model the `tessellation` property then gives the level it picked, the others pick it
when tessellate() is called) of a tessellated model's render geometry
(analyze's primitives, memory_bytes and crack_rate, and RayScene). Raises quadtri.Error with the library's message for
an unknown model or a mesh it rejects.
)doc")
      .def(py::init([](const std::string& name, py::handle V, py::handle F, py::handle N,
                       py::handle NI, py::handle tessellation) {
             auto mesh = std::make_shared<TriangleMesh>(meshFromArrays(V, F, N, NI));
             if (mesh->triangles.empty())
               throw py::value_error(
                   "F: shape (0, 3): a model is built from at least one triangle (as a mesh file "
                   "holding none is refused)");
             for (size_t t = 0; t < mesh->triangles.size(); ++t) {
               const Tri& f = mesh->triangles[t];
               if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0])
                 throw py::value_error(fmt::format(
                     "F: row {} ({}, {}, {}) names a vertex twice: no triangle (a mesh file's such "
                     "rows are removed on loading; load_mesh gives the repaired arrays)",
                     t, f[0], f[1], f[2]));
             }
             PyModel model;
             model.tessellation = tessellationOf(tessellation);
             LibraryCall call;
             mesh->validate("mesh");
             const auto start = std::chrono::steady_clock::now();
             model.model = makeModel(name, std::move(mesh));
             model.convertSeconds =
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
             // A tessellated model renders its lattice: its automatic level is picked now. The
             // others resolve it when they are tessellated (tessellate()).
             model.tessellation = renderTessellation(*model.model, model.tessellation);
             return model;
           }),
           py::arg("name"), py::arg("V"), py::arg("F"), py::arg("N") = py::none(),
           py::arg("NI") = py::none(), py::arg("tessellation") = 8)
      .def_property_readonly("name", [](const PyModel& p) { return std::string(p.model->name()); })
      .def_property_readonly(
          "representation",
          [](const PyModel& p) { return representationName(p.model->representation()); },
          "How it is drawn: 'input-triangles', 'tessellated', 'implicit' (quadric patches) or "
          "'bezier' (quartic Bézier pieces).")
      .def_property_readonly("patch_count", [](const PyModel& p) { return p.model->patchCount(); })
      .def_property_readonly("tessellation",
                             [](const PyModel& p) { return tessellationValue(p.tessellation); })
      .def_property_readonly(
          "convert_seconds", [](const PyModel& p) { return p.convertSeconds; },
          "Wall time of the conversion (analyze's convert_seconds).")
      .def(
          "mesh",
          [](const PyModel& p, bool split) { return meshArrays(p.model->mesh(), split, "mesh"); },
          py::arg("split") = false, "The input mesh as V, F, N (split=True: V, F, N, NI).")
      .def(
          "evaluate",
          [](const PyModel& p, py::handle t, py::handle u, py::handle v) {
            py::object broadcast = py::module_::import("numpy").attr("broadcast_arrays")(
                indexArray(t, "t"), floatArray(u, "u"), floatArray(v, "v"));
            const IndexArray ts = IndexArray::ensure(broadcast[py::int_(0)]);
            const FloatArray us = FloatArray::ensure(broadcast[py::int_(1)]),
                             vs = FloatArray::ensure(broadcast[py::int_(2)]);
            std::vector<py::ssize_t> shape(ts.shape(), ts.shape() + ts.ndim());
            const size_t n = size_t(ts.size());
            for (size_t i = 0; i < n; ++i)
              if (ts.data()[i] < 0 || size_t(ts.data()[i]) >= p.model->patchCount())
                throw py::value_error(fmt::format("t: patch {} out of range [0, {})", ts.data()[i],
                                                  p.model->patchCount()));
            // The patch's domain, with a hair of slack for (u, v) computed in floating point.
            constexpr double kSlack = 1e-9;
            for (size_t i = 0; i < n; ++i) {
              const double u1 = us.data()[i], v1 = vs.data()[i];
              if (!(u1 >= -kSlack && v1 >= -kSlack && u1 + v1 <= 1.0 + kSlack))
                throw py::value_error(fmt::format(
                    "u, v: ({}, {}) at index {} is not a point of the patch: expected u >= 0, "
                    "v >= 0 and u + v <= 1",
                    u1, v1, i));
            }
            shape.push_back(3);
            py::array_t<double> P(shape), N(shape);
            double *pp = P.mutable_data(), *pn = N.mutable_data();
            {
              LibraryCall call;
              for (size_t i = 0; i < n; ++i) {
                const SurfacePoint s =
                    p.model->evaluate(size_t(ts.data()[i]), us.data()[i], vs.data()[i]);
                for (int k = 0; k < 3; ++k) {
                  pp[3 * i + k] = s.position[k];
                  pn[3 * i + k] = s.normal[k];
                }
              }
            }
            return py::make_tuple(P, N);
          },
          py::arg("t"), py::arg("u"), py::arg("v"), R"doc(
Position and unit geometric normal of patch t at barycentric (u, v): (0, 0) is corner 0, (1, 0)
corner 1, (0, 1) corner 2; u >= 0, v >= 0, u + v <= 1 (ValueError otherwise, NaN included).
t, u, v broadcast against each other; returns P, N of their shape + (3,).
)doc")
      .def(
          "tessellate",
          [](const PyModel& p, py::handle level, bool split) {
            const Tessellation t = level.is_none() ? p.tessellation : tessellationOf(level);
            TriangleMesh mesh;
            {
              LibraryCall call;
              mesh = tessellate(*p.model, t);
            }
            return meshArrays(mesh, split, "tessellation");
          },
          py::arg("level") = py::none(), py::arg("split") = false, R"doc(
The model's surface as triangles, V, F, N, as `quadtri convert MESH -o OUT.obj` writes it: a lattice
of level N (N^2 triangles per patch), "thesis" or "auto" (default: the model's tessellation), welded where
the model shares its edges, with the surface normals; flat, shading and shading-offset return their
input triangles (split normals as load_mesh treats them).
)doc")
      .def(
          "save",
          [](const PyModel& p, py::handle path, py::handle level) {
            const Tessellation requested = level.is_none() ? p.tessellation : tessellationOf(level);
            const std::string file = pathOf(path);
            LibraryCall call;
            // As convert: a surface at the level it resolves to, patches naming what renders.
            const std::string ext = std::filesystem::path(file).extension().string();
            const bool patches = ext == ".json" || ext == ".qtp";
            return writeConversion(*p.model,
                                   patches ? renderTessellation(*p.model, requested)
                                           : resolveTessellation(*p.model, requested),
                                   file);
          },
          py::arg("path"), py::arg("level") = py::none(), R"doc(
Writes what `quadtri convert MESH --model NAME -o PATH` writes, by PATH's extension: .obj or .ply
the surface (tessellate's triangles, streamed a block of patches at a time, never whole in memory),
.json the patch JSON, .qtp the binary patch table. Returns the triangles written to an
OBJ/PLY file (0 otherwise). The file appears whole or not at all.
)doc")
      .def(
          "patch_json", [](const PyModel& p) { return toPython(conversion(p)); },
          "What `quadtri convert MESH --model NAME -o OUT.json` writes, as a dict (README, \"Patch "
          "JSON\").")
      .def(
          "patches",
          [](const PyModel& p) {
            const PackedRecords packed = [&] {
              LibraryCall call;
              return packedPatches(*p.model);
            }();
            return recordsFromBytes(packed.layout, packed.bytes.data(), packed.count);
          },
          R"doc(
Every patch's data as a numpy structured array, one record per input triangle, one field per key
of the patch JSON (README, "Patch JSON"): e.g. p["vertices"] (m, 3, 3); for implicit models
p["quadric"] (m, 10), the coefficients A..J of Ax^2+By^2+Cz^2+Dxy+Exz+Fyz+Gx+Hy+Iz+J = 0,
p["planes"] (m, 6, 4) clip planes (n, d) keeping n.x + d >= 0, zero-padded (a zero plane keeps
everything) with their count in p["planes_count"], p["bounds"]["min"], p["bounds"]["max"] (m, 3)
and p["orientation"]; nested JSON objects are nested fields (p["control_points"]["b01"]).
)doc")
      .def(
          "bridges",
          [](const PyModel& p) {
            const PackedRecords packed = [&] {
              LibraryCall call;
              return packedBridges(*p.model);
            }();
            return recordsFromBytes(packed.layout, packed.bytes.data(), packed.count);
          },
          R"doc(
The edge bridges of quadric-implicit-robust as a structured array (empty for other models and where
neighbours meet exactly): joins (b, 2) the two patches, plane (b, 4) the shared edge plane, planes
(b, 6, 4) with planes_count, bounds min/max (README, "Patch JSON").
)doc")
      .def(
          "analyze",
          [](const PyModel& p, py::handle linesArg, py::handle seedArg,
             std::optional<AnalyticSurface> truth, const std::string& meshName, int edgeSamples,
             int truthLevel) {
            const uint64_t lines = wholeNumber(linesArg, "lines");
            const uint64_t seed = wholeNumber(seedArg, "seed");
            if (lines == 0) throw py::value_error("lines 0: expected a positive number of lines");
            AnalysisOptions options;
            options.tessellation = p.tessellation;
            options.crack.lines = lines;
            options.crack.seed = seed;
            options.edgeSamples = edgeSamples;
            options.truthLevel = truthLevel;
            nlohmann::ordered_json json;
            {
              LibraryCall call;
              json = toJson(analyzeModel(*p.model, meshName, truth, p.convertSeconds, options));
            }
            return toPython(json);
          },
          py::arg("lines") = 100000, py::arg("seed") = 1, py::arg("truth") = py::none(),
          py::arg("mesh_name") = "", py::arg("edge_samples") = 9, py::arg("truth_level") = 12,
          R"doc(
The metrics of `quadtri analyze MESH --model NAME --json` as a dict with the same keys, in the same
order, and the same values (None where the CLI prints null): crack_rate from `lines` random lines
seeded by `seed` (closed meshes only), truth_distance against `truth` (a quadtri.Surface; the CLI
uses the built-in shape's), "mesh" set to mesh_name.
)doc")
      .def(
          "truth_distance",
          [](const PyModel& p, const AnalyticSurface& truth, int level) {
            LibraryCall call;
            return truthDistance(*p.model, truth, level);
          },
          py::arg("truth"), py::arg("level") = 12,
          "max over a lattice of `level` on every patch of truth.distance(P) / truth.size "
          "(analyze's truth_distance, without the other metrics).")
      .def("__repr__", [](const PyModel& p) {
        return fmt::format("quadtri.Model('{}', {} patches, tessellation={})", p.model->name(),
                           p.model->patchCount(),
                           p.tessellation.kind == Tessellation::Kind::Lattice
                               ? std::to_string(p.tessellation.level)
                               : "'" + tessellationName(p.tessellation) + "'");
      });
}

}  // namespace quadtri::python
