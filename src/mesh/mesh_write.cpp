// Mesh export: OBJ and binary PLY, from a whole mesh (saveMesh) or block by block
// (saveMeshStream), written as streams.
#include <fmt/format.h>

#include <array>
#include <cstring>
#include <iterator>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "first_equal.h"
#include "mesh_check.h"
#include "quadtri/io/atomic_stream.h"
#include "quadtri/math/error.h"
#include "quadtri/math/parallel.h"
#include "quadtri/mesh/mesh_io.h"

namespace quadtri {

namespace {

// Writes line(b, i) for every i in [0, count), in order. The lines are formatted in parallel,
// kChunk to a buffer and kWindow buffers at a time, then written in order: the text held is a
// window's, a few MB, and the bytes are those of formatting them one by one.
template <typename Line>
void writeLines(std::ostream& out, size_t count, const Line& line) {
  constexpr size_t kChunk = 16384, kWindow = 8;
  std::vector<fmt::memory_buffer> text(kWindow);
  for (size_t first = 0; first < count; first += kChunk * kWindow) {
    const size_t chunks = std::min(kWindow, (count - first + kChunk - 1) / kChunk);
    parallelFor(size_t(0), chunks, [&](size_t c) {
      fmt::memory_buffer& b = text[c];
      b.clear();
      const size_t begin = first + c * kChunk, end = std::min(count, begin + kChunk);
      for (size_t i = begin; i < end; ++i) line(b, i);
    });
    for (size_t c = 0; c < chunks; ++c) out.write(text[c].data(), std::streamsize(text[c].size()));
  }
}

// OBJ's lines: %.17g, as an ostream with precision 17 writes a double, so that every double
// reads back exactly; indices from 1.
void objPoint(fmt::memory_buffer& b, const char* tag, const Vec3& p) {
  fmt::format_to(std::back_inserter(b), "{} {:.17g} {:.17g} {:.17g}\n", tag, p.x(), p.y(), p.z());
}
void objFace(fmt::memory_buffer& b, const Tri& tri, const Tri* normals) {
  b.push_back('f');
  for (int k = 0; k < 3; ++k) {
    fmt::format_to(std::back_inserter(b), " {}", tri[k] + 1);
    if (normals) fmt::format_to(std::back_inserter(b), "//{}", (*normals)[k] + 1);
  }
  b.push_back('\n');
}

// PLY holds 32-bit floats (what other tools read): a coordinate past a float's range would be
// written as infinite, and no reader could take the file back.
void checkFloatRange(const Vec3& p, size_t vertex, const std::filesystem::path& path) {
  const double largest = p.cwiseAbs().maxCoeff();
  if (!(largest <= double(std::numeric_limits<float>::max())))
    fail(
        "{}: vertex {} has a coordinate of {}, beyond a 32-bit float's range (PLY is written with "
        "floats); write OBJ, which keeps 17 digits",
        path.string(), vertex, largest);
}

// A binary little-endian PLY file's header, and its values through a buffer of about 1 MB.
std::string plyHeader(size_t vertices, bool normals, size_t faces) {
  return fmt::format(
      "ply\nformat binary_little_endian 1.0\ncomment written by quadtri\n"
      "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n{}"
      "element face {}\nproperty list uchar uint vertex_indices\nend_header\n",
      vertices, normals ? "property float nx\nproperty float ny\nproperty float nz\n" : "", faces);
}
class PlyOut {
 public:
  PlyOut(std::ostream& out, std::string header) : out_(out), buffer_(std::move(header)) {}
  void vertex(const Vec3& p, const Vec3* n) {
    for (int k = 0; k < 3; ++k) put(float(p[k]));
    if (n)
      for (int k = 0; k < 3; ++k) put(float((*n)[k]));
    flush(false);
  }
  void face(uint32_t a, uint32_t b, uint32_t c) {
    put(uint8_t(3));
    put(a);
    put(b);
    put(c);
    flush(false);
  }
  void flush(bool always) {
    if (!always && buffer_.size() < (size_t(1) << 20)) return;
    out_.write(buffer_.data(), std::streamsize(buffer_.size()));
    buffer_.clear();
  }

