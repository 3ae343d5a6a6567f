// SPDX-License-Identifier: MIT
#pragma once
// The switches of a simulated axis: a negative and a positive limit switch and a home (reference)
// cam at fixed mechanical positions, reported as CiA 402 0x60FD bits (hil::digital_input), plus
// bits a test or a scenario forces directly. Used by every plant-backed drive that reports digital
// inputs (the `sim` transport, the simulated CiA 402 node). Pure: the caller passes the position.
//
// Positions are plant increments of the mechanical position (Plant::position_inc(), the reading
// before any homing re-reference): a switch is part of the machine, not of the encoder.
//   negative limit  active at position <= negative
//   positive limit  active at position >= positive
//   home switch     active at home[0] <= position <= home[1]

#include <cstdint>
#include <expected>
#include <optional>

#include <yaml-cpp/yaml.h>

#include "hil/config/yaml_config.hpp"
#include "hil/core/config_error.hpp"

namespace hil::mocks {

struct HomeCam {
  double from_inc = 0.0;
  double to_inc = 0.0;  ///< >= from_inc
};

struct PlantSwitches {
  std::optional<double> negative_inc;
  std::optional<double> positive_inc;
  std::optional<HomeCam> home;

  /// 0x60FD bits 0..2 at mechanical `position_inc`.
  [[nodiscard]] std::uint32_t inputs(double position_inc) const noexcept;
  [[nodiscard]] bool any() const noexcept { return negative_inc || positive_inc || home; }
};

/// The digital inputs of a simulated drive: switch bits from the position, overridden bit by bit
/// where forced. Thread: the simulation's (the motion thread for `sim`, the channel's for a node).
class SimulatedInputs {
 public:
  explicit SimulatedInputs(PlantSwitches switches = {}) : switches_(switches) {}
  /// Force the bits of `mask` to those of `value` (a test's or a scenario's own input bits).
  void force(std::uint32_t mask, std::uint32_t value) noexcept {
    forced_mask_ |= mask;
    forced_value_ = (forced_value_ & ~mask) | (value & mask);
  }
  /// The bits of `mask` follow the switches again.
  void release(std::uint32_t mask) noexcept { forced_mask_ &= ~mask; }
  [[nodiscard]] std::uint32_t inputs(double position_inc) const noexcept {
    return (switches_.inputs(position_inc) & ~forced_mask_) | (forced_value_ & forced_mask_);
  }
  [[nodiscard]] const PlantSwitches& switches() const noexcept { return switches_; }

 private:
  PlantSwitches switches_;
  std::uint32_t forced_mask_ = 0;
  std::uint32_t forced_value_ = 0;
};

/// Parse a drive block's `switches:` map, `{negative: -500, positive: 9500, home: [1000, 1200]}`
/// (every key optional; increments). `node` is the map, `where` its key path (`...drive.switches`).
/// Errors: unknown keys, non-numbers, values outside +-1e15, a home cam that is not two ascending
/// numbers, negative >= positive.
[[nodiscard]] std::expected<PlantSwitches, ConfigError> parse_switches(const YAML::Node& node,
                                                                       const yaml::Where& where);

}  // namespace hil::mocks
