// SPDX-License-Identifier: MIT
#pragma once
// AxisPort on the motion core: a CLM axis is a hil::motion::Axis in IU over any hil::Drive
// (transport sim, canopen, modbus, stepdir), so the same CLM program runs on every transport.

#include <string>

#include "hil/controllers/clm14/axis_port.hpp"
#include "hil/controllers/clm14/master_encoder.hpp"
#include "hil/controllers/clm14/settings.hpp"
#include "hil/motion/axis.hpp"

namespace hil::controllers::clm14 {

/// Axis configuration in IU from the CLM parameters: increments per IU from the encoder (Ax19
/// pulses × 4 quadrature per Ax01), velocity Ax06, acceleration Ax08, jog Ax07, linear limits
/// Ax03/Ax04 are the CLM's business (errors 46/47/50/51), not soft limits of the axis.
/// `following_error_window` 0 = 10 % of Vmax × 1 s [decided; Ax11/Ax12/Ax14 are not modelled].
[[nodiscard]] motion::AxisConfig make_axis_config(const AxisSettings& s, std::string name,
                                                  double following_error_window = 0.0);

class MotionAxisPort final : public AxisPort {
 public:
  /// `axis` must outlive the port.
  explicit MotionAxisPort(motion::Axis& axis) : axis_(axis) {}
  [[nodiscard]] AxisFeedback feedback() const override;
  void move_to(double target, const MoveLimits& limits) override;
  void run(double velocity, const MoveLimits& limits) override;
  void stop() override;
  void quick_stop() override;
  void set_enabled(bool on) override;
  void home() override;
  void reset() override;
  void follow(std::int64_t position_inc, double velocity_inc_per_s, double acceleration_inc_per_s2) override;

 private:
  [[nodiscard]] motion::Limits clamp(const MoveLimits& l) const;
  motion::Axis& axis_;
};

/// Master encoder 1 on the motion core: a machine axis whose drive counts the material (the
/// measuring wheel of a flying cutoff, a line shaft); the count is its actual position in drive
/// increments. Configure that axis with master_encoder_config() so one increment is one
/// quadrature count of C000.
class MotionMasterEncoder final : public MasterEncoderPort {
 public:
  explicit MotionMasterEncoder(const motion::Axis& axis) : axis_(axis) {}
  [[nodiscard]] std::uint32_t count() const override {
    return static_cast<std::uint32_t>(static_cast<std::uint64_t>(axis_.status().position_inc));
  }

 private:
  const motion::Axis& axis_;
};

/// Axis configuration of master encoder 1 in IU: C000 pulses × 4 quadrature counts per C002 IU;
/// limits [decided]: velocity 2 × A106, acceleration 10 × A108 (the material is moved by the
/// scenario, not by the CLM; the CLM's error 4D watches 1.25 × Vmax where VEO 5 uses it).
[[nodiscard]] motion::AxisConfig master_encoder_config(const MasterEncoderSettings& me, const AxisSettings& axis1,
                                                       std::string name);

}  // namespace hil::controllers::clm14
