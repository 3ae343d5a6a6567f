// SPDX-License-Identifier: MIT
// The controller part of the Machine: building the scenario's controller, taking the axes'
// configuration from it, binding the axes and attaching the scenario's I/O stimuli.
#include <algorithm>
#include <memory>

#include <fmt/format.h>

#include "hil/controllers/amkasyn/amkasyn_controller.hpp"
#include "hil/controllers/clm14/runtime_controller.hpp"
#include "hil/controllers/drive_io.hpp"
#include "hil/controllers/elg/elg_controller.hpp"
#include "hil/controllers/io_stimulus.hpp"
#include "hil/controllers/parameter_controller.hpp"
#include "hil/controllers/s5/ip247_controller.hpp"
#include "hil/controllers/s5/wf725_controller.hpp"
#include "hil/runtime/condition.hpp"
#include "hil/runtime/machine.hpp"

namespace hil::runtime {

std::optional<ConfigError> Machine::build_controller(const Scenario& scenario,
                                                     const controllers::ControllerRegistry* registry) {
  const ControllerBlock& b = *scenario.controller;
  controllers::ControllerSpec spec;
  spec.device = b.device;
  spec.parameters = b.parameters;
  for (const auto& p : b.programs) spec.programs.emplace_back(p);
  for (const auto& [k, v] : b.options) spec.options.emplace(k, v);
  spec.cycle = b.cycle;
  spec.file = scenario.file;
  spec.line = b.source.line;
  controllers::ControllerRegistry builtin;
  if (registry == nullptr) {
    builtin = controllers::builtin_controllers();
    // clm14: with programs the CLM1.4 model runs them (issue 15); without, the parameter-only
    // controller configures the axes (issue 14) and names its generic signals.
    auto programs = std::make_shared<controllers::ControllerRegistry>();
    controllers::clm14::register_clm14(*programs);
    auto parameters = std::make_shared<controllers::ControllerRegistry>(controllers::builtin_controllers());
    builtin.add("clm14", [programs, parameters](const controllers::ControllerSpec& s) {
      return s.programs.empty() ? parameters->create(s) : programs->create(s);
    });
    // ip247: with programs, an interface DB or PLC DBs the module runs (its modes and programs, commanded
    // through the interface DB by `plc:` steps, issue 19); without, the parameter-only controller.
    auto module = std::make_shared<controllers::ControllerRegistry>();
    controllers::s5::register_ip247(*module);
    builtin.add("ip247", [module, parameters](const controllers::ControllerSpec& s) {
      const bool module_keys = s.options.contains("interface_db") || s.options.contains("plc_dbs");
      return s.programs.empty() && !module_keys ? parameters->create(s) : module->create(s);
    });
    controllers::elg::register_elg(builtin);
    controllers::amkasyn::register_amkasyn(builtin);
    // wf725-726: with programs or the DB-axis keys the WF module model runs (issue 19); without,
    // the parameter-only controller configures the axis the scenario commands.
    auto wf_module = std::make_shared<controllers::ControllerRegistry>();
    controllers::s5::register_wf725(*wf_module);
    builtin.add("wf725-726", [wf_module, parameters](const controllers::ControllerSpec& s) {
      return controllers::s5::wf725_wants_module(s) ? wf_module->create(s) : parameters->create(s);
    });
    registry = &builtin;
  }
  auto created = registry->create(spec);
  if (!created) return created.error();
  controller_ = std::move(*created);
  const auto fail = [&](std::string key, std::string message) {
    return ConfigError{scenario.file, b.source.line, 0, std::move(key), std::move(message)};
  };
  const Duration cycle = controller_->cycle_period();
  if (cycle < scenario.period || cycle % scenario.period != Duration::zero()) {
    return fail("controller.cycle",
                fmt::format("the {} controller cycle {:.3f} ms is not a whole multiple of the scenario period "
                            "{:.3f} ms: set 'period:' to a divisor of it or give 'controller: {{cycle: ...}}'",
                            b.device, to_seconds(cycle) * 1e3, to_seconds(scenario.period) * 1e3));
  }
  controller_every_ = static_cast<std::uint64_t>(cycle / scenario.period);

  std::string names;
  for (const auto& ca : controller_->axis_specs()) names += (names.empty() ? "" : ", ") + ca.name;
  for (const auto& ca : controller_->axis_specs()) {
    const AxisSpec* s = scenario.find_axis(ca.name);
    if (s == nullptr) {
      return fail("machine.axes", fmt::format("the {} parameter file {} defines axis '{}': add it under machine.axes "
                                              "with its drive (- name: {}\n    drive: {{transport: sim}})",
                                              b.device, b.parameters, ca.name, ca.name));
    }
    if (!s->from_controller) {
      return ConfigError{scenario.file, s->source.line, 0, s->source.path,
                         fmt::format("axis '{}' is an axis of the {} controller: its scaling, limits and "
                                     "supervision come from {}; give it only name, units and drive",
                                     ca.name, b.device, b.parameters)};
    }
    auto copy = std::make_unique<AxisSpec>(*s);
    if (!s->units.empty() && s->units != "mm") {
      copy->units = s->units;
    } else {
      copy->units = ca.units;
    }
    copy->rotary = ca.config.rotary;
    copy->modulo = ca.config.modulo;
    copy->inc_per_unit_num = ca.config.inc_per_unit.num;
    copy->inc_per_unit_den = ca.config.inc_per_unit.den;
    copy->max_velocity = ca.config.limits.velocity;
    copy->max_acceleration = ca.config.limits.acceleration;
    copy->soft_limit_min = ca.config.soft_limit_min;
    copy->soft_limit_max = ca.config.soft_limit_max;
    copy->backlash = ca.config.backlash;
    copy->in_position_window = ca.config.in_position_window;
    copy->standstill_window = ca.config.standstill_window;
    controller_specs_.push_back(std::move(copy));
  }
  for (const auto& s : scenario.axes) {
    if (!s.from_controller) continue;
    const bool known =
        std::ranges::any_of(controller_->axis_specs(), [&](const auto& ca) { return ca.name == s.name; });
    if (!known) {
      return ConfigError{scenario.file, s.source.line, 0, s.source.path,
                         fmt::format("axis '{}' has no inc_per_unit and limits, and the {} controller has no axis "
                                     "of that name (it has: {})",
                                     s.name, b.device, names.empty() ? "none" : names)};
    }
  }
  return std::nullopt;
}

const AxisSpec& Machine::controller_spec(const AxisSpec& spec) const noexcept {
  if (!spec.from_controller) return spec;
  for (const auto& s : controller_specs_)
    if (s->name == spec.name) return *s;
  return spec;
}

std::expected<motion::AxisConfig, ConfigError> Machine::controller_axis_config(const AxisSpec& spec,
                                                                               const std::string& file) const {
  for (const auto& ca : controller_->axis_specs()) {
    if (ca.name != spec.name) continue;
    auto v = motion::validate(ca.config);
    if (!v) {
      return std::unexpected(ConfigError{file, spec.source.line, 0, spec.source.path,
                                         fmt::format("the {} parameters give axis '{}' a configuration the motion "
                                                     "core rejects: {}",
                                                     controller_->device(), spec.name, v.error())});
    }
    return *v;
  }
  return std::unexpected(ConfigError{file, spec.source.line, 0, spec.source.path, "not a controller axis"});
}

std::optional<ConfigError> Machine::bind_controller(const Scenario& scenario) {
  std::vector<motion::Axis*> axes;
  controller_axis_.assign(axes_.size(), -1);
  for (const auto& ca : controller_->axis_specs()) {
    MachineAxis* a = find(ca.name);
    if (a == nullptr)
      return ConfigError{scenario.file, scenario.controller->source.line, 0, "controller", "axis missing"};
    controller_axis_[static_cast<std::size_t>(a - axes_.data())] = static_cast<int>(axes.size());
    axes.push_back(a->axis.get());
  }
  if (auto r = controller_->bind_axes(axes); !r) {
    return ConfigError{scenario.file, scenario.controller->source.line, 0, "controller", r.error()};
  }
  return std::nullopt;
}

std::expected<controllers::BitAddress, ConfigError> Machine::resolve_signal(const Scenario& scenario,
                                                                            const std::string& signal,
                                                                            const SourceRef& src) const {
  auto a = controller_->resolve_bit(signal);
  if (!a) return std::unexpected(ConfigError{scenario.file, src.line, 0, src.path, a.error()});
  if (!controller_->io().contains(*a)) {
    return std::unexpected(
        ConfigError{scenario.file, src.line, 0, src.path,
                    fmt::format("'{}' is outside the {} controller's I/O image", signal, controller_->device())});
  }
  return *a;
}

void Machine::report_signal(const std::string& name, controllers::BitAddress a) {
  for (const auto& [n, addr] : io_signals_)
    if (n == name) return;
  io_signals_.emplace_back(name, a);
}

std::optional<ConfigError> Machine::attach_io(const Scenario& scenario, const Clock& clock) {
  auto& io = controller_->io();
  for (const auto& s : io.signals())
    if (s.bit) report_signal(s.name, controllers::BitAddress{s.area, s.byte, *s.bit});
  const auto resolve = [&](const std::string& signal, const SourceRef& src) {
    return resolve_signal(scenario, signal, src);
  };
  // Real I/O first: a scenario stimulus on the same bit overrides it (later sources win).
  for (const IoLink& link : scenario.io_links)
    if (auto e = attach_io_link(scenario, link, clock)) return e;
  const Duration cycle = controller_->cycle_period();
  for (const IoStimulus& st : scenario.io) {
    auto bit = resolve(st.signal, st.source);
    if (!bit) return bit.error();
    if (bit->area != controllers::IoArea::input && bit->area != controllers::IoArea::data) {
      return ConfigError{scenario.file, st.source.line, 0, st.source.path,
                         fmt::format("'{}' is a {} ({}): the scenario drives inputs (and device data bits) only",
                                     st.signal, controllers::to_string(bit->area), controllers::format_address(*bit))};
    }
    report_signal(st.signal, *bit);
    std::unique_ptr<controllers::IoSource> src;
    const Duration width = st.kind == IoStimulus::Kind::pulse && st.width == Duration::zero() ? cycle : st.width;
    switch (st.kind) {
      case IoStimulus::Kind::set:
      case IoStimulus::Kind::pulse:
        if (st.at) {
          src = std::make_unique<controllers::TimedInput>(*bit, st.value, *st.at, width);
          // The controller reads it at its next cycle after the end: run until then.
          last_stimulus_ = std::max(last_stimulus_, *st.at + width + cycle);
        } else {
          motion::Axis* ax = find(st.when->axis)->axis.get();
          src = std::make_unique<controllers::ConditionInput>(
              *bit, st.value, [ax, c = *st.when] { return condition_met(c, *ax); }, width);
        }
        break;
      case IoStimulus::Kind::cam:
        src = std::make_unique<controllers::PositionCam>(*bit, *find(st.axis)->axis, st.from, st.to, st.active_low);
        break;
      case IoStimulus::Kind::mark: {
        auto m = std::make_unique<controllers::RegistrationMark>(*bit, *find(st.axis)->axis, st.position, st.accuracy,
                                                                 st.width);
        m->reserve(1024);
        src = std::move(m);
        break;
      }
    }
    io.attach(*src);
    stimuli_.push_back(std::move(src));
  }
  if (auto e = attach_analog(scenario)) return e;
  for (const IoExpectation& e : scenario.io_expectations) {
    auto bit = resolve(e.signal, e.source);
    if (!bit) return bit.error();
    report_signal(e.signal, *bit);
  }
  for (const ControllerExpectation& e : scenario.controller_expectations) {
    if (e.kind != ControllerExpectation::Kind::value) continue;
    if (auto h = controller_->resolve_value(e.name); !h)
      return ConfigError{scenario.file, e.source.line, 0, e.source.path + ".controller", h.error()};
  }
  return std::nullopt;
}

std::optional<ConfigError> Machine::attach_analog(const Scenario& scenario) {
  // One schedule per input, its entries in file order (strictly increasing `at`).
  std::vector<std::pair<std::string, std::vector<const AnalogStimulus*>>> inputs;
  for (const AnalogStimulus& a : scenario.analog) {
    auto it = std::find_if(inputs.begin(), inputs.end(), [&](const auto& p) { return p.first == a.input; });
    if (it == inputs.end()) it = inputs.insert(inputs.end(), {a.input, {}});
    it->second.push_back(&a);
  }
  const Duration cycle = controller_->cycle_period();
  for (const auto& [name, entries] : inputs) {
    const AnalogStimulus& first = *entries.front();
    auto spec = controller_->resolve_analog(name);
    if (!spec) return ConfigError{scenario.file, first.source.line, 0, first.source.path + ".analog", spec.error()};
    std::vector<controllers::AnalogStep> steps;
    for (const AnalogStimulus* a : entries) {
      if (a->value < spec->min || a->value > spec->max)
        return ConfigError{scenario.file, a->source.line, 0, a->source.path + ".value",
                           fmt::format("{} {} is outside the input {}'s range {} .. {} {}", a->value, spec->unit, name,
                                       spec->min, spec->max, spec->unit)};
      if (!steps.empty() && a->at <= steps.back().at)
        return ConfigError{scenario.file, a->source.line, 0, a->source.path + ".at",
                           fmt::format("the entries of analog input {} must come in increasing time", name)};
      steps.push_back({a->at, a->value, a->ramp});
    }
    auto src = std::make_unique<controllers::AnalogSchedule>(*controller_, spec->handle, std::move(steps));
    // The controller samples the last value at its next cycle: run until then.
    last_stimulus_ = std::max(last_stimulus_, src->last_change() + cycle);
    controller_->io().attach(*src);
    stimuli_.push_back(std::move(src));
  }
  return std::nullopt;
}

std::optional<ConfigError> Machine::attach_io_link(const Scenario& scenario, const IoLink& link, const Clock& clock) {
  // Each signal resolves to a bit of the areas its direction allows; it is then reported like io: signals.
  const ResolveLinkBit resolve = [&](const IoLinkBit& b,
                                     bool input) -> std::expected<controllers::BitAddress, ConfigError> {
    auto a = resolve_signal(scenario, b.signal, b.source);
    if (!a) return a;
    using controllers::IoArea;
    const bool ok = input ? a->area == IoArea::input || a->area == IoArea::data
                          : a->area == IoArea::output || a->area == IoArea::marker;
    if (!ok) {
      return std::unexpected(ConfigError{
          scenario.file, b.source.line, 0, b.source.path,
          fmt::format("'{}' is a {} bit ({}): a link's {} are {} bits", b.signal, controllers::to_string(a->area),
                      controllers::format_address(*a), input ? "inputs" : "outputs",
                      input ? "input (or device data)" : "output (or marker)")});
    }
    report_signal(b.signal, *a);
    return a;
  };
  if (const auto* d = std::get_if<DriveLinkDevice>(&link.device)) return make_drive_link(scenario, link, *d, resolve);
  if (const auto* g = std::get_if<GpioLinkDevice>(&link.device))
    return make_gpio_link(scenario, link, *g, clock, resolve);
  if (const auto* m = std::get_if<ModbusLinkDevice>(&link.device)) return make_modbus_link(scenario, link, *m, resolve);
  return std::nullopt;
}

std::optional<ConfigError> Machine::make_gpio_link(const Scenario& scenario, const IoLink& link,
                                                   const GpioLinkDevice& device, const Clock& clock,
                                                   const ResolveLinkBit& resolve) {
  controllers::GpioLinkConfig config;
  config.chip = device.chip;
  config.consumer = device.consumer;
  const auto lines = [&](const std::vector<IoLinkBit>& bits, bool input,
                         std::vector<controllers::GpioLinkLine>& out) -> std::optional<ConfigError> {
    for (const IoLinkBit& b : bits) {
      auto a = resolve(b, input);
      if (!a) return a.error();
      const auto& g = std::get<GpioLinkBit>(b.where);
      out.push_back(
          {b.signal, g.offset, g.name, *a, g.active_low, gpio::parse_bias(g.bias).value_or(gpio::Bias::as_is), g.mock});
    }
    return std::nullopt;
  };
  if (auto e = lines(link.inputs, true, config.inputs)) return e;
  if (auto e = lines(link.outputs, false, config.outputs)) return e;
  auto opened = controllers::GpioLink::open(std::move(config), clock);
  if (!opened) {
    return ConfigError{scenario.file, link.source.line, 0, link.source.path + ".gpio",
                       fmt::format("cannot open the GPIO lines: {}", opened.error())};
  }
  auto& io = controller_->io();
  if (auto* src = (*opened)->source()) io.attach(*src);
  if (auto* sink = (*opened)->sink()) io.attach(*sink);
  gpio_links_.push_back(GpioLinkEntry{link.source.path, std::move(*opened)});
  return std::nullopt;
}

std::optional<ConfigError> Machine::make_drive_link(const Scenario& scenario, const IoLink& link,
                                                    const DriveLinkDevice& device, const ResolveLinkBit& resolve) {
  const auto it = std::ranges::find_if(axes_, [&](const MachineAxis& a) { return a.spec->name == device.axis; });
  if (it == axes_.end()) {
    std::string names;
    for (const auto& a : axes_) names += (names.empty() ? "" : ", ") + a.spec->name;
    return ConfigError{scenario.file, link.source.line, 0, link.source.path + ".drive",
                       fmt::format("unknown axis '{}': the machine's axes are {}", device.axis, names)};
  }
  motion::Axis& axis = *it->axis;
  const auto caps = axis.drive().capabilities();
  const auto fail = [&](const IoLinkBit& b, std::string message) {
    return ConfigError{scenario.file, b.source.line, 0, b.source.path, std::move(message)};
  };
  std::vector<controllers::DriveIoBit> inputs, outputs;
  for (const IoLinkBit& b : link.inputs) {
    const unsigned n = std::get<DriveLinkBit>(b.where).bit;
    if (!caps.digital_inputs)
      return fail(b, fmt::format("the drive of axis {} ({}) has no digital inputs (CiA 402 0x60FD): a canopen drive "
                                 "needs 0x60FD in its EDS, a sim drive has them always, see docs/canopen.md",
                                 device.axis, axis.drive().name()));
    auto a = resolve(b, true);
    if (!a) return a.error();
    inputs.push_back({static_cast<std::uint8_t>(n), *a});
  }
  std::uint32_t used = 0;  // the bits earlier links of this axis drive
  for (const auto& [name, bits] : drive_output_bits_)
    if (name == device.axis) used |= bits;
  std::uint32_t mine = 0;
  for (const IoLinkBit& b : link.outputs) {
    const unsigned n = std::get<DriveLinkBit>(b.where).bit;
    const std::uint32_t mask = 1U << n;
    if ((caps.digital_output_mask & mask) == 0)
      return fail(b, fmt::format("bit {} is not among the digital outputs the drive of axis {} ({}) applies (mask "
                                 "0x{:08X}){}",
                                 n, device.axis, axis.drive().name(), caps.digital_output_mask,
                                 caps.digital_output_mask == 0
                                     ? ": it has no digital outputs (a canopen drive needs 0x60FE:1 in its EDS)"
                                     : "; a canopen drive's `output_mask` (0x60FE:2) sets them"));
    if ((used & mask) != 0 || (mine & mask) != 0)
      return fail(b, fmt::format("drive bit {} of axis {} is already driven by another output", n, device.axis));
    mine |= mask;
    auto a = resolve(b, false);
    if (!a) return a.error();
    outputs.push_back({static_cast<std::uint8_t>(n), *a});
  }
  drive_output_bits_.emplace_back(device.axis, mine);
  auto& io = controller_->io();
  if (!inputs.empty()) {
    drive_inputs_.push_back(std::make_unique<controllers::DriveInputs>(axis, std::move(inputs)));
    io.attach(*drive_inputs_.back());
  }
  if (!outputs.empty()) {
    drive_outputs_.push_back(std::make_unique<controllers::DriveOutputs>(axis, std::move(outputs)));
    io.attach(*drive_outputs_.back());
  }
  return std::nullopt;
}

}  // namespace hil::runtime
