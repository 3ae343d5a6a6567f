// SPDX-License-Identifier: MIT
#pragma once
// CiA 301 static data types (§7.4.7, object indices 0x0001..0x001B) and access types.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace hil::canopen {

enum class DataType : std::uint16_t {
  boolean = 0x0001,
  integer8 = 0x0002,
  integer16 = 0x0003,
  integer32 = 0x0004,
  unsigned8 = 0x0005,
  unsigned16 = 0x0006,
  unsigned32 = 0x0007,
  real32 = 0x0008,
  visible_string = 0x0009,
  octet_string = 0x000A,
  unicode_string = 0x000B,
  time_of_day = 0x000C,
  time_difference = 0x000D,
  domain = 0x000F,
  integer24 = 0x0010,
  real64 = 0x0011,
  integer40 = 0x0012,
  integer48 = 0x0013,
  integer56 = 0x0014,
  integer64 = 0x0015,
  unsigned24 = 0x0016,
  unsigned40 = 0x0018,
  unsigned48 = 0x0019,
  unsigned56 = 0x001A,
  unsigned64 = 0x001B,
};

/// Known data type code (EDS `DataType=`), nullopt otherwise.
[[nodiscard]] std::optional<DataType> data_type_from_code(std::uint32_t code) noexcept;
/// Size in bytes of a fixed-size type; 0 for strings and domains (variable length).
[[nodiscard]] std::size_t data_type_size(DataType t) noexcept;
[[nodiscard]] bool is_signed(DataType t) noexcept;
[[nodiscard]] bool is_integer(DataType t) noexcept;  ///< boolean, integerN, unsignedN
[[nodiscard]] bool is_variable_length(DataType t) noexcept;
[[nodiscard]] std::string_view to_string(DataType t) noexcept;

/// EDS AccessType (CiA 306 §4.6.3): rw, wo, ro, const, rwr (rw, mapped to TPDO), rww (rw, RPDO).
enum class Access : std::uint8_t { ro, wo, rw, rwr, rww, const_ };
[[nodiscard]] std::optional<Access> access_from_string(std::string_view s) noexcept;  ///< case-insensitive
[[nodiscard]] std::string_view to_string(Access a) noexcept;
[[nodiscard]] constexpr bool readable(Access a) noexcept {
  return a != Access::wo;
}
[[nodiscard]] constexpr bool writable(Access a) noexcept {
  return a == Access::wo || a == Access::rw || a == Access::rwr || a == Access::rww;
}

}  // namespace hil::canopen
