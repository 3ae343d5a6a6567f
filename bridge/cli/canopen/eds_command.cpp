// SPDX-License-Identifier: MIT
// `hilbridge canopen eds check|show FILE`: what an EDS/DCF declares (identity, objects, PDO capabilities,
// CiA 402 modes), the parser's warnings, and what hilbridge's master will do with it on an axis
// in each setup (PDO layout, SDO-polled / SDO-written objects, what is missing).
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "hil/canopen/eds.hpp"
#include "hil/cia402/layout.hpp"
#include "hil/cli/context.hpp"

namespace hil::cli::canopen_cli {
namespace {

namespace co = hil::canopen;

struct EdsArgs {
  std::string file;
  int node = 0;      ///< 0: the DCF's NodeID, else 1
  std::string mode;  ///< empty: every setup
  bool json = false;
};

std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20)
          out += fmt::format("\\u{:04x}", static_cast<unsigned>(static_cast<unsigned char>(c)));
        else
          out.push_back(c);
    }
  }
  return out + "\"";
}

std::string modes_text(std::uint32_t m) {
  static constexpr std::pair<std::uint32_t, const char*> names[] = {
      {1u << 0, "PP"}, {1u << 1, "VL"},  {1u << 2, "PV"},  {1u << 3, "TQ"}, {1u << 5, "HM"},
      {1u << 6, "IP"}, {1u << 7, "CSP"}, {1u << 8, "CSV"}, {1u << 9, "CST"}};
  std::string list;
  for (auto [bit, name] : names)
    if (m & bit) list += (list.empty() ? "" : ", ") + std::string(name);
  return list.empty() ? "none" : list;
}

struct PdoSummary {
  int count = 0;
  int fixed = 0;
  std::size_t max_entries = 0;
};

PdoSummary pdo_summary(const co::DeviceDescription& d, bool rx) {
  PdoSummary s;
  for (unsigned n = 0; n < 512; ++n) {
    const auto comm = static_cast<std::uint16_t>((rx ? 0x1400 : 0x1800) + n);
    const auto map = static_cast<std::uint16_t>((rx ? 0x1600 : 0x1A00) + n);
    if (d.od.find(comm, 1) == nullptr || !d.od.has_object(map)) continue;
    ++s.count;
    std::size_t entries = 0;
    for (std::uint8_t k = 1; k <= 8; ++k)
      if (d.od.find(map, k)) entries = k;
    s.max_entries = std::max(s.max_entries, entries);
    const auto* sub0 = d.od.find(map, 0);
    if ((d.info.granularity && *d.info.granularity == 0) || sub0 == nullptr || !co::writable(sub0->access)) ++s.fixed;
  }
  return s;
}

