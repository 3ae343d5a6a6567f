// SPDX-License-Identifier: MIT
// `hilbridge emulate modbus-io`: the simulated Modbus/TCP digital I/O terminal as a process (the
// far end of a scenario's `io_links: - modbus: {bus: "tcp://HOST:PORT"}` without hardware).
#include <signal.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "hil/cli/context.hpp"
#include "hil/mocks/modbus_server.hpp"
#include "hil/modbus/bus_address.hpp"

namespace hil::cli {
namespace {

struct EmulateIoOptions {
  std::string listen = "127.0.0.1:1502";
  int unit = 1;
  int coils = 64;
  int discrete_inputs = 64;
  std::vector<int> set_inputs;
  double duration_s = 0.0;
  bool quiet = false;
};

int run_emulate_io(const EmulateIoOptions& o) {
  const auto ep = modbus::parse_endpoint(o.listen, true, 502, true);
  if (!ep) {
    std::fprintf(stderr, "hilbridge emulate modbus-io: --listen: %s\n", ep.error().c_str());
    return 2;
  }
  for (const int a : o.set_inputs) {
    if (a < 0 || a >= o.discrete_inputs) {
      std::fprintf(stderr, "hilbridge emulate modbus-io: --set-input %d: the terminal has discrete inputs 0..%d\n", a,
                   o.discrete_inputs - 1);
      return 2;
    }
  }
  mocks::ModbusServerConfig config;
  config.listen_host = ep->host;
  config.port = ep->port;
  config.handler.unit_id = static_cast<std::uint8_t>(o.unit);
  if (!o.quiet)
    config.log = [](std::string_view msg) { std::fprintf(stderr, "%.*s\n", static_cast<int>(msg.size()), msg.data()); };
  mocks::IoTerminal terminal{
      mocks::IoTerminalConfig{static_cast<std::uint16_t>(o.coils), static_cast<std::uint16_t>(o.discrete_inputs)}};
  for (const int a : o.set_inputs) terminal.set_discrete_input(static_cast<std::uint16_t>(a), true);

  // Block the stop signals before the server's thread exists (it inherits the mask), so only
  // this thread receives them (sigtimedwait below).
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

  mocks::ModbusDriveServer server(std::move(terminal), config);
  if (auto ec = server.start()) {
    std::fprintf(stderr, "hilbridge emulate modbus-io: cannot listen on %s: %s\n", o.listen.c_str(),
                 ec.message().c_str());
    return 1;
  }
  // Scripts parse this line for the port (with --listen HOST:0).
  std::printf("modbus-io: %d coils, %d discrete inputs listening on %s unit %d\n", o.coils, o.discrete_inputs,
              modbus::Endpoint{ep->host, server.port()}.to_string().c_str(), o.unit);
  std::fflush(stdout);

  // Report every coil change (what the clients switched), sampled every 10 ms.
  std::vector<std::uint8_t> last(static_cast<std::size_t>(o.coils), 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(o.duration_s);
  for (;;) {
    server.with_terminal([&](mocks::IoTerminal& t) {
      for (std::size_t a = 0; a < last.size(); ++a) {
        const std::uint8_t now = t.coil(static_cast<std::uint16_t>(a)) ? 1 : 0;
        if (now == last[a]) continue;
        last[a] = now;
        std::printf("modbus-io: coil %zu -> %u\n", a, now);
      }
    });
    std::fflush(stdout);
    if (o.duration_s > 0 && std::chrono::steady_clock::now() >= deadline) break;
    timespec ts{0, 10'000'000};
    const int sig = sigtimedwait(&stop_signals, nullptr, &ts);
    if (sig == SIGINT || sig == SIGTERM) break;
  }
  server.stop();
  const auto s = server.stats();
  const auto writes = server.with_terminal([](mocks::IoTerminal& t) { return t.coil_write_requests(); });
  std::printf("modbus-io: stopped; %llu connections, %llu requests (%llu coil writes), %llu exceptions\n",
              static_cast<unsigned long long>(s.connections_accepted), static_cast<unsigned long long>(s.requests),
              static_cast<unsigned long long>(writes), static_cast<unsigned long long>(s.exceptions));
  return 0;
}

}  // namespace

void register_emulate_modbus_io(Context& ctx) {
  auto o = std::make_shared<EmulateIoOptions>();
  auto* cmd = ctx.emulate.add_subcommand(
      "modbus-io", "Simulated digital I/O terminal on Modbus/TCP: coils (FC 1/5/15) and discrete inputs (FC 2)");
  cmd->add_option("--listen", o->listen,
                  "HOST:PORT to bind (default 127.0.0.1:1502, loopback only; port 0 picks a free port, printed on "
                  "stdout)");
  cmd->add_option("--unit", o->unit, "Unit id (default 1; any unit is answered)")->check(CLI::Range(0, 255));
  cmd->add_option("--coils", o->coils, "Coils 0..N-1 (default 64)")->check(CLI::Range(1, 65535));
  cmd->add_option("--discrete-inputs", o->discrete_inputs, "Discrete inputs 0..N-1 (default 64)")
      ->check(CLI::Range(1, 65535));
  cmd->add_option("--set-input", o->set_inputs, "A discrete input that reads 1 (repeatable; the others read 0)");
  cmd->add_option("--duration", o->duration_s, "Stop after this many seconds (default: until SIGINT/SIGTERM)")
      ->check(CLI::Range(0.0, 1e7));
  cmd->add_flag("--quiet", o->quiet, "Do not log malformed frames and refused connections on stderr");
  cmd->footer(
      "Prints every coil change ('modbus-io: coil 17 -> 1'). Example:\n"
      "  hilbridge emulate modbus-io --listen 127.0.0.1:1502 --set-input 0 &\n"
      "  scenario: io_links: [{modbus: {bus: \"tcp://127.0.0.1:1502\"}, inputs: {start: {discrete_input: 0}}}]");
  cmd->callback([&ctx, o] { ctx.exit_code = run_emulate_io(*o); });
}

}  // namespace hil::cli
