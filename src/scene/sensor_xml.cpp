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
#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>

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
  } else if (props.type() == "tent") {
    filter.type = FilterDesc::Type::Tent;
    filter.radius = props.getFloat("radius", 1.0);
    if (!(filter.radius > 0.0)) props.fail("radius", "must be > 0, got {}", filter.radius);
  } else {
    element.fail("unknown rfilter type '{}'; expected box, tent or gaussian", props.type());
  }
  props.finish();
  return filter;
}

FilmDesc parseFilm(const XmlElement& element, std::vector<std::string>& notes) {
  ObjectProperties props(element, {"rfilter"});
  checkType(props, "hdrfilm");
  props.ignore("file_format", "the output's extension picks EXR or PNG", notes);
  props.ignore("pixel_format", "quadtri writes RGB", notes);
  props.ignore("component_format", "EXR is written as 32-bit float", notes);
  props.ignore("sample_border", "samples are taken inside each pixel's filter footprint", notes);
  props.ignore("compensate", "sums are accumulated in double precision", notes);
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
  // Mitsuba's crop window: defaults to the whole film; must lie inside it.
  const long long cropX = props.getInteger("crop_offset_x", 0);
  const long long cropY = props.getInteger("crop_offset_y", 0);
  if (cropX < 0 || cropX >= width)
    props.fail("crop_offset_x", "must be in [0, width = {}), got {}", width, cropX);
  if (cropY < 0 || cropY >= height)
    props.fail("crop_offset_y", "must be in [0, height = {}), got {}", height, cropY);
  const long long cropWidth = props.getInteger("crop_width", width - cropX);
  const long long cropHeight = props.getInteger("crop_height", height - cropY);
  if (cropWidth < 1 || cropX + cropWidth > width)
    props.fail("crop_width", "must be in [1, width - crop_offset_x = {}], got {}", width - cropX,
               cropWidth);
  if (cropHeight < 1 || cropY + cropHeight > height)
    props.fail("crop_height", "must be in [1, height - crop_offset_y = {}], got {}", height - cropY,
               cropHeight);
  film.cropX = int(cropX);
  film.cropY = int(cropY);
  film.cropWidth = int(cropWidth);
  film.cropHeight = int(cropHeight);
  if (const std::optional<XmlElement> filter = props.takeOptional("rfilter"))
    film.filter = parseFilter(*filter);
  props.finish();
  return film;
}

SamplerDesc parseSampler(const XmlElement& element, std::vector<std::string>& notes) {
  ObjectProperties props(element, {});
  // Mitsuba's other samplers place the same number of samples with less variance; quadtri
  // draws them independently, which gives the same expected image with more noise.
  static constexpr std::string_view kSamplers[] = {"independent", "stratified", "multijitter",
                                                   "orthogonal", "ldsampler"};
  if (std::find(std::begin(kSamplers), std::end(kSamplers), props.type()) == std::end(kSamplers))
    element.fail(
        "unknown sampler type '{}'; expected independent (or stratified, multijitter, "
        "orthogonal, ldsampler, which quadtri samples independently)",
        props.type());
  if (props.type() != "independent")
    notes.push_back(
        fmt::format("{}: note: sampler '{}' is sampled as 'independent' (the same "
                    "expected image, other noise)",
                    props.location(), props.type()));
  props.ignore("jitter", "samples are drawn independently", notes);
  props.ignore("strength", "samples are drawn independently", notes);
  SamplerDesc sampler;
  sampler.location = props.location();
  const long long count = props.getInteger("sample_count", 4);
  if (count < 1 || count > kMaxSceneSamples)
    props.fail("sample_count", "must be in [1, {}], got {}", kMaxSceneSamples, count);
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

/// focal_length "50mm" (or a bare number of millimetres) as Mitsuba reads it: the diagonal
/// field of view of a 35 mm film (36 × 24 mm, diagonal 43.27 mm).
double fovFromFocalLength(ObjectProperties& props) {
  const std::string text = props.getString("focal_length");
  std::string_view number(text);
  if (number.size() > 2 && number.substr(number.size() - 2) == "mm") number.remove_suffix(2);
  double mm = 0.0;
  try {
    size_t used = 0;
    mm = std::stod(std::string(number), &used);
    if (used != number.size()) mm = -1.0;
  } catch (const std::exception&) {
    mm = -1.0;
  }
  if (!(mm > 0.0)) props.fail("focal_length", "'{}' is not a length like \"50mm\"", text);
  return 2.0 * std::atan(std::hypot(36.0, 24.0) / (2.0 * mm)) * 180.0 / kPi;
}

}  // namespace

SensorDesc parseSensor(const XmlElement& element, std::vector<std::string>& notes) {
  ObjectProperties props(element, {"film", "sampler"});
  checkType(props, "perspective");
  SensorDesc sensor;
  sensor.location = props.location();
  props.ignore("focus_distance", "a pinhole camera is in focus everywhere", notes);
  props.ignore("aperture_radius", "a pinhole camera has no aperture", notes);
  props.ignore("shutter_open", "the scene is static", notes);
  props.ignore("shutter_close", "the scene is static", notes);
  props.ignore("srf", "quadtri renders in RGB", notes);
  if (props.has("focal_length")) {
    if (props.has("fov")) props.fail("focal_length", "and fov both given; use one of them");
    sensor.fov = fovFromFocalLength(props);
    sensor.fovAxis = FovAxis::Diagonal;
    if (props.has("fov_axis"))
      props.fail("fov_axis", "does not apply to focal_length (always the film's diagonal)");
  } else {
    sensor.fov = props.getFloat("fov");
    sensor.fovAxis = parseFovAxis(props);
  }
  if (!(sensor.fov > 0.0 && sensor.fov < 180.0))
    props.fail("fov", "must be in (0, 180) degrees, got {}", sensor.fov);
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
  sensor.principalPointOffset = Vec2(props.getFloat("principal_point_offset_x", 0.0),
                                     props.getFloat("principal_point_offset_y", 0.0));
  if (const std::optional<XmlElement> film = props.takeOptional("film")) {
    sensor.film = parseFilm(*film, notes);
  } else {
    sensor.film.location = sensor.location;
  }
  if (const std::optional<XmlElement> sampler = props.takeOptional("sampler")) {
    sensor.sampler = parseSampler(*sampler, notes);
  } else {
    sensor.sampler.location = sensor.location;
  }
  props.finish();
  return sensor;
}

}  // namespace quadtri
