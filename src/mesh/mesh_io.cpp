#include "quadtri/mesh/mesh_io.h"

#include <assimp/DefaultIOSystem.h>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <string_view>

#include "first_equal.h"
#include "mesh_check.h"
#include "quadtri/io/atomic_file.h"
#include "quadtri/io/atomic_stream.h"
#include "quadtri/io/memory_limit.h"
#include "quadtri/math/error.h"
#include "quadtri/math/large_array.h"
#include "quadtri/math/parallel.h"
#include "quadtri/math/parallel_invoke.h"
#include "quadtri/mesh/mesh_reader.h"

namespace quadtri {
namespace {

// Assimp's file system, but the mesh file itself is served from the bytes the loader has read
// (and checked) already, so the file is read once; any other file it opens (an OBJ's mtllib)
// comes from the disk as before.
class BufferIoSystem : public Assimp::IOSystem {
 public:
  BufferIoSystem(std::string name, std::string_view bytes)
      : name_(std::move(name)), bytes_(bytes) {}
  bool Exists(const char* file) const override { return file == name_ || disk_.Exists(file); }
  char getOsSeparator() const override { return disk_.getOsSeparator(); }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (file == name_ && std::string_view(mode).find_first_of("wa+") == std::string_view::npos)
      return new Assimp::MemoryIOStream(reinterpret_cast<const uint8_t*>(bytes_.data()),
                                        bytes_.size(), false);
    return disk_.Open(file, mode);
  }
  void Close(Assimp::IOStream* file) override { delete file; }

