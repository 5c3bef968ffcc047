// `--spp`, `--model`, `--seed`, `-D`, `--threads` and `--time`: registered on every command
// that takes them from this one place, with one help text each, and parsed into the library's
// RenderSettings (quadtri/scene/render_settings.h), so they mean the same in `render`, `figure`
// and `study`.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "quadtri/scene/render_settings.h"

namespace quadtri::cli {

/// Which of the shared options a command takes.
enum RenderFlag : unsigned {
  kSppFlag = 1u << 0,        ///< --spp N
  kModelFlag = 1u << 1,      ///< --model NAME (one model for every obj/ply shape)
  kModelListFlag = 1u << 2,  ///< --model A,B,... (the models a command measures; study)
  kSeedFlag = 1u << 3,       ///< --seed N
  kDefineFlag = 1u << 4,     ///< -D name=value (repeatable)
  kThreadsFlag = 1u << 5,    ///< --threads N
  kTimeFlag = 1u << 6,       ///< --time SECONDS
};

class RenderFlags {
 public:
  /// Registers the options `which` names on `sub`. `seedHelp` replaces --seed's help where the
  /// seed drives something else than the sampler (study: the crack-rate lines).
  void add(CLI::App* sub, unsigned which, const std::string& seedHelp = "");
  /// The options given, checked: "--spp 0: expected a positive count", "-D x: expected
  /// name=value", "--model NAME: unknown model; ...", "--time 0: expected a positive number of
  /// seconds" (a given --time must be positive), "--threads -1: ...".
  RenderSettings settings() const;
  /// --model as a list (kModelListFlag), each name checked; empty when not given.
  std::vector<std::string> models() const;

 private:
  std::string model_;
  std::vector<std::string> modelList_, defines_;
  int spp_ = 0, threads_ = 0;
  double time_ = 0.0;
  std::optional<uint64_t> seed_;
  CLI::Option* sppOption_ = nullptr;
  CLI::Option* timeOption_ = nullptr;
};

}  // namespace quadtri::cli
