// SPDX-License-Identifier: MIT
#pragma once
// CLM1.4 I/O and marker addresses (manual §9.1, §5.6; profiles/devices/clm14/io.yaml):
// `Ix.yy.z` inputs, `Qx.yy.z` outputs, `Mx.yy.z` markers. x = group (0 system I/O and system
// markers, 1 user I/O, 2 fieldbus image, 3..6 further marker groups), yy = byte in the group
// (two digits), z = bit 0..7. The CLM's "00.00.0" (no address, "unused") is not an address:
// parse_clm_address rejects it; callers test is_clm_unused() first.
//
// On the I/O image each group takes `clm_group_stride` bytes: byte = x * 64 + yy, so every CLM
// address has exactly one image bit and the mapping is invertible. Pure functions, no I/O.

#include <cstdint>
#include <expected>
#include <optional>
#include <string>
#include <string_view>

#include "hil/controllers/io_image.hpp"

namespace hil::controllers {

inline constexpr std::uint32_t clm_group_stride = 64;  ///< image bytes per CLM group
inline constexpr std::uint8_t clm_max_group = 9;

struct ClmAddress {
  char type = 'I';         ///< 'I' input, 'Q' output, 'M' marker
  std::uint8_t group = 0;  ///< x: 0..9
  std::uint8_t byte = 0;   ///< yy: 0..63
  std::uint8_t bit = 0;    ///< z: 0..7
  friend bool operator==(const ClmAddress&, const ClmAddress&) = default;
};

/// "I0.00.1", "Q1.02.7", "M2.03.4" (upper or lower case letter). Errors say what is wrong
/// ("'I0.0.1': byte needs two digits (yy), e.g. I0.00.1").
[[nodiscard]] std::expected<ClmAddress, std::string> parse_clm_address(std::string_view text);
/// True for the CLM's "no address" forms "00.00.0" and "0.00.0" (a parameter that names no I/O).
[[nodiscard]] bool is_clm_unused(std::string_view text) noexcept;
/// "I0.00.1".
[[nodiscard]] std::string format_clm_address(const ClmAddress& a);

/// Image bit of a CLM address: area from the letter, byte = group * clm_group_stride + yy.
[[nodiscard]] constexpr BitAddress to_bit_address(const ClmAddress& a) noexcept {
  const IoArea area = a.type == 'Q' ? IoArea::output : a.type == 'M' ? IoArea::marker : IoArea::input;
  return {area, static_cast<std::uint32_t>(a.group) * clm_group_stride + a.byte, a.bit};
}
/// The CLM address of an image bit; empty for the data area or a byte beyond group 9.
[[nodiscard]] std::optional<ClmAddress> to_clm_address(BitAddress a) noexcept;

/// Image layout holding CLM groups 0..`groups`-1 in every area (`groups` * 64 bytes each).
[[nodiscard]] constexpr IoLayout clm_io_layout(std::uint32_t input_groups, std::uint32_t output_groups,
                                               std::uint32_t marker_groups) noexcept {
  return IoLayout{
      {input_groups * clm_group_stride, output_groups * clm_group_stride, marker_groups * clm_group_stride, 0}};
}

}  // namespace hil::controllers
