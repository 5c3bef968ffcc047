// The scene XML with its -D substitution. The input's leading lines of the form
// "-Dname=value" are the command line's defines; the rest is the scene's text, parsed as if it
// were a file in an empty scratch folder (so <include> and mesh paths that name other files
// fail cleanly). A scene that parses is also printed back (toString of each part).
#include "fuzz_common.h"
#include "quadtri/scene/scene_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace quadtri;
  std::string_view text = fuzz::asText(data, size);
  SceneDefines defines;
  while (text.substr(0, 2) == "-D") {
    const size_t eol = text.find('\n');
    const std::string_view line =
        text.substr(2, eol == std::string_view::npos ? text.npos : eol - 2);
    const size_t eq = line.find('=');
    if (eq != std::string_view::npos)
      defines[std::string(line.substr(0, eq))] = std::string(line.substr(eq + 1));
    if (eol == std::string_view::npos) {
      text = {};
      break;
    }
    text.remove_prefix(eol + 1);
  }
  static const std::filesystem::path file = fuzz::scratchDir() / "scene" / "scene.xml";
  return fuzz::runClean([&] {
    const SceneDescription scene = parseSceneDescription(text, file, defines);
    (void)toString(scene.sensor);
    (void)toString(scene.integrator);
    for (const ShapeDesc& s : scene.shapes) (void)toString(s);
  });
}
