// <shape type="obj|ply|rectangle|cube|sphere">.
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
//   <shape type="sphere"><point name="center" value="0, 1, 0"/><float name="radius" value="0.5"/>
//     <emitter type="area"><rgb name="radiance" value="10"/></emitter>
//   </shape>
#include <fmt/ranges.h>

#include <algorithm>

#include "properties.h"
#include "quadtri/surface/model.h"
#include "scene_parser.h"

namespace quadtri {

namespace {

void parseMeshParameters(ObjectProperties& props, ShapeDesc& desc) {
  const std::string filename = props.getString("filename");
  if (filename.empty()) props.fail("filename", "must name a file");
  const std::filesystem::path folder = props.element().file->path().parent_path();
  desc.filename = folder / filename;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(desc.filename, ec))
    props.fail("filename", "'{}' is not a readable file", desc.filename.string());
  const std::string normals = props.getString("normals", "file");
  if (normals != "file" && normals != "average" && normals != "angle")
    props.fail("normals", "'{}' is not a normal source; expected file, average or angle", normals);
  desc.normals.source = parseNormalSource(normals);
  if (props.has("crease_angle")) {
    if (desc.normals.source == NormalSource::Average)
      props.fail("crease_angle", "applies to angle-weighted normals, not to normals 'average'");
    desc.normals.creaseAngleDeg = props.getFloat("crease_angle");
    if (!(desc.normals.creaseAngleDeg >= 0.0 && desc.normals.creaseAngleDeg <= 180.0))
      props.fail("crease_angle", "{} is out of range: expected degrees from 0 to 180",
                 desc.normals.creaseAngleDeg);
  }
  desc.faceNormals = props.getBoolean("face_normals", false);
  desc.model = props.getString("model", "shading");
  const std::vector<std::string>& models = modelNames();
  if (std::find(models.begin(), models.end(), desc.model) == models.end())
    props.fail("model", "'{}' is not a model; expected one of {}", desc.model,
               fmt::join(models, ", "));
  // Tessellation::parse validates the text where the renderer builds the shape.
  desc.tessellation = props.getString("tessellation", "");
}

/// The BSDF a shape names by <ref> or nests, or the shared default diffuse 0.5.
size_t shapeBsdf(ObjectProperties& props, SceneParseState& state) {
  const std::optional<XmlElement> nested = props.takeOptional("bsdf");
  const std::optional<XmlElement> ref = props.takeOptional("ref");
  if (nested && ref) ref->fail("{} has both a nested <bsdf> and a <ref>", props.describe());
  if (nested) return parseBsdf(*nested, state);
  if (ref) return resolveBsdfRef(*ref, state);
  if (!state.defaultBsdf) {
    BsdfDesc diffuse;
    diffuse.location = "(default bsdf)";
    state.scene.bsdfs.push_back(diffuse);
    state.defaultBsdf = state.scene.bsdfs.size() - 1;
  }
  return *state.defaultBsdf;
}

}  // namespace

ShapeDesc parseShape(const XmlElement& element, SceneParseState& state) {
  ObjectProperties props(element, {"bsdf", "ref", "emitter"});
  ShapeDesc desc;
  desc.id = props.id();
  desc.location = props.location();
  const std::string& type = props.type();
  if (type == "obj" || type == "ply") {
    desc.type = type == "obj" ? ShapeDesc::Type::Obj : ShapeDesc::Type::Ply;
    parseMeshParameters(props, desc);
    props.ignore("flip_tex_coords", "quadtri reads no texture coordinates", state.scene.notes);
  } else if (type == "rectangle") {
    desc.type = ShapeDesc::Type::Rectangle;
  } else if (type == "cube") {
    desc.type = ShapeDesc::Type::Cube;
  } else if (type == "sphere") {
    desc.type = ShapeDesc::Type::Sphere;
  } else {
    element.fail("unknown shape type '{}'; expected obj, ply, rectangle, cube or sphere", type);
  }
  desc.flipNormals = props.getBoolean("flip_normals", false);
  desc.toWorld = props.getTransform("to_world").value_or(Mat4::Identity());
  if (desc.type == ShapeDesc::Type::Sphere) {
    // Mitsuba's sphere: to_world · translate(center) · scale(radius) of the unit sphere.
    const Vec3 center = props.getVector("center", Vec3(Vec3::Zero()));
    const double radius = props.getFloat("radius", 1.0);
    if (!(radius > 0.0)) props.fail("radius", "must be > 0, got {}", radius);
    Mat4 local = Mat4::Identity();
    local.diagonal().head<3>().setConstant(radius);
    local.block<3, 1>(0, 3) = center;
    desc.toWorld = desc.toWorld * local;
  }
  desc.bsdf = shapeBsdf(props, state);
  if (const std::optional<XmlElement> emitter = props.takeOptional("emitter"))
    desc.areaRadiance = parseAreaEmitter(*emitter, state.scene.notes);
  props.finish();
  state.declareId(desc.id, element);
  return desc;
}

}  // namespace quadtri
