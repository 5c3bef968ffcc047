// Moves of each patch's quadric along its pencil q + μL² (corners and their normals stay), and
// the separator plane between neighbours, for `quadric-implicit-robust`.
#pragma once

#include <array>
#include <vector>

#include "quadtri/mesh/topology.h"
#include "quadtri/surface/edge_curves.h"
#include "quadtri/surface/quadric_patch.h"

namespace quadtri {

/// Moves every patch along its pencil, q_t + μ_t p_t, so that neighbours pass at the same
/// signed distance from each shared edge's arc midpoint (sparse least squares, regularised
/// toward μ = 0 and held there where the corner-normal error shows generic data).
void agreeAcrossEdges(const TriangleMesh& mesh, const MeshTopology& topo,
                      const std::vector<Vec3>& arcMidpoints,
                      const std::vector<std::array<Vec3, 3>>& controlPoints,
                      const std::vector<QuadricCoeffs>& pencils,
                      const std::vector<double>& cornerNormalErrorDeg,
                      std::vector<QuadricPatch>& patches);

/// Replaces q by the graph member q + λ·pencil (quadratic form zero along n) where some line
/// along n through the parametric patch misses q or meets it facing away from n.
void coverTriangle(const QuadraticPatch& parametric, const Vec3& n, const QuadricCoeffs& pencil,
                   QuadricCoeffs& q);

/// Turns the edge plane (through va, vb; `direction` in it, perpendicular to the chord) about
/// the chord onto the plane of the line pair a − κb, when that is real and within 30°.
void alignWithCrossing(const QuadricCoeffs& a, const QuadricCoeffs& b, const Vec3& va,
                       const Vec3& vb, Vec4& plane, Vec3& direction);

}  // namespace quadtri
