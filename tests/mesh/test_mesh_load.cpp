// The loader reads a file once and welds without a map; the native reader of plain OBJ files
// gives the mesh Assimp gives, in double precision; saveMesh streams the same bytes as before.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <string>

#include "fixtures/temp_files.h"
#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/mesh_reader.h"
#include "quadtri/mesh/shapes.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

class MeshLoad : public fixtures::TempFiles {
 protected:
  MeshLoad() : TempFiles("mesh-load") {}
};

std::string bits(const Vec3& v) {
  std::string s(sizeof(double) * 3, '\0');
  std::memcpy(s.data(), v.data(), s.size());
  return s;
}

// Every field, bit for bit.
void expectIdentical(const TriangleMesh& a, const TriangleMesh& b, const std::string& what) {
  ASSERT_EQ(a.positions.size(), b.positions.size()) << what;
  for (size_t i = 0; i < a.positions.size(); ++i)
    ASSERT_EQ(bits(a.positions[i]), bits(b.positions[i])) << what << ": position " << i;
  ASSERT_EQ(a.triangles, b.triangles) << what;
  ASSERT_EQ(a.normals.size(), b.normals.size()) << what;
  for (size_t i = 0; i < a.normals.size(); ++i)
    ASSERT_EQ(bits(a.normals[i]), bits(b.normals[i])) << what << ": normal " << i;
  ASSERT_EQ(a.normalIndices, b.normalIndices) << what;
  EXPECT_EQ(a.repairs.summary(), b.repairs.summary()) << what;
}

