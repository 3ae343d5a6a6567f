// SPDX-License-Identifier: MIT
#pragma once
// The optional outputs of `hilbridge run`: --trace (CSV) and --plot (SVG).

#include <optional>
#include <string>
#include <vector>

#include "hil/runtime/svg_plot.hpp"
#include "hil/runtime/trace_csv.hpp"

namespace hil::cli {

class RunOutputs {
 public:
  /// Opens the trace file now (so a bad path fails before the run); empty paths are skipped.
  [[nodiscard]] std::optional<std::string> open(const std::string& trace, const std::string& plot);
  [[nodiscard]] std::vector<runtime::RunObserver*> observers();
  /// Closes the trace and writes the plot. An error message when a file could not be written.
  [[nodiscard]] std::optional<std::string> close(const runtime::RunResult& result);
  [[nodiscard]] const std::vector<std::string>& written() const noexcept { return written_; }

 private:
  std::string trace_path_, plot_path_;
  std::optional<runtime::TraceCsvWriter> trace_;
  std::optional<runtime::PlotRecorder> plot_;
  std::vector<std::string> written_;
};

}  // namespace hil::cli
