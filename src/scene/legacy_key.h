// Internal to src/scene: the render-key layout of quadtri 0.1.0, from before the plugin
// registries, when every BSDF, emitter, integrator and shape was one flat struct and the key
// hashed all of its fields. The built-in plugins write their parameters into these structs
// (PluginParams::addToKey) so that their keys, and with them the EXR tiles' scene keys and the
// render states of --checkpoint, stay what they were. New plugins need none of this.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "quadtri/mesh/normals.h"
#include "quadtri/scene/bsdf/dielectric_xml.h"
#include "quadtri/scene/plugin.h"

namespace quadtri::legacy_key {

/// The index of each type in 0.1.0's enums.
enum class Integrator { Path, Direct, Normals, Adaptive };
enum class Bsdf { Diffuse, Dielectric, Conductor, RoughConductor, TwoSided };
enum class Emitter { Point, Constant };
enum class Shape { Obj, Ply, Rectangle, Cube, Sphere };

struct IntegratorFields {
  Integrator type = Integrator::Path;
  int maxDepth = -1, rrDepth = 5;
  bool hideEmitters = false;
  int emitterSamples = 1, bsdfSamples = 1;
  double threshold = 0.05;
  int minSamples = 16, maxSamples = 0;

  void write(KeyWriter& key) const {
    key.value(type);
    key.value(maxDepth);
    key.value(rrDepth);
    key.value(hideEmitters);
    key.value(emitterSamples);
    key.value(bsdfSamples);
    key.value(threshold);
    key.value(minSamples);
    key.value(maxSamples);
  }
};

struct BsdfFields {
  Bsdf type = Bsdf::Diffuse;
  Color reflectance = Color::Constant(0.5);
  IorValue intIor = std::string("bk7"), extIor = std::string("air");
  std::string material = "none";
  Color eta = Color::Zero(), k = Color::Ones();
  double alpha = 0.1;
  int64_t nested = -1;

  void write(KeyWriter& key) const {
    key.value(type);
    key.color(reflectance);
    for (const IorValue* ior : {&intIor, &extIor}) {
      key.value(uint64_t(ior->index()));
      if (const double* v = std::get_if<double>(ior))
        key.value(*v);
      else
        key.text(std::get<std::string>(*ior));
    }
    key.text(material);
    key.color(eta);
    key.color(k);
    key.value(alpha);
    key.value(nested);
  }
};

struct EmitterFields {
  Emitter type = Emitter::Point;
  Color intensity = Color::Ones();
  Vec3 position = Vec3::Zero();
  Color radiance = Color::Ones();

  void write(KeyWriter& key) const {
    key.value(type);
    key.color(intensity);
    key.vector(position);
    key.color(radiance);
  }
};

/// The fields of a shape before its placement (which render_key.cpp writes for every shape).
struct ShapeFields {
  Shape type = Shape::Obj;
  std::optional<std::filesystem::path> file;  ///< obj/ply
  std::string model = "shading";
  std::string tessellation;
  NormalOptions normals;
  bool faceNormals = false;

  void write(KeyWriter& key) const {
    key.value(type);
    if (file) key.file(*file);
    key.text(model);
    key.text(tessellation);
    key.value(normals.source);
    key.value(normals.creaseAngleDeg);
    key.value(faceNormals);
  }
};

}  // namespace quadtri::legacy_key
