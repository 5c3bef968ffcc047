#include "quadtri/scene/shape/builtin_shapes_xml.h"

#include "../legacy_key.h"
#include "../properties.h"
#include "../scene_parser.h"
#include "quadtri/render/render_scene.h"
#include "quadtri/surface/model_memory.h"
#include "shape_geometry.h"

namespace quadtri {

namespace {

// Mitsuba's rectangle [-1,1]² in z = 0 facing +z, and cube [-1,1]³ facing outwards.
TriangleMesh rectangleMesh() {
  TriangleMesh m;
  m.positions = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

TriangleMesh cubeMesh() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
  // Each face as a quad wound counter-clockwise seen from outside.
  const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

// Built-in meshes are `flat` triangles whatever --model says.
void addFlatShape(ShapeBuildContext& context, TriangleMesh mesh) {
  setModelBytes(context.budget, "flat", Tessellation{}, ModelUse::Render);
  addMeshShape(context, std::move(mesh), "flat", Tessellation{});
}

}  // namespace

void RectangleShapeParams::build(ShapeBuildContext& context) const {
  addFlatShape(context, rectangleMesh());
}

void CubeShapeParams::build(ShapeBuildContext& context) const {
  addFlatShape(context, cubeMesh());
}

void SphereShapeParams::build(ShapeBuildContext& context) const {
  const ShapeDesc& desc = context.desc;
  context.scene.addSphere(Vec3::Zero(), 1.0, desc.toWorld, desc.flipNormals, context.bsdf,
                          desc.areaRadiance, context.name);
}

std::shared_ptr<const SceneShapeParams> parseRectangleShape(ObjectProperties& props,
                                                            ShapeDesc& desc,
                                                            SceneParseState& /*state*/) {
  parseShapePlacement(props, desc);
  return std::make_shared<RectangleShapeParams>();
}

std::shared_ptr<const SceneShapeParams> parseCubeShape(ObjectProperties& props, ShapeDesc& desc,
                                                       SceneParseState& /*state*/) {
  parseShapePlacement(props, desc);
  return std::make_shared<CubeShapeParams>();
}

std::shared_ptr<const SceneShapeParams> parseSphereShape(ObjectProperties& props, ShapeDesc& desc,
                                                         SceneParseState& /*state*/) {
  parseShapePlacement(props, desc);
  // Mitsuba's sphere: to_world · translate(center) · scale(radius) of the unit sphere.
  const Vec3 center = props.getVector("center", Vec3(Vec3::Zero()));
  const double radius = props.getFloat("radius", 1.0);
  if (!(radius > 0.0)) props.fail("radius", "must be > 0, got {}", radius);
  Mat4 local = Mat4::Identity();
  local.diagonal().head<3>().setConstant(radius);
  local.block<3, 1>(0, 3) = center;
  desc.toWorld = desc.toWorld * local;
  return std::make_shared<SphereShapeParams>();
}

void RectangleShapeParams::addToKey(KeyWriter& key, std::string_view /*type*/) const {
  legacy_key::ShapeFields fields;
  fields.type = legacy_key::Shape::Rectangle;
  fields.write(key);
}

void CubeShapeParams::addToKey(KeyWriter& key, std::string_view /*type*/) const {
  legacy_key::ShapeFields fields;
  fields.type = legacy_key::Shape::Cube;
  fields.write(key);
}

void SphereShapeParams::addToKey(KeyWriter& key, std::string_view /*type*/) const {
  legacy_key::ShapeFields fields;
  fields.type = legacy_key::Shape::Sphere;
  fields.write(key);
}

}  // namespace quadtri
