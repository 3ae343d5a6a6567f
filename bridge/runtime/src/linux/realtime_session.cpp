// SPDX-License-Identifier: MIT
#include "hil/runtime/linux/realtime_session.hpp"

#include <fcntl.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "hil/runtime/linux/absolute_sleeper.hpp"

namespace hil::runtime::linux_rt {
namespace {

constexpr std::size_t prefault_stack_bytes = 256 * 1024;

std::string executable() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  return n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : std::string("hilbridge");
}

std::string limit_text(int resource, bool bytes) {
  rlimit rl{};
  if (getrlimit(resource, &rl) != 0) return "unknown";
  if (rl.rlim_cur == RLIM_INFINITY) return "unlimited";
  return bytes ? fmt::format("{} KiB", rl.rlim_cur / 1024) : fmt::format("{}", rl.rlim_cur);
}

// Touch the stack the cycle thread will use, so (with the memory locked) it never faults.
[[gnu::noinline]] void prefault_stack() {
  unsigned char stack[prefault_stack_bytes];
  std::memset(stack, 0, sizeof stack);
  asm volatile("" : : "r"(stack) : "memory");  // keep the writes
}

bool set_affinity(const std::vector<int>& cpus) {
  cpu_set_t set;
  CPU_ZERO(&set);
  for (int c : cpus)
    if (c >= 0 && c < CPU_SETSIZE) CPU_SET(static_cast<std::size_t>(c), &set);
  return sched_setaffinity(0, sizeof set, &set) == 0;
}

RealtimeProblem scheduling_problem(int priority, int err) {
  std::string m = fmt::format("SCHED_FIFO priority {} was refused for the cycle thread (sched_setscheduler: {})",
                              priority, std::strerror(err));
  if (err == EPERM)
    m += fmt::format(
        ". Real-time scheduling needs CAP_SYS_NICE or an RLIMIT_RTPRIO of at least {} (now {}). Either run as root, "
        "or give the binary the capabilities: sudo setcap cap_sys_nice,cap_ipc_lock=ep {}, or allow your group in "
        "/etc/security/limits.conf ('@realtime - rtprio 99' and '@realtime - memlock unlimited', then log in "
        "again); in a container add --cap-add=SYS_NICE; with CONFIG_RT_GROUP_SCHED the cgroup also needs "
        "cpu.rt_runtime_us > 0",
        priority, limit_text(RLIMIT_RTPRIO, false), executable());
  return {RealtimeSetting::scheduling, err, std::move(m)};
}

RealtimeProblem memory_problem(int err) {
  std::string m = fmt::format("locking the process' memory was refused (mlockall: {})", std::strerror(err));
  if (err == EPERM || err == ENOMEM)
    m += fmt::format(
        ". It needs CAP_IPC_LOCK or an RLIMIT_MEMLOCK above the process' size (now {}): run as root, or sudo setcap "
        "cap_sys_nice,cap_ipc_lock=ep {}, or '@realtime - memlock unlimited' in /etc/security/limits.conf; or turn "
        "it off with the scenario key realtime: {{lock_memory: false}} (page faults may then delay cycles)",
        limit_text(RLIMIT_MEMLOCK, true), executable());
  return {RealtimeSetting::memory_lock, err, std::move(m)};
}

RealtimeProblem dma_problem(int err) {
  std::string m = fmt::format("cannot hold /dev/cpu_dma_latency at 0 (open for writing: {})", std::strerror(err));
  if (err == EACCES || err == EPERM)
    m += ". Only root may write it by default: run as root, or add a udev rule such as KERNEL==\"cpu_dma_latency\", "
         "GROUP=\"realtime\", MODE=\"0660\"; or turn it off with realtime: {dma_latency: false} (deep C-states may "
         "then add wake-up latency)";
  else if (err == ENOENT)
    m += ". This kernel has no PM QoS interface (CONFIG_PM); turn it off with realtime: {dma_latency: false}";
  return {RealtimeSetting::dma_latency, err, std::move(m)};
}

}  // namespace

