// SIGINT, SIGTERM and SIGHUP as requests to stop: what a terminal's Ctrl-C, a batch scheduler's
// preemption or timeout (Slurm, Kubernetes, systemd send SIGTERM) and a closed session send.
#pragma once

#include <atomic>

namespace quadtri {

/// Makes SIGINT, SIGTERM and SIGHUP end the process at once, as they do by default, but after
/// removing every temporary file of writeAtomically and writing one line naming the signal to
/// stderr; the status is 128 + its number. For commands that have nothing to finish: while a
/// StopSignals lives, its handlers take over, and its destructor brings these back. A signal
/// the process was started ignoring (nohup's SIGHUP) stays ignored, here and in StopSignals.
void exitCleanlyOnStopSignals();

/// While an instance lives, the first SIGINT, SIGTERM or SIGHUP sets stopRequested() and is
/// remembered; the process keeps running, so the caller can finish what is in flight and write
/// what it has. A second one of any of them removes every temporary file of writeAtomically
/// (removeTemporaryFilesNow), writes one line naming it to stderr and ends the process at once
/// with status 128 + its number. The destructor restores the previous handlers. One instance at
/// a time (the handlers share one process-wide state).
class StopSignals {
 public:
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  /// Becomes true at the first signal; pass it as a cancel flag.
  static const std::atomic<bool>& stopRequested();
  /// The first signal's number, 0 while none came.
  static int signalNumber();
  /// "SIGINT", "SIGTERM", "SIGHUP", or "a signal" for any other number.
  static const char* signalName(int number);
};

}  // namespace quadtri
