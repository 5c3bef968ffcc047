#include "soak_cases.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <random>

#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/model.h"

namespace quadtri::soak {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

uint64_t mix(uint64_t x) {  // splitmix64's finaliser
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

class Random {
 public:
  Random(uint64_t seed, int index) : engine_(mix(seed ^ mix(uint64_t(index) + 1))) {}
  double uniform(double lo = 0.0, double hi = 1.0) {
    return std::uniform_real_distribution<double>(lo, hi)(engine_);
  }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(engine_); }
  bool chance(double p) { return uniform() < p; }
  template <class T>
  const T& pick(const std::vector<T>& items) {
    return items[size_t(integer(0, int(items.size()) - 1))];
  }
  Vec3 direction() {
    const double z = uniform(-1.0, 1.0), phi = uniform(0.0, 2.0 * M_PI);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return Vec3(r * std::cos(phi), r * std::sin(phi), z);
  }

 private:
  std::mt19937_64 engine_;
};

/// A mesh as an OBJ file holds it, so that damage (zero normals, repeated indices, faces on
/// an edge already shared by two) reaches the loader as a user's file would.
struct ObjMesh {
  std::vector<Vec3> v, vn;
  std::vector<std::array<int, 3>> f, fn;  ///< 0-based; fn empty: no normals

  static ObjMesh from(const TriangleMesh& mesh) {
    ObjMesh o;
    o.v = mesh.positions;
    for (const Tri& t : mesh.triangles) o.f.push_back({int(t[0]), int(t[1]), int(t[2])});
    if (!mesh.normalIndices.empty()) {
      o.vn = mesh.normals;
      for (const Tri& t : mesh.normalIndices) o.fn.push_back({int(t[0]), int(t[1]), int(t[2])});
    }
    return o;
  }
  bool hasNormals() const { return !fn.empty(); }
  void addFace(std::array<int, 3> face, std::array<int, 3> normals) {
    f.push_back(face);
    if (hasNormals()) fn.push_back(normals);
  }
  int addNormal(const Vec3& n) {
    vn.push_back(n);
    return int(vn.size()) - 1;
  }
  Bounds3 bounds() const {
    Bounds3 b;
    for (const auto& face : f)
      for (int i : face) b.extend(v[size_t(i)]);
    return b;
  }
  std::string text() const {
    std::string s = "# quadtri soak\n";
    for (const Vec3& p : v) s += fmt::format("v {:.17g} {:.17g} {:.17g}\n", p.x(), p.y(), p.z());
    for (const Vec3& n : vn) s += fmt::format("vn {:.17g} {:.17g} {:.17g}\n", n.x(), n.y(), n.z());
    for (size_t t = 0; t < f.size(); ++t) {
      if (hasNormals())
        s += fmt::format("f {}//{} {}//{} {}//{}\n", f[t][0] + 1, fn[t][0] + 1, f[t][1] + 1,
                         fn[t][1] + 1, f[t][2] + 1, fn[t][2] + 1);
      else
        s += fmt::format("f {} {} {}\n", f[t][0] + 1, f[t][1] + 1, f[t][2] + 1);
    }
    return s;
  }
};

void writeText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) fail("{}: cannot write the soak case", path.string());
}

