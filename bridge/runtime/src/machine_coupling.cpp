// SPDX-License-Identifier: MIT
// Couplings of a machine: scaling user units to increments, stepping each coupling just before
// its slave's update, and the `couple:` step (docs/coupling.md, docs/scenarios.md "Coupling").
#include "hil/runtime/machine_coupling.hpp"

#include <cmath>
#include <limits>
#include <numeric>

#include <fmt/format.h>

#include "hil/runtime/machine.hpp"

namespace hil::runtime {
namespace {

// Round a scaled value that must be whole (a periodic table's length and lift).
std::optional<double> whole(double v) {
  const double r = std::round(v);
  if (std::fabs(v - r) > 1e-6 * std::max(1.0, std::fabs(v))) return std::nullopt;
  return r;
}

bool at_rest(const motion::AxisStatus& st) {
  return st.state == motion::AxisState::standstill || st.state == motion::AxisState::moving;
}

}  // namespace

std::int64_t MachineCoupling::master_to_inc(double units) const noexcept {
  return static_cast<std::int64_t>(
      std::llround(units * static_cast<double>(master_num) / static_cast<double>(master_den)));
}

std::optional<ConfigError> MachineCouplings::build(const Scenario& scenario, const std::vector<MachineAxis>& axes) {
  scenario_ = &scenario;
  by_axis_.assign(axes.size(), nullptr);
  for (const auto& m : scenario.masters) {
    MachineMaster mm;
    mm.spec = &m;
    mm.inc_per_unit = static_cast<double>(m.inc_per_unit_num) / static_cast<double>(m.inc_per_unit_den);
    masters_.push_back(std::move(mm));
  }
  auto axis_index = [&](const std::string& name) -> std::optional<std::size_t> {
    for (std::size_t i = 0; i < axes.size(); ++i)
      if (axes[i].spec->name == name) return i;
    return std::nullopt;
  };
  for (const auto& spec : scenario.couplings) {
    auto c = std::make_unique<MachineCoupling>();
    c->spec = &spec;
    const auto si = axis_index(spec.slave);
    if (!si)
      return ConfigError{scenario.file, spec.source.line, 0, spec.source.path + ".slave",
                         fmt::format("unknown axis '{}'", spec.slave)};
    c->slave = *si;
    const AxisSpec& sa = *axes[*si].spec;
    const std::int64_t sg = std::gcd(sa.inc_per_unit_num, sa.inc_per_unit_den);
    c->slave_num = sa.inc_per_unit_num / sg;
    c->slave_den = sa.inc_per_unit_den / sg;
    switch (spec.source_kind) {
      case MasterSource::time:
        c->master_num = 1'000'000;  // master units = seconds, increments = microseconds
        c->master_den = 1;
        break;
      case MasterSource::axis_command:
      case MasterSource::axis_actual: {
        c->master_axis = axis_index(spec.master);
        const AxisSpec& ma = *axes[*c->master_axis].spec;
        const std::int64_t g = std::gcd(ma.inc_per_unit_num, ma.inc_per_unit_den);
        c->master_num = ma.inc_per_unit_num / g;
        c->master_den = ma.inc_per_unit_den / g;
        break;
      }
      case MasterSource::virtual_axis:
        for (std::size_t i = 0; i < masters_.size(); ++i)
          if (masters_[i].spec->name == spec.master) {
            c->master_virtual = i;
            const std::int64_t g = std::gcd(masters_[i].spec->inc_per_unit_num, masters_[i].spec->inc_per_unit_den);
            c->master_num = masters_[i].spec->inc_per_unit_num / g;
            c->master_den = masters_[i].spec->inc_per_unit_den / g;
          }
        break;
    }
    const double sipu = static_cast<double>(c->slave_num) / static_cast<double>(c->slave_den);
    const double mipu = static_cast<double>(c->master_num) / static_cast<double>(c->master_den);
    motion::SlaveLimits lim;
    lim.velocity = (spec.velocity > 0 ? spec.velocity : sa.max_velocity) * sipu;
    lim.acceleration = (spec.acceleration > 0 ? spec.acceleration : sa.max_acceleration) * sipu;
    lim.acceleration_filter_cycles = spec.acceleration_filter_cycles;
    lim.following_error_window = spec.following_error * sipu;
    c->coupling = motion::Coupling(spec.slave, lim);
    for (const auto& cam : scenario.cams) {
      motion::CamTableSpec t = cam.table;
      for (auto& p : t.points) {
        p.x *= mipu;
        p.y *= sipu;
      }
      t.start_slope *= sipu / mipu;
      t.end_slope *= sipu / mipu;
      std::string why;
      if (t.periodic) {
        auto& last = t.points.back();
        const auto x = whole(last.x), y = whole(last.y);
        if (!x || !y)
          why = fmt::format(
              "cam '{}' is periodic but its last point is not whole increments for coupling '{}' ({} x {} "
              "master inc, {} slave inc)",
              cam.name, spec.slave, last.x, last.y, last.y);
        else {
          last.x = *x;
          last.y = *y;
        }
      }
      std::optional<motion::CamTable> table;
      if (why.empty()) {
        auto made = motion::CamTable::make(t);
        if (made)
          table = std::move(*made);
        else
          why = fmt::format("cam '{}' for coupling '{}': {}", cam.name, spec.slave, made.error());
      }
      c->cams.push_back(std::move(table));
      c->cam_errors.push_back(std::move(why));
    }
    by_axis_[c->slave] = c.get();
    couplings_.push_back(std::move(c));
  }
  return std::nullopt;
}

void MachineCouplings::begin_cycle(const CycleTime& cycle) noexcept {
  for (auto& m : masters_) m.master.update(cycle.period);
  for (auto& c : couplings_)
    if (c->spec->source_kind == MasterSource::time) c->time.update(cycle.period);
}

std::int64_t MachineCouplings::master_position(MachineCoupling& c, const std::vector<MachineAxis>& axes) noexcept {
  switch (c.spec->source_kind) {
    case MasterSource::axis_command:
      return axes[*c.master_axis].axis->status().command_inc;
    case MasterSource::axis_actual:
      return axes[*c.master_axis].axis->status().position_inc;
    case MasterSource::virtual_axis:
      return masters_[*c.master_virtual].master.position();
    case MasterSource::time:
      return c.time.position();
  }
  return 0;
}

void MachineCouplings::before_axis(std::size_t index, std::vector<MachineAxis>& axes, const CycleTime& cycle) noexcept {
  if (index >= by_axis_.size() || !by_axis_[index]) return;
  MachineCoupling& c = *by_axis_[index];
  const std::int64_t m = master_position(c, axes);
  c.master_inc = m;
  c.plot_master = c.master_units(m);
  motion::Axis& axis = *axes[index].axis;
  if (!c.active) {
    c.plot_slave = axis.status().command_position;
    c.plot_cam = NAN;
    return;
  }
  const auto& out = c.coupling.update(m, cycle.period, axis.status().position_inc);
  c.plot_slave =
      static_cast<double>(out.position_inc) * static_cast<double>(c.slave_den) / static_cast<double>(c.slave_num);
  c.plot_cam = c.coupling.law() == motion::Coupling::Law::cam && c.coupling.cam().table()
                   ? c.master_units(static_cast<std::int64_t>(c.coupling.cam().table_position()))
                   : NAN;
  if (c.coupling.faulted()) {
    axis.raise_fault(c.coupling.fault());
    c.active = false;
    return;
  }
  if (axis.follow(out.position_inc, out.velocity_inc_per_s, out.acceleration_inc_per_s2)) c.active = false;
}

MachineCoupling* MachineCouplings::find(const std::string& slave) noexcept {
  for (auto& c : couplings_)
    if (c->spec->slave == slave) return c.get();
  return nullptr;
}

MachineMaster* MachineCouplings::find_master(const std::string& name) noexcept {
  for (auto& m : masters_)
    if (m.spec->name == name) return &m;
  return nullptr;
}

std::string MachineCouplings::command(const CoupleStep& step, std::vector<MachineAxis>& axes) {
  using Action = CoupleStep::Action;
  if (step.action == Action::master_velocity) {
    MachineMaster* mm = find_master(step.slave);
    if (!mm) return fmt::format("unknown virtual master '{}'", step.slave);
    mm->target_velocity_inc = step.velocity * mm->inc_per_unit;
    mm->master.set_velocity(mm->target_velocity_inc, step.acceleration * mm->inc_per_unit);
    return {};
  }
  MachineCoupling* c = find(step.slave);
  if (!c) return fmt::format("axis '{}' is not the slave of a coupling", step.slave);
  motion::Axis& axis = *axes[c->slave].axis;
  motion::Coupling& k = c->coupling;
  const auto law = k.law();
  const std::optional<std::int64_t> at =
      step.at ? std::optional<std::int64_t>(c->master_to_inc(*step.at)) : std::nullopt;
  auto activate = [&]() -> std::string {
    if (c->active) return {};
    if (!at_rest(axis.status()))
      return fmt::format("slave axis '{}' must be enabled and not in error to couple (state {})", step.slave,
                         motion::to_string(axis.status().state));
    if (k.faulted()) k.reset(master_position(*c, axes));
    const std::int64_t m = master_position(*c, axes);
    k.cam().set_table(nullptr);
    k.use(motion::Coupling::Law::none);
    k.start(m, axis.status().command_inc);
    c->master_inc = m;
    c->active = true;
    return {};
  };
  switch (step.action) {
    case Action::gear: {
      if (c->active && law == motion::Coupling::Law::cam)
        return fmt::format("axis '{}' runs a cam: disengage it before engaging a gear", step.slave);
      using i128 = motion::i128;
      i128 n = static_cast<i128>(step.ratio_num) * c->slave_num * c->master_den;
      i128 d = static_cast<i128>(step.ratio_den) * c->slave_den * c->master_num;
      i128 a = n < 0 ? -n : n, b = d;
      while (b != 0) {
        const i128 r = a % b;
        a = b;
        b = r;
      }
      if (a != 0) {
        n /= a;
        d /= a;
      }
      const motion::GearRatio r{static_cast<std::int64_t>(n), static_cast<std::int64_t>(d)};
      if (n > motion::max_gear_term || n < -motion::max_gear_term || d > motion::max_gear_term || !motion::valid(r))
        return fmt::format("gear ratio {}/{} is {}/{} in increments: numerator and denominator must stay within 2^31",
                           step.ratio_num, step.ratio_den, static_cast<long long>(n), static_cast<long long>(d));
      const std::int64_t ramp = c->master_to_inc(step.ramp);
      if (auto e = activate(); !e.empty()) return e;
      k.use(motion::Coupling::Law::gear);
      if (auto ec = k.gear().change({r, ramp, at}))
        return fmt::format("gear change rejected ({}): a ratio ramp is still running or the ramp is too long",
                           ec.message());
      return {};
    }
    case Action::cam: {
      std::size_t idx = 0;
      while (idx < scenario_->cams.size() && scenario_->cams[idx].name != step.cam) ++idx;
      if (idx >= c->cams.size() || !c->cams[idx]) return c->cam_errors.at(idx);
      const motion::CamTable* table = &*c->cams[idx];
      if (c->active && law == motion::Coupling::Law::gear)
        return fmt::format("axis '{}' is geared: disengage it before starting a cam", step.slave);
      if (!c->active) {
        if (auto e = activate(); !e.empty()) return e;
        k.use(motion::Coupling::Law::cam);
        if (at) {
          k.cam().queue({table, at});
        } else {
          k.cam().set_table(table);
          k.cam().start(c->master_inc, static_cast<double>(axis.status().command_inc), c->master_to_inc(step.phase));
        }
      } else {
        k.cam().queue({table, at});  // switch at the table end or at `at`
      }
      return {};
    }
    case Action::disengage:
      if (!c->active) return fmt::format("axis '{}' is not coupled", step.slave);
      if (law == motion::Coupling::Law::gear) {
        if (auto ec = k.gear().disengage(c->master_to_inc(step.ramp), at))
          return fmt::format("disengage rejected ({}): a ratio ramp is still running", ec.message());
      } else if (law == motion::Coupling::Law::cam) {
        k.cam().queue({nullptr, at.value_or(c->master_inc)});  // without `at`: at once
      }
      return {};
    case Action::superimpose: {
      if (!c->active) return fmt::format("axis '{}' is not coupled: a superimposed move needs a coupling", step.slave);
      const double sipu = static_cast<double>(c->slave_num) / static_cast<double>(c->slave_den);
      if (auto ec = k.superimposed().move_by(
              step.distance * sipu,
              motion::Limits{step.velocity * sipu, step.acceleration * sipu, std::numeric_limits<double>::infinity()}))
        return fmt::format("superimposed move rejected: {}", ec.message());
      return {};
    }
    case Action::master_velocity:
      break;
  }
  return {};
}

bool MachineCouplings::done(const CoupleStep& step, std::vector<MachineAxis>& axes) {
  using Action = CoupleStep::Action;
  if (step.action == Action::master_velocity) {
    MachineMaster* mm = find_master(step.slave);
    return mm && mm->master.velocity() == mm->target_velocity_inc;
  }
  MachineCoupling* c = find(step.slave);
  if (!c) return true;
  const motion::Coupling& k = c->coupling;
  switch (step.action) {
    case Action::gear:
      return c->active && k.gear().phase() == motion::GearPhase::steady && k.gear().engaged();
    case Action::cam:
      return c->active && k.cam().table() != nullptr && !k.cam().switch_pending();
    case Action::disengage: {
      if (!c->active) return true;
      const bool idle = k.law() == motion::Coupling::Law::gear
                            ? k.gear().phase() == motion::GearPhase::steady && !k.gear().engaged()
                            : k.cam().table() == nullptr && !k.cam().switch_pending();
      if (!idle || k.superimposed().busy()) return false;
      c->active = false;  // the slave stands: hand it back as a normal axis
      (void)axes[c->slave].axis->stop();
      return true;
    }
    case Action::superimpose:
      return !c->active || !k.superimposed().busy();
    case Action::master_velocity:
      break;
  }
  return true;
}

}  // namespace hil::runtime
