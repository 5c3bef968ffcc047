// Turns a validated SceneDescription into the objects that render it.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "quadtri/render/integrator/integrator.h"
#include "quadtri/render/render_scene.h"
#include "quadtri/render/renderer.h"
#include "quadtri/scene/scene_description.h"

namespace quadtri {

/// A scene ready to render, with the integrator and the sampler/film settings it asked for.
struct BuiltScene {
  std::unique_ptr<RenderScene> scene;
  std::shared_ptr<const Integrator> integrator;
  RenderOptions options;      ///< samplesPerPixel, seed and filter from the description
  size_t inputTriangles = 0;  ///< triangles of the obj/ply meshes before any model
  /// One line per obj/ply shape whose model folds or falls back more than the conversion
  /// warning allows (conversionWarning, corner_stats.h), naming the shape's element.
  std::vector<std::string> warnings;
  /// With deferModelChecks, the model checks not yet run, one per obj/ply shape whose model
  /// has patches (each holds its model, and so its mesh, until it is run): each gives what
  /// `warnings` would have held for it.
  std::vector<ModelCheck> modelChecks;
  /// The digest of every mesh file as its loader read it, for renderKeys (so that the render
  /// key does not read the files again).
  FileDigests fileDigests;
};

/// Builds every shape, BSDF and emitter. obj/ply meshes are loaded with their `normals`
/// (ShapeDesc::normals: a file without normals gets them split at the crease angle), placed by
/// to_world
/// (positions by the matrix, normals by its inverse transpose; a mirroring matrix reverses the
/// winding so the face normals keep agreeing with the shading normals) and converted by their
/// model, or by `modelOverride` when given; rectangles and cubes are `flat` triangle meshes;
/// spheres are analytic quadrics. Errors name the XML element's FILE:LINE. With maxMemoryBytes
/// (0: no limit), the image (renderImageBytes) and every mesh file with its model
/// (loadMesh's MemoryBudget, modelBytesPerTriangle for rendering) are charged against it before
/// they are built, and the first that would exceed it is refused with the estimate.
/// With deferModelChecks, the model checks of the mesh shapes whose models have patches are
/// left in BuiltScene::modelChecks instead of being run into BuiltScene::warnings.
BuiltScene buildScene(const SceneDescription& description,
                      const std::optional<std::string>& modelOverride = std::nullopt,
                      uint64_t maxMemoryBytes = 0, bool deferModelChecks = false);

}  // namespace quadtri
