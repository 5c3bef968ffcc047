// The randomized soak's scenes (README "Reliability"): each case is a scene file and the mesh
// files it names, written into a folder, with what its render must satisfy.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace quadtri::soak {

/// What a case's render is checked against.
struct Expectation {
  /// The input is broken on purpose: loading or rendering it must throw quadtri::Error whose
  /// message names one of `files`.
  bool error = false;
  /// Only a constant environment of radiance `environment` lights the scene.
  bool furnace = false;
  double environment = 0.0;
  /// Every pixel's expected value is exactly `environment`: a furnace whose surfaces neither
  /// absorb nor emit, seen from outside, with a model whose shading normal is its geometric
  /// normal (a shading normal that differs loses energy at grazing angles).
  bool exact = false;
  /// The expected value of no pixel exceeds this (energy conservation; infinite when unknown,
  /// as with a point light, whose irradiance has no bound near it).
  double upperBound = 0.0;
  /// The mesh file has a defect the loader repairs or reports: a warning must name it.
  bool repairReported = false;
  /// The image holds normals, not radiance: its channels lie in [−1, 1].
  bool normals = false;
};

struct Case {
  uint64_t seed = 0;
  int index = 0;
  std::string summary;  ///< one line: mesh, damage, model, bsdf, lights, camera, scale
  std::filesystem::path scene;
  std::vector<std::filesystem::path> files;  ///< the scene and every mesh file it names
  Expectation expect;
};

/// Where a case's mesh comes from, besides the built-in shapes.
struct CaseSources {
  /// Meshes to draw from (corpus files); empty: built-in shapes and generated soups only.
  std::vector<std::filesystem::path> meshes;
};

/// Writes case `index` of the run `seed` into `folder` (created). Deterministic in
/// (seed, index): the same pair writes the same files.
Case writeCase(uint64_t seed, int index, const CaseSources& sources,
               const std::filesystem::path& folder);

}  // namespace quadtri::soak