int run_eds(const EdsArgs& a, bool show) {
  std::ifstream in(a.file, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "hilbridge eds: cannot open '%s': check the path\n", a.file.c_str());
    return 2;
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  auto d = co::parse_eds(ss.str(), a.file, static_cast<co::NodeId>(a.node));
  if (d && a.node == 0 && !d->dcf_node_id) d = co::parse_eds(ss.str(), a.file, 1);
  const int node = a.node != 0 ? a.node : (d && d->dcf_node_id ? *d->dcf_node_id : 1);
  if (!d) {
    if (a.json)
      fmt::print("{{\"file\": {}, \"ok\": false, \"error\": {}}}\n", json_string(a.file),
                 json_string(d.error().describe()));
    else
      fmt::print(stderr, "hilbridge eds: {} is rejected: {}\n", a.file, d.error().describe());
    return 1;
  }
  std::vector<cia402::OperatingSetup> setups;
  if (a.mode.empty() || a.mode == "csp") setups.push_back(cia402::OperatingSetup::csp);
  if (a.mode.empty() || a.mode == "csv") setups.push_back(cia402::OperatingSetup::csv);
  if (a.mode.empty() || a.mode == "pp") setups.push_back(cia402::OperatingSetup::pp);
  struct Plan {
    cia402::OperatingSetup setup;
    std::expected<cia402::AxisConfig, ConfigError> config;
  };
  std::vector<Plan> plans;
  bool usable = false;
  for (auto s : setups) {
    cia402::AxisOptions o;
    o.node = static_cast<co::NodeId>(node);
    o.setup = s;
    plans.push_back({s, cia402::make_axis_config(*d, o)});
    usable = usable || plans.back().config.has_value();
  }
  const auto device_type = d->od.find(0x1000, 0) ? static_cast<std::uint32_t>(d->od.get_int(0x1000, 0)) : 0u;
  const auto* modes = d->od.find(0x6502, 0);
  const auto rx = pdo_summary(*d, true);
  const auto tx = pdo_summary(*d, false);
  std::size_t objects = 0;
  {
    int last = -1;
    for (const auto& [key, v] : d->od.variables())
      if (v.index != last) {
        ++objects;
        last = v.index;
      }
  }
  if (a.json) {
    std::string out = "{";
    out += fmt::format("\"file\": {}, \"ok\": true, \"dcf\": {}, \"usable_as_axis\": {}, ", json_string(a.file),
                       d->is_dcf, usable);
    out += fmt::format(
        "\"identity\": {{\"vendor_name\": {}, \"vendor_id\": {}, \"product_name\": {}, \"product_code\": {}, "
        "\"revision\": {}, \"device_type\": {}}}, ",
        json_string(d->info.vendor_name), d->info.vendor_number, json_string(d->info.product_name),
        d->info.product_number, d->info.revision_number, device_type);
    out += fmt::format("\"objects\": {}, \"sub_objects\": {}, ", objects, d->od.size());
    out += fmt::format(
        "\"pdos\": {{\"rx\": {{\"count\": {}, \"fixed\": {}, \"max_entries\": {}}}, \"tx\": {{\"count\": {}, "
        "\"fixed\": {}, \"max_entries\": {}}}}}, ",
        rx.count, rx.fixed, rx.max_entries, tx.count, tx.fixed, tx.max_entries);
    out += modes ? fmt::format("\"supported_modes\": {}, ", modes->as_uint()) : "\"supported_modes\": null, ";
    out += "\"warnings\": [";
    for (std::size_t i = 0; i < d->warnings.size(); ++i) {
      const auto& w = d->warnings[i];
      out += fmt::format("{}{{\"line\": {}, \"key\": {}, \"message\": {}}}", i ? ", " : "", w.line, json_string(w.key),
                         json_string(w.message));
    }
    out += "], \"axis\": {";
    for (std::size_t i = 0; i < plans.size(); ++i) {
      const auto& p = plans[i];
      out += fmt::format("{}{}: ", i ? ", " : "", json_string(cia402::to_string(p.setup)));
      if (!p.config) {
        out += fmt::format("{{\"ok\": false, \"error\": {}}}", json_string(p.config.error().message));
        continue;
      }
      out += "{\"ok\": true, \"decisions\": [";
      const auto& dec = p.config->layout.decisions;
      for (std::size_t k = 0; k < dec.size(); ++k) out += (k ? ", " : "") + json_string(dec[k]);
      out += "], \"sdo_polled\": [";
      const auto polled = p.config->layout.polled();
      for (std::size_t k = 0; k < polled.size(); ++k) out += fmt::format("{}{}", k ? ", " : "", polled[k].index);
      out += "], \"sdo_written\": [";
      const auto written = p.config->layout.written();
      for (std::size_t k = 0; k < written.size(); ++k) out += fmt::format("{}{}", k ? ", " : "", written[k].index);
      out += "]}";
    }
    out += "}}";
    fmt::print("{}\n", out);
    return usable ? 0 : 1;
  }
  fmt::print("file: {} ({})\n", a.file, d->is_dcf ? "DCF" : "EDS");
  fmt::print("identity: vendor 0x{:08X} '{}', product 0x{:08X} '{}', revision 0x{:08X}\n", d->info.vendor_number,
             d->info.vendor_name, d->info.product_number, d->info.product_name, d->info.revision_number);
  fmt::print("device type: 0x{:08X}{}\n", device_type,
             (device_type & 0xFFFF) == 402 ? " (CiA 402 drive)" : " (not a CiA 402 drive)");
  fmt::print("objects: {} objects, {} sub-objects\n", objects, d->od.size());
  fmt::print("PDOs: {} RPDO(s), {} TPDO(s), up to {} / {} entries, {} / {} fixed{}\n", rx.count, tx.count,
             rx.max_entries, tx.max_entries, rx.fixed, tx.fixed,
             d->info.granularity ? fmt::format(", Granularity {}", *d->info.granularity) : std::string());
  if (modes)
    fmt::print("modes (0x6502): 0x{:08X} = {}\n", modes->as_uint(),
               modes_text(static_cast<std::uint32_t>(modes->as_uint())));
  else
    fmt::print("modes (0x6502): not declared\n");
  if (d->is_dcf) fmt::print("DCF: {} ParameterValue(s) to download at boot\n", d->parameter_values.size());
  fmt::print("warnings: {}\n", d->warnings.size());
  for (const auto& w : d->warnings) fmt::print("  {}\n", w.describe());
  for (const auto& p : plans) {
    fmt::print("axis (node {}, mode {}): ", node, cia402::to_string(p.setup));
    if (!p.config) {
      fmt::print("not usable: {}\n", p.config.error().message);
      continue;
    }
    fmt::print("ok\n");
    for (const auto& line : p.config->layout.decisions) fmt::print("  {}\n", line);
  }
  if (show) {
    fmt::print("object dictionary:\n");
    for (const auto& [key, v] : d->od.variables()) {
      std::string value;
      if (co::is_integer(v.type))
        value = fmt::format("{}", co::is_signed(v.type) ? v.as_int() : static_cast<std::int64_t>(v.as_uint()));
      else if (v.type == co::DataType::visible_string)
        value = "'" + std::string(v.value.begin(), v.value.end()) + "'";
      else
        value = fmt::format("{} byte(s)", v.value.size());
      fmt::print("  0x{:04X}:{:<3} {:<40} {:<15} {:<5} {:<4} {}\n", v.index, v.sub, v.name.substr(0, 40),
                 co::to_string(v.type), co::to_string(v.access), v.pdo_mappable ? "PDO" : "", value);
    }
  }
  if (!usable)
    fmt::print(stderr, "hilbridge eds: {} cannot drive a CiA 402 axis in {}\n", a.file,
               a.mode.empty() ? "any mode" : "mode " + a.mode);
  return usable ? 0 : 1;
}

}  // namespace