std::vector<int> parse_cpu_list(std::string_view list) {
  std::vector<int> out;
  while (!list.empty() && (list.back() == '\n' || list.back() == ' ')) list.remove_suffix(1);
  if (list.empty()) return out;
  std::size_t pos = 0;
  while (pos <= list.size()) {
    const std::size_t comma = std::min(list.find(',', pos), list.size());
    const std::string_view item = list.substr(pos, comma - pos);
    const std::size_t dash = item.find('-');
    int lo = 0, hi = 0;
    const auto num = [](std::string_view s, int& v) {
      const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
      return r.ec == std::errc{} && r.ptr == s.data() + s.size() && v >= 0 && v < CPU_SETSIZE;
    };
    if (dash == std::string_view::npos) {
      if (!num(item, lo)) return {};
      hi = lo;
    } else if (!num(item.substr(0, dash), lo) || !num(item.substr(dash + 1), hi) || hi < lo) {
      return {};
    }
    for (int c = lo; c <= hi; ++c) out.push_back(c);
    pos = comma + 1;
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<int> allowed_cpus() {
  std::vector<int> out;
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return out;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(static_cast<std::size_t>(c), &set)) out.push_back(c);
  return out;
}

std::vector<int> isolated_cpus() {
  std::ifstream in("/sys/devices/system/cpu/isolated");
  std::string line;
  if (!in || !std::getline(in, line)) return {};
  return parse_cpu_list(line);
}

std::expected<std::unique_ptr<RealtimeSession>, RealtimeProblem> RealtimeSession::begin(
    const RealtimeOptions& options) {
  std::unique_ptr<RealtimeSession> s(new RealtimeSession());
  RealtimeReport& r = s->report_;
  r.requested = true;
  r.absolute_sleeps = true;
  const auto refuse = [&](RealtimeProblem p) -> bool {
    if (!options.fallback) return true;
    r.fallbacks.push_back(std::move(p));
    return false;
  };

  // Affinity: the cycle CPU, and this thread (with whatever it starts before enter_cycle_cpu)
  // on the others.
  s->original_cpus_ = allowed_cpus();
  const auto& allowed = s->original_cpus_;
  std::optional<int> cpu;
  if (options.cpu) {
    if (std::find(allowed.begin(), allowed.end(), *options.cpu) == allowed.end()) {
      RealtimeProblem p{RealtimeSetting::cpu_affinity, EINVAL,
                        fmt::format("CPU {} is not available to this process (allowed: {}); choose one of them "
                                    "with --realtime-cpu or the scenario key realtime: {{cpu: N}}",
                                    *options.cpu, fmt::join(allowed, ","))};
      if (!options.fallback) return std::unexpected(std::move(p));
      r.fallbacks.push_back(std::move(p));
    } else {
      cpu = options.cpu;
    }
  } else if (!allowed.empty()) {
    for (int c : isolated_cpus())
      if (!cpu && std::find(allowed.begin(), allowed.end(), c) != allowed.end()) cpu = c;
    if (!cpu) cpu = allowed.back();
  }
  if (cpu) {
    r.cpu = cpu;
    for (int c : allowed)
      if (c != *cpu) r.io_cpus.push_back(c);
    if (!r.io_cpus.empty()) (void)set_affinity(r.io_cpus);
  }

#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer's mlockall is a no-op that returns 0: an instrumented build (CI's) locks
  // nothing, and its report says so rather than "memory locked".
  constexpr bool mlockall_works = false;
#else
  constexpr bool mlockall_works = true;
#endif
  if (options.lock_memory && mlockall_works) {
    if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
      s->locked_ = true;
      r.memory_locked = true;
      prefault_stack();
    } else if (const int err = errno; refuse(memory_problem(err))) {
      return std::unexpected(memory_problem(err));
    }
  }

  if (options.dma_latency) {
    const int fd = open("/dev/cpu_dma_latency", O_WRONLY | O_CLOEXEC);
    const std::int32_t zero = 0;
    if (fd >= 0 && write(fd, &zero, sizeof zero) == static_cast<ssize_t>(sizeof zero)) {
      s->dma_fd_ = fd;  // the request holds while the file stays open
      r.dma_latency_held = true;
    } else {
      const int err = errno;
      if (fd >= 0) close(fd);
      if (refuse(dma_problem(err))) return std::unexpected(dma_problem(err));
    }
  }

  sched_param sp{};
  sp.sched_priority = options.priority;
  // SCHED_RESET_ON_FORK: threads this one starts (transports, resolvers) run normally.
  if (sched_setscheduler(0, SCHED_FIFO | SCHED_RESET_ON_FORK, &sp) == 0) {
    s->scheduled_ = true;
    r.priority = options.priority;
  } else if (const int err = errno; refuse(scheduling_problem(options.priority, err))) {
    return std::unexpected(scheduling_problem(options.priority, err));
  }
  if (!s->scheduled_) minimise_timer_slack();
  return s;
}

void RealtimeSession::enter_cycle_cpu() noexcept {
  if (report_.cpu) (void)set_affinity({*report_.cpu});
}

RealtimeSession::~RealtimeSession() {
  if (scheduled_) {
    sched_param sp{};
    (void)sched_setscheduler(0, SCHED_OTHER, &sp);
  }
  if (dma_fd_ >= 0) close(dma_fd_);
  if (locked_) (void)munlockall();
  if (!original_cpus_.empty()) (void)set_affinity(original_cpus_);
}

}  // namespace hil::runtime::linux_rt
