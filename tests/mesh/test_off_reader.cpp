// The native OFF reader (mesh/off_reader.cpp): what it reads (counts, coordinates, comments,
// colours, NOFF normals, fan triangulation, faces of fewer than three corners dropped), the
// errors that name the file and the line, and, with QUADTRI_CORPUS set, every OFF file of the
// corpus manifest at the manifest's triangle count and closedness.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fixtures/temp_files.h"
#include "quadtri/io/csv.h"
#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/mesh_io_check.h"
#include "quadtri/mesh/mesh_reader.h"
#include "quadtri/mesh/topology.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

class OffReader : public fixtures::TempFiles {
 protected:
  OffReader() : TempFiles("off-reader") {}
  // loadMesh's error on the file, which must be refused.
  std::string refusal(const std::string& name, const std::string& text, bool checked = true) {
    const fs::path path = write(name, text);
    try {
      loadMesh(path);
    } catch (const Error& e) {
      // inspectMeshFile checks the whole file too, and refuses it with the same words.
      if (checked) try {
          inspectMeshFile(path);
          ADD_FAILURE() << name << ": inspectMeshFile accepts what loadMesh refuses: " << e.what();
        } catch (const Error& check) {
          EXPECT_EQ(std::string(check.what()), e.what());
        }
      return e.what();
    }
    ADD_FAILURE() << name << ": no error";
    return "";
  }
};

// A quad and a triangle sharing an edge, with everything the format allows around them:
// comments before the keyword, after numbers and on their own lines, the counts on the
// keyword's line, blank lines, CRLF line ends, tabs, a leading '+'.
TEST_F(OffReader, ReadsCountsCoordinatesAndComments) {
  const fs::path path = write("quad.off",
                              "# a comment\r\n"
                              "OFF 5 2 6 # counts on the keyword's line\r\n"
                              "\r\n"
                              "0 0 0#origin\r\n"
                              "1\t0 0\r\n"
                              "  # a comment line between vertices\r\n"
                              "1 1 +0\r\n"
                              "0 1 0\r\n"
                              "0.5 2.25 -1e-1\r\n"
                              "4 0 1 2 3\r\n"
                              "3 3 2 4 # last\r\n");
  const MeshFileInfo info = inspectMeshFile(path);
  EXPECT_EQ(info.format, "OFF");
  EXPECT_EQ(info.vertices, 5u);
  EXPECT_EQ(info.faces, 2u);
  const TriangleMesh m = loadMesh(path);
  ASSERT_EQ(m.positions.size(), 5u);
  EXPECT_EQ(m.positions[0], Vec3(0, 0, 0));
  EXPECT_EQ(m.positions[1], Vec3(1, 0, 0));
  EXPECT_EQ(m.positions[2], Vec3(1, 1, 0));
  EXPECT_EQ(m.positions[3], Vec3(0, 1, 0));
  // The nearest double to -1e-1 (Assimp's formats would give the nearest float).
  EXPECT_EQ(m.positions[4], Vec3(0.5, 2.25, -0.1));
  // The quad fanned from its first corner.
  EXPECT_EQ(m.triangles, (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}, {3, 2, 4}}));
  EXPECT_FALSE(m.repairs.any()) << m.repairs.summary();
}

// A convex polygon of k corners is k - 2 triangles fanned from its first corner; faces of 0, 1
// or 2 corners (points and lines) are dropped, as scripts/corpus-manifest.py counts them.
TEST_F(OffReader, FansPolygonsAndDropsPointsAndLines) {
  const fs::path path = write("fan.off",
                              "OFF\n6 5 0\n"
                              "0 0 0\n2 0 0\n3 1 0\n2 2 0\n0 2 0\n-1 1 0\n"
                              "6 0 1 2 3 4 5\n"
                              "0\n1 3\n2 0 5\n3 0 4 5\n");
  const TriangleMesh m = loadMesh(path);
  ASSERT_EQ(m.positions.size(), 6u);
  EXPECT_EQ(m.positions[3], Vec3(2, 2, 0));
  // The last face repeats the fan's last triangle: a duplicate, which the repair removes.
  EXPECT_EQ(m.triangles, (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}}));
  EXPECT_EQ(m.repairs.duplicateFaces, 1u);
}

