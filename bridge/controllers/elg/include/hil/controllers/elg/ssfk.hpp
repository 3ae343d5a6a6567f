// SPDX-License-Identifier: MIT
#pragma once
// SSFK, the ELG's concentricity / pitch-error compensation of the drive axis C (MD 5016 bits 1-2,
// MD 6000-6249, MD 316*-328*; digest §9.2). The 06.85 manual lists it as "in preparation" and gives
// the data but no algorithm (digest §12.9); hilbridge reads the data as a 1-bit-per-point
// incremental table, each [I] decision documented in docs/elg.md ("SSFK"):
// - points 1..1000, four per byte (byte 6000 = points 4..1 in bit pairs 7/6..1/0); per point the
//   upper bit is the sign (1 = +, 0 = -), the lower bit "no" (1 = no compensation at this point);
// - the table starts at the point the pointer names (MD 316* for the + direction, MD 320* for the -
//   direction when MD 5016 bit 2 "direction-dependent" is set; MD 316* otherwise): 1..1000 is a
//   point number, 6000..6249 the MD byte (its first point), 0 = point 1; other values: no table;
// - C's position counts from its reference point (MD 240*), modulo one revolution; at every
//   MD 324* counts one more point is passed and its step of MD 328* counts (signed) is added;
//   the compensation at a position is the sum of the steps of the points passed (no point passed:
//   0; beyond the table's end: the sum of all);
// - it acts only once C is referenced (REF, 7.3: "needed whenever SSFK is used on C").
// Pure: the machine adds compensation() to C's position commands and subtracts it from C's actual
// value, so the ELG works in compensated coordinates.

#include <array>
#include <cstdint>
#include <vector>

namespace hil::controllers::elg {

struct SsfkData {
  bool active = false;                                 ///< MD 5016 bit 1
  bool direction_dependent = false;                    ///< MD 5016 bit 2
  std::int64_t pointer_plus = 0;                       ///< MD 316* of C
  std::int64_t pointer_minus = 0;                      ///< MD 320* of C
  std::int64_t distance = 0;                           ///< MD 324*: MS units between two points (0: no SSFK)
  std::int64_t step = 0;                               ///< MD 328*: MS units per point
  std::int64_t revolution = 720000;                    ///< counts of one revolution of C (4 x MD 396*)
  std::array<std::uint8_t, 250> flags = filled(0x55);  ///< MD 6000..6249 (default: every point "no")

  static constexpr std::array<std::uint8_t, 250> filled(std::uint8_t v) {
    std::array<std::uint8_t, 250> a{};
    a.fill(v);
    return a;
  }
};

class Ssfk {
 public:
  Ssfk() = default;
  explicit Ssfk(const SsfkData& data);

  /// Whether the compensation acts at all (MD 5016 bit 1, MD 324* > 0).
  [[nodiscard]] bool active() const noexcept { return active_; }
  /// The compensation in counts at C's position `from_reference` (counts from the reference point)
  /// moving in `direction` (+1 / -1; 0 counts as +).
  [[nodiscard]] std::int64_t compensation(std::int64_t from_reference, int direction) const noexcept;
  /// Point k (1..1000): +1, -1 or 0 ("no").
  [[nodiscard]] int point(int k) const noexcept;

 private:
  std::vector<std::int64_t> prefix(std::int64_t pointer) const;

  SsfkData data_;
  bool active_ = false;
  std::vector<std::int64_t> plus_;   ///< plus_[n]: sum of the first n points from the + pointer
  std::vector<std::int64_t> minus_;  ///< the same from the - pointer
};

}  // namespace hil::controllers::elg
