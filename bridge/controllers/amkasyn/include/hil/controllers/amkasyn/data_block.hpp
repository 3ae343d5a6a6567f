// SPDX-License-Identifier: MIT
#pragma once
// An AMKASYN PS data block: 16-bit data words DW0..DWn. DD n = (DW n+1 << 16) | DW n (low word
// first, Intel order); within a word DL = high byte, DR = low byte (manual §2.1, digest §1.9).

#include <cstddef>
#include <cstdint>
#include <vector>

namespace hil::controllers::amkasyn {

class DataBlock {
 public:
  explicit DataBlock(std::size_t words = 34) : w_(words, 0) {}

  [[nodiscard]] std::size_t size() const noexcept { return w_.size(); }
  /// Unsigned word; 0 beyond the end (an unused field reads 0, as in the manual's examples).
  [[nodiscard]] std::uint16_t uw(std::size_t n) const noexcept { return n < w_.size() ? w_[n] : 0; }
  [[nodiscard]] std::int16_t dw(std::size_t n) const noexcept { return static_cast<std::int16_t>(uw(n)); }
  [[nodiscard]] std::uint8_t dr(std::size_t n) const noexcept { return static_cast<std::uint8_t>(uw(n) & 0xFF); }
  [[nodiscard]] std::uint8_t dl(std::size_t n) const noexcept { return static_cast<std::uint8_t>(uw(n) >> 8); }
  [[nodiscard]] std::int32_t dd(std::size_t n) const noexcept {
    return static_cast<std::int32_t>((static_cast<std::uint32_t>(uw(n + 1)) << 16) | uw(n));
  }

  /// Setters grow the block as needed.
  DataBlock& set_dw(std::size_t n, std::int32_t v) {
    grow(n + 1);
    w_[n] = static_cast<std::uint16_t>(v);
    return *this;
  }
  DataBlock& set_dr(std::size_t n, std::uint8_t v) {
    grow(n + 1);
    w_[n] = static_cast<std::uint16_t>((w_[n] & 0xFF00u) | v);
    return *this;
  }
  DataBlock& set_dl(std::size_t n, std::uint8_t v) {
    grow(n + 1);
    w_[n] = static_cast<std::uint16_t>((w_[n] & 0x00FFu) | (static_cast<unsigned>(v) << 8));
    return *this;
  }
  DataBlock& set_dd(std::size_t n, std::int64_t v) {
    grow(n + 2);
    const auto u = static_cast<std::uint32_t>(v);
    w_[n] = static_cast<std::uint16_t>(u & 0xFFFFu);
    w_[n + 1] = static_cast<std::uint16_t>(u >> 16);
    return *this;
  }

 private:
  void grow(std::size_t n) {
    if (w_.size() < n) w_.resize(n, 0);
  }
  std::vector<std::uint16_t> w_;
};

}  // namespace hil::controllers::amkasyn
