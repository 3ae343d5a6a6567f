// SPDX-License-Identifier: MIT
#pragma once
// Linux real-time environment of the cycle thread: SCHED_FIFO (with SCHED_RESET_ON_FORK, so
// threads it starts later run normally), mlockall and a pre-faulted stack, /dev/cpu_dma_latency
// held at 0, CPU affinity (the cycle thread alone on its CPU, every thread created in between on
// the others). RAII: the destructor restores normal scheduling, unlocks memory, releases the
// latency request and restores the affinity.
//
// Use on the thread that will run the cycles:
//   auto rt = RealtimeSession::begin(options);   // before the machine is built
//   ... build transports (threads they start inherit the non-real-time CPUs) ...
//   rt->enter_cycle_cpu();                        // this thread onto the cycle CPU
// Thread: the calling thread's settings only (plus the process' memory lock).

#include <cstddef>
#include <expected>
#include <memory>
#include <vector>

#include "hil/runtime/realtime.hpp"

namespace hil::runtime::linux_rt {

class RealtimeSession {
 public:
  /// Apply `options` (enabled must be true) to the calling thread. A refused setting is an
  /// error (the first one, with what to do) unless options.fallback, when it is skipped and
  /// listed in report().fallbacks. Affinity: the calling thread moves to the CPUs other than the
  /// cycle CPU until enter_cycle_cpu().
  [[nodiscard]] static std::expected<std::unique_ptr<RealtimeSession>, RealtimeProblem> begin(
      const RealtimeOptions& options);
  ~RealtimeSession();
  RealtimeSession(const RealtimeSession&) = delete;
  RealtimeSession& operator=(const RealtimeSession&) = delete;

  /// Pin the calling thread to the cycle CPU (no-op when no CPU could be chosen).
  void enter_cycle_cpu() noexcept;

  [[nodiscard]] const RealtimeReport& report() const noexcept { return report_; }

 private:
  RealtimeSession() = default;
  RealtimeReport report_;
  int dma_fd_ = -1;
  bool scheduled_ = false;
  bool locked_ = false;
  std::vector<int> original_cpus_;
};

/// The CPUs this thread may run on (sched_getaffinity), ascending.
[[nodiscard]] std::vector<int> allowed_cpus();
/// The CPUs in /sys/devices/system/cpu/isolated (isolcpus=), ascending; empty when none.
[[nodiscard]] std::vector<int> isolated_cpus();
/// Parse a kernel CPU list ("1,3-5"); empty on a syntax error.
[[nodiscard]] std::vector<int> parse_cpu_list(std::string_view list);

}  // namespace hil::runtime::linux_rt