/// One random defect of the kinds the issue names; returns its name and whether the loader
/// reports it (mesh_repair.h: a sliver is a valid triangle, reported by nothing).
std::pair<std::string, bool> damage(ObjMesh& m, Random& rng) {
  if (m.f.empty()) return {"none", false};
  const size_t t = size_t(rng.integer(0, int(m.f.size()) - 1));
  const std::array<int, 3> face = m.f[t];
  const std::array<int, 3> normals = m.hasNormals() ? m.fn[t] : std::array<int, 3>{};
  const int k = rng.integer(0, 2);
  const int a = face[size_t(k)], b = face[size_t((k + 1) % 3)], c = face[size_t((k + 2) % 3)];
  const Vec3 pa = m.v[size_t(a)], pb = m.v[size_t(b)], pc = m.v[size_t(c)];
  const Vec3 cross = (pb - pa).cross(pc - pa);
  const Vec3 up = cross.norm() > 0.0 ? Vec3(cross.normalized()) : Vec3(0, 0, 1);
  const double edge = std::max((pb - pa).norm(), 1e-9);
  auto vertex = [&](const Vec3& p) {
    m.v.push_back(p);
    return int(m.v.size()) - 1;
  };
  auto normal = [&] { return m.hasNormals() ? m.addNormal(up) : 0; };
  switch (rng.integer(0, 7)) {
    case 0:
      m.addFace(face, normals);
      return {"duplicate face", true};
    case 1:
      m.addFace({face[0], face[2], face[1]}, {normals[0], normals[2], normals[1]});
      return {"duplicate face, reversed", true};
    case 2: {  // another face on edge ab: non-manifold where two faces already share it
      const long long sharing = std::count_if(m.f.begin(), m.f.end(), [&](const auto& g) {
        const auto has = [&](int v) { return std::find(g.begin(), g.end(), v) != g.end(); };
        return has(a) && has(b);
      });
      const int n = normal();
      m.addFace({a, b, vertex(0.5 * (pa + pb) + edge * up)}, {n, n, n});
      return {"fin", sharing >= 2};
    }
    case 3: {
      const int n = normal();
      m.addFace({a, a, b}, {n, n, n});
      return {"degenerate face (repeated vertex)", true};
    }
    case 4: {
      const int n = normal();
      m.addFace({a, vertex(0.5 * (pa + pb)), b}, {n, n, n});
      return {"degenerate face (collinear)", true};
    }
    case 5: {
      const int n = normal();
      m.addFace({a, b, vertex(0.5 * (pa + pb) + 1e-7 * edge * up)}, {n, n, n});
      return {"sliver", false};
    }
    case 6:  // Assimp's OBJ importer drops it before the loader sees it
      vertex(pa + 3.0 * edge * up);
      return {"isolated vertex", false};
    default:
      if (!m.hasNormals()) return {"none", false};
      m.vn[size_t(normals[size_t(k)])] = Vec3::Zero();
      return {"zero-length normal", true};
  }
}

