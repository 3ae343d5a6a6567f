// SPDX-License-Identifier: MIT
#pragma once
// CLM1.4 I/O and marker addressing (manual §9.1, digest clm14.md §3.1/§3.5): `<type><source>.<byte>.<bit>`
// with type I (input), Q (output) or M (marker); source 0 system, 1 user, 2 fieldbus image (for
// markers: the marker group 0..6). "I1.00.6" = user input byte 0 bit 6; a byte is "M2.02".
// Pure codec plus the device's address space (Image): bytes in, bytes out, no I/O.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace hil::controllers::clm14 {

enum class Area : std::uint8_t { input, output, marker };

struct ByteAddress {
  Area area = Area::input;
  std::uint8_t source = 0;  ///< 0..2 for I/Q, marker group 0..6 for M
  std::uint8_t byte = 0;
  friend bool operator==(const ByteAddress&, const ByteAddress&) = default;
};

struct BitAddress {
  ByteAddress byte;
  std::uint8_t bit = 0;  ///< 0..7
  friend bool operator==(const BitAddress&, const BitAddress&) = default;
};

/// Bytes per source: inputs/outputs 16 per source (I0.00..I2.15), markers 50 per group (M0.00..M6.49).
inline constexpr int io_bytes = 16;
inline constexpr int marker_bytes = 50;

/// "I1.00.3" / "Q0.01.1" / "M2.03.4"; nullopt when malformed or outside the address space.
[[nodiscard]] std::optional<BitAddress> parse_bit(std::string_view text) noexcept;
/// "M2.02" / "Q1.01"; nullopt when malformed or outside the address space.
[[nodiscard]] std::optional<ByteAddress> parse_byte(std::string_view text) noexcept;
/// An I/O field of a parameter: "I1.00.0", or "00.00.0" = not used (nullopt, ok = true).
struct OptionalBit {
  std::optional<BitAddress> bit;
  bool ok = true;
};
[[nodiscard]] OptionalBit parse_optional_bit(std::string_view text) noexcept;
[[nodiscard]] std::string to_string(const BitAddress& a);
[[nodiscard]] std::string to_string(const ByteAddress& a);

/// The device's address space: inputs, outputs and markers as bytes. Outputs and markers are
/// written by the NC tasks and the logic task; inputs by the owner (stimuli, hardware).
class Image {
 public:
  /// Bytes of the whole address space: inputs and outputs of sources 0..2, then marker groups 0..6.
  static constexpr std::size_t size = 2 * 3 * io_bytes + 7 * marker_bytes;
  /// Where a byte lives in the flat address space. Out-of-range sources and bytes wrap (parse_bit
  /// never yields them); compiled code (the logic task) resolves its operands with this once.
  [[nodiscard]] static constexpr std::size_t offset(const ByteAddress& a) noexcept {
    switch (a.area) {
      case Area::input:
        return static_cast<std::size_t>(a.source % 3 * io_bytes + a.byte % io_bytes);
      case Area::output:
        return static_cast<std::size_t>(3 * io_bytes + a.source % 3 * io_bytes + a.byte % io_bytes);
      case Area::marker:
        break;
    }
    return static_cast<std::size_t>(6 * io_bytes + a.source % 7 * marker_bytes + a.byte % marker_bytes);
  }

  [[nodiscard]] std::uint8_t byte(const ByteAddress& a) const noexcept { return bytes_[offset(a)]; }
  void set_byte(const ByteAddress& a, std::uint8_t v) noexcept { bytes_[offset(a)] = v; }
  [[nodiscard]] bool bit(const BitAddress& a) const noexcept { return (byte(a.byte) >> a.bit) & 1U; }
  void set_bit(const BitAddress& a, bool v) noexcept {
    auto& b = bytes_[offset(a.byte)];
    b = static_cast<std::uint8_t>(v ? (b | (1U << a.bit)) : (b & ~(1U << a.bit)));
  }
  /// The flat address space, indexed by offset().
  [[nodiscard]] std::array<std::uint8_t, size>& bytes() noexcept { return bytes_; }
  [[nodiscard]] const std::array<std::uint8_t, size>& bytes() const noexcept { return bytes_; }
  /// Clear a whole marker group or output source.
  void clear_markers(int group) noexcept {
    std::fill_n(
        bytes_.begin() + static_cast<std::ptrdiff_t>(offset({Area::marker, static_cast<std::uint8_t>(group), 0})),
        marker_bytes, std::uint8_t{0});
  }
  void clear_outputs(int source) noexcept {
    std::fill_n(
        bytes_.begin() + static_cast<std::ptrdiff_t>(offset({Area::output, static_cast<std::uint8_t>(source), 0})),
        io_bytes, std::uint8_t{0});
  }
  void clear_inputs() noexcept { std::fill_n(bytes_.begin(), 3 * io_bytes, std::uint8_t{0}); }

