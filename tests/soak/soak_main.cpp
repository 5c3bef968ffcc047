// quadtri_soak: the randomized soak (README "Reliability"). Writes random scenes (soak_cases.h),
// renders each at a tiny resolution through the library, as `quadtri render` does, and checks:
// no crash, no NaN or infinity in the image and no sample dropped as one, pixel means within
// what energy conservation allows (a two-sided test where a furnace fixes the answer), and a
// clear error, naming the file, for every input that is refused. A failure prints the seed and
// case that reproduce it.
//
//   quadtri_soak [--seed S] [--count N (0: until stopped)] [--first I] [--case I]
//                [--corpus DIR] [--work DIR] [--keep] [--threads T] [--verbose]
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "quadtri/math/error.h"
#include "quadtri/render/renderer.h"
#include "quadtri/scene/scene_render.h"
#include "soak_cases.h"

namespace fs = std::filesystem;
using namespace quadtri;

namespace {

struct Options {
  uint64_t seed = 1;
  long long count = 50;
  int first = 0;
  std::optional<int> only;
  fs::path corpus;
  fs::path work;
  bool keep = false;
  bool verbose = false;
  int threads = 0;
};

/// Allowed deviation of a mean, in standard errors. Over the CI's cases and channels the
/// family-wise chance of a false failure stays below 1e-3.
constexpr double kSigmas = 5.0;

struct Tally {
  long long cases = 0, rendered = 0, rejected = 0, exact = 0, bounded = 0, failures = 0;
};

std::vector<fs::path> corpusMeshes(const fs::path& folder) {
  std::vector<fs::path> meshes;
  if (folder.empty()) return meshes;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    const std::string ext = entry.path().extension().string();
    if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl") continue;
    if (entry.file_size() > 300'000) continue;  // a tiny render should stay tiny
    meshes.push_back(fs::absolute(entry.path()));
  }
  std::sort(meshes.begin(), meshes.end());
  return meshes;
}

bool namesAFile(const std::string& message, const soak::Case& c) {
  for (const fs::path& file : c.files)
    if (message.find(file.filename().string()) != std::string::npos) return true;
  return false;
}

/// Why the rendered image breaks the case's expectation; empty when it does not.
std::string checkImage(const soak::Case& c, const RenderResult& r) {
  const Image& image = r.image;
  if (r.stats.nonFiniteSamples > 0)
    return fmt::format("{} samples were NaN or infinite", r.stats.nonFiniteSamples);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const Color& p = image.at(x, y);
      for (int k = 0; k < 3; ++k) {
        if (!std::isfinite(p[k])) return fmt::format("pixel ({}, {}) is not finite", x, y);
        if (c.expect.normals ? std::abs(p[k]) > 1.0 + 1e-9 : p[k] < 0.0)
          return fmt::format("pixel ({}, {}) channel {} = {} is out of range", x, y, k, p[k]);
      }
    }
  const double n = double(image.pixels.size());
  for (int k = 0; k < 3; ++k) {
    double sum = 0.0, sum2 = 0.0;
    for (const Color& p : image.pixels) {
      sum += p[k];
      sum2 += p[k] * p[k];
    }
    const double mean = sum / n;
    const double se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1.0));
    if (c.expect.exact) {
      const double e = c.expect.environment;
      if (std::abs(mean - e) > kSigmas * se + 1e-9 * e)
        return fmt::format("channel {} mean {} ± {} in a lossless furnace of radiance {}", k, mean,
                           se, e);
    }
    const double bound = c.expect.upperBound;
    if (std::isfinite(bound) && mean > bound + kSigmas * se + 1e-9 * bound)
      return fmt::format("channel {} mean {} ± {} exceeds the energy bound {}", k, mean, se, bound);
  }
  return "";
}

