// SPDX-License-Identifier: MIT
#pragma once
// What the CLM1.4 client and emulator need from the device profile: the parameter list with
// defaults and validation, the program command set and the serial error texts. The profile
// (profiles/devices/clm14.yaml through hil::profiles) is the single source of this data;
// make_profile_device_data() adapts it, nothing here repeats it.

#include <expected>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace hil::serial::clm14 {

/// Why a field was rejected, with the device's serial error number for it.
struct FieldRejection {
  int serial_error = 3;  ///< CLM serial error the device answers with (03 block data, 16 value too large, ...)
  std::string message;   ///< which field, what was wrong, what is allowed
};

class DeviceData {
 public:
  virtual ~DeviceData() = default;
  /// Every parameter number in transfer order: B000..B019, then A100..A142 for each axis 1..axes
  /// (axis x uses Ax00..Ax42), then C000..C008.
  [[nodiscard]] virtual std::vector<std::string> parameter_numbers(int axes) const = 0;
  /// Default data text of a parameter as the device sends it ("019200 0 1 8 1"), or "" if unknown.
  [[nodiscard]] virtual std::string parameter_default(std::string_view number) const = 0;
  /// Check a parameter's data text against the profile's fields and ranges; returns the
  /// canonical text (exact field widths) on success.
  [[nodiscard]] virtual std::expected<std::string, FieldRejection> check_parameter(std::string_view number,
                                                                                   std::string_view data) const = 0;
  /// Check a program line "MNE data" (mnemonic and operands); canonical text on success.
  [[nodiscard]] virtual std::expected<std::string, FieldRejection> check_program_line(std::string_view line) const = 0;
  /// The device's 20-character text for serial error `code` (status 01).
  [[nodiscard]] virtual std::string serial_error_text(int code) const = 0;
  /// The device's text for fault (B018 / status 53) code `code` (hex code, e.g. 0x02).
  [[nodiscard]] virtual std::string fault_text(int code) const = 0;
  /// Hardware + firmware identification for status 19 / 05.
  [[nodiscard]] virtual std::string identification() const = 0;
};

/// Load the CLM1.4 profile (profiles/devices/clm14.yaml, or `path` if not empty).
[[nodiscard]] std::expected<std::shared_ptr<const DeviceData>, std::string> load_device_data(
    const std::string& path = {});

}  // namespace hil::serial::clm14
