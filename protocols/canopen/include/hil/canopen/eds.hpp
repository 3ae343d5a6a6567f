// SPDX-License-Identifier: MIT
#pragma once
// EDS / DCF parser (CiA 306-1 v1.3): builds an ObjectDictionary from an electronic data sheet.
// Supports VAR / ARRAY / RECORD objects, sub-object sections ([1018sub1]), CompactSubObj with
// [xxxxName] / [xxxxValue] sections, `$NODEID` expressions ("$NODEID+0x180", "0x580+$NODEID"),
// decimal / hex / octal literals, LowLimit / HighLimit, PDOMapping, AccessType, DCF
// ParameterValue (which overrides DefaultValue and is collected for configuration download) and
// [DeviceComissioning] NodeID.
// Lenient like python-canopen and the CANopen editors, and loud about it: keys in any case,
// inline `;` comments, duplicate sections/keys, objects outside the object lists, wrong
// SupportedObjects / SubNumber counts, missing optional keys (ParameterName, AccessType,
// PDOMapping, sub-index 0), unknown sections, unknown data or object types (the object is
// skipped) are each a warning with file, line and key. Errors (the file is rejected) only for
// what cannot be understood: a malformed line, a key outside a section, a DCF ParameterValue
// that does not parse or fit (it would be written to the device), a DefaultValue that does not
// fit its type, and a file without any object. Errors name the file, the line, section and key.
// Pure: text in, description or error out; load_eds() reads the file first.

#include <cstdint>
#include <expected>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hil/canopen/cob_id.hpp"
#include "hil/canopen/object_dictionary.hpp"
#include "hil/core/config_error.hpp"

namespace hil::canopen {

struct DeviceInfo {
  std::string vendor_name;
  std::uint32_t vendor_number = 0;
  std::string product_name;
  std::uint32_t product_number = 0;
  std::uint32_t revision_number = 0;
  std::string order_code;
  std::optional<int> granularity;  ///< [DeviceInfo] Granularity: 0 = PDO mapping cannot be changed
  std::optional<int> nr_of_rxpdo;  ///< [DeviceInfo] NrOfRXPDO
  std::optional<int> nr_of_txpdo;  ///< [DeviceInfo] NrOfTXPDO
};

/// A value to write into the device during boot-up (DCF ParameterValue).
struct ParameterValue {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  std::vector<std::uint8_t> bytes;
};

struct DeviceDescription {
  std::string file;
  DeviceInfo info;
  ObjectDictionary od;
  std::vector<ParameterValue> parameter_values;  ///< in OD order
  std::optional<NodeId> dcf_node_id;             ///< [DeviceComissioning] NodeID
  /// Oddities the parser accepted, in file order: file, line, "[section] Key", what and what it did.
  std::vector<ConfigError> warnings;
  /// True when the file has ParameterValue entries or a [DeviceComissioning] section (a DCF).
  bool is_dcf = false;
};

/// Parse EDS/DCF text. `node_id` replaces $NODEID (a DCF's own NodeID wins when `node_id` is 0).
/// ConfigError::key is "[section] Key".
[[nodiscard]] std::expected<DeviceDescription, ConfigError> parse_eds(std::string_view text, std::string_view file_name,
                                                                      NodeId node_id);
[[nodiscard]] std::expected<DeviceDescription, ConfigError> load_eds(const std::filesystem::path& path, NodeId node_id);

/// Evaluate an EDS integer expression: literals (decimal, 0x hex, leading-0 octal, optional
/// sign) joined by + or -, and $NODEID. nullopt when malformed.
[[nodiscard]] std::optional<std::int64_t> eval_eds_integer(std::string_view text, NodeId node_id) noexcept;

}  // namespace hil::canopen