 private:
  std::string name_;
  std::string_view bytes_;
  mutable Assimp::DefaultIOSystem disk_;
};

// One mesh as a reader gives it (Assimp's post-processed scene, or the native OBJ or OFF
// reader): its vertices, their normals (when the file has them) and its triangles. A vertex's
// position is row pointOf[v] of `points` (row v without pointOf), its normal row normalOf[v] of
// `normals` likewise: the native OBJ reader's vertices are face corners (as Assimp's OBJ importer
// lays them out), which index the file's v and vn lines. The native OFF reader's vertices are the
// file's vertex lines, as Assimp's OFF importer gave them, and its triangles are `corners`, 3
// vertices each. Without faces or corners, vertices 3f, 3f+1 and 3f+2 make triangle f.
struct Part {
  // Assimp's rows are floats, the native readers' doubles: one of each pair is set.
  const aiVector3D* points = nullptr;
  const mesh_check::Point3* exactPoints = nullptr;
  size_t pointCount = 0;
  const uint32_t* pointOf = nullptr;
  const aiVector3D* normals = nullptr;
  const mesh_check::Point3* exactNormals = nullptr;
  size_t normalCount = 0;
  const uint32_t* normalOf = nullptr;
  size_t vertexCount = 0;
  const aiFace* faces = nullptr;
  size_t faces_ = 0;
  const uint32_t* corners = nullptr;
  size_t cornerCount = 0;
  std::array<double, 3> point(size_t r) const {
    if (exactPoints) return exactPoints[r];
    return {double(points[r].x), double(points[r].y), double(points[r].z)};
  }
  Vec3 normal(size_t r) const {
    if (exactNormals) return Vec3(exactNormals[r][0], exactNormals[r][1], exactNormals[r][2]);
    return Vec3(normals[r].x, normals[r].y, normals[r].z);
  }
  uint32_t pointRow(size_t v) const { return pointOf ? pointOf[v] : uint32_t(v); }
  uint32_t normalRow(size_t v) const { return normalOf ? normalOf[v] : uint32_t(v); }
  size_t faceCount() const { return faces ? faces_ : corners ? cornerCount / 3 : vertexCount / 3; }
  /// Face f's corners; false when it is not a triangle (skipped).
  bool triangle(size_t f, std::array<uint32_t, 3>& out) const {
    if (corners) {
      out = {corners[3 * f], corners[3 * f + 1], corners[3 * f + 2]};
      return true;
    }
    if (!faces) {
      out = {uint32_t(3 * f), uint32_t(3 * f + 1), uint32_t(3 * f + 2)};
      return true;
    }
    if (faces[f].mNumIndices != 3) return false;
    out = {faces[f].mIndices[0], faces[f].mIndices[1], faces[f].mIndices[2]};
    return true;
  }
};

// Row bases of `count(part)` rows per part, and the total (over 2^32 - 1: an error).
template <typename Count>
std::vector<size_t> bases(const std::string& name, const std::vector<Part>& parts,
                          const Count& count) {
  std::vector<size_t> base(parts.size() + 1, 0);
  for (size_t m = 0; m < parts.size(); ++m) base[m + 1] = base[m] + count(parts[m]);
  if (base.back() > size_t(std::numeric_limits<uint32_t>::max()))
    fail("{}: {} vertices, more than the {} a mesh can index", name, base.back(),
         std::numeric_limits<uint32_t>::max());
  return base;
}

// The welded mesh of the parts: positions welded by exact equality and numbered by first
// appearance (part by part, vertex by vertex), each with the value of its first vertex; normals
// (allHaveNormals) welded likewise, each part's new ones numbered before the face normals that
// replace its broken ones.
TriangleMesh weldParts(const std::string& name, const std::vector<Part>& parts,
                       bool allHaveNormals) {
  const std::vector<size_t> base = bases(name, parts, [](const Part& p) { return p.vertexCount; });
  const std::vector<size_t> pointBase =
      bases(name, parts, [](const Part& p) { return p.pointCount; });
  const std::vector<size_t> normalBase =
      bases(name, parts, [&](const Part& p) { return allHaveNormals ? p.normalCount : 0; });
  // Positions as the readers give them (doubles; Assimp's floats widened), normals as the mesh
  // keeps them (unit doubles).
  std::vector<std::array<double, 3>> pointKeys =
      largeVector<std::array<double, 3>>(pointBase.back());
  std::vector<std::array<double, 3>> normalKeys =
      largeVector<std::array<double, 3>>(normalBase.back());
  std::vector<char> normalOk(normalBase.back(), 0);
  for (size_t m = 0; m < parts.size(); ++m) {
    const Part& part = parts[m];
    parallelFor(size_t(0), part.pointCount,
                [&](size_t r) { pointKeys[pointBase[m] + r] = part.point(r); });
    if (!allHaveNormals) continue;
    parallelFor(size_t(0), part.normalCount, [&](size_t r) {
      const Vec3 n = part.normal(r);
      // A zero or broken normal in the file is replaced by the face normal below; its key (zero)
      // matches no unit normal.
      const size_t i = normalBase[m] + r;
      normalOk[i] = allFinite(n) && n.norm() > 1e-12;
      const Vec3 unit = normalOk[i] ? Vec3(n.normalized()) : Vec3::Zero();
      normalKeys[i] = {unit.x(), unit.y(), unit.z()};
    });
  }
  for (size_t m = 0; m < parts.size(); ++m)
    for (size_t v = 0; v < parts[m].vertexCount; ++v) {
      const std::array<double, 3>& p = pointKeys[pointBase[m] + parts[m].pointRow(v)];
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
        fail("{}: vertex {} of mesh {} has a non-finite coordinate", name, v, m);
    }
  // Welded by exact equality (the rows of equal points have one first row), numbered by the
  // first vertex that uses them.
  const std::vector<uint32_t> firstPoint = mesh_detail::firstEqual(pointKeys);
  const std::vector<uint32_t> firstNormal = mesh_detail::firstEqual(normalKeys);
  TriangleMesh mesh;
  std::vector<uint32_t> pos = largeVector<uint32_t>(base.back()),
                        nrm = largeVector<uint32_t>(allHaveNormals ? base.back() : 0);
  {
    std::vector<uint32_t> idOfRow = largeVector(pointBase.back(), ~0u);
    for (size_t m = 0; m < parts.size(); ++m)
      for (size_t v = 0; v < parts[m].vertexCount; ++v) {
        const size_t row = pointBase[m] + parts[m].pointRow(v);
        uint32_t& id = idOfRow[firstPoint[row]];
        if (id == ~0u) {
          id = uint32_t(mesh.positions.size());
          const std::array<double, 3>& p = pointKeys[row];
          mesh.positions.emplace_back(p[0], p[1], p[2]);
        }
        pos[base[m] + v] = id;
      }
  }
  std::vector<std::array<double, 3>>().swap(pointKeys);
  std::vector<uint32_t> normalIdOfRow = largeVector(normalBase.back(), ~0u);
  size_t triangles = 0;
  for (size_t m = 0; m < parts.size(); ++m) triangles += parts[m].faceCount();
  reserveLarge(mesh.triangles, triangles);
  if (allHaveNormals) reserveLarge(mesh.normalIndices, triangles);
  for (size_t m = 0; m < parts.size(); ++m) {
    const Part& part = parts[m];
    // Normals are numbered mesh by mesh: the new ones of this mesh's vertices, then the face
    // normals that replace its broken ones.
    if (allHaveNormals)
      for (size_t v = 0; v < part.vertexCount; ++v) {
        const size_t row = normalBase[m] + part.normalRow(v);
        if (!normalOk[row]) {
          nrm[base[m] + v] = ~0u;
          continue;
        }
        uint32_t& id = normalIdOfRow[firstNormal[row]];
        if (id == ~0u) {
          id = uint32_t(mesh.normals.size());
          const std::array<double, 3>& n = normalKeys[row];
          mesh.normals.emplace_back(n[0], n[1], n[2]);
        }
        nrm[base[m] + v] = id;
      }
    const size_t b = base[m];
    for (size_t f = 0; f < part.faceCount(); ++f) {
      std::array<uint32_t, 3> face{};
      if (!part.triangle(f, face)) continue;
      for (unsigned k = 0; k < 3; ++k)
        if (face[k] >= part.vertexCount)
          fail("{}: face {} of mesh {} refers to vertex {}, but the mesh has {} vertices", name, f,
               m, face[k], part.vertexCount);
      mesh.triangles.push_back({pos[b + face[0]], pos[b + face[1]], pos[b + face[2]]});
      if (allHaveNormals) {
        Tri ni{nrm[b + face[0]], nrm[b + face[1]], nrm[b + face[2]]};
        for (uint32_t& i : ni)
          if (i == ~0u) {
            mesh.normals.push_back(mesh.faceNormal(mesh.triangles.size() - 1));
            i = uint32_t(mesh.normals.size() - 1);
            ++mesh.repairs.replacedNormals;
          }
        mesh.normalIndices.push_back(ni);
      }
    }
  }
  return mesh;
}

// An OBJ file's bytes with every comment ('#' to the end of its line) turned into spaces:
// Assimp's importer reads a comment after a face's indices as one more index and refuses the
// file, where the check (and the native reader) read it as a comment.
std::string withoutObjComments(const std::string& bytes) {
  std::string out = bytes;
  bool comment = false;
  for (char& c : out) {
    if (c == '\n') {
      comment = false;
    } else if (c == '#' || comment) {
      comment = c != '\r';
      if (comment) c = ' ';
    }
  }
  return out;
}

// Reads the file's bytes with Assimp (its OBJ, PLY and STL importers; OFF only when asked for,
// MeshReader::Assimp).
TriangleMesh loadWithAssimp(const std::string& name, const std::string& ext,
                            const std::string& bytes) {
  Assimp::Importer importer;
  importer.SetIOHandler(new BufferIoSystem(name, bytes));  // the importer owns it
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // Read first, check every face, then post-process: Assimp's importers keep an index a file
  // gives beyond its vertices (a binary PLY face list longer than the file) and an OFF face of
  // no vertices, and its post-processing steps then read out of bounds or abort.
  const aiScene* scene = importer.ReadFile(name, 0);
  if (!scene || !scene->mRootNode)
    fail("{}: cannot read mesh ({})", name, importer.GetErrorString());
  // A file of points alone (a scan's point cloud): say so, rather than what Assimp's
  // post-processing says once it has dropped them ("all meshes are orphaned").
  size_t faces = 0, vertices = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    faces += scene->mMeshes[m]->mNumFaces;
    vertices += scene->mMeshes[m]->mNumVertices;
  }
  if (faces == 0)
    fail("{}: no faces: {} vertices and no triangle to build a surface from (a point cloud?)", name,
         vertices);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* am = scene->mMeshes[m];
    for (unsigned f = 0; f < am->mNumFaces; ++f) {
      const aiFace& face = am->mFaces[f];
      if (face.mNumIndices == 0) fail("{}: face {} of mesh {} has no vertices", name, f, m);
      for (unsigned k = 0; k < face.mNumIndices; ++k)
        if (face.mIndices[k] >= am->mNumVertices)
          fail("{}: face {} of mesh {} refers to vertex {}, but the mesh has {} vertices", name, f,
               m, face.mIndices[k], am->mNumVertices);
    }
  }
  scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_SortByPType |
                                       aiProcess_PreTransformVertices);
  if (!scene || !scene->mRootNode)
    fail("{}: cannot read mesh ({})", name, importer.GetErrorString());
  bool allHaveNormals = scene->mNumMeshes > 0 && ext != ".stl";
  std::vector<Part> parts(scene->mNumMeshes);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* am = scene->mMeshes[m];
    if (!am->HasNormals()) allHaveNormals = false;
    parts[m].points = am->mVertices;
    parts[m].pointCount = am->mNumVertices;
    parts[m].normals = am->mNormals;
    parts[m].normalCount = am->mNormals ? am->mNumVertices : 0;
    parts[m].vertexCount = am->mNumVertices;
    parts[m].faces = am->mFaces;
    parts[m].faces_ = am->mNumFaces;
  }
  return weldParts(name, parts, allHaveNormals);
}

}  // namespace

