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

extern "C" void onExitSignal(int number) {
  removeTemporaryFilesNow();
  writeStderr("\nquadtri: stopped by ");
  writeStderr(StopSignals::signalName(number));
  writeStderr(", the outputs not yet written are not written\n");
  ::_exit(128 + number);
}

// Installs `handler` for `number` unless the signal is ignored (nohup ignores SIGHUP, a
// non-interactive shell's `cmd &` ignores SIGINT): what the caller chose to ignore stays so.
// `before` receives the disposition it had.
void installUnlessIgnored(int number, void (*handler)(int), struct sigaction* before) {
  struct sigaction current {};
  sigaction(number, nullptr, &current);
  if (before) *before = current;
  if (current.sa_handler == SIG_IGN) return;
  struct sigaction action {};
  action.sa_handler = handler;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(number, &action, nullptr);
}

}  // namespace

void exitCleanlyOnStopSignals() {
  for (const int number : kSignals) installUnlessIgnored(number, onExitSignal, nullptr);
}

StopSignals::StopSignals() {
  if (installed.exchange(true)) fail("StopSignals: only one instance at a time");
  stopFlag.store(false);
  firstSignal.store(0);
  for (size_t i = 0; i < std::size(kSignals); ++i)
    installUnlessIgnored(kSignals[i], onStopSignal, &previous[i]);
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
