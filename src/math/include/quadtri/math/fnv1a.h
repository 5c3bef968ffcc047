// 64-bit FNV-1a: the hash of a file's bytes that render keys and mesh loading share.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string_view>

namespace quadtri {

struct Fnv1a {
  uint64_t hash = 0xcbf29ce484222325ULL;
  void bytes(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) hash = (hash ^ p[i]) * 0x100000001b3ULL;
  }
};

/// A file's identity as read: the FNV-1a of its bytes and their count.
struct FileDigest {
  uint64_t hash = 0;
  uint64_t bytes = 0;
  static FileDigest of(std::string_view content) {
    Fnv1a h;
    h.bytes(content.data(), content.size());
    return {h.hash, uint64_t(content.size())};
  }
};

/// The digests of files already read, by the path they were read from.
using FileDigests = std::map<std::filesystem::path, FileDigest>;

}  // namespace quadtri
