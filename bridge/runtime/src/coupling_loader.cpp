// SPDX-License-Identifier: MIT
// Scenario keys of coupled motion (docs/scenarios.md "Coupling").
#include "coupling_loader.hpp"

#include <algorithm>
#include <numeric>

#include <fmt/format.h>

#include "hil/runtime/scenario_loader.hpp"

namespace hil::runtime::detail {
namespace {

bool valid_name(const std::string& n) {
  if (n.empty() || n.size() > 32) return false;
  return std::all_of(n.begin(), n.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-'; });
}

// A signed exact ratio: "3/2", "-1", "0.75", "-12.5/7".
std::pair<std::int64_t, std::int64_t> signed_ratio(const Field& f, std::string_view what) {
  std::string text;
  if (f.node().IsScalar()) text = f.node().Scalar();
  bool neg = !text.empty() && text.front() == '-';
  const auto r = parse_ratio(neg ? std::string_view(text).substr(1) : std::string_view(text));
  if (!r) f.fail(fmt::format("expected {} as an integer, 'num/den' or a decimal (not 0), got {}", what, f.describe()));
  const std::int64_t g = std::gcd(r->first, r->second);
  return {(neg ? -1 : 1) * (r->first / g), r->second / g};
}

}  // namespace

void load_coupling_machine(const Field& machine, Scenario& s) {
  auto taken = [&](const std::string& n) {
    if (s.find_axis(n)) return true;
    for (const auto& m : s.masters)
      if (m.name == n) return true;
    return false;
  };
  if (auto ms = machine.child("masters"); ms.present()) {
    for (const Field& f : ms.items()) {
      f.expect_map({"name", "units", "inc_per_unit"});
      VirtualMasterSpec m;
      m.source = {f.line(), f.path()};
      const Field name = f.required("name", "the master's name");
      m.name = name.as_string("a master name");
      if (!valid_name(m.name)) name.fail("names use letters, digits, '_' and '-' (1..32 characters)");
      if (taken(m.name)) name.fail(fmt::format("'{}' is already an axis or master name", m.name));
      if (auto u = f.child("units"); u.present()) m.units = u.as_string("a unit name");
      if (auto r = f.child("inc_per_unit"); r.present()) {
        const auto v = parse_ratio(r.as_string("a ratio"));
        if (!v)
          r.fail(fmt::format("expected increments per unit (integer, 'num/den' or decimal > 0), got {}", r.describe()));
        m.inc_per_unit_num = v->first;
        m.inc_per_unit_den = v->second;
      }
      s.masters.push_back(std::move(m));
    }
  }
  if (auto cs = machine.child("cams"); cs.present()) {
    for (const Field& f : cs.items()) {
      f.expect_map({"name", "interpolation", "periodic", "start_slope", "end_slope", "points"});
      CamSpec c;
      c.source = {f.line(), f.path()};
      const Field name = f.required("name", "the cam table's name");
      c.name = name.as_string("a cam name");
      for (const auto& o : s.cams)
        if (o.name == c.name) name.fail(fmt::format("cam '{}' is defined twice", c.name));
      if (auto i = f.child("interpolation"); i.present())
        c.table.interpolation = static_cast<motion::CamInterpolation>(
            i.as_enum({"linear", "cubic_natural", "cubic_clamped", "cubic_periodic"}));
      if (auto p = f.child("periodic"); p.present()) c.table.periodic = p.as_bool();
      if (auto v = f.optional_number("start_slope", "a slope in slave units per master unit")) c.table.start_slope = *v;
      if (auto v = f.optional_number("end_slope", "a slope in slave units per master unit")) c.table.end_slope = *v;
      const Field pts = f.required("points", "a list of [master, slave] pairs in units, from [0, 0]");
      for (const Field& p : pts.items()) {
        if (!p.node().IsSequence() || p.node().size() != 2)
          p.fail(fmt::format("expected a pair [master, slave] in units, got {}", p.describe()));
        const auto it = p.items();
        c.table.points.push_back(
            {it[0].as_number("a master position in units"), it[1].as_number("a slave position in units")});
      }
      // Check the shape here (in units) so the error points at the file; the machine scales it.
      if (auto t = motion::CamTable::make([&] {
            auto spec = c.table;
            spec.periodic = false;  // whole increments are checked once the units are known
            if (spec.interpolation == motion::CamInterpolation::cubic_periodic) spec.periodic = true;
            return spec;
          }());
          !t && t.error().find("whole increments") == std::string::npos)
        pts.fail(t.error());
      s.cams.push_back(std::move(c));
    }
  }
  if (auto cs = machine.child("couplings"); cs.present()) {
    for (const Field& f : cs.items()) {
      f.expect_map({"slave", "master", "source", "limits"});
      CouplingSpec c;
      c.source = {f.line(), f.path()};
      const Field slave = f.required("slave", "the slave axis");
      c.slave = slave.as_string("an axis name");
      if (!s.find_axis(c.slave)) slave.fail(fmt::format("unknown axis '{}'", c.slave));
      for (const auto& o : s.couplings)
        if (o.slave == c.slave) slave.fail(fmt::format("axis '{}' is already the slave of a coupling", c.slave));
      const Field master = f.required("master", "an axis, a virtual master (machine.masters) or 'time'");
      c.master = master.as_string("a master name");
      if (c.master == "time") {
        c.source_kind = MasterSource::time;
      } else if (s.find_axis(c.master)) {
        if (c.master == c.slave) master.fail("an axis cannot be its own master");
        c.source_kind = MasterSource::axis_command;
        if (auto src = f.child("source"); src.present())
          c.source_kind =
              src.as_enum({"command", "actual"}) == 0 ? MasterSource::axis_command : MasterSource::axis_actual;
      } else {
        bool found = false;
        for (const auto& m : s.masters) found = found || m.name == c.master;
        if (!found)
          master.fail(fmt::format("unknown master '{}': not an axis, not in machine.masters, not 'time'", c.master));
        c.source_kind = MasterSource::virtual_axis;
      }
      if (f.child("source").present() && c.source_kind != MasterSource::axis_command &&
          c.source_kind != MasterSource::axis_actual)
        f.child("source").fail("'source' (command/actual) applies to axis masters only");
      if (auto l = f.child("limits"); l.present()) {
        l.expect_map({"velocity", "acceleration", "acceleration_filter", "following_error"});
        c.velocity = l.optional_positive("velocity", "a slave velocity in units/s").value_or(0.0);
        c.acceleration = l.optional_positive("acceleration", "a slave acceleration in units/s^2").value_or(0.0);
        if (auto af = l.child("acceleration_filter"); af.present()) {
          const double n = af.as_positive("a number of cycles (1..64)");
          if (n != std::floor(n) || n > 64) af.fail("expected a whole number of cycles, 1..64");
          c.acceleration_filter_cycles = static_cast<int>(n);
        }
        c.following_error = l.optional_positive("following_error", "a window in slave units").value_or(0.0);
      }
      s.couplings.push_back(std::move(c));
    }
  }
}

CoupleStep load_couple_step(const Field& v, const Scenario& s) {
  v.expect_map({"slave", "master", "gear", "cam", "disengage", "velocity", "acceleration", "superimpose", "at", "ramp",
                "phase"});
  CoupleStep c;
  const auto find_coupling = [&](const Field& f) {
    const std::string n = f.as_string("a slave axis");
    for (const auto& k : s.couplings)
      if (k.slave == n) return n;
    f.fail(fmt::format("axis '{}' is not the slave of a coupling in machine.couplings", n));
  };
  int actions = 0;
  if (v.child("gear").present()) ++actions;
  if (v.child("cam").present()) ++actions;
  if (v.child("disengage").present()) ++actions;
  if (v.child("superimpose").present()) ++actions;
  if (v.child("master").present()) ++actions;
  if (actions != 1)
    v.fail(
        "a couple step does exactly one of: gear: RATIO, cam: TABLE, disengage: true, superimpose: DISTANCE "
        "(each with slave:), or master: NAME with velocity:");
  if (auto m = v.child("master"); m.present()) {
    c.action = CoupleStep::Action::master_velocity;
    c.slave = m.as_string("a virtual master");
    bool found = false;
    for (const auto& vm : s.masters) found = found || vm.name == c.slave;
    if (!found) m.fail(fmt::format("unknown virtual master '{}' (machine.masters)", c.slave));
    c.velocity = v.required("velocity", "the master velocity in units/s").as_number("a velocity in units/s");
    c.acceleration = v.required("acceleration", "the ramp in units/s^2").as_positive("an acceleration in units/s^2");
    for (const char* k : {"slave", "at", "ramp", "phase"})
      if (v.child(k).present()) v.child(k).fail(fmt::format("'{}' does not apply to a master velocity change", k));
    return c;
  }
  c.slave = find_coupling(v.required("slave", "the coupled slave axis"));
  if (auto a = v.child("at"); a.present()) c.at = a.as_number("a master position in master units");
  if (auto r = v.child("ramp"); r.present()) c.ramp = r.as_non_negative("a ramp length in master units");
  if (auto g = v.child("gear"); g.present()) {
    c.action = CoupleStep::Action::gear;
    const auto [n, d] = signed_ratio(g, "a gear ratio in slave units per master unit");
    c.ratio_num = n;
    c.ratio_den = d;
  } else if (auto cm = v.child("cam"); cm.present()) {
    c.action = CoupleStep::Action::cam;
    c.cam = cm.as_string("a cam table name");
    bool found = false;
    for (const auto& t : s.cams) found = found || t.name == c.cam;
    if (!found) cm.fail(fmt::format("unknown cam '{}' (machine.cams)", c.cam));
    if (auto p = v.child("phase"); p.present()) c.phase = p.as_non_negative("a table position in master units");
    if (v.child("ramp").present()) v.child("ramp").fail("a cam starts without a ramp (use a coupling table)");
  } else if (auto dz = v.child("disengage"); dz.present()) {
    c.action = CoupleStep::Action::disengage;
    if (!dz.as_bool()) dz.fail("expected 'disengage: true'");
  } else if (auto sp = v.child("superimpose"); sp.present()) {
    c.action = CoupleStep::Action::superimpose;
    c.distance = sp.as_number("a distance in slave units");
    c.velocity = v.required("velocity", "the superimposed velocity in units/s").as_positive("a velocity in units/s");
    c.acceleration =
        v.required("acceleration", "the superimposed ramp in units/s^2").as_positive("an acceleration in units/s^2");
    for (const char* k : {"at", "ramp"})
      if (v.child(k).present()) v.child(k).fail(fmt::format("'{}' does not apply to a superimposed move", k));
  }
  if (c.action != CoupleStep::Action::cam && v.child("phase").present())
    v.child("phase").fail("'phase' applies to 'cam:' only");
  return c;
}

}  // namespace hil::runtime::detail
