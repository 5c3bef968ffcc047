#include "quadtri/io/image_module.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "quadtri/math/error.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

// The library folder of an install, relative to its prefix (CMake's CMAKE_INSTALL_LIBDIR).
#ifndef QUADTRI_INSTALL_LIBDIR
#define QUADTRI_INSTALL_LIBDIR "lib"
#endif

constexpr const char* kFileName = "libquadtri_image.so";

// Where the module may be: lib/quadtri/ (or LIBDIR/quadtri/, LIBDIR as installed) in the
// folder of the program or library holding this code, or in a folder above it. The build tree
// puts the module in <build>/lib/quadtri/, an install in <prefix>/LIBDIR/quadtri/; the
// programs (bin/, tests/, bench/) and the Python module (LIBDIR/python3/...) lie below both.
std::vector<fs::path> candidates() {
  std::vector<fs::path> paths;
  if (const char* env = std::getenv("QUADTRI_IMAGE_MODULE"); env && *env) {
    paths.emplace_back(env);
    return paths;
  }
  // The object holding this code (a shared library or the Python module), then the program
  // itself (dladdr names the main program only as it was started, perhaps without a folder).
  std::vector<fs::path> starts;
  Dl_info info{};
  static const int anchor = 0;
  std::error_code ec;
  if (dladdr(&anchor, &info) != 0 && info.dli_fname && std::strchr(info.dli_fname, '/'))
    starts.push_back(fs::weakly_canonical(fs::path(info.dli_fname), ec).parent_path());
  if (const fs::path self = fs::read_symlink("/proc/self/exe", ec); !ec)
    starts.push_back(self.parent_path());
  for (fs::path dir : starts)
    for (int up = 0; up < 6 && !dir.empty(); ++up) {
      for (const char* libdir : {"lib", QUADTRI_INSTALL_LIBDIR}) {
        const fs::path path = dir / libdir / "quadtri" / kFileName;
        if (std::find(paths.begin(), paths.end(), path) == paths.end()) paths.push_back(path);
      }
      if (dir == dir.parent_path()) break;
      dir = dir.parent_path();
    }
  return paths;
}

const ImageModule* load() {
  const std::vector<fs::path> paths = candidates();
  std::string tried;
  for (const fs::path& path : paths) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
      tried +=
          "\n  " + path.string() +
          (fs::is_directory(path, ec) ? ": a folder, not the module's file" : ": no such file");
      continue;
    }
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* why = dlerror();
      tried += "\n  " + path.string() + ": " + (why ? why : "dlopen failed");
      continue;
    }
    using Entry = const ImageModule* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, "quadtri_image_module"));
    if (!entry) {
      tried += "\n  " + path.string() + ": no entry point quadtri_image_module";
      continue;
    }
    return entry();  // the handle stays open for the life of the process
  }
  fail(
      "cannot load quadtri's image module {} (it reads and writes image files with "
      "OpenImageIO); set QUADTRI_IMAGE_MODULE to its path. Tried:{}",
      kFileName, tried.empty() ? std::string("\n  nowhere: no folder to look in") : tried);
}

}  // namespace

const ImageModule& imageModule() {
  // Not a function-local static initialised by load(): a failed load throws, and the next
  // call should say why again rather than see a half-made object.
  static std::mutex mutex;
  static const ImageModule* module = nullptr;
  std::lock_guard lock(mutex);
  if (!module) module = load();
  return *module;
}

}  // namespace quadtri
