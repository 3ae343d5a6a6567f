// SPDX-License-Identifier: MIT
#pragma once
// `hilbridge run --json`: the run result as one JSON document (verdict, failures, axes,
// expectations, faults, scheduler statistics with the wake-up latency histogram, the real-time
// settings in force, transport reports). Documented in docs/runtime.md.

#include <chrono>
#include <string>
#include <string_view>

#include "hil/core/clock.hpp"
#include "hil/runtime/run_result.hpp"

namespace hil::cli {

/// Microseconds as double: the unit of every period, latency and cycle-work figure in the JSON.
[[nodiscard]] inline double to_microseconds(Duration d) noexcept {
  return std::chrono::duration<double, std::micro>(d).count();
}

/// A JSON string literal (quotes included) for `s` (UTF-8 passed through, control characters escaped).
[[nodiscard]] std::string json_string(std::string_view s);
[[nodiscard]] std::string run_json(const runtime::RunResult& r);
/// {"priority":..,"policy":"SCHED_FIFO","cpu":..,"io_cpus":[..],...,"fallbacks":[..]}
[[nodiscard]] std::string realtime_json(const runtime::RealtimeReport& r);

}  // namespace hil::cli
