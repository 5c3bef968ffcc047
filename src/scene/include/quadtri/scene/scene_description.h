// A scene file's content as validated, typed values (docs/DESIGN.md §5): what the renderer is built
// from. No rendering objects live here; every record keeps the "FILE:LINE" it came from so that
// later stages can name it in their errors.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "quadtri/math/color.h"
#include "quadtri/math/vec.h"
#include "quadtri/mesh/normals.h"
#include "quadtri/render/camera.h"
#include "quadtri/scene/plugin.h"

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

/// The light transport algorithm: a registered integrator (plugin.h) and its parameters.
struct IntegratorDesc {
  std::string type = "path";  ///< a name of integratorNames()
  std::shared_ptr<const IntegratorParams> params;
  std::string location;

  /// The plugin's parameters as `T`, or null when they are of another plugin.
  template <typename T>
  const T* as() const {
    return dynamic_cast<const T*>(params.get());
  }
};

/// A BSDF: a registered type (plugin.h) and its parameters.
struct BsdfDesc {
  std::string type;  ///< a name of bsdfNames()
  std::string id;    ///< empty when unnamed
  std::shared_ptr<const BsdfParams> params;
  std::string location;

  template <typename T>
  const T* as() const {
    return dynamic_cast<const T*>(params.get());
  }
};

/// A light that is not attached to a shape (area lights live in ShapeDesc).
struct EmitterDesc {
  std::string type;  ///< a name of emitterNames() placed at the scene's level
  std::shared_ptr<const EmitterParams> params;
  std::string location;

  template <typename T>
  const T* as() const {
    return dynamic_cast<const T*>(params.get());
  }
};

/// One shape: a registered type (plugin.h) with its parameters, and the placement every shape
/// has. Built-in shapes live in object space and are placed by toWorld: rectangle = [-1,1]² in
/// z=0 facing +z; cube = [-1,1]³; sphere = the unit sphere (its center and radius are folded
/// into toWorld).
struct ShapeDesc {
  std::string type;  ///< a name of shapeNames()
  std::string id;    ///< empty when unnamed
  std::shared_ptr<const SceneShapeParams> params;
  bool flipNormals = false;
  Mat4 toWorld = Mat4::Identity();
  size_t bsdf = 0;                    ///< index into SceneDescription::bsdfs
  std::optional<Color> areaRadiance;  ///< set when a nested area emitter makes it a light
  std::string location;

  template <typename T>
  const T* as() const {
    return dynamic_cast<const T*>(params.get());
  }
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

/// Sets the normals of every shape that reads a mesh file (obj/ply; SceneShapeParams::withNormals;
/// `render --normals`, `--crease-angle`): `source` where given, `creaseAngleDeg` where given.
/// Throws Error for an angle outside [0, 180].
void overrideNormals(SceneDescription& scene, std::optional<NormalSource> source,
                     std::optional<double> creaseAngleDeg);

/// The parameters in Mitsuba-like syntax, for error messages and logs.
std::string toString(const SensorDesc& sensor);
std::string toString(const IntegratorDesc& integrator);
std::string toString(const BsdfDesc& bsdf);
std::string toString(const EmitterDesc& emitter);
std::string toString(const ShapeDesc& shape);

/// Mitsuba's name of the field-of-view axis.
std::string_view fovAxisName(FovAxis axis);

}  // namespace quadtri
