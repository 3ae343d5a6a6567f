// SPDX-License-Identifier: MIT
// `hilbridge emulate cia402`: simulated CiA 402 nodes as a process on a real bus (SocketCAN,
// socketcand), one channel per node, stepped every millisecond on real time until SIGINT/SIGTERM.
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <asio/signal_set.hpp>
#include <asio/steady_timer.hpp>

#include "hil/cli/context.hpp"
#include "hil/cli/duration_option.hpp"
#include "hil/mocks/cia402_node.hpp"
#include "hil/mocks/key_range.hpp"
#include "session.hpp"

namespace hil::cli::canopen_cli {
namespace {

struct EmulateArgs {
  std::string bus;
  std::vector<int> nodes;
  Duration duration{};  ///< 0: until SIGINT/SIGTERM
  double kv = 50.0;
  double max_velocity = 5.0e6;
  std::string eds;  ///< the user's EDS/DCF (empty: the shipped simulated drive's)
};

int run_emulate(const EmulateArgs& a) {
  if (std::set<int>(a.nodes.begin(), a.nodes.end()).size() != a.nodes.size()) {
    std::fprintf(stderr, "hilbridge emulate cia402: a --node is given twice\n");
    return 2;
  }
  std::string eds_text;
  if (!a.eds.empty()) {
    std::ifstream in(a.eds, std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "hilbridge emulate cia402: --eds %s: cannot open the file: check the path\n", a.eds.c_str());
      return 2;
    }
    std::ostringstream ss;
    ss << in.rdbuf();
    eds_text = ss.str();
    for (int n : a.nodes) {
      auto d = mocks::load_node_eds(eds_text, a.eds, static_cast<canopen::NodeId>(n));
      if (!d) {
        std::fprintf(stderr, "hilbridge emulate cia402: --eds: %s\n", d.error().describe().c_str());
        return 2;
      }
      for (const auto& w : d->warnings)
        std::fprintf(stderr, "hilbridge emulate cia402: warning: %s\n", w.describe().c_str());
      if (n == a.nodes.front())
        std::printf(
            "hilbridge emulate cia402: object dictionary, PDO defaults and identity from %s ('%s', vendor "
            "0x%08X, product 0x%08X)\n",
            a.eds.c_str(), d->info.product_name.c_str(), d->info.vendor_number, d->info.product_number);
    }
  }
  asio::io_context io;
  SteadyClock clock;
  can::VirtualBusRegistry vbuses(clock);
  std::vector<std::unique_ptr<can::Channel>> channels;
  std::vector<std::unique_ptr<mocks::Cia402Node>> nodes;
  for (int n : a.nodes) {
    auto ch = can::make_channel(
        a.bus, can::ChannelRequest{io.get_executor(), clock, &vbuses, "cia402-node-" + std::to_string(n)});
    if (!ch) {
      std::fprintf(stderr, "hilbridge emulate cia402: --bus %s: %s\n", a.bus.c_str(), ch.error().message.c_str());
      return 1;
    }
    mocks::Cia402NodeOptions o;
    o.node = static_cast<canopen::NodeId>(n);
    o.plant.kv_per_s = a.kv;
    o.plant.max_velocity_inc_per_s = a.max_velocity;
    o.eds_text = eds_text;
    o.eds_name = a.eds;
    channels.push_back(std::move(*ch));
    nodes.push_back(std::make_unique<mocks::Cia402Node>(*channels.back(), o));
  }
  for (auto& n : nodes) {
    n->start(clock.now());
    std::printf("hilbridge emulate cia402: node %d up on %s (boot-up sent)\n", n->node_id(), a.bus.c_str());
  }
  std::fflush(stdout);
  asio::signal_set signals(io, SIGINT, SIGTERM);
  bool stop = false;
  signals.async_wait([&](const std::error_code& ec, int) {
    if (!ec) stop = true;
  });
  asio::steady_timer timer(io);
  const auto end = a.duration > Duration::zero() ? clock.now() + a.duration : TimePoint::max();
  auto next = std::chrono::steady_clock::now();
  std::function<void()> tick = [&] {
    next += std::chrono::milliseconds(1);
    timer.expires_at(next);
    timer.async_wait([&](const std::error_code& ec) {
      if (ec || stop) return;
      const auto now = clock.now();
      for (auto& n : nodes) n->step(now);
      if (now >= end) {
        stop = true;
        return;
      }
      tick();
    });
  };
  tick();
  while (!stop && io.run_one() > 0) {
  }
  signals.cancel();
  timer.cancel();
  io.poll();
  return 0;
}

}  // namespace

void register_emulate_cia402(Context& ctx) {
  auto a = std::make_shared<EmulateArgs>();
  auto* c = ctx.emulate.add_subcommand("cia402",
                                       "Simulated CiA 402 servo drive(s) on a CAN bus (CANopen slave, plant model)");
  c->add_option("--bus", a->bus, "Bus URL: vcan0, can0, socketcand://HOST[:PORT]/BUS, or virtual:NAME")->required();
  c->add_option("--node", a->nodes, "Node-ID 1..127 (repeat for several nodes)")->required()->check(CLI::Range(1, 127));
  add_duration_option(*c, "--duration", a->duration, "Stop after this long, e.g. 30s (default: until SIGINT/SIGTERM)",
                      "s");
  c->add_option("--eds", a->eds,
                "Build the node from this EDS/DCF (object dictionary, PDO defaults, identity) to rehearse against "
                "your own drive; default: the shipped simulated drive");
  c->add_option("--kv", a->kv, "Plant position-loop gain Kv in 1/s, (0, 10000] (default 50)")
      ->check(CLI::Range(std::nextafter(0.0, 1.0), mocks::kv_range.max));
  c->add_option("--max-velocity", a->max_velocity, "Plant velocity limit in increments/s, (0, 1e12] (default 5e6)")
      ->check(CLI::Range(std::nextafter(0.0, 1.0), mocks::max_velocity_range.max));
  c->footer(
      "The node's object dictionary is the EDS profiles/canopen/hil_cia402_drive.eds (compiled in), or\n"
      "the one given with --eds (objects the model needs but the EDS lacks take internal values).\n"
      "Fault injection over SDO: 0x2100 error code (u16, 0 clears), 0x2101 heartbeat loss (u8),\n"
      "0x2102 SDO answer delay ms (u16, 0xFFFF = no answer), 0x2103 following error offset (i32).\n"
      "Examples:\n"
      "  hilbridge emulate cia402 --bus vcan0 --node 5\n"
      "  hilbridge emulate cia402 --bus socketcand://127.0.0.1:29536/can0 --node 3 --eds my_drive.eds\n"
      "  hilbridge emulate cia402 --bus socketcand://127.0.0.1:29536/can0 --node 1 --node 2\n"
      "  hilbridge canopen sdo write --bus vcan0 5 0x2100:0 0x2310 --type u16   # inject over-current");
  c->callback([&ctx, a] { ctx.exit_code = run_emulate(*a); });
}

}  // namespace hil::cli::canopen_cli
