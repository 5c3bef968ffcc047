// Stop signals and the temporary files a signal handler may have to remove.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>

#include "quadtri/io/atomic_file.h"
#include "quadtri/io/stop_signals.h"
#include "quadtri/math/error.h"

namespace quadtri {
namespace {

namespace fs = std::filesystem;

TEST(AtomicFile, RemoveTemporaryFilesNowRemovesTheFileBeingWritten) {
  const fs::path dir = fs::temp_directory_path() / "quadtri_test_atomic_file";
  fs::create_directories(dir);
  const fs::path target = dir / "out.txt";
  fs::path seen;
  // What a signal handler does while an output is being written: the temporary file goes, the
  // rename fails, nothing appears at the target.
  EXPECT_THROW(writeAtomically(target,
                               [&](const fs::path& tmp) {
                                 std::ofstream(tmp) << "half";
                                 seen = tmp;
                                 ASSERT_TRUE(fs::exists(tmp));
                                 removeTemporaryFilesNow();
                                 EXPECT_FALSE(fs::exists(tmp));
                               }),
               Error);
  EXPECT_FALSE(seen.empty());
  EXPECT_FALSE(fs::exists(target));
  // After a write the table no longer names the file: removing now touches nothing.
  writeTextFile(target, "whole");
  removeTemporaryFilesNow();
  std::ifstream in(target);
  std::string text;
  in >> text;
  EXPECT_EQ(text, "whole");
  fs::remove_all(dir);
}

// Starts each test from the default dispositions, whatever this process inherited.
void defaultStopSignals() {
  for (const int number : {SIGINT, SIGTERM, SIGHUP}) std::signal(number, SIG_DFL);
}

TEST(StopSignals, FirstSignalSetsTheFlagAndIsRemembered) {
  defaultStopSignals();
  for (const int number : {SIGTERM, SIGHUP, SIGINT}) {
    const StopSignals signals;
    EXPECT_FALSE(StopSignals::stopRequested().load());
    EXPECT_EQ(StopSignals::signalNumber(), 0);
    std::raise(number);  // handled: the process goes on
    EXPECT_TRUE(StopSignals::stopRequested().load());
    EXPECT_EQ(StopSignals::signalNumber(), number);
    EXPECT_THROW(StopSignals another, Error);
  }
  EXPECT_STREQ(StopSignals::signalName(SIGTERM), "SIGTERM");
  EXPECT_STREQ(StopSignals::signalName(SIGHUP), "SIGHUP");
  EXPECT_STREQ(StopSignals::signalName(SIGINT), "SIGINT");
}

TEST(StopSignals, AnIgnoredSignalStaysIgnored) {
  defaultStopSignals();
  std::signal(SIGHUP, SIG_IGN);  // as under nohup
  {
    const StopSignals signals;
    std::raise(SIGHUP);
    EXPECT_FALSE(StopSignals::stopRequested().load());
    std::raise(SIGTERM);
    EXPECT_EQ(StopSignals::signalNumber(), SIGTERM);
  }
  struct sigaction now {};
  sigaction(SIGHUP, nullptr, &now);
  EXPECT_EQ(now.sa_handler, SIG_IGN);
  defaultStopSignals();
}

TEST(StopSignalsDeathTest, SecondSignalExitsAtOnceWith128PlusItsNumber) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");  // TBB's threads may be running
  defaultStopSignals();
  EXPECT_EXIT(
      {
        const StopSignals signals;
        std::raise(SIGTERM);
        std::raise(SIGHUP);
        std::abort();  // not reached
      },
      ::testing::ExitedWithCode(128 + SIGHUP), "SIGHUP again: stopped at once");
}

TEST(StopSignalsDeathTest, OtherCommandsExitAtOnceRemovingTheirTemporaryFile) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  defaultStopSignals();
  const fs::path dir = fs::temp_directory_path() / "quadtri_test_exit_signal";
  fs::create_directories(dir);
  EXPECT_EXIT(
      {
        exitCleanlyOnStopSignals();
        writeAtomically(dir / "out.txt", [](const fs::path& tmp) {
          std::ofstream(tmp) << "half";
          std::raise(SIGTERM);
        });
        std::abort();  // not reached
      },
      ::testing::ExitedWithCode(128 + SIGTERM), "stopped by SIGTERM");
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
  defaultStopSignals();
}

}  // namespace
}  // namespace quadtri
