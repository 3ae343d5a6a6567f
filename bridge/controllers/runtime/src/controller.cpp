// SPDX-License-Identifier: MIT
#include "hil/controllers/controller.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace hil::controllers {
namespace {

class ControllerCategory final : public std::error_category {
 public:
  const char* name() const noexcept override { return "controller"; }
  std::string message(int v) const override {
    switch (static_cast<ControllerFault>(v)) {
      case ControllerFault::none:
        return "no fault";
      case ControllerFault::hard_limit_negative:
        return "negative limit switch reached";
      case ControllerFault::hard_limit_positive:
        return "positive limit switch reached";
    }
    return fmt::format("unknown controller fault {}", v);
  }
};

}  // namespace

const std::error_category& controller_category() noexcept {
  static const ControllerCategory c;
  return c;
}

Controller::Controller(std::shared_ptr<const profiles::Profile> profile, profiles::ParameterSet parameters,
                       IoLayout layout, Duration cycle)
    : profile_(std::move(profile)), parameters_(std::move(parameters)), cycle_(cycle), io_(layout) {}

Controller::~Controller() = default;

void Controller::add_axis(ControllerAxis axis) {
  specs_.push_back(std::move(axis));
}

std::expected<void, std::string> Controller::bind_axes(std::span<motion::Axis* const> axes) {
  if (axes.size() != specs_.size()) {
    return std::unexpected(
        fmt::format("{} controller declares {} axes, {} were bound", device(), specs_.size(), axes.size()));
  }
  for (std::size_t i = 0; i < axes.size(); ++i) {
    if (axes[i] == nullptr) return std::unexpected(fmt::format("{} controller: axis {} is null", device(), i));
  }
  axes_.assign(axes.begin(), axes.end());
  seen_fault_.assign(axes_.size(), {});
  limit_hit_.assign(axes_.size(), 0);
  return check_axes();
}

std::expected<BitAddress, std::string> Controller::resolve_bit(std::string_view text) const {
  if (auto a = io_.find_bit(text)) return *a;
  return std::unexpected(fmt::format("'{}' is not an I/O name of the {} controller", text, device()));
}

std::expected<std::size_t, std::string> Controller::resolve_value(std::string_view name) const {
  const auto names = trace_signals();
  std::string list;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return i;
    list += (list.empty() ? "" : ", ") + names[i];
  }
  if (list.empty()) return std::unexpected(fmt::format("the {} controller shows no values by name", device()));
  return std::unexpected(fmt::format("'{}' is not a value of the {} controller (it shows: {})", name, device(), list));
}

std::expected<AnalogInputSpec, std::string> Controller::resolve_analog(std::string_view name) const {
  return std::unexpected(fmt::format("'{}': the {} controller has no analog inputs", name, device()));
}

bool Controller::power_up_axes() noexcept {
  if (!axes_enabled_) {
    for (motion::Axis* a : axes_) (void)a->enable();
    axes_enabled_ = true;
  }
  return std::all_of(axes_.begin(), axes_.end(), [](const motion::Axis* a) {
    const auto s = a->status().state;
    return s != motion::AxisState::disabled && s != motion::AxisState::enabling;
  });
}

const profiles::ErrorCatalogue* Controller::catalogue(std::string_view id) const noexcept {
  return profile_->catalogue(id);
}

ControllerStatus Controller::step(const CycleTime& cycle) noexcept {
  io_.read_inputs(cycle.now);
  supervise_axes(cycle.now);
  on_cycle(cycle);
  io_.write_outputs(cycle.now);
  return errors_.blocks_motion() ? ControllerStatus::error : ControllerStatus::ok;
}

