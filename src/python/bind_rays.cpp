// RayScene: models in the renderer's Embree scene, intersected with many rays at once.
#include <pybind11/stl.h>
#include <tbb/task_arena.h>

#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <span>

#include "arrays.h"
#include "bindings.h"
#include "quadtri/math/error.h"
#include "quadtri/math/parallel.h"
#include "quadtri/render/render_scene.h"

namespace quadtri::python {

namespace {

struct PyRayScene {
  struct Entry {
    std::shared_ptr<const SurfaceModel> model;
    size_t trianglesPerPatch = 1;  // tessellated models: render triangles per input triangle
  };
  std::unique_ptr<RenderScene> scene = std::make_unique<RenderScene>();
  std::vector<Entry> entries;            // by model index
  std::vector<int64_t> modelOfGeometry;  // geometry id → model index

  // The input triangle a hit of `primitive` on model `index` belongs to (-1 for an edge bridge).
  int64_t patchOf(size_t index, uint32_t primitive) const {
    const Entry& e = entries[index];
    switch (e.model->representation()) {
      case Representation::InputTriangles:
        return primitive;
      case Representation::Tessellated:
        return int64_t(primitive / e.trianglesPerPatch);
      case Representation::Implicit:
        return primitive < e.model->patchCount() ? int64_t(primitive) : -1;
      case Representation::Bezier:
        return primitive < e.model->bezierPieces().size()
                   ? int64_t(e.model->bezierPieces()[primitive].triangle)
                   : -1;
    }
    return -1;
  }
};

// Origins and directions: (k, 3) each, or one of them (3,) for every ray.
struct Rays {
  FloatArray origins, directions;
  size_t count = 0;
  bool oneOrigin = false, oneDirection = false;
  double tnear = 0, tfar = kInfinity;

  Ray ray(size_t i) const {
    const double* o = origins.data() + (oneOrigin ? 0 : 3 * i);
    const double* d = directions.data() + (oneDirection ? 0 : 3 * i);
    return Ray{Vec3(o[0], o[1], o[2]), Vec3(d[0], d[1], d[2]), tnear, tfar};
  }
};

FloatArray rayRows(py::handle obj, const char* name, bool& one) {
  const std::string what = "float array of shape (k, 3) or (3,)";
  const FloatArray a = floatArray(obj, name, what);
  one = a.ndim() == 1 && a.shape(0) == 3;
  if (!one && (a.ndim() != 2 || a.shape(1) != 3))
    throw py::value_error(fmt::format("{}: expected a {}, got shape {}", name, what, shapeOf(a)));
  return a;
}

Rays raysOf(py::handle origins, py::handle directions, double tnear, double tfar) {
  Rays r;
  r.origins = rayRows(origins, "origins", r.oneOrigin);
  r.directions = rayRows(directions, "directions", r.oneDirection);
  const size_t no = r.oneOrigin ? 1 : size_t(r.origins.shape(0));
  const size_t nd = r.oneDirection ? 1 : size_t(r.directions.shape(0));
  if (!r.oneOrigin && !r.oneDirection && no != nd)
    throw py::value_error(fmt::format(
        "origins, directions: expected the same number of rays, got {} origins and {} directions",
        no, nd));
  r.count = r.oneOrigin ? nd : no;
  if (r.oneOrigin && r.oneDirection) r.count = 1;
  for (const auto& [name, a] : {std::pair{"origins", &r.origins}, {"directions", &r.directions}})
    for (py::ssize_t i = 0; i < a->size(); ++i) {
      if (!std::isfinite(a->data()[i]))
        throw py::value_error(fmt::format("{}: row {} is not finite", name, i / 3));
      if (!(std::abs(a->data()[i]) <= Accel::kLargestRayCoordinate))
        throw py::value_error(
            fmt::format("{}: row {} has a coordinate of {}: expected one within ±{:g}, the largest "
                        "Embree traces",
                        name, i / 3, a->data()[i], Accel::kLargestRayCoordinate));
    }
  if (!(tnear >= 0.0) || !(tfar >= tnear))
    throw py::value_error(
        fmt::format("tnear = {}, tfar = {}: expected 0 <= tnear <= tfar", tnear, tfar));
  r.tnear = tnear;
  r.tfar = tfar;
  return r;
}

// The `threads` argument of the tracing calls: 0 for every core TBB offers, else that many.
int threadCount(int threads) {
  if (threads < 0)
    throw py::value_error(
        fmt::format("threads = {}: expected 0 (every core) or a positive count", threads));
  return threads;
}

// Runs f(range) over slices of [0, count) in parallel (at least `grain` at a time) on at most
// `threads` threads (0: all), without the GIL, on threads in Embree's float mode.
template <typename F>
void forEachSlice(size_t count, int threads, F f, size_t grain = 256) {
  LibraryCall call;
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    parallelForRange(tbb::blocked_range<size_t>(0, count, grain),
                     [&](const tbb::blocked_range<size_t>& range) {
                       const FlushToZeroScope flushToZero;
                       f(range.begin(), range.end());
                     });
  });
}