// The same mesh, positions within a float's rounding of each other (`precise` read in double,
// `rounded` by Assimp in float), and each corner's normal within what that rounding moves it
// (normals the loader computes from the positions included). Normals equal as floats but not as
// doubles stay apart in `precise`, so the normals are compared corner by corner.
void expectSameToFloatPrecision(const TriangleMesh& precise, const TriangleMesh& rounded,
                                const std::string& what) {
  ASSERT_EQ(precise.positions.size(), rounded.positions.size()) << what;
  for (size_t i = 0; i < precise.positions.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double x = precise.positions[i][c], y = rounded.positions[i][c];
      EXPECT_LE(std::abs(x - y), 1.2e-7 * std::abs(x)) << what << ": position " << i;
    }
  ASSERT_EQ(precise.triangles, rounded.triangles) << what;
  ASSERT_EQ(precise.normalIndices.size(), rounded.normalIndices.size()) << what;
  for (size_t t = 0; t < precise.normalIndices.size(); ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_LE((precise.normals[precise.normalIndices[t][k]] -
                 rounded.normals[rounded.normalIndices[t][k]])
                    .norm(),
                1e-3)
          << what << ": triangle " << t << " corner " << k;
  EXPECT_EQ(precise.repairs.summary(), rounded.repairs.summary()) << what;
}

TEST_F(MeshLoad, NativeObjReaderGivesAssimpsMeshInDoublePrecision) {
  std::map<std::string, std::string> files;
  // Written by quadtri: 17 significant digits, split normals (a cylinder's caps and side).
  for (const char* spec : {"torus:1,0.35,24,12", "cylinder:16,3", "genus2:8"}) {
    const fs::path path = dir / (std::string(spec).substr(0, 5) + ".obj");
    saveMesh(parseBuiltinSpec(spec)->mesh, path);
    std::ifstream in(path, std::ios::binary);
    files[path.filename().string()] = std::string(std::istreambuf_iterator<char>(in), {});
  }
  // Numbers in every form both parsers take, negative indices, texture coordinates, smoothing
  // groups, CRLF line ends, a duplicate vertex and -0, a zero normal (replaced by the face's).
  files["forms.obj"] =
      "# forms\r\nv 0 0 0\r\nv 1.5e-1 +0.25 -0\r\nv 0.5 5. 1E+2\r\nv -0.000001 1e-7 3\r\n"
      "v 0 0 0\r\nv 123456.789012345678 -98765.4321 0.1\r\ns 1\r\nvt 0 0\r\nvt 1 1\r\n"
      "vn 0 0 1\r\nvn 0 0 0\r\nvn 0.3 0.4 0.5\r\n"
      "f 1/1/1 2/2/1 3/1/3\r\nf -3/-1/-1 -2/-2/-2 -1/-1/-3\r\n\r\ns off\r\nf 5//1 2//3 4//3\r\n";
  files["plain.obj"] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 0\nf 1 2 3\nf 2 4 3\nf 5 3 4";
  // Comments after values, faces included (Assimp's importer read one after a face's indices
  // as an index and refused the file: it is now given the file with its comments blanked).
  files["comment.obj"] = "v 0 0 0 # origin\nv 1 0 0\nv 0 1 0\nf 1 2 3 # first\nf 1 3 2\t#\n";
  // Read by Assimp alone (the native reader declines): a group, a quad, and both with comments.
  files["group.obj"] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\ng top\nf 1 2 3\nf 2 4 3\n";
  files["quad.obj"] = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
  files["groupcomment.obj"] =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\r\ng top # g\r\nf 1 2 3 4 # quad\r\nf 1 3 2 #\n";
  // Assimp drops a v line with a number starting with '.': the native reader declines it.
  files["dot.obj"] = "v 0 0 0\nv 1 0 0\nv .5 1 0\nv 0 1 0\nf 1 2 3\n";
  for (const auto& [name, text] : files) {
    const fs::path path = write(name, text);
    for (const NormalOptions& normals :
         {NormalOptions{}, NormalOptions{NormalSource::Angle, 30.0}}) {
      const TriangleMesh native = loadMeshWith(MeshReader::Auto, path, normals);
      const TriangleMesh assimp = loadMeshWith(MeshReader::Assimp, path, normals);
      expectSameToFloatPrecision(native, assimp, name);
      expectIdentical(loadMesh(path, normals), native, name);
    }
  }
}

// A mesh saved as OBJ or OFF (17 significant digits) loads again bit for bit: positions far
// from the origin keep their detail (a float would move a unit shape at 10^6 by up to 0.03).
TEST_F(MeshLoad, SavedMeshesLoadBitForBitFarFromTheOrigin) {
  for (const double offset : {0.0, 1e4, 1e6}) {
    TriangleMesh mesh = parseBuiltinSpec("torus:1,0.35,24,12")->mesh;
    for (Vec3& p : mesh.positions) p += Vec3(offset, -offset, 0.5 * offset);
    for (const char* ext : {".obj", ".off"}) {
      const fs::path path = dir / (std::string("far") + ext);
      if (std::string(ext) == ".obj") {
        saveMesh(mesh, path);
      } else {  // quadtri writes no OFF: the same 17 digits by hand
        std::ostringstream off;
        off << std::setprecision(17) << "OFF\n"
            << mesh.positions.size() << ' ' << mesh.triangleCount() << " 0\n";
        for (const Vec3& p : mesh.positions) off << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
        for (const Tri& tri : mesh.triangles)
          off << "3 " << tri[0] << ' ' << tri[1] << ' ' << tri[2] << '\n';
        write(path.filename().string(), off.str());
      }
      const TriangleMesh loaded = loadMesh(path);
      ASSERT_EQ(loaded.positions.size(), mesh.positions.size()) << offset << ext;
      ASSERT_EQ(loaded.triangleCount(), mesh.triangleCount()) << offset << ext;
      for (size_t t = 0; t < mesh.triangleCount(); ++t)
        for (int k = 0; k < 3; ++k)
          ASSERT_EQ(bits(loaded.corner(t, k)), bits(mesh.corner(t, k)))
              << offset << ext << " triangle " << t << " corner " << k;
    }
  }
}

// A triangle counts as zero-area to within the precision its file is read in: a real one a
// tenth wide at 10^6 is one from OBJ (doubles), but not from ASCII PLY (Assimp's floats resolve
// 0.06 there); three decimal points on a line are one in either.
TEST_F(MeshLoad, ZeroAreaIsJudgedAtThePrecisionTheFileIsReadIn) {
  const std::string far = "1000000 0 0\n1000000.1 0 0\n1000000 0.1 0\n";
  const auto obj = [](const std::string& points) {
    std::string text;
    std::istringstream in(points);
    for (std::string line; std::getline(in, line);) text += "v " + line + "\n";
    return text + "f 1 2 3\n";
  };
  const auto ply = [](const std::string& points) {
    return "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
           "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
           "end_header\n" +
           points + "3 0 1 2\n";
  };
  EXPECT_EQ(loadMesh(write("far.obj", obj(far))).repairs.zeroAreaFaces, 0u);
  EXPECT_EQ(loadMesh(write("far.ply", ply(far))).repairs.zeroAreaFaces, 1u);
  const std::string line = "0.1 0.1 0.1\n0.2 0.2 0.2\n0.3 0.3 0.3\n";
  EXPECT_EQ(loadMesh(write("line.obj", obj(line))).repairs.zeroAreaFaces, 1u);
  EXPECT_EQ(loadMesh(write("line.ply", ply(line))).repairs.zeroAreaFaces, 1u);
}

// PLY is written with 32-bit floats: a coordinate past their range is refused by name (it would
// be written as infinite, a file no reader takes back), and nothing is left behind; OBJ keeps it.
TEST_F(MeshLoad, PlyRefusesCoordinatesBeyondAFloat) {
  TriangleMesh mesh = parseBuiltinSpec("tetrahedron")->mesh;
  mesh.positions[2].y() = 1e39;
  const fs::path ply = dir / "big.ply", obj = dir / "big.obj";
  try {
    saveMesh(mesh, ply);
    ADD_FAILURE() << "wrote a coordinate of 1e39 as a float";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 2 has a coordinate of 1e+39, beyond a 32-bit "
                                         "float's range"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(ply));
  saveMesh(mesh, obj);
  EXPECT_EQ(loadMesh(obj).positions.size(), mesh.positions.size());
}

TEST_F(MeshLoad, PositionsAreWeldedInOrderOfFirstUse) {
  // Vertex 3 (0, 0, -0) equals vertex 1 (0, 0, 0): one position, with the sign of its first
  // use. Positions are numbered as the faces first use them, not as the file lists them.
  const fs::path path = write("order.obj",
                              "v 5 5 5\nv 1 0 0\nv 0 0 -0\nv 0 1 0\nv 0 0 0\n"
                              "f 2 3 4\nf 4 5 1\nf 1 5 2\n");
  for (const MeshReader reader : {MeshReader::Auto, MeshReader::Assimp}) {
    const TriangleMesh m = loadMeshWith(reader, path);
    ASSERT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.positions[0], Vec3(1, 0, 0));
    EXPECT_EQ(m.positions[1], Vec3(0, 0, 0));
    EXPECT_TRUE(std::signbit(m.positions[1].z()));  // the first use was "0 0 -0"
    EXPECT_EQ(m.positions[2], Vec3(0, 1, 0));
    EXPECT_EQ(m.positions[3], Vec3(5, 5, 5));
    EXPECT_EQ(m.triangles, (std::vector<Tri>{{0, 1, 2}, {2, 1, 3}, {3, 1, 0}}));
  }
}