/// Runs one case; returns the failure, empty when it passed.
std::string runCase(const soak::Case& c, const Options& options, Tally& tally) {
  try {
    SceneRenderRequest request;
    request.settings.threads = options.threads;
    std::vector<std::string> warnings;
    request.warn = [&](const std::string& w) { warnings.push_back(w); };
    PreparedRender prepared = prepareSceneRender(c.scene, request);
    const RenderResult result =
        render(*prepared.built.scene, *prepared.built.integrator, prepared.options);
    if (c.expect.error) return "the broken input rendered instead of being refused";
    if (std::string why = checkImage(c, result); !why.empty()) return why;
    if (c.expect.repairReported &&
        std::none_of(warnings.begin(), warnings.end(), [&](const std::string& w) {
          return w.find(c.files.back().filename().string()) != std::string::npos;
        }))
      return "the mesh's defects were repaired or kept without a warning naming the file";
    ++tally.rendered;
    tally.exact += c.expect.exact;
    tally.bounded += std::isfinite(c.expect.upperBound);
    if (options.verbose) std::cout << "  rendered\n";
    return "";
  } catch (const Error& e) {
    if (!namesAFile(e.what(), c))
      return fmt::format("refused without naming the file: {}", e.what());
    ++tally.rejected;
    if (options.verbose) std::cout << "  refused: " << e.what() << '\n';
    return "";
  } catch (const std::exception& e) {
    return fmt::format("threw {} instead of quadtri::Error", e.what());
  }
}

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "quadtri_soak: " << why
            << "\nusage: quadtri_soak [--seed S] [--count N] [--first I] [--case I] "
               "[--corpus DIR] [--work DIR] [--keep] [--threads T] [--verbose]\n";
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(a + " needs a value");
      return argv[++i];
    };
    try {
      if (a == "--seed")
        o.seed = std::stoull(value());
      else if (a == "--count")
        o.count = std::stoll(value());
      else if (a == "--first")
        o.first = std::stoi(value());
      else if (a == "--case")
        o.only = std::stoi(value());
      else if (a == "--corpus")
        o.corpus = value();
      else if (a == "--work")
        o.work = value();
      else if (a == "--threads")
        o.threads = std::stoi(value());
      else if (a == "--keep")
        o.keep = true;
      else if (a == "--verbose" || a == "-v")
        o.verbose = true;
      else
        usage("unknown argument " + a);
    } catch (const std::logic_error&) {
      usage("bad number after " + a);
    }
  }
  if (o.count < 0) usage("--count must be 0 (until stopped) or positive");
  if (o.work.empty())
    o.work = fs::temp_directory_path() / fmt::format("quadtri-soak-{}", ::getpid());
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  soak::CaseSources sources;
  sources.meshes = corpusMeshes(options.corpus);
  Tally tally;
  const long long first = options.only ? *options.only : options.first;
  const long long last = options.only ? first + 1 : options.count == 0 ? -1 : first + options.count;
  for (long long i = first; last < 0 || i < last; ++i) {
    const fs::path folder = options.work / fmt::format("case-{}", i);
    std::string failure;
    soak::Case c;
    try {
      c = soak::writeCase(options.seed, int(i), sources, folder);
      if (options.verbose) std::cout << fmt::format("case {}: {}\n", i, c.summary);
      failure = runCase(c, options, tally);
    } catch (const std::exception& e) {
      failure = fmt::format("writing the case failed: {}", e.what());
    }
    ++tally.cases;
    if (!failure.empty()) {
      ++tally.failures;
      std::cout << fmt::format(
          "FAIL seed {} case {}: {}\n  {}\n  reproduce: quadtri_soak --seed {} --case {} "
          "--keep --work DIR{}\n",
          options.seed, i, c.summary, failure, options.seed, i,
          options.corpus.empty() ? "" : " --corpus " + options.corpus.string());
    } else if (!options.keep) {
      fs::remove_all(folder);
    }
    std::cout.flush();
  }
  if (!options.keep && tally.failures == 0) fs::remove_all(options.work);
  std::cout << fmt::format(
      "soak seed {}: {} cases, {} rendered ({} in a lossless furnace, {} under an energy "
      "bound), {} refused with an error naming the file, {} failed\n",
      options.seed, tally.cases, tally.rendered, tally.exact, tally.bounded, tally.rejected,
      tally.failures);
  return tally.failures == 0 ? 0 : 1;
}