// A polygon that is not convex is cut into ears in its plane: still k - 2 triangles on its own
// corners, but none folds over (its fan from corner 0 would hold the clockwise (0, 2, 3)).
TEST_F(OffReader, CutsNonConvexPolygonsIntoEars) {
  const fs::path path = write("arrow.off", "OFF\n4 1 0\n0 0 0\n2 1 0\n0 2 0\n0.5 1 0\n4 0 1 2 3\n");
  const TriangleMesh m = loadMesh(path);
  ASSERT_EQ(m.positions.size(), 4u);
  // The ears (3, 0, 1) and (2, 3, 1).
  EXPECT_EQ(m.positions[3], Vec3(0.5, 1, 0));
  EXPECT_EQ(m.triangles, (std::vector<Tri>{{3, 0, 1}, {2, 3, 1}}));
  double area = 0;
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    EXPECT_EQ(m.faceNormal(t), Vec3(0, 0, 1)) << t;
    area += m.faceCross(t).norm() / 2;
  }
  EXPECT_EQ(area, 1.5);  // the arrow's area; the fan's triangles would sum to 2.5
}

// COFF: a colour after each vertex (integers or floats, 3 or 4 of them) and after each face
// (CGAL's mesh_with_colors.off writes a comment right after one: "0.9 0 0#red"); none is read.
TEST_F(OffReader, IgnoresVertexAndFaceColours) {
  const fs::path path = write("colours.off",
                              "#this is a comment\nCOFF\n4 2 0\n\n"
                              "-1 -1 0 0.9 0.0 0.0 #red\n"
                              "1 -1 0 0.9 0 0#red\n"
                              "1 1 0 255 255 255 255\n"
                              "-1 1 0 0 0 0.9   #blue\n"
                              "3 0 1 2     0.9 0 0       #red\n"
                              "3 0 2 3 0 0 255 128\n");
  const TriangleMesh m = loadMesh(path);
  ASSERT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.positions[2], Vec3(1, 1, 0));
  EXPECT_EQ(m.triangles, (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}}));
}

// NOFF: the normal after each vertex is the file's shading normal (with NormalSource::File);
// a zero one is replaced by the face normal, as in every format.
TEST_F(OffReader, NoffNormalsAreTheFilesNormals) {
  const fs::path path = write("normals.off",
                              "NOFF\n4 2 0\n"
                              "0 0 0 0 0 2\n1 0 0 0 0.6 0.8\n0 1 0 0 0 0\n1 1 0 0 0 1\n"
                              "3 0 1 2\n3 1 3 2\n");
  const TriangleMesh m = loadMesh(path, NormalOptions{NormalSource::File});
  ASSERT_TRUE(m.hasNormals());
  const auto normal = [&](size_t t, int k) { return m.normals[m.normalIndices[t][k]]; };
  EXPECT_EQ(normal(0, 0), Vec3(0, 0, 1));  // unit length
  EXPECT_NEAR((normal(0, 1) - Vec3(0, 0.6, 0.8)).norm(), 0.0, 1e-7);
  EXPECT_EQ(normal(0, 2), Vec3(0, 0, 1));  // the zero normal: the face's
  EXPECT_EQ(normal(1, 1), Vec3(0, 0, 1));
  EXPECT_EQ(m.repairs.replacedNormals, 2u);  // vertex 2 in both triangles
}

// Positions are welded by exact equality of their doubles: two vertex lines of one point (and
// -0 = +0, the first one's sign kept) are one position, numbered in the file's order (as
// Assimp's OFF importer numbered them); an unused vertex is removed and reported.
TEST_F(OffReader, WeldsEqualPositionsInTheFilesOrder) {
  const fs::path path = write("weld.off",
                              "OFF\n6 2 0\n"
                              "5 5 5\n1 0 0\n0 0 -0\n0 1 0\n0 0 0\n1.000000000000000001 0 0\n"
                              "3 1 2 3\n3 3 4 5\n");
  const TriangleMesh m = loadMesh(path);
  // 5 5 5 is unused; 1.000000000000000001 is 1 as a double.
  ASSERT_EQ(m.positions.size(), 3u);
  EXPECT_EQ(m.positions[0], Vec3(1, 0, 0));
  EXPECT_TRUE(std::signbit(m.positions[1].z()));
  EXPECT_EQ(m.triangles, (std::vector<Tri>{{0, 1, 2}}));
  EXPECT_EQ(m.repairs.duplicateFaces, 1u);    // (2, 1, 0) is the first one, reversed
  EXPECT_EQ(m.repairs.isolatedVertices, 1u);  // 5 5 5
}

// Points equal as floats but not as doubles stay two points: a float would weld 1.00000001
// to 1.
TEST_F(OffReader, PointsApartAsDoublesStayApart) {
  const TriangleMesh m = loadMesh(write("near.off",
                                        "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1.00000001 0 0\n"
                                        "3 0 1 2\n3 0 3 2\n"));
  ASSERT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.positions[3].x(), 1.00000001);
  EXPECT_EQ(m.repairs.duplicateFaces, 0u);
}

