// SPDX-License-Identifier: MIT
#include "hil/runtime/realtime.hpp"

#include <fmt/format.h>

namespace hil::runtime {

std::string_view to_string(RealtimeSetting s) noexcept {
  switch (s) {
    case RealtimeSetting::scheduling:
      return "scheduling";
    case RealtimeSetting::memory_lock:
      return "memory_lock";
    case RealtimeSetting::cpu_affinity:
      return "cpu_affinity";
    case RealtimeSetting::dma_latency:
      return "dma_latency";
  }
  return "?";
}

std::string RealtimeReport::describe() const {
  std::string out = priority > 0 ? fmt::format("SCHED_FIFO {}", priority) : "normal scheduling (SCHED_OTHER)";
  if (cpu) {
    out += fmt::format(" on CPU {}", *cpu);
    if (!io_cpus.empty()) out += fmt::format(" (other threads on CPU {})", fmt::join(io_cpus, ","));
  }
  out += memory_locked ? ", memory locked" : ", memory not locked";
  out += dma_latency_held ? ", cpu_dma_latency held at 0" : ", cpu_dma_latency not held";
  if (absolute_sleeps) out += ", clock_nanosleep(TIMER_ABSTIME) wake-ups";
  for (const auto& f : fallbacks) out += fmt::format("; fell back: {} ({})", to_string(f.setting), f.message);
  return out;
}

}  // namespace hil::runtime
