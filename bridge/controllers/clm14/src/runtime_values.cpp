// SPDX-License-Identifier: MIT
// The CLM1.4's values by name for scenario expectations (`expect: {controller: NAME, value: V}`):
// what the manual's status readout shows (§9.2 status 00/02/04/41/53, digest clm14.md §2.8), read
// from the running model.
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "hil/controllers/clm14/runtime_controller.hpp"

namespace hil::controllers::clm14 {

namespace {

/// A handle is kind << 24 | argument.
enum class ValueKind : std::size_t {
  variable = 1,       ///< argument: n
  byte = 2,           ///< argument: area << 16 | source << 8 | byte
  counter = 3,        ///< argument: line
  task_line = 4,      ///< argument: task 1..5
  task_depth = 5,     ///< argument: task
  task_active = 6,    ///< argument: task
  error = 7,          ///< no argument
  axis_position = 8,  ///< argument: axis 1..4
  axis_latched = 9,   ///< argument: axis
  mode = 10,
  run = 11,
  cuts = 12,            ///< flying cutoff: synchronisations (cuts) so far
  last_cut = 13,        ///< flying cutoff: the material point of the last cut, IU
  length_counter = 14,  ///< argument: 1 material, 2 product (status 54)
};

constexpr std::size_t handle(ValueKind k, std::size_t argument) noexcept {
  return static_cast<std::size_t>(k) << 24 | argument;
}

constexpr std::string_view value_names =
    "V000..V999, I1.02 / Q1.02 / M2.00 (a byte), counter.NNNN (the COU/BAC on line NNNN), task1.line / "
    "task1.depth / task1.active (tasks 1..5), error, axis1.position / axis1.latched (axes 1..4), mode, run, "
    "cuts / cut.last (flying cutoff), length.material / length.product (status 54)";

std::optional<int> number(std::string_view s) {
  int v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || end != s.data() + s.size() || s.empty()) return std::nullopt;
  return v;
}

}  // namespace

std::expected<std::size_t, std::string> RuntimeController::resolve_value(std::string_view name) const {
  const auto bad = [&](std::string_view why) {
    return std::unexpected(fmt::format("'{}' is not a CLM1.4 value{}{} (the CLM shows: {})", name,
                                       why.empty() ? "" : ": ", why, value_names));
  };
  if (name.size() == 4 && name[0] == 'V') {
    if (const auto n = number(name.substr(1))) return handle(ValueKind::variable, static_cast<std::size_t>(*n));
    return bad("a variable is V and three digits");
  }
  if (const auto b = parse_byte(name))
    return handle(ValueKind::byte, static_cast<std::size_t>(b->area) << 16 | std::size_t{b->source} << 8 | b->byte);
  if (name.starts_with("counter.")) {
    const auto line = name.size() == 12 ? number(name.substr(8)) : std::nullopt;
    if (!line || *line >= clm14::Controller::program_lines)
      return bad("a counter is counter.NNNN, NNNN a program line");
    if (!model_.counter(*line)) return bad(fmt::format("line {:04d} of the program holds no COU or BAC", *line));
    return handle(ValueKind::counter, static_cast<std::size_t>(*line));
  }
  if (name.starts_with("task") && name.size() > 6 && name[5] == '.') {
    const auto t = number(name.substr(4, 1));
    const std::string_view what = name.substr(6);
    if (!t || *t < 1 || *t > 5) return bad("tasks are task1..task5");
    const auto tt = static_cast<std::size_t>(*t);
    if (what == "line") return handle(ValueKind::task_line, tt);
    if (what == "depth") return handle(ValueKind::task_depth, tt);
    if (what == "active") return handle(ValueKind::task_active, tt);
    return bad("a task shows .line, .depth and .active");
  }
  if (name.starts_with("axis") && name.size() > 6 && name[5] == '.') {
    const auto a = number(name.substr(4, 1));
    const std::string_view what = name.substr(6);
    if (!a || *a < 1 || *a > 4) return bad("axes are axis1..axis4");
    const auto specs = axis_specs();
    if (std::none_of(specs.begin(), specs.end(), [&](const auto& s) { return s.name == std::to_string(*a); }))
      return bad(fmt::format("the parameter file enables no axis {} (B000)", *a));
    const auto aa = static_cast<std::size_t>(*a);
    if (what == "position") return handle(ValueKind::axis_position, aa);
    if (what == "latched") return handle(ValueKind::axis_latched, aa);
    return bad("an axis shows .position and .latched");
  }
  if (name == "error") return handle(ValueKind::error, 0);
  if (name == "mode") return handle(ValueKind::mode, 0);
  if (name == "run") return handle(ValueKind::run, 0);
  if (name == "cuts") return handle(ValueKind::cuts, 0);
  if (name == "cut.last") return handle(ValueKind::last_cut, 0);
  if (name == "length.material") return handle(ValueKind::length_counter, 1);
  if (name == "length.product") return handle(ValueKind::length_counter, 2);
  return bad("");
}

double RuntimeController::value(std::size_t h) const noexcept {
  const auto kind = static_cast<ValueKind>(h >> 24);
  const std::size_t arg = h & 0xFFFFFF;
  const int i = static_cast<int>(arg);
  switch (kind) {
    case ValueKind::variable:
      return to_double(model_.variable(i));
    case ValueKind::byte:
      return model_.image().byte(ByteAddress{static_cast<Area>(arg >> 16), static_cast<std::uint8_t>((arg >> 8) & 0xFF),
                                             static_cast<std::uint8_t>(arg & 0xFF)});
    case ValueKind::counter: {
      const auto c = model_.counter(i);
      return c ? c->count : std::numeric_limits<double>::quiet_NaN();
    }
    case ValueKind::task_line:
      return model_.task(i).pc;
    case ValueKind::task_depth:
      return model_.task(i).depth;
    case ValueKind::task_active:
      return model_.task(i).active ? 1.0 : 0.0;
    case ValueKind::error:
      return model_.error();
    case ValueKind::axis_position:
      return model_.position(i);
    case ValueKind::axis_latched:
      return model_.latched_position(i);
    case ValueKind::mode:
      return static_cast<double>(model_.mode());
    case ValueKind::run:
      return static_cast<double>(model_.run_state());
    case ValueKind::cuts:
      return static_cast<double>(model_.cuts());
    case ValueKind::last_cut:
      return model_.last_cut_point();
    case ValueKind::length_counter:
      return model_.length_counter(i);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

std::expected<AnalogInputSpec, std::string> RuntimeController::resolve_analog(std::string_view name) const {
  if (name.size() == 3 && name.substr(0, 2) == "AE" && name[2] >= '1' && name[2] <= '4')
    return AnalogInputSpec{static_cast<std::size_t>(name[2] - '0'), -10.0, 10.0, "V"};
  return std::unexpected(fmt::format("'{}' is not a CLM1.4 analog input (AE1..AE4, volts)", name));
}

void RuntimeController::set_analog(std::size_t handle, double value) noexcept {
  model_.set_analog_input(static_cast<int>(handle), static_cast<int>(std::lround(value * 1000.0)));
}

}  // namespace hil::controllers::clm14
