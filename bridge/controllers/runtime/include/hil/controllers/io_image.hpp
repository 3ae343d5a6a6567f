// SPDX-License-Identifier: MIT
#pragma once
// The digital I/O image of one controller: bytes of inputs, outputs, markers and device data
// (S5 data-block words), with names for bits and bytes, read and written once per controller
// cycle. Devices put their own addressing on it through small pure codecs
// (io_address_clm.hpp: CLM1.4 `I0.00.1`; io_address_s5.hpp: S5 `E 4.1`, `DB10 D 2.0`).
//
// One controller cycle (Controller::step does this; docs/controllers.md):
//   1. read_inputs(now):   the image as it stands is kept as `previous`, then every IoSource
//                          writes the inputs it owns (scenario stimuli, cams, GPIO, Modbus, CiA 402);
//   2. the device logic:   reads inputs, markers and edges, writes outputs and markers;
//   3. write_outputs(now): every IoSink reads the outputs/markers it serves (trace, GPIO, ...).
//
// Thread: configuration (the constructor, name_*(), attach()) before the run; everything else on
// the cycle thread only. The cyclic members are noexcept, never allocate and never block; an
// address outside the layout reads 0 and is ignored on write (addresses are checked with
// contains() or come from name lookups and codecs checked at configuration time).

#include <array>
#include <compare>
#include <cstdint>
#include <expected>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "hil/core/clock.hpp"

namespace hil::controllers {

/// The areas of the image. `data` holds device data words the PLC side writes (S5 DB bits).
enum class IoArea : std::uint8_t { input, output, marker, data };
inline constexpr std::size_t io_area_count = 4;
[[nodiscard]] std::string_view to_string(IoArea area) noexcept;

/// One bit: `byte` counts from 0 within its area, `bit` is 0..7 (bit 0 = least significant).
struct BitAddress {
  IoArea area = IoArea::input;
  std::uint32_t byte = 0;
  std::uint8_t bit = 0;
  friend auto operator<=>(const BitAddress&, const BitAddress&) = default;
};

/// One byte of an area.
struct ByteAddress {
  IoArea area = IoArea::input;
  std::uint32_t byte = 0;
  friend auto operator<=>(const ByteAddress&, const ByteAddress&) = default;
};

/// Size of each area in bytes, indexed by IoArea.
struct IoLayout {
  std::array<std::uint32_t, io_area_count> bytes{};
  [[nodiscard]] std::uint32_t size(IoArea area) const noexcept { return bytes[static_cast<std::size_t>(area)]; }
};

/// A named bit or byte ("start", "limit_plus_x", "I0.00.3").
struct IoSignal {
  std::string name;
  IoArea area = IoArea::input;
  std::uint32_t byte = 0;
  std::optional<std::uint8_t> bit;  ///< empty: the name denotes the whole byte
};

class IoImage;

/// Writes inputs into the image once per controller cycle (scenario stimuli, position cams,
/// GPIO lines, Modbus coils, CiA 402 0x60FD). Called by IoImage::read_inputs on the cycle
/// thread, in attach order (a later source overrides an earlier one on the same bit). Must not
/// block, throw or re-enter the image's cycle functions; may only call get/set members.
class IoSource {
 public:
  virtual ~IoSource() = default;
  /// `now` = the controller cycle's nominal time (CycleTime::now).
  virtual void read(TimePoint now, IoImage& image) noexcept = 0;
};

/// Reads outputs and markers from the image once per controller cycle (GPIO outputs, Modbus
/// coils, CiA 402 0x60FE, recorders). Called by IoImage::write_outputs on the cycle thread, in
/// attach order, after the device logic ran. Must not block or throw; must not modify the image.
class IoSink {
 public:
  virtual ~IoSink() = default;
  virtual void write(TimePoint now, const IoImage& image) noexcept = 0;
};

class IoImage {
 public:
  /// All bits 0. Areas may have size 0.
  explicit IoImage(IoLayout layout = {});