TriangleMesh loadMeshWith(MeshReader reader, const std::filesystem::path& path,
                          const NormalOptions& normals, MemoryBudget* budget) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail("{}: no such file", name);
  const std::string ext = mesh_check::lowerExtension(path);
  if (ext != ".obj" && ext != ".ply" && ext != ".stl" && ext != ".off")
    fail("{}: unsupported mesh format '{}': expected .obj, .ply, .stl or .off", name, ext);
  // The file is read once: the checks and Assimp both read these bytes.
  const std::string bytes = mesh_check::readMeshFile(path);
  // The header's counts must fit in the file and the memory they need in the budget before
  // Assimp allocates for them. An OBJ file is read by the native reader (readPlainObj) while it
  // is checked, when the budget has room for what that reader may hold (its vectors take less
  // than kPlainObjBytesPerByte per byte of the file); the check's error, if any, is the one
  // thrown, and the reader's result is only used once the check has passed.
  constexpr uint64_t kPlainObjBytesPerByte = 8;
  MeshFileInfo info;
  FileDigest digest;
  std::optional<mesh_check::ObjCorners> plain;
  std::string plyText;  // an ASCII PLY file as Assimp is given it (inspectPly)
  bool plainTried = false;
  const bool plainObj = reader == MeshReader::Auto && ext == ".obj";
  const uint64_t plainBytes = kPlainObjBytesPerByte * uint64_t(bytes.size());
  if (plainObj &&
      (!budget || budget->maxBytes == 0 || budget->usedBytes + plainBytes <= budget->maxBytes)) {
    // The digest (for render keys, TriangleMesh::fileDigest) is taken beside the check, while
    // the reader runs.
    parallelInvoke(
        [&] {
          info = mesh_check::inspectMeshBytes(path, bytes);
          digest = FileDigest::of(bytes);
        },
        [&] { plain = mesh_check::readPlainObj(bytes); });
    plainTried = true;
  } else {
    // An OFF file's body is checked by the reader that reads it (readOffBody), below.
    info = mesh_check::inspectMeshBytes(path, bytes, /*offBody=*/ext != ".off", &plyText);
    if (ext != ".off") digest = FileDigest::of(bytes);
  }
  // The OBJ pre-pass counts faces exactly; without this, Assimp's refusal ("all meshes are
  // orphaned") would not say what is wrong.
  if (info.format == "OBJ" && info.faces == 0)
    fail("{}: the file holds no faces (no 'f' line); a mesh needs at least one triangle", name);
  if (budget) chargeMeshFile(*budget, info, path);
  TriangleMesh mesh;
  int significandBits = 53;  // the precision of the coordinates: doubles, but floats from Assimp
  // A plain OBJ file (mesh_check::readPlainObj) is read natively, as Assimp reads it but in
  // double precision.
  if (plainObj && !plainTried) plain = mesh_check::readPlainObj(bytes);
  if (ext == ".off" && reader == MeshReader::Auto) {
    // OFF is read natively, never by Assimp (mesh_check::readOff); the digest is taken while it
    // reads.
    mesh_check::OffMesh off;
    parallelInvoke([&] { digest = FileDigest::of(bytes); },
                   [&] { off = mesh_check::readOff(name, bytes); });
    Part part;
    part.exactPoints = off.points.data();
    part.pointCount = off.points.size();
    part.exactNormals = off.normals.data();
    part.normalCount = off.normals.size();
    part.vertexCount = off.points.size();
    part.corners = off.corners.data();
    part.cornerCount = off.corners.size();
    mesh = weldParts(name, {part}, off.header.normals);
  } else if (plain) {
    Part part;
    part.exactPoints = plain->points.data();
    part.pointCount = plain->points.size();
    part.pointOf = plain->pointOf.data();
    part.exactNormals = plain->normals.data();
    part.normalCount = plain->normals.size();
    part.normalOf = plain->normalOf.data();
    part.vertexCount = plain->pointOf.size();
    mesh = weldParts(name, {part}, !plain->normalOf.empty());
  } else {
    if (ext == ".off") {
      // Assimp's OFF importer reads out of bounds on a face of no vertex (fuzz_off).
      const mesh_check::OffBody body =
          mesh_check::readOffBody(name, bytes, mesh_check::readOffHeader(name, bytes), nullptr);
      if (body.firstEmptyFaceLine != 0)
        fail("{}:{}: a face of no vertex, which Assimp's OFF importer cannot read", name,
             body.firstEmptyFaceLine);
      digest = FileDigest::of(bytes);
    }
    mesh = loadWithAssimp(name, ext,
                          ext == ".obj"     ? withoutObjComments(bytes)
                          : plyText.empty() ? bytes
                                            : plyText);
    significandBits = 24;
  }
  if (mesh.triangles.empty()) fail("{}: the file holds no triangles", name);
  repairMesh(mesh, significandBits);
  if (mesh.triangles.empty())
    fail("{}: every triangle names a vertex twice; no surface is left", name);
  applyNormals(mesh, normals);
  mesh.validate(name);
  mesh.fileDigest = digest;
  return mesh;
}

