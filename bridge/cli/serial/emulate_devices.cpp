// SPDX-License-Identifier: MIT
// `hilbridge emulate clm14 | elg-tape | ip247 | wf725`.
#include <fmt/format.h>

#include <asio/io_context.hpp>
#include <expected>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <thread>

#include "emulate.hpp"
#include "emulate_machine.hpp"
#include "hil/cli/context.hpp"
#include "hil/cli/duration_option.hpp"
#include "hil/controllers/clm14/motion_axis_port.hpp"
#include "hil/controllers/elg/elg_controller.hpp"
#include "hil/controllers/parameter_file.hpp"
#include "hil/controllers/s5/ip247_follower.hpp"
#include "hil/controllers/s5/ip247_module_endpoint.hpp"
#include "hil/controllers/s5/ip247_rack.hpp"
#include "hil/core/clock.hpp"
#include "hil/core/text_file.hpp"
#include "hil/mocks/legacy/clm14_line.hpp"
#include "hil/mocks/legacy/clm14_retrofit.hpp"
#include "hil/mocks/legacy/elg_run_endpoint.hpp"
#include "hil/mocks/legacy/elg_tape_endpoint.hpp"
#include "hil/mocks/legacy/s5_block_endpoint.hpp"
#include "hil/runtime/machine.hpp"
#include "hil/runtime/scenario_loader.hpp"
#include "hil/serial/clm14/device_data.hpp"
#include "hil/serial/file_lock.hpp"
#include "hil/serial/profile_checks.hpp"
#include "hil/serial/tape/elg_tape.hpp"

