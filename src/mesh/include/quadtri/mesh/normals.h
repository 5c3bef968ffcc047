// Vertex shading normals for meshes whose file has none.
#pragma once

#include <string_view>

#include "quadtri/mesh/triangle_mesh.h"

namespace quadtri {

enum class NormalSource {
  /// Keep the file's normals; a file without normals gets angle-weighted normals split at the
  /// crease angle (computeCreaseNormals), as a modelling tool's auto-smooth makes them.
  File,
  Average,  ///< thesis eq. 2.8: normalised sum of the unit normals of the adjacent faces
  /// Face normals weighted by the corner angle (Thürmer and Wüthrich 1998), split at the crease
  /// angle (computeCreaseNormals).
  Angle,
};

/// Modelling tools' auto-smooth angle: edges sharper than this get split normals.
inline constexpr double kDefaultCreaseAngleDeg = 30.0;

/// Which normals a mesh gets (`--normals`) and where computed angle-weighted ones are split
/// (`--crease-angle`). Converts implicitly from a NormalSource with the default crease angle.
struct NormalOptions {
  NormalSource source = NormalSource::File;
  double creaseAngleDeg = kDefaultCreaseAngleDeg;

  NormalOptions() = default;
  NormalOptions(NormalSource s, double creaseDeg = kDefaultCreaseAngleDeg)  // NOLINT: implicit
      : source(s), creaseAngleDeg(creaseDeg) {}
};

NormalSource parseNormalSource(std::string_view name);

/// Throws Error unless 0 ≤ degrees ≤ 180 (names `--crease-angle` in the message).
void checkCreaseAngle(double degrees);

/// Replaces the mesh's normals by one smooth normal per vertex. A vertex whose weighted sum
/// vanishes (e.g. a needle of opposite faces) gets the normal of its first adjacent face.
void computeVertexNormals(TriangleMesh& mesh, NormalSource source);

/// Replaces the mesh's normals by angle-weighted normals split at creases. Around each vertex
/// the faces fall into smooth fans: two faces that share an edge at the vertex are in the same
/// fan when the angle between their face normals is at most `creaseAngleDeg` (180: no angle
/// splits). Boundary and non-manifold edges (one side, or more than two) always end a fan, and
/// so does a zero-area face, which carries no direction: it gets the vertex's unsplit
/// angle-weighted normal. Each fan gets the normalised angle-weighted sum of its face normals,
/// stored once and indexed by its corners (normalIndices), so a crease stays split while the
/// positions stay welded. Where a vertex has one fan this is computeVertexNormals(Angle) bit
/// for bit. Throws Error for an angle outside [0, 180].
void computeCreaseNormals(TriangleMesh& mesh, double creaseAngleDeg = kDefaultCreaseAngleDeg);

/// Computes the normals `options` asks for: File keeps a mesh's normals and computes crease
/// normals only when it has none, Average is computeVertexNormals(Average), Angle is
/// computeCreaseNormals.
void applyNormals(TriangleMesh& mesh, const NormalOptions& options);

}  // namespace quadtri
