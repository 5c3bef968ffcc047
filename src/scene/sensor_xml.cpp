// <sensor type="perspective">, <film type="hdrfilm">, <rfilter>, <sampler type="independent">.
//
//   <sensor type="perspective">
//     <float name="fov" value="45"/>                 <!-- degrees, required -->
//     <string name="fov_axis" value="x"/>            <!-- x|y|diagonal|smaller|larger -->
//     <float name="near_clip" value="0.01"/> <float name="far_clip" value="10000"/>
//     <transform name="to_world"><lookat origin="0,0,4" target="0,0,0" up="0,1,0"/></transform>
//     <film type="hdrfilm">
//       <integer name="width" value="768"/> <integer name="height" value="576"/>
//       <rfilter type="gaussian"><float name="stddev" value="0.5"/></rfilter>
//     </film>
//     <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
//   </sensor>
#include <cmath>

#include "properties.h"
#include "scene_parser.h"

namespace quadtri {

namespace {

/// Largest image side accepted, so that width·height stays within a 32-bit pixel index.
constexpr long long kMaxImageSide = 1 << 15;

void checkType(const ObjectProperties& props, std::string_view expected) {
  if (props.type() != expected)
    props.element().fail("unknown {} type '{}'; expected {}", props.element().tag(), props.type(),
                         expected);
}

FilterDesc parseFilter(const XmlElement& element) {
  ObjectProperties props(element, {});
  FilterDesc filter;
  if (props.type() == "box") {
    filter.type = FilterDesc::Type::Box;
  } else if (props.type() == "gaussian") {
    filter.type = FilterDesc::Type::Gaussian;
    filter.stddev = props.getFloat("stddev", 0.5);
    if (!(filter.stddev > 0.0)) props.fail("stddev", "must be > 0, got {}", filter.stddev);
  } else {
    element.fail("unknown rfilter type '{}'; expected box or gaussian", props.type());
  }
  props.finish();
  return filter;
}

FilmDesc parseFilm(const XmlElement& element) {
  ObjectProperties props(element, {"rfilter"});
  checkType(props, "hdrfilm");
  FilmDesc film;
  film.location = props.location();
  const long long width = props.getInteger("width", 768);
  const long long height = props.getInteger("height", 576);
  if (width < 1 || width > kMaxImageSide)
    props.fail("width", "must be in [1, {}], got {}", kMaxImageSide, width);
  if (height < 1 || height > kMaxImageSide)
    props.fail("height", "must be in [1, {}], got {}", kMaxImageSide, height);
  film.width = int(width);
  film.height = int(height);
  if (const std::optional<XmlElement> filter = props.takeOptional("rfilter"))
    film.filter = parseFilter(*filter);
  props.finish();
  return film;
}

SamplerDesc parseSampler(const XmlElement& element) {
  ObjectProperties props(element, {});
  checkType(props, "independent");
  SamplerDesc sampler;
  sampler.location = props.location();
  const long long count = props.getInteger("sample_count", 4);
  if (count < 1 || count > (1 << 24))
    props.fail("sample_count", "must be in [1, {}], got {}", 1 << 24, count);
  const long long seed = props.getInteger("seed", 0);
  if (seed < 0 || seed > 0x7fffffff) props.fail("seed", "must be in [0, 2^31), got {}", seed);
  sampler.sampleCount = int(count);
  sampler.seed = int(seed);
  props.finish();
  return sampler;
}

FovAxis parseFovAxis(ObjectProperties& props) {
  const std::string axis = props.getString("fov_axis", "x");
  if (axis == "x") return FovAxis::X;
  if (axis == "y") return FovAxis::Y;
  if (axis == "diagonal") return FovAxis::Diagonal;
  if (axis == "smaller") return FovAxis::Smaller;
  if (axis == "larger") return FovAxis::Larger;
  props.fail("fov_axis", "'{}' is not one of x, y, diagonal, smaller, larger", axis);
}

}  // namespace

SensorDesc parseSensor(const XmlElement& element) {
  ObjectProperties props(element, {"film", "sampler"});
  checkType(props, "perspective");
  SensorDesc sensor;
  sensor.location = props.location();
  sensor.fov = props.getFloat("fov");
  if (!(sensor.fov > 0.0 && sensor.fov < 180.0))
    props.fail("fov", "must be in (0, 180) degrees, got {}", sensor.fov);
  sensor.fovAxis = parseFovAxis(props);
  sensor.nearClip = props.getFloat("near_clip", 1e-2);
  sensor.farClip = props.getFloat("far_clip", 1e4);
  if (!(sensor.nearClip > 0.0)) props.fail("near_clip", "must be > 0, got {}", sensor.nearClip);
  if (!(sensor.farClip > sensor.nearClip))
    props.fail("far_clip", "must exceed near_clip ({}), got {}", sensor.nearClip, sensor.farClip);
  if (const std::optional<Mat4> toWorld = props.getTransform("to_world")) {
    // A pinhole's rays need unit directions: like Mitsuba, reject scale in the camera transform.
    for (int c = 0; c < 3; ++c)
      if (std::abs(toWorld->block<3, 1>(0, c).norm() - 1.0) > 1e-4)
        props.fail("to_world", "a camera transform must not scale (column {} has length {})", c,
                   toWorld->block<3, 1>(0, c).norm());
    sensor.toWorld = *toWorld;
  }
  if (const std::optional<XmlElement> film = props.takeOptional("film")) {
    sensor.film = parseFilm(*film);
  } else {
    sensor.film.location = sensor.location;
  }
  if (const std::optional<XmlElement> sampler = props.takeOptional("sampler")) {
    sensor.sampler = parseSampler(*sampler);
  } else {
    sensor.sampler.location = sensor.location;
  }
  props.finish();
  return sensor;
}

}  // namespace quadtri
