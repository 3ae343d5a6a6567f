// SPDX-License-Identifier: MIT
// CLI module `canopen`: the `hilbridge canopen` group (`sdo read|write`, `nmt ...`, `scan`,
// `eds check|show`; docs/cli.md "Command groups"; the old top-level names are hidden aliases
// that warn), `hilbridge emulate cia402`, and the `canopen` transport for `hilbridge run`.
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "hil/canopen/nmt.hpp"
#include "hil/canopen/sdo_client.hpp"
#include "hil/cia402/canopen_transport.hpp"
#include "hil/cli/context.hpp"
#include "hil/cli/duration_option.hpp"
#include "hil/cli/json_output.hpp"
#include "hil/cli/progress.hpp"
#include "session.hpp"
#include "values.hpp"

namespace hil::cli {
namespace canopen_cli {
void register_emulate_cia402(Context& ctx);
CLI::App* register_eds(Context& ctx, CLI::App& parent);
}  // namespace canopen_cli

namespace {

using namespace canopen_cli;
namespace co = hil::canopen;

constexpr const char* k_bus_help =
    "Bus URL: a SocketCAN interface (vcan0, can0), socketcand://HOST[:PORT]/BUS (e.g. the hub of "
    "`hilbridge can hub`), or virtual:NAME";

struct SdoArgs {
  std::string bus;
  int node = 0;
  std::string object;
  std::string value;
  std::string type;
  Duration timeout = std::chrono::milliseconds(500);
  int retries = 0;
  bool block = false;
  bool json = false;  ///< read --json (docs/json.md)
};

/// The value of an SDO upload for --json: a number for the integer, boolean and real types, the
/// formatted text otherwise (x: "0x00000A11", vs: the string, os/d: hex bytes); without --type the
/// unsigned little-endian value of 1..8 bytes, else null.
nlohmann::json value_json(const std::string& type, const std::vector<std::uint8_t>& bytes) {
  if (type.empty()) {
    if (bytes.empty() || bytes.size() > 8) return nullptr;
    std::uint64_t u = 0;
    for (std::size_t i = 0; i < bytes.size(); ++i) u |= std::uint64_t{bytes[i]} << (8 * i);
    return u;
  }
  const std::string text = format_value(type, bytes);
  if (type == "b" || type.starts_with('i') || type.starts_with('u') || type.starts_with('r')) {
    auto j = nlohmann::json::parse(text, nullptr, false);
    if (!j.is_discarded() && j.is_number()) return j;
  }
  return text;
}

int run_sdo(const SdoArgs& a, bool upload) {
  const char* cmd = upload ? "sdo read" : "sdo write";
  const std::string prefix = fmt::format("hilbridge {}: ", cmd);
  const auto failed = [&](const std::string& what, int code, nlohmann::json extra = nlohmann::json::object()) {
    return report_error(a.json, prefix, what, code, std::move(extra));
  };
  auto obj = parse_object(a.object);
  if (!obj) return failed(obj.error(), 2);
  std::vector<std::uint8_t> data;
  if (!upload) {
    if (a.type.empty()) {
      std::fprintf(stderr, "hilbridge %s: --type is required for a write (one of: %s)\n", cmd,
                   value_types_help().c_str());
      return 2;
    }
    auto enc = encode_value(a.type, a.value);
    if (!enc) {
      std::fprintf(stderr, "hilbridge %s: VALUE %s\n", cmd, enc.error().c_str());
      return 2;
    }
    data = std::move(*enc);
  } else if (!a.type.empty() && !is_value_type(a.type)) {
    return failed(fmt::format("unknown --type '{}'; use one of: {}", a.type, value_types_help()), 2);
  }
  BusSession s(a.bus, "hilbridge-sdo");
  if (!s.ok()) return failed(fmt::format("--bus {}: {}", a.bus, s.error()), 1);
  co::SdoClientOptions o;
  o.timeout = a.timeout;
  o.retries = a.retries;
  o.block = a.block;
  co::SdoClient client(
      static_cast<co::NodeId>(a.node),
      [&](const can::Frame& f) {
        if (auto ec = s.channel().send(f))
          std::fprintf(stderr, "hilbridge %s: send failed: %s\n", cmd, ec.message().c_str());
      },
      o);
  s.channel().set_receive_handler([&](const can::Frame& f, TimePoint t) { client.on_frame(f, t); });
  std::optional<ProgressBar> bar;
  client.set_progress([&](std::size_t done, std::size_t total) {
    if (total < 1024) return;
    if (!bar) bar.emplace(fmt::format("node {} {}", a.node, a.object), total, "B", s.clock());
    bar->update(done);
  });
  bool finished = false;
  std::error_code result;
  std::vector<std::uint8_t> value;
  auto done = [&](std::error_code ec, std::vector<std::uint8_t> d) {
    finished = true;
    result = ec;
    value = std::move(d);
  };
  if (upload)
    client.async_upload(obj->first, obj->second, s.now(), done);
  else
    client.async_download(obj->first, obj->second, data, s.now(), done);
  const auto limit = o.timeout * (a.retries + 1) * 4 + std::chrono::seconds(2) + std::chrono::milliseconds(data.size());
  s.run([&] { return finished; }, [&](TimePoint t) { client.step(t); }, limit);
  if (bar) bar->finish(finished && !result ? "done" : "failed");
  if (!finished) return failed(fmt::format("node {} did not complete the transfer", a.node), 1);
  if (result) {
    nlohmann::json extra{{"node", a.node},
                         {"index", fmt::format("0x{:04X}", obj->first)},
                         {"subindex", obj->second},
                         {"abort_code", fmt::format("0x{:08X}", static_cast<std::uint32_t>(result.value()))}};
    return failed(fmt::format("node {} {}: SDO abort {}", a.node, a.object, result.message()), 1, std::move(extra));
  }
  if (upload && a.json) {
    print_json({{"bus", a.bus},
                {"node", a.node},
                {"index", fmt::format("0x{:04X}", obj->first)},
                {"subindex", obj->second},
                {"type", a.type.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.type)},
                {"size", value.size()},
                {"data", hex_bytes(value.data(), value.size())},
                {"value", value_json(a.type, value)},
                {"text", format_value(a.type, value)}});
  } else if (upload) {
    std::printf("%s\n", format_value(a.type, value).c_str());
  }
  return 0;
}

CLI::App* register_sdo(Context& ctx, CLI::App& parent) {
  auto* sdo = parent.add_subcommand("sdo", "Read or write one object of a CANopen node with SDO (CiA 301)");
  sdo->require_subcommand(1);
  for (const bool upload : {true, false}) {
    auto a = std::make_shared<SdoArgs>();
    auto* c = sdo->add_subcommand(upload ? "read" : "write",
                                  upload ? "SDO upload: print the value of NODE INDEX:SUB"
                                         : "SDO download: write VALUE (given --type) to NODE INDEX:SUB");
    c->add_option("--bus", a->bus, k_bus_help)->required();
    c->add_option("node", a->node, "Node-ID 1..127")->required()->check(CLI::Range(1, 127));
    c->add_option("object", a->object, "Object as INDEX:SUB in hex, e.g. 0x1018:1 or 6041:0")->required();
    if (!upload)
      c->add_option("value", a->value, "Value in the --type's notation (integers: decimal or 0x hex)")->required();
    c->add_option("--type,-t", a->type,
                  "Value type: " + value_types_help() + (upload ? " (default: raw hex and unsigned)" : ""));
    add_duration_option(*c, "--timeout", a->timeout, "Timeout per SDO answer, e.g. 2s (default 500ms; 1ms .. 10min)",
                        "ms", {std::chrono::milliseconds(1), std::chrono::minutes(10)});
    c->add_option("--retries", a->retries, "Retries after a timeout (default 0)")->check(CLI::Range(0, 10));
    c->add_flag("--block", a->block, "Use SDO block transfer (CRC-16) for values over 28 bytes");
    if (upload)
      c->add_flag("--json", a->json,
                  "Print one JSON object on stdout (value, raw bytes, text; docs/json.md); errors as "
                  "{\"error\": ...} with the abort code");
    c->footer(upload ? "Examples:\n  hilbridge canopen sdo read --bus vcan0 5 0x1018:1 --type x32\n"
                       "  hilbridge canopen sdo read --bus socketcand://127.0.0.1:29536/can0 5 0x1008:0 --type vs\n"
                       "Exit status: 0 ok, 1 abort/timeout (the CiA 301 abort code is printed), 2 usage."
                     : "Examples:\n  hilbridge canopen sdo write --bus vcan0 5 0x1017:0 100 --type u16\n"
                       "  hilbridge canopen sdo write --bus vcan0 5 0x6060:0 8 --type i8\n"
                       "Exit status: 0 ok, 1 abort/timeout (the CiA 301 abort code is printed), 2 usage.");
    c->callback([&ctx, a, upload] { ctx.exit_code = run_sdo(*a, upload); });
  }
  return sdo;
}

CLI::App* register_nmt(Context& ctx, CLI::App& parent) {
  struct NmtArgs {
    std::string command, bus, node;
  };
  auto a = std::make_shared<NmtArgs>();
  auto* c = parent.add_subcommand("nmt", "Send an NMT node-control command (CiA 301 §7.2.8.3.1)");
  c->add_option("command", a->command, "start | stop | preop | reset | reset-comm")
      ->required()
      ->check(CLI::IsMember({"start", "stop", "preop", "reset", "reset-comm"}));
  c->add_option("target", a->node, "Node-ID 1..127, or `all`")->required();
  c->add_option("--bus", a->bus, k_bus_help)->required();
  c->footer(
      "Examples:\n  hilbridge canopen nmt start --bus vcan0 all\n  hilbridge canopen nmt reset-comm --bus vcan0 5\n"
      "`reset` is NMT reset node (0x81), `reset-comm` reset communication (0x82).");
  c->callback([&ctx, a] {
    co::NodeId node = 0;
    if (a->node != "all") {
      int n = 0;
      try {
        std::size_t pos = 0;
        n = std::stoi(a->node, &pos, 0);
        if (pos != a->node.size()) n = -1;
      } catch (...) {
        n = -1;
      }
      if (n < 1 || n > 127) {
        std::fprintf(stderr, "hilbridge nmt: target '%s' must be a node-ID 1..127 or `all`\n", a->node.c_str());
        ctx.exit_code = 2;
        return;
      }
      node = static_cast<co::NodeId>(n);
    }
    const std::map<std::string, co::NmtCommand> cmds{{"start", co::NmtCommand::start},
                                                     {"stop", co::NmtCommand::stop},
                                                     {"preop", co::NmtCommand::enter_preoperational},
                                                     {"reset", co::NmtCommand::reset_node},
                                                     {"reset-comm", co::NmtCommand::reset_communication}};
    BusSession s(a->bus, "hilbridge-nmt");
    if (!s.ok()) {
      std::fprintf(stderr, "hilbridge nmt: --bus %s: %s\n", a->bus.c_str(), s.error().c_str());
      ctx.exit_code = 1;
      return;
    }
    if (auto ec = s.channel().send(co::make_nmt(cmds.at(a->command), node))) {
      std::fprintf(stderr, "hilbridge nmt: send failed on %s: %s\n", a->bus.c_str(), ec.message().c_str());
      ctx.exit_code = 1;
      return;
    }
    s.run([] { return false; }, {}, std::chrono::milliseconds(20));  // let the frame leave
    ctx.exit_code = 0;
  });
  return c;
}

CLI::App* register_scan(Context& ctx, CLI::App& parent) {
  struct ScanArgs {
    std::string bus;
    Duration timeout = std::chrono::milliseconds(300);
    bool json = false;
  };
  auto a = std::make_shared<ScanArgs>();
  auto* c = parent.add_subcommand("scan",
                                  "Find CANopen nodes (SDO upload of 0x1000 to 1..127) and read their identity 0x1018");
  c->add_option("--bus", a->bus, k_bus_help)->required();
  add_duration_option(*c, "--timeout", a->timeout, "How long to wait for answers, e.g. 1s (default 300ms; 10ms .. 60s)",
                      "ms", {std::chrono::milliseconds(10), std::chrono::seconds(60)});
  c->add_flag("--json", a->json,
              "Print one JSON object on stdout: {\"nodes\": [{\"node\", \"device_type\", \"vendor_id\", ...}]} "
              "(docs/json.md)");
  c->footer(
      "Prints one line per node: node-ID, device type, vendor-ID, product code, revision, serial, name.\n"
      "Example:\n  hilbridge canopen scan --bus vcan0");
  c->callback([&ctx, a] {
    BusSession s(a->bus, "hilbridge-scan");
    if (!s.ok()) {
      ctx.exit_code = report_error(a->json, "hilbridge scan: ", fmt::format("--bus {}: {}", a->bus, s.error()), 1);
      return;
    }
    struct Found {
      std::uint32_t values[5]{};
      std::string name;
      int pending = 0;
      bool alive = false;
    };
    std::map<int, Found> found;
    std::vector<std::unique_ptr<co::SdoClient>> clients(128);
    co::SdoClientOptions o;
    o.timeout = a->timeout;
    int outstanding = 0;
    auto u32 = [](const std::vector<std::uint8_t>& d) {
      std::uint32_t v = 0;
      for (std::size_t i = 0; i < d.size() && i < 4; ++i) v |= std::uint32_t{d[i]} << (8 * i);
      return v;
    };
    for (int n = 1; n <= 127; ++n) {
      clients[n] = std::make_unique<co::SdoClient>(
          static_cast<co::NodeId>(n), [&](const can::Frame& f) { (void)s.channel().send(f); }, o);
      ++outstanding;
      clients[n]->async_upload(0x1000, 0, s.now(), [&, n](std::error_code ec, std::vector<std::uint8_t> d) {
        --outstanding;
        if (ec && ec != co::SdoAbort::timeout) found[n].alive = true;  // answered, with an abort
        if (ec) return;
        auto& f = found[n];
        f.alive = true;
        f.values[0] = u32(d);
        for (std::uint8_t sub = 1; sub <= 4; ++sub) {
          ++outstanding;
          clients[n]->async_upload(0x1018, sub, s.now(), [&, n, sub](std::error_code e, std::vector<std::uint8_t> v) {
            --outstanding;
            if (!e) found[n].values[sub] = u32(v);
          });
        }
        ++outstanding;
        clients[n]->async_upload(0x1008, 0, s.now(), [&, n](std::error_code e, std::vector<std::uint8_t> v) {
          --outstanding;
          if (!e) found[n].name.assign(v.begin(), v.end());
        });
      });
    }
    s.channel().set_receive_handler([&](const can::Frame& f, TimePoint t) {
      if (f.id > 0x580 && f.id <= 0x5FF) clients[f.id - 0x580]->on_frame(f, t);
    });
    s.run([&] { return outstanding == 0; },
          [&](TimePoint t) {
            for (int n = 1; n <= 127; ++n) clients[n]->step(t);
          },
          o.timeout * 8 + std::chrono::seconds(1));
    int count = 0;
    if (a->json) {
      // An abort to 0x1000 still counts as an answer; the identity members are then 0.
      nlohmann::json nodes = nlohmann::json::array();
      for (const auto& [n, f] : found) {
        if (!f.alive) continue;
        ++count;
        nodes.push_back({{"node", n},
                         {"device_type", f.values[0]},
                         {"vendor_id", f.values[1]},
                         {"product_code", f.values[2]},
                         {"revision", f.values[3]},
                         {"serial", f.values[4]},
                         {"name", f.name}});
      }
      print_json({{"bus", a->bus},
                  {"timeout_ms", std::chrono::duration_cast<std::chrono::milliseconds>(a->timeout).count()},
                  {"count", count},
                  {"nodes", std::move(nodes)}});
      std::fprintf(stderr, "%d node(s) answered on %s\n", count, a->bus.c_str());
      ctx.exit_code = 0;
      return;
    }
    std::printf("node  device-type  vendor-id   product     revision    serial      name\n");
    for (const auto& [n, f] : found) {
      if (!f.alive) continue;
      ++count;
      std::printf("%4d  0x%08X   0x%08X  0x%08X  0x%08X  0x%08X  %s\n", n, f.values[0], f.values[1], f.values[2],
                  f.values[3], f.values[4], f.name.c_str());
    }
    std::fprintf(stderr, "%d node(s) answered on %s\n", count, a->bus.c_str());
    ctx.exit_code = 0;
  });
  return c;
}

/// The old top-level spelling `hilbridge NAME ...` of `hilbridge canopen NAME ...`: hidden from
/// --help, works as before, and every use warns on stderr naming the new spelling.
void deprecate_top_level(CLI::App& cmd) {
  cmd.group("");
  cmd.preparse_callback([name = cmd.get_name()](std::size_t) {
    fmt::print(stderr, "hilbridge: warning: hilbridge {0} is deprecated; write hilbridge canopen {0}\n", name);
  });
}

}  // namespace

void register_canopen(Context& ctx) {
  // One grouping rule (docs/cli.md, "Command groups"): a command that speaks one protocol lives in
  // that protocol's group. The CANopen services and the EDS tools: `hilbridge canopen ...`.
  auto* group = ctx.app.add_subcommand(
      "canopen",
      "CANopen tools (CiA 301/306): sdo read|write, nmt, scan, eds check|show (the simulated node: "
      "`emulate cia402`)");
  group->require_subcommand(1);
  register_sdo(ctx, *group);
  register_nmt(ctx, *group);
  register_scan(ctx, *group);
  canopen_cli::register_eds(ctx, *group);
  for (CLI::App* old : {register_sdo(ctx, ctx.app), register_nmt(ctx, ctx.app), register_scan(ctx, ctx.app),
                        canopen_cli::register_eds(ctx, ctx.app)})
    deprecate_top_level(*old);
  canopen_cli::register_emulate_cia402(ctx);
  ctx.transports.add("canopen", [] { return cia402::make_canopen_transport(); });
}

}  // namespace hil::cli
