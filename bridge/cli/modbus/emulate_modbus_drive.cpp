// SPDX-License-Identifier: MIT
// `hilbridge emulate modbus-drive`: the simulated Modbus/TCP drive server as a process.
#include <signal.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "hil/cli/context.hpp"
#include "hil/cli/duration_option.hpp"
#include "hil/cli/endpoint_text.hpp"
#include "hil/drives/modbus_transport.hpp"
#include "hil/mocks/modbus_server.hpp"
#include "hil/modbus/profile.hpp"

namespace hil::cli {
namespace {

struct EmulateOptions {
  std::string listen = "127.0.0.1:1502";
  std::string profile = "cia402";
  int unit = -1;
  bool strict_unit = false;
  Duration step_period = std::chrono::milliseconds(1);
  int max_connections = 64;
  Duration duration{};  ///< 0: until SIGINT/SIGTERM
  Duration frame_timeout = std::chrono::seconds(5);
  bool quiet = false;
};

int run_emulate(const EmulateOptions& opts) {
  EmulateOptions o = opts;
  o.listen = std::string(strip_tcp_scheme(o.listen));  // HOST:PORT or tcp://HOST:PORT (docs/cli.md)
  const auto colon = o.listen.rfind(':');
  if (colon == std::string::npos) {
    std::fprintf(
        stderr,
        "hilbridge emulate modbus-drive: --listen '%s': expected HOST:PORT (e.g. 127.0.0.1:1502, port 0 = any)\n",
        o.listen.c_str());
    return 2;
  }
  std::string host = o.listen.substr(0, colon);
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
  int port = -1;
  try {
    port = std::stoi(o.listen.substr(colon + 1));
  } catch (...) {
  }
  if (port < 0 || port > 65535) {
    std::fprintf(stderr, "hilbridge emulate modbus-drive: --listen '%s': port must be 0..65535\n", o.listen.c_str());
    return 2;
  }
  const std::string path = drives::resolve_modbus_profile(o.profile, ".");
  auto profile = modbus::load_profile(path);
  if (!profile) {
    std::fprintf(stderr, "hilbridge emulate modbus-drive: %s\n", profile.error().describe().c_str());
    return 2;
  }
  mocks::ModbusServerConfig config;
  config.listen_host = host;
  config.port = static_cast<std::uint16_t>(port);
  config.handler.unit_id = o.unit >= 0 ? static_cast<std::uint8_t>(o.unit) : profile->unit_id;
  config.handler.strict_unit = o.strict_unit;
  config.max_connections = static_cast<std::size_t>(o.max_connections);
  config.auto_step = o.step_period;
  config.frame_timeout = o.frame_timeout;
  if (!o.quiet)
    config.log = [](std::string_view msg) { std::fprintf(stderr, "%.*s\n", static_cast<int>(msg.size()), msg.data()); };
  const std::string name = profile->name;

  // Block the stop signals before the server's threads exist, so they inherit the mask and
  // only this thread receives them (sigtimedwait below).
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

  mocks::ModbusDriveServer server(mocks::DriveDevice(std::move(*profile)), config);
  if (auto ec = server.start()) {
    std::fprintf(stderr, "hilbridge emulate modbus-drive: cannot listen on %s: %s\n", o.listen.c_str(),
                 ec.message().c_str());
    return 1;
  }
  // Scripts parse this line for the port (with --listen HOST:0).
  std::printf("modbus-drive: profile %s (%s) listening on %s:%u unit %u%s\n", name.c_str(), path.c_str(), host.c_str(),
              server.port(), config.handler.unit_id, o.strict_unit ? " (strict unit)" : "");
  std::fflush(stdout);

  const auto deadline = std::chrono::steady_clock::now() + o.duration;
  for (;;) {
    timespec ts{1, 0};
    if (o.duration > Duration::zero()) {
      const auto left = deadline - std::chrono::steady_clock::now();
      if (left <= std::chrono::steady_clock::duration::zero()) break;
      const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(left).count();
      ts = timespec{static_cast<time_t>(std::min<long long>(ns / 1000000000, 1)),
                    ns >= 1000000000 ? 0 : static_cast<long>(ns % 1000000000)};
    }
    const int sig = sigtimedwait(&stop_signals, nullptr, &ts);
    if (sig == SIGINT || sig == SIGTERM) break;
  }
  server.stop();
  const auto s = server.stats();
  std::printf("modbus-drive: stopped; %llu connections, %llu requests, %llu exceptions, %llu malformed, %llu stalled\n",
              static_cast<unsigned long long>(s.connections_accepted), static_cast<unsigned long long>(s.requests),
              static_cast<unsigned long long>(s.exceptions), static_cast<unsigned long long>(s.malformed),
              static_cast<unsigned long long>(s.stalled));
  return 0;
}

}  // namespace

void register_emulate_modbus_drive(Context& ctx) {
  auto o = std::make_shared<EmulateOptions>();
  auto* cmd = ctx.emulate.add_subcommand(
      "modbus-drive",
      "Simulated servo/stepper drive on Modbus/TCP: serves a register profile backed by the plant model");
  cmd->add_option(
      "--listen", o->listen,
      "HOST:PORT or tcp://HOST:PORT to bind, HOST an address or a host name (default 127.0.0.1:1502, loopback only; "
      "0.0.0.0:502 serves the network; port 0 "
      "picks a free port, printed on stdout)");
  cmd->add_option(
      "--profile", o->profile,
      "Register profile: a name in profiles/modbus (cia402, vendor_simple) or a YAML path (default cia402)");
  cmd->add_option("--unit", o->unit, "Unit id to answer as (default: the profile's)")->check(CLI::Range(0, 255));
  cmd->add_flag("--strict-unit", o->strict_unit,
                "Answer only our unit id (and 0/255); others get exception 0B. Default: any unit, like libmodbus");
  const DurationRange step_range{std::chrono::microseconds(100), std::chrono::seconds(1)};
  add_duration_option(*cmd, "--step-period", o->step_period,
                      "Plant step period in real time (default 1ms; 100us .. 1s)", "ms", step_range);
  add_duration_alias(*cmd, "--step-period-ms", "--step-period", o->step_period, "ms", step_range);
  cmd->add_option("--max-connections", o->max_connections, "Simultaneous clients (default 64)")
      ->check(CLI::Range(1, 1024));
  add_duration_option(*cmd, "--duration", o->duration, "Stop after this long, e.g. 30s (default: until SIGINT/SIGTERM)",
                      "s");
  add_duration_option(*cmd, "--frame-timeout", o->frame_timeout,
                      "Close a connection whose started frame is still incomplete after this long (default 5s; "
                      "1ms .. 1h)",
                      "s", {std::chrono::milliseconds(1), std::chrono::hours(1)});
  cmd->add_flag("--quiet", o->quiet, "Do not log malformed frames and refused connections on stderr");
  cmd->footer(
      "Function codes: 3, 4, 6, 16, 22, 23; others answer exception 01. Writes to read-only registers answer 02.\n"
      "Example:\n"
      "  hilbridge emulate modbus-drive --listen 127.0.0.1:1502 --profile cia402 &\n"
      "  hilbridge modbus write 127.0.0.1:1502 1 0 6 && hilbridge modbus read 127.0.0.1:1502 1 10 --type hex");
  cmd->callback([&ctx, o] { ctx.exit_code = run_emulate(*o); });
}

}  // namespace hil::cli