 private:
  std::array<std::uint8_t, size> bytes_{};
};

/// Named system I/O (manual §9.1, digest §3.2/§3.3).
namespace sys {
inline constexpr BitAddress parameter_mode{{Area::input, 0, 0}, 0};
inline constexpr BitAddress automatic{{Area::input, 0, 0}, 1};
inline constexpr BitAddress emergency_stop_ok{{Area::input, 0, 0}, 2};  ///< active low: 1 = no E-Stop
inline constexpr BitAddress start{{Area::input, 0, 0}, 3};
inline constexpr BitAddress immediate_stop_ok{{Area::input, 0, 0}, 4};  ///< active low
inline constexpr BitAddress external_clear{{Area::input, 0, 0}, 7};
inline constexpr BitAddress restart{{Area::input, 0, 1}, 6};
/// Raster 1 (X3/16, fast input of axis 1: SRM, RMI, LMR, LMK, SRP).
inline constexpr BitAddress raster1{{Area::input, 0, 1}, 7};
/// Enable inputs of axes 1..4: I0.00.5, I0.00.6, I0.02.0, I0.02.3.
inline constexpr std::array<BitAddress, 4> enable{
    {{{Area::input, 0, 0}, 5}, {{Area::input, 0, 0}, 6}, {{Area::input, 0, 2}, 0}, {{Area::input, 0, 2}, 3}}};
/// Jog forward / reverse of axes 1..4.
inline constexpr std::array<BitAddress, 4> jog_forward{
    {{{Area::input, 0, 1}, 0}, {{Area::input, 0, 1}, 2}, {{Area::input, 0, 2}, 1}, {{Area::input, 0, 2}, 4}}};
inline constexpr std::array<BitAddress, 4> jog_reverse{
    {{{Area::input, 0, 1}, 1}, {{Area::input, 0, 1}, 3}, {{Area::input, 0, 2}, 2}, {{Area::input, 0, 2}, 5}}};
inline constexpr BitAddress out_manual{{Area::output, 0, 0}, 0};
inline constexpr BitAddress out_automatic{{Area::output, 0, 0}, 1};
inline constexpr BitAddress out_parameter{{Area::output, 0, 0}, 2};
inline constexpr BitAddress out_error{{Area::output, 0, 0}, 5};  ///< active low: 1 = no error
inline constexpr BitAddress out_restart_possible{{Area::output, 0, 1}, 0};
inline constexpr BitAddress out_run{{Area::output, 0, 1}, 1};
inline constexpr BitAddress out_inhibit{{Area::output, 0, 1}, 5};
/// Drive enable outputs of axes 1..4: Q0.00.3, Q0.00.6, Q0.01.6, Q0.01.7.
inline constexpr std::array<BitAddress, 4> out_drive_enable{
    {{{Area::output, 0, 0}, 3}, {{Area::output, 0, 0}, 6}, {{Area::output, 0, 1}, 6}, {{Area::output, 0, 1}, 7}}};
/// Brake outputs (1 = released) of axes 1..4: Q0.00.4, Q0.00.7, Q0.02.0, Q0.02.1.
inline constexpr std::array<BitAddress, 4> out_brake{
    {{{Area::output, 0, 0}, 4}, {{Area::output, 0, 0}, 7}, {{Area::output, 0, 2}, 0}, {{Area::output, 0, 2}, 1}}};
}  // namespace sys

}  // namespace hil::controllers::clm14