void Controller::supervise_axes(TimePoint now) noexcept {
  for (std::size_t i = 0; i < axes_.size(); ++i) {
    auto& ax = *axes_[i];
    const auto& spec = specs_[i];
    const auto& st = ax.status();
    // Hard-limit switches: an active switch stops an axis that moves onto it (quick stop), once
    // per activation; moving away from it is allowed.
    const auto& ls = spec.limit_switches;
    const auto active = [&](const std::optional<BitAddress>& a) { return a && (io_.get(*a) != ls.normally_closed); };
    const bool neg = active(ls.negative);
    const bool pos = active(ls.positive);
    const bool moving = st.state == motion::AxisState::moving;
    for (const int side : {-1, +1}) {
      const bool on = side < 0 ? neg : pos;
      const std::uint8_t bit = side < 0 ? 1 : 2;
      if (!on) {
        limit_hit_[i] = static_cast<std::uint8_t>(limit_hit_[i] & ~bit);
        continue;
      }
      const bool toward = side < 0 ? st.command_velocity < 0.0 : st.command_velocity > 0.0;
      if (!moving || !toward) continue;
      (void)ax.quick_stop();
      if ((limit_hit_[i] & bit) != 0) continue;
      limit_hit_[i] = static_cast<std::uint8_t>(limit_hit_[i] | bit);
      hil::Fault f{
          make_error_code(side < 0 ? ControllerFault::hard_limit_negative : ControllerFault::hard_limit_positive),
          fmt::format("axis '{}': {} limit switch active at {:.6g}", spec.name, side < 0 ? "negative" : "positive",
                      st.position)};
      if (const auto code = map_axis_fault(i, f, st); code && code->catalogue != nullptr) {
        auto e = make_device_error(*code->catalogue, code->code, now, static_cast<int>(i), "axis " + spec.name);
        e.cause = f.code;
        if (errors_.raise(e)) apply_reaction(e);
      }
    }
    // Supervision faults of the motion core, once per fault.
    if (st.state != motion::AxisState::error) {
      seen_fault_[i] = {};
      continue;
    }
    if (!st.fault.code || st.fault.code == seen_fault_[i]) continue;
    seen_fault_[i] = st.fault.code;
    if (const auto code = map_axis_fault(i, st.fault, st); code && code->catalogue != nullptr) {
      auto e = make_device_error(*code->catalogue, code->code, now, static_cast<int>(i), "axis " + spec.name);
      e.cause = st.fault.code;
      if (errors_.raise(e)) apply_reaction(e);
    }
  }
}

void Controller::apply_reaction(const DeviceError& e) noexcept {
  const auto react = [&](motion::Axis& ax) {
    switch (e.reaction) {
      case profiles::Reaction::message:
        break;
      case profiles::Reaction::stop:
        // A stop under the normal limits, unless a (quick) stop already runs.
        if (ax.status().state == motion::AxisState::moving) (void)ax.stop();
        break;
      case profiles::Reaction::drive_off:
      case profiles::Reaction::needs_reset:
        (void)ax.disable();
        break;
    }
  };
  if (e.axis >= 0 && static_cast<std::size_t>(e.axis) < axes_.size()) {
    react(*axes_[static_cast<std::size_t>(e.axis)]);
  } else {
    for (auto* ax : axes_) react(*ax);
  }
}

void Controller::raise(const profiles::ErrorCatalogue& catalogue, int code, TimePoint now, int axis,
                       std::string_view context, std::optional<AckRule> ack, bool react) noexcept {
  auto e = make_device_error(catalogue, code, now, axis, context, ack);
  if (errors_.raise(e) && react) apply_reaction(e);
}

namespace {
std::expected<std::uint32_t, std::string> data_word_byte(std::span<const S5DataBlock> blocks, std::string_view device,
                                                         int db, int dw) {
  for (const auto& b : blocks) {
    if (b.number != db) continue;
    if (dw < 0 || dw >= b.words)
      return std::unexpected(fmt::format("DB{} of the {} controller has data words 0..{}; DW {} is beyond it", db,
                                         device, b.words - 1, dw));
    return b.base + 2U * static_cast<std::uint32_t>(dw);
  }
  std::string list;
  for (const auto& b : blocks) list += fmt::format("{}DB{}", list.empty() ? "" : ", ", b.number);
  return std::unexpected(fmt::format("the {} controller has no data block DB{} ({})", device, db,
                                     list.empty() ? "it has no PLC data blocks" : "it has " + list));
}
}  // namespace

std::expected<std::uint16_t, std::string> Controller::read_data_word(int db, int dw) const {
  const auto at = data_word_byte(data_blocks(), device(), db, dw);
  if (!at) return std::unexpected(at.error());
  return static_cast<std::uint16_t>((io_.get(ByteAddress{IoArea::data, *at}) << 8) |
                                    io_.get(ByteAddress{IoArea::data, *at + 1}));
}

std::expected<void, std::string> Controller::write_data_word(int db, int dw, std::uint16_t value) {
  const auto at = data_word_byte(data_blocks(), device(), db, dw);
  if (!at) return std::unexpected(at.error());
  io_.set(ByteAddress{IoArea::data, *at}, static_cast<std::uint8_t>(value >> 8));
  io_.set(ByteAddress{IoArea::data, *at + 1}, static_cast<std::uint8_t>(value & 0xFF));
  return {};
}

std::size_t Controller::acknowledge(Acknowledgement how) noexcept {
  const auto n = errors_.acknowledge(how);
  for (std::size_t i = 0; i < axes_.size(); ++i) {
    if (axes_[i]->status().state == motion::AxisState::error && !errors_.blocks_motion(static_cast<int>(i))) {
      (void)axes_[i]->reset();
    }
  }
  return n;
}

}  // namespace hil::controllers
