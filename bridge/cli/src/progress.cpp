// SPDX-License-Identifier: MIT
#include "hil/cli/progress.hpp"

#include <unistd.h>

#include <algorithm>

#include <fmt/format.h>

namespace hil::cli {

ProgressBar::ProgressBar(std::string label, std::uint64_t total, std::string unit, const Clock& clock, std::FILE* out)
    : label_(std::move(label)),
      total_(total),
      unit_(std::move(unit)),
      clock_(clock),
      out_(out),
      tty_(::isatty(::fileno(out)) != 0),
      start_(clock.now()) {}

void ProgressBar::update(std::uint64_t done) {
  done_ = std::min(std::max(done_, done), total_);
  const auto now = clock_.now();
  if (tty_) {
    if (now - last_draw_ < std::chrono::milliseconds(100) && done_ != total_) return;
    last_draw_ = now;
    draw(false);
  } else {
    const int decile = total_ == 0 ? 10 : static_cast<int>(done_ * 10 / total_);
    if (decile != last_decile_) {
      last_decile_ = decile;
      draw(false);
    }
  }
}

void ProgressBar::finish(const std::string& outcome) {
  draw(true);
  fmt::print(out_, " {}\n", outcome);
  std::fflush(out_);
}

void ProgressBar::draw(bool final) {
  const double frac = total_ == 0 ? 1.0 : static_cast<double>(done_) / static_cast<double>(total_);
  const double elapsed = to_seconds(clock_.now() - start_);
  const double rate = elapsed > 0 ? static_cast<double>(done_) / elapsed : 0.0;
  std::string eta = "--:--";
  if (rate > 0 && done_ < total_) {
    const auto left = static_cast<long>(static_cast<double>(total_ - done_) / rate + 0.5);
    eta = fmt::format("{:02}:{:02}", left / 60, left % 60);
  } else if (done_ >= total_) {
    eta = "00:00";
  }
  constexpr int width = 30;
  const int filled = static_cast<int>(frac * width);
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(width, '.');
  const auto line = fmt::format("{} [{}] {:3.0f}% {}/{} {} {:.0f} {}/s ETA {}", label_, bar, frac * 100.0, done_,
                                total_, unit_, rate, unit_, eta);
  if (tty_)
    fmt::print(out_, "\r{}\x1b[K", line);
  else
    fmt::print(out_, "{}{}", line, final ? "" : "\n");
  std::fflush(out_);
}

}  // namespace hil::cli
