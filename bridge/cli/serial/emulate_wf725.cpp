// SPDX-License-Identifier: MIT
// `hilbridge emulate wf725`: a running WF 725/726 module behind 3964R/RK512 (docs/wf725.md, "The
// module on a serial line"): its 1..3 axes (DB axis each), the MD images, the shared program
// memory and user data blocks served by Wf725ModulePolicy; each axis simulated (--md) or
// (--machine) on a machine file's real-transport drive.
#include <fmt/format.h>

#include <algorithm>

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
  std::vector<std::string> md;
  std::vector<std::string> programs;
  std::string module;
  std::vector<std::string> axis;
  std::vector<int> db;
  std::vector<std::string> machine;
};

/// One simulated axis of the module.
struct SimAxis {
  std::string md;
  std::string letter;
  int db = 10;
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

/// The scenario of one simulated axis: the axis on the sim transport, the WF controller from the
/// options; the programs go into the first axis' memory (the module's, shared by its axes).
std::string sim_scenario(const Wf725Opts& o, const SimAxis& a, bool first) {
  std::string c =
      fmt::format("{{device: wf725-726, parameters: {}, db: {}, axis: {}", quoted(absolute(a.md)), a.db, a.letter);
  if (!o.module.empty()) c += ", module: " + o.module;
  if (first && !o.programs.empty()) {
    c += ", programs: [";
    for (std::size_t i = 0; i < o.programs.size(); ++i) c += (i ? ", " : "") + quoted(absolute(o.programs[i]));
    c += "]";
  }
  c += "}";
  return fmt::format(
      "name: emulate wf725\nperiod: 1ms\ncontroller: {}\nmachine:\n  axes:\n    - name: {}\n"
      "      drive: {{transport: sim, kv: 200, feedforward: 1.0, velocity_lag: 0}}\n",
      c, a.letter);
}

/// The simulated axes of --md/--axis/--db: letters A, B, C in order unless given, DB axis numbers
/// one --db each or consecutive from the first (10, 11, 12).
std::expected<std::vector<SimAxis>, std::string> sim_axes(const Wf725Opts& o) {
  const std::size_t n = o.md.size();
  if (n > s5c::wf725_max_axes)
    return std::unexpected("a WF 725/726 has at most 3 axes (A, B, C): give --md 1..3 times");
  if (!o.axis.empty() && o.axis.size() != n)
    return std::unexpected(fmt::format("--axis: give one letter per --md ({} --md, {} --axis)", n, o.axis.size()));
  if (o.db.size() > 1 && o.db.size() != n)
    return std::unexpected(fmt::format(
        "--db: give one DB per --md or only the first (consecutive numbers); {} --md, {} --db", n, o.db.size()));
  std::vector<SimAxis> axes;
  for (std::size_t i = 0; i < n; ++i) {
    SimAxis a;
    a.md = o.md[i];
    a.letter = o.axis.empty() ? std::string(1, static_cast<char>('A' + i)) : o.axis[i];
    const int first = o.db.empty() ? 10 : o.db.front();
    a.db = o.db.size() == n ? o.db[i] : first + static_cast<int>(i);
    if (a.db > 255) return std::unexpected(fmt::format("--db: axis {} would get DB{} (2..255)", a.letter, a.db));
    axes.push_back(std::move(a));
  }
  return axes;
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

/// A console command of the running module.
std::string console(lg::S5BlockEndpoint& s, const s5c::Wf725ModulePolicy& pol, const std::vector<MachineFile*>& ms,
                    const std::string& c) {
  if (c == "status") {
    std::string out;
    for (const auto* a : pol.axes()) out += (out.empty() ? "" : "\n") + status_line(*a);
    return out;
  }
  if (c == "machine") {
    std::string out;
    for (const auto* m : ms)
      for (const auto& a : m->machine->axes()) {
        const auto& st = a.axis->status();
        out +=
            fmt::format("{}machine axis {}: position {:.4f} state {}{}", out.empty() ? "" : "\n", a.spec->name,
                        st.position, hil::motion::to_string(st.state), st.fault ? " fault " + st.fault.describe() : "");
      }
    return out;
  }
  if (c.starts_with("input ")) {
    std::istringstream in(c.substr(6));
    std::string name;
    int v = -1;
    in >> name >> v;
    bool any = false;
    // X7 inputs are the module's: every axis' image has them; an axis' own inputs resolve on it only.
    for (auto* a : pol.axes()) {
      const auto bit = a->resolve_bit(name);
      if (!bit || bit->area != hil::controllers::IoArea::input) continue;
      if (v != 0 && v != 1) break;
      a->io().set(*bit, v == 1);
      any = true;
    }
    if (!any)
      return "error: input NAME 0|1 with an input of the module (x7_e1..x7_e6, limit_plus_A, "
             "encoder_cable_break_B, ...)";
    return "ok " + c;
  }
  if (c == "programs") {
    std::string out;
    if (pol.axes().empty()) return "no axes";
    const auto& store = pol.axes().front()->programs();
    for (const auto& p : store.all())
      out +=
          fmt::format("{}program {}{}{}: {} blocks", out.empty() ? "" : "\n", p.number,
                      p.valid_axes.empty() ? "" : " axes " + p.valid_axes, p.ram ? " RAM" : " EEPROM", p.blocks.size());
    return out.empty() ? std::string("no programs") : out;
  }
  if (c == "rejection") return pol.last_rejection().empty() ? std::string("none") : pol.last_rejection();
  if (c == "dbs") {
    std::string out;
    for (const auto& [n, w] : s.store()) out += fmt::format("{}DB{} {} words", out.empty() ? "" : "\n", n, w.size());
    return out.empty() ? std::string("no user data blocks") : out;
  }
  return "error: unknown command (status, machine, input NAME 0|1, programs, rejection, dbs, quit)";
}

}  // namespace

void register_wf725_emulator(Context& ctx) {
  auto o = std::make_shared<Wf725Opts>();
  o->e.link.format = "8E1";
  o->e.link.baud = 9600;
  auto* cmd = ctx.emulate.add_subcommand(
      "wf725",
      "Emulated SIMATIC S5 WF 725/726 positioning module behind 3964R/RK512: up to three axes (A, B, C) running the "
      "WF's modes, submodes, traversing programs and errors (docs/wf725.md) on simulated drives or, with --machine, "
      "on real-transport drives, sharing one program memory. RK512 SEND writes, FETCH reads: DB 10, 11, 12 (--db) = "
      "the DB axis of axis A, B, C (DW 0..47, live actual value and status), DB 1 = MD 1..50 of the first axis, "
      "DX 1..3 = MD 1..50 of axis 1..3 (100 words, binary; written in mode MD I/O only), other DBs = user data "
      "blocks (program text for data codes 44/45). The state file keeps the user data blocks and the program "
      "memory.");
  add_emulate_options(*cmd, o->e);
  cmd->add_option("--md", o->md,
                  "An axis' machine-data list MD 1..50 (profile wf725-726, text 'MD 3 = 6000' per line, e.g. "
                  "examples/controllers/wf725-axis-a.txt); once per axis (1..3: A, B, C in order); required "
                  "without --machine")
      ->check(CLI::ExistingFile);
  cmd->add_option("--program", o->programs,
                  "Program file(s) in the module's memory at power-up ('%5 A RAM' headers, N-blocks; "
                  "docs/wf725.md); repeatable. They replace saved programs of the same number.")
      ->check(CLI::ExistingFile);
  cmd->add_option("--module", o->module,
                  "WF725A, WF725B, WF726A, WF726B or WF726C (default WF726A): memory limits, cycle, MD 15 meaning")
      ->check(CLI::IsMember({"WF725A", "WF725B", "WF726A", "WF726B", "WF726C"}));
  cmd->add_option("--axis", o->axis, "The axis letters, one per --md (default A, B, C in order)")
      ->check(CLI::IsMember({"A", "B", "C"}));
  cmd->add_option("--db", o->db,
                  "DB numbers of the DB axes (2..255): one per --md, or the first only (the others follow: "
                  "default 10, 11, 12)")
      ->check(CLI::Range(2, 255));
  cmd->add_option("--machine", o->machine,
                  "Retrofit mode, once per axis: a machine file (a scenario with controller: {device: wf725-726, "
                  "parameters: MD-LIST, programs: [...], db: N, axis: A} and the axis under machine.axes on its "
                  "drive: a CiA 402 drive over canopen, modbus, sim; io_links and io: stimuli wire its switches) "
                  "instead of --md/--program/--module/--axis/--db");
  cmd->footer(
      "Console commands (stdin): 'status' (per axis: mode, submode, actual value, PEH/SYN, error DR 4, DW 40, "
      "program and block), 'machine' (the machine axes: position, state, fault), 'input NAME 0|1' (an input of the "
      "module: X7 x7_e1..6 on every axis, limit_plus_A, the encoder fault inputs encoder_cable_break_A, ...), "
      "'programs' (the program memory), 'rejection' (why the last RK512 job was refused), 'dbs' (user data "
      "blocks), 'quit'.\n"
      "Examples: hilbridge emulate wf725 --pty --md examples/controllers/wf725-axis-a.txt --program progs.wf\n"
      "          hilbridge emulate wf725 --pty --module WF726A --md axis-a.txt --md axis-b.txt --md axis-c.txt\n"
      "          hilbridge emulate wf725 --tcp 4001 --machine wf-canopen.yaml   (retrofit mode, e.g. behind a "
      "serial-over-IP adapter)");
  cmd->callback([&ctx, o] {
    const auto fail = [&](const std::string& what) {
      fmt::print(stderr, "error: {}\n", what);
      ctx.exit_code = 2;
    };
    std::vector<std::unique_ptr<MachineFile>> machines;
    if (!o->machine.empty()) {
      if (!o->md.empty() || !o->programs.empty() || !o->module.empty() || !o->axis.empty() || !o->db.empty())
        return fail(
            "--machine: the machine files' controller blocks give the MD lists, programs, module, axis letters and "
            "DB numbers: drop --md, --program, --module, --axis and --db");
      if (o->machine.size() > s5c::wf725_max_axes)
        return fail("--machine: a WF 725/726 has at most 3 axes: give 1..3 machine files, one per axis");
      for (const auto& file : o->machine) {
        if (!std::filesystem::exists(file)) return fail(fmt::format("--machine: {} does not exist", file));
        auto sc = hil::runtime::load_scenario(file);
        if (!sc) return fail("--machine: " + sc.error().describe());
        // The WF module model (not the parameter-only controller): its DB axis is what the line serves.
        if (sc->controller && sc->controller->device == "wf725-726" && !sc->controller->options.contains("db"))
          sc->controller->options.emplace("db", std::to_string(10 + machines.size()));
        auto built = build_machine<MachineFile>(
            std::move(*sc), ctx.transports, [&](const hil::runtime::Scenario& s) { return check_machine(s, file); });
        if (!built) return fail("--machine: " + built.error());
        machines.push_back(std::move(*built));
      }
    } else {
      if (o->md.empty())
        return fail(
            "give each axis' machine data with --md FILE (MD 1..50, profile wf725-726, e.g. "
            "examples/controllers/wf725-axis-a.txt; once per axis) or machine files with --machine");
      const auto axes = sim_axes(*o);
      if (!axes) return fail(axes.error());
      for (std::size_t i = 0; i < axes->size(); ++i) {
        auto sc = hil::runtime::parse_scenario(sim_scenario(*o, (*axes)[i], i == 0), "emulate wf725");
        if (!sc) return fail(sc.error().describe());
        auto built = build_machine<MachineFile>(std::move(*sc), ctx.transports,
                                                [](const hil::runtime::Scenario&) { return std::string(); });
        if (!built) return fail(fmt::format("axis {}: {}", (*axes)[i].letter, built.error()));
        machines.push_back(std::move(*built));
      }
    }
    std::vector<s5c::Wf725Controller*> ctls;
    for (auto& m : machines) {
      auto* ctl = dynamic_cast<s5c::Wf725Controller*>(m->machine->controller());
      if (ctl == nullptr)
        return fail(
            "the machine file's wf725-726 controller is not one axis of the module model (give it db: N or "
            "programs:; one machine file per axis: axis_b/axis_c are for scenarios)");
      if (ctl->interface_db().number == s5c::wf725_md_image_db)
        return fail("db: 1 is the MD image of the emulator: give the DB axis another number (2..255)");
      for (const auto* c : ctls) {
        if (c->interface_db().number == ctl->interface_db().number)
          return fail(fmt::format("axes {} and {} have the same DB axis DB{}: give each its own number",
                                  c->axis_specs()[0].name, ctl->axis_specs()[0].name, ctl->interface_db().number));
        if (c->axis_specs()[0].name == ctl->axis_specs()[0].name)
          return fail(
              fmt::format("two axes are named {}: a module has the axes A, B, C once each", ctl->axis_specs()[0].name));
      }
      ctls.push_back(ctl);
    }
    // Every axis' programs go into the module's one memory (the first axis'): a --machine file's
    // programs: of a later axis are stored there too.
    for (std::size_t i = 1; i < ctls.size(); ++i)
      for (const auto& p : ctls[i]->programs().all())
        if (const int e = ctls.front()->store_program(p))
          return fail(fmt::format("axis {}: program {} does not fit the module's memory (WF message {})",
                                  ctls[i]->axis_specs()[0].name, p.number, e));
    // Split drive (MD 27 of axis A, docs/wf725.md "Split drive"): the partner follows axis A. Each
    // period axis A's machine cycles first; every axis takes its split-drive set-point before its
    // update.
    if (auto coupled = s5c::wf725_couple_split_drive(ctls); !coupled) return fail(coupled.error());
    std::vector<std::pair<MachineFile*, s5c::Wf725Controller*>> order;
    for (std::size_t i = 0; i < machines.size(); ++i) order.emplace_back(machines[i].get(), ctls[i]);
    std::stable_partition(order.begin(), order.end(), [](const auto& p) { return p.second->axis_letter() == 'A'; });
    std::vector<MachineFile*> ms;
    for (auto& m : machines) ms.push_back(m.get());
    auto policy =
        std::make_unique<s5c::Wf725ModulePolicy>(ctls, machines.front()->scenario.period, [order](const CycleTime& c) {
          for (const auto& [m, ctl] : order) {
            m->io.poll();
            ctl->split_drive_period(c);
            m->machine->cycle(c);
          }
        });
    auto* pol = policy.get();
    lg::S5BlockEndpoint ep(std::move(policy));
    pol->share_store(ep.store());
    const auto locked = resolve_state(o->e, "wf725");
    if (!locked) return fail(locked.error());
    const auto& state = *locked;
    if (auto text = read_file(state))
      if (auto r = ep.load_state(*text); !r) fmt::print(stderr, "warning: {}\n", r.error());
    ctx.exit_code = serve(ep, o->e, state, [pol, ms](lg::Endpoint& e, const std::string& c) -> std::string {
      return console(static_cast<lg::S5BlockEndpoint&>(e), *pol, ms, c);
    });
  });
}

}  // namespace hil::cli::serial_cli