namespace hil::cli::serial_cli {

namespace lg = hil::mocks::legacy;

void register_wf725_emulator(Context& ctx);  // emulate_wf725.cpp

namespace {

/// Retrofit mode: the CLM's axes 1..4 are the axes of a machine file, each on its transport
/// (CANopen, Modbus, step/dir, sim), driven once per NC cycle; axes named ME1 / ME2 are master
/// encoders 1 / 2 (lg::Clm14Retrofit).
struct Retrofit : MachineFile {
  std::optional<lg::Clm14Retrofit> ports;
};

std::expected<std::unique_ptr<Retrofit>, std::string> make_retrofit(const std::string& file,
                                                                    const TransportRegistry& registry) {
  auto loaded = load_machine<Retrofit>(file, registry, [&](const hil::runtime::Scenario& sc) {
    std::vector<std::string> names;
    for (const auto& a : sc.axes) names.push_back(a.name);
    auto roles = lg::clm14_machine_roles(names, file);
    return roles ? std::string() : roles.error();
  });
  if (!loaded) return std::unexpected(loaded.error());
  auto r = std::move(*loaded);
  std::vector<std::string> names;
  std::vector<hil::motion::Axis*> axes;
  for (auto& a : r->machine->axes()) {
    names.push_back(a.spec->name);
    axes.push_back(a.axis.get());
  }
  r->ports.emplace(axes, *lg::clm14_machine_roles(names, file));
  return r;
}

/// `emulate ip247 --machine`: the module's axes 1..3 drive the axes of a machine file (a scenario
/// with only `machine:`, axes in pulses: inc_per_unit 1), each on its transport (step/dir on a GPIO
/// chip, CANopen CSP, sim), through their cyclic set-point once per module cycle.
struct Ip247Retrofit : MachineFile {
  std::array<hil::controllers::s5::Ip247Follower, 3> followers{};
  /// The machine's time when its power sections were up (power_up_ip247_machine).
  TimePoint powered_at{};
  /// Machine time minus module time: the machine's timeline goes on from where power-up left it.
  std::optional<Duration> time_offset;
};

bool takes_setpoints(const hil::motion::Axis& a) {
  const auto st = a.status().state;
  return st == hil::motion::AxisState::standstill || st == hil::motion::AxisState::moving ||
         st == hil::motion::AxisState::stopping;
}

/// Switches the machine's power sections on before the module serves its line, as on a machine
/// whose drives are up before the PLC starts jobs: the axes are enabled and cycled on the machine
/// file's clock, in real time (a chip's reset pulse is a real 100 ms), until every one takes
/// set-points (BB high). Without it the first jobs met BB low: a step/dir drive is `enabling` for
/// its reset pulse (reset_pulse_ms) while the module already pulsed.
std::expected<void, std::string> power_up_ip247_machine(Ip247Retrofit& rf, Duration cycle, const std::string& file) {
  auto& axes = rf.machine->axes();
  for (auto& a : axes) (void)a.axis->enable();
  const TimePoint start = rf.clock.now();
  for (TimePoint t = start;; t += cycle) {
    rf.io.poll();
    rf.machine->cycle(CycleTime{t, cycle});
    bool up = true;
    for (const auto& a : axes) {
      const auto& st = a.axis->status();
      if (st.state == hil::motion::AxisState::error)
        return std::unexpected(
            fmt::format("{}: axis '{}' did not come up: {}", file, a.spec->name, st.fault.describe()));
      up = up && takes_setpoints(*a.axis);
    }
    if (up) {
      rf.powered_at = t + cycle;
      return {};
    }
    if (t - start > std::chrono::seconds(10))
      return std::unexpected(fmt::format("{}: the machine axes did not become ready within 10 s", file));
    std::this_thread::sleep_until(rf.clock.to_steady(t + cycle));
  }
}

std::expected<std::unique_ptr<Ip247Retrofit>, std::string> make_ip247_retrofit(const std::string& file,
                                                                               const TransportRegistry& registry) {
  auto loaded = load_machine<Ip247Retrofit>(file, registry, [&](const hil::runtime::Scenario& sc) {
    return sc.axes.empty() || sc.axes.size() > 3
               ? fmt::format("{}: machine.axes: give 1 to 3 axes (IP247 axes 1..3, in pulses)", file)
               : std::string();
  });
  if (!loaded) return std::unexpected(loaded.error());
  auto r = std::move(*loaded);
  for (const auto& a : r->machine->axes()) {
    if (a.axis->drive().capabilities().drive_profile)
      return std::unexpected(
          fmt::format("{}: axis '{}': its drive plans its own trajectory; the IP247's pulses are a "
                      "cyclic set-point: use a cyclic drive (stepdir profile: motion, CSP, sim)",
                      file, a.spec->name));
  }
  return r;
}

/// The module's hooks for a retrofit: BB and the limit/reference lines from the machine axes, the
/// axes following the module's pulses after every module cycle.
hil::controllers::s5::Ip247ModuleHooks ip247_retrofit_hooks(Ip247Retrofit& rf,
                                                            hil::controllers::s5::Ip247ModulePolicy& module,
                                                            Duration cycle) {
  namespace s5 = hil::controllers::s5;
  s5::Ip247ModuleHooks h;
  h.inputs = [&rf, &module](int n, s5::Ip247Inputs& in) {
    auto& axes = rf.machine->axes();
    if (static_cast<std::size_t>(n) > axes.size()) return;
    auto& ax = *axes[static_cast<std::size_t>(n - 1)].axis;
    in.ready = takes_setpoints(ax);
    if (!ax.drive().capabilities().digital_inputs) return;  // the mock switches only
    // CiA 402 0x60FD bits are "active"; the module reads raw levels and applies NO/NC itself. A
    // switch is actuated when the drive's line or the mock switch says so.
    const std::uint32_t di = ax.drive().feedback().digital_inputs;
    const auto& md = module.axis(n).machine_data();
    const bool nc = md && md->limits_normally_closed;
    const bool start = ((di & hil::digital_input::negative_limit) != 0) || (in.limit_start != nc);
    const bool end = ((di & hil::digital_input::positive_limit) != 0) || (in.limit_end != nc);
    in.limit_start = start != nc;
    in.limit_end = end != nc;
    in.reference = in.reference || (di & hil::digital_input::home_switch) != 0;
  };
  h.after_cycle = [&rf, &module, cycle](TimePoint now) {
    rf.io.poll();
    auto& axes = rf.machine->axes();
    // The module's cycles run on the line's clock; the machine's go on from its power-up (never
    // back in time), in step with the module's.
    if (!rf.time_offset) rf.time_offset = std::max(rf.clock.now(), rf.powered_at) - now;
    for (std::size_t i = 0; i < axes.size() && i < 3; ++i) {
      auto& ax = *axes[i].axis;
      if (takes_setpoints(ax)) rf.followers[i].step(ax, module.axis(static_cast<int>(i) + 1), cycle.count());
    }
    rf.machine->cycle(CycleTime{now + *rf.time_offset, cycle});
  };
  return h;
}

std::expected<lg::ClmMode, std::string> parse_mode(std::string_view s) {
  if (s == "parameter") return lg::ClmMode::parameter;
  if (s == "manual") return lg::ClmMode::manual;
  if (s == "auto" || s == "automatic") return lg::ClmMode::automatic;
  return std::unexpected(fmt::format("mode '{}' unknown: use parameter, manual or auto", s));
}

}  // namespace

void register_emulators(Context& ctx) {
  // --- CLM1.4 -------------------------------------------------------------------------------
  struct ClmOpts {
    EmulateOptions e;
    std::string mode = "manual";
    int stations = 0;
    int axes = 2;
    std::string machine;
  };
  auto co = std::make_shared<ClmOpts>();
  auto* clm = ctx.emulate.add_subcommand(
      "clm14",
      "Emulated Rexroth CLM1.4 on its serial interface: 3000 program lines, parameters (writable in Parameter mode "
      "only, "
      "validated when leaving it), variables, logic task, status queries, interface commands, RS-485 stations.");
  add_emulate_options(*clm, co->e);
  clm->add_option("--mode", co->mode, "Mode inputs at start: parameter, manual or auto")->capture_default_str();
  clm->add_option("--stations", co->stations, "0 = one RS-232 unit; 1..32 = that many RS-485 stations on the line")
      ->check(CLI::Range(0, 32))
      ->capture_default_str();
  clm->add_option("--axes", co->axes, "Axes (A1xx..A4xx parameter blocks)")
      ->check(CLI::Range(1, 4))
      ->capture_default_str();
  clm->add_option("--machine", co->machine,
                  "Retrofit mode: a machine file (scenario with machine.axes, units = the CLM's IU) whose axes 1..4 "
                  "are the CLM's axes on real-transport drives (canopen, modbus, stepdir, sim); axes named ME1 / ME2 "
                  "are master encoders 1 / 2 (their actual increments are the encoder counts)")
      ->check(CLI::ExistingFile);
  clm->footer(
      "Console commands (stdin): 'mode parameter|manual|auto' changes the mode inputs of every station, "
      "'input I1.00.0 1' sets an input bit, 'material 40' runs the material under master encoder 1 at 40 IU/s (the "
      "simulated measuring wheel, status 47), 'analog 1 5000' sets analog input AE1 to 5000 mV (status 49/45), "
      "'test-speed 10' keys in the flying cutoff test mode's speed step, "
      "'start' / 'stop' / 'clear' act like the Start input, Immediate Stop "
      "and External Clear, 'status' prints mode, run state, fault and positions per station, 'quit' stops (state "
      "is saved).\n"
      "Examples: hilbridge emulate clm14 --pty --format 7E2 --mode parameter --stations 32\n"
      "          hilbridge emulate clm14 --machine machine.yaml --port /dev/ttyUSB0   (retrofit mode)");
  clm->callback([&ctx, co] {
    auto mode = parse_mode(co->mode);
    if (!mode) {
      fmt::print(stderr, "error: --mode: {}\n", mode.error());
      ctx.exit_code = 2;
      return;
    }
    auto data = hil::serial::clm14::load_device_data();
    if (!data) {
      fmt::print(stderr, "error: device profile clm14: {}\n", data.error());
      ctx.exit_code = 2;
      return;
    }
    std::unique_ptr<Retrofit> retrofit;
    if (!co->machine.empty()) {
      if (co->stations > 1) {
        fmt::print(stderr, "error: --machine drives one unit; use --stations 0 or 1\n");
        ctx.exit_code = 2;
        return;
      }
      auto r = make_retrofit(co->machine, ctx.transports);
      if (!r) {
        fmt::print(stderr, "error: --machine: {}\n", r.error());
        ctx.exit_code = 2;
        return;
      }
      retrofit = std::move(*r);
      co->axes = std::max(co->axes, static_cast<int>(retrofit->ports->axis_count()));
    }
    lg::Clm14Line line(*data, co->stations, co->axes);
    if (retrofit) {
      auto* rf = retrofit.get();
      rf->ports->attach(line.station(0), [rf](const CycleTime& c) {
        rf->io.poll();
        rf->machine->cycle(c);
      });
    }
    const auto locked = resolve_state(co->e, "clm14");
    if (!locked) {
      fmt::print(stderr, "error: {}\n", locked.error());
      ctx.exit_code = 2;
      return;
    }
    const auto& state = *locked;
    if (auto text = read_file(state)) {
      if (auto r = line.load_state(*text); !r)
        fmt::print(stderr, "warning: {}: {}; starting from defaults\n", state.string(), r.error());
    }
    line.set_mode(*mode);
    ctx.exit_code = serve(line, co->e, state, [](lg::Endpoint& ep, const std::string& cmd) -> std::string {
      auto& l = static_cast<lg::Clm14Line&>(ep);
      if (cmd.starts_with("mode ")) {
        auto m = parse_mode(cmd.substr(5));
        if (!m) return "error: " + m.error();
        l.set_mode(*m);
        return "ok " + cmd;
      }
      namespace cc = hil::controllers::clm14;
      if (cmd.starts_with("input ")) {
        std::istringstream in(cmd.substr(6));
        std::string addr;
        int v = -1;
        in >> addr >> v;
        auto b = cc::parse_bit(addr);
        if (!b || b->byte.area != cc::Area::input || (v != 0 && v != 1))
          return "error: input ADDRESS 0|1, e.g. input I1.00.0 1";
        for (std::size_t i = 0; i < l.size(); ++i) l.station(i).controller().image().set_bit(*b, v == 1);
        return "ok " + cmd;
      }
      if (cmd.starts_with("material ") || cmd.starts_with("analog ") || cmd.starts_with("test-speed ")) {
        // the unit's hardware: the material under master encoder 1 (IU/s), an analog input
        // AE1..AE4 (mV), the flying cutoff test mode's speed step (the CTA's keys)
        std::istringstream in(cmd);
        std::string what;
        double a = 0.0, b = 0.0;
        in >> what >> a;
        const bool two = what == "analog";
        if (two) in >> b;
        if (in.fail() || !(in >> std::ws).eof())
          return "error: material IU_PER_S | analog 1..4 MILLIVOLTS | test-speed 0..31";
        if (two && (a < 1 || a > 4 || std::abs(b) > 10000)) return "error: analog 1..4 -10000..10000 (mV)";
        if (what == "test-speed" && (a < 0 || a > 31 || a != std::floor(a))) return "error: test-speed 0..31";
        for (std::size_t i = 0; i < l.size(); ++i) {
          auto& st = l.station(i);
          if (what == "material" && !st.set_material_velocity(a))
            return st.external_master_encoder() ? "error: master encoder 1 is the machine axis ME1 (--machine)"
                                                : "error: master encoder 1 is not used (C002 = 0)";
          if (two) st.controller().set_analog_input(static_cast<int>(a), static_cast<int>(std::lround(b)));
          if (what == "test-speed") st.controller().set_test_speed_step(static_cast<int>(a));
        }
        return "ok " + cmd;
      }
      if (cmd == "start" || cmd == "stop" || cmd == "clear") {
        for (std::size_t i = 0; i < l.size(); ++i) {
          auto& c = l.station(i).controller();
          if (cmd == "start") (void)c.command_start();
          if (cmd == "stop") c.command_stop();
          if (cmd == "clear") c.command_clear();
        }
        return "ok " + cmd;
      }
      if (cmd == "status") {
        std::string s;
        for (std::size_t i = 0; i < l.size(); ++i) {
          const auto& st = l.station(i);
          const auto& c = st.controller();
          s += fmt::format("{}station {} mode {} run {} fault {:02X} line {:04d} pos {:.3f} {:.3f}", i ? "\n" : "",
                           st.station(), cc::to_string(c.mode()),
                           c.run_state() == cc::RunState::running   ? "running"
                           : c.run_state() == cc::RunState::stopped ? "stopped"
                                                                    : "idle",
                           st.fault(), c.task(1).pc, c.position(1), c.position(2));
          if (!c.error_message().empty()) s += " (" + c.error_message() + ")";
        }
        return s;
      }
      return "error: unknown command (mode parameter|manual|auto, input ADDR 0|1, material V, analog N MV, "
             "test-speed N, start, stop, clear, status, quit)";
    });
  });

  // --- ELG tape reader/punch, and the running ELG ------------------------------------------
  struct ElgOpts {
    EmulateOptions e;
    std::string tape;
    std::string program;
    std::string machine;
    Duration cycle = std::chrono::milliseconds(2);
    bool hold = false;
  };
  auto eo = std::make_shared<ElgOpts>();
  eo->e.link.format = "8N2";
  eo->e.link.baud = 4800;
  auto* elg = ctx.emulate.add_subcommand("elg-tape",
                                         "Emulated SINUMERIK ELG universal interface: reads %TEA1 / %SEA tapes (ISO, "
                                         "even parity in bit 7) and punches them on "
                                         "Data Start (a DC2 byte from the peer). With --program the gearbox runs: "
                                         "NC program, PC and ELG on the host's time, and the interface answers "
                                         "from the running model (Data Start while coupled: alarm 2214).");
  add_emulate_options(*elg, eo->e);
  elg->add_option("--tape", eo->tape,
                  "The %TEA1 machine-data tape (text) that configures the running gearbox and fills its MD store")
      ->check(CLI::ExistingFile);
  elg->add_option("--program", eo->program, "Run the ELG: the System 3 NC program (FILE.nc) of the hobbing cycle")
      ->check(CLI::ExistingFile);
  elg->add_option("--machine", eo->machine,
                  "Retrofit mode: a machine file (scenario with machine.axes B, C, Z, X [, Y]; their scaling as the "
                  "tape's MD 396*/5002 give it) whose axes are the ELG's on real-transport drives")
      ->check(CLI::ExistingFile);
  const DurationRange elg_cycle{std::chrono::microseconds(500), std::chrono::milliseconds(100)};
  add_duration_option(*elg, "--cycle", eo->cycle, "ELG cycle with --program (default 2ms)", "ms", elg_cycle);
  elg->add_flag("--hold", eo->hold, "With --program: wait for the console command 'start' (NC start)");
  elg->footer(
      "Console commands: 'alarm', 'clear', 'quit'; with --program also 'status', 'start', 'reset' (ELG-RESET "
      "pulse), 'fe on|off' (A67.1), 'pc read CODING ADDRESS', 'pc write CODING ADDRESS VALUE' (PC data channel, "
      "12.5: coding 9 R, 10 MD word/service, 12 actual value, 27 alarms, 28 MD bits, 29 SD bits). Data Start "
      "(MD tape, then SD tape) is a DC2 byte from the peer.\n"
      "Examples: hilbridge emulate elg-tape --pty\n"
      "          hilbridge emulate elg-tape --pty --tape md.tape.txt --program hobbing.nc\n"
      "          hilbridge emulate elg-tape --port /dev/ttyUSB0 --tape md.tape.txt --program hobbing.nc "
      "--machine machine.yaml   (retrofit mode)");
  elg->callback([&ctx, eo] {
    auto fail = [&](const std::string& what) {
      fmt::print(stderr, "error: {}\n", what);
      ctx.exit_code = 2;
    };
    auto check = hil::serial::load_elg_check();
    if (!check) return fail("device profile: " + check.error());
    if (eo->program.empty()) {
      if (!eo->tape.empty() || !eo->machine.empty())
        return fail("--tape and --machine run the gearbox: give the NC program with --program");
      lg::ElgTapeEndpoint ep(*check);
      const auto locked = resolve_state(eo->e, "elg");
      if (!locked) return fail(locked.error());
      const auto& state = *locked;
      if (auto text = read_file(state))
        if (auto r = ep.load_state(*text); !r) fmt::print(stderr, "warning: {}\n", r.error());
      ctx.exit_code = serve(ep, eo->e, state, [](lg::Endpoint& e, const std::string& cmd) -> std::string {
        auto& t = static_cast<lg::ElgTapeEndpoint&>(e);
        if (cmd == "alarm")
          return t.alarm() == 0 ? std::string("no alarm") : fmt::format("alarm {}: {}", t.alarm(), t.alarm_text());
        if (cmd == "clear") {
          t.clear_alarm();
          return "ok";
        }
        return "error: unknown command (alarm, clear, quit); Data Start is a DC2 byte from the peer";
      });
      return;
    }
    // The running ELG: configured from its MD tape, the NC program on simulated or real axes.
    namespace ce = hil::controllers::elg;
    if (eo->tape.empty()) return fail("--program needs --tape FILE: the %TEA1 machine-data tape of the gearbox");
    auto loaded = hil::controllers::load_parameter_file("sinumerik-elg", eo->tape);
    if (!loaded) return fail(loaded.error().describe());
    auto setup = ce::elg_setup_from_tape(*loaded, ce::HobbingConfig{}, eo->cycle);
    if (!setup) return fail(setup.error().describe());
    auto text = read_text_file(eo->program);
    if (!text) return fail(text.error());
    auto program = ce::parse_nc_program(*text);
    if (!program) return fail(fmt::format("{}:{}: {}", eo->program, program.error().line, program.error().what()));
    auto tape_text = read_text_file(eo->tape);
    if (!tape_text) return fail(tape_text.error());
    auto sections = hil::serial::tape::parse_elg_text(*tape_text);
    if (!sections) return fail(fmt::format("{}: {}", eo->tape, sections.error().message));
    std::vector<std::pair<std::string, motion::Ratio>> wanted;
    for (const auto& a : setup->axes) wanted.emplace_back(a.name, a.config.inc_per_unit);
    std::unique_ptr<MachineFile> retrofit;
    std::vector<motion::Axis*> real_axes;
    if (!eo->machine.empty()) {
      auto r =
          load_machine<MachineFile>(eo->machine, ctx.transports, [&](const hil::runtime::Scenario& sc) -> std::string {
            for (const auto& [name, ratio] : wanted) {
              const auto it =
                  std::find_if(sc.axes.begin(), sc.axes.end(), [&](const auto& a) { return a.name == name; });
              if (it == sc.axes.end())
                return fmt::format("{}: machine.axes: the ELG needs axis {} (B, C, Z, X{})", eo->machine, name,
                                   wanted.size() > 4 ? ", Y" : "");
            }
            return {};
          });
      if (!r) return fail("--machine: " + r.error());
      retrofit = std::move(*r);
      for (const auto& [name, ratio] : wanted) {
        for (auto& a : retrofit->machine->axes()) {
          if (a.axis->config().name != name) continue;
          const auto& have = a.axis->config().inc_per_unit;
          if (have.num * ratio.den != ratio.num * have.den)
            return fail(
                fmt::format("--machine: axis {}: {}/{} increments per unit, the tape's MD give {}/{} (counts "
                            "of the ELG: rotary 4 x MD 396* per 360 deg, linear 1e6 / MS[nm] per mm)",
                            name, have.num, have.den, ratio.num, ratio.den));
          real_axes.push_back(a.axis.get());
        }
      }
    }
    lg::ElgRunOptions run;
    run.auto_start = !eo->hold;
    lg::ElgRunEndpoint ep(*check, std::move(*setup), std::move(*program), eo->cycle, {}, run);
    if (retrofit) {
      auto* rf = retrofit.get();
      ep.use_axes(real_axes, [rf](const CycleTime& c) {
        rf->io.poll();
        rf->machine->cycle(c);
      });
    }
    const auto locked = resolve_state(eo->e, "elg");
    if (!locked) return fail(locked.error());
    const auto& state = *locked;
    if (auto t = read_file(state))
      if (auto r = ep.load_state(*t); !r) fmt::print(stderr, "warning: {}\n", r.error());
    // The store holds what the gearbox runs with: the tape's data over the saved state.
    for (const auto& sec : *sections)
      for (const auto& en : sec.entries) ep.tape().set_datum(sec.kind, en.number, en.value);
    ctx.exit_code = serve(ep, eo->e, state, [](lg::Endpoint& e, const std::string& cmd) -> std::string {
      auto& r = static_cast<lg::ElgRunEndpoint&>(e);
      if (cmd == "status") return r.status();
      if (cmd == "alarm") {
        const auto alarms = r.alarms();
        if (alarms.empty()) return "no alarm";
        std::string out;
        for (int a : alarms)
          out += fmt::format(
              "{}alarm {}: {}", out.empty() ? "" : "\n", a,
              a == r.tape().alarm() ? r.tape().alarm_text() : std::string(ce::alarm_text(static_cast<ce::Alarm>(a))));
        return out;
      }
      if (cmd == "clear") {
        r.tape().clear_alarm();
        return "ok";
      }
      if (cmd == "start") {
        r.start();
        return "ok start";
      }
      if (cmd == "reset") {
        r.pulse_reset();
        return "ok reset";
      }
      if (cmd == "fe on" || cmd == "fe off") {
        r.set_fe_monitor(cmd == "fe on");
        return "ok " + cmd;
      }
      if (cmd.starts_with("pc ")) {
        std::istringstream in(cmd.substr(3));
        std::string op, value;
        int coding = -1, address = -1;
        in >> op >> coding >> address >> value;
        const bool write = op == "write";
        const auto v = write ? ce::parse_pc_value(value) : std::optional<ce::PcValue>(ce::PcValue{});
        if ((op != "read" && op != "write") || coding < 0 || coding > 63 || address < 0 || address > 9999 || !v)
          return "error: pc read CODING ADDRESS | pc write CODING ADDRESS VALUE (e.g. pc read 10 3961, pc write 9 40 "
                 "500)";
        ce::PcRequest req{write, static_cast<std::uint8_t>(coding), static_cast<std::uint8_t>(address % 100),
                          static_cast<std::uint8_t>(address / 100), *v};
        const auto reply = r.pc_request(req);
        if (!reply.performed)
          return fmt::format("acknowledged, not performed: alarm {} {}", static_cast<int>(*reply.alarm),
                             ce::alarm_text(*reply.alarm));
        return fmt::format("ok {}", ce::to_string(reply.value));
      }
      return "error: unknown command (status, alarm, clear, start, reset, fe on|off, pc read|write, quit)";
    });
  });

  // --- IP247 (the WF 725/726: emulate_wf725.cpp) ----------------------------------------------
  register_wf725_emulator(ctx);
  {
    const std::string dev = "ip247";
    auto so = std::make_shared<EmulateOptions>();
    so->link.format = "8E1";
    so->link.baud = 9600;
    auto* cmd = ctx.emulate.add_subcommand(
        dev,
        "Emulated SIMATIC S5 IP247 modules (one or several, one line each): MD and traversing-program DBs, "
        "axis interface DBs and data jobs behind 3964R/RK512 (SEND writes, FETCH reads)");
    add_emulate_options(*cmd, *so);
    auto switches = std::make_shared<std::vector<std::string>>();
    auto cycle = std::make_shared<Duration>(std::chrono::milliseconds(1));
    auto machines = std::make_shared<std::vector<std::string>>();
    auto tiles = std::make_shared<std::vector<int>>();
    cmd->add_option("--tile", *tiles,
                    "SSNR base of a module (switch S2, a multiple of 4): axes 1..3 on TILE..TILE+2, the data "
                    "channel on TILE+3 (the SSNR of the data jobs in DX 4); default 0. Repeat it for a rack of "
                    "several modules: one module per --tile, each on its own line (docs/ip247.md)")
        ->check(CLI::Range(0, 252));
    cmd->add_option("--machine", *machines,
                    "Retrofit mode: a machine file (scenario with machine.axes, 1 increment = 1 pulse) whose axes "
                    "1..3 are the module's axes on real transports (step/dir on a GPIO chip, CiA 402 CSP, sim); "
                    "their limit and reference lines replace the mock switches when the drive reports them. With "
                    "several modules: once per module, in the order of --tile");
    cmd->add_option("--switch", *switches,
                    "Mock switch of an axis, actuated as a function of the pulses output: "
                    "[MODULE.]AXIS:limit-start:PULSES, [MODULE.]AXIS:limit-end:PULSES or [MODULE.]AXIS:cam:FROM:TO "
                    "(MODULE 1.. in the order of --tile, default 1); repeatable");
    const DurationRange cycle_range{std::chrono::microseconds(1), std::chrono::seconds(1)};
    add_duration_option(*cmd, "--cycle", *cycle, "Module cycle, e.g. 2ms (default 1ms; 1us .. 1s)", "ms", cycle_range);
    add_duration_alias(*cmd, "--cycle-ms", "--cycle", *cycle, "ms", cycle_range);
    cmd->callback([&ctx, so, dev, switches, cycle, machines, tiles] {
      namespace s5 = hil::controllers::s5;
      const auto fail = [&](const std::string& message) {
        fmt::print(stderr, "error: {}\n", message);
        ctx.exit_code = 2;
      };
      // The rack: one module per --tile (none: one module on tile 0), each on its own line.
      const std::vector<int> rack = tiles->empty() ? std::vector<int>{0} : *tiles;
      if (!machines->empty() && machines->size() != rack.size())
        return fail(
            fmt::format("--machine given {} times for {} module(s): give one machine file per module, in "
                        "the order of --tile",
                        machines->size(), rack.size()));
      std::vector<s5::Ip247ModuleOptions> opts(rack.size());
      for (std::size_t i = 0; i < rack.size(); ++i) {
        opts[i].cycle = *cycle;
        opts[i].tile = rack[i];
      }
      for (const auto& sw : *switches) {
        int module = 1, axis = 0;
        long long a = 0, b = 0;
        char kind[16] = {};
        std::string text = sw;
        if (const auto dot = text.find('.'); dot != std::string::npos && dot < text.find(':')) {
          module = std::atoi(text.substr(0, dot).c_str());
          text = text.substr(dot + 1);
        }
        const int n = std::sscanf(text.c_str(), "%d:%15[a-z-]:%lld:%lld", &axis, kind, &a, &b);
        const std::string k = kind;
        if (n < 3 || axis < 1 || axis > 3 || module < 1 || module > static_cast<int>(rack.size()) ||
            (k == "cam" && n != 4) || (k != "cam" && k != "limit-start" && k != "limit-end") || cycle->count() <= 0)
          return fail(
              fmt::format("--switch '{}': expected [MODULE.]AXIS:limit-start:P, [MODULE.]AXIS:limit-end:P "
                          "or [MODULE.]AXIS:cam:A:B (MODULE 1..{})",
                          sw, rack.size()));
        auto& s = opts[static_cast<std::size_t>(module - 1)].switches[static_cast<std::size_t>(axis - 1)];
        if (k == "cam") s.cam = std::pair<std::int64_t, std::int64_t>{a, b};
        if (k == "limit-start") s.limit_start_at = a;
        if (k == "limit-end") s.limit_end_at = a;
      }
      // Per module (s5::Ip247Rack): its policy (a running module: 3 axes on the IP247 step planner,
      // DX1..3 = axis interface DBs, DB n = MD and VP images), its endpoint, its state file; the PLC's
      // DBs of the data jobs (DX 5..255) are one PLC's, shared by the modules. Here: the retrofits.
      auto made = s5::Ip247Rack::make(opts);
      if (!made) return fail(fmt::format("--tile: {}", made.error()));
      s5::Ip247Rack modules = std::move(*made);
      std::vector<std::unique_ptr<Ip247Retrofit>> retrofits(modules.size());  // outlive the endpoints' hooks
      std::vector<std::filesystem::path> states(modules.size());
      for (std::size_t i = 0; i < modules.size(); ++i) {
        if (!machines->empty()) {
          auto r = make_ip247_retrofit((*machines)[i], ctx.transports);
          if (!r) return fail(fmt::format("--machine: {}", r.error()));
          retrofits[i] = std::move(*r);
          if (auto up = power_up_ip247_machine(*retrofits[i], opts[i].cycle, (*machines)[i]); !up)
            return fail(fmt::format("--machine: {}", up.error()));
          modules.policy(i).set_hooks(ip247_retrofit_hooks(*retrofits[i], modules.policy(i), opts[i].cycle));
        }
        EmulateOptions so_m = *so;
        if (modules.size() > 1 && so->state_file != "none")
          so_m.state_file =
              modules
                  .state_path(so->state_file.empty() ? default_state_path(dev) : std::filesystem::path(so->state_file),
                              i)
                  .string();
        const auto locked = resolve_state(so_m, dev);
        if (!locked) return fail(locked.error());
        states[i] = *locked;
        if (auto text = read_file(states[i]))
          if (auto r = modules.load(i, *text); !r) fmt::print(stderr, "warning: {}\n", r.error());
      }
      std::vector<ServedLine> lines;
      for (std::size_t i = 0; i < modules.size(); ++i) lines.push_back(ServedLine{&modules.endpoint(i), states[i]});
      const bool several = modules.size() > 1;
      ctx.exit_code = serve_lines(
          lines, *so,
          [&modules, &retrofits, several](std::span<lg::Endpoint* const>, const std::string& c) -> std::string {
            std::string out;
            const auto prefix = [&](std::size_t i) {
              return several ? fmt::format("module {} (tile {}) ", i + 1, modules.tile(i)) : std::string();
            };
            if (c == "axes") {
              for (std::size_t i = 0; i < modules.size(); ++i)
                for (int n = 1; n <= 3; ++n) {
                  const auto& a = modules.policy(i).axis(n);
                  out +=
                      fmt::format("{}axis {}: BA{} actual {} remaining {} M{} attributes {:02X} error {}\n", prefix(i),
                                  n, a.ba(), a.actual(), a.remaining(), a.m_output(), a.attributes(), a.error());
                }
              return out;
            }
            if (c == "machine" && retrofits.front()) {  // the retrofits' machine axes (increments = pulses)
              for (std::size_t i = 0; i < modules.size(); ++i)
                for (const auto& a : retrofits[i]->machine->axes()) {
                  const auto& st = a.axis->status();
                  out += fmt::format("{}machine axis {}: position {} inc state {}{}\n", prefix(i), a.spec->name,
                                     st.position_inc, hil::motion::to_string(st.state),
                                     st.fault ? " fault " + st.fault.describe() : "");
                }
              return out;
            }
            if (c == "rejection") {
              for (std::size_t i = 0; i < modules.size(); ++i) {
                const auto& r = modules.policy(i).last_rejection();
                out += fmt::format("{}{}{}", out.empty() ? "" : "\n", prefix(i), r.empty() ? std::string("none") : r);
              }
              return out;
            }
            if (c == "dbs") {
              for (std::size_t i = 0; i < modules.size(); ++i)
                for (const auto& [n, w] : modules.endpoint(i).store())
                  out += fmt::format("{}DB{} {} words\n", prefix(i), n, w.size());
              return out.empty() ? std::string("no DBs") : out;
            }
            if (c == "error") {
              for (std::size_t i = 0; i < modules.size(); ++i) {
                const auto& e = modules.endpoint(i).last_error();
                out +=
                    fmt::format("{}{}{}", out.empty() ? "" : "\n", prefix(i), e.empty() ? std::string("no error") : e);
              }
              return out;
            }
            return retrofits.front() ? "error: unknown command (dbs, error, axes, machine, rejection, quit)"
                                     : "error: unknown command (dbs, error, axes, rejection, quit)";
          });
    });
  }
}

}  // namespace hil::cli::serial_cli
