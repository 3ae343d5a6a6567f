// SPDX-License-Identifier: MIT
#pragma once
// The end-of-run summary printed by `hilbridge run` (per axis: final position, maximum
// following error, faults; expectations; scheduler statistics; transport reports; verdict).

#include <cstdio>

#include "hil/runtime/run_result.hpp"

namespace hil::cli {

void print_summary(std::FILE* out, const runtime::RunResult& r);
/// "12345 cycles at 1.000 ms; wake-up latency min/mean/p99/max 3/12/40/95 us; 0 overruns"
[[nodiscard]] std::string describe_scheduler(const runtime::SchedulerStats& s);

}  // namespace hil::cli
