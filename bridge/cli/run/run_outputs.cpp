// SPDX-License-Identifier: MIT
#include "run_outputs.hpp"

#include <fstream>

#include <fmt/format.h>

namespace hil::cli {

std::optional<std::string> RunOutputs::open(const std::string& trace, const std::string& plot) {
  trace_path_ = trace;
  plot_path_ = plot;
  if (!trace.empty()) {
    trace_.emplace();
    if (auto ec = trace_->open(trace)) return fmt::format("cannot write the trace file {}: {}", trace, ec.message());
  }
  if (!plot.empty()) {
    std::ofstream probe(plot, std::ios::app);  // fail before the run, not after it
    if (!probe) return fmt::format("cannot write the plot file {}", plot);
    plot_.emplace();
  }
  return std::nullopt;
}

std::vector<runtime::RunObserver*> RunOutputs::observers() {
  std::vector<runtime::RunObserver*> out;
  if (trace_) out.push_back(&*trace_);
  if (plot_) out.push_back(&*plot_);
  return out;
}

std::optional<std::string> RunOutputs::close(const runtime::RunResult&) {
  std::optional<std::string> err;
  if (trace_) {
    if (auto ec = trace_->close())
      err = fmt::format("writing the trace file {} failed: {}", trace_path_, ec.message());
    else
      written_.push_back(fmt::format("{} ({} rows)", trace_path_, trace_->rows()));
  }
  if (plot_) {
    std::ofstream out(plot_path_, std::ios::trunc);
    out << runtime::render_svg(plot_->data());
    out.close();
    if (!out)
      err = fmt::format("writing the plot file {} failed", plot_path_);
    else
      written_.push_back(plot_path_);
  }
  return err;
}

}  // namespace hil::cli
