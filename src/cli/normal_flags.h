// `--normals` and `--crease-angle`, shared by every command that loads meshes.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "quadtri/mesh/normals.h"

namespace quadtri::cli {

struct NormalFlags {
  std::string source;  ///< empty: not given (render, figure: keep each scene shape's own)
  double creaseAngleDeg = kDefaultCreaseAngleDeg;
  CLI::Option* sourceOption = nullptr;
  CLI::Option* creaseOption = nullptr;

  /// The options asked for; throws Error for --crease-angle with --normals average, which does
  /// not split, or for an angle outside [0, 180].
  NormalOptions options() const;
  /// For scene overrides: the source and angle only where given.
  std::optional<NormalSource> sourceOverride() const;
  std::optional<double> creaseOverride() const;
};

/// Registers --normals (file, average or angle; `sourceHelp` says what file means here, and
/// `defaultSource` is its value when not given, empty for none) and --crease-angle.
void addNormalFlags(CLI::App* sub, NormalFlags& flags, const std::string& sourceHelp,
                    const std::string& defaultSource = "file");

}  // namespace quadtri::cli
