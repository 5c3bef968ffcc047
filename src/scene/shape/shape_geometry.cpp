#include "shape_geometry.h"

#include <fmt/format.h>

#include "quadtri/mesh/mesh_io_check.h"
#include "quadtri/render/render_scene.h"
#include "quadtri/scene/scene_description.h"
#include "quadtri/surface/creases.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/model_memory.h"

namespace quadtri {

void transformMesh(TriangleMesh& mesh, const Mat4& toWorld, bool flipNormals) {
  const Mat3 linear = toWorld.topLeftCorner<3, 3>();
  const Vec3 translation = toWorld.topRightCorner<3, 1>();
  const Mat3 normalMatrix = linear.inverse().transpose();
  for (Vec3& p : mesh.positions) p = linear * p + translation;
  for (Vec3& n : mesh.normals)
    n = safeNormalized((flipNormals ? -1.0 : 1.0) * (normalMatrix * n), n);
  if ((linear.determinant() < 0.0) != flipNormals) {
    for (Tri& t : mesh.triangles) std::swap(t[1], t[2]);
    for (Tri& t : mesh.normalIndices) std::swap(t[1], t[2]);
    // The loader's edge adjacency names each side by its corners' order, which just changed
    // in place (the cache cannot see that: the array is the same).
    mesh.topologyCache.forget();
  }
}

std::shared_ptr<const SurfaceModel> addMeshShape(ShapeBuildContext& context, TriangleMesh mesh,
                                                 const std::string& model,
                                                 const Tessellation& tessellation) {
  const ShapeDesc& desc = context.desc;
  transformMesh(mesh, desc.toWorld, desc.flipNormals);
  const auto shared = std::make_shared<TriangleMesh>(std::move(mesh));
  std::shared_ptr<const SurfaceModel> converted = makeModel(model, shared);
  // A model traced as patches or pieces is done with the mesh's edge adjacency once built (the
  // loader's, 48 MB at a million triangles). Where its fold check waits until after the render
  // (context.modelChecks, as mesh_file_xml.cpp defers it) and will not read it (a mesh without
  // creases: edgeEndsNeedTopology), the adjacency is dropped here, so that it is not held
  // through the acceleration structure's build, the render's peak. A mesh with creases keeps
  // it: its check would build it again after the render, above the peak it saved.
  const Representation kind = converted->representation();
  // (The models that keep the input triangles have no check, and skip the corner pass.)
  const bool checkIsLater = context.modelChecks && kind != Representation::InputTriangles &&
                            !edgeEndsNeedTopology(*shared);
  if (checkIsLater && (kind == Representation::Implicit || kind == Representation::Bezier))
    shared->topologyCache.forget();
  const Tessellation resolved = renderTessellation(*converted, tessellation);
  const std::string name = fmt::format("{} ({})", desc.location, model);
  chargeResolvedTessellation(context.budget, model, tessellation, resolved, ModelUse::Render,
                             converted->patchCount(), name);
  // Long patches traced as parts (quadric_patch_parts.h) cost more than the model's
  // per-triangle charge, measured on meshes without them: charged once their count is known.
  const size_t partsBefore = context.scene.patchPartBytes();
  context.scene.addModel(converted, resolved, context.bsdf, desc.areaRadiance, context.name);
  // A tessellated model reads the adjacency while its lattice is welded, in addModel.
  if (checkIsLater && kind == Representation::Tessellated) shared->topologyCache.forget();
  if (const size_t parts = context.scene.patchPartBytes() - partsBefore)
    chargeMemory(context.budget, parts, name, "tracing its long patches in parts");
  return converted;
}

}  // namespace quadtri