TriangleMesh loadMesh(const std::filesystem::path& path, const NormalOptions& normals,
                      MemoryBudget* budget) {
  return loadMeshWith(MeshReader::Auto, path, normals, budget);
}

}  // namespace quadtri

namespace quadtri {

BuiltinMesh loadMeshSpec(const std::string& spec, const NormalOptions& normals,
                         MemoryBudget* budget) {
  // Not the throwing exists(): a spec too long for a file name is still a spec.
  std::error_code ec;
  if (std::filesystem::exists(spec, ec)) {
    BuiltinMesh b;
    b.mesh = loadMesh(spec, normals, budget);
    b.description = std::filesystem::path(spec).filename().string();
    return b;
  }
  const std::optional<ShapeSpec> shape = parseShapeSpec(spec);
  if (!shape) {
    fail("{}: no such file, and not a built-in shape (expected a mesh file or one of {})", spec,
         fmt::join(builtinShapeNames(), ", "));
  }
  // Charged before it is built: a spec such as cube:1024 must be refused, not built.
  const uint64_t triangles = builtinTriangleCount(*shape);
  if (budget)
    chargeMemory(
        *budget, modelBytes(*budget, triangles), spec,
        fmt::format("building {} of its {} triangles", describeModelBytes(*budget), triangles));
  BuiltinMesh b = makeBuiltin(shape->name, shape->params);
  applyNormals(b.mesh, normals);  // File keeps the shape's analytic normals
  return b;
}

}  // namespace quadtri