// Runs f(i) for every ray, as forEachSlice does.
template <typename F>
void forEachRay(size_t count, int threads, F f) {
  forEachSlice(count, threads, [&](size_t begin, size_t end) {
    for (size_t i = begin; i != end; ++i) f(i);
  });
}

// Runs f(i, hit) with every ray's nearest hit, as forEachSlice does; the rays are traced
// Accel::kPacketSize at a time (RenderScene::intersect of a span: Embree's packets, which
// coherent rays such as a camera's share). The packets are rays 16j to 16j + 15 whatever the
// threads: where a ray hits two triangles at exactly the same t, Embree's packet kernel may
// settle the tie by the other rays of its packet, so packets that began wherever a thread's
// slice began would make such hits depend on the threads.
template <typename F>
void forEachHit(const RenderScene& scene, const Rays& rays, int threads, F f) {
  constexpr size_t kLanes = Accel::kPacketSize;
  const size_t packets = (rays.count + kLanes - 1) / kLanes;
  forEachSlice(
      packets, threads,
      [&](size_t begin, size_t end) {
        std::array<Ray, kLanes> batch;
        std::array<std::optional<SurfaceInteraction>, kLanes> hits;
        for (size_t packet = begin; packet < end; ++packet) {
          const size_t first = packet * kLanes;
          const size_t n = std::min(kLanes, rays.count - first);
          for (size_t k = 0; k < n; ++k) batch[k] = rays.ray(first + k);
          scene.intersect(std::span<const Ray>(batch).first(n), std::span(hits).first(n));
          for (size_t k = 0; k < n; ++k) f(first + k, hits[k]);
        }
      },
      16);
}

}  // namespace

