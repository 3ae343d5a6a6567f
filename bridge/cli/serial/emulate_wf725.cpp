// SPDX-License-Identifier: MIT
// `hilbridge emulate wf725`: a running WF 725/726 axis behind 3964R/RK512 (docs/wf725.md, "The
// module on a serial line"): the DB axis, the MD image and user data blocks served by
// Wf725ModulePolicy, the axis simulated or (--machine) on a machine file's real-transport drive.
#include <fmt/format.h>

#include <filesystem>
#include <sstream>

#include "emulate.hpp"
#include "emulate_machine.hpp"
#include "hil/controllers/s5/wf725_controller.hpp"
#include "hil/controllers/s5/wf725_module_endpoint.hpp"
#include "hil/mocks/legacy/s5_block_endpoint.hpp"

namespace hil::cli::serial_cli {

namespace lg = hil::mocks::legacy;
namespace s5c = hil::controllers::s5;

namespace {

struct Wf725Opts {
  EmulateOptions e;
  std::string md;
  std::vector<std::string> programs;
  std::string module;
  std::string axis = "A";
  int db = 10;
  std::string machine;
};

/// A YAML double-quoted scalar (JSON escapes are YAML's).
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string absolute(const std::string& p) {
  std::error_code ec;
  const auto a = std::filesystem::absolute(p, ec);
  return ec ? p : a.string();
}

/// The scenario of the simulated module: the axis on the sim transport, the WF controller from
/// the options.
std::string sim_scenario(const Wf725Opts& o) {
  std::string c =
      fmt::format("{{device: wf725-726, parameters: {}, db: {}, axis: {}", quoted(absolute(o.md)), o.db, o.axis);
  if (!o.module.empty()) c += ", module: " + o.module;
  if (!o.programs.empty()) {
    c += ", programs: [";
    for (std::size_t i = 0; i < o.programs.size(); ++i) c += (i ? ", " : "") + quoted(absolute(o.programs[i]));
    c += "]";
  }
  c += "}";
  return fmt::format(
      "name: emulate wf725\nperiod: 1ms\ncontroller: {}\nmachine:\n  axes:\n    - name: {}\n"
      "      drive: {{transport: sim, kv: 200, feedforward: 1.0, velocity_lag: 0}}\n",
      c, o.axis);
}

/// What a machine file must be for the WF: a scenario with the WF controller and its axis, and
/// no run of its own (program/expect steps would never run).
std::string check_machine(const hil::runtime::Scenario& sc, const std::string& file) {
  if (!sc.controller || sc.controller->device != "wf725-726")
    return fmt::format(
        "{}: give the module in a 'controller:' block: {{device: wf725-726, parameters: MD-LIST, programs: [...], "
        "db: 10}} (its axis under machine.axes with name and drive only)",
        file);
  if (!sc.program.empty() || !sc.expectations.empty() || !sc.io_expectations.empty() ||
      !sc.controller_expectations.empty())
    return fmt::format(
        "{}: a machine file for `emulate wf725` has no program: or expect: steps (the PLC on the line commands "
        "the module); remove them",
        file);
  return {};
}

std::string status_line(const s5c::Wf725Controller& c) {
  namespace db = s5c::wf_db;
  const auto w = [&](std::uint16_t n) { return c.read_db_word(n); };
  const auto bit = [&](std::uint16_t n, int b) { return ((w(n) >> b) & 1) != 0; };
  return fmt::format(
      "axis {}: DB{} mode {:02X} submode {} actual {:.0f} um{}{}{}{} error {:02X} io {:04X} program {} block {}",
      c.axis_specs()[0].name, c.interface_db().number, w(db::dw_state) >> 8, w(db::dw_state) & 0xFF, c.actual_um(),
      bit(db::dw_status, db::bit_peh) ? " PEH" : "", bit(db::dw_status, db::bit_syn) ? " SYN" : "",
      bit(db::dw_status, db::bit_moving_plus) ? " +" : "", bit(db::dw_status, db::bit_moving_minus) ? " -" : "",
      w(db::dw_error) & 0xFF, w(db::dw_io_error), w(db::dw_block) >> 8, w(db::dw_block) & 0xFF);
}

}  // namespace

void register_wf725_emulator(Context& ctx) {
  auto o = std::make_shared<Wf725Opts>();
  o->e.link.format = "8E1";
  o->e.link.baud = 9600;
  auto* cmd = ctx.emulate.add_subcommand(
      "wf725",
      "Emulated SIMATIC S5 WF 725/726 positioning module behind 3964R/RK512: one axis running the WF's modes, "
      "submodes, traversing programs and errors (docs/wf725.md) on a simulated drive or, with --machine, on a "
      "real-transport drive. RK512 SEND writes, FETCH reads: DB 10 (--db) = the DB axis (DW 0..47, live actual "
      "value and status), DB 1 = MD 1..50 (100 words, binary; written in mode MD I/O only), other DBs = user data "
      "blocks (program text for data codes 44/45).");
  add_emulate_options(*cmd, o->e);
  cmd->add_option("--md", o->md,
                  "The axis' machine-data list MD 1..50 (profile wf725-726, text 'MD 3 = 6000' per line, e.g. "
                  "examples/controllers/wf725-axis-a.txt); required without --machine")
      ->check(CLI::ExistingFile);
  cmd->add_option("--program", o->programs,
                  "Program file(s) in the module's memory at power-up ('%5 A RAM' headers, N-blocks; "
                  "docs/wf725.md); repeatable")
      ->check(CLI::ExistingFile);
  cmd->add_option("--module", o->module,
                  "WF725A, WF725B, WF726A, WF726B or WF726C (default WF726A): memory limits, cycle, MD 15 meaning")
      ->check(CLI::IsMember({"WF725A", "WF725B", "WF726A", "WF726B", "WF726C"}));
  cmd->add_option("--axis", o->axis, "The axis letter (A, B, C)")
      ->check(CLI::IsMember({"A", "B", "C"}))
      ->capture_default_str();
  cmd->add_option("--db", o->db, "DB number of the DB axis (2..255)")->check(CLI::Range(2, 255))->capture_default_str();
  cmd->add_option("--machine", o->machine,
                  "Retrofit mode: a machine file (a scenario with controller: {device: wf725-726, parameters: MD-LIST, "
                  "programs: [...], db: N} and the axis under machine.axes on its drive: a CiA 402 drive over "
                  "canopen, modbus, sim; io_links and io: stimuli wire its switches) instead of --md/--program/"
                  "--module/--axis/--db")
      ->check(CLI::ExistingFile);
  cmd->footer(
      "Console commands (stdin): 'status' (mode, submode, actual value, PEH/SYN, error DR 4, DW 40, program and "
      "block), 'machine' (the machine axis: position, state, fault), 'input NAME 0|1' (an input of the module: "
      "X7 x7_e1..6, limit_plus_A, the encoder fault inputs encoder_cable_break_A, ...), 'rejection' (why the last "
      "RK512 job was "
      "refused), 'dbs' (user data blocks), 'quit'.\n"
      "Examples: hilbridge emulate wf725 --pty --md examples/controllers/wf725-axis-a.txt --program progs.wf\n"
      "          hilbridge emulate wf725 --tcp 4001 --machine wf-canopen.yaml   (retrofit mode, e.g. behind a "
      "serial-over-IP adapter)");
  cmd->callback([&ctx, o] {
    const auto fail = [&](const std::string& what) {
      fmt::print(stderr, "error: {}\n", what);
      ctx.exit_code = 2;
    };
    std::expected<std::unique_ptr<MachineFile>, std::string> built;
    if (!o->machine.empty()) {
      if (!o->md.empty() || !o->programs.empty() || !o->module.empty())
        return fail(
            "--machine: the machine file's controller block gives the MD list, programs and module: drop --md, "
            "--program and --module");
      auto sc = hil::runtime::load_scenario(o->machine);
      if (!sc) return fail("--machine: " + sc.error().describe());
      // The WF module model (not the parameter-only controller): its DB axis is what the line serves.
      if (sc->controller && sc->controller->device == "wf725-726" && !sc->controller->options.contains("db"))
        sc->controller->options.emplace("db", "10");
      const std::string file = o->machine;
      built = build_machine<MachineFile>(std::move(*sc), ctx.transports,
                                         [&](const hil::runtime::Scenario& s) { return check_machine(s, file); });
      if (!built) return fail("--machine: " + built.error());
    } else {
      if (o->md.empty())
        return fail(
            "give the axis' machine data with --md FILE (MD 1..50, profile wf725-726, e.g. "
            "examples/controllers/wf725-axis-a.txt) or a machine file with --machine");
      auto sc = hil::runtime::parse_scenario(sim_scenario(*o), "emulate wf725");
      if (!sc) return fail(sc.error().describe());
      built = build_machine<MachineFile>(std::move(*sc), ctx.transports,
                                         [](const hil::runtime::Scenario&) { return std::string(); });
      if (!built) return fail(built.error());
    }
    auto rf = std::move(*built);
    auto* ctl = dynamic_cast<s5c::Wf725Controller*>(rf->machine->controller());
    if (ctl == nullptr)
      return fail("the machine file's wf725-726 controller is not the module model (give it db: N or programs:)");
    if (ctl->interface_db().number == s5c::wf725_md_image_db)
      return fail("db: 1 is the MD image of the emulator: give the DB axis another number (2..255)");
    auto* m = rf.get();
    auto policy = std::make_unique<s5c::Wf725ModulePolicy>(std::vector<s5c::Wf725Controller*>{ctl}, m->scenario.period,
                                                           [m](const CycleTime& c) {
                                                             m->io.poll();
                                                             m->machine->cycle(c);
                                                           });
    auto* pol = policy.get();
    lg::S5BlockEndpoint ep(std::move(policy));
    pol->share_store(ep.store());
    const auto locked = resolve_state(o->e, "wf725");
    if (!locked) return fail(locked.error());
    const auto& state = *locked;
    if (auto text = read_file(state))
      if (auto r = ep.load_state(*text); !r) fmt::print(stderr, "warning: {}\n", r.error());
    ctx.exit_code = serve(ep, o->e, state, [pol, m](lg::Endpoint& e, const std::string& c) -> std::string {
      auto& s = static_cast<lg::S5BlockEndpoint&>(e);
      if (c == "status") {
        std::string out;
        for (const auto* a : pol->axes()) out += (out.empty() ? "" : "\n") + status_line(*a);
        return out;
      }
      if (c == "machine") {
        std::string out;
        for (const auto& a : m->machine->axes()) {
          const auto& st = a.axis->status();
          out += fmt::format("{}machine axis {}: position {:.4f} state {}{}", out.empty() ? "" : "\n", a.spec->name,
                             st.position, hil::motion::to_string(st.state),
                             st.fault ? " fault " + st.fault.describe() : "");
        }
        return out;
      }
      if (c.starts_with("input ")) {
        std::istringstream in(c.substr(6));
        std::string name;
        int v = -1;
        in >> name >> v;
        auto* a = pol->axes().front();
        const auto bit = a->resolve_bit(name);
        if (!bit || bit->area != hil::controllers::IoArea::input || (v != 0 && v != 1))
          return "error: input NAME 0|1 with an input of the module (x7_e1..x7_e6, limit_plus_A, "
                 "encoder_cable_break_A, ...)";
        a->io().set(*bit, v == 1);
        return "ok " + c;
      }
      if (c == "rejection") return pol->last_rejection().empty() ? std::string("none") : pol->last_rejection();
      if (c == "dbs") {
        std::string out;
        for (const auto& [n, w] : s.store())
          out += fmt::format("{}DB{} {} words", out.empty() ? "" : "\n", n, w.size());
        return out.empty() ? std::string("no user data blocks") : out;
      }
      return "error: unknown command (status, machine, input NAME 0|1, rejection, dbs, quit)";
    });
  });
}

}  // namespace hil::cli::serial_cli
