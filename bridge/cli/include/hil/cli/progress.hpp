// SPDX-License-Identifier: MIT
#pragma once
// Progress bar with rate and ETA for long transfers. On a terminal it redraws one line on
// stderr; otherwise (CI logs, pipes) it prints a line every 10 %. Uses the injected clock.

#include <cstdint>
#include <cstdio>
#include <string>

#include "hil/core/clock.hpp"

namespace hil::cli {

class ProgressBar {
 public:
  ProgressBar(std::string label, std::uint64_t total, std::string unit, const Clock& clock, std::FILE* out = stderr);
  /// Set the amount done so far (monotonic). Cheap: redraws at most every 100 ms.
  void update(std::uint64_t done);
  /// Final line ("done" or the reason it stopped).
  void finish(const std::string& outcome);

 private:
  void draw(bool final);
  std::string label_;
  std::uint64_t total_;
  std::string unit_;
  const Clock& clock_;
  std::FILE* out_;
  bool tty_;
  TimePoint start_;
  TimePoint last_draw_{};
  std::uint64_t done_ = 0;
  int last_decile_ = -1;
};

}  // namespace hil::cli
