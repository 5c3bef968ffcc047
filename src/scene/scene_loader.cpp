// The <scene> level: version, <default>, $name substitution, <include>, and dispatch of each
// top-level object to its plugin parser.
#include "quadtri/scene/scene_loader.h"

#include <fstream>
#include <sstream>

#include "quadtri/scene/integrator/path_xml.h"
#include "scene_parser.h"

namespace quadtri {

void SceneParseState::declareId(const std::string& id, const XmlElement& at) {
  if (id.empty()) return;
  const auto [it, inserted] = idLocations.emplace(id, at.location());
  if (!inserted) at.fail("id '{}' is already used at {}", id, it->second);
}

namespace {

/// Includes nest at most this deep, which also stops a file that includes itself.
constexpr int kMaxIncludeDepth = 16;

std::string readFile(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    fail("{}: a folder, expected a scene file (Mitsuba 3 XML)", path.string());
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot open the scene file", path.string());
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) fail("{}: cannot read the scene file", path.string());
  return std::move(text).str();
}

class SceneParser {
 public:
  explicit SceneParser(const SceneDefines& defines) : defines_(defines), params_(defines) {}

  SceneDescription parse(const XmlFile& file) {
    state_.scene.file = file.path();
    const XmlElement root{&file, file.root()};
    parseFile(root, 0);
    if (!sensorLocation_)
      root.fail("the scene has no <sensor type=\"perspective\">; quadtri needs one");
    SceneDescription& scene = state_.scene;
    IntegratorDesc& integrator = scene.integrator;
    if (!integratorLocation_) {
      integrator.type = "path";
      integrator.params = std::make_shared<PathIntegratorParams>();
      integrator.location = root.location();
    }
    if (std::shared_ptr<const IntegratorParams> resolved = integrator.params->withSamplerCount(
            scene.sensor.sampler.sampleCount, integrator.location, scene.file.string()))
      integrator.params = std::move(resolved);
    return std::move(state_.scene);
  }

 private:
  void parseFile(const XmlElement& root, int depth) {
    if (root.tag() != "scene") root.fail("the root element is <{}>, expected <scene>", root.tag());
    root.checkAttributes({"version"});
    checkVersion(root);
    for (const XmlElement& child : root.children()) {
      // Document order matters: a <default> applies to the elements after it.
      substituteParameters(child, params_);
      const std::string_view tag = child.tag();
      if (tag == "default") {
        parseDefault(child);
      } else if (tag == "include") {
        parseInclude(child, depth);
      } else if (tag == "sensor") {
        if (sensorLocation_) child.fail("a second <sensor> (first at {})", *sensorLocation_);
        state_.scene.sensor = parseSensor(child, state_.scene.notes);
        sensorLocation_ = child.location();
      } else if (tag == "integrator") {
        if (integratorLocation_)
          child.fail("a second <integrator> (first at {})", *integratorLocation_);
        state_.scene.integrator = parseIntegrator(child, state_.scene.notes);
        integratorLocation_ = child.location();
      } else if (tag == "bsdf") {
        parseBsdf(child, state_);
      } else if (tag == "emitter") {
        state_.scene.emitters.push_back(parseEmitter(child, state_.scene.notes));
      } else if (tag == "shape") {
        state_.scene.shapes.push_back(parseShape(child, state_));
      } else {
        child.fail(
            "unknown element <{}> in <scene>; expected default, include, sensor, "
            "integrator, bsdf, emitter or shape",
            tag);
      }
    }
  }

  /// Mitsuba 2 and 3 share this syntax; 0.x files use other names and need Mitsuba's upgrade.
  static void checkVersion(const XmlElement& root) {
    const std::string_view version = root.required("version");
    const size_t dot = version.find('.');
    const long long major = parseInteger(root, version.substr(0, dot), "version");
    if (major != 2 && major != 3)
      root.fail("scene version '{}' is not supported; expected 3.x.y (Mitsuba 3 syntax)", version);
  }

  void parseDefault(const XmlElement& element) {
    element.checkAttributes({"name", "value"});
    const std::string name(element.required("name"));
    if (!element.has("value")) element.fail("<default name=\"{}\"> needs a 'value'", name);
    const auto [it, inserted] = defaultLocations_.emplace(name, element.location());
    if (!inserted) element.fail("<default name=\"{}\"> repeats the one at {}", name, it->second);
    state_.scene.defaultNames.push_back(name);
    // Values from the command line win over the file's defaults.
    if (!defines_.count(name)) params_[name] = element.attr("value");
  }

  void parseInclude(const XmlElement& element, int depth) {
    element.checkAttributes({"filename"});
    if (depth + 1 > kMaxIncludeDepth)
      element.fail("<include> nests deeper than {} files (does a file include itself?)",
                   kMaxIncludeDepth);
    const std::filesystem::path path =
        element.file->path().parent_path() / std::string(element.required("filename"));
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
      element.fail("<include> file '{}' does not exist", path.string());
    const XmlFile included(readFile(path), path);
    parseFile(XmlElement{&included, included.root()}, depth + 1);
  }

  const SceneDefines& defines_;
  std::map<std::string, std::string> params_;
  std::map<std::string, std::string> defaultLocations_;
  std::optional<std::string> sensorLocation_;
  std::optional<std::string> integratorLocation_;
  SceneParseState state_;
};

}  // namespace

SceneDescription parseSceneDescription(std::string_view xml, const std::filesystem::path& file,
                                       const SceneDefines& defines) {
  const XmlFile parsed(xml, file);
  return SceneParser(defines).parse(parsed);
}

SceneDescription loadSceneDescription(const std::filesystem::path& file,
                                      const SceneDefines& defines) {
  return parseSceneDescription(readFile(file), file, defines);
}

}  // namespace quadtri
