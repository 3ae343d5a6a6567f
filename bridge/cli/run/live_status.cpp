// SPDX-License-Identifier: MIT
#include "live_status.hpp"

#include <unistd.h>

#include <fmt/format.h>

namespace hil::cli {

LiveStatus::LiveStatus(std::FILE* out) : out_(out), tty_(::isatty(::fileno(out)) != 0) {}

void LiveStatus::on_start(const runtime::Scenario& scenario, const runtime::Machine& machine) {
  machine_ = &machine;
  lines_ = machine.axes().size() + 1;
  fmt::print(out_, "running {}{}\n", scenario.name.empty() ? scenario.file : scenario.name,
             scenario.description.empty() ? "" : ": " + scenario.description);
  for (const auto& note : machine.io_link_notes()) fmt::print(out_, "{}\n", note);
  std::fflush(out_);
}

void LiveStatus::on_cycle(Duration t, const runtime::Machine& machine) noexcept {
  last_t_ = t;
  if (tty_) {
    const auto now = std::chrono::steady_clock::now();
    if (drawn_ && now - last_wall_ < std::chrono::milliseconds(100)) return;
    last_wall_ = now;
  } else {
    if (t < next_plain_) return;
    next_plain_ = t + std::chrono::seconds(1);
  }
  try {
    draw(t, machine);
  } catch (...) {  // a failing terminal write must never stop the cycle
  }
}

void LiveStatus::draw(Duration t, const runtime::Machine& machine) {
  std::string block;
  if (tty_ && drawn_) block += fmt::format("\x1b[{}F", lines_);  // back to the first line of the block
  const char* eol = tty_ ? "\x1b[K\n" : "\n";
  block += fmt::format("t={:8.3f} s{}", to_seconds(t), eol);
  for (const auto& a : machine.axes()) {
    const auto& st = a.axis->status();
    const std::string& u = a.spec->units;
    std::string fault = st.fault ? "  " + st.fault.describe() : "";
    if (fault.size() > 70) fault = fault.substr(0, 67) + "...";
    block +=
        fmt::format("  {:<8} pos {:>11.3f} {:<3} vel {:>10.3f} {}/s  fe {:>8.4f} {:<3} {:<10}{}{}", a.spec->name,
                    st.position, u, st.velocity, u, st.following_error, u, motion::to_string(st.state), fault, eol);
  }
  std::fputs(block.c_str(), out_);
  std::fflush(out_);
  drawn_ = true;
}

void LiveStatus::on_finish(const runtime::RunResult&) {
  if (machine_) {
    drawn_ = drawn_ && tty_;
    try {
      draw(last_t_, *machine_);  // the final state, always
    } catch (...) {
    }
  }
}

}  // namespace hil::cli
