// SPDX-License-Identifier: MIT
#include "hil/core/fault.hpp"

#include <cstdio>
#include <string>

#include "hil/core/config_error.hpp"
#include "hil/core/drive.hpp"
#include "hil/core/printable.hpp"

namespace hil {
namespace {

class MotionCategory final : public std::error_category {
 public:
  const char* name() const noexcept override { return "motion"; }
  std::string message(int v) const override {
    switch (static_cast<MotionFault>(v)) {
      case MotionFault::none:
        return "no fault";
      case MotionFault::following_error:
        return "following error outside the static window";
      case MotionFault::following_error_dynamic:
        return "following error outside the speed-dependent window";
      case MotionFault::standstill:
        return "axis left the standstill window";
      case MotionFault::in_position_timeout:
        return "target not reached inside the in-position window in time";
      case MotionFault::software_limit:
        return "software limit";
      case MotionFault::drive_fault:
        return "drive fault";
      case MotionFault::drive_lost:
        return "drive communication lost";
      case MotionFault::not_enabled:
        return "drive not enabled";
      case MotionFault::invalid_command:
        return "invalid command";
    }
    return "unknown motion fault " + std::to_string(v);
  }
};

class PlantCategory final : public std::error_category {
 public:
  const char* name() const noexcept override { return "plant"; }
  std::string message(int v) const override {
    switch (static_cast<PlantFault>(v)) {
      case PlantFault::none:
        return "no fault";
      case PlantFault::encoder:
        return "encoder fault";
      case PlantFault::not_ready:
        return "drive not ready";
      case PlantFault::following_blowup:
        return "plant does not follow its command";
    }
    return "unknown plant fault " + std::to_string(v);
  }
};

}  // namespace

const std::error_category& motion_category() noexcept {
  static const MotionCategory c;
  return c;
}
const std::error_category& plant_category() noexcept {
  static const PlantCategory c;
  return c;
}

std::string Fault::describe() const {
  if (!code) return "no fault";
  // Spec codes above a byte are hexadecimal in their specs (CiA 402 0x2310, SDO abort
  // 0x06020000, Modbus link errors 0x102); small ones (exception codes, error numbers) decimal.
  const auto v = static_cast<unsigned>(code.value());
  std::string s = std::string(code.category().name()) + ":";
  if (v < 0x100) {
    s += std::to_string(code.value());
  } else {
    char hex[16];
    std::snprintf(hex, sizeof hex, v <= 0xFFFF ? "0x%04X" : "0x%08X", v);
    s += hex;
  }
  if (!text.empty()) return s + " " + text;
  return s + " " + code.message();
}

std::string ConfigError::describe() const {
  std::string where = file.empty() ? std::string("<input>") : file;
  if (line > 0) where += ":" + std::to_string(line);
  if (column > 0) where += ":" + std::to_string(column);
  // The key and the message may quote the input: never raw binary on the terminal.
  if (!key.empty()) return printable(where + ": " + key + ": " + message);
  return printable(where + ": " + message);
}

std::string_view to_string(DriveState s) noexcept {
  switch (s) {
    case DriveState::not_ready:
      return "not_ready";
    case DriveState::switch_on_disabled:
      return "switch_on_disabled";
    case DriveState::ready_to_switch_on:
      return "ready_to_switch_on";
    case DriveState::switched_on:
      return "switched_on";
    case DriveState::operation_enabled:
      return "operation_enabled";
    case DriveState::quick_stop_active:
      return "quick_stop_active";
    case DriveState::fault_reaction_active:
      return "fault_reaction_active";
    case DriveState::fault:
      return "fault";
  }
  return "?";
}

std::string_view to_string(DriveRequest r) noexcept {
  switch (r) {
    case DriveRequest::enable:
      return "enable";
    case DriveRequest::disable:
      return "disable";
    case DriveRequest::quick_stop:
      return "quick_stop";
    case DriveRequest::fault_reset:
      return "fault_reset";
    case DriveRequest::home:
      return "home";
  }
  return "?";
}

}  // namespace hil
