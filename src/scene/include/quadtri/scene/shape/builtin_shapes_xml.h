// Mitsuba's built-in shapes, placed by to_world (and flip_normals):
//
//   <shape type="rectangle"/>  <!-- [-1,1]² in z = 0, facing +z -->
//   <shape type="cube"/>       <!-- [-1,1]³, facing outwards -->
//   <shape type="sphere"><point name="center" value="0, 1, 0"/><float name="radius" value="0.5"/>
//     <emitter type="area"><rgb name="radiance" value="10"/></emitter>
//   </shape>
#pragma once

#include "quadtri/scene/plugin.h"

namespace quadtri {

/// The rectangle, as `flat` triangles.
struct RectangleShapeParams final : SceneShapeParams {
  std::string toString() const override { return {}; }
  /// The layout of quadtri 0.1.0's render keys (legacy_key.h).
  void addToKey(KeyWriter& key, std::string_view type) const override;
  void build(ShapeBuildContext& context) const override;
};

/// The cube, as `flat` triangles.
struct CubeShapeParams final : SceneShapeParams {
  std::string toString() const override { return {}; }
  /// The layout of quadtri 0.1.0's render keys (legacy_key.h).
  void addToKey(KeyWriter& key, std::string_view type) const override;
  void build(ShapeBuildContext& context) const override;
};

/// The analytic unit sphere; its center and radius are folded into the shape's to_world
/// (Mitsuba's to_world · translate(center) · scale(radius)).
struct SphereShapeParams final : SceneShapeParams {
  std::string toString() const override { return {}; }
  /// The layout of quadtri 0.1.0's render keys (legacy_key.h).
  void addToKey(KeyWriter& key, std::string_view type) const override;
  void build(ShapeBuildContext& context) const override;
};

std::shared_ptr<const SceneShapeParams> parseRectangleShape(ObjectProperties& props,
                                                            ShapeDesc& desc,
                                                            SceneParseState& state);
std::shared_ptr<const SceneShapeParams> parseCubeShape(ObjectProperties& props, ShapeDesc& desc,
                                                       SceneParseState& state);
std::shared_ptr<const SceneShapeParams> parseSphereShape(ObjectProperties& props, ShapeDesc& desc,
                                                         SceneParseState& state);

}  // namespace quadtri
