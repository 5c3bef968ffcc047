// `quadtri render SCENE.xml -o out.exr [-o out.png]`: renders a Mitsuba-style scene.
#include <fmt/core.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>

#include "commands.h"
#include "quadtri/math/error.h"
#include "quadtri/render/image_io.h"
#include "quadtri/scene/scene_render.h"
#include "quadtri/surface/model.h"

namespace quadtri::cli {
namespace {

// Set by SIGINT: the renderer stops starting pixels and the image so far is written.
std::atomic<bool> interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void onInterrupt(int) {
  interrupted.store(true);
}

}  // namespace

Action addRenderCommand(CLI::App& app) {
  struct Options {
    std::string scene, model;
    std::vector<std::string> outputs, defines;
    int spp = 0, threads = 0;
    double timeLimit = 0.0;
    std::optional<uint64_t> seed;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "render", "Render a Mitsuba 3 XML scene to EXR (linear) and/or PNG (sRGB)");
  sub->add_option("scene", opt->scene, "Scene file (.xml)")->required()->check(CLI::ExistingFile);
  sub->add_option("-o,--output", opt->outputs, "Output image, .exr or .png (may be given twice)")
      ->required();
  sub->add_option("--model", opt->model, "Model for every obj/ply shape, overriding the scene")
      ->check(CLI::IsMember(modelNames()));
  sub->add_option("-D", opt->defines, "Scene parameter name=value (overrides <default>)");
  CLI::Option* sppOption = sub->add_option(
      "--spp", opt->spp,
      "Samples per pixel (overrides the sampler; the cap per pixel of an adaptive integrator)");
  sub->add_option("--threads", opt->threads, "Worker threads (0: all)")->capture_default_str();
  CLI::Option* timeOption = sub->add_option("--time", opt->timeLimit,
                                            "Time budget in seconds; unfinished pixels stay black");
  sub->add_option("--seed", opt->seed, "Sampler seed (overrides the sampler)");
  return [opt, sppOption, timeOption]() {
    const bool sppGiven = sppOption->count() > 0, timeGiven = timeOption->count() > 0;
    SceneDefines defines;
    for (const std::string& d : opt->defines) {
      const size_t eq = d.find('=');
      if (eq == std::string::npos || eq == 0) fail("-D {}: expected name=value", d);
      defines[d.substr(0, eq)] = d.substr(eq + 1);
    }
    for (const std::string& out : opt->outputs) {
      const std::string ext = std::filesystem::path(out).extension().string();
      if (ext != ".exr" && ext != ".png") fail("output {}: expected a .exr or .png file", out);
    }
    if (sppGiven && opt->spp <= 0) fail("--spp {}: expected a positive count", opt->spp);
    if (opt->threads < 0) fail("--threads {}: expected 0 (all) or a positive count", opt->threads);
    if (timeGiven && !(opt->timeLimit > 0.0))
      fail("--time {}: expected a positive number of seconds", opt->timeLimit);

    SceneRenderRequest request;
    request.defines = defines;
    if (!opt->model.empty()) request.model = opt->model;
    if (sppGiven) request.samplesPerPixel = opt->spp;
    request.seed = opt->seed;
    request.threads = opt->threads;
    request.timeLimitSeconds = opt->timeLimit;
    request.warn = [](const std::string& message) { fmt::print(stderr, "warning: {}\n", message); };
    PreparedRender prepared = prepareSceneRender(opt->scene, request);
    const BuiltScene& built = prepared.built;
    RenderOptions& options = prepared.options;
    options.cancel = &interrupted;
    options.progress = isatty(STDERR_FILENO) != 0;

    const auto previous = std::signal(SIGINT, onInterrupt);
    const RenderResult result = render(*built.scene, *built.integrator, options);
    std::signal(SIGINT, previous);

    for (const std::string& out : opt->outputs) {
      const size_t replaced = writeImage(result.image, out);
      if (replaced)
        fmt::print(stderr, "warning: {}: {} non-finite values written as 0\n", out, replaced);
      fmt::print("wrote {}\n", out);
    }
    const RenderStats& s = result.stats;
    fmt::print("integrator      {}\n", built.integrator->toString());
    fmt::print("image           {}x{}, {:.1f} samples/pixel{}\n", result.image.width,
               result.image.height, s.meanSamplesPerPixel(),
               s.unfinishedPixels ? fmt::format(" over the {} finished pixels",
                                                result.image.pixels.size() - s.unfinishedPixels)
                                  : std::string());
    fmt::print("wall time       {:.3f} s\n", s.seconds);
    fmt::print("samples         {}\n", s.samples);
    fmt::print("rays traced     {}\n", s.rays);
    fmt::print("rays/s          {:.3g}\n", s.seconds > 0 ? double(s.rays) / s.seconds : 0.0);
    fmt::print("primitives      {} (from {} input triangles)\n", built.scene->primitiveCount(),
               built.inputTriangles);
    fmt::print("geometry memory {:.2f} MiB\n",
               double(built.scene->geometryBytes()) / (1024.0 * 1024.0));
    if (s.nonFiniteSamples)
      fmt::print(stderr, "warning: {} NaN/Inf samples dropped\n", s.nonFiniteSamples);
    if (s.unfinishedPixels)
      fmt::print(stderr, "warning: {} of {} pixels not rendered ({}), left black\n",
                 s.unfinishedPixels, result.image.pixels.size(),
                 interrupted.load() ? "interrupted" : "time limit");
    return interrupted.load() ? 130 : 0;
  };
}

}  // namespace quadtri::cli
