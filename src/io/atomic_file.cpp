#include "quadtri/io/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cstring>
#include <fstream>
#include <vector>

#include "quadtri/io/atomic_stream.h"
#include "quadtri/math/error.h"

namespace quadtri {
namespace {

// The temporary files being written, for removeTemporaryFilesNow: a fixed table that a signal
// handler can read without locks or allocation. A slot is 0 (free), 1 (being filled) or 2 (its
// path is a temporary file that may exist).
constexpr int kSlots = 32;
constexpr size_t kPathBytes = 4096;
struct TempSlot {
  std::atomic<int> state{0};
  char path[kPathBytes];
};
TempSlot tempSlots[kSlots];
static_assert(std::atomic<int>::is_always_lock_free, "signal handlers read the slots");

// Records `tmp` before it is created; -1 when the table is full or the path too long (the file
// is then only removed by the normal paths).
int registerTemporary(const std::filesystem::path& tmp) {
  const std::string& text = tmp.native();
  if (text.size() >= kPathBytes) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (tempSlots[i].state.compare_exchange_strong(expected, 1)) {
      std::memcpy(tempSlots[i].path, text.c_str(), text.size() + 1);
      tempSlots[i].state.store(2, std::memory_order_release);
      return i;
    }
  }
  return -1;
}

void unregisterTemporary(int slot) {
  if (slot >= 0) tempSlots[slot].state.store(0, std::memory_order_release);
}

}  // namespace

void removeTemporaryFilesNow() noexcept {
  for (TempSlot& slot : tempSlots)
    if (slot.state.load(std::memory_order_acquire) == 2) ::unlink(slot.path);
}

void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path& tmp)>& write) {
  namespace fs = std::filesystem;
  static std::atomic<unsigned> counter{0};
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(dir)) fail("{}: the folder {} does not exist", path.string(), dir.string());
  const fs::path tmp = dir / fmt::format(".{}.{}-{}.tmp{}", path.stem().string(), ::getpid(),
                                         counter++, path.extension().string());
  const int slot = registerTemporary(tmp);
  try {
    write(tmp);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    unregisterTemporary(slot);
    throw;
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
  }
  unregisterTemporary(slot);
  if (ec) fail("{}: cannot write ({})", path.string(), ec.message());
}

void writeStreamAtomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream& out)>& write) {
  writeAtomically(path, [&](const std::filesystem::path& tmp) {
    std::vector<char> buffer(size_t(1) << 20);
    std::ofstream out;
    out.rdbuf()->pubsetbuf(buffer.data(), std::streamsize(buffer.size()));
    out.open(tmp, std::ios::binary);
    if (!out) fail("{}: cannot write", path.string());
    write(out);
    out.close();
    if (!out) fail("{}: cannot write", path.string());
  });
}

void checkDistinctFiles(const std::vector<std::filesystem::path>& inputs,
                        const std::filesystem::path& output, const std::string& what) {
  namespace fs = std::filesystem;
  // One file under two names when both exist and are equivalent (a link, "a/../b"); a name that
  // does not exist is only itself.
  const auto same = [](const fs::path& a, const fs::path& b) {
    std::error_code ec;
    if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec) && !ec;
    return a.lexically_normal() == b.lexically_normal();
  };
  for (size_t i = 0; i < inputs.size(); ++i) {
    if (same(inputs[i], output))
      fail("{}: the output is also an input ({} {}): writing it would replace what is read",
           output.string(), what, i + 1);
    for (size_t j = 0; j < i; ++j)
      if (same(inputs[j], inputs[i]))
        fail("{}: given twice ({}s {} and {}{})", inputs[i].string(), what, j + 1, i + 1,
             inputs[j] == inputs[i] ? "" : fmt::format(", as {}", inputs[j].string()));
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
