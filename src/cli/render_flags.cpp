#include "render_flags.h"

#include "commands.h"
#include "quadtri/math/error.h"

namespace quadtri::cli {

void RenderFlags::add(CLI::App* sub, unsigned which, const std::string& seedHelp) {
  if (which & kModelFlag)
    sub->add_option("--model", model_, "Model for every obj/ply shape, overriding the scene");
  if (which & kModelListFlag)
    sub->add_option("--model", modelList_, "Models, comma-separated (default: every model)")
        ->delimiter(',');
  if (which & kDefineFlag)
    sub->add_option("-D", defines_, "Scene parameter name=value (overrides <default>)");
  if (which & kSppFlag)
    sppOption_ = sub->add_option(
        "--spp", spp_,
        "Samples per pixel: the sampler's sample_count and the cap per pixel of an adaptive "
        "integrator (does not set $spp; -D spp=N does)");
  if (which & kThreadsFlag)
    sub->add_option("--threads", threads_, "Worker threads (0: all)")->capture_default_str();
  if (which & kTimeFlag)
    timeOption_ = sub->add_option(
        "--time", time_, "Time budget in seconds per render; unfinished pixels stay black");
  if (which & kSeedFlag)
    sub->add_option("--seed", seed_,
                    seedHelp.empty() ? "Sampler seed (overrides the sampler)" : seedHelp)
        ->check(wholeNumber());
}

RenderSettings RenderFlags::settings() const {
  RenderSettings settings;
  for (const std::string& d : defines_) addDefine(settings.defines, d);
  if (!model_.empty()) settings.model = model_;
  if (sppOption_ && sppOption_->count() > 0) {
    if (spp_ <= 0) fail("--spp {}: expected a positive count", spp_);
    settings.samplesPerPixel = spp_;
  }
  settings.seed = seed_;
  settings.threads = threads_;
  if (timeOption_ && timeOption_->count() > 0) {
    if (!(time_ > 0.0)) fail("--time {}: expected a positive number of seconds", time_);
    settings.timeLimitSeconds = time_;
  }
  settings.validate("--");
  return settings;
}

std::vector<std::string> RenderFlags::models() const {
  std::vector<std::string> models;
  for (const std::string& item : modelList_)
    for (std::string& name : splitList(item)) {
      checkModelName("--model", name);
      models.push_back(std::move(name));
    }
  return models;
}

}  // namespace quadtri::cli