// saveMesh as it was before it streamed: the whole file in an ostringstream, split normals
// through a std::map.
std::string referenceObj(const TriangleMesh& mesh) {
  std::ostringstream out;
  out.precision(17);
  out << "# written by quadtri\n";
  for (const Vec3& p : mesh.positions) out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  for (const Vec3& n : mesh.normals) out << "vn " << n.x() << ' ' << n.y() << ' ' << n.z() << '\n';
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    out << 'f';
    for (int k = 0; k < 3; ++k) {
      out << ' ' << mesh.triangles[t][k] + 1;
      if (mesh.hasNormals()) out << "//" << mesh.normalIndices[t][k] + 1;
    }
    out << '\n';
  }
  return out.str();
}

std::string referencePly(const TriangleMesh& mesh) {
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
  return out.str();
}

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST_F(MeshLoad, SavedFilesAreTheBytesTheyWereBeforeStreaming) {
  // The large torus is written in more than one window of lines (saveMesh formats an OBJ's
  // lines in parallel, 131,072 at a time).
  for (const char* spec :
       {"cylinder:16,3", "torus:1,0.35,40,20", "genus2:8", "cube:2", "torus:1,0.35,400,200"}) {
    TriangleMesh mesh = parseBuiltinSpec(spec)->mesh;
    TriangleMesh bare = mesh;
    bare.normals.clear();
    bare.normalIndices.clear();
    // One normal per point, indexed as the points are (a tessellated surface without creases):
    // the writer's path without a table per corner.
    TriangleMesh perPoint = bare;
    for (size_t v = 0; v < perPoint.positions.size(); ++v)
      perPoint.normals.push_back(Vec3(0.0, 0.6, 0.8) + 1e-3 * double(v) * Vec3::UnitX());
    perPoint.normalIndices = perPoint.triangles;
    for (const TriangleMesh* m : {&mesh, &bare, &perPoint}) {
      saveMesh(*m, dir / "out.obj");
      saveMesh(*m, dir / "out.ply");
      EXPECT_EQ(readAll(dir / "out.obj"), referenceObj(*m)) << spec;
      EXPECT_EQ(readAll(dir / "out.ply"), referencePly(*m)) << spec;
    }
  }
}

TEST_F(MeshLoad, AFailedSaveLeavesNothingBehind) {
  TriangleMesh mesh = parseBuiltinSpec("icosahedron")->mesh;
  mesh.positions[3].x() = std::nan("");
  EXPECT_THROW(saveMesh(mesh, dir / "bad.ply"), Error);
  EXPECT_TRUE(fs::is_empty(dir));
}

}  // namespace
}  // namespace quadtri
