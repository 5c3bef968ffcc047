// One interface for every way of turning a triangle mesh into render primitives (docs/DESIGN.md
// §3).
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "quadtri/mesh/triangle_mesh.h"

namespace quadtri {

struct QuadricPatch;
struct BezierTriangle;
class PatchRecord;

/// A point on a model's surface with its unit geometric normal, oriented to the side of the
/// mesh's shading normals.
struct SurfacePoint {
  Vec3 position;
  Vec3 normal;
};

/// How the renderer and the crack-rate analysis draw a model.
enum class Representation {
  InputTriangles,  ///< the mesh's own triangles (flat, shading, shading-offset)
  Tessellated,     ///< a triangle lattice evaluated on each patch (tessellate.h)
  Implicit,        ///< quadric patches intersected directly (quadric_patch.h)
  Bezier,          ///< quartic Bézier pieces intersected directly (bezier_triangle.h)
};

/// A mesh converted by one model. Patch t corresponds to triangle t of the mesh and is
/// parametrised by barycentric (u, v): (0,0) is corner 0, (1,0) corner 1, (0,1) corner 2.
class SurfaceModel {
 public:
  explicit SurfaceModel(std::shared_ptr<const TriangleMesh> mesh) : mesh_(std::move(mesh)) {}
  virtual ~SurfaceModel() = default;
  SurfaceModel(const SurfaceModel&) = delete;
  SurfaceModel& operator=(const SurfaceModel&) = delete;

  virtual std::string_view name() const = 0;
  const TriangleMesh& mesh() const { return *mesh_; }
  const std::shared_ptr<const TriangleMesh>& meshPtr() const { return mesh_; }
  size_t patchCount() const { return mesh_->triangleCount(); }

  /// Position and unit geometric normal of patch t at barycentric (u, v).
  virtual SurfacePoint evaluate(size_t t, double u, double v) const = 0;
  /// evaluate(t, u, v).position; the parametric models skip the normal.
  virtual Vec3 position(size_t t, double u, double v) const { return evaluate(t, u, v).position; }
  /// out[i] = position(t, uv[i].x(), uv[i].y()) for i < count, bit for bit; the models that
  /// rebuild a patch from the mesh per call build it once here.
  virtual void positions(size_t t, const Vec2* uv, size_t count, Vec3* out) const {
    for (size_t i = 0; i < count; ++i) out[i] = position(t, uv[i].x(), uv[i].y());
  }

  /// out[i] = evaluate(t, uv[i].x(), uv[i].y()) for i < count, bit for bit; the models that
  /// rebuild a patch from the mesh per call build it once here.
  virtual void evaluateMany(size_t t, const Vec2* uv, size_t count, SurfacePoint* out) const {
    for (size_t i = 0; i < count; ++i) out[i] = evaluate(t, uv[i].x(), uv[i].y());
  }

  virtual Representation representation() const { return Representation::Tessellated; }
  /// True when neighbouring patches share their boundary curves, so a tessellation may weld
  /// boundary vertices (false only for reproductions that are known to crack).
  virtual bool sharesEdges() const { return true; }
  /// For InputTriangles: whether the renderer interpolates the mesh's shading normals.
  virtual bool interpolatesShadingNormals() const { return false; }
  /// For InputTriangles: whether rays leaving towards the shading normal's side start from the
  /// shadow-terminator offset point (shading_offset.h) instead of the hit.
  virtual bool liftsRayOrigins() const { return false; }
  /// Implicit models: what the renderer and the crack-rate analysis trace, the patches first
  /// (index t is patch t) and then any extra primitives that join them (edge bridges, see
  /// QuadricPatch::joins); empty for other models.
  virtual const std::vector<QuadricPatch>& renderPatches() const;
  /// Implicit models: their quadric patches, one per triangle (the first patchCount() of
  /// renderPatches()); empty otherwise.
  std::span<const QuadricPatch> quadricPatches() const;
  /// Bezier models: their pieces, each naming its triangle (BezierTriangle::triangle); empty
  /// otherwise.
  virtual const std::vector<BezierTriangle>& bezierPieces() const;
  /// Bytes of the model's own patch records (0 when it renders tessellated triangles).
  virtual size_t patchMemoryBytes() const { return 0; }
  /// Writes the data of patch t into `out`, an empty record (PatchRecord::clear), for `quadtri
  /// convert`'s JSON and binary patch outputs (see README, "Patch JSON").
  virtual void patchRecord(size_t t, PatchRecord& out) const = 0;
  /// patchRecord(t) as JSON.
  nlohmann::json patchJson(size_t t) const;

  /// Whether patch t gave up one of its constraints while the model was built (a fallback:
  /// a clamped edge control point, a patch replaced by its triangle's plane, ...; each model
  /// says which). Always false for models without such a path.
  bool fellBack(size_t t) const { return !fallbacks_.empty() && fallbacks_[t] != 0; }
  /// Number of patches t with fellBack(t).
  size_t fallbackCount() const { return fallbackCount_; }

 protected:
  /// Records which patches fell back: one flag per patch (or none, meaning no patch did).
  /// Recording changes nothing else about the model.
  void setFallbacks(std::vector<uint8_t> flags);

 private:
  std::shared_ptr<const TriangleMesh> mesh_;
  std::vector<uint8_t> fallbacks_;
  size_t fallbackCount_ = 0;
};

/// Every model name, in the order `--model all` lists them.
const std::vector<std::string>& modelNames();

/// Converts `mesh` with the named model; throws Error listing the valid names otherwise.
std::unique_ptr<SurfaceModel> makeModel(std::string_view name,
                                        std::shared_ptr<const TriangleMesh> mesh);

}  // namespace quadtri
