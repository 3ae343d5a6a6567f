// SPDX-License-Identifier: MIT
#pragma once
// What the CLM1.4 model needs from one of its axes: commands out (absolute moves that may be
// re-planned while running, velocity runs, stops, enable, homing) and feedback in. Positions are
// in the axis' own coordinates in IU; the CLM adds its homing offset and SAC offsets itself.
// motion_axis_port.hpp implements it on hil::motion::Axis, which closes the loop over any
// transport (sim, CANopen, Modbus, step/dir). Called on the controller's cycle thread only;
// nothing blocks; nothing throws.

#include <cstdint>
#include <limits>

namespace hil::controllers::clm14 {

struct MoveLimits {
  double velocity = 0.0;                                  ///< IU/s, > 0
  double acceleration = 0.0;                              ///< IU/s², > 0
  double jerk = std::numeric_limits<double>::infinity();  ///< IU/s³; inf = trapezoid
};

struct AxisFeedback {
  double position = 0.0;          ///< actual, IU (axis coordinates)
  double velocity = 0.0;          ///< actual, IU/s
  double following_error = 0.0;   ///< IU
  double command_position = 0.0;  ///< the trajectory's set-point, IU (axis coordinates)
  double command_velocity = 0.0;  ///< the trajectory's velocity, IU/s
  bool busy = false;              ///< a move or stop profile is running
  bool in_position = false;       ///< the profile ended and the axis settled at its target
  bool enabled = false;           ///< operation enabled
  bool referenced = false;        ///< the drive's homing completed
  bool fault = false;             ///< the axis holds a fault (following error, drive fault, lost drive)
  std::int64_t position_inc = 0;  ///< actual, drive increments (the master of a slave axis, FOL)
  std::int64_t command_inc = 0;   ///< set-point, drive increments (the master of a synchronous axis)
};

class AxisPort {
 public:
  virtual ~AxisPort() = default;
  [[nodiscard]] virtual AxisFeedback feedback() const = 0;
  /// Absolute move in axis coordinates; re-plans from the current state when already moving.
  virtual void move_to(double target, const MoveLimits& limits) = 0;
  /// Run at a signed velocity until stop() or another command.
  virtual void run(double velocity, const MoveLimits& limits) = 0;
  /// Ramped stop (remaining distance is the caller's business).
  virtual void stop() = 0;
  /// E-Stop: command 0 without a ramp.
  virtual void quick_stop() = 0;
  virtual void set_enabled(bool on) = 0;
  /// Start the drive's homing; feedback().referenced reports completion.
  virtual void home() = 0;
  /// Acknowledge an axis fault.
  virtual void reset() = 0;
  /// Coupled motion (FOL, flying cutoff): this cycle's set-point from a hil::motion::Coupling, in
  /// drive increments (CouplingOutput). Ended by stop() or a new move_to()/run().
  virtual void follow(std::int64_t position_inc, double velocity_inc_per_s, double acceleration_inc_per_s2) = 0;
};

}  // namespace hil::controllers::clm14
