// SPDX-License-Identifier: MIT
// Coupling step 5: law + superimposed move -> slave limits and following-error monitor ->
// the slave's set-point. See coupling.hpp for the rules.
#include "hil/motion/coupling.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace hil::motion {
namespace {

class CouplingCategory final : public std::error_category {
 public:
  const char* name() const noexcept override { return "coupling"; }
  std::string message(int v) const override {
    switch (static_cast<CouplingFault>(v)) {
      case CouplingFault::none:
        return "no fault";
      case CouplingFault::velocity_limit:
        return "coupling demands more than the slave's velocity limit";
      case CouplingFault::acceleration_limit:
        return "coupling demands more than the slave's acceleration limit";
      case CouplingFault::following_error:
        return "slave does not follow the coupling (following error)";
      case CouplingFault::invalid:
        return "invalid coupling parameter";
    }
    return fmt::format("unknown coupling fault {}", v);
  }
};

}  // namespace

const std::error_category& coupling_category() noexcept {
  static const CouplingCategory c;
  return c;
}

Coupling::Coupling(std::string name, SlaveLimits limits) : name_(std::move(name)), limits_(limits) {
  limits_.acceleration_filter_cycles = std::clamp(limits_.acceleration_filter_cycles, 1, max_filter);
}

void Coupling::start(std::int64_t master_inc, std::int64_t slave_inc, std::int64_t cam_phase) noexcept {
  gear_.start(master_inc, slave_inc);
  cam_.start(master_inc, static_cast<double>(slave_inc), cam_phase);
  superimposed_.clear();
  hold_ = static_cast<double>(slave_inc);
  first_ = true;
  prev_y_ = static_cast<double>(slave_inc);
  prev_v_ = prev_vf_ = 0.0;
  v_sum_ = 0.0;
  v_n_ = v_i_ = 0;
  out_ = CouplingOutput{slave_inc, static_cast<double>(slave_inc), 0.0, 0.0, static_cast<bool>(fault_)};
}

void Coupling::reset(std::int64_t master_inc) noexcept {
  fault_ = {};
  const double y = out_.position;
  const auto whole = static_cast<std::int64_t>(std::floor(y));
  gear_.start(master_inc, whole);
  cam_.start(master_inc, y, static_cast<std::int64_t>(cam_.table_position()));
  superimposed_.clear();
  hold_ = y;
  prev_y_ = y;
  prev_v_ = prev_vf_ = 0.0;
  v_sum_ = 0.0;
  v_n_ = v_i_ = 0;
  out_.faulted = false;
  out_.velocity_inc_per_s = out_.acceleration_inc_per_s2 = 0.0;
}

void Coupling::raise(CouplingFault f, std::string text) noexcept {
  if (fault_) return;  // the first fault stays
  fault_ = hil::Fault{make_error_code(f), std::move(text)};
}

double Coupling::law_position(std::int64_t m) noexcept {
  switch (law_) {
    case Law::gear:
      return gear_.update(m);
    case Law::cam:
      return cam_.update(m);
    case Law::none:
      break;
  }
  gear_.start(m, static_cast<std::int64_t>(std::floor(hold_)));  // keeps the gear in step for a later use(gear)
  return hold_;
}

const CouplingOutput& Coupling::update(std::int64_t master_inc, hil::Duration period,
                                       std::optional<std::int64_t> slave_actual_inc) noexcept {
  const double T = hil::to_seconds(period);
  superimposed_.update(period);
  const double y = law_position(master_inc) + superimposed_.offset();
  demanded_ = y;
  if (!(T > 0.0)) return out_;

  if (!fault_ && slave_actual_inc && limits_.following_error_window > 0.0) {
    const double fe = static_cast<double>(out_.position_inc - *slave_actual_inc);
    if (std::fabs(fe) > limits_.following_error_window)
      raise(CouplingFault::following_error,
            fmt::format("coupling '{}': slave following error {} inc exceeds the coupling window {} inc; slave braked "
                        "to rest (reset the coupling)",
                        name_, fe, limits_.following_error_window));
  }

  if (!fault_) {
    const double v = (y - prev_y_) / T;
    // Moving average of v over N cycles (noisy masters), then the acceleration.
    const int n = limits_.acceleration_filter_cycles;
    v_sum_ += v - (v_n_ == n ? v_hist_[v_i_] : 0.0);
    v_hist_[v_i_] = v;
    v_i_ = (v_i_ + 1) % n;
    if (v_n_ < n) ++v_n_;
    const double vf = v_sum_ / v_n_;
    const double a = (vf - prev_vf_) / T;
    const char* law = law_ == Law::gear ? "gear" : law_ == Law::cam ? "cam" : "superimposed move";
    if (std::fabs(v) > limits_.velocity * (1.0 + 1e-12)) {
      raise(CouplingFault::velocity_limit,
            fmt::format("coupling '{}': the {} demands a slave velocity of {:.6g} inc/s, above the limit {:.6g} inc/s "
                        "(master at {}); slave braked to rest (reset the coupling)",
                        name_, law, v, limits_.velocity, master_inc));
    } else if (std::fabs(a) > limits_.acceleration * (1.0 + 1e-12)) {
      raise(CouplingFault::acceleration_limit,
            fmt::format("coupling '{}': the {} demands a slave acceleration of {:.6g} inc/s^2, above the limit {:.6g} "
                        "inc/s^2 (master at {}); slave braked to rest (reset the coupling)",
                        name_, law, a, limits_.acceleration, master_inc));
    } else {
      out_.position = y;
      out_.velocity_inc_per_s = v;
      out_.acceleration_inc_per_s2 = first_ ? 0.0 : (v - prev_v_) / T;
      prev_vf_ = vf;
    }
  }
  if (fault_) {
    // Brake from the last output velocity at the slave's acceleration, then hold.
    const double step = std::isfinite(limits_.acceleration) ? limits_.acceleration * T : std::fabs(prev_v_);
    const double v = prev_v_ > 0 ? std::max(0.0, prev_v_ - step) : std::min(0.0, prev_v_ + step);
    out_.acceleration_inc_per_s2 = (v - prev_v_) / T;
    out_.velocity_inc_per_s = v;
    out_.position = prev_y_ + v * T;
    out_.faulted = true;
  }
  first_ = false;
  prev_y_ = out_.position;
  prev_v_ = out_.velocity_inc_per_s;
  out_.position_inc = static_cast<std::int64_t>(std::floor(out_.position + 0.5));
  return out_;
}

}  // namespace hil::motion
