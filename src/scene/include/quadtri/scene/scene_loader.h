// Reads a Mitsuba 3 XML scene (the subset docs/DESIGN.md §5 names) into a SceneDescription.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <string_view>

#include "quadtri/scene/scene_description.h"

namespace quadtri {

/// $name values given on the command line (-D name=value); they win over <default>.
using SceneDefines = std::map<std::string, std::string>;

/// Reads and validates the scene file. Every error is a quadtri::Error whose message starts
/// "FILE:LINE: " and says what was expected.
SceneDescription loadSceneDescription(const std::filesystem::path& file,
                                      const SceneDefines& defines = {});

/// Same, from text: `file` names the text in messages and its folder resolves relative paths
/// (meshes, <include>).
SceneDescription parseSceneDescription(std::string_view xml, const std::filesystem::path& file,
                                       const SceneDefines& defines = {});

}  // namespace quadtri
