// `quadtri reproduce`: its options are checked before anything runs, and a repository without
// the teapot is refused at once, naming the file, with nothing written.
#include <gtest/gtest.h>

#include "cli/cli_runner.h"

namespace quadtri::test {
namespace {

namespace fs = std::filesystem;

TEST(CliReproduce, QuickAndFullExcludeEachOther) {
  const fs::path dir = freshDir("reproduce-options");
  CliProcess p({"reproduce", "--quick", "--full", "--out", (dir / "out").string()}, dir);
  EXPECT_NE(p.wait(), 0);
  EXPECT_NE(p.stderrText().find("excludes"), std::string::npos) << p.stderrText();
  EXPECT_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

TEST(CliReproduce, RefusesARootWithoutTheTeapotBeforeRendering) {
  const fs::path dir = freshDir("reproduce-root");
  CliProcess p({"reproduce", "--quick", "--root", dir.string(), "--out", (dir / "out").string(),
                "--work", (dir / "work").string()},
               dir);
  EXPECT_EQ(p.wait(), 1) << p.stderrText();
  const std::string err = p.stderrText();
  EXPECT_NE(err.find("quadtri: error: reproduce: "), std::string::npos) << err;
  EXPECT_NE(err.find("teapot.obj is missing"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quadtri::test
