// SPDX-License-Identifier: MIT
#include "hil/drives/stepdir/transport_factory.hpp"

#include <fmt/format.h>

#include "hil/core/forwarding_drive.hpp"
#include "hil/drives/stepdir/axis.hpp"
#include "hil/drives/stepdir/stepdir_drive.hpp"
#include "hil/gpio/linux/gpiod_lines.hpp"

namespace hil::drives::stepdir {

namespace {

/// The drive the factory hands out: the StepDirDrive holding its Axis (lines, sink, writer), so the
/// drive goes before them; its fault injection passes through.
class AxisDrive final : public ForwardingDrive, public FaultInjectable {
 public:
  using ForwardingDrive::ForwardingDrive;
  [[nodiscard]] std::vector<std::string> injectable_faults() const override {
    return inner_faults()->injectable_faults();
  }
  bool inject_fault(std::string_view name, bool active) override { return inner_faults()->inject_fault(name, active); }
};

}  // namespace

using hil::stepdir::Ip247Ramp;

void VerifyingSink::output(std::span<const gpio::Edge> edges) noexcept {
  verifier.feed(edges);
  if (next) next->output(edges);
}

StepDirTransportFactory::StepDirTransportFactory() = default;
StepDirTransportFactory::~StepDirTransportFactory() = default;

std::expected<DrivePtr, ConfigError> StepDirTransportFactory::make_drive(const std::string& axis_name,
                                                                         const YAML::Node& drive_node,
                                                                         RunEnvironment& env) {
  verify_ = verify_ || env.verify_edge_streams;
  auto cfg = parse_stepdir_config(drive_node, hil::yaml::Where{env.source_file, env.drive_path(axis_name)});
  if (!cfg) return std::unexpected(cfg.error());
  auto ramp = Ip247Ramp::make(cfg->ramp, cfg->timing.min_period_ns());
  if (!ramp) return std::unexpected(ConfigError{env.source_file, 0, 0, "drive", "ramp table could not be generated"});
  auto axis = std::make_shared<Axis>(cfg->timing);
  axis->name = axis_name;
  std::vector<gpio::LineSpec> outs{cfg->step, cfg->dir};
  if (cfg->enable) outs.push_back(*cfg->enable);
  std::vector<gpio::LineSpec> ins;
  for (const auto* s : {&cfg->ready, &cfg->limit_start, &cfg->limit_end, &cfg->reference}) {
    if (*s) ins.push_back(**s);
  }
  gpio::LineBank* out_bank = nullptr;
  gpio::LineBank* in_bank = nullptr;
  if (!cfg->chip) {
    axis->mock_out = std::make_unique<gpio::mock::MockLines>(outs, env.clock);
    axis->mock_out->set_record_limit(1u << 20);
    axis->mock_in = std::make_unique<gpio::mock::MockLines>(ins, env.clock);
    axis->decoder =
        std::make_unique<gpio::mock::StepDirDecoder>(*axis->mock_out, out_step, out_dir, !cfg->timing.step_idle_level(),
                                                     cfg->timing.dir_forward_level, cfg->mock.initial_position);
    axis->wire_mock_switches(*cfg);
    axis->sink.next = axis->mock_out.get();
    out_bank = axis->mock_out.get();
    in_bank = axis->mock_in.get();
  } else {
    auto o = gpio::linux_gpiod::GpiodLines::open(*cfg->chip, outs, "hilbridge-" + axis_name);
    if (!o)
      return std::unexpected(
          ConfigError{env.source_file, 0, 0, env.drive_path(axis_name) + ".lines", o.error().message});
    axis->real_out = std::move(*o);
    if (!ins.empty()) {
      auto i = gpio::linux_gpiod::GpiodLines::open(*cfg->chip, ins, "hilbridge-" + axis_name);
      if (!i)
        return std::unexpected(
            ConfigError{env.source_file, 0, 0, env.drive_path(axis_name) + ".lines", i.error().message});
      axis->real_in = std::move(*i);
      in_bank = axis->real_in.get();
    }
    gpio::EdgeWriterOptions wo;
    wo.spin_window = cfg->writer_spin;
    wo.late_threshold = cfg->writer_late;
    wo.realtime_priority = cfg->writer_rt_priority;
    axis->writer = std::make_unique<gpio::AsyncEdgeWriter>(*axis->real_out, axis->steady, wo);
    axis->late_us = static_cast<double>(cfg->writer_late.count()) / 1000.0;
    // Map the run's timeline onto the writer's steady clock.
    axis->writer->set_time_offset(axis->steady.now().time_since_epoch().count() -
                                  env.clock.now().time_since_epoch().count());
    axis->sink.next = axis->writer.get();
    out_bank = axis->real_out.get();
  }
  auto drive = std::make_unique<StepDirDrive>(fmt::format("stepdir:{}", axis_name), *cfg,
                                              std::make_shared<const Ip247Ramp>(std::move(*ramp)), *out_bank, in_bank,
                                              axis->sink);
  if (axis->mock_in) {
    Axis* a = axis.get();
    drive->set_fault_injector(
        {"not_ready", "limit_start", "limit_end", "broken_wire_start", "broken_wire_end", "cam_stuck"},
        [a](std::string_view n, bool on) { return a->inject(n, on); });
  }
  axis->drive = drive.get();
  axes_.push_back(axis);
  return std::make_unique<AxisDrive>(std::move(drive), std::move(axis));
}

TransportReport StepDirTransportFactory::finish(const CycleTime&) {
  TransportReport rep;
  for (const auto& a : axes_) {
    if (a->writer && !a->writer->drain(std::chrono::seconds(10))) {
      rep.lines.push_back(fmt::format("{}: edge writer did not drain within 10 s", a->name));
      rep.ok = false;
    }
    const auto& st = a->sink.verifier.stats();
    std::string line = fmt::format("{}: {} steps out (net {:+}, backlash {}), fastest {:.1f} Hz", a->name,
                                   st.steps_forward + st.steps_backward, st.net_steps(),
                                   a->drive ? a->drive->planner().backlash_steps_total() : 0, st.max_frequency_hz());
    if (a->drive && a->drive->lag_cycles()) line += fmt::format(", lagging in {} cycles", a->drive->lag_cycles());
    if (const auto& v = a->sink.verifier.first_violation()) {
      line += fmt::format("; timing VIOLATION: {}", v->describe());
      if (verify_) rep.ok = false;
    } else {
      line += "; timing rules held";
    }
    rep.lines.push_back(std::move(line));
    if (a->mock_out && !a->mock_out->errors().empty()) {
      rep.lines.push_back(fmt::format("{}: mock lines: {}", a->name, a->mock_out->errors().front()));
      rep.ok = false;
    }
    if (a->writer) {
      const auto ws = a->writer->stats();
      rep.lines.push_back(fmt::format(
          "{}: writer: {} edges, {} late (> {} us), error mean {:.1f} us, p99 <= {:.1f} us, max {:.1f} us, max slip "
          "{:.1f} us, {} I/O errors",
          a->name, ws.edges, ws.late, a->late_us, ws.mean_error_ns() / 1000.0,
          static_cast<double>(ws.quantile_bound_ns(0.99)) / 1000.0, static_cast<double>(ws.max_error_ns) / 1000.0,
          static_cast<double>(ws.max_slip_ns) / 1000.0, ws.io_errors));
      if (ws.io_errors) rep.ok = false;
      if (auto ec = a->writer->realtime_error()) {
        rep.lines.push_back(
            fmt::format("{}: writer: SCHED_FIFO refused ({}); ran with normal scheduling", a->name, ec.message()));
      }
    }
  }
  return rep;
}

}  // namespace hil::drives::stepdir
