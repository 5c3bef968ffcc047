// Built-in shapes with their true analytic surface, so models can be measured against it.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "quadtri/mesh/triangle_mesh.h"

namespace quadtri {

/// The surface a built-in mesh samples: sphere (radius a), ellipsoid (semi-axes a, b, c),
/// torus (major radius a, minor radius b, around the z axis), the genus-2 "pretzel"
/// f = (x⁴ − x² + y²)² + z² − a² = 0, a tube around Gerono's figure-eight lemniscate
/// y² = x² − x⁴ (two holes for 0 < a < 1/4), or, with creases, an axis-aligned box centred at
/// the origin (half extents a, b, c) or a capped cylinder around the z axis (radius a, z from
/// −b to b).
struct AnalyticSurface {
  enum class Kind { Sphere, Ellipsoid, Torus, Genus2, Box, Cylinder } kind = Kind::Sphere;
  double a = 1, b = 1, c = 1;

  /// Unsigned distance from p to the surface. Genus2: to the nearest surface point found by
  /// Newton's iteration along ∇f from p (isosurface.h) followed by 8 rounds of projecting p
  /// onto the tangent plane there and Newton again; always an upper bound (every candidate is
  /// on the surface), converged near the surface. Where Newton fails, |f|/|∇f|.
  double distance(const Vec3& p) const;
  /// Outward unit normal at the surface point nearest to p (exact for points on the surface;
  /// on a box's or cylinder's crease, the normal of one of the faces that meet there).
  Vec3 normal(const Vec3& p) const;
  /// Characteristic size used to make distances relative: the largest extent's half.
  double size() const;
};

struct BuiltinMesh {
  TriangleMesh mesh;
  std::optional<AnalyticSurface> truth;  ///< none for shapes that sample no smooth surface
  std::string description;
};

/// Parameters of a built-in shape; unused fields are ignored by shapes that do not take them.
struct ShapeParams {
  int level = 2;      ///< icosphere subdivision level (20·4^level triangles)
  int segments = 32;  ///< uv-sphere, torus, cylinder: divisions around the axis
  int rings = 16;     ///< uv-sphere, torus: divisions along the profile; cylinder: along its height
  Vec3 radii{1.0, 0.7, 0.5};         ///< ellipsoid semi-axes
  double major = 1.0, minor = 0.35;  ///< torus radii
  int cells = 24;                    ///< genus2: marching-tetrahedra cells along its length
  int divisions = 1;  ///< cube: divisions of each edge (2·divisions² triangles a face)
  /// Normals from the true surface (split at a cube's or cylinder's creases: each face, cap
  /// and the side carry their own); otherwise thesis eq. 2.8.
  bool analyticNormals = true;
};

/// Names accepted by makeBuiltin, in the order the CLI lists them.
const std::vector<std::string>& builtinShapeNames();

/// Builds a shape by name: triangle, tetrahedron, icosahedron, icosphere, uv-sphere,
/// ellipsoid, torus, genus2 (the pretzel of AnalyticSurface with tube a = 0.2, meshed by
/// marching tetrahedra: irregular triangles, slivers, saddles, valences 4 to 8), cube (the box
/// [−1, 1]³, each face a grid of `divisions`² squares cut into two triangles) or cylinder
/// (radius 1, z from −1 to 1, `segments` around and `rings` along the side, each cap a fan
/// around its centre). Polyhedra are inscribed in the unit sphere and carry the sphere's
/// normals at their vertices (as the thesis' scenes do); the cube and the cylinder carry split
/// normals, one per face, per cap and the side's radial ones, so their creases stay sharp.
/// Throws Error for an unknown name or bad parameters: a level outside 0 to 8, segments × rings
/// over 2^20, a radius outside 1e-6 to 1e6 (or not finite), a count that is not a whole number.
BuiltinMesh makeBuiltin(std::string_view name, const ShapeParams& params = {});

/// Parses "NAME" or "NAME:ARGS" (icosphere:3, uv-sphere:32,16, ellipsoid:1,0.7,0.5,
/// torus:1,0.35, torus:1,0.35,48,24, genus2:CELLS, cube:DIVISIONS or cylinder:SEGMENTS[,RINGS])
/// into a built-in mesh; nullopt when NAME is not a built-in shape.
std::optional<BuiltinMesh> parseBuiltinSpec(std::string_view spec);

/// A built-in shape spec parsed but not built: its name and parameters.
struct ShapeSpec {
  std::string name;
  ShapeParams params;
};

/// Parses a spec as parseBuiltinSpec does, without building it; nullopt when NAME is not a
/// built-in shape. Throws Error for malformed numbers.
std::optional<ShapeSpec> parseShapeSpec(std::string_view spec);

/// The triangles makeBuiltin builds for the shape, known before it is built, so that a memory
/// budget can refuse it first; 0 where makeBuiltin refuses the parameters. Exact except for
/// genus2, where it is 16·cells², above the 10.2·cells² measured for 8 to 128 cells.
uint64_t builtinTriangleCount(const ShapeSpec& shape);

}  // namespace quadtri
