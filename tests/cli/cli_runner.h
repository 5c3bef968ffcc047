// Runs the quadtri binary (QUADTRI_CLI, set by CMake to $<TARGET_FILE:quadtri>) as a child
// process with stdout and stderr going to files, for tests of what the command line does.
#pragma once

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace quadtri::test {

/// A started `quadtri ARGS...`; its stdout and stderr are the files out and err.
class CliProcess {
 public:
  CliProcess(const std::vector<std::string>& args, const std::filesystem::path& logDir,
             const std::string& tag = "cli")
      : out_(logDir / (tag + ".stdout")), err_(logDir / (tag + ".stderr")) {
    std::vector<std::string> argv{QUADTRI_CLI};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<char*> cargv;
    for (std::string& a : argv) cargv.push_back(a.data());
    cargv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    // The stop signals start at their default even when this process ignores one (nohup).
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t defaults;
    sigemptyset(&defaults);
    for (const int number : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&defaults, number);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);
    start_ = std::chrono::steady_clock::now();
    const int rc = posix_spawn(&pid_, QUADTRI_CLI, &actions, &attributes, cargv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    if (rc != 0) throw std::runtime_error("cannot start " + std::string(QUADTRI_CLI));
  }
  ~CliProcess() {
    if (pid_ > 0 && !finished_) {
      ::kill(pid_, SIGKILL);
      wait();
    }
  }

  pid_t pid() const { return pid_; }
  void signal(int number) const { ::kill(pid_, number); }

  /// Waits up to `timeout` seconds for `text` to appear in stderr; false on timeout or exit.
  bool waitForStderr(const std::string& text, double timeout = 60.0) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
    while (std::chrono::steady_clock::now() < deadline) {
      if (stderrText().find(text) != std::string::npos) return true;
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        finished_ = true;
        status_ = status;
        return stderrText().find(text) != std::string::npos;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
  }

  /// Waits for the process; returns its exit status, or 128 + the signal that killed it.
  int wait() {
    if (!finished_) {
      rusage usage{};
      int status = 0;
      ::wait4(pid_, &status, 0, &usage);
      finished_ = true;
      status_ = status;
      cpuSeconds_ = double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                    1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    }
    wallSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    return WIFEXITED(status_) ? WEXITSTATUS(status_) : 128 + WTERMSIG(status_);
  }
  bool killedBySignal() const { return finished_ && WIFSIGNALED(status_); }
  /// Whether the process has exited and been reaped (by wait or waitForStderr).
  bool finished() const { return finished_; }
  /// User + system CPU time of the finished process (0 when waitForStderr reaped it).
  double cpuSeconds() const { return cpuSeconds_; }
  double wallSeconds() const { return wallSeconds_; }

  std::string stdoutText() const { return read(out_); }
  std::string stderrText() const { return read(err_); }

 private:
  static std::string read(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::filesystem::path out_, err_;
  pid_t pid_ = -1;
  bool finished_ = false;
  int status_ = 0;
  double cpuSeconds_ = 0.0, wallSeconds_ = 0.0;
  std::chrono::steady_clock::time_point start_;
};

/// The unsigned integer written just before the first `suffix` in `text` (no std::regex: GCC
/// 12 warns inside it under the sanitizers), or -1.
inline long numberBefore(const std::string& text, const std::string& suffix) {
  const size_t at = text.find(suffix);
  if (at == std::string::npos) return -1;
  size_t start = at;
  while (start > 0 && std::isdigit(static_cast<unsigned char>(text[start - 1]))) --start;
  return start == at ? -1 : std::stol(text.substr(start, at - start));
}

/// Files in `dir` whose names contain ".tmp" (writeAtomically's temporary files).
inline std::vector<std::string> temporaryFiles(const std::filesystem::path& dir) {
  std::vector<std::string> found;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().filename().string().find(".tmp") != std::string::npos)
      found.push_back(entry.path().filename().string());
  return found;
}

/// A fresh empty folder under the system's temporary folder, for one test.
inline std::filesystem::path freshDir(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("quadtri-" + name + "-" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace quadtri::test
