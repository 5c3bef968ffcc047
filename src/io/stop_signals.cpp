#include "quadtri/io/stop_signals.h"

#include <unistd.h>

#include <csignal>
#include <cstring>

#include "quadtri/io/atomic_file.h"
#include "quadtri/math/error.h"

namespace quadtri {
namespace {

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
std::atomic<bool> stopFlag{false};
std::atomic<int> firstSignal{0};
std::atomic<bool> installed{false};
struct sigaction previous[std::size(kSignals)];
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "the signal handler needs lock-free atomics");

void writeStderr(const char* text) {
  const size_t n = std::strlen(text);
  // Nothing can be done about a failed write to stderr while exiting.
  if (::write(STDERR_FILENO, text, n) < 0) return;
}

extern "C" void onStopSignal(int number) {
  int expected = 0;
  if (firstSignal.compare_exchange_strong(expected, number)) {
    stopFlag.store(true);
    return;
  }
  // A second signal: nothing more is written, no temporary file stays behind.
  removeTemporaryFilesNow();
  writeStderr("\nquadtri: ");
  writeStderr(StopSignals::signalName(number));
  writeStderr(" again: stopped at once, the outputs not yet written are not written\n");
  ::_exit(128 + number);
}

}  // namespace

StopSignals::StopSignals() {
  if (installed.exchange(true)) fail("StopSignals: only one instance at a time");
  stopFlag.store(false);
  firstSignal.store(0);
  struct sigaction action {};
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  for (size_t i = 0; i < std::size(kSignals); ++i) sigaction(kSignals[i], &action, &previous[i]);
}

StopSignals::~StopSignals() {
  for (size_t i = 0; i < std::size(kSignals); ++i) sigaction(kSignals[i], &previous[i], nullptr);
  installed.store(false);
}

const std::atomic<bool>& StopSignals::stopRequested() {
  return stopFlag;
}

int StopSignals::signalNumber() {
  return firstSignal.load();
}

const char* StopSignals::signalName(int number) {
  switch (number) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "a signal";
  }
}

}  // namespace quadtri
