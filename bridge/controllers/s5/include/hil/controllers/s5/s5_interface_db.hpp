// SPDX-License-Identifier: MIT
#pragma once
// An S5 module's interface data block (the DB axis of the WF 725/726, the axis DB of the IP247)
// as plain data words in the controller's I/O image: the PLC writes command words, the module
// writes status words, both through this view. DW w takes the image's data bytes base + 2w (DL,
// bits 15..8) and base + 2w + 1 (DR, bits 7..0), the S5 word order of io_address_s5.hpp, so a
// scenario's `io:` step can address the same bits as `DB10 D 2.0` and a PLC peer (RK512, the
// scenario's `plc:` steps) reads and writes whole words (read_word / write_word). Double words
// (DD) are DW w (high word) + DW w+1. Pure view, no I/O; an address beyond the block reads 0
// and writes nothing.
// Thread: the controller's cycle thread (or configuration time); allocation-free after construction.

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "hil/controllers/io_address_s5.hpp"
#include "hil/controllers/io_image.hpp"

namespace hil::controllers::s5 {

class S5InterfaceDb {
 public:
  S5InterfaceDb(IoImage& image, S5DataBlock block) : image_(&image), block_(block), seen_(block.words, 0) {}

  [[nodiscard]] const S5DataBlock& block() const noexcept { return block_; }
  [[nodiscard]] bool contains(std::uint16_t word) const noexcept { return word < block_.words; }

  [[nodiscard]] std::uint16_t read_word(std::uint16_t w) const noexcept {
    if (!contains(w)) return 0;
    return static_cast<std::uint16_t>((image_->get(left(w)) << 8) | image_->get(right(w)));
  }
  void write_word(std::uint16_t w, std::uint16_t v) noexcept {
    if (!contains(w)) return;
    image_->set(left(w), static_cast<std::uint8_t>(v >> 8));
    image_->set(right(w), static_cast<std::uint8_t>(v & 0xFF));
  }
  /// DW w as the module saw it at its last end_cycle(): edges of PLC command bits, whoever wrote
  /// them in between (an `io:` stimulus in read_inputs, or write_word from a PLC peer).
  [[nodiscard]] std::uint16_t previous_word(std::uint16_t w) const noexcept { return contains(w) ? seen_[w] : 0; }
  /// The module's cycle ends: the words now are the reference of the next edges.
  void end_cycle() noexcept {
    for (std::uint16_t w = 0; w < block_.words; ++w) seen_[w] = read_word(w);
  }
  /// D w.b, b = 0..15 (bit 0 = least significant of DR).
  [[nodiscard]] bool bit(std::uint16_t w, std::uint8_t b) const noexcept { return ((read_word(w) >> b) & 1U) != 0; }
  void set_bit(std::uint16_t w, std::uint8_t b, bool on) noexcept {
    if (contains(w)) image_->set(bit_address(w, b), on);
  }
  [[nodiscard]] bool rising(std::uint16_t w, std::uint8_t b) const noexcept {
    return bit(w, b) && ((previous_word(w) >> b) & 1U) == 0;
  }
  [[nodiscard]] bool falling(std::uint16_t w, std::uint8_t b) const noexcept {
    return !bit(w, b) && ((previous_word(w) >> b) & 1U) != 0;
  }
  [[nodiscard]] std::uint8_t dl(std::uint16_t w) const noexcept { return static_cast<std::uint8_t>(read_word(w) >> 8); }
  [[nodiscard]] std::uint8_t dr(std::uint16_t w) const noexcept {
    return static_cast<std::uint8_t>(read_word(w) & 0xFF);
  }
  void set_dl(std::uint16_t w, std::uint8_t v) noexcept {
    if (contains(w)) image_->set(left(w), v);
  }
  void set_dr(std::uint16_t w, std::uint8_t v) noexcept {
    if (contains(w)) image_->set(right(w), v);
  }
  /// DD w: DW w high word, DW w+1 low word, 32-bit two's complement.
  [[nodiscard]] std::int32_t read_dd(std::uint16_t w) const noexcept {
    const auto u = (static_cast<std::uint32_t>(read_word(w)) << 16) | read_word(static_cast<std::uint16_t>(w + 1));
    return static_cast<std::int32_t>(u);
  }
  void write_dd(std::uint16_t w, std::int32_t v) noexcept {
    const auto u = static_cast<std::uint32_t>(v);
    write_word(w, static_cast<std::uint16_t>(u >> 16));
    write_word(static_cast<std::uint16_t>(w + 1), static_cast<std::uint16_t>(u & 0xFFFF));
  }
  /// The image bit of D w.b (for naming signals).
  [[nodiscard]] BitAddress bit_address(std::uint16_t w, std::uint8_t b) const noexcept {
    return b >= 8 ? BitAddress{IoArea::data, block_.base + 2U * w, static_cast<std::uint8_t>(b - 8)}
                  : BitAddress{IoArea::data, block_.base + 2U * w + 1, b};
  }

 private:
  [[nodiscard]] ByteAddress left(std::uint16_t w) const noexcept { return {IoArea::data, block_.base + 2U * w}; }
  [[nodiscard]] ByteAddress right(std::uint16_t w) const noexcept { return {IoArea::data, block_.base + 2U * w + 1}; }

  IoImage* image_;
  S5DataBlock block_;
  std::vector<std::uint16_t> seen_;  ///< words at the last end_cycle()
};

/// A number as the manual writes it in a data word shown in KH (hex digits = decimal digits):
/// 123 -> 0x0123. Numbers 0..9999.
[[nodiscard]] constexpr std::uint16_t s5_bcd_word(int n) noexcept {
  std::uint16_t v = 0;
  for (int shift = 0; shift < 16 && n > 0; shift += 4, n /= 10) v = static_cast<std::uint16_t>(v | ((n % 10) << shift));
  return v;
}

}  // namespace hil::controllers::s5