  [[nodiscard]] const IoLayout& layout() const noexcept { return layout_; }
  [[nodiscard]] bool contains(BitAddress a) const noexcept { return a.bit < 8 && a.byte < layout_.size(a.area); }
  [[nodiscard]] bool contains(ByteAddress a) const noexcept { return a.byte < layout_.size(a.area); }

  // --- names (configuration time) ---------------------------------------------------------
  /// Gives `address` the name `name` (non-empty, unique across bits and bytes; several names
  /// may denote the same bit). Error text names the name and the address.
  std::expected<void, std::string> name_bit(std::string name, BitAddress address);
  std::expected<void, std::string> name_byte(std::string name, ByteAddress address);
  [[nodiscard]] std::optional<BitAddress> find_bit(std::string_view name) const noexcept;
  [[nodiscard]] std::optional<ByteAddress> find_byte(std::string_view name) const noexcept;
  /// Every name, in the order given.
  [[nodiscard]] std::span<const IoSignal> signals() const noexcept { return signals_; }

  // --- sources and sinks (configuration time) ----------------------------------------------
  /// Not owned: each must outlive the image's cycles.
  void attach(IoSource& source);
  void attach(IoSink& sink);

  // --- cyclic access (cycle thread; noexcept, allocation-free) ------------------------------
  [[nodiscard]] bool get(BitAddress a) const noexcept {
    return contains(a) && ((bytes_[offset(a.area) + a.byte] >> a.bit) & 1U) != 0;
  }
  void set(BitAddress a, bool value) noexcept {
    if (!contains(a)) return;
    auto& b = bytes_[offset(a.area) + a.byte];
    b = static_cast<std::uint8_t>(value ? (b | (1U << a.bit)) : (b & ~(1U << a.bit)));
  }
  [[nodiscard]] std::uint8_t get(ByteAddress a) const noexcept {
    return contains(a) ? bytes_[offset(a.area) + a.byte] : std::uint8_t{0};
  }
  void set(ByteAddress a, std::uint8_t value) noexcept {
    if (contains(a)) bytes_[offset(a.area) + a.byte] = value;
  }
  /// The bit as it stood when read_inputs() began (the end of the previous controller cycle).
  [[nodiscard]] bool previous(BitAddress a) const noexcept {
    return contains(a) && ((previous_[offset(a.area) + a.byte] >> a.bit) & 1U) != 0;
  }
  /// 0 -> 1 / 1 -> 0 since the previous cycle (CLM Start and External Clear are rising edges).
  [[nodiscard]] bool rising(BitAddress a) const noexcept { return get(a) && !previous(a); }
  [[nodiscard]] bool falling(BitAddress a) const noexcept { return !get(a) && previous(a); }
  /// The bytes of one area (size layout().size(area)).
  [[nodiscard]] std::span<const std::uint8_t> bytes(IoArea area) const noexcept {
    return {bytes_.data() + offset(area), layout_.size(area)};
  }
  [[nodiscard]] std::span<const std::uint8_t> previous_bytes(IoArea area) const noexcept {
    return {previous_.data() + offset(area), layout_.size(area)};
  }

  // --- the cycle (Controller::step calls these) -------------------------------------------
  /// Keep the image as `previous`, then let every source write its inputs.
  void read_inputs(TimePoint now) noexcept;
  /// Hand the image to every sink.
  void write_outputs(TimePoint now) const noexcept;

 private:
  [[nodiscard]] std::size_t offset(IoArea area) const noexcept { return offsets_[static_cast<std::size_t>(area)]; }
  std::expected<void, std::string> add_name(IoSignal signal);

  IoLayout layout_;
  std::array<std::size_t, io_area_count> offsets_{};
  std::vector<std::uint8_t> bytes_;
  std::vector<std::uint8_t> previous_;
  std::vector<IoSignal> signals_;
  std::vector<IoSource*> sources_;
  std::vector<IoSink*> sinks_;
};

/// "input 3.1" / "marker 12" (area byte.bit): the generic address text of the image.
[[nodiscard]] std::string format_address(BitAddress a);
[[nodiscard]] std::string format_address(ByteAddress a);

}  // namespace hil::controllers
