// SPDX-License-Identifier: MIT
#pragma once
// Presenting wake-up latency: a coarse histogram (decade steps 1-2-5 µs), its text and JSON
// forms, and the minimum cycle period a measured latency distribution recommends. Pure
// functions of a LatencyHistogram (`hilbridge run` summary and --json, `hilbridge latency`).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hil/runtime/latency_histogram.hpp"

namespace hil::runtime {

struct LatencyBin {
  Duration from{};
  std::optional<Duration> to;  ///< unset: the open last bin (20 ms and more)
  std::uint64_t count = 0;
};

/// Bins 0-10, 10-20, 20-50, 50-100, ... 10-20 ms µs and >= 20 ms; every sample in exactly one.
[[nodiscard]] std::vector<LatencyBin> latency_bins(const LatencyHistogram& h);

/// Lines "    20-50 us      1234  37.10 %  ########", one per non-empty bin (the empty ones between
/// the first and the last non-empty bins too), each indented by `indent`.
[[nodiscard]] std::string format_latency_histogram(const LatencyHistogram& h, std::string_view indent = "  ");

/// {"samples":N,"min_us":..,"mean_us":..,"p50_us":..,"p99_us":..,"p999_us":..,"max_us":..,
///  "bins":[{"from_us":0,"to_us":10,"count":N},...,{"from_us":20000,"to_us":null,"count":N}]}
[[nodiscard]] std::string latency_json(const LatencyHistogram& h);

/// The cycle periods hilbridge recommends from (100 µs .. 1 s: 100, 125, 200, 250, 500 µs, 1, 2,
/// 2.5, 4, 5, 10, 20, 25, 50, 100, 200, 250, 500 ms, 1 s).
[[nodiscard]] const std::vector<Duration>& standard_periods();

/// The smallest standard period that is at least twice the worst latency plus the worst cycle
/// work (so a cycle woken at its worst still has half a period left before the next deadline);
/// nullopt when even 1 s is too short or there are no samples.
[[nodiscard]] std::optional<Duration> recommended_min_period(const LatencyHistogram& h, Duration cycle_work = {});

}  // namespace hil::runtime
