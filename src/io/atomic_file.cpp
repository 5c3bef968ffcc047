#include "quadtri/io/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <fstream>

#include "quadtri/math/error.h"

namespace quadtri {

void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path& tmp)>& write) {
  namespace fs = std::filesystem;
  static std::atomic<unsigned> counter{0};
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(dir)) fail("{}: the folder {} does not exist", path.string(), dir.string());
  const fs::path tmp = dir / fmt::format(".{}.{}-{}.tmp{}", path.stem().string(), ::getpid(),
                                         counter++, path.extension().string());
  try {
    write(tmp);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    fail("{}: cannot write ({})", path.string(), ec.message());
  }
}

void writeTextFile(const std::filesystem::path& path, const std::string& text) {
  writeAtomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out) fail("{}: cannot write", path.string());
  });
}

}  // namespace quadtri
