// SPDX-License-Identifier: MIT
#pragma once
// Test helper: run an independent peer (python3-can script, can-utils) as a child process with
// its stdout+stderr on a pipe; read lines and wait for exit with bounded timeouts (poll, no sleeps).
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

extern char** environ;

namespace hil::can::test {

class Subprocess {
 public:
  explicit Subprocess(const std::vector<std::string>& argv) {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) return;
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, fds[1], 1);
    posix_spawn_file_actions_adddup2(&fa, fds[1], 2);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    if (posix_spawn(&pid_, args[0], &fa, nullptr, args.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&fa);
    ::close(fds[1]);
    fd_ = fds[0];
  }
  ~Subprocess() {
    if (pid_ > 0 && !exit_code_) {
      ::kill(pid_, SIGKILL);
      int st = 0;
      ::waitpid(pid_, &st, 0);
    }
    if (fd_ >= 0) ::close(fd_);
  }
  Subprocess(const Subprocess&) = delete;
  Subprocess& operator=(const Subprocess&) = delete;

  [[nodiscard]] bool started() const { return pid_ > 0; }
  /// Next output line (without '\n'), or nothing on EOF/timeout.
  std::optional<std::string> read_line(std::chrono::milliseconds timeout = std::chrono::seconds(10)) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (;;) {
      if (auto nl = buf_.find('\n'); nl != std::string::npos) {
        std::string line = buf_.substr(0, nl);
        buf_.erase(0, nl + 1);
        output_ += line + "\n";
        return line;
      }
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      if (left.count() <= 0 || fd_ < 0) return std::nullopt;
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) return std::nullopt;
      char tmp[4096];
      const auto n = ::read(fd_, tmp, sizeof tmp);
      if (n <= 0) {
        if (!buf_.empty()) {
          std::string line;
          line.swap(buf_);
          output_ += line + "\n";
          return line;
        }
        return std::nullopt;
      }
      buf_.append(tmp, static_cast<std::size_t>(n));
    }
  }
  /// Read lines until one contains `needle` (bounded). Returns it.
  std::optional<std::string> wait_for_line(const std::string& needle,
                                           std::chrono::milliseconds timeout = std::chrono::seconds(10)) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      auto line =
          read_line(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()));
      if (!line) return std::nullopt;
      if (line->find(needle) != std::string::npos) return line;
    }
    return std::nullopt;
  }
  /// Exit code after the child ends (bounded; killed on timeout -> -1).
  int wait(std::chrono::milliseconds timeout = std::chrono::seconds(10)) {
    if (exit_code_) return *exit_code_;
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (
        read_line(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()))) {
    }
    int st = 0;
    for (;;) {
      const pid_t r = ::waitpid(pid_, &st, WNOHANG);
      if (r == pid_) break;
      if (std::chrono::steady_clock::now() >= deadline) {
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &st, 0);
        exit_code_ = -1;
        return -1;
      }
      pollfd p{fd_, POLLIN, 0};  // the pipe closes when the child exits
      ::poll(&p, 1, 10);
      if (fd_ >= 0 && (p.revents & POLLIN)) (void)read_line(std::chrono::milliseconds(1));
    }
    exit_code_ = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
    return *exit_code_;
  }
  void terminate() {
    if (pid_ > 0 && !exit_code_) ::kill(pid_, SIGTERM);
  }
  [[nodiscard]] const std::string& output() const { return output_; }

 private:
  pid_t pid_ = -1;
  int fd_ = -1;
  std::string buf_;
  std::string output_;
  std::optional<int> exit_code_;
};

/// True if /usr/bin/python3 can import `module`.
inline bool python_has(const std::string& module) {
  if (::access("/usr/bin/python3", X_OK) != 0) return false;
  Subprocess p({"/usr/bin/python3", "-c", "import " + module});
  return p.started() && p.wait(std::chrono::seconds(90)) == 0;  // slow under QEMU TCG
}

}  // namespace hil::can::test
