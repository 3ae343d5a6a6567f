// SPDX-License-Identifier: MIT
#pragma once
// SIMATIC S5 operand addresses as the IP247 and WF 725/726 manuals write them (German
// mnemonics): bits `E 4.1` (input), `A 5.0` (output), `M 10.3` (marker); bytes `EB 4`, `AB 5`,
// `MB 10`; data-block bits `D 2.0` (data word 2, bit 0..15) and bytes `DL 2` / `DR 2` (left =
// high byte, right = low byte of DW 2), each optionally prefixed by the block: `DB10 D 2.0`.
// Spaces between mnemonic and number are optional ("E4.1" = "E 4.1"); case is ignored.
//
// On the I/O image: E/A/M byte n is byte n of the input/output/marker area; a data block lies
// in the `data` area at the base byte an S5DataBlock gives it, DW w taking bytes base + 2w (DL,
// bits 15..8) and base + 2w + 1 (DR, bits 7..0), the S5's big-endian word order. Pure, no I/O.

#include <cstdint>
#include <expected>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "hil/controllers/io_image.hpp"

namespace hil::controllers {

enum class S5Operand : std::uint8_t {
  input_bit,        ///< E n.b
  output_bit,       ///< A n.b
  marker_bit,       ///< M n.b
  input_byte,       ///< EB n
  output_byte,      ///< AB n
  marker_byte,      ///< MB n
  data_bit,         ///< D w.b (b = 0..15)
  data_left_byte,   ///< DL w
  data_right_byte,  ///< DR w
};

struct S5Address {
  S5Operand operand = S5Operand::input_bit;
  std::uint16_t db = 0;     ///< data block number (data operands only); 0 = none given
  std::uint16_t index = 0;  ///< byte number (E/A/M: 0..255) or data word number (0..255)
  std::uint8_t bit = 0;     ///< 0..7 (E/A/M) or 0..15 (D)
  friend bool operator==(const S5Address&, const S5Address&) = default;
  [[nodiscard]] bool is_bit() const noexcept {
    return operand == S5Operand::input_bit || operand == S5Operand::output_bit || operand == S5Operand::marker_bit ||
           operand == S5Operand::data_bit;
  }
};

/// Parses "E 4.1", "a5.0", "MB 10", "DB10 D 2.0", "DR 3". A data operand without "DB n" takes
/// `default_db` (error when none). Errors name the text and the rule broken.
[[nodiscard]] std::expected<S5Address, std::string> parse_s5_address(std::string_view text,
                                                                     std::optional<std::uint16_t> default_db = {});
/// "E 4.1", "MB 10", "DB10 D 2.0" (the DB prefix whenever db != 0).
[[nodiscard]] std::string format_s5_address(const S5Address& a);

/// Where one data block lies in the image's data area.
struct S5DataBlock {
  std::uint16_t number = 0;   ///< DB number
  std::uint32_t base = 0;     ///< first byte in the data area (DL of DW 0)
  std::uint16_t words = 256;  ///< data words DW 0..words-1
};

/// Image bit of a bit operand; errors for byte operands, an unknown DB or a word beyond it.
[[nodiscard]] std::expected<BitAddress, std::string> to_bit_address(const S5Address& a,
                                                                    std::span<const S5DataBlock> blocks = {});
/// Image byte of a byte operand (EB/AB/MB/DL/DR).
[[nodiscard]] std::expected<ByteAddress, std::string> to_byte_address(const S5Address& a,
                                                                      std::span<const S5DataBlock> blocks = {});

}  // namespace hil::controllers
