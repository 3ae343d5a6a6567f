// SPDX-License-Identifier: MIT
#pragma once
// The CLM1.4's own homing (manual §7.9, digest clm14.md §5.7; Ax23-Ax25): options 1-4 as a pure
// step function in encoder increments. The caller (Controller, homing_run.cpp) reads the axis,
// the home switch and the marker once per NC cycle, calls step() and carries out the command
// (run at a velocity, stop, move to a count); on `done` the marker / switch-edge count becomes the
// Ax25 position. Option 5 (passive, flying cutoff) moves nothing and is watched by the caller.
//
//   option 1 (type 0) switch + marker: to the cam at V1 in the Ax24 direction d; on the cam
//            reverse and leave it at V2 = V1/4; approach again at V3 = min(V2, 10 inc/cycle) and
//            take the first marker after the cam edge; reverse and creep at V4 = min(V3, 1
//            inc/cycle) back to that marker. Started on the cam: leave it at V2 first.
//   option 2 (type 1) marker only: the first marker at min(V1, 10 inc/cycle) in d, then at V1 to
//            1/32 revolution before the second, which is taken at V4.
//   option 3 (type 2) switch only: at V1 in d to a rising edge of the switch.
//   option 4 (type 3) as 3, but started on the switch it leaves it first (at V2 against d).
//
// Errors (the device's numbers of axis 1; the caller adds the axis offset): 49 the axis brakes
// past the cam (cam too short) or the switch drops between edge and marker; 4A no marker within
// one revolution; 4B edge-marker distance outside 1/16..15/16 revolution; 4F the marker stays
// high over 1/16 revolution; 52 homing not possible (no switch configured for a switch option,
// type 4 on a normal axis, or no cam within the search travel [decided]).
//
// Thread: the controller's cycle thread. Never throws, never blocks.

#include <cstdint>
#include <optional>

#include "hil/controllers/clm14/address.hpp"

namespace hil::controllers::clm14 {

/// Where an axis' marker pulse comes from [decided; the CLM reads the encoder's marker track]:
/// by default the encoder itself, one mark per revolution (4 × Ax19 counts) at the counts
/// offset_inc + k × 4 × Ax19 of the axis' actual increments (hil::motion::ZeroMarkGrid), exact to
/// the count at any speed; or, with `input`, a bit of the image (an index signal wired to an
/// input, a scenario's stimulus), whose rising edge is the mark at the position of that cycle.
struct MarkerSource {
  std::int64_t offset_inc = 0;
  std::optional<BitAddress> input;
};

struct HomingSetup {
  int type = 0;                       ///< Ax24 t: 0..3 = options 1..4
  int direction = 1;                  ///< Ax24 sign: +1 / -1
  double v1_inc_per_s = 0.0;          ///< Ax24 ‰ × Ax06, in increments/s (no override, §7.3)
  double cycle_s = 0.002;             ///< NC cycle
  std::int64_t revolution_inc = 4;    ///< one encoder revolution: 4 × Ax19 counts
  std::int64_t search_limit_inc = 0;  ///< most travel looking for the cam / switch edge (0 = unlimited)
  bool has_switch = true;             ///< Ax23 names a home switch
};

/// What the axis sees this cycle.
struct HomingInput {
  std::int64_t position_inc = 0;       ///< actual, encoder increments (never re-referenced)
  bool standstill = true;              ///< no profile runs and the set-point is at rest
  bool home_switch = false;            ///< the Ax23 home switch (active high)
  std::optional<std::int64_t> marker;  ///< the marker passed since the last cycle, at that count
  bool marker_high = false;            ///< the marker line is high now
};

/// What the caller does with the axis this cycle.
struct HomingCommand {
  enum class Kind : std::uint8_t { none, run, stop, move };
  Kind kind = Kind::none;
  double velocity_inc_per_s = 0.0;  ///< run: signed; move: the speed limit
  std::int64_t target_inc = 0;      ///< move: the target count
};

enum class HomingStatus : std::uint8_t { idle, busy, done, failed };

class Homing {
 public:
  /// Begin a homing run from `in`. Returns the first command (none when it failed at once: see
  /// error()).
  HomingCommand start(const HomingSetup& setup, const HomingInput& in);
  /// One NC cycle. Each command is returned once, when it changes.
  HomingCommand step(const HomingInput& in);
  /// Ends the run without a result (stop, mode change, error); the caller stops the axis.
  void abort() noexcept { phase_ = Phase::idle; }

  [[nodiscard]] HomingStatus status() const noexcept;
  /// The CLM error number for axis 1 (0x49, 0x4A, 0x4B, 0x4F, 0x52) once failed, else 0.
  [[nodiscard]] int error() const noexcept { return error_; }
  /// The count that becomes the Ax25 position (valid once done).
  [[nodiscard]] std::int64_t home_inc() const noexcept { return home_inc_; }
  /// Edge-to-marker distance of option 1 (increments, valid once the marker was taken).
  [[nodiscard]] std::int64_t edge_to_marker_inc() const noexcept { return edge_marker_; }

 private:
  enum class Phase : std::uint8_t {
    idle,
    seek_cam,       // option 1: to the cam at V1
    brake_on_cam,   // option 1: stopping on the cam
    leave_cam,      // options 1 and 4: off the cam at V2 against d
    brake_off_cam,  // stopping off the cam
    approach,       // option 1: to the edge and the first marker at V3
    brake_marker,   // option 1: stopping behind the marker
    creep_back,     // option 1: back to the marker at V4
    first_marker,   // option 2: the first marker at min(V1, 10 inc/cycle)
    to_second,      // option 2: to 1/32 revolution before the second
    creep_second,   // option 2: the second marker at V4
    seek_edge,      // options 3 and 4: to the rising edge at V1
    brake_final,    // every option: stopping after the reference was taken
    done,
    failed
  };
  HomingCommand fail(int code);
  HomingCommand run(double v);
  HomingCommand stop(Phase next);
  [[nodiscard]] double v1() const noexcept { return setup_.v1_inc_per_s; }
  [[nodiscard]] double v2() const noexcept { return setup_.v1_inc_per_s / 4.0; }
  [[nodiscard]] double v3() const noexcept;
  [[nodiscard]] double v4() const noexcept;
  [[nodiscard]] bool beyond(std::int64_t from, std::int64_t pos, std::int64_t limit) const noexcept;
  /// Stuck-high check over the travel since the marker line rose (4F).
  bool marker_stuck(const HomingInput& in);

  HomingSetup setup_{};
  Phase phase_ = Phase::idle;
  int error_ = 0;
  std::int64_t origin_ = 0;   ///< where the current search started
  std::int64_t edge_ = 0;     ///< option 1: the cam edge (switch rose during the approach)
  bool edge_seen_ = false;    ///< option 1: the approach has re-entered the cam
  bool switch_last_ = false;  ///< the switch in the previous cycle (edges)
  std::int64_t mark_ = 0;     ///< the marker taken
  std::int64_t edge_marker_ = 0;
  std::int64_t home_inc_ = 0;
  std::optional<std::int64_t> high_since_;  ///< count where the marker line rose
};

}  // namespace hil::controllers::clm14
