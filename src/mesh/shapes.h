// Built-in shapes with their true analytic surface, so models can be measured against it.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "mesh/triangle_mesh.h"

namespace quadtri {

/// The smooth surface a built-in mesh samples: sphere (radius a), ellipsoid (semi-axes a, b,
/// c) or torus (major radius a, minor radius b, around the z axis).
struct AnalyticSurface {
  enum class Kind { Sphere, Ellipsoid, Torus } kind = Kind::Sphere;
  double a = 1, b = 1, c = 1;

  /// Unsigned distance from p to the surface.
  double distance(const Vec3& p) const;
  /// Outward unit normal at the surface point nearest to p (exact for points on the surface).
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
  int level = 2;                     ///< icosphere subdivision level (20·4^level triangles)
  int segments = 32;                 ///< uv-sphere and torus: divisions around the main axis
  int rings = 16;                    ///< uv-sphere and torus: divisions along the profile
  Vec3 radii{1.0, 0.7, 0.5};         ///< ellipsoid semi-axes
  double major = 1.0, minor = 0.35;  ///< torus radii
  bool analyticNormals = true;       ///< normals from the true surface; otherwise thesis eq. 2.8
};

/// Names accepted by makeBuiltin, in the order the CLI lists them.
const std::vector<std::string>& builtinShapeNames();

/// Builds a shape by name: triangle, tetrahedron, icosahedron, icosphere, uv-sphere,
/// ellipsoid, torus. Polyhedra are inscribed in the unit sphere and carry the sphere's normals
/// at their vertices (as the thesis' scenes do). Throws Error for an unknown name or bad
/// parameters.
BuiltinMesh makeBuiltin(std::string_view name, const ShapeParams& params = {});

/// Parses "NAME" or "NAME:ARGS" (icosphere:3, uv-sphere:32,16, ellipsoid:1,0.7,0.5,
/// torus:1,0.35 or torus:1,0.35,48,24) into a built-in mesh; nullopt when NAME is not a
/// built-in shape.
std::optional<BuiltinMesh> parseBuiltinSpec(std::string_view spec);

}  // namespace quadtri
