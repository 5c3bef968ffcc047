// <shape type="obj"> (or "ply"): a mesh file converted by a model.
//
//   <shape type="obj">
//     <string name="filename" value="meshes/teapot.obj"/>  <!-- relative to the XML file -->
//     <string name="model" value="quadric-implicit"/>      <!-- quadtri: see modelNames() -->
//     <string name="tessellation" value="8"/>              <!-- quadtri: N or "thesis" -->
//     <string name="normals" value="file"/>                 <!-- quadtri: file, average, angle -->
//     <float name="crease_angle" value="30"/>               <!-- quadtri: degrees, 0 to 180 -->
//     <boolean name="face_normals" value="false"/> <boolean name="flip_normals" value="false"/>
//     <transform name="to_world"> ... </transform>
//     <ref id="glass"/>                                     <!-- or a nested <bsdf> -->
//   </shape>
#pragma once

#include "quadtri/scene/plugin.h"

namespace quadtri {

/// A mesh file (any format loadMesh reads; registered as obj and ply) under a model.
struct MeshFileShapeParams final : SceneShapeParams {
  std::filesystem::path filename;  ///< resolved against the scene file's folder
  std::string model = "shading";   ///< a name from modelNames()
  /// "N", "thesis", "auto" or "auto:TOLERANCE" for Tessellation::parse; empty for "auto".
  std::string tessellation;
  /// The shading normals (`normals`: file, average or angle; `crease_angle` in degrees, for
  /// normals computed angle-weighted: a file without normals, or `angle`).
  NormalOptions normals;
  bool faceNormals = false;

  std::string toString() const override;
  /// Loads the mesh (charged to the memory budget with its model), converts it with the model
  /// (or --model) and adds it; a model that folds or falls back adds a warning.
  void build(ShapeBuildContext& context) const override;
  std::vector<std::filesystem::path> files() const override { return {filename}; }
  /// The layout of quadtri 0.1.0's render keys (legacy_key.h), the file's bytes included.
  void addToKey(KeyWriter& key, std::string_view type) const override;
  std::shared_ptr<const SceneShapeParams> withNormals(
      std::optional<NormalSource> source, std::optional<double> creaseDeg) const override;
};

std::shared_ptr<const SceneShapeParams> parseMeshFileShape(ObjectProperties& props, ShapeDesc& desc,
                                                           SceneParseState& state);

}  // namespace quadtri