// A file may start with its counts (the keyword is optional); the header's counts may also
// follow the keyword on a later line.
TEST_F(OffReader, TheKeywordIsOptional) {
  for (const char* text : {"3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                           "OFF\n# counts next\n\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                           "STCOFF 3 1 0\n0 0 0 1 1 1 0 0\n1 0 0 1 1 1 1 0\n0 1 0 1 1 1 0 1\n"
                           "3 0 1 2"}) {
    const TriangleMesh m = loadMesh(write("bare.off", text));
    EXPECT_EQ(m.triangles, (std::vector<Tri>{{0, 1, 2}})) << text;
    EXPECT_EQ(m.positions[2], Vec3(0, 1, 0)) << text;
  }
}

// Native and Assimp readers give the same mesh, bit for bit, on a file both read alike
// (triangles only, numbers exact as floats): the file's vertices, welded in their order.
TEST_F(OffReader, GivesAssimpsMeshOnTriangles) {
  const fs::path path = write("tris.off",
                              "OFF\n5 4 0\n0 0 0\n1 0 0\n0 1 0\n0.5 0.5 1\n0 0 0\n"
                              "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 4 3\n");
  for (const NormalOptions& normals : {NormalOptions{}, NormalOptions{NormalSource::Angle, 30.0}}) {
    const TriangleMesh native = loadMeshWith(MeshReader::Auto, path, normals);
    const TriangleMesh assimp = loadMeshWith(MeshReader::Assimp, path, normals);
    EXPECT_EQ(native.positions, assimp.positions);
    EXPECT_EQ(native.triangles, assimp.triangles);
    EXPECT_EQ(native.normals, assimp.normals);
    EXPECT_EQ(native.normalIndices, assimp.normalIndices);
  }
}

TEST_F(OffReader, BadFilesAreRefusedNamingTheLine) {
  const auto expectRefused = [&](const std::string& name, const std::string& text,
                                 const std::vector<std::string>& parts, bool checked = true) {
    const std::string message = refusal(name, text, checked);
    for (const std::string& p : parts)
      EXPECT_NE(message.find(p), std::string::npos) << p << " in: " << message;
  };
  const std::string tri = "0 0 0\n1 0 0\n0 1 0\n";
  expectRefused("empty.off", "# nothing\n\n", {"empty.off: the file is empty"});
  expectRefused("keyword.off", "# x\nPFF\n3 1 0\n",
                {"keyword.off:2: expected the OFF keyword", "found 'PFF'"});
  expectRefused("counts.off", "OFF\n\n3 x 0\n" + tri, {"counts.off:3:", "counts are '3 x'"});
  expectRefused("negative.off", "OFF\n-3 1 0\n" + tri, {"negative.off:2:", "counts are '-3 1'"});
  expectRefused("binary.off", "OFF BINARY\n", {"binary.off:1: binary OFF is not supported"});
  expectRefused("homogeneous.off", "4OFF\n3 1 0\n", {"homogeneous.off:1: '4OFF'", "4OFF"});
  expectRefused("dimension.off", "nOFF\n3\n3 1 0\n", {"dimension.off:1: 'nOFF'"});
  expectRefused("wide.off", "OFF\n4294967296 1 0\n",
                {"wide.off: the OFF header declares 4294967296 vertices", "the file has 19 bytes"});
  expectRefused("short.off", "OFF\n3 1 0\n0 0 0\n# two\n1 0\n0 1 0\n3 0 1 2\n",
                {"short.off:5: vertex 1 needs 3 finite coordinates: '1 0'"});
  expectRefused("word.off", "OFF\n3 1 0\n0 0 0\n1 0 x\n0 1 0\n3 0 1 2\n",
                {"word.off:4: vertex 1 needs 3 finite coordinates: 'x' is not a number: '1 0 x'"});
  expectRefused("nan.off", "OFF\n3 1 0\n0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n",
                {"nan.off:4: vertex 1 needs 3 finite coordinates: 'nan' is not finite"});
  // Finite as a double, not as a float.
  expectRefused("huge.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1e309 0\n3 0 1 2\n",
                {"huge.off:5: vertex 2 needs 3 finite coordinates: '1e309'"});
  expectRefused("noff.off", "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0\n0 1 0 0 0 1\n3 0 1 2\n",
                {"noff.off:4: vertex 1 needs 3 finite coordinates and 3 normal components"});
  expectRefused("index.off", "OFF\n3 2 0\n" + tri + "3 0 1 2\n3 0 1 3\n",
                {"index.off:7: face 1: index '3' is not a vertex (0 to 2)"});
  expectRefused("minus.off", "OFF\n3 1 0\n" + tri + "3 0 -1 2\n",
                {"minus.off:6: face 0: index '-1' is not a vertex"});
  expectRefused("few.off", "OFF\n3 1 0\n" + tri + "4 0 1 2\n",
                {"few.off:6: face 0: expected 4 vertex indices after its count, found 3"});
  expectRefused("count.off", "OFF\n3 1 0\n" + tri + "three 0 1 2\n",
                {"count.off:6: face 0: expected its vertex count, found 'three'"});
  expectRefused("truncated.off", "OFF\n3 2 0\n" + tri + "3 0 1 2\n",
                {"truncated.off: the OFF header declares 3 vertices and 2 faces, the file holds 3 "
                 "and 1 (it ends at line 6)"});
  // Counts over what the file's size can hold are refused from the header, before anything is
  // allocated (6 bytes per vertex at the least).
  expectRefused("big.off", "OFF\n1000000000 1 0\n" + tri + "3 0 1 2\n",
                {"big.off: the OFF header declares 1000000000 vertices", "6 per vertex"});
  // Only points and lines: no surface (refused by the loader, not the file check).
  expectRefused("lines.off", "OFF\n3 2 0\n" + tri + "2 0 1\n1 2\n",
                {"lines.off: the file holds no triangles"}, false);
}

