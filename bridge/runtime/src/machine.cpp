// SPDX-License-Identifier: MIT
#include "hil/runtime/machine.hpp"

#include <limits>
#include <numeric>

#include <fmt/format.h>

namespace hil::runtime {

std::expected<motion::AxisConfig, ConfigError> make_axis_config(const AxisSpec& s, const std::string& file) {
  motion::AxisConfig c;
  c.name = s.name;
  const std::int64_t g = std::gcd(s.inc_per_unit_num, s.inc_per_unit_den);
  c.inc_per_unit = motion::Ratio{s.inc_per_unit_num / g, s.inc_per_unit_den / g};
  c.rotary = s.rotary;
  c.modulo = s.modulo;
  c.limits.velocity = s.max_velocity;
  c.limits.acceleration = s.max_acceleration;
  c.limits.jerk = s.max_jerk > 0.0 ? s.max_jerk : std::numeric_limits<double>::infinity();
  c.quick_stop_deceleration = s.quick_stop_deceleration;
  c.jog_velocity = s.jog_velocity;
  c.soft_limit_min = s.soft_limit_min;
  c.soft_limit_max = s.soft_limit_max;
  c.backlash = s.backlash;
  c.following_error.dynamic = s.following_error_dynamic;
  c.following_error.static_window = s.following_error_window;
  c.following_error.kv_per_s = s.following_error_kv_per_s;
  c.following_error.min_window = s.following_error_min;
  c.following_error.max_window = s.following_error_max;
  if (c.following_error.dynamic && c.following_error.static_window <= 0.0)
    c.following_error.static_window = s.following_error_max;
  c.standstill_window = s.standstill_window;
  c.in_position_window = s.in_position_window;
  if (s.in_position_timeout) c.in_position_timeout = *s.in_position_timeout;
  if (s.enable_timeout) c.enable_timeout = *s.enable_timeout;
  if (s.feedback_timeout) c.feedback_timeout = *s.feedback_timeout;
  switch (s.fault_reaction) {
    case FaultReaction::quick_stop:
      c.reaction = motion::FaultReaction::quick_stop;
      break;
    case FaultReaction::stop:
      c.reaction = motion::FaultReaction::stop;
      break;
    case FaultReaction::disable:
      c.reaction = motion::FaultReaction::disable;
      break;
  }
  auto v = motion::validate(c);
  if (!v) return std::unexpected(ConfigError{file, s.source.line, 0, s.source.path, v.error()});
  return *v;
}

std::expected<Machine, ConfigError> Machine::build(const Scenario& scenario, const TransportRegistry& registry,
                                                   RunEnvironment& env,
                                                   const controllers::ControllerRegistry* controllers) {
  Machine m;
  if (scenario.controller) {
    if (auto e = m.build_controller(scenario, controllers)) return std::unexpected(*e);
  }
  for (const AxisSpec& scenario_spec : scenario.axes) {
    const AxisSpec& spec = m.controller_spec(scenario_spec);
    const int drive_line = spec.drive.IsDefined() ? spec.drive.Mark().line + 1 : spec.source.line;
    const std::string drive_path = spec.source.path + ".drive";
    auto config =
        spec.from_controller ? m.controller_axis_config(spec, scenario.file) : make_axis_config(spec, scenario.file);
    if (!config) return std::unexpected(config.error());

    TransportFactory* factory = nullptr;
    for (auto& f : m.factories_)
      if (f.name == spec.transport) factory = f.factory.get();
    if (!factory) {
      auto created = registry.create(spec.transport);
      if (!created) {
        std::string known;
        for (const auto& n : registry.names()) known += (known.empty() ? "" : ", ") + n;
        return std::unexpected(ConfigError{scenario.file, drive_line, 0, drive_path + ".transport",
                                           fmt::format("unknown transport '{}'; this hilbridge knows: {}",
                                                       spec.transport, known.empty() ? "(none)" : known)});
      }
      factory = created.get();
      m.factories_.push_back(Factory{spec.transport, std::move(created)});
    }
    env.drive_key = drive_path;
    auto drive = factory->make_drive(spec.name, spec.drive, env);
    env.drive_key.clear();
    if (!drive) {
      ConfigError e = drive.error();
      if (e.file.empty()) e.file = scenario.file;
      if (e.line == 0) e.line = drive_line;
      return std::unexpected(e);
    }
    if (!*drive)
      return std::unexpected(ConfigError{scenario.file, drive_line, 0, drive_path,
                                         fmt::format("transport '{}' built no drive", spec.transport)});
    MachineAxis a;
    a.spec = &spec;
    a.transport = spec.transport;
    a.injectable = dynamic_cast<FaultInjectable*>(drive->get());
    a.axis = std::make_unique<motion::Axis>(std::move(*config), std::move(*drive));
    m.axes_.push_back(std::move(a));
  }
  if (auto e = m.couplings_.build(scenario, m.axes_)) return std::unexpected(*e);
  if (m.controller_) {
    if (auto e = m.bind_controller(scenario)) return std::unexpected(*e);
    if (auto e = m.attach_io(scenario, env.clock)) return std::unexpected(*e);
  }
  return m;
}

void Machine::cycle(const CycleTime& cycle) noexcept {
  for (auto& f : factories_) f.factory->begin_cycle(cycle);
  couplings_.begin_cycle(cycle);
  for (std::size_t i = 0; i < axes_.size(); ++i) {
    couplings_.before_axis(i, axes_, cycle);
    if (i < controller_axis_.size() && controller_axis_[i] >= 0)
      controller_->before_axis_update(static_cast<std::size_t>(controller_axis_[i]), cycle);
    axes_[i].axis->update(cycle);
  }
  for (auto& f : factories_) f.factory->end_cycle(cycle);
  if (controller_ && cycle_count_ % controller_every_ == 0) {
    (void)controller_->step(CycleTime{cycle.now, controller_->cycle_period()});
  }
  ++cycle_count_;
}

std::vector<NamedReport> Machine::finish(const CycleTime& cycle) {
  std::vector<NamedReport> out;
  for (auto& f : factories_) out.push_back(NamedReport{f.name, f.factory->finish(cycle)});
  return out;
}

MachineAxis* Machine::find(const std::string& name) noexcept {
  for (auto& a : axes_)
    if (a.spec->name == name) return &a;
  return nullptr;
}

std::vector<std::string> Machine::transports() const {
  std::vector<std::string> out;
  for (const auto& f : factories_) out.push_back(f.name);
  return out;
}

}  // namespace hil::runtime
