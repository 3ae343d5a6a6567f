// SPDX-License-Identifier: MIT
#pragma once
// `hilbridge run --trace FILE.csv`: one row per cycle, columns per axis:
//   t_s, <axis>_position_<unit>, <axis>_command_<unit>, <axis>_velocity_<unit>_per_s,
//   <axis>_following_error_<unit>, <axis>_state, <axis>_fault
// Streams through a buffered file; nothing per cycle is kept in memory.

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <system_error>

#include "hil/runtime/run_observer.hpp"

namespace hil::runtime {

class TraceCsvWriter final : public RunObserver {
 public:
  /// Opens (truncates) `path`. Error: the OS error.
  [[nodiscard]] std::error_code open(const std::filesystem::path& path);
  void on_start(const Scenario& scenario, const Machine& machine) override;
  void on_cycle(Duration t, const Machine& machine) noexcept override;
  void on_finish(const RunResult&) override;
  /// Flush and close; the first write error of the run, if any.
  [[nodiscard]] std::error_code close();
  [[nodiscard]] std::uint64_t rows() const noexcept { return rows_; }

 private:
  struct FileCloser {
    void operator()(std::FILE* f) const noexcept { std::fclose(f); }
  };
  std::unique_ptr<std::FILE, FileCloser> file_;
  std::error_code error_;
  std::uint64_t rows_ = 0;
  std::size_t signals_ = 0;  ///< the controller's trace_signals()
  std::string line_;
};

}  // namespace hil::runtime
