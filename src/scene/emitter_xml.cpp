// <emitter type="point|area|constant">.
//
//   <emitter type="point">
//     <rgb name="intensity" value="10"/>  <!-- W/sr -->
//     <point name="position" x="0" y="1.9" z="0"/>  <!-- or a to_world transform -->
//   </emitter>
//   <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
//   <shape type="rectangle"> <emitter type="area"><rgb name="radiance" value="5"/></emitter>
//   </shape>
#include "properties.h"
#include "scene_parser.h"

namespace quadtri {

namespace {

Color nonNegativeColor(ObjectProperties& props, std::string_view name,
                       std::optional<Color> fallback) {
  const Color c = props.getColor(name, fallback);
  if (!(c >= 0.0).all()) props.fail(name, "must be >= 0, got {}, {}, {}", c[0], c[1], c[2]);
  return c;
}

}  // namespace

EmitterDesc parseEmitter(const XmlElement& element, std::vector<std::string>& notes) {
  ObjectProperties props(element, {});
  // Mitsuba's relative chance of picking this light: it changes the noise, not the image.
  props.ignore("sampling_weight", "quadtri picks lights by their power", notes);
  EmitterDesc desc;
  desc.location = props.location();
  if (props.type() == "point") {
    desc.type = EmitterDesc::Type::Point;
    desc.intensity = nonNegativeColor(props, "intensity", Color(Color::Ones()));
    const Vec3 position = props.getVector("position", Vec3(Vec3::Zero()));
    const std::optional<Mat4> toWorld = props.getTransform("to_world");
    if (toWorld && props.has("position"))
      props.fail("position", "and to_world both given; use one of them");
    desc.position = toWorld ? Vec3(toWorld->block<3, 1>(0, 3)) : position;
  } else if (props.type() == "constant") {
    desc.type = EmitterDesc::Type::Constant;
    desc.radiance = nonNegativeColor(props, "radiance", Color(Color::Ones()));
  } else if (props.type() == "area") {
    element.fail("emitter 'area' must be nested inside a <shape>");
  } else {
    element.fail("unknown emitter type '{}'; expected point, area (inside a shape) or constant",
                 props.type());
  }
  props.finish();
  return desc;
}

Color parseAreaEmitter(const XmlElement& element, std::vector<std::string>& notes) {
  ObjectProperties props(element, {});
  props.ignore("sampling_weight", "quadtri picks lights by their power", notes);
  if (props.type() != "area")
    element.fail("a <shape> may only contain an emitter of type 'area', got '{}'", props.type());
  const Color radiance = nonNegativeColor(props, "radiance", Color(Color::Ones()));
  props.finish();
  return radiance;
}

}  // namespace quadtri
