#include "quadtri/scene/shape/mesh_file_xml.h"

#include <fmt/ranges.h>

#include <algorithm>

#include "../legacy_key.h"
#include "../properties.h"
#include "../scene_parser.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/surface/corner_stats.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/model_memory.h"
#include "shape_geometry.h"

namespace quadtri {

std::string MeshFileShapeParams::toString() const {
  return fmt::format(" filename={} model={} tessellation={} face_normals={}", filename.string(),
                     model, tessellation.empty() ? "auto" : tessellation, faceNormals);
}

void MeshFileShapeParams::build(ShapeBuildContext& context) const {
  const std::string& chosen = context.modelOverride ? *context.modelOverride : model;
  const Tessellation tess =
      tessellation.empty() ? Tessellation::adaptive() : Tessellation::parse(tessellation);
  setModelBytes(context.budget, chosen, tess, ModelUse::Render);
  TriangleMesh mesh = loadMesh(filename, normals, &context.budget);
  if (faceNormals) {
    mesh.normals.clear();
    mesh.normalIndices.clear();
  }
  context.inputTriangles += mesh.triangleCount();
  if (mesh.fileDigest.bytes > 0) context.fileDigests[filename] = mesh.fileDigest;
  if (std::optional<std::string> repaired =
          repairWarning(mesh, fmt::format("{} {}", context.desc.location, filename.string())))
    context.warnings.push_back(std::move(*repaired));
  const std::shared_ptr<const SurfaceModel> converted =
      addMeshShape(context, std::move(mesh), chosen, tess);
  ModelCheck check = [converted,
                      label = fmt::format("{} {}", context.desc.location, filename.string())] {
    return conversionWarning(*converted, label);
  };
  // Deferred for every model with patches: the check evaluates every corner, a tenth to a
  // fifth of a tessellated model's time to the first pixel. The model is then held past the
  // build with its mesh (on a million-triangle torus quadric-param's peak went from 393 to
  // 429 MiB; pn, phong and nagata keep nothing per triangle on a smooth mesh).
  const Representation kind = converted->representation();
  if (context.modelChecks && kind != Representation::InputTriangles) {
    context.modelChecks->push_back(std::move(check));
  } else if (std::optional<std::string> warning = check()) {
    context.warnings.push_back(std::move(*warning));
  }
}

std::shared_ptr<const SceneShapeParams> MeshFileShapeParams::withNormals(
    std::optional<NormalSource> source, std::optional<double> creaseDeg) const {
  auto params = std::make_shared<MeshFileShapeParams>(*this);
  if (source) params->normals.source = *source;
  if (creaseDeg) params->normals.creaseAngleDeg = *creaseDeg;
  return params;
}

std::shared_ptr<const SceneShapeParams> parseMeshFileShape(ObjectProperties& props, ShapeDesc& desc,
                                                           SceneParseState& state) {
  auto params = std::make_shared<MeshFileShapeParams>();
  const std::string filename = props.getString("filename");
  if (filename.empty()) props.fail("filename", "must name a file");
  const std::filesystem::path folder = props.element().file->path().parent_path();
  params->filename = folder / filename;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(params->filename, ec))
    props.fail("filename", "'{}' is not a readable file", params->filename.string());
  const std::string normals = props.getString("normals", "file");
  if (normals != "file" && normals != "average" && normals != "angle")
    props.fail("normals", "'{}' is not a normal source; expected file, average or angle", normals);
  params->normals.source = parseNormalSource(normals);
  if (props.has("crease_angle")) {
    if (params->normals.source == NormalSource::Average)
      props.fail("crease_angle", "applies to angle-weighted normals, not to normals 'average'");
    params->normals.creaseAngleDeg = props.getFloat("crease_angle");
    if (!(params->normals.creaseAngleDeg >= 0.0 && params->normals.creaseAngleDeg <= 180.0))
      props.fail("crease_angle", "{} is out of range: expected degrees from 0 to 180",
                 params->normals.creaseAngleDeg);
  }
  params->faceNormals = props.getBoolean("face_normals", false);
  params->model = props.getString("model", "shading");
  const std::vector<std::string>& models = modelNames();
  if (std::find(models.begin(), models.end(), params->model) == models.end())
    props.fail("model", "'{}' is not a model; expected one of {}", params->model,
               fmt::join(models, ", "));
  // Tessellation::parse validates the text where the renderer builds the shape.
  params->tessellation = props.getString("tessellation", "");
  props.ignore("flip_tex_coords", "quadtri reads no texture coordinates", state.scene.notes);
  parseShapePlacement(props, desc);
  return params;
}

void MeshFileShapeParams::addToKey(KeyWriter& key, std::string_view type) const {
  legacy_key::ShapeFields fields;
  fields.type = type == "ply" ? legacy_key::Shape::Ply : legacy_key::Shape::Obj;
  fields.file = filename;
  fields.model = model;
  // No tessellation named meant level 8 before `auto` became the default: the key names `auto`,
  // so a render state or tile of the old default is not resumed or merged with the new one
  // (and naming `auto` gives the same key as naming nothing).
  fields.tessellation = tessellation.empty() ? "auto" : tessellation;
  fields.normals = normals;
  fields.faceNormals = faceNormals;
  fields.write(key);
}

}  // namespace quadtri
