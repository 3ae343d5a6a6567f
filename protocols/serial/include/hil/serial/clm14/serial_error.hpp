// SPDX-License-Identifier: MIT
#pragma once
// CLM1.4 serial transmission errors (status 01, manual §9.2; digest clm14.md §2.9). The enum
// values are the device's error numbers. The 20-character texts the device sends belong to the
// device profile (profiles/devices/clm14.yaml), not to this code.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

namespace hil::serial::clm14 {

enum class SerialError : std::uint8_t {
  block_number_wrong = 1,  ///< instruction number not decimal
  format_error = 2,        ///< data format wrong
  block_data_error = 3,    ///< instruction data wrong
  checksum_error = 4,      ///< checksum wrong
  invalid_mode = 5,        ///< parameter write outside Parameter mode
  wrong_param_number = 6,  ///< parameter number not decimal
  param_number_too_large = 7,
  wrong_status_number = 8,
  status_illegal = 9,
  mwheel_param_error = 10,
  invalid_param_block = 11,
  block_number_too_large = 12,
  invalid_program_command = 13,
  value_too_large = 16,
  not_accepted = 18,
  wrong_variable_number = 23,
  invalid_operand = 25,
};

[[nodiscard]] const std::error_category& serial_error_category() noexcept;
[[nodiscard]] inline std::error_code make_error_code(SerialError e) noexcept {
  return {static_cast<int>(e), serial_error_category()};
}

/// The status-01 error telegram body: "01 ff <text, padded/cut to 20> ".
[[nodiscard]] std::string make_error_body(int code, std::string_view text20);

struct ErrorReport {
  int code = 0;
  std::string text;  ///< trailing padding removed
};
/// Parse the body of an X telegram if it is a status-01 error report.
[[nodiscard]] std::optional<ErrorReport> parse_error_body(std::string_view body);

}  // namespace hil::serial::clm14

template <>
struct std::is_error_code_enum<hil::serial::clm14::SerialError> : std::true_type {};
