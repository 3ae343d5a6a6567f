// SPDX-License-Identifier: MIT
#pragma once
// can-utils text forms (pure): the cansend frame spec `123#DEADBEEF` and the candump log line
// `(1700000000.123456) can0 123#DEADBEEF` written by `candump -l` and read by `canplayer`.
//
// Frame spec (can-utils lib.c): 3 hex digits = 11-bit id, 8 hex digits = 29-bit id; an 8-digit id
// with CAN_ERR_FLAG (0x20000000) set is an error frame; `#R` (optionally followed by a DLC digit
// 0..8) is a remote frame; data are up to 8 hex bytes, optionally separated by '.'. CAN FD (`##`)
// and the len8_dlc form (`_`) are refused with a clear error: this layer carries classic CAN.

#include <cstdint>
#include <expected>
#include <string>
#include <string_view>
#include <system_error>

#include "hil/can/frame.hpp"
#include "hil/can/socketcand.hpp"  // Timestamp

namespace hil::can::candump {

enum class ParseErrc {
  missing_separator = 1,  ///< no '#'
  bad_id,                 ///< not 3 or 8 hex digits / out of range
  bad_data,               ///< odd number of hex digits, non-hex, or more than 8 bytes
  bad_rtr_length,         ///< `#R` followed by something other than one digit 0..8
  fd_not_supported,       ///< `##` CAN FD frame
  bad_timestamp,          ///< log line: not `(SECONDS.FRACTION)`
  bad_interface,          ///< log line: missing or overlong interface name
  trailing_garbage,
};
[[nodiscard]] const std::error_category& parse_category() noexcept;
[[nodiscard]] inline std::error_code make_error_code(ParseErrc e) noexcept {
  return {static_cast<int>(e), parse_category()};
}

struct LogRecord {
  socketcand::Timestamp time;
  std::string interface;
  Frame frame;
  friend bool operator==(const LogRecord&, const LogRecord&) = default;
};

/// `123#DEADBEEF` -> Frame.
[[nodiscard]] std::expected<Frame, std::error_code> parse_frame_spec(std::string_view spec) noexcept;
/// Frame -> `123#DEADBEEF` (appended). Error frames as `2000xxxx#...` with all 8 data bytes.
void format_frame_spec(std::string& out, const Frame& frame);
[[nodiscard]] std::string format_frame_spec(const Frame& frame);

/// One log line (a trailing '\n'/'\r' is ignored; candump -x's direction flag T/R is accepted).
[[nodiscard]] std::expected<LogRecord, std::error_code> parse_log_line(std::string_view line) noexcept;
/// `(sec.usec) iface spec` without a newline (appended).
void format_log_line(std::string& out, const LogRecord& record);

}  // namespace hil::can::candump

template <>
struct std::is_error_code_enum<hil::can::candump::ParseErrc> : std::true_type {};
