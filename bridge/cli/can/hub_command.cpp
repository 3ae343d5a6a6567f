// SPDX-License-Identifier: MIT
// `hilbridge can hub`: a socketcand server in front of an in-process virtual bus on real time
// (or, with --bridge, in front of a SocketCAN interface).
#include <cstdio>
#include <memory>

#include <fmt/format.h>
#include <asio/io_context.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/signal_set.hpp>

#include "commands.hpp"
#include "hil/can/io/bus_runner.hpp"
#include "hil/can/io/socketcand_server.hpp"
#include "hil/can/linux/socketcan_channel.hpp"
#include "hil/can/virtual_bus.hpp"
#include "hil/cli/duration_option.hpp"
#include "hil/cli/endpoint_text.hpp"

namespace hil::cli::can_cmd {

namespace {

struct HubOptions {
  std::string listen = "127.0.0.1:29536";
  std::string bus_name;
  std::string bridge;
  Duration latency{};
  std::size_t max_clients = 32;
  bool error_frames = false;
  Duration join_hold = std::chrono::milliseconds(50);
};

/// "HOST:PORT" or "[V6]:PORT", optionally after "tcp://" -> endpoint, or an error sentence.
std::expected<asio::ip::tcp::endpoint, std::string> parse_listen(const std::string& given) {
  const std::string text(strip_tcp_scheme(given));
  std::string host;
  std::string port;
  if (text.starts_with("[")) {
    const auto close = text.find(']');
    if (close == std::string::npos || close + 1 >= text.size() || text[close + 1] != ':')
      return std::unexpected("--listen '" + text + "': expected [IPV6]:PORT");
    host = text.substr(1, close - 1);
    port = text.substr(close + 2);
  } else {
    const auto colon = text.rfind(':');
    if (colon == std::string::npos)
      return std::unexpected("--listen '" + text + "': expected HOST:PORT, e.g. 127.0.0.1:29536");
    host = text.substr(0, colon);
    port = text.substr(colon + 1);
  }
  std::error_code ec;
  const auto address = asio::ip::make_address(host, ec);
  if (ec) return std::unexpected("--listen '" + text + "': '" + host + "' is not an IP address (" + ec.message() + ")");
  unsigned long p = 0;
  try {
    std::size_t used = 0;
    p = std::stoul(port, &used);
    if (used != port.size() || p > 65535) throw std::out_of_range("port");
  } catch (...) {
    return std::unexpected("--listen '" + text + "': the port must be a number 0..65535");
  }
  return asio::ip::tcp::endpoint(address, static_cast<unsigned short>(p));
}

int run_hub(const HubOptions& o) {
  auto endpoint = parse_listen(o.listen);
  if (!endpoint) {
    fmt::print(stderr, "hilbridge can hub: {}\n", endpoint.error());
    return 2;
  }
  asio::io_context io;
  SteadyClock clock;
  const std::string bus_name = !o.bus_name.empty() ? o.bus_name : (!o.bridge.empty() ? o.bridge : "can0");
  std::unique_ptr<can::VirtualBus> bus;
  std::unique_ptr<can::AsioBusRunner> runner;
  can::socketcand::BusOpener opener;
  if (o.bridge.empty()) {
    bus = std::make_unique<can::VirtualBus>(clock, bus_name, can::VirtualBusOptions{.latency = o.latency});
    runner = std::make_unique<can::AsioBusRunner>(io.get_executor(), *bus, clock);
    opener = [&bus, bus_name, error_frames = o.error_frames](
                 std::string_view name,
                 const std::string& peer) -> std::expected<std::unique_ptr<can::Channel>, std::error_code> {
      if (name != bus_name) return std::unexpected(std::make_error_code(std::errc::no_such_device));
      can::ParticipantOptions po;
      if (error_frames) po.filters.error_mask = can::error_class::all;
      return bus->attach("socketcand:" + peer, po);
    };
  } else {
    // Probe the interface once so a typo fails now, with a diagnostic, not at the first client.
    std::string diag;
    if (auto probe = can::socketcan::SocketCanChannel::open(io.get_executor(), clock, o.bridge, {}, &diag); !probe) {
      fmt::print(stderr, "hilbridge can hub: --bridge {}: {}\n", o.bridge, diag);
      return 1;  // the interface cannot be opened (docs/cli.md)
    }
    opener = [&io, &clock, bus_name, iface = o.bridge, error_frames = o.error_frames](
                 std::string_view name,
                 const std::string&) -> std::expected<std::unique_ptr<can::Channel>, std::error_code> {
      if (name != bus_name) return std::unexpected(std::make_error_code(std::errc::no_such_device));
      can::socketcan::SocketCanOptions so;
      so.filters.error_mask = error_frames ? can::error_class::all : 0;
      auto ch = can::socketcan::SocketCanChannel::open(io.get_executor(), clock, iface, so);
      if (!ch) return std::unexpected(ch.error());
      return std::unique_ptr<can::Channel>(std::move(*ch));
    };
  }
  can::socketcand::ServerOptions server_options;
  server_options.max_clients = o.max_clients;
  server_options.join_hold = o.join_hold;
  can::socketcand::Server server(io.get_executor(), clock, opener, server_options);
  if (auto ec = server.listen(*endpoint)) {
    fmt::print(stderr, "hilbridge can hub: cannot listen on {}: {} (another hub or socketcand on that port?)\n",
               o.listen, ec.message());
    return 1;  // as every server that cannot listen (emulate modbus-drive, emulate clm14 --tcp)
  }
  const auto local = server.local_endpoint();
  const std::string host =
      local.address().is_v6() ? "[" + local.address().to_string() + "]" : local.address().to_string();
  fmt::print("hilbridge can hub: {} bus '{}' on {}:{}; connect with socketcand://{}:{}/{} (Ctrl-C to stop)\n",
             o.bridge.empty() ? "virtual" : "SocketCAN " + o.bridge, bus_name, host, local.port(), host, local.port(),
             bus_name);
  std::fflush(stdout);
  asio::signal_set signals(io, SIGINT, SIGTERM);
  signals.async_wait([&](const std::error_code&, int) {
    server.close();
    runner.reset();
    io.stop();
  });
  io.run();
  const auto& s = server.stats();
  fmt::print(
      "hilbridge can hub: stopped; clients {} (refused {}), frames from clients {}, to clients {}, dropped for slow "
      "clients {}, held while joining (delivered) {}, protocol errors {}\n",
      s.accepted, s.refused, s.frames_from_clients, s.frames_to_clients, s.dropped_slow_client, s.held_at_join,
      s.protocol_errors);
  return 0;
}

}  // namespace

void add_hub(CLI::App& can, Context& ctx) {
  auto o = std::make_shared<HubOptions>();
  auto* cmd = can.add_subcommand("hub", "Serve a CAN bus to socketcand clients (python-can, SavvyCAN, hilbridge)");
  cmd->footer(
      "Serve a CAN bus over the socketcand protocol (TCP, raw mode). Without --bridge the bus is an\n"
      "in-process virtual bus on real time: every frame a client sends reaches all other clients.\n"
      "With --bridge IFACE each client gets its own SocketCAN socket on IFACE, like socketcand itself.\n"
      "python-can: can.Bus(interface='socketcand', host=HOST, port=PORT, channel=BUS)");
  cmd->add_option("--listen", o->listen,
                  "HOST:PORT or tcp://HOST:PORT to listen on (port 0: any free port, printed at start)")
      ->capture_default_str();
  cmd->add_option("--bus-name", o->bus_name,
                  "Bus name clients open (`< open NAME >`); default can0, or the --bridge interface");
  cmd->add_option("--bridge", o->bridge, "Expose this SocketCAN interface (vcan0, can0) instead of a virtual bus");
  const DurationRange latency_range{Duration{}, std::chrono::seconds(1)};
  add_duration_option(*cmd, "--latency", o->latency, "Virtual bus: delivery latency per frame, e.g. 30us (0 .. 1s)",
                      "us", latency_range);
  add_duration_alias(*cmd, "--latency-us", "--latency", o->latency, "us", latency_range);
  cmd->add_option("--max-clients", o->max_clients, "Refuse clients beyond this many")->capture_default_str();
  const DurationRange hold_range{Duration{}, std::chrono::seconds(10)};
  add_duration_option(*cmd, "--join-hold", o->join_hold,
                      "A client that entered raw mode gets every frame from then on; frames are queued (never "
                      "dropped) until it sends its first element or this time has passed, because python-can 4.1 "
                      "fails to connect when a frame follows its `< ok >` in the same read; 0 = like socketcand "
                      "(default 50ms, at most 10s)",
                      "ms", hold_range);
  add_duration_alias(*cmd, "--join-hold-ms", "--join-hold", o->join_hold, "ms", hold_range);
  add_duration_alias(*cmd, "--join-grace-ms", "--join-hold", o->join_hold, "ms", hold_range);
  cmd->add_flag("--error-frames", o->error_frames, "Forward error frames to clients as `< error CLASS TIME >`");
  cmd->callback([o, &ctx] { ctx.exit_code = run_hub(*o); });
}

}  // namespace hil::cli::can_cmd