ObjMesh soup(Random& rng) {
  ObjMesh m;
  const int n = rng.integer(1, 40);
  for (int i = 0; i < n; ++i) {
    const Vec3 p(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const double size = std::pow(10.0, rng.uniform(-4.0, 0.0));
    const int base = int(m.v.size());
    for (int k = 0; k < 3; ++k) m.v.push_back(p + size * rng.direction());
    m.f.push_back({base, base + 1, base + 2});
  }
  return m;
}

/// A mesh whose file the loader must refuse, and what is wrong with it.
std::pair<std::string, std::string> brokenObj(Random& rng) {
  switch (rng.integer(0, 2)) {
    case 0:
      return {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", "face index past the vertices"};
    case 1:
      return {"v 0 0 0\nv 1 0 0\n", "no faces"};
    default:
      return {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9\n", "negative face index past the vertices"};
  }
}

struct Bsdf {
  std::string xml;
  std::string name;
  double albedo = 1.0;    ///< an upper bound of its directional albedo
  bool lossless = false;  ///< albedo exactly 1 in every direction on its front side
  /// Lossless on both sides too. A one-sided BSDF is black from behind, so it conserves a
  /// furnace's energy only where no ray reaches a back side: a watertight closed surface.
  bool bothSides = false;
  /// Radiance inside a dielectric of index η is η² times the radiance outside (the basic
  /// radiance L/η² is what refraction conserves): a camera inside glass may see that much.
  double gain = 1.0;
};

Bsdf randomBsdf(Random& rng) {
  switch (rng.integer(0, 6)) {
    case 6: {  // Mitsuba's blendbsdf of a diffuse and a mirror lobe
      const double w = rng.uniform(), r = rng.chance(0.5) ? 1.0 : rng.uniform();
      return {fmt::format("<bsdf type=\"blendbsdf\"><float name=\"weight\" value=\"{}\"/>"
                          "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"{}\"/>"
                          "</bsdf><bsdf type=\"conductor\"/></bsdf>",
                          w, r),
              fmt::format("blend {:.3g} of diffuse {:.3g} and mirror", w, r), 1.0, r == 1.0};
    }
    case 0: {
      const double r = rng.chance(0.5) ? 1.0 : rng.uniform();
      return {fmt::format("<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"{0}, {0}, "
                          "{0}\"/></bsdf>",
                          r),
              fmt::format("diffuse {:.3g}", r), r, r == 1.0};
    }
    case 1: {
      const double ior = rng.uniform(1.0, 2.5);
      return {fmt::format("<bsdf type=\"dielectric\"><float name=\"int_ior\" value=\"{}\"/>"
                          "</bsdf>",
                          ior),
              fmt::format("dielectric {:.3g}", ior),
              1.0,
              true,
              true,
              ior * ior};
    }
    case 2:
      return {"<bsdf type=\"conductor\"/>", "mirror", 1.0, true};
    case 3: {
      const std::string material = rng.pick(std::vector<std::string>{"Au", "Cu", "Al"});
      return {fmt::format("<bsdf type=\"conductor\"><string name=\"material\" value=\"{}\"/>"
                          "</bsdf>",
                          material),
              "conductor " + material, 1.0, false};
    }
    case 4: {
      const double alpha = std::pow(10.0, rng.uniform(-2.0, 0.0));
      return {fmt::format("<bsdf type=\"roughconductor\"><string name=\"distribution\" "
                          "value=\"ggx\"/><float name=\"alpha\" value=\"{}\"/></bsdf>",
                          alpha),
              fmt::format("roughconductor {:.3g}", alpha), 1.0, false};
    }
    default: {
      const double r = rng.chance(0.5) ? 1.0 : rng.uniform();
      return {fmt::format("<bsdf type=\"twosided\"><bsdf type=\"diffuse\"><rgb "
                          "name=\"reflectance\" value=\"{}\"/></bsdf></bsdf>",
                          r),
              fmt::format("twosided diffuse {:.3g}", r), r, r == 1.0, r == 1.0};
    }
  }
}

std::string vec(const Vec3& p) {
  return fmt::format("{:.17g}, {:.17g}, {:.17g}", p.x(), p.y(), p.z());
}

/// Models whose shading normal is the geometric normal of what the ray hits.
bool exactNormals(const std::string& model) {
  return model == "flat" || model == "quadric-implicit" || model == "quadric-g1";
}

}  // namespace

Case writeCase(uint64_t seed, int index, const CaseSources& sources,
               const std::filesystem::path& folder) {
  Random rng(seed, index);
  std::filesystem::create_directories(folder);
  Case c;
  c.seed = seed;
  c.index = index;
  c.scene = folder / "scene.xml";
  c.files.push_back(c.scene);
  std::vector<std::string> summary;

  // The mesh: a built-in shape, a corpus mesh, a triangle soup or a broken file; then damage.
  const std::filesystem::path meshFile = folder / "mesh.obj";
  std::filesystem::path meshPath = meshFile;
  std::optional<ObjMesh> obj;
  bool closedShape = false;  ///< an undamaged built-in shape (each is closed)
  const double kind = rng.uniform();
  if (kind < 0.08) {
    const auto [text, what] = brokenObj(rng);
    writeText(meshFile, text);
    c.expect.error = true;
    summary.push_back("broken OBJ: " + what);
  } else if (kind < 0.2) {
    obj = soup(rng);
    summary.push_back(fmt::format("soup of {} triangles", obj->f.size()));
  } else if (kind < 0.45 && !sources.meshes.empty()) {
    const std::filesystem::path file = rng.pick(sources.meshes);
    summary.push_back("corpus " + file.filename().string());
    try {
      obj = ObjMesh::from(loadMesh(file));
      if (rng.chance(0.5)) meshPath = file;  // the file itself, its loaded copy for the bounds
    } catch (const Error&) {
      // A corpus file the loader refuses (data/README.md lists them): the render must refuse
      // it too, naming it.
      meshPath = file;
      obj.reset();
      c.expect.error = true;
    }
  } else {
    const std::string spec = rng.pick(std::vector<std::string>{
        "icosphere:0", "icosphere:1", "icosphere:2", "uv-sphere:12,8", "ellipsoid:1,0.7,0.5",
        "torus:1,0.35,24,12", "genus2:10", "cube:2", "cylinder:12,2", "cube:1"});
    obj = ObjMesh::from(parseBuiltinSpec(spec)->mesh);
    closedShape = true;
    summary.push_back(spec);
  }
  if (obj && meshPath == meshFile) {
    if (rng.chance(0.35)) {
      const int defects = rng.integer(1, 4);
      bool zeroNormalOnly = true;
      for (int i = 0; i < defects; ++i) {
        const auto [what, reported] = damage(*obj, rng);
        summary.push_back(what);
        c.expect.repairReported |= reported;
        if (reported && what != "zero-length normal") zeroNormalOnly = false;
      }
      closedShape = false;
      if (obj->hasNormals() && rng.chance(0.2)) {
        obj->vn.clear();
        obj->fn.clear();
        summary.push_back("normals dropped");
        if (zeroNormalOnly) c.expect.repairReported = false;
      }
    }
    writeText(meshFile, obj->text());
  }
  c.files.push_back(meshPath);

  // Placement: the mesh's bounding sphere becomes the unit sphere, then scaled by `scale`.
  Vec3 center = Vec3::Zero();
  double radius = 1.0;
  if (obj) {
    const Bounds3 b = obj->bounds();
    if (!b.empty()) {
      center = 0.5 * (b.lo + b.hi);
      radius = std::max(0.5 * (b.hi - b.lo).norm(), 1e-12);
    }
  }
  const double scale = rng.chance(0.5) ? 1.0 : std::pow(10.0, rng.uniform(-6.0, 6.0));
  summary.push_back(fmt::format("scale {:.3g}", scale));

  // Half the furnaces get a model and a BSDF for which the furnace fixes every pixel's value.
  const bool furnace = rng.chance(0.5);
  const bool aimExact = furnace && rng.chance(0.5);
  const std::string model =
      aimExact ? rng.pick(std::vector<std::string>{"flat", "quadric-implicit", "quadric-g1"})
               : rng.pick(modelNames());
  summary.push_back(model);
  Bsdf bsdf = randomBsdf(rng);
  while (aimExact && !bsdf.lossless) bsdf = randomBsdf(rng);
  summary.push_back(bsdf.name);
  // Every model but these two cracks 0 lines on the built-in shapes (README, crack_rate).
  const bool watertight =
      closedShape && model != "quadric-implicit" && model != "quadric-edges-eq42";
  // Glass bounds radiance by η² only where its interface is closed and consistently oriented:
  // a path that slips through a crack can be refracted "in" twice.
  if (bsdf.gain > 1.0 && !watertight) bsdf.gain = kInf;

  // The camera: outside looking at the centre, inside the mesh's bounds, or grazing the
  // bounding sphere.
  const Vec3 d = rng.direction();
  const Vec3 side = d.unitOrthogonal();
  Vec3 origin, target;
  bool outside = true;
  switch (rng.integer(0, 2)) {
    case 0:
      origin = rng.uniform(2.5, 4.0) * d;
      target = Vec3::Zero();
      summary.push_back("camera outside");
      break;
    case 1:
      origin = 0.05 * rng.direction();
      target = rng.direction();
      outside = false;
      summary.push_back("camera inside");
      break;
    default:
      origin = 3.0 * d;
      target = side;
      summary.push_back("camera grazing");
  }
  const Vec3 up = std::abs((target - origin).normalized().dot(Vec3(0, 1, 0))) > 0.99
                      ? Vec3(1, 0, 0)
                      : Vec3(0, 1, 0);

  std::string shapes, emitters, integrator;
  c.expect.furnace = furnace;
  double lightMax = 0.0, albedo = bsdf.albedo;
  int maxDepth = -1;
  bool pointLight = false;
  if (furnace) {
    c.expect.environment = rng.uniform(0.5, 2.0);
    emitters = fmt::format(
        "<emitter type=\"constant\"><rgb name=\"radiance\" value=\"{}\"/>"
        "</emitter>",
        c.expect.environment);
    integrator = rng.chance(0.7) ? "<integrator type=\"path\"><integer name=\"max_depth\" "
                                   "value=\"-1\"/></integrator>"
                                 : "<integrator type=\"adaptive\"><float name=\"threshold\" "
                                   "value=\"0.1\"/><integer name=\"min_samples\" value=\"4\"/>"
                                   "<integer name=\"max_samples\" value=\"16\"/><integrator "
                                   "type=\"path\"/></integrator>";
    summary.push_back(fmt::format("furnace {:.3g}", c.expect.environment));
    // (Glass on geometry that cracks has an infinite gain: no exact value either.)
    c.expect.exact = outside && exactNormals(model) && std::isfinite(bsdf.gain) &&
                     (bsdf.bothSides || (bsdf.lossless && watertight));
    c.expect.upperBound = std::isinf(bsdf.gain) ? kInf : c.expect.environment * bsdf.gain;
  } else {
    const double floor = rng.uniform(0.2, 0.8);
    albedo = std::max(albedo, floor);
    shapes += fmt::format(
        "<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"{0}\"/>"
        "<rotate x=\"1\" angle=\"-90\"/><translate value=\"0, {1}, 0\"/></transform>"
        "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"{2}\"/></bsdf></shape>\n",
        3.0 * scale, -1.2 * scale, floor);
    if (rng.chance(0.6)) {
      const double le = rng.uniform(1.0, 10.0);
      lightMax = std::max(lightMax, le);
      shapes += fmt::format(
          "<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"{0}\"/>"
          "<rotate x=\"1\" angle=\"90\"/><translate value=\"0, {1}, 0\"/></transform>"
          "<emitter type=\"area\"><rgb name=\"radiance\" value=\"{2}\"/></emitter></shape>\n",
          0.8 * scale, 2.5 * scale, le);
      summary.push_back(fmt::format("area light {:.3g}", le));
    }
    if (rng.chance(0.3)) {
      const double le = rng.uniform(1.0, 10.0);
      lightMax = std::max(lightMax, le);
      shapes += fmt::format(
          "<shape type=\"sphere\"><point name=\"center\" value=\"{}\"/><float name=\"radius\" "
          "value=\"{}\"/><emitter type=\"area\"><rgb name=\"radiance\" value=\"{}\"/></emitter>"
          "</shape>\n",
          vec(scale * Vec3(1.5, 1.5, 0.5)), 0.3 * scale, le);
      summary.push_back(fmt::format("sphere light {:.3g}", le));
    }
    if (rng.chance(0.4)) {
      const double le = rng.uniform(0.0, 1.0);
      lightMax = std::max(lightMax, le);
      emitters += fmt::format(
          "<emitter type=\"constant\"><rgb name=\"radiance\" value=\"{}\"/>"
          "</emitter>\n",
          le);
      summary.push_back(fmt::format("environment {:.3g}", le));
    }
    if (lightMax == 0.0 || rng.chance(0.3)) {
      pointLight = true;
      emitters += fmt::format(
          "<emitter type=\"point\"><point name=\"position\" value=\"{}\"/>"
          "<rgb name=\"intensity\" value=\"{}\"/></emitter>\n",
          vec(scale * Vec3(0.3, 2.4, 1.0)), 10.0 * scale * scale);
      summary.push_back("point light");
    }
    const double which = rng.uniform();
    if (which < 0.1) {
      integrator = "<integrator type=\"normals\"/>";
      c.expect.normals = true;
      summary.push_back("normals");
    } else if (which < 0.3) {
      integrator = "<integrator type=\"direct\"/>";
      maxDepth = 2;
      summary.push_back("direct");
    } else {
      maxDepth = rng.pick(std::vector<int>{-1, 1, 2, 4, 8});
      integrator = fmt::format(
          "<integrator type=\"path\"><integer name=\"max_depth\" "
          "value=\"{}\"/></integrator>",
          maxDepth);
      summary.push_back(fmt::format("path max_depth {}", maxDepth));
    }
    // Emission ≤ lightMax everywhere and every bounce keeps at most `albedo` of it: the
    // Neumann series' first maxDepth terms, or all of them.
    if (pointLight || c.expect.normals) {
      c.expect.upperBound = kInf;
    } else if (maxDepth < 0) {
      c.expect.upperBound = albedo < 1.0 ? lightMax / (1.0 - albedo) : kInf;
    } else {
      double sum = 0.0, term = 1.0;
      for (int k = 0; k < maxDepth; ++k, term *= albedo) sum += term;
      c.expect.upperBound = lightMax * sum;
    }
    c.expect.upperBound = std::isinf(bsdf.gain) ? kInf : c.expect.upperBound * bsdf.gain;
  }

  const int width = rng.integer(6, 16), height = rng.integer(6, 16);
  const std::string filter = rng.pick(std::vector<std::string>{"box", "tent", "gaussian"});
  const Vec3 move = -center;
  std::string object = fmt::format(
      "<shape type=\"obj\"><string name=\"filename\" value=\"{}\"/><string name=\"model\" "
      "value=\"{}\"/><transform name=\"to_world\"><translate value=\"{}\"/><scale value=\"{}\"/>"
      "</transform>{}</shape>\n",
      meshPath.string(), model, vec(move), scale / radius, bsdf.xml);

  // A broken scene around a good mesh: the parser must name the element.
  if (!c.expect.error && rng.chance(0.06)) {
    c.expect.error = true;
    switch (rng.integer(0, 2)) {
      case 0:
        shapes += "<shape type=\"sphere\"><float name=\"radius\" value=\"-1\"/></shape>\n";
        summary.push_back("broken scene: negative radius");
        break;
      case 1:
        shapes += "<bsdf type=\"velvet\" id=\"v\"/>\n";
        summary.push_back("broken scene: unknown bsdf");
        break;
      default:
        object = fmt::format(
            "<shape type=\"obj\"><string name=\"filename\" value=\"{}\"/>"
            "<string name=\"model\" value=\"no-such-model\"/></shape>\n",
            meshPath.string());
        summary.push_back("broken scene: unknown model");
    }
  }

  const std::string xml = fmt::format(
      R"(<?xml version="1.0"?>
<scene version="3.0.0">
{integrator}
<sensor type="perspective"><float name="fov" value="{fov}"/>
<transform name="to_world"><lookat origin="{origin}" target="{target}" up="{up}"/></transform>
<film type="hdrfilm"><integer name="width" value="{w}"/><integer name="height" value="{h}"/>
<rfilter type="{filter}"/></film>
<sampler type="independent"><integer name="sample_count" value="8"/></sampler>
</sensor>
{object}{shapes}{emitters}
</scene>
)",
      fmt::arg("integrator", integrator), fmt::arg("fov", rng.uniform(20.0, 70.0)),
      fmt::arg("origin", vec(scale * origin)), fmt::arg("target", vec(scale * target)),
      fmt::arg("up", vec(up)), fmt::arg("w", width), fmt::arg("h", height),
      fmt::arg("filter", filter), fmt::arg("object", object), fmt::arg("shapes", shapes),
      fmt::arg("emitters", emitters));
  writeText(c.scene, xml);
  c.summary = fmt::format("{}", fmt::join(summary, ", "));
  return c;
}

}  // namespace quadtri::soak
