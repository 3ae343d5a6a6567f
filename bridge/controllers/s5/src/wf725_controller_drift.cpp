// SPDX-License-Identifier: MIT
// WF 725/726 drift and its compensation (digest §4.3 MD 35, §6.1 submode RUN, §6.4 data code 10;
// docs/wf725.md "Drift"). Open loop (AK) has no K_v loop and no MD 35: the drive creeps. The drive behind X3 has an
// input offset (controller key `drift`, mV): at zero command it runs at v_d = drift / MD 23 x MD 3, so the WF's
// proportional loop K_v (MD 22) holds the axis at a standstill following error of -v_d / K_v. MD 35 is the module's
// compensation, "-(standstill following error)", added to the command so that the error reads
// about 0; limited to +-255 resolution steps so that a drive fault is not masked. In a P loop a
// velocity offset v is a position offset v / K_v, so both reach the axis as its set-point offset
// (motion::Axis::set_setpoint_offset): the drive gets command + v_d / K_v - MD 35, the following
// error stays against the command.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hil/controllers/s5/wf725_controller.hpp"

namespace hil::controllers::s5 {
namespace {

using namespace wf_db;

/// The basic resolution A in µm (MD 49: 1 = 1 µm, 2 = 10 µm, 3 = 100 µm).
std::int64_t resolution_um(const Wf725MachineData& md) noexcept {
  const std::int64_t r = md.integer(49);
  return r == 3 ? 100 : r == 2 ? 10 : 1;
}

/// MD 35's limit: +-255 resolution steps (+-255 / 2 550 / 25 500 µm).
std::int64_t md35_limit_um(const Wf725MachineData& md) noexcept {
  return 255 * resolution_um(md);
}

}  // namespace

double Wf725Controller::drift_offset_um() const noexcept {
  if (!md_.closed_loop()) return creep_mm_ / um;
  const double md3 = static_cast<double>(md_.get(3)), md22 = static_cast<double>(md_.get(22));
  const double md23 = static_cast<double>(md_.get(23));
  // v_d / K_v in µm: (drift / MD 23 x MD 3 [mm/min]) / (MD 22 [(m/min)/mm] x 1000 [(mm/min)/mm]) x 1000.
  const double drift_um = md23 > 0.0 && md22 > 0.0 ? opt_.drift_mv / md23 * md3 / md22 : 0.0;
  // A value written beyond the limit by data code 50 acts as the limit (the module limits it).
  const auto limit = md35_limit_um(md_);
  const double md35 = static_cast<double>(std::clamp(md_.integer(35), -limit, limit));
  return drift_um - md35;
}

void Wf725Controller::drift_cycle(TimePoint now) {
  if (!md_.closed_loop()) {
    // Open loop: no position loop holds the drift: the powered drive creeps at drift / 10 V x its
    // speed at 10 V (level x 100 mV is the same scale), also at speed level 0. Unpowered it stands,
    // and the set-point takes the actual over when it comes back: the creep starts again from 0.
    const bool powered = axis(0).status().drive_state == DriveState::operation_enabled;
    if (!powered || opt_.drift_mv == 0.0) {
      creep_mm_ = 0.0;
    } else if (drift_at_ != TimePoint{}) {
      const double v_mm_s = opt_.drift_mv / 10000.0 * opt_.drive.speed_at_10v_mm_min / 60.0;
      creep_mm_ += v_mm_s * to_seconds(now - drift_at_);
    }
    drift_at_ = now;
  }
  const double offset_mm = drift_offset_um() * um;
  auto& ax = axis(0);
  if (ax.setpoint_offset() != offset_mm) (void)ax.set_setpoint_offset(offset_mm);
}

std::int32_t Wf725Controller::compensate_drift(TimePoint now) {
  const auto current = static_cast<std::int32_t>(md_.integer(35));
  if (!md_.closed_loop()) {
    raise_io(113, now, "data code 10: drift compensation (MD 35) is closed loop only");
    return current;
  }
  if (!traversing_ || submode_ != Submode::run) {
    raise_io(900, now,
             fmt::format("data code 10 compensates the drift in mode traversing, submode RUN ({}) only",
                         static_cast<int>(Submode::run)),
             "standard2");
    return current;
  }
  const auto& st = axis(0).status();
  if (!drive_enabled_ || st.state != motion::AxisState::standstill || job_ != Job::none || errors().blocks_motion(0)) {
    raise_io(202, now,
             "data code 10: the axis is not under position control at rest (drive enable D 2.0, no error, no motion)",
             "memory_admin");
    return current;
  }
  // The error now is MD 35 - drift / K_v (µm); the compensation that makes it 0 is MD 35 - error,
  // i.e. "-(standstill following error)" from MD 35 = 0. In resolution steps, within the limit.
  const double error_um = st.following_error / um;
  const auto a = resolution_um(md_), limit = md35_limit_um(md_);
  const auto steps = std::llround((static_cast<double>(current) - error_um) / static_cast<double>(a));
  const std::int64_t md35 = std::clamp<std::int64_t>(steps * a, -limit, limit);
  md_.set(35, static_cast<long double>(md35));
  drift_cycle(now);
  return static_cast<std::int32_t>(md35);
}

}  // namespace hil::controllers::s5
