// SPDX-License-Identifier: MIT
#pragma once
// Live one-line-per-axis status of `hilbridge run`: on a terminal the block is redrawn in place
// (ANSI cursor up + erase line) at most every 100 ms of wall time; otherwise a plain line per
// axis every second of scenario time (CI logs, pipes).

#include <chrono>
#include <cstdio>

#include "hil/runtime/run_observer.hpp"

namespace hil::cli {

class LiveStatus final : public runtime::RunObserver {
 public:
  explicit LiveStatus(std::FILE* out = stdout);
  void on_start(const runtime::Scenario& scenario, const runtime::Machine& machine) override;
  void on_cycle(Duration t, const runtime::Machine& machine) noexcept override;
  void on_finish(const runtime::RunResult& result) override;

 private:
  void draw(Duration t, const runtime::Machine& machine);
  std::FILE* out_;
  bool tty_;
  bool drawn_ = false;
  std::size_t lines_ = 0;
  std::chrono::steady_clock::time_point last_wall_{};
  Duration next_plain_{};
  Duration last_t_{};
  const runtime::Machine* machine_ = nullptr;
};

}  // namespace hil::cli