void bindRays(py::module_& m) {
  py::class_<PyRayScene>(m, "RayScene", R"doc(
Models in one Embree scene, built as the renderer builds them (RenderScene): input triangles,
tessellated triangles (each model's tessellation), quadric patches with their edge bridges, or
Bézier pieces.
Models are placed as they are (no transform); the scene keeps them alive.

RayScene([model, ...])
)doc")
      .def(py::init([](const std::vector<const PyModel*>& models) {
             PyRayScene s;
             LibraryCall call;
             for (size_t i = 0; i < models.size(); ++i) {
               const PyModel& pm = *models[i];
               const uint32_t id = s.scene->addModel(pm.model, pm.tessellation, nullptr,
                                                     std::nullopt, fmt::format("model {}", i));
               if (id >= s.modelOfGeometry.size()) s.modelOfGeometry.resize(id + 1, -1);
               s.modelOfGeometry[id] = int64_t(i);
               s.entries.push_back({pm.model, pm.tessellation.trianglesPerPatch()});
             }
             s.scene->commit();
             return s;
           }),
           py::arg("models"))
      .def("__len__", [](const PyRayScene& s) { return s.entries.size(); })
      .def_property_readonly(
          "primitive_count", [](const PyRayScene& s) { return s.scene->primitiveCount(); },
          "Triangles and patches handed to Embree.")
      .def_property_readonly("geometry_bytes",
                             [](const PyRayScene& s) { return s.scene->geometryBytes(); })
      .def(
          "cast_rays",
          [](const PyRayScene& s, py::handle origins, py::handle directions, double tnear,
             double tfar, int threads) {
            const Rays rays = raysOf(origins, directions, tnear, tfar);
            threads = threadCount(threads);
            const py::ssize_t k = py::ssize_t(rays.count);
            py::array_t<double> t(k), position({k, py::ssize_t(3)}), geometric({k, py::ssize_t(3)}),
                shading({k, py::ssize_t(3)});
            py::array_t<int64_t> primitive(k), patch(k), geometry(k);
            double *pt = t.mutable_data(), *pp = position.mutable_data(),
                   *pg = geometric.mutable_data(), *ps = shading.mutable_data();
            int64_t *pprim = primitive.mutable_data(), *ppatch = patch.mutable_data(),
                    *pgeom = geometry.mutable_data();
            forEachHit(*s.scene, rays, threads,
                       [&](size_t i, const std::optional<SurfaceInteraction>& si) {
                         if (!si) {
                           pt[i] = kInfinity;
                           for (int c = 0; c < 3; ++c) {
                             pp[3 * i + c] = std::numeric_limits<double>::quiet_NaN();
                             pg[3 * i + c] = ps[3 * i + c] = 0.0;
                           }
                           pprim[i] = ppatch[i] = pgeom[i] = -1;
                           return;
                         }
                         pt[i] = si->t;
                         for (int c = 0; c < 3; ++c) {
                           pp[3 * i + c] = si->p[c];
                           pg[3 * i + c] = si->geometricNormal[c];
                           ps[3 * i + c] = si->shadingNormal[c];
                         }
                         const int64_t model = s.modelOfGeometry[si->geometryId];
                         pgeom[i] = model;
                         pprim[i] = si->primitive;
                         ppatch[i] = s.patchOf(size_t(model), si->primitive);
                       });
            py::dict out;
            out["t"] = t;
            out["position"] = position;
            out["geometric_normal"] = geometric;
            out["shading_normal"] = shading;
            out["primitive"] = primitive;
            out["patch"] = patch;
            out["geometry"] = geometry;
            return out;
          },
          py::arg("origins"), py::arg("directions"), py::arg("tnear") = 0.0,
          py::arg("tfar") = kInfinity, py::arg("threads") = 0, R"doc(
Nearest hit of every ray o + t d, t in (tnear, tfar), traced in parallel without the GIL on
`threads` threads (0: every core TBB offers), 16 consecutive rays at a time (a camera's rays
in pixel order share Embree's traversal); the hits do not depend on the thread count.
origins and directions are (k, 3) float arrays (or one of them (3,), shared by every ray);
directions need not be unit, t is in units of their length. Returns a dict of arrays:

  t                 (k,)   the hit's ray parameter; inf where the ray misses
  position          (k, 3) the hit point as the renderer takes it (on a quadric patch to double
                           precision, in a triangle's plane); NaN on a miss
  geometric_normal  (k, 3) unit; the triangle's winding or the patch's oriented gradient, not
                           flipped towards the ray; 0 on a miss
  shading_normal    (k, 3) unit: the interpolated normal (shading, tessellated models), the
                           patch's normal (implicit models; an edge bridge's mean of its two
                           patches'), the face normal (flat); 0 on a miss
  primitive         (k,)   int64: the triangle of the render geometry (input triangles, or the
                           tessellation's), or the patch (implicit; >= patch_count: a bridge), or
                           the Bézier piece (bezier); -1 on a miss
  patch             (k,)   int64: the input triangle the hit belongs to; -1 on a miss or a bridge
  geometry          (k,)   int64: the index of the hit model in the list; -1 on a miss
)doc")
      .def(
          "occluded",
          [](const PyRayScene& s, py::handle origins, py::handle directions, double tnear,
             double tfar, int threads) {
            const Rays rays = raysOf(origins, directions, tnear, tfar);
            threads = threadCount(threads);
            py::array_t<bool> out(py::ssize_t(rays.count));
            bool* po = out.mutable_data();
            forEachRay(rays.count, threads,
                       [&](size_t i) { po[i] = s.scene->occluded(rays.ray(i)); });
            return out;
          },
          py::arg("origins"), py::arg("directions"), py::arg("tnear") = 0.0,
          py::arg("tfar") = kInfinity, py::arg("threads") = 0,
          "(k,) bool: whether anything is hit in (tnear, tfar), as for shadow rays; on `threads` "
          "threads as cast_rays.");
}

}  // namespace quadtri::python