CLI::App* register_eds(Context& ctx, CLI::App& parent) {
  auto* eds = parent.add_subcommand("eds", "Check or show an EDS/DCF file and what hilbridge's master does with it");
  eds->require_subcommand(1);
  for (const bool show : {false, true}) {
    auto a = std::make_shared<EdsArgs>();
    auto* c = eds->add_subcommand(show ? "show" : "check",
                                  show ? "Everything `check` prints, plus every object of the dictionary"
                                       : "Identity, PDO capabilities, modes, warnings and the axis layout per mode");
    c->add_option("FILE", a->file, "EDS or DCF file")->required();
    c->add_option("--node", a->node, "Node-ID for $NODEID expressions (default 1, or the DCF's NodeID)")
        ->check(CLI::Range(1, 127));
    c->add_option("--mode", a->mode, "Only this setup: csp, csv or pp (default: all three)")
        ->check(CLI::IsMember({"csp", "csv", "pp"}));
    c->add_flag("--json", a->json, "One JSON object on stdout");
    c->footer(
        "Exit status: 0 the file parses and can drive a CiA 402 axis (in the given mode, or in one of them),\n"
        "1 the file is rejected or no setup is usable (the reasons are printed), 2 the file cannot be opened.\n"
        "Examples:\n"
        "  hilbridge canopen eds check drive.eds\n"
        "  hilbridge canopen eds show axis.dcf --mode pp --json");
    c->callback([&ctx, a, show] { ctx.exit_code = run_eds(*a, show); });
  }
  return eds;
}

}  // namespace hil::cli::canopen_cli
