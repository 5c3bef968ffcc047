#include "quadtri/render/render_state.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <string>

#include "quadtri/io/atomic_file.h"
#include "quadtri/math/error.h"

namespace quadtri {
namespace {

constexpr char kMagic[8] = {'Q', 'T', 'R', 'S', 'T', 'A', 'T', 'E'};
constexpr uint32_t kFormatVersion = 1;
constexpr size_t kHeaderBytes = 8 + 4 + 4 + 4 + 8;
constexpr size_t kPixelBytes = 4 + 3 * 8;

template <typename T>
void put(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(value));
}

template <typename T>
T get(const std::string& in, size_t& offset) {
  T value;
  std::memcpy(&value, in.data() + offset, sizeof(value));
  offset += sizeof(value);
  return value;
}

}  // namespace

size_t RenderState::finishedPixels() const {
  size_t n = 0;
  for (uint32_t s : samples) n += s > 0 ? 1 : 0;
  return n;
}

void saveRenderState(const RenderState& state, const std::filesystem::path& path) {
  const size_t n = size_t(state.width) * size_t(state.height);
  if (state.samples.size() != n || state.pixels.size() != n)
    fail("{}: render state of {}x{} pixels holds {} counts and {} values", path.string(),
         state.width, state.height, state.samples.size(), state.pixels.size());
  std::string out;
  out.reserve(kHeaderBytes + n * kPixelBytes);
  out.append(kMagic, sizeof(kMagic));
  put(out, kFormatVersion);
  put(out, uint32_t(state.width));
  put(out, uint32_t(state.height));
  put(out, state.key);
  for (uint32_t s : state.samples) put(out, s);
  for (const Color& c : state.pixels)
    for (int k = 0; k < 3; ++k) put(out, double(c[k]));
  writeTextFile(path, out);
}

RenderState loadRenderState(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot open the render state", name);
  std::error_code ec;
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size < kHeaderBytes)
    fail("{}: not a render state ({} bytes, expected a {}-byte header first)", name, ec ? 0 : size,
         kHeaderBytes);
  std::string header(kHeaderBytes, '\0');
  in.read(header.data(), std::streamsize(header.size()));
  if (std::memcmp(header.data(), kMagic, sizeof(kMagic)) != 0)
    fail("{}: not a render state (expected the magic QTRSTATE)", name);
  size_t offset = sizeof(kMagic);
  const uint32_t version = get<uint32_t>(header, offset);
  if (version != kFormatVersion)
    fail("{}: render state format {}, expected {}", name, version, kFormatVersion);
  RenderState state;
  state.width = int(get<uint32_t>(header, offset));
  state.height = int(get<uint32_t>(header, offset));
  state.key = get<uint64_t>(header, offset);
  const uint64_t n = uint64_t(uint32_t(state.width)) * uint64_t(uint32_t(state.height));
  // n ≤ size / kPixelBytes first: the product below cannot wrap for a lying header.
  if (state.width <= 0 || state.height <= 0 || n > size / kPixelBytes ||
      size != kHeaderBytes + n * kPixelBytes)
    fail("{}: render state of {}x{} pixels should take {} bytes, the file has {}", name,
         state.width, state.height, kHeaderBytes + n * kPixelBytes, size);
  std::string body(size - kHeaderBytes, '\0');
  in.read(body.data(), std::streamsize(body.size()));
  if (!in) fail("{}: cannot read the render state", name);
  offset = 0;
  state.samples.resize(n);
  state.pixels.resize(n, Color::Zero());
  for (uint32_t& s : state.samples) s = get<uint32_t>(body, offset);
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      const double v = get<double>(body, offset);
      if (!std::isfinite(v))
        fail("{}: render state pixel {} (x {}, y {}) has a non-finite value", name, i,
             i % size_t(state.width), i / size_t(state.width));
      state.pixels[i][k] = v;
    }
  return state;
}

}  // namespace quadtri
