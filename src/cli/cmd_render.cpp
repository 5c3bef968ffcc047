// `quadtri render SCENE.xml -o out.exr [-o out.png]`: renders a Mitsuba-style scene.
#include <fmt/core.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>

#include "commands.h"
#include "normal_flags.h"
#include "quadtri/io/image_module.h"
#include "quadtri/io/memory_limit.h"
#include "quadtri/io/stop_signals.h"
#include "quadtri/math/error.h"
#include "quadtri/render/image_io.h"
#include "quadtri/render/render_state.h"
#include "quadtri/render/tiles.h"
#include "quadtri/scene/render_key.h"
#include "quadtri/scene/scene_render.h"
#include "render_flags.h"

namespace quadtri::cli {
namespace {

// What the pixels got, for the message of a stopped render: "1200 of 4800 pixels got 16
// samples each, the other 3600 got none (black)".
std::string samplesPerPixelReport(const RenderStats& s, size_t pixels) {
  if (s.finishedPixels == 0)
    return fmt::format("none of the {} pixels got a sample (all black)", pixels);
  const std::string got =
      s.minPixelSamples == s.maxPixelSamples
          ? fmt::format("{} samples each", s.minPixelSamples)
          : fmt::format("{} to {} samples ({:.1f} on average)", s.minPixelSamples,
                        s.maxPixelSamples, s.meanSamplesPerPixel());
  if (s.finishedPixels == pixels) return fmt::format("every pixel got {}", got);
  return fmt::format("{} of {} pixels got {}, the other {} got none (black)", s.finishedPixels,
                     pixels, got, pixels - s.finishedPixels);
}

}  // namespace

Action addRenderCommand(CLI::App& app) {
  struct Options {
    std::string scene;
    std::vector<std::string> outputs;
    double checkpoint = 0.0;
    RenderFlags flags;
    NormalFlags normals;
    std::string resume, crop, tile;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "render", "Render a Mitsuba 3 XML scene to EXR (linear) and/or PNG (sRGB)");
  sub->add_option("scene", opt->scene, "Scene file (.xml)")->required()->check(CLI::ExistingFile);
  sub->add_option("-o,--output", opt->outputs, "Output image, .exr or .png (may be given twice)")
      ->required()
      ->check(outputFile());
  opt->flags.add(sub, kModelFlag | kDefineFlag | kSppFlag | kThreadsFlag | kTimeFlag | kSeedFlag);
  addNormalFlags(sub, opt->normals,
                 "Shading normals of every obj/ply shape, overriding the scene's: file (as "
                 "given; angle-weighted and split at --crease-angle when missing), average "
                 "(thesis eq. 2.8) or angle (angle-weighted, split at --crease-angle)",
                 "");
  const auto maxMemory = addMaxMemoryOption(*sub);
  CLI::Option* checkpointOption = sub->add_option(
      "--checkpoint", opt->checkpoint,
      "Every SECONDS, save the finished pixels to FIRST_OUTPUT.state (and when stopped early), "
      "for --resume; removed once the image is complete (as is FIRST_OUTPUT.state when "
      "--resume read it)");
  sub->add_option("--resume", opt->resume,
                  "Resume the render saved in STATE (by --checkpoint): only the pixels it lacks "
                  "are rendered; refused unless the scene, options, seed and version match")
      ->check(CLI::ExistingFile);
  sub->add_option("--crop", opt->crop,
                  "Render only the film window X,Y,W,H (replaces the scene's crop window); the "
                  "EXR keeps its place on the film, for `quadtri merge`");
  sub->add_option("--tile", opt->tile,
                  "Render only tile I of N (1 <= I <= N): film rows [(I-1)*H/N, I*H/N), for "
                  "`quadtri merge`");
  return [opt, checkpointOption, maxMemory]() {
    const bool checkpointGiven = checkpointOption->count() > 0;
    const RenderSettings settings = opt->flags.settings();
    for (const std::string& out : opt->outputs) {
      const std::string ext = std::filesystem::path(out).extension().string();
      if (ext != ".exr" && ext != ".png") fail("output {}: expected a .exr or .png file", out);
    }
    std::optional<PixelWindow> crop;
    std::optional<TileIndex> tile;
    if (!opt->crop.empty()) crop = PixelWindow::parse(opt->crop);
    if (!opt->tile.empty()) tile = TileIndex::parse(opt->tile);
    if (crop && tile) fail("--crop and --tile: give one or the other");
    if (crop || tile)
      for (const std::string& out : opt->outputs)
        if (std::filesystem::path(out).extension() != ".exr")
          fail(
              "output {}: {} renders a window of the film, written as .exr only (its data "
              "window places it on the film); merge the tiles with `quadtri merge`",
              out, crop ? "--crop" : "--tile");
    // The image module now, so that a missing one stops the command before the render rather
    // than after it.
    if (!opt->outputs.empty()) imageModule();
    if (checkpointGiven && !(opt->checkpoint > 0.0))
      fail("--checkpoint {}: expected a positive number of seconds", opt->checkpoint);
    const uint64_t memoryLimit = maxMemory();

    // From here SIGINT, SIGTERM and SIGHUP stop the render and the pixels so far are written;
    // a second one ends the process at once, leaving no temporary file.
    const StopSignals signals;

    SceneRenderRequest request;
    request.settings = settings;
    request.crop = crop;
    request.tile = tile;
    request.normals = opt->normals.sourceOverride();
    request.creaseAngleDegrees = opt->normals.creaseOverride();
    request.maxMemoryBytes = memoryLimit;
    request.warn = [](const std::string& message) { fmt::print(stderr, "warning: {}\n", message); };
    request.note = [](const std::string& message) { fmt::print(stderr, "{}\n", message); };
    // The fold and fallback warnings evaluate every corner of each model: run after the image,
    // they do not hold back its first pixel (a render stopped before it starts prints none).
    request.deferModelChecks = true;
    // Time to first pixel counts from here: the scene's loading, conversion and acceleration
    // structure, then the render until its first pixel is finished.
    const auto commandStart = std::chrono::steady_clock::now();
    PreparedRender prepared = prepareSceneRender(opt->scene, request);
    const double buildSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - commandStart).count();
    const SceneDescription& description = prepared.description;
    const BuiltScene& built = prepared.built;
    RenderOptions& options = prepared.options;
    options.cancel = &StopSignals::stopRequested();
    options.progress = isatty(STDERR_FILENO) != 0;
    const PerspectiveCamera& camera = built.scene->camera();

    // Checkpoints and resuming: a state is only resumed by the render that saved it.
    const std::optional<std::string>& modelOverride = settings.model;
    const RenderKeys keys = renderKeys(description, options, modelOverride, &built.fileDigests);
    const uint64_t key = keys.render;
    std::optional<RenderState> resumed;
    if (!opt->resume.empty()) {
      resumed = loadRenderState(opt->resume);
      checkResumable(*resumed, key, camera.width(), camera.height(), opt->resume);
      options.resume = &*resumed;
      fmt::print(stderr, "resuming {}: {} of {} pixels already rendered\n", opt->resume,
                 resumed->finishedPixels(), resumed->samples.size());
    }
    const std::filesystem::path statePath = opt->outputs.front() + ".state";
    if (checkpointGiven) {
      options.checkpointSeconds = opt->checkpoint;
      options.stateKey = key;
      options.checkpoint = [statePath](const RenderState& state) {
        saveRenderState(state, statePath);
      };
    }

    if (const int sig = StopSignals::signalNumber()) {
      fmt::print(stderr, "quadtri: stopped by {} before rendering; nothing written\n",
                 StopSignals::signalName(sig));
      return 128 + sig;
    }
    if (crop || tile)
      fmt::print(
          stderr, "{}: window {} of the {}x{} film\n",
          tile ? "tile " + tile->toString() : std::string("crop"),
          PixelWindow{camera.cropX(), camera.cropY(), camera.width(), camera.height()}.toString(),
          camera.filmWidth(), camera.filmHeight());
    fmt::print(stderr, "rendering {}x{}, {} samples/pixel{}\n", camera.width(), camera.height(),
               built.integrator->adaptive()
                   ? fmt::format("up to {}", built.integrator->adaptive()->maxSamples)
                   : std::to_string(options.samplesPerPixel),
               settings.threads > 0 ? fmt::format(", {} thread{}", settings.threads,
                                                  settings.threads == 1 ? "" : "s")
                                    : std::string());
    const RenderResult result = render(*built.scene, *built.integrator, options);
    if (!result.checkpointError.empty())
      fmt::print(stderr, "warning: checkpoints stopped: {}\n", result.checkpointError);
    // An image that is not complete leaves its state behind to resume (saved before the
    // images, so a second signal while they are written keeps it); a complete one removes the
    // checkpoint once the images are written.
    std::string saved;
    if (checkpointGiven && result.stats.unfinishedPixels > 0) {
      saveRenderState(result.state(key), statePath);
      saved = fmt::format("; saved {}, resume with --resume {}", statePath.string(),
                          statePath.string());
    }
    // An EXR keeps its window's place on the film and what `quadtri merge` checks.
    ImageFrame frame;
    frame.x = camera.cropX();
    frame.y = camera.cropY();
    frame.filmWidth = camera.filmWidth();
    frame.filmHeight = camera.filmHeight();
    frame.attributes = {
        {tile_attribute::kSceneKey, fmt::format("{:016x}", keys.film)},
        {tile_attribute::kScene, std::filesystem::path(opt->scene).filename().string()},
        {tile_attribute::kSeed, std::to_string(options.seed)},
        {tile_attribute::kSamples, std::to_string(options.samplesPerPixel)},
        {tile_attribute::kModel, modelOverride.value_or("scene")},
        {tile_attribute::kUnfinished, std::to_string(result.stats.unfinishedPixels)},
        {tile_attribute::kTile, tile   ? tile->toString()
                                : crop ? std::string("crop")
                                       : (frame.wholeFilm(result.image) ? "film" : "crop")}};
    for (const std::string& out : opt->outputs) {
      const bool exr = std::filesystem::path(out).extension() == ".exr";
      const size_t replaced =
          exr ? writeImage(result.image, out, frame) : writeImage(result.image, out);
      if (replaced)
        fmt::print(stderr, "warning: {}: {} non-finite values written as 0\n", out, replaced);
      fmt::print("wrote {}\n", out);
    }
    // A complete image needs no state: the one its checkpoints saved, or the one it resumed
    // when that is this output's own (FIRST_OUTPUT.state), which would otherwise be resumed
    // again by the next --resume.
    std::error_code ignored;
    const bool resumedOwnState =
        !opt->resume.empty() && std::filesystem::equivalent(opt->resume, statePath, ignored);
    if ((checkpointGiven || resumedOwnState) && result.stats.unfinishedPixels == 0)
      std::filesystem::remove(statePath, ignored);
    // The model checks left for after the image (deferModelChecks), once the images and the
    // state are safe (a second signal meanwhile loses nothing), and without the acceleration
    // structure, whose memory their buffers then take instead of adding to the peak.
    const size_t primitives = built.scene->primitiveCount();
    const size_t geometryBytes = built.scene->geometryBytes();
    if (!built.modelChecks.empty()) {
      prepared.built.scene.reset();
      for (const ModelCheck& check : built.modelChecks)
        if (const std::optional<std::string> warning = check()) request.warn(*warning);
    }
    const RenderStats& s = result.stats;
    fmt::print("integrator      {}\n", built.integrator->toString());
    fmt::print("image           {}x{}, {:.1f} samples/pixel{}\n", result.image.width,
               result.image.height, s.meanSamplesPerPixel(),
               s.unfinishedPixels ? fmt::format(" over the {} finished pixels",
                                                result.image.pixels.size() - s.unfinishedPixels)
                                  : std::string());
    fmt::print("wall time       {:.3f} s\n", s.seconds);
    fmt::print("scene build     {:.3f} s (loading, conversion, acceleration structure)\n",
               buildSeconds);
    if (s.finishedPixels > s.resumedPixels)
      fmt::print("first pixel     {:.3f} s after the scene file was opened\n",
                 buildSeconds + s.firstPixelSeconds);
    fmt::print("samples         {}\n", s.samples);
    fmt::print("rays traced     {}\n", s.rays);
    fmt::print("rays/s          {:.3g}\n", s.seconds > 0 ? double(s.rays) / s.seconds : 0.0);
    fmt::print("primitives      {} (from {} input triangles)\n", primitives, built.inputTriangles);
    fmt::print("geometry memory {:.2f} MiB\n", double(geometryBytes) / (1024.0 * 1024.0));
    fmt::print("peak memory     {:.2f} MiB (resident)\n",
               double(peakResidentBytes()) / (1024.0 * 1024.0));
    if (s.nonFiniteSamples)
      fmt::print(stderr, "warning: {} NaN/Inf samples dropped\n", s.nonFiniteSamples);
    if (const int sig = StopSignals::signalNumber()) {
      fmt::print(stderr, "quadtri: stopped by {}{}: {}; wrote {}{}\n", StopSignals::signalName(sig),
                 s.stopped ? "" : " after the render",
                 samplesPerPixelReport(s, result.image.pixels.size()),
                 fmt::join(opt->outputs, ", "), saved);
      return 128 + sig;
    }
    if (s.unfinishedPixels)
      fmt::print(stderr, "warning: {} of {} pixels not rendered (time limit), left black{}\n",
                 s.unfinishedPixels, result.image.pixels.size(), saved);
    return 0;
  };
}

}  // namespace quadtri::cli
