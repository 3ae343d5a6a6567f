// SPDX-License-Identifier: MIT
#pragma once
// SDO abort codes (CiA 301 §7.2.4.3.17, table 22). The enum values ARE the wire codes, so
// `std::error_code(SdoAbort::...)`.value() is what goes into bytes 4..7 of an abort frame.

#include <cstdint>
#include <string_view>
#include <system_error>

namespace hil::canopen {

enum class SdoAbort : std::uint32_t {
  none = 0,
  toggle_bit = 0x05030000,         ///< toggle bit not alternated
  timeout = 0x05040000,            ///< SDO protocol timed out
  command_specifier = 0x05040001,  ///< client/server command specifier not valid or unknown
  block_size = 0x05040002,         ///< invalid block size (block mode only)
  sequence_number = 0x05040003,    ///< invalid sequence number (block mode only)
  crc = 0x05040004,                ///< CRC error (block mode only)
  out_of_memory = 0x05040005,
  unsupported_access = 0x06010000,
  write_only = 0x06010001,    ///< attempt to read a write-only object
  read_only = 0x06010002,     ///< attempt to write a read-only object
  no_object = 0x06020000,     ///< object does not exist in the object dictionary
  not_mappable = 0x06040041,  ///< object cannot be mapped to the PDO
  pdo_length = 0x06040042,    ///< number and length of mapped objects exceed PDO length
  parameter_incompatible = 0x06040043,
  internal_incompatible = 0x06040047,
  hardware = 0x06060000,
  type_mismatch = 0x06070010,  ///< data type does not match, length of service parameter does not match
  length_too_high = 0x06070012,
  length_too_low = 0x06070013,
  no_sub_index = 0x06090011,
  invalid_value = 0x06090030,
  value_too_high = 0x06090031,
  value_too_low = 0x06090032,
  max_less_than_min = 0x06090036,
  resource_unavailable = 0x060A0023,
  general = 0x08000000,
  data_transfer = 0x08000020,
  data_transfer_local = 0x08000021,
  data_transfer_state = 0x08000022,
  no_od = 0x08000023,
  no_data = 0x08000024,
};

/// Spec text of a code ("Toggle bit not alternated"); "Unknown SDO abort code" otherwise.
[[nodiscard]] std::string_view describe(SdoAbort a) noexcept;
/// True when `code` is one of the CiA 301 abort codes above.
[[nodiscard]] bool is_known_abort_code(std::uint32_t code) noexcept;

/// Category "canopen.sdo"; message() is "0x06090011 Sub-index does not exist".
const std::error_category& sdo_category() noexcept;
inline std::error_code make_error_code(SdoAbort a) noexcept {
  return {static_cast<int>(static_cast<std::uint32_t>(a)), sdo_category()};
}

}  // namespace hil::canopen

template <>
struct std::is_error_code_enum<hil::canopen::SdoAbort> : std::true_type {};
