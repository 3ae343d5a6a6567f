// SPDX-License-Identifier: MIT
// `hilbridge modbus read|write`: quick register checks against a drive (libmodbus client), and
// registration of the `modbus` transport.
#include <modbus.h>

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "hil/cli/context.hpp"
#include "hil/cli/json_output.hpp"
#include "hil/cli/progress.hpp"
#include "hil/drives/modbus_transport.hpp"
#include "hil/modbus/adu.hpp"
#include "hil/modbus/error.hpp"
#include "hil/modbus/packing.hpp"

namespace hil::cli {

void register_emulate_modbus_drive(Context& ctx);  // emulate_modbus_drive.cpp
void register_emulate_modbus_io(Context& ctx);     // emulate_modbus_io.cpp

namespace {

struct Endpoint {
  std::string host;
  std::uint16_t port = modbus::kDefaultPort;
};

/// "host", "host:port", "[v6]:port".
std::optional<Endpoint> parse_endpoint(const std::string& s, std::string& why) {
  Endpoint e;
  std::string port_text;
  if (!s.empty() && s.front() == '[') {
    const auto close = s.find(']');
    if (close == std::string::npos) return why = "missing ']' in an IPv6 address", std::nullopt;
    e.host = s.substr(1, close - 1);
    if (close + 1 < s.size()) {
      if (s[close + 1] != ':') return why = "expected ':PORT' after ']'", std::nullopt;
      port_text = s.substr(close + 2);
    }
  } else if (const auto colon = s.rfind(':'); colon != std::string::npos && s.find(':') == colon) {
    e.host = s.substr(0, colon);
    port_text = s.substr(colon + 1);
  } else {
    e.host = s;
  }
  if (e.host.empty()) return why = "empty host", std::nullopt;
  if (!port_text.empty()) {
    unsigned v = 0;
    auto [p, ec] = std::from_chars(port_text.data(), port_text.data() + port_text.size(), v);
    if (ec != std::errc{} || p != port_text.data() + port_text.size() || v < 1 || v > 65535)
      return why = fmt::format("port '{}' is not 1..65535", port_text), std::nullopt;
    e.port = static_cast<std::uint16_t>(v);
  }
  return e;
}

struct Common {
  std::string endpoint;
  int unit = 1;
  int address = 0;
  std::string type = "u16";
  std::string word_order = "high_first";
  double timeout_s = 1.0;
  bool json = false;  ///< read --json: one object on stdout (docs/json.md)
};

std::optional<modbus::ValueFormat> parse_format(const Common& c, std::string& why) {
  modbus::ValueFormat f;
  if (c.type == "u16" || c.type == "hex")
    f = {1, false};
  else if (c.type == "s16")
    f = {1, true};
  else if (c.type == "u32")
    f = {2, false};
  else if (c.type == "s32")
    f = {2, true};
  else
    return why = fmt::format("--type '{}': expected u16, s16, u32, s32 or hex", c.type), std::nullopt;
  if (c.word_order == "low_first")
    f.order = modbus::WordOrder::low_first;
  else if (c.word_order != "high_first")
    return why = fmt::format("--word-order '{}': expected high_first or low_first", c.word_order), std::nullopt;
  return f;
}

using CtxPtr = std::unique_ptr<modbus_t, void (*)(modbus_t*)>;

CtxPtr connect(const Common& c, const Endpoint& ep, std::string& why) {
  CtxPtr ctx(modbus_new_tcp_pi(ep.host.c_str(), std::to_string(ep.port).c_str()), [](modbus_t* m) {
    modbus_close(m);
    modbus_free(m);
  });
  if (!ctx) {
    why = fmt::format("cannot create a Modbus/TCP context for {}:{}: {}", ep.host, ep.port, modbus_strerror(errno));
    return ctx;
  }
  const auto us = static_cast<std::uint32_t>(c.timeout_s * 1e6);
  modbus_set_response_timeout(ctx.get(), us / 1000000, us % 1000000);
  modbus_set_slave(ctx.get(), c.unit);
  if (modbus_connect(ctx.get()) != 0) {
    why = fmt::format("cannot connect to {}:{}: {} (is the drive or `hilbridge emulate modbus-drive` running?)",
                      ep.host, ep.port, modbus_strerror(errno));
    ctx.reset();
  }
  return ctx;
}

std::string describe_failure(int err) {
  return modbus::make_error_code(modbus::from_libmodbus_errno(err)).message() +
         fmt::format(" [libmodbus: {}]", modbus_strerror(err));
}

int fail(const std::string& what, bool json = false) {
  return report_error(json, "hilbridge modbus: ", what, 1);
}

int run_read(const Common& c, int count, bool input) {
  const auto failed = [&](const std::string& what) { return fail(what, c.json); };
  std::string why;
  auto ep = parse_endpoint(c.endpoint, why);
  if (!ep) return failed(fmt::format("HOST[:PORT] '{}': {}", c.endpoint, why));
  auto fmt_ = parse_format(c, why);
  if (!fmt_) return failed(why);
  const int regs_needed = count * fmt_->words;
  if (c.address + regs_needed > 65536)
    return failed(fmt::format("ADDR {} + {} registers runs past 65535", c.address, regs_needed));
  auto ctx = connect(c, *ep, why);
  if (!ctx) return failed(why);
  std::vector<std::uint16_t> regs(static_cast<std::size_t>(regs_needed));
  const int chunks = (regs_needed + modbus::kMaxReadRegisters - 1) / modbus::kMaxReadRegisters;
  SteadyClock clock;
  std::unique_ptr<ProgressBar> bar;
  if (chunks > 8) bar = std::make_unique<ProgressBar>("read", static_cast<std::uint64_t>(regs_needed), "reg", clock);
  for (int done = 0; done < regs_needed;) {
    const int n = std::min<int>(modbus::kMaxReadRegisters, regs_needed - done);
    const int addr = c.address + done;
    const int rc = input ? modbus_read_input_registers(ctx.get(), addr, n, regs.data() + done)
                         : modbus_read_registers(ctx.get(), addr, n, regs.data() + done);
    if (rc != n) {
      const int err = errno;
      if (bar) bar->finish("failed");
      return failed(fmt::format("FC {} read of {} register(s) at {} from {}:{} unit {} failed: {}", input ? 4 : 3, n,
                                addr, ep->host, ep->port, c.unit, describe_failure(err)));
    }
    done += n;
    if (bar) bar->update(static_cast<std::uint64_t>(done));
  }
  if (bar) bar->finish("done");
  if (c.json) {
    nlohmann::json values = nlohmann::json::array();
    for (int i = 0; i < count; ++i) {
      const auto words = std::span<const std::uint16_t>(regs.data() + i * fmt_->words, fmt_->words);
      nlohmann::json v{{"address", c.address + i * fmt_->words},
                       {"value", modbus::unpack_value(words, *fmt_)},
                       {"registers", std::vector<std::uint16_t>(words.begin(), words.end())}};
      if (c.type == "hex") v["hex"] = fmt::format("0x{:04X}", modbus::unpack_value(words, *fmt_));
      values.push_back(std::move(v));
    }
    print_json({{"host", ep->host},
                {"port", ep->port},
                {"unit", c.unit},
                {"function_code", input ? 4 : 3},
                {"address", c.address},
                {"count", count},
                {"type", c.type},
                {"word_order", c.word_order},
                {"values", std::move(values)}});
    return 0;
  }
  for (int i = 0; i < count; ++i) {
    const auto v =
        modbus::unpack_value(std::span<const std::uint16_t>(regs.data() + i * fmt_->words, fmt_->words), *fmt_);
    const int addr = c.address + i * fmt_->words;
    if (c.type == "hex")
      fmt::print("{}: 0x{:04X}\n", addr, v);
    else
      fmt::print("{}: {}\n", addr, v);
  }
  return 0;
}

int run_write(const Common& c, const std::vector<std::string>& values, int fc) {
  std::string why;
  auto ep = parse_endpoint(c.endpoint, why);
  if (!ep) return fail(fmt::format("HOST[:PORT] '{}': {}", c.endpoint, why));
  auto f = parse_format(c, why);
  if (!f) return fail(why);
  std::vector<std::uint16_t> regs;
  for (const auto& text : values) {
    std::int64_t v = 0;
    const bool hex = text.starts_with("0x") || text.starts_with("0X");
    const char* b = text.data() + (hex ? 2 : 0);
    auto [p, ec] = std::from_chars(b, text.data() + text.size(), v, hex ? 16 : 10);
    if (ec != std::errc{} || p != text.data() + text.size())
      return fail(fmt::format("value '{}' is not an integer", text));
    if (modbus::saturate(v, *f) != v) return fail(fmt::format("value {} does not fit --type {}", v, c.type));
    std::uint16_t r[2] = {};
    modbus::pack_value(v, *f, std::span<std::uint16_t>(r, f->words));
    regs.insert(regs.end(), r, r + f->words);
  }
  if (fc == 0) fc = regs.size() == 1 ? 6 : 16;
  if (fc == 6 && regs.size() != 1) return fail("--fc 6 writes exactly one register; use --fc 16 for several");
  if (regs.size() > modbus::kMaxWriteRegisters)
    return fail(fmt::format("at most {} registers per FC 16 request, got {}", modbus::kMaxWriteRegisters, regs.size()));
  if (c.address + static_cast<int>(regs.size()) > 65536) return fail("the values run past address 65535");
  auto ctx = connect(c, *ep, why);
  if (!ctx) return fail(why);
  const int rc = fc == 6 ? modbus_write_register(ctx.get(), c.address, regs[0])
                         : modbus_write_registers(ctx.get(), c.address, static_cast<int>(regs.size()), regs.data());
  if (rc < 0) {
    const int err = errno;
    return fail(fmt::format("FC {} write of {} register(s) at {} to {}:{} unit {} failed: {}", fc, regs.size(),
                            c.address, ep->host, ep->port, c.unit, describe_failure(err)));
  }
  fmt::print("wrote {} register{} at {} (FC {})\n", regs.size(), regs.size() == 1 ? "" : "s", c.address, fc);
  return 0;
}

void add_common(CLI::App* cmd, Common& c) {
  cmd->add_option("endpoint", c.endpoint, "Drive address: HOST, HOST:PORT or [IPv6]:PORT (default port 502)")
      ->required();
  cmd->add_option("unit", c.unit, "Unit id (slave id) 0..255; most Modbus/TCP drives accept 1 or 255")
      ->required()
      ->check(CLI::Range(0, 255));
  cmd->add_option("address", c.address, "First register, PDU address 0..65535 (0-based, as on the wire)")
      ->required()
      ->check(CLI::Range(0, 65535));
  cmd->add_option("--type", c.type, "Value type: u16 (default), s16, u32, s32, hex (u16 shown in hex)");
  cmd->add_option("--word-order", c.word_order, "32-bit word order: high_first (default) or low_first");
  cmd->add_option("--timeout", c.timeout_s, "Response timeout in seconds (default 1)")->check(CLI::Range(0.001, 60.0));
}

}  // namespace

void register_modbus(Context& ctx) {
  ctx.transports.add("modbus", [] { return drives::make_modbus_transport(); });

  auto* mb = ctx.app.add_subcommand("modbus", "Quick Modbus/TCP register checks against a drive (libmodbus client)");
  mb->require_subcommand(1);
  mb->footer(
      "Examples:\n"
      "  hilbridge modbus read 127.0.0.1:1502 1 10 7 --type hex   # status block of the cia402 profile\n"
      "  hilbridge modbus read 10.0.0.5 1 1 --input --type s32 --word-order low_first\n"
      "  hilbridge modbus write 127.0.0.1:1502 1 0 6              # control word: Shutdown\n"
      "  hilbridge modbus write 127.0.0.1:1502 1 2 -5000 --type s32\n"
      "Exit status 0 on success; 1 with the Modbus exception or link error on stderr.");

  auto common_r = std::make_shared<Common>();
  auto count = std::make_shared<int>(1);
  auto input = std::make_shared<bool>(false);
  auto* rd = mb->add_subcommand("read", "Read holding registers (FC 3) or input registers (FC 4, --input)");
  add_common(rd, *common_r);
  rd->add_option("count", *count, "Number of values (default 1); more than 125 registers are read in several requests")
      ->check(CLI::Range(1, 65536));
  rd->add_flag("--input", *input, "Read input registers (FC 4) instead of holding registers (FC 3)");
  rd->add_flag("--json", common_r->json,
               "Print one JSON object on stdout (values with address and raw registers; docs/json.md); errors as "
               "{\"error\": ...} too");
  rd->callback([&ctx, common_r, count, input] { ctx.exit_code = run_read(*common_r, *count, *input); });

  auto common_w = std::make_shared<Common>();
  auto values = std::make_shared<std::vector<std::string>>();
  auto fc = std::make_shared<int>(0);
  auto* wr = mb->add_subcommand("write", "Write holding registers (FC 6 for one register, FC 16 for several)");
  add_common(wr, *common_w);
  wr->add_option("values", *values, "Values (decimal or 0x hex), packed per --type and --word-order")->required();
  wr->add_option("--fc", *fc, "Force the function code: 6 (one register) or 16")->check(CLI::IsMember({6, 16}));
  wr->callback([&ctx, common_w, values, fc] { ctx.exit_code = run_write(*common_w, *values, *fc); });

  register_emulate_modbus_drive(ctx);
  register_emulate_modbus_io(ctx);
}

}  // namespace hil::cli
