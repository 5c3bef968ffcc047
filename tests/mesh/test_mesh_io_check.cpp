// Hostile mesh headers are refused before anything is allocated; the memory budget refuses
// meshes that would not fit; valid files pass the pre-pass.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include "quadtri/io/memory_limit.h"
#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/mesh_io_check.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

const fs::path kAssimpModels = "/usr/share/assimp/models";

fs::path testDir() {
  const fs::path dir = fs::temp_directory_path() / "quadtri_test_mesh_io_check";
  fs::create_directories(dir);
  return dir;
}

fs::path writeFile(const std::string& name, const std::string& bytes) {
  const fs::path path = testDir() / name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

template <typename T>
std::string bytesOf(const T& value) {
  return std::string(reinterpret_cast<const char*>(&value), sizeof(value));
}

// A binary STL: an 80-byte header, `declared` as the count and `facets` zero facets.
std::string binaryStl(uint32_t declared, int facets) {
  return std::string(80, '\0') + bytesOf(declared) + std::string(size_t(50) * facets, '\0');
}

// Runs f, which must throw Error, within a second; returns the message.
std::string refusal(const std::function<void()>& f) {
  const auto start = std::chrono::steady_clock::now();
  std::string message;
  try {
    f();
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  return message;
}

void expectContains(const std::string& message, const std::vector<std::string>& parts) {
  for (const std::string& p : parts)
    EXPECT_NE(message.find(p), std::string::npos) << p << " in: " << message;
}

TEST(MeshIoCheck, AssimpOutOfMemoryOffIsRefusedFromItsHeader) {
  const fs::path path = kAssimpModels / "invalid" / "OutOfMemory.off";
  if (!fs::exists(path)) GTEST_SKIP() << path << " absent (Debian's assimp-testmodels)";
  const std::string message = refusal([&] { loadMesh(path); });
  // 353,535,235,358 vertices of at least "0 0 0\n" each, in a 309-byte file.
  expectContains(message, {path.string(), "353535235358 vertices", "6 faces", "2121211412160 bytes",
                           "309 bytes"});
}

TEST(MeshIoCheck, OffCountsOverTheFileSizeAreRefused) {
  const fs::path path = writeFile("big.off", "OFF\n1000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const std::string message = refusal([&] { loadMesh(path); });
  expectContains(message, {path.string(), "1000000000 vertices", "6000000002 bytes", "6 per vertex",
                           "the file has 45 bytes"});
  // A comment and the COFF keyword: a colour value more per vertex.
  const fs::path coff =
      writeFile("big.coff.off", "# colours\nCOFF\n100 1 0\n0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 2\n");
  expectContains(refusal([&] { inspectMeshFile(coff); }), {"100 vertices", "8 per vertex"});
  // Close to the least size passes: 3 vertices "0 0 0", one face "1 0", no last newline (a
  // face "0" is refused: Assimp's importer reads out of bounds on it).
  const fs::path tight = writeFile("tight.off", "OFF 3 1 0\n0 0 0\n0 0 0\n0 0 0\n1 0");
  EXPECT_EQ(inspectMeshFile(tight).vertices, 3u);
  expectContains(refusal([&] { inspectMeshFile(writeFile("bad.off", "OFF\nx 1 0\n")); }),
                 {"bad.off", "expected the vertex and face counts"});
}

TEST(MeshIoCheck, AsciiPlyCountsOverTheFileSizeAreRefused) {
  const fs::path path = writeFile(
      "big-ascii.ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 2000000000\nproperty list uchar int vertex_indices\n"
      "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const std::string message = refusal([&] { loadMesh(path); });
  expectContains(message, {path.string(), "ascii", "2000000000 face × 2 bytes", "4000000018 bytes",
                           "26 bytes after its header"});
}

TEST(MeshIoCheck, BinaryPlyCountsOverTheFileSizeAreRefused) {
  std::string body;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) body += bytesOf(v);
  body += '\3';
  for (int32_t i : {0, 1, 2}) body += bytesOf(i);
  const fs::path path = writeFile(
      "big-binary.ply",
      "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\nproperty list uchar int "
      "vertex_indices\nend_header\n" +
          body);
  const std::string message = refusal([&] { loadMesh(path); });
  expectContains(message, {path.string(), "binary_little_endian", "4000000000 vertex × 12 bytes",
                           "48000000001 bytes", "49 bytes after its header"});
  // Counts that fit in the file but not in Assimp's 32-bit counters are refused too: an element
  // without properties takes no bytes.
  const fs::path wide =
      writeFile("wide.ply",
                "ply\nformat binary_little_endian 1.0\nelement vertex 5000000000\n"
                "end_header\n");
  expectContains(refusal([&] { inspectMeshFile(wide); }),
                 {"5000000000 'vertex' elements", "4294967295"});
  expectContains(refusal([&] {
                   inspectMeshFile(writeFile("type.ply",
                                             "ply\nformat ascii 1.0\nelement vertex 1\n"
                                             "property float128 x\nend_header\n0\n"));
                 }),
                 {"type.ply:4", "float128"});
}

TEST(MeshIoCheck, PlyListCountsAreCheckedAgainstTheBytesLeft) {
  // Assimp reserves what a list count says before reading its values (fuzz_ply: a count of
  // 1,111,111,110 in a 2 KB ASCII file was 8.9 GB).
  const std::string header =
      "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 2\nproperty list FACE_COUNT int vertex_indices\nend_header\n";
  const auto plyHeader = [&](const std::string& format, const std::string& countType) {
    std::string h = "ply\nformat " + format + " 1.0\n" + header;
    h.replace(h.find("FACE_COUNT"), 10, countType);
    return h;
  };
  const std::string ascii = plyHeader("ascii", "uchar") + "0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n";
  expectContains(
      refusal([&] { loadMesh(writeFile("ascii-list.ply", ascii + "1111111110 0 2 1\n")); }),
      {"ascii-list.ply:15: element 'face' 1: list 'vertex_indices' has count "
       "'1111111110'"});
  expectContains(refusal([&] { loadMesh(writeFile("ascii-short.ply", ascii)); }),
                 {"ascii-short.ply: the file ends at element 'face' 1 of 2"});
  EXPECT_EQ(loadMesh(writeFile("ascii-ok.ply", ascii + "\n3 1 3 2 7\n")).triangleCount(), 2u)
      << "a blank line and a word past the last property are accepted, as Assimp does";
  // Assimp reads the digits that begin an unknown element's name as its count (fuzz_ply).
  std::string digitName = ascii;
  digitName.replace(digitName.find("element vertex 4"), 16, "element 99999999999vertex 4");
  expectContains(refusal([&] { loadMesh(writeFile("digit-name.ply", digitName)); }),
                 {"digit-name.ply:3: element name '99999999999vertex' begins with a digit"});

  // Binary, both byte orders: counts decoded with the file's order and the type's sign.
  const auto big = [](auto v) {
    std::string b = bytesOf(v);
    std::reverse(b.begin(), b.end());
    return b;
  };
  std::string vertices;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 1.f, 1.f, 0.f}) vertices += big(v);
  std::string faces = big(int16_t(3));
  for (int32_t i : {0, 1, 2}) faces += big(i);
  const std::string bigEndian = plyHeader("binary_big_endian", "short") + vertices + faces;
  std::string second = big(int16_t(3));
  for (int32_t i : {1, 3, 2}) second += big(i);
  EXPECT_EQ(loadMesh(writeFile("big-ok.ply", bigEndian + second)).triangleCount(), 2u);
  expectContains(
      refusal([&] { loadMesh(writeFile("big-negative.ply", bigEndian + big(int16_t(-1)))); }),
      {"big-negative.ply: element 'face' 1 of 2: list 'vertex_indices' declares -1 values"});
  std::string little;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 1.f, 1.f, 0.f}) little += bytesOf(v);
  little += bytesOf(uint32_t(3)) + bytesOf(int32_t(0)) + bytesOf(int32_t(1)) + bytesOf(int32_t(2));
  little += bytesOf(uint32_t(1000000000)) + bytesOf(int32_t(0));
  expectContains(
      refusal([&] {
        loadMesh(writeFile("little-huge.ply", plyHeader("binary_little_endian", "uint") + little));
      }),
      {"little-huge.ply: element 'face' 1 of 2: list 'vertex_indices' declares "
       "1000000000 values of 4 bytes; the file has 4 bytes left"});
  expectContains(refusal([&] {
                   inspectMeshFile(writeFile("float-count.ply",
                                             plyHeader("binary_little_endian", "float") + little));
                 }),
                 {"float-count.ply:8: list 'vertex_indices' has count type 'float'"});
  // A word Assimp cannot read shifts the values after it (a coordinate became a list count).
  expectContains(refusal([&] { loadMesh(writeFile("comma.ply", ascii + "3 1 ,3 2\n")); }),
                 {"comma.ply:15: element 'face' 1: list 'vertex_indices' holds ',3', expected an "
                  "integer"});
  expectContains(
      refusal([&] {
        loadMesh(writeFile("coordinate.ply", plyHeader("ascii", "uchar") + "0 0 0\n1 ,0 0\n" +
                                                 std::string(20, '\n')));
      }),
      {"coordinate.ply:11: element 'vertex' 1: property 'y' is ',0', expected a number"});
  // A vertical tab after end_header: Assimp would not see the header end (fuzz_ply: a hang).
  expectContains(refusal([&] {
                   inspectMeshFile(writeFile("vtab.ply",
                                             "ply\nformat ascii 1.0\n"
                                             "end_header\v0 0 0\n"));
                 }),
                 {"vtab.ply:3: control character 0x0b in the PLY header"});
  expectContains(refusal([&] { loadMesh(writeFile("vtab-body.ply", ascii + "3 1\v3 2\n")); }),
                 {"vtab-body.ply:15: control character 0x0b in an ASCII PLY element"});
  // A line among an element's properties that is none: Assimp would read another layout.
  expectContains(
      refusal([&] {
        inspectMeshFile(writeFile("not-a-property.ply",
                                  "ply\nformat ascii 1.0\nelement vertex 1\n"
                                  "property float x\npro0.0perty float y\nend_header\n0\n"));
      }),
      {"not-a-property.ply:5: 'pro0.0perty float y': expected 'property'"});
  // An obj_info line among an element's properties: Assimp ends the element there and reads
  // the body with one property fewer (fuzz_ply: a list count of 10^9 from a coordinate).
  const std::string objInfo =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "obj_info float y\nproperty float z\nelement face 1\n"
      "property list uint int vertex_indices\nend_header\n";
  const std::string objInfoBody(3 * 8 + 4 + 12, '\0');
  expectContains(
      refusal([&] { inspectMeshFile(writeFile("obj-info.ply", objInfo + objInfoBody)); }),
      {"obj-info.ply:6: property of element 'vertex' after the obj_info line 5"});
  // An element Assimp does not know, holding data before the vertices: Assimp takes it as
  // empty and reads the faces from its bytes (fuzz_ply: a list count of 540 million).
  const std::string unknownFirst =
      "ply\nformat ascii 1.0\nelement camera 1\nproperty float f\nelement vertex 3\n"
      "property float x\nproperty float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n"
      "7\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  expectContains(refusal([&] { loadMesh(writeFile("unknown-first.ply", unknownFirst)); }),
                 {"unknown-first.ply:3: element 'camera' holds 1 entries before element 'vertex' "
                  "(line 5)"});
  // After the mesh's own elements, or empty, it shifts nothing.
  const std::string unknownLast =
      "ply\nformat ascii 1.0\nelement note 0\nproperty float f\nelement vertex 3\n"
      "property float x\nproperty float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nelement camera 1\nproperty float f\n"
      "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n7\n";
  EXPECT_EQ(loadMesh(writeFile("unknown-last.ply", unknownLast)).triangleCount(), 1u);
  // A coordinate whose integer part overflows Assimp's 64-bit read: Assimp stalls on it and
  // reads it again as the next values, a list count included (fuzz_ply: 7 GB reserved).
  const std::string longNumber =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 " +
      std::string(25, '8') + ".5 0\n3 0 1 2\n";
  expectContains(
      refusal([&] { loadMesh(writeFile("long-number.ply", longNumber)); }),
      {"long-number.ply:12: element 'vertex' 2: property 'y' is '8888", "more than 19 digits"});
  // 19 digits, and any number of leading zeros, are read whole.
  const std::string nineteen =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 " +
      std::string(30, '0') + "1 -" + std::string(19, '1') + ".5\n3 0 1 2\n";
  EXPECT_EQ(loadMesh(writeFile("nineteen.ply", nineteen)).triangleCount(), 1u);
  // A format line repeated among the properties ends them for Assimp too.
  expectContains(
      refusal([&] {
        inspectMeshFile(writeFile("format-again.ply",
                                  "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                  "format ascii 1.0\nproperty float y\nend_header\n0 0\n"));
      }),
      {"format-again.ply:5: a 'format' line after element 'vertex'"});
  // Between elements and before the first one, obj_info declares nothing to either reader.
  const std::string between =
      "ply\nformat ascii 1.0\nobj_info scanner 1\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nobj_info 2\nelement face 1\n"
      "property list uchar int vertex_indices\nobj_info 3\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(loadMesh(writeFile("obj-info-ok.ply", between)).triangleCount(), 1u);
}

// Assimp 5.2 reads an ASCII PLY line by line into one buffer that keeps what longer lines
// left in it: a line short of its properties read the rest from there (a list count of
// 1,491,307,314 from an earlier line's word, 12 GB), a blank line after another or after a CRLF
// line became an element, and a comment ended an element's properties. Assimp is given each
// element on a line of its own with every property present, so the mesh is the file's, read
// as the checks read it.
TEST(MeshIoCheck, AsciiPlyReachesAssimpOneCompleteElementPerLine) {
  const auto header = [](const std::string& comment) {
    return "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 3\nproperty float x\n" +
           comment +
           "property float y\nproperty float z\nproperty list uchar int vertex_indices\n"
           "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  };
  // Vertex 1 stops after its y: z reads 0 and its list one 0, not the words of vertex 0.
  const std::string body = "0 0 0 0 9 9 9 9 9 9 1491307314\n1 00000000000000\n0 1 0 0\n3 0 1 2\n";
  const TriangleMesh mesh = loadMesh(writeFile("short.ply", header("") + body));
  ASSERT_EQ(mesh.triangleCount(), 1u);
  EXPECT_EQ(mesh.positions[mesh.triangles[0][1]], Vec3(1, 0, 0));
  // Blank lines, LF or CRLF, one or several, are skipped, and a comment among the properties
  // ends none: the same mesh.
  const std::string blank = header("comment among the properties\n") +
                            "0 0 0 0 9 9 9 9 9 9 1491307314\n\n\n1 0\n\n0 1 0 0\n\n\n\n3 0 1 2\n";
  EXPECT_EQ(loadMesh(writeFile("blank.ply", blank)).positions, mesh.positions);
  std::string crlf;
  for (const char c : blank) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  EXPECT_EQ(loadMesh(writeFile("crlf.ply", crlf)).positions, mesh.positions);
  // Assimp reads an unsigned value's digits only: "-5" would stay for the signed list count
  // after it, 4294967291 values.
  const std::string sign =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty uchar flags\n"
      "property list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
  expectContains(refusal([&] { loadMesh(writeFile("sign.ply", sign + "-5 3 0 1 2\n")); }),
                 {"sign.ply:14: element 'face' 0: property 'flags' is '-5', expected an unsigned "
                  "integer"});
  expectContains(refusal([&] { loadMesh(writeFile("signs.ply", sign + "5 +-3 0 1 2\n")); }),
                 {"signs.ply:14: element 'face' 0: list 'vertex_indices' has count '+-3'"});
  expectContains(refusal([&] {
                   loadMesh(writeFile("nan.ply",
                                      "ply\nformat ascii 1.0\nelement vertex 1\n"
                                      "property float x\nend_header\nnan(7)\n"));
                 }),
                 {"nan.ply:6: element 'vertex' 0: property 'x' is 'nan(7)', expected a number"});
  EXPECT_EQ(loadMesh(writeFile("plus.ply", sign + "+5 3 0 +1 2\n")).triangleCount(), 1u);
  // Assimp reads a float's exponent as a 64-bit integer and stops at one that overflows, so its
  // digits would be read again as the list count after it (2·10^9 values).
  const std::string exponent =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty float q\n"
      "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
  expectContains(
      refusal([&] {
        loadMesh(writeFile("exponent.ply", exponent + "1e36893488149419103232 3 0 1 2\n"));
      }),
      {"exponent.ply:14: element 'face' 0: property 'q' is '1e36893488149419103232'",
       "exponent has more than 19 digits"});
  EXPECT_EQ(loadMesh(writeFile("exponent-ok.ply", exponent + "1e-0000000000000000000000000000038 3 "
                                                             "0 1 2\n"))
                .triangleCount(),
            1u);
  // Elements without properties take a line per entry here and are left out of Assimp's text,
  // which would have read their lines as blank ones, skipped some and read every later line one
  // element late (a coordinate as a list count of 2·10^9).
  for (const char* element : {"foo", "material"}) {
    const std::string empty = std::string("ply\nformat ascii 1.0\nelement ") + element +
                              " 2\nelement vertex 4\nproperty float x\nproperty float y\n"
                              "property float z\nelement face 2\n"
                              "property list uchar int vertex_indices\nend_header\na\nb\n0 0 0\n"
                              "1 0 0\n0 1 0\n2 0 1\n3 0 1 2\n3 0 2 3\n";
    const TriangleMesh m = loadMesh(writeFile("empty-element.ply", empty));
    EXPECT_EQ(m.triangleCount(), 2u) << element;
    EXPECT_EQ(m.positions[m.triangles[1][2]], Vec3(2, 0, 1)) << element;
  }
}

TEST(MeshIoCheck, BinaryStlCountsOverTheFileSizeAreRefused) {
  const fs::path path = writeFile("big.stl", binaryStl(100000000, 1));
  expectContains(refusal([&] { loadMesh(path); }),
                 {path.string(), "100000000 triangles", "5000000084 bytes", "134 bytes"});
  // 2^31 + 1 facets: 84 + 50 n wraps to the file's 134 bytes in 32 bits, Assimp's arithmetic.
  const fs::path wrap = writeFile("wrap.stl", binaryStl(2147483649u, 1));
  expectContains(refusal([&] { loadMesh(wrap); }),
                 {wrap.string(), "2147483649 triangles", "107374182534 bytes", "134 bytes"});
  const MeshFileInfo ok = inspectMeshFile(writeFile("two.stl", binaryStl(2, 2)));
  EXPECT_EQ(ok.format, "STL binary");
  EXPECT_EQ(ok.triangles, 2u);
  EXPECT_EQ(ok.vertices, 6u);
}

TEST(MeshIoCheck, ObjIndexFarPastTheVerticesIsRefused) {
  const fs::path path = writeFile("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 1000000000000\n");
  expectContains(refusal([&] { loadMesh(path); }),
                 {path.string() + ":4", "1000000000000", "out of range", "expected 1..3"});
  // Past what a long holds: still "out of range", not "not an integer".
  const fs::path huge =
      writeFile("huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n");
  expectContains(refusal([&] { loadMesh(huge); }),
                 {"huge.obj:4", "99999999999999999999 is out of range"});
}

TEST(MeshIoCheck, CountsOfValidFiles) {
  const fs::path obj = writeFile("quad.obj",
                                 "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
                                 "f 1//1 2//1 3//1 4//1\nf 1 2 3\n");
  const MeshFileInfo o = inspectMeshFile(obj);
  EXPECT_EQ(o.format, "OBJ");
  EXPECT_EQ(o.vertices, 4u);
  EXPECT_EQ(o.normals, 1u);
  EXPECT_EQ(o.faces, 2u);
  EXPECT_EQ(o.corners, 7u);
  EXPECT_EQ(o.triangles, 3u);
  EXPECT_EQ(o.loadBytes, estimateLoadBytes(o));
  EXPECT_GT(o.loadBytes, o.fileBytes);
  const fs::path stl = writeFile(
      "one.stl",
      "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
      "endloop\nendfacet\nendsolid t\n");
  const MeshFileInfo s = inspectMeshFile(stl);
  EXPECT_EQ(s.format, "STL ascii");
  EXPECT_EQ(s.faces, 1u);
  EXPECT_EQ(loadMesh(stl).triangleCount(), 1u);
}

TEST(MeshIoCheck, AssimpTestModelsPassThePrePass) {
  // The pre-pass must not refuse what Assimp reads: of every OBJ/PLY/STL/OFF in
  // assimp-testmodels, it refuses only pond.0.ply, whose body is 69 bytes short of its
  // header's 70,051 vertices (a point cloud Assimp does not load either),
  // number_formats.obj, which OBJ's validating pass refused before (line 11: "3.1+e2"), and
  // OFF/invalid.off, whose 4 declared faces are 3 lines, one "2\r20" (the OFF body check).
  if (!fs::exists(kAssimpModels)) GTEST_SKIP() << kAssimpModels << " absent (assimp-testmodels)";
  std::vector<std::string> refused;
  int loaded = 0;
  for (const char* folder : {"OBJ", "PLY", "STL", "OFF"})
    for (const auto& entry : fs::recursive_directory_iterator(kAssimpModels / folder)) {
      std::string ext = entry.path().extension().string();
      for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
      if (!entry.is_regular_file() ||
          (ext != ".obj" && ext != ".ply" && ext != ".stl" && ext != ".off"))
        continue;
      MeshFileInfo info;
      try {
        info = inspectMeshFile(entry.path());
      } catch (const Error& e) {
        refused.push_back(fs::relative(entry.path(), kAssimpModels).string());
        continue;
      }
      try {
        const TriangleMesh mesh = loadMesh(entry.path());
        ++loaded;
        // OBJ and STL count their triangles exactly (OFF and PLY: the declared faces), before
        // the loader removes collapsed and duplicate ones (mesh_repair.h).
        if (info.format == "OBJ" || info.format.rfind("STL", 0) == 0) {
          EXPECT_EQ(info.triangles, mesh.triangleCount() + mesh.repairs.collapsedFaces +
                                        mesh.repairs.duplicateFaces)
              << entry.path();
        }
      } catch (const Error&) {
        // Files Assimp or the OBJ pass refuse for other reasons (empty, points only, ...).
      }
    }
  std::sort(refused.begin(), refused.end());
  EXPECT_EQ(refused, (std::vector<std::string>{"OBJ/number_formats.obj", "OFF/invalid.off",
                                               "PLY/pond.0.ply"}));
  EXPECT_GE(loaded, 20);
}

TEST(MeshIoCheck, MemoryBudgetRefusesBeforeLoading) {
  const fs::path obj = writeFile("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const MeshFileInfo info = inspectMeshFile(obj);
  MemoryBudget budget;
  budget.maxBytes = info.loadBytes + 999;
  budget.bytesPerTriangle = 1000;  // one triangle: 1 byte over
  const std::string message = refusal([&] { loadMesh(obj, NormalSource::File, &budget); });
  expectContains(message, {obj.string(), "needs about", formatBytes(info.loadBytes + 1000),
                           "--max-memory limit of " + formatBytes(budget.maxBytes)});
  EXPECT_EQ(budget.usedBytes, 0u);
  budget.maxBytes += 1;
  EXPECT_EQ(loadMesh(obj, NormalSource::File, &budget).triangleCount(), 1u);
  EXPECT_EQ(budget.usedBytes, info.loadBytes + 1000);
  // A second mesh on the same budget is charged on top of the first.
  expectContains(refusal([&] { loadMesh(obj, NormalSource::File, &budget); }),
                 {"on top of the " + formatBytes(budget.usedBytes)});
  // Built-in shapes are charged their model before it is built: icosphere:3 has 1280 triangles.
  MemoryBudget shapes;
  shapes.maxBytes = 1279 * 1000;
  shapes.bytesPerTriangle = 1000;
  expectContains(refusal([&] { loadMeshSpec("icosphere:3", NormalSource::File, &shapes); }),
                 {"icosphere:3", "1280 triangles"});
}

TEST(MeshIoCheck, CappedModelBytesStopGrowingAtTheirCap) {
  MemoryBudget budget;
  budget.bytesPerTriangle = 100;
  budget.cappedBytesPerTriangle = 50;
  budget.cappedBytes = 5000;
  EXPECT_EQ(modelBytes(budget, 0), 0u);
  EXPECT_EQ(modelBytes(budget, 10), 10u * 150u);              // below the cap: 150 per triangle
  EXPECT_EQ(modelBytes(budget, 100), 100u * 150u);            // at the cap exactly
  EXPECT_EQ(modelBytes(budget, 1000), 1000u * 100u + 5000u);  // above it: 100 per triangle more
  EXPECT_EQ(modelBytes(budget, ~uint64_t(0)), ~uint64_t(0));  // saturates, never wraps
  expectContains(describeModelBytes(budget),
                 {formatBytes(100) + " per triangle",
                  formatBytes(50) + " more per triangle up to " + formatBytes(5000)});
  // Charged so: a built-in shape over the limit only through its uncapped part is refused, one
  // that a per-triangle estimate of the capped part would refuse is not.
  budget.maxBytes = 1280 * 100 + 5000;
  EXPECT_EQ(loadMeshSpec("icosphere:3", NormalSource::File, &budget).mesh.triangleCount(), 1280u);
  EXPECT_EQ(budget.usedBytes, 1280u * 100u + 5000u);
  MemoryBudget tight = budget;
  tight.usedBytes = 0;
  tight.maxBytes -= 1;
  expectContains(refusal([&] { loadMeshSpec("icosphere:3", NormalSource::File, &tight); }),
                 {"icosphere:3", "more per triangle up to"});
  // A floor: a mesh of few triangles is charged it, one past it its per-triangle bytes.
  MemoryBudget floored;
  floored.bytesPerTriangle = 100;
  floored.cappedBytesPerTriangle = 50;
  floored.cappedBytes = 5000;
  floored.cappedFloorBytes = 2000;
  EXPECT_EQ(modelBytes(floored, 0), 2000u);
  EXPECT_EQ(modelBytes(floored, 10), 10u * 100u + 2000u);
  EXPECT_EQ(modelBytes(floored, 60), 60u * 150u);
  EXPECT_EQ(modelBytes(floored, 1000), 1000u * 100u + 5000u);
  expectContains(describeModelBytes(floored), {formatBytes(50) + " more per triangle, at least " +
                                               formatBytes(2000) + ", up to " + formatBytes(5000)});
}

TEST(MemoryLimit, ByteSizes) {
  EXPECT_EQ(parseByteSize("123456"), 123456u);
  EXPECT_EQ(parseByteSize("8G"), uint64_t(8) << 30);
  EXPECT_EQ(parseByteSize("512m"), uint64_t(512) << 20);
  EXPECT_EQ(parseByteSize("1.5GiB"), uint64_t(3) << 29);
  EXPECT_EQ(parseByteSize("2T"), uint64_t(2) << 40);
  EXPECT_EQ(parseByteSize("64KB"), uint64_t(64) << 10);
  for (const char* bad : {"", "G", "-1G", "1e9", "12X", "0", "0.1"}) {
    EXPECT_THROW(parseByteSize(bad), Error) << bad;
  }
  try {
    parseByteSize("lots", "--max-memory");
    ADD_FAILURE();
  } catch (const Error& e) {
    expectContains(e.what(), {"--max-memory lots", "8G or 512M"});
  }
  EXPECT_EQ(formatBytes(512), "512 B");
  EXPECT_EQ(formatBytes(uint64_t(3) << 29), "1.50 GiB");
  EXPECT_EQ(formatBytes(uint64_t(300) << 20), "300 MiB");
  EXPECT_GT(physicalMemoryBytes(), uint64_t(64) << 20);
  EXPECT_EQ(defaultMemoryLimit(), uint64_t(double(physicalMemoryBytes()) * kDefaultMemoryShare));
}

// Inputs the fuzzers found (fuzz/, tests/fuzz-regressions/): each is a clean error now.
TEST(MeshIoCheck, FuzzFindingsAreCleanErrors) {
  // An OFF vertex line short of coordinates: Assimp's importer read out of bounds.
  expectContains(
      refusal([&] {
        loadMesh(writeFile("short.off", "OFF\n3 1 0\n0 0 0\n-0.5 0..5\n0 1 0\n3 0 1 2\n"));
      }),
      {"short.off:4: vertex 1 needs 3 finite coordinates"});
  // A binary PLY face whose index lies past the vertices: Assimp's post-processing read out of
  // bounds.
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) ply += bytesOf(v);
  ply +=
      std::string(1, char(3)) + bytesOf(int32_t(0)) + bytesOf(int32_t(1)) + bytesOf(int32_t(70000));
  expectContains(refusal([&] { loadMesh(writeFile("far-index.ply", ply)); }),
                 {"far-index.ply: face 0 of mesh 0 refers to vertex 70000, but the mesh has 3"});
  // An ASCII STL facet of two vertices.
  expectContains(refusal([&] {
                   loadMesh(writeFile("two.stl",
                                      "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                                      "vertex 1 0 0\nendloop\nendfacet\nendsolid t\n"));
                 }),
                 {"two.stl: facet 1 has 2 vertices, expected 3"});
  // Shape specs: a count that is no whole number, a grid too fine, a radius out of range, a
  // shape over the budget (refused before it is built), a spec too long for a file name.
  expectContains(refusal([] { loadMeshSpec("uv-sphere:1e300,4"); }), {"must be a whole number"});
  expectContains(refusal([] { loadMeshSpec("torus:1,0.3,100000,100000"); }), {"too fine"});
  expectContains(refusal([] { loadMeshSpec("ellipsoid:1e300,1,1"); }), {"out of range"});
  MemoryBudget budget;
  budget.maxBytes = uint64_t(64) << 20;
  budget.bytesPerTriangle = 512;
  expectContains(refusal([&] { loadMeshSpec("cube:1024", {}, &budget); }),
                 {"cube:1024", "12582912 triangles"});
  EXPECT_NE(refusal([] { loadMeshSpec("uv-sphere:" + std::string(5000, '9')); }), "");
}

}  // namespace
}  // namespace quadtri
