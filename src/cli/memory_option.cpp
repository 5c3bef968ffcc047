// `--max-memory`, shared by convert, analyze and render.
#include <fmt/core.h>

#include <memory>

#include "commands.h"
#include "quadtri/io/memory_limit.h"

namespace quadtri::cli {

std::function<uint64_t()> addMaxMemoryOption(CLI::App& sub) {
  auto text = std::make_shared<std::string>();
  sub.add_option("--max-memory", *text,
                 fmt::format("Refuse a mesh (or image) whose estimated memory exceeds BYTES, or "
                             "NNG / NNM (binary units); default {:.0f}% of the physical memory, "
                             "{} here",
                             100.0 * kDefaultMemoryShare, formatBytes(defaultMemoryLimit())));
  return [text]() { return text->empty() ? defaultMemoryLimit() : parseByteSize(*text); };
}

}  // namespace quadtri::cli