// Through the command line: a bad OFF is a non-zero exit naming the line, and no output file.
TEST_F(OffReader, TheCliRefusesABadFileAndWritesNothing) {
  const fs::path in = write("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  const fs::path out = dir / "out.ply";
  const fs::path log = dir / "log.txt";
  const std::string command = std::string(QUADTRI_CLI) + " convert " + in.string() +
                              " --model flat -o " + out.string() + " > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  EXPECT_NE(status, 0);
  std::ifstream logFile(log);
  const std::string text(std::istreambuf_iterator<char>(logFile), {});
  EXPECT_NE(text.find("bad.off:6: face 0: index '7' is not a vertex (0 to 2)"), std::string::npos)
      << text;
  EXPECT_FALSE(fs::exists(out));
}

// Every OFF file of the corpus manifest loads with the manifest's triangle count (before the
// repair removes collapsed and duplicate triangles) and, when the manifest says closed, closed.
// Needs the corpus (scripts/fetch-corpus.sh); skipped when QUADTRI_CORPUS is unset.
TEST(OffCorpus, EveryManifestOffLoadsWithItsCounts) {
  const char* corpus = std::getenv("QUADTRI_CORPUS");
  if (!corpus || !*corpus) GTEST_SKIP() << "QUADTRI_CORPUS is not set";
  const CsvTable table =
      readCsvFile(fs::path(QUADTRI_TEST_DIR) / ".." / "data" / "corpus-manifest.csv");
  ASSERT_FALSE(table.rows.empty());
  const std::vector<std::string>& head = table.rows[0];
  const auto column = [&](const std::string& name) {
    const auto it = std::find(head.begin(), head.end(), name);
    EXPECT_NE(it, head.end()) << name;
    return size_t(it - head.begin());
  };
  const size_t pathColumn = column("path"), triangles = column("triangles"),
               closed = column("closed");
  int files = 0, closedFiles = 0;
  for (size_t r = 1; r < table.rows.size(); ++r) {
    const std::vector<std::string>& row = table.rows[r];
    const fs::path file = fs::path(corpus) / row[pathColumn];
    if (file.extension() != ".off") continue;
    ++files;
    ASSERT_TRUE(fs::exists(file)) << file << " is missing: run scripts/fetch-corpus.sh";
    TriangleMesh m;
    try {
      m = loadMesh(file, NormalOptions{NormalSource::File});
    } catch (const Error& e) {
      ADD_FAILURE() << e.what();
      continue;
    }
    EXPECT_EQ(m.triangleCount() + m.repairs.collapsedFaces + m.repairs.duplicateFaces,
              std::stoull(row[triangles]))
        << row[pathColumn];
    if (row[closed] == "yes") {
      ++closedFiles;
      EXPECT_TRUE(m.topology().isClosed()) << row[pathColumn] << " loads open";
    }
  }
  EXPECT_EQ(files, 138);
  EXPECT_EQ(closedFiles, 90);
}

}  // namespace
}  // namespace quadtri
