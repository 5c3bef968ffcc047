// The shadow-terminator offset of `shading-offset` (Hanika 2021, "Hacking the shadow terminator",
// Ray Tracing Gems II, ch. 4): ray origins lifted from the flat triangle onto a smooth height
// field that its vertex normals describe.
#pragma once

#include <array>

#include "quadtri/mesh/triangle_mesh.h"

namespace quadtri {

/// The point p = Σ bᵢvᵢ of triangle (v₀, v₁, v₂) lifted by its unit vertex normals nᵢ:
/// p' = Σ bᵢ (vᵢ + tᵢ) with tᵢ = p − vᵢ, less its component along nᵢ where p lies below vᵢ's
/// tangent plane (tᵢ·nᵢ < 0). So p' = p + Σ bᵢ max(0, −tᵢ·nᵢ) nᵢ: p at the corners, p on flat
/// data, lifted towards the normals on convex regions, never moved on concave ones. Normals
/// are normalised here. Returns p exactly for a degenerate triangle (area below 1e-12 of its
/// squared edge lengths), a zero or non-finite normal, a non-finite result, or a lift that would
/// put p' below the triangle's plane (the side the normals' sum faces), which only normals
/// facing away from their triangle can cause.
Vec3 shadingOffsetPoint(const std::array<Vec3, 3>& v, const std::array<Vec3, 3>& n, const Vec3& b);

/// shadingOffsetPoint for triangle t of `mesh` (its corner normals) at barycentrics b.
Vec3 shadingOffsetPoint(const TriangleMesh& mesh, size_t t, const Vec3& b);

}  // namespace quadtri
