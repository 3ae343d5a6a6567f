// SPDX-License-Identifier: MIT
#include "hil/runtime/trace_csv.hpp"

#include <cerrno>

#include <fmt/format.h>

namespace hil::runtime {
namespace {

/// A CSV field (RFC 4180): quoted, with quotes doubled, when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

}  // namespace

std::error_code TraceCsvWriter::open(const std::filesystem::path& path) {
  file_.reset(std::fopen(path.c_str(), "w"));
  if (!file_) return {errno, std::generic_category()};
  std::setvbuf(file_.get(), nullptr, _IOFBF, 1 << 16);
  return {};
}

void TraceCsvWriter::on_start(const Scenario&, const Machine& machine) {
  if (!file_) return;
  std::string h = "t_s";
  for (const auto& a : machine.axes()) {
    const std::string& n = a.spec->name;
    const std::string& u = a.spec->units;
    for (const std::string& column :
         {fmt::format("{}_position_{}", n, u), fmt::format("{}_command_{}", n, u),
          fmt::format("{}_velocity_{}_per_s", n, u), fmt::format("{}_following_error_{}", n, u),
          fmt::format("{}_state", n), fmt::format("{}_fault", n)}) {
      h += ',';
      h += csv_field(column);
    }
  }
  // The controller's I/O (inputs, outputs, markers it names and those the scenario uses), one
  // 0/1 column each, and its newest active device error.
  for (const auto& [name, address] : machine.io_signals()) {
    h += ',';
    h += csv_field(fmt::format("io_{}", name));
  }
  if (const auto* c = machine.controller()) {
    // Its analog values (ctl_NAME), then its newest active device error.
    const auto names = c->trace_signals();
    signals_ = names.size();
    for (const auto& name : names) {
      h += ',';
      h += csv_field("ctl_" + name);
    }
    h += ",controller_error";
  }
  h += '\n';
  if (std::fputs(h.c_str(), file_.get()) < 0 && !error_) error_ = {errno, std::generic_category()};
}

void TraceCsvWriter::on_cycle(Duration t, const Machine& machine) noexcept {
  if (!file_ || error_) return;
  try {
    line_.clear();
    fmt::format_to(std::back_inserter(line_), "{:.6f}", to_seconds(t));
    for (const auto& a : machine.axes()) {
      const auto& st = a.axis->status();
      fmt::format_to(std::back_inserter(line_), ",{:.6f},{:.6f},{:.6f},{:.6f},{},", st.position, st.command_position,
                     st.velocity, st.following_error, motion::to_string(st.state));
      if (st.fault)
        fmt::format_to(std::back_inserter(line_), "{}:{}", st.fault.code.category().name(), st.fault.code.value());
    }
    if (const auto* c = machine.controller()) {
      for (const auto& [name, address] : machine.io_signals()) {
        line_ += ',';
        line_ += c->io().get(address) ? '1' : '0';
      }
      for (std::size_t i = 0; i < signals_; ++i)
        fmt::format_to(std::back_inserter(line_), ",{:.6f}", c->trace_value(i));
      line_ += ',';
      if (const auto active = c->errors().active(); !active.empty()) {
        const auto& e = active.back();
        fmt::format_to(std::back_inserter(line_), "{}:{}", e.fault.code.category().name(), e.code_text());
      }
    }
    line_ += '\n';
    if (std::fwrite(line_.data(), 1, line_.size(), file_.get()) != line_.size())
      error_ = {errno, std::generic_category()};
    ++rows_;
  } catch (...) {
    error_ = std::make_error_code(std::errc::not_enough_memory);
  }
}

void TraceCsvWriter::on_finish(const RunResult&) {
  if (file_ && std::fflush(file_.get()) != 0 && !error_) error_ = {errno, std::generic_category()};
}

std::error_code TraceCsvWriter::close() {
  if (file_) {
    if (std::fclose(file_.release()) != 0 && !error_) error_ = {errno, std::generic_category()};
  }
  return error_;
}

}  // namespace hil::runtime
