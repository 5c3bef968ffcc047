#include "quadtri/mesh/mesh_io.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/ranges.h>

#include <assimp/Importer.hpp>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "quadtri/io/atomic_file.h"
#include "quadtri/io/memory_limit.h"
#include "quadtri/math/error.h"

namespace quadtri {
namespace {

struct VecLess {
  bool operator()(const Vec3& a, const Vec3& b) const {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  }
};

std::string lowerExtension(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

TriangleMesh loadMesh(const std::filesystem::path& path, const NormalOptions& normals,
                      MemoryBudget* budget) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) fail("{}: no such file", name);
  const std::string ext = lowerExtension(path);
  if (ext != ".obj" && ext != ".ply" && ext != ".stl" && ext != ".off")
    fail("{}: unsupported mesh format '{}': expected .obj, .ply, .stl or .off", name, ext);
  // The header's counts must fit in the file and the memory they need in the budget before
  // Assimp allocates for them.
  const MeshFileInfo info = inspectMeshFile(path);
  // The OBJ pre-pass counts faces exactly; without this, Assimp's refusal ("all meshes are
  // orphaned") would not say what is wrong.
  if (info.format == "OBJ" && info.faces == 0)
    fail("{}: the file holds no faces (no 'f' line); a mesh needs at least one triangle", name);
  if (budget) chargeMeshFile(*budget, info, path);
  Assimp::Importer importer;
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // Read first, check every face, then post-process: Assimp's importers keep an index a file
  // gives beyond its vertices (a binary PLY face list longer than the file) and an OFF face of
  // no vertices, and its post-processing steps then read out of bounds or abort.
  const aiScene* scene = importer.ReadFile(name, 0);
  if (!scene || !scene->mRootNode)
    fail("{}: cannot read mesh ({})", name, importer.GetErrorString());
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
  TriangleMesh mesh;
  std::map<Vec3, uint32_t, VecLess> weld, normalWeld;
  bool allHaveNormals = scene->mNumMeshes > 0 && ext != ".stl";
  for (unsigned m = 0; m < scene->mNumMeshes; ++m)
    if (!scene->mMeshes[m]->HasNormals()) allHaveNormals = false;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* am = scene->mMeshes[m];
    std::vector<uint32_t> pos(am->mNumVertices), nrm(am->mNumVertices);
    for (unsigned v = 0; v < am->mNumVertices; ++v) {
      const Vec3 p(am->mVertices[v].x, am->mVertices[v].y, am->mVertices[v].z);
      if (!allFinite(p)) fail("{}: vertex {} of mesh {} has a non-finite coordinate", name, v, m);
      auto [it, inserted] = weld.try_emplace(p, uint32_t(mesh.positions.size()));
      if (inserted) mesh.positions.push_back(p);
      pos[v] = it->second;
      if (allHaveNormals) {
        const Vec3 n(am->mNormals[v].x, am->mNormals[v].y, am->mNormals[v].z);
        // A zero or broken normal in the file is replaced by the face normal below (marked ~0u).
        if (!allFinite(n) || !(n.norm() > 1e-12)) {
          nrm[v] = ~0u;
          continue;
        }
        auto [nit, ninserted] =
            normalWeld.try_emplace(n.normalized(), uint32_t(mesh.normals.size()));
        if (ninserted) mesh.normals.push_back(n.normalized());
        nrm[v] = nit->second;
      }
    }
    for (unsigned f = 0; f < am->mNumFaces; ++f) {
      const aiFace& face = am->mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (unsigned k = 0; k < 3; ++k)
        if (face.mIndices[k] >= am->mNumVertices)
          fail("{}: face {} of mesh {} refers to vertex {}, but the mesh has {} vertices", name, f,
               m, face.mIndices[k], am->mNumVertices);
      mesh.triangles.push_back(
          {pos[face.mIndices[0]], pos[face.mIndices[1]], pos[face.mIndices[2]]});
      if (allHaveNormals) {
        Tri ni{nrm[face.mIndices[0]], nrm[face.mIndices[1]], nrm[face.mIndices[2]]};
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
  if (mesh.triangles.empty()) fail("{}: the file holds no triangles", name);
  repairMesh(mesh);
  if (mesh.triangles.empty())
    fail("{}: every triangle names a vertex twice; no surface is left", name);
  applyNormals(mesh, normals);
  mesh.validate(name);
  return mesh;
}

void saveMesh(const TriangleMesh& mesh, const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  for (const Vec3& p : mesh.positions)
    if (!allFinite(p)) fail("{}: refusing to write a non-finite vertex", path.string());
  if (ext == ".obj") {
    std::ostringstream out;
    out.precision(17);
    out << "# written by quadtri\n";
    for (const Vec3& p : mesh.positions)
      out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    for (const Vec3& n : mesh.normals)
      out << "vn " << n.x() << ' ' << n.y() << ' ' << n.z() << '\n';
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      out << 'f';
      for (int k = 0; k < 3; ++k) {
        out << ' ' << mesh.triangles[t][k] + 1;
        if (mesh.hasNormals()) out << "//" << mesh.normalIndices[t][k] + 1;
      }
      out << '\n';
    }
    writeTextFile(path, out.str());
    return;
  }
  if (ext == ".ply") {
    // PLY has per-vertex attributes only: split normals become duplicated vertices.
    std::vector<Vec3> pos, nrm;
    std::vector<Tri> tris;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> ids;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      Tri out{};
      for (int k = 0; k < 3; ++k) {
        const uint32_t pi = mesh.triangles[t][k];
        const uint32_t ni = mesh.hasNormals() ? mesh.normalIndices[t][k] : 0;
        auto [it, inserted] = ids.try_emplace({pi, ni}, uint32_t(pos.size()));
        if (inserted) {
          pos.push_back(mesh.positions[pi]);
          if (mesh.hasNormals()) nrm.push_back(mesh.normals[ni]);
        }
        out[k] = it->second;
      }
      tris.push_back(out);
    }
    std::ostringstream out(std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\ncomment written by quadtri\n"
        << "element vertex " << pos.size()
        << "\nproperty float x\nproperty float y\nproperty float z\n";
    if (!nrm.empty()) out << "property float nx\nproperty float ny\nproperty float nz\n";
    out << "element face " << tris.size()
        << "\nproperty list uchar uint vertex_indices\nend_header\n";
    auto put = [&](const auto& value) {
      out.write(reinterpret_cast<const char*>(&value), sizeof(value));
    };
    for (size_t i = 0; i < pos.size(); ++i) {
      for (int c = 0; c < 3; ++c) put(float(pos[i][c]));
      if (!nrm.empty())
        for (int c = 0; c < 3; ++c) put(float(nrm[i][c]));
    }
    for (const Tri& t : tris) {
      put(uint8_t(3));
      for (uint32_t i : t) put(i);
    }
    writeTextFile(path, out.str());
    return;
  }
  fail("{}: unsupported output format '{}': expected .obj or .ply", path.string(), ext);
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
    chargeMemory(*budget, triangles * budget->bytesPerTriangle, spec,
                 fmt::format("building {} per triangle of its {} triangles",
                             formatBytes(budget->bytesPerTriangle), triangles));
  BuiltinMesh b = makeBuiltin(shape->name, shape->params);
  applyNormals(b.mesh, normals);  // File keeps the shape's analytic normals
  return b;
}

}  // namespace quadtri
