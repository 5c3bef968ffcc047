// writeStreamAtomically: the stream's bytes appear at the path at once; an exception from the
// writer leaves neither the file nor its temporary behind, nor touches an existing file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "quadtri/io/atomic_stream.h"
#include "quadtri/math/error.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(AtomicStream, WritesTheStreamAndLeavesNothingOnFailure) {
  const fs::path dir =
      fs::temp_directory_path() / ("quadtri-atomic-stream-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path path = dir / "out.bin";
  // More than the 1 MiB buffer, so the temporary file holds bytes before the rename.
  const std::string big(3 << 20, 'x');
  writeStreamAtomically(path, [&](std::ostream& out) { out << big << '\n'; });
  EXPECT_EQ(readAll(path), big + "\n");
  EXPECT_THROW(writeStreamAtomically(path,
                                     [&](std::ostream& out) {
                                       out << big;
                                       fail("stopped half way");
                                     }),
               Error);
  EXPECT_EQ(readAll(path), big + "\n");  // the old file stays whole
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file();
  EXPECT_EQ(files, 1u);  // no temporary left
  const fs::path fresh = dir / "fresh.bin";
  EXPECT_THROW(writeStreamAtomically(fresh,
                                     [&](std::ostream& out) {
                                       out << big;
                                       fail("stopped");
                                     }),
               Error);
  EXPECT_FALSE(fs::exists(fresh));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quadtri
