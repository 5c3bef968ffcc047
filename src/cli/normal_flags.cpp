#include "normal_flags.h"

#include <fmt/format.h>

#include "quadtri/math/error.h"

namespace quadtri::cli {

void addNormalFlags(CLI::App* sub, NormalFlags& flags, const std::string& sourceHelp,
                    const std::string& defaultSource) {
  flags.source = defaultSource;
  flags.sourceOption = sub->add_option("--normals", flags.source, sourceHelp)
                           ->check(CLI::IsMember({"file", "average", "angle"}));
  if (!defaultSource.empty()) flags.sourceOption->capture_default_str();
  flags.creaseOption =
      sub->add_option("--crease-angle", flags.creaseAngleDeg,
                      fmt::format("Degrees: computed angle-weighted normals (a file without "
                                  "normals, --normals angle) split where faces meet at more "
                                  "than this (180: never; default {:g})",
                                  kDefaultCreaseAngleDeg));
}

NormalOptions NormalFlags::options() const {
  const NormalSource s = parseNormalSource(source.empty() ? "file" : source);
  if (creaseOption && creaseOption->count() > 0) {
    if (s == NormalSource::Average)
      fail(
          "--crease-angle applies to angle-weighted normals, not to --normals average (thesis "
          "eq. 2.8 never splits)");
    checkCreaseAngle(creaseAngleDeg);
  }
  return {s, creaseAngleDeg};
}

std::optional<NormalSource> NormalFlags::sourceOverride() const {
  (void)options();  // validates the combination
  if (!sourceOption || sourceOption->count() == 0) return std::nullopt;
  return parseNormalSource(source);
}

std::optional<double> NormalFlags::creaseOverride() const {
  if (!creaseOption || creaseOption->count() == 0) return std::nullopt;
  checkCreaseAngle(creaseAngleDeg);
  return creaseAngleDeg;
}

}  // namespace quadtri::cli