 private:
  template <typename T>
  void put(const T& value) {
    const size_t at = buffer_.size();
    buffer_.resize(at + sizeof(value));
    std::memcpy(buffer_.data() + at, &value, sizeof(value));  // little-endian, as on x86 and ARM
  }
  std::ostream& out_;
  std::string buffer_;
};

}  // namespace

void saveMesh(const TriangleMesh& mesh, const std::filesystem::path& path) {
  const std::string ext = mesh_check::lowerExtension(path);
  for (const Vec3& p : mesh.positions)
    if (!allFinite(p)) fail("{}: refusing to write a non-finite vertex", path.string());
  if (ext != ".obj" && ext != ".ply")
    fail("{}: unsupported output format '{}': expected .obj or .ply", path.string(), ext);
  if (ext == ".ply")
    for (size_t i = 0; i < mesh.positions.size(); ++i) checkFloatRange(mesh.positions[i], i, path);
  // Written as a stream through buffers of a few MB; the text is never whole in memory.
  if (ext == ".obj") {
    writeStreamAtomically(path, [&](std::ostream& out) {
      out << "# written by quadtri\n";
      writeLines(out, mesh.positions.size(),
                 [&](fmt::memory_buffer& b, size_t i) { objPoint(b, "v", mesh.positions[i]); });
      writeLines(out, mesh.normals.size(),
                 [&](fmt::memory_buffer& b, size_t i) { objPoint(b, "vn", mesh.normals[i]); });
      writeLines(out, mesh.triangles.size(), [&](fmt::memory_buffer& b, size_t t) {
        objFace(b, mesh.triangles[t], mesh.hasNormals() ? &mesh.normalIndices[t] : nullptr);
      });
    });
    return;
  }
  // PLY has per-vertex attributes only: split normals become duplicated vertices, one per
  // distinct (position, normal) pair, numbered by first appearance in corner order.
  const size_t corners = 3 * mesh.triangles.size();
  std::vector<uint32_t> vertexOf;  // corner -> PLY vertex (the general case only)
  std::vector<uint32_t> cornerOf;  // PLY vertex -> its first corner
  // Where every corner's normal index is its position index (no normals, or one normal per
  // point, as a tessellated surface without creases has), the pairs are the positions: a PLY
  // vertex per position, numbered by first appearance, with no table per corner.
  const bool onePerPosition = !mesh.hasNormals() || mesh.normalIndices == mesh.triangles;
  std::vector<uint32_t> idOfPosition;  // position -> PLY vertex, in that case
  if (onePerPosition) {
    idOfPosition.assign(mesh.positions.size(), ~0u);
    for (size_t c = 0; c < corners; ++c) {
      uint32_t& v = idOfPosition[mesh.triangles[c / 3][c % 3]];
      if (v == ~0u) {
        v = uint32_t(cornerOf.size());
        cornerOf.push_back(uint32_t(c));
      }
    }
  } else {
    vertexOf.resize(corners);
    std::vector<std::array<uint32_t, 3>> pairs(corners);
    parallelFor(size_t(0), corners, [&](size_t c) {
      pairs[c] = {mesh.triangles[c / 3][c % 3], mesh.normalIndices[c / 3][c % 3], 0};
    });
    const std::vector<uint32_t> head = mesh_detail::firstEqual(pairs);
    for (size_t c = 0; c < corners; ++c) {
      if (head[c] == c) {
        vertexOf[c] = uint32_t(cornerOf.size());
        cornerOf.push_back(uint32_t(c));
      } else {
        vertexOf[c] = vertexOf[head[c]];
      }
    }
  }
  writeStreamAtomically(path, [&](std::ostream& out) {
    PlyOut ply(out, plyHeader(cornerOf.size(), mesh.hasNormals(), mesh.triangles.size()));
    for (const uint32_t c : cornerOf)
      ply.vertex(mesh.positions[mesh.triangles[c / 3][c % 3]],
                 mesh.hasNormals() ? &mesh.normals[mesh.normalIndices[c / 3][c % 3]] : nullptr);
    const auto id = [&](size_t t, int k) {
      return onePerPosition ? idOfPosition[mesh.triangles[t][k]] : vertexOf[3 * t + k];
    };
    for (size_t t = 0; t < mesh.triangles.size(); ++t) ply.face(id(t, 0), id(t, 1), id(t, 2));
    ply.flush(true);
  });
}

void saveMeshStream(const MeshStream& mesh, const std::filesystem::path& path) {
  const std::string ext = mesh_check::lowerExtension(path);
  if (ext != ".obj" && ext != ".ply")
    fail("{}: unsupported output format '{}': expected .obj or .ply", path.string(), ext);
  const size_t extras = mesh.hasNormals ? mesh.extraNormals : 0;
  std::vector<Vec3> positions, normals;
  std::vector<Tri> triangles, normalIndices;
  size_t seen = 0;
  // Block b's points (or, with `extra`, its extra normals and their points' positions).
  const auto points = [&](size_t b, bool extra) {
    positions.clear();
    normals.clear();
    (extra ? mesh.blockExtraNormals : mesh.blockPoints)(b, positions, normals);
    for (size_t i = 0; i < positions.size(); ++i) {
      if (!allFinite(positions[i]))
        fail("{}: refusing to write a non-finite vertex", path.string());
      if (ext == ".ply") checkFloatRange(positions[i], seen + i, path);
    }
    if (mesh.hasNormals && normals.size() != positions.size())
      fail("{}: block {} has {} points and {} normals", path.string(), b, positions.size(),
           normals.size());
    seen += positions.size();
  };
  const auto faces = [&](size_t b) {
    triangles.clear();
    normalIndices.clear();
    mesh.blockTriangles(b, triangles, normalIndices);
    if (!normalIndices.empty() && normalIndices.size() != triangles.size())
      fail("{}: block {} has {} triangles and {} normal triples", path.string(), b,
           triangles.size(), normalIndices.size());
    for (size_t t = 0; t < triangles.size(); ++t)
      for (int k = 0; k < 3; ++k)
        if (triangles[t][k] >= mesh.points ||
            (!normalIndices.empty() && normalIndices[t][k] >= mesh.points + extras))
          fail("{}: triangle {} of block {} names point {} or normal {} of {} and {}",
               path.string(), t, b, triangles[t][k],
               normalIndices.empty() ? triangles[t][k] : normalIndices[t][k], mesh.points,
               mesh.points + extras);
    seen += triangles.size();
  };
  // A corner's normal: its point's, or the one the block names.
  const auto normalOf = [&](size_t t) -> const Tri& {
    return normalIndices.empty() ? triangles[t] : normalIndices[t];
  };
  const auto check = [&](size_t expected, const char* what) {
    if (seen != expected)
      fail("{}: the blocks hold {} {}, not the {} announced", path.string(), seen, what, expected);
    seen = 0;
  };
  writeStreamAtomically(path, [&](std::ostream& out) {
    if (ext == ".obj") {
      out << "# written by quadtri\n";
      for (size_t b = 0; b < mesh.blocks; ++b) {
        points(b, false);
        writeLines(out, positions.size(),
                   [&](fmt::memory_buffer& text, size_t i) { objPoint(text, "v", positions[i]); });
      }
      check(mesh.points, "points");
      if (mesh.hasNormals) {
        for (const bool extra : {false, true}) {
          for (size_t b = 0; b < mesh.blocks && (!extra || extras > 0); ++b) {
            points(b, extra);
            writeLines(out, normals.size(), [&](fmt::memory_buffer& text, size_t i) {
              objPoint(text, "vn", normals[i]);
            });
          }
          check(extra ? extras : mesh.points, extra ? "extra normals" : "points");
        }
      }
      for (size_t b = 0; b < mesh.blocks; ++b) {
        faces(b);
        writeLines(out, triangles.size(), [&](fmt::memory_buffer& text, size_t t) {
          objFace(text, triangles[t], mesh.hasNormals ? &normalOf(t) : nullptr);
        });
      }
      check(mesh.triangles, "triangles");
      return;
    }
    // A vertex per normal: the points with their own, then each extra normal at its point; a
    // corner's vertex is its normal's.
    PlyOut ply(out, plyHeader(mesh.points + extras, mesh.hasNormals, mesh.triangles));
    for (const bool extra : {false, true}) {
      for (size_t b = 0; b < mesh.blocks && (!extra || extras > 0); ++b) {
        points(b, extra);
        for (size_t i = 0; i < positions.size(); ++i)
          ply.vertex(positions[i], mesh.hasNormals ? &normals[i] : nullptr);
      }
      check(extra ? extras : mesh.points, extra ? "extra normals" : "points");
    }
    for (size_t b = 0; b < mesh.blocks; ++b) {
      faces(b);
      for (size_t t = 0; t < triangles.size(); ++t)
        ply.face(normalOf(t)[0], normalOf(t)[1], normalOf(t)[2]);
    }
    check(mesh.triangles, "triangles");
    ply.flush(true);
  });
}

}  // namespace quadtri
