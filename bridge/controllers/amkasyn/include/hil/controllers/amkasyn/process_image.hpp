// SPDX-License-Identifier: MIT
#pragma once
// What the fast functions read and write (manual §2.3, digest §1.6 "data holders"):
//   - the PS image: inputs E, outputs A, flags M (256 bytes each). Words and double words follow
//     the S5-style AWL convention of the PS: MW n = MB n (high byte) . MB n+1 (low byte),
//     MD n = MW n (high word) . MW n+2 [decision, docs/amkasyn.md: the manual never shows a
//     byte-level example];
//   - the drives AW1..AW8: command value sources SWQ1 (16-bit position) / SWQ2 (32-bit), the
//     32-bit position feedback, the configurable messages (16-bit ID 32785, 32-bit ID 32786);
//   - the AZ messages 1..4 (32-bit counters, e.g. the pulse-generator input X32);
//   - the analog outputs AA1..AA4;
//   - the internal sinks of SF0..SF15 (source address 255 + n links SFs).
// A data holder is (address, offset) as in the FB 207 init DB. 16-bit holders are wrapping
// position counters: consumers differentiate them modulo 2^16.
// Until the controller runtime's I/O image (issue 14) is merged this is the SF's own image; the
// adapter maps E/A/M onto it byte for byte.

#include <array>
#include <cstdint>
#include <optional>

namespace hil::controllers::amkasyn {

constexpr int max_sf = 16;  ///< SF0..SF15 (AZ-PS4 from V02.09)

struct DriveChannels {
  std::int16_t swq1 = 0;                            ///< sink offset 4: 16-bit position command (wrapping)
  std::int32_t swq2 = 0;                            ///< sink offset 16: 32-bit position or speed (0.0001 rpm) command
  bool swq1_written = false, swq2_written = false;  ///< set when an SF wrote it this cycle
  std::int32_t position_feedback = 0;               ///< source offsets 21 (32-bit) and 5 (low word)
  std::int32_t message32 = 0;  ///< Config-AW message32 (ID 32786): offsets 19 (32-bit), 3 (low word)
  std::int16_t message16 = 0;  ///< Config-AW message16 (ID 32785): offset 2
  /// The drive's reference (zero-pulse) latch: pulses seen so far and the position feedback at
  /// the last one (EPOS substitutional positioning, "continuous homing").
  /// The SAK lead the SF commanding this drive added to its command in its last cycle (command
  /// units); SIDIFF subtracts it from the drive's following error.
  std::int32_t sak_part = 0;
  std::uint32_t reference_count = 0;
  std::int32_t reference_position = 0;
};

/// The zero-pulse (reference) input of a counter behind an AZ message (X32 or an AZ-IG1 channel):
/// pulses seen so far and the 32-bit counter value latched at the last one. What the 32-bit AZ
/// message (source offsets 16..22) carries besides the count (manual: "including the reference
/// pulse"); read by IMES, FIPW printing mark control and external-master sync.
struct ZeroPulseLatch {
  std::uint32_t count = 0;
  std::int32_t position = 0;
  /// A pulse at `counter_value` (for the adapter and tests).
  void pulse(std::int32_t counter_value) noexcept {
    ++count;
    position = counter_value;
  }
};

struct ProcessImage {
  std::array<std::uint8_t, 256> e{}, a{}, m{};
  std::array<DriveChannels, 8> aw{};        ///< AW1..AW8
  std::array<std::int32_t, 4> az{};         ///< AZ messages 1..4 (32-bit counters)
  std::array<ZeroPulseLatch, 4> az_zero{};  ///< their zero-pulse inputs
  /// The zero-pulse latch that travels with a 32-bit AZ message a DCOPY copies into MD 4n (the
  /// counter in MD 4n, the latch here; FIPW/XFIPW "MD addr. ext. sync." DR7).
  std::array<ZeroPulseLatch, 32> md_zero{};
  std::array<std::int32_t, 4> analog_out{};  ///< AA1..AA4 (10000 = end value)

  [[nodiscard]] bool bit(const std::array<std::uint8_t, 256>& area, int byte, int bit_no) const noexcept {
    return ((area[static_cast<std::size_t>(byte & 0xFF)] >> bit_no) & 1) != 0;
  }
  [[nodiscard]] std::int16_t mw(int n) const noexcept { return word(m, n); }
  [[nodiscard]] std::int32_t md(int n) const noexcept { return dword(m, n); }
  [[nodiscard]] std::int16_t ew(int n) const noexcept { return word(e, n); }
  [[nodiscard]] std::int32_t ed(int n) const noexcept { return dword(e, n); }
  void set_mw(int n, std::int32_t v) noexcept { set_word(m, n, v); }
  void set_md(int n, std::int64_t v) noexcept {
    set_word(m, n, static_cast<std::int32_t>(static_cast<std::uint32_t>(v) >> 16));
    set_word(m, n + 2, static_cast<std::int32_t>(static_cast<std::uint32_t>(v) & 0xFFFFu));
  }
  void set_ew(int n, std::int32_t v) noexcept { set_word(e, n, v); }

  static std::int16_t word(const std::array<std::uint8_t, 256>& area, int n) noexcept {
    const auto hi = area[static_cast<std::size_t>(n & 0xFF)], lo = area[static_cast<std::size_t>((n + 1) & 0xFF)];
    return static_cast<std::int16_t>(static_cast<std::uint16_t>((hi << 8) | lo));
  }
  static std::int32_t dword(const std::array<std::uint8_t, 256>& area, int n) noexcept {
    const auto hi = static_cast<std::uint16_t>(word(area, n)), lo = static_cast<std::uint16_t>(word(area, n + 2));
    return static_cast<std::int32_t>((static_cast<std::uint32_t>(hi) << 16) | lo);
  }
  static void set_word(std::array<std::uint8_t, 256>& area, int n, std::int32_t v) noexcept {
    const auto u = static_cast<std::uint16_t>(v);
    area[static_cast<std::size_t>(n & 0xFF)] = static_cast<std::uint8_t>(u >> 8);
    area[static_cast<std::size_t>((n + 1) & 0xFF)] = static_cast<std::uint8_t>(u & 0xFF);
  }
};

/// An FB 207 data-holder address.
struct Holder {
  std::uint8_t address = 0;
  std::uint8_t offset = 0;
  friend bool operator==(const Holder&, const Holder&) = default;
};

/// A value read from a source: 16-bit holders set `wide` = false (a wrapping counter).
struct HolderValue {
  std::int32_t value = 0;
  bool wide = true;
};

/// Whether (address, offset) is a source / sink the manual defines (digest §1.6).
[[nodiscard]] bool valid_source(Holder h) noexcept;
[[nodiscard]] bool valid_sink(Holder h) noexcept;
/// Reads a source from `image`; `links` are the internal sinks of SF0..SF15 (address 255).
[[nodiscard]] HolderValue read_source(const ProcessImage& image, const std::array<std::int32_t, max_sf>& links,
                                      Holder h) noexcept;
/// The current value of a sink (incremental copy starts from it).
[[nodiscard]] std::int32_t read_sink(const ProcessImage& image, Holder h) noexcept;
/// Writes a sink (SWQ1 takes the low 16 bits).
void write_sink(ProcessImage& image, Holder h, std::int32_t v) noexcept;

}  // namespace hil::controllers::amkasyn
