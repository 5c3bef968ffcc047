// Triangle meshes from patches: the render geometry of the tessellated models.
#pragma once

#include <filesystem>
#include <string>

#include "quadtri/mesh/triangle_mesh.h"
#include "quadtri/surface/model.h"

namespace quadtri {

/// How finely each patch is tessellated.
struct Tessellation {
  enum class Kind {
    Lattice,     ///< triangle lattice of level n: (n+1)(n+2)/2 points, n² triangles per patch
    ThesisGrid,  ///< the thesis' 50×50 uv grid: 2500 points, 4802 triangles per patch (Table 5.1)
    Adaptive,    ///< the lattice of the lowest level within `tolerance` (resolveTessellation)
  } kind = Kind::Lattice;
  /// Lattice: its level; ThesisGrid: 50; Adaptive: the highest level it may pick.
  int level = 8;
  /// Adaptive: how far the lattice's flat triangles may stray from the surface, as a share of
  /// the mesh's bounding-box diagonal.
  double tolerance = 0.0;

  static constexpr double kDefaultTolerance = 1e-4;
  static constexpr int kMaxAdaptiveLevel = 8;

  static Tessellation thesis() { return {Kind::ThesisGrid, 50}; }
  static Tessellation adaptive(double tolerance = kDefaultTolerance) {
    return {Kind::Adaptive, kMaxAdaptiveLevel, tolerance};
  }
  /// Parses "N" (lattice level), "thesis", "auto" or "auto:TOLERANCE".
  static Tessellation parse(const std::string& text);
  /// Triangles per patch; for Adaptive, at its lowest level, 1 (what it costs at least: the
  /// memory budget charges the rest once the level is known, chargeResolvedTessellation).
  size_t trianglesPerPatch() const;
};

/// Level 1's distance from the surface, over every patch of `model`: how far the flat
/// triangle through a patch's corners strays from the patch (an estimate, see
/// resolveTessellation).
double levelOneDeviation(const SurfaceModel& model);

/// The tessellation `tessellation` stands for on `model`: itself, unless it is Adaptive. Then
/// the lattice of the lowest level n (1 to tessellation.level) at which levelOneDeviation / n²
/// is within tolerance times the mesh's bounding-box diagonal: a patch's distance from its
/// lattice's triangles shrinks as 1/n², exactly for quadratic patches. Coarse meshes get
/// the highest level, dense ones few triangles per patch.
Tessellation resolveTessellation(const SurfaceModel& model, const Tessellation& tessellation);

/// The tessellation `model` is rendered with: resolveTessellation for a tessellated model, and
/// `tessellation` as it is for the others, which are traced as they are (no lattice to pick).
Tessellation renderTessellation(const SurfaceModel& model, const Tessellation& tessellation);

/// Evaluates every patch of `model` on the tessellation's points (an Adaptive one resolved
/// first) and triangulates them. Vertex
/// normals are the model's surface normals. When model.sharesEdges(), points on a mesh edge and
/// at mesh vertices are created once and shared by both patches (welded), so the tessellation
/// of a closed mesh is closed; where the mesh splits normals (on such an edge or at such a
/// vertex) each patch keeps its own surface normal there (per-corner normals), so a crease
/// stays sharp in shading. InputTriangles models return their mesh unchanged.
TriangleMesh tessellate(const SurfaceModel& model, const Tessellation& tessellation);

/// Writes tessellate(model, tessellation) to an OBJ or PLY file (saveMesh's formats) and
/// returns its triangle count, never building the surface whole: its points are numbered first
/// (a few bytes per patch and per welded point), and so are its crease normals (where a crease
/// gives a welded point another normal on one side, counted per patch); then the points are
/// evaluated and written a block of patches at a time, their positions and normals (OBJ
/// evaluates them twice: its normals follow all its positions), the crease normals, and the
/// triangles (saveMeshStream). The OBJ bytes are saveMesh's; a PLY file lists its vertices in
/// point order, a crease normal's vertex after them. A block holds about `blockPoints` points
/// (at least one patch).
inline constexpr size_t kTessellationBlockPoints = size_t(1) << 20;
size_t saveTessellation(const SurfaceModel& model, const Tessellation& tessellation,
                        const std::filesystem::path& path,
                        size_t blockPoints = kTessellationBlockPoints);

}  // namespace quadtri
