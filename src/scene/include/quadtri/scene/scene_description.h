// A scene file's content as validated, typed values (docs/DESIGN.md §5): what the renderer is built
// from. No rendering objects live here; every record keeps the "FILE:LINE" it came from so that
// later stages can name it in their errors.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "quadtri/math/color.h"
#include "quadtri/math/vec.h"
#include "quadtri/mesh/normals.h"
#include "quadtri/render/camera.h"

namespace quadtri {

/// Pixel reconstruction filter: box (one pixel wide), tent of radius `radius` pixels (default
/// 1) or Gaussian of standard deviation stddev pixels (Mitsuba's default, stddev 0.5,
/// truncated at 4 stddev).
struct FilterDesc {
  enum class Type { Box, Gaussian, Tent } type = Type::Gaussian;
  double stddev = 0.5;
  double radius = 1.0;
};

/// hdrfilm: image size in pixels and its reconstruction filter.
struct FilmDesc {
  int width = 768;
  int height = 576;
  /// crop_offset_x/y, crop_width/height: the window of the film that is rendered (the whole
  /// film by default); the image has the window's size.
  int cropX = 0, cropY = 0, cropWidth = 0, cropHeight = 0;
  FilterDesc filter;
  std::string location;
};

/// independent sampler: samples per pixel and the seed mixed into every pixel's stream.
struct SamplerDesc {
  int sampleCount = 4;
  int seed = 0;
  std::string location;
};

/// Pinhole camera. toWorld maps camera space (origin at the eye, looking along +z, +y up in
/// the image, +x = up × forward) to world space; fov is in degrees along fovAxis.
struct SensorDesc {
  Mat4 toWorld = Mat4::Identity();
  double fov = 0.0;
  FovAxis fovAxis = FovAxis::X;
  double nearClip = 1e-2;
  double farClip = 1e4;
  /// principal_point_offset_x/y: the optical axis' offset from the film's centre, in units
  /// of the film's width and height.
  Vec2 principalPointOffset = Vec2::Zero();
  FilmDesc film;
  SamplerDesc sampler;
  std::string location;
};

/// The light transport algorithm. Fields not used by `type` keep their defaults.
struct IntegratorDesc {
  enum class Type {
    Path,      ///< unidirectional path tracing with NEE and MIS
    Direct,    ///< direct illumination only
    Normals,   ///< colours surfaces by their normal (quadtri-specific)
    Adaptive,  ///< path tracing until each pixel's relative standard error < threshold
  } type = Type::Path;
  int maxDepth = -1;  ///< path/adaptive: longest path in segments; -1 = unbounded
  int rrDepth = 5;    ///< path/adaptive: depth at which Russian roulette starts
  bool hideEmitters = false;
  int emitterSamples = 1;   ///< direct: light samples per shading point
  int bsdfSamples = 1;      ///< direct: BSDF samples per shading point
  double threshold = 0.05;  ///< adaptive: relative standard error that stops a pixel
  int minSamples = 16;      ///< adaptive: samples taken before the first test
  int maxSamples = 0;       ///< adaptive: cap per pixel (defaults to the sampler's sample_count)
  std::string location;
};

/// An index of refraction: a number or a named medium ("bk7", "air", ...) to be looked up.
using IorValue = std::variant<double, std::string>;

/// A BSDF with its parameters. Fields not used by `type` keep their defaults.
struct BsdfDesc {
  enum class Type { Diffuse, Dielectric, Conductor, RoughConductor, TwoSided } type = Type::Diffuse;
  std::string id;                            ///< empty when unnamed
  Color reflectance = Color::Constant(0.5);  ///< diffuse albedo
  IorValue intIor = std::string("bk7");      ///< dielectric: interior
  IorValue extIor = std::string("air");      ///< dielectric: exterior
  /// conductor/roughconductor: named metal; "none" means the explicit eta and k below
  /// (Mitsuba's default eta = 0, k = 1 is a perfect mirror).
  std::string material = "none";
  Color eta = Color::Zero();
  Color k = Color::Ones();
  double alpha = 0.1;  ///< roughconductor: GGX roughness
  /// twosided: index of the wrapped BSDF in SceneDescription::bsdfs (always lower than this
  /// BSDF's own index).
  std::optional<size_t> nested;
  std::string location;
};

/// A light that is not attached to a shape (area lights live in ShapeDesc).
struct EmitterDesc {
  enum class Type {
    Point,     ///< isotropic point light: intensity in W/sr at position
    Constant,  ///< constant environment: radiance from every direction
  } type = Type::Point;
  Color intensity = Color::Ones();
  Vec3 position = Vec3::Zero();
  Color radiance = Color::Ones();
  std::string location;
};

/// One shape. Built-in shapes live in object space and are placed by toWorld: rectangle =
/// [-1,1]² in z=0 facing +z; cube = [-1,1]³; sphere = the unit sphere (its center and radius
/// are folded into toWorld).
struct ShapeDesc {
  enum class Type { Obj, Ply, Rectangle, Cube, Sphere } type = Type::Obj;
  std::string id;                  ///< empty when unnamed
  std::filesystem::path filename;  ///< obj/ply: resolved against the scene file's folder
  std::string model = "shading";   ///< obj/ply: a name from modelNames()
  /// obj/ply: "N" or "thesis" for Tessellation::parse; empty for the default.
  std::string tessellation;
  /// obj/ply: the shading normals (`normals`: file, average or angle; `crease_angle` in
  /// degrees, for normals computed angle-weighted: a file without normals, or `angle`).
  NormalOptions normals;
  bool faceNormals = false;
  bool flipNormals = false;
  Mat4 toWorld = Mat4::Identity();
  size_t bsdf = 0;                    ///< index into SceneDescription::bsdfs
  std::optional<Color> areaRadiance;  ///< set when a nested area emitter makes it a light
  std::string location;
};

/// Everything a scene file says, validated.
struct SceneDescription {
  std::filesystem::path file;
  SensorDesc sensor;
  IntegratorDesc integrator;
  std::vector<BsdfDesc> bsdfs;
  std::vector<EmitterDesc> emitters;
  std::vector<ShapeDesc> shapes;
  /// Names of the file's <default> elements (the parameters -D is meant to override).
  std::vector<std::string> defaultNames;
  /// "FILE:LINE: ..." for every property accepted without effect on quadtri's image (for
  /// example hdrfilm's pixel_format): the CLI prints them as notes.
  std::vector<std::string> notes;
};

/// Sets the samples per pixel (`render --spp`): the sampler's sample_count and, for an adaptive
/// integrator, its cap per pixel (min_samples lowered to it where needed). Throws Error below 1,
/// or below 2 for an adaptive integrator.
void overrideSamplesPerPixel(SceneDescription& scene, int samplesPerPixel);

/// Sets every obj/ply shape's normals (`render --normals`, `--crease-angle`): `source` where
/// given, `creaseAngleDeg` where given. Throws Error for an angle outside [0, 180].
void overrideNormals(SceneDescription& scene, std::optional<NormalSource> source,
                     std::optional<double> creaseAngleDeg);

/// The parameters in Mitsuba-like syntax, for error messages and logs.
std::string toString(const SensorDesc& sensor);
std::string toString(const IntegratorDesc& integrator);
std::string toString(const BsdfDesc& bsdf);
std::string toString(const EmitterDesc& emitter);
std::string toString(const ShapeDesc& shape);

/// Mitsuba's name of each enum value.
std::string_view fovAxisName(FovAxis axis);
std::string_view integratorTypeName(IntegratorDesc::Type type);
std::string_view bsdfTypeName(BsdfDesc::Type type);
std::string_view emitterTypeName(EmitterDesc::Type type);
std::string_view shapeTypeName(ShapeDesc::Type type);

}  // namespace quadtri
