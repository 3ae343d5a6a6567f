// SPDX-License-Identifier: MIT
#pragma once
// Real-time operation of the cycle thread (docs/runtime.md, "Real-time operation"): what a run
// asks for (RealtimeOptions: `hilbridge run --realtime`, the scenario key `realtime:`) and what
// it got (RealtimeReport, printed in the summary and in `--json`). Portable data only; the Linux
// implementation is hil/runtime/linux/realtime_session.hpp.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace hil::runtime {

struct RealtimeOptions {
  bool enabled = false;
  int priority = 80;        ///< SCHED_FIFO priority, 1..99 (cyclictest's usual 80)
  std::optional<int> cpu;   ///< CPU of the cycle thread; unset = the first isolated CPU, else the last allowed one
  bool lock_memory = true;  ///< mlockall(MCL_CURRENT | MCL_FUTURE) and a pre-faulted stack
  bool dma_latency = true;  ///< hold /dev/cpu_dma_latency at 0 (no deep C-states) while running
  bool fallback = false;    ///< a refused setting is reported and skipped instead of failing the run
};

/// One real-time setting; the values name what the summary prints.
enum class RealtimeSetting : std::uint8_t { scheduling, memory_lock, cpu_affinity, dma_latency };
[[nodiscard]] std::string_view to_string(RealtimeSetting s) noexcept;

/// A setting the system refused: which, the errno, and the message (what, why, what to do).
struct RealtimeProblem {
  RealtimeSetting setting = RealtimeSetting::scheduling;
  int error = 0;  ///< errno of the refused call
  std::string message;
};

/// What the cycle thread actually runs with.
struct RealtimeReport {
  bool requested = false;
  int priority = 0;          ///< SCHED_FIFO priority in force; 0 = normal scheduling
  std::optional<int> cpu;    ///< CPU the cycle thread is pinned to
  std::vector<int> io_cpus;  ///< CPUs left to the other threads (I/O, transports)
  bool memory_locked = false;
  bool dma_latency_held = false;
  bool absolute_sleeps = false;            ///< clock_nanosleep(TIMER_ABSTIME) wake-ups
  std::vector<RealtimeProblem> fallbacks;  ///< refused settings skipped because fallback was allowed

  /// "SCHED_FIFO 80 on CPU 1 (I/O on CPU 0), memory locked, cpu_dma_latency 0, absolute sleeps"
  [[nodiscard]] std::string describe() const;
};

}  // namespace hil::runtime
