// SPDX-License-Identifier: MIT
#include "hil/mocks/gpio/mock_lines.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace hil::gpio::mock {

bool InputScript::level_at(std::int64_t t_ns) const noexcept {
  bool level = initial;
  for (const auto& [t, l] : changes) {
    if (t > t_ns) break;
    level = l;
  }
  return level;
}

MockLines::MockLines(std::vector<LineSpec> specs, const Clock& clock)
    : specs_(std::move(specs)),
      clock_(clock),
      levels_(specs_.size()),
      sources_(specs_.size()),
      forced_(specs_.size()),
      failing_(specs_.size()) {
  for (std::size_t i = 0; i < specs_.size(); ++i) levels_[i] = specs_[i].initial;
}

void MockLines::record(const Edge& e) noexcept {
  if (e.line >= specs_.size() || specs_[e.line].direction != LineDirection::output) {
    if (errors_.size() < 100)
      errors_.push_back(fmt::format("edge at {} ns on line {} which is not an output", e.t_ns, e.line));
    return;
  }
  if (e.t_ns < last_t_ && errors_.size() < 100) {
    errors_.push_back(fmt::format("edge at {} ns on '{}' is earlier than the previous edge at {} ns", e.t_ns,
                                  specs_[e.line].role, last_t_));
  }
  if (levels_[e.line] == e.level && errors_.size() < 100) {
    errors_.push_back(fmt::format("edge at {} ns on '{}' does not change the level", e.t_ns, specs_[e.line].role));
  }
  last_t_ = std::max(last_t_, e.t_ns);
  levels_[e.line] = e.level;
  ++edges_seen_;
  if (recorded_.size() < record_limit_) {
    try {
      recorded_.push_back(e);
    } catch (...) {
      record_limit_ = recorded_.size();
    }
  }
  for (auto& f : observers_) f(e);
}

std::error_code MockLines::set_value(std::size_t index, bool level) noexcept {
  if (index >= specs_.size() || specs_[index].direction != LineDirection::output) {
    return std::make_error_code(std::errc::invalid_argument);
  }
  if (failing_[index]) return failing_[index];
  if (levels_[index] != level)
    record(Edge{clock_.now().time_since_epoch().count(), static_cast<std::uint16_t>(index), level});
  return {};
}

std::expected<bool, std::error_code> MockLines::get_value(std::size_t index) noexcept {
  if (index >= specs_.size()) return std::unexpected(std::make_error_code(std::errc::invalid_argument));
  if (failing_[index]) return std::unexpected(failing_[index]);
  if (specs_[index].direction == LineDirection::output) return levels_[index];
  if (forced_[index]) return *forced_[index];
  if (sources_[index]) return sources_[index](clock_.now().time_since_epoch().count());
  return levels_[index];
}

void MockLines::output(std::span<const Edge> edges) noexcept {
  for (const Edge& e : edges) record(e);
}

void MockLines::set_input(std::size_t index, bool level) {
  sources_.at(index) = nullptr;
  levels_.at(index) = level;
}

void MockLines::set_input_source(std::size_t index, InputSource source) {
  sources_.at(index) = std::move(source);
}

void MockLines::fail_line(std::size_t index, std::error_code error) {
  failing_.at(index) = error;
}

void MockLines::force_input(std::size_t index, std::optional<bool> level) {
  forced_.at(index) = level;
}

StepDirDecoder::StepDirDecoder(MockLines& outputs, std::uint16_t step_line, std::uint16_t dir_line, bool active_level,
                               bool dir_forward_level, std::int64_t initial_position)
    : step_line_(step_line),
      dir_line_(dir_line),
      active_level_(active_level),
      dir_forward_level_(dir_forward_level),
      dir_level_(outputs.output_level(dir_line)),
      position_(initial_position) {
  outputs.add_observer([this](const Edge& e) { on_edge(e); });
}

void StepDirDecoder::on_edge(const Edge& e) {
  if (e.line == step_line_ || e.line == dir_line_) queue_.push_back(e);
}

std::int64_t StepDirDecoder::position_at(std::int64_t t_ns) {
  while (head_ < queue_.size() && queue_[head_].t_ns <= t_ns) {
    const Edge& e = queue_[head_++];
    if (e.line == dir_line_) {
      dir_level_ = e.level;
    } else if (e.level == active_level_) {
      position_ += dir_level_ == dir_forward_level_ ? 1 : -1;
    }
  }
  if (head_ > 4096 && head_ * 2 > queue_.size()) {
    queue_.erase(queue_.begin(), queue_.begin() + static_cast<std::ptrdiff_t>(head_));
    head_ = 0;
  }
  return position_;
}

}  // namespace hil::gpio::mock
