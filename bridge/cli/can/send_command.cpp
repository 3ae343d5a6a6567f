// SPDX-License-Identifier: MIT
// `hilbridge can send` (cansend syntax) and `hilbridge can replay` (candump log files).
#include <cstdio>
#include <fstream>
#include <memory>
#include <vector>

#include <fmt/format.h>
#include <asio/io_context.hpp>
#include <asio/steady_timer.hpp>

#include "commands.hpp"
#include "hil/can/candump.hpp"
#include "hil/can/io/make_channel.hpp"
#include "hil/can/io/socketcand_channel.hpp"
#include "hil/can/linux/socketcan_channel.hpp"
#include "hil/cli/duration_option.hpp"
#include "hil/cli/progress.hpp"

namespace hil::cli::can_cmd {

namespace {

/// Run `io` until the channel handed every queued frame to the kernel (bounded).
bool flush(asio::io_context& io, can::Channel& ch, std::chrono::seconds limit = std::chrono::seconds(5)) {
  const auto end = std::chrono::steady_clock::now() + limit;
  auto pending = [&ch]() -> std::size_t {
    if (auto* sc = dynamic_cast<can::socketcand::SocketcandChannel*>(&ch)) return sc->tx_pending_bytes();
    if (auto* sk = dynamic_cast<can::socketcan::SocketCanChannel*>(&ch)) return sk->tx_queued();
    return 0;
  };
  while (pending() > 0) {
    if (std::chrono::steady_clock::now() > end) return false;
    io.run_one_for(std::chrono::milliseconds(10));
    io.restart();
  }
  return true;
}

struct Timed {
  can::Frame frame;
  Duration at{0};
};

/// Send frames at their offsets (real time); 0 offsets go back to back. Returns the exit code.
int send_all(const std::string& bus, const std::vector<Timed>& frames, const char* verb, bool progress) {
  asio::io_context io;
  SteadyClock clock;
  auto url = can::parse_bus_url(bus);
  if (!url) {
    fmt::print(stderr, "hilbridge can {}: --bus: {}\n", verb, url.error());
    return 2;  // the command line is wrong
  }
  auto channel = can::make_channel(*url, {io.get_executor(), clock});
  if (!channel) {
    fmt::print(stderr, "hilbridge can {}: {}\n", verb, channel.error().message);
    return 1;  // the bus cannot be reached (as sdo, scan, nmt)
  }
  std::unique_ptr<ProgressBar> bar;
  if (progress) bar = std::make_unique<ProgressBar>(std::string("replay ") + bus, frames.size(), "frames", clock);
  const auto start = clock.now();
  asio::steady_timer timer(io);
  std::size_t sent = 0;
  for (const auto& t : frames) {
    if (t.at > Duration{0}) {
      timer.expires_at(clock.to_steady(start + t.at));
      std::error_code ec;
      // Keep the channel's I/O running while waiting for the frame's time.
      bool due = false;
      timer.async_wait([&due](const std::error_code&) { due = true; });
      while (!due) {
        io.run_one();
      }
      io.restart();
      (void)ec;
    }
    std::error_code ec = (*channel)->send(t.frame);
    for (int retry = 0; ec == std::errc::no_buffer_space && retry < 500;
         ++retry) {  // back-pressure: let the queue drain
      io.run_one_for(std::chrono::milliseconds(10));
      io.restart();
      ec = (*channel)->send(t.frame);
    }
    if (ec) {
      fmt::print(stderr, "hilbridge can {}: frame {} ({}) not sent: {}\n", verb, sent + 1,
                 can::candump::format_frame_spec(t.frame), ec.message());
      return 1;
    }
    ++sent;
    if (bar) bar->update(sent);
  }
  if (!flush(io, **channel)) {
    fmt::print(stderr, "hilbridge can {}: the bus did not accept all frames within 5 s\n", verb);
    return 1;
  }
  if (bar) bar->finish("done");
  return 0;
}

struct SendOptions {
  std::string bus;
  std::vector<std::string> frames;
  Duration interval{};  ///< pause between frames
};

int run_send(const SendOptions& o) {
  std::vector<Timed> frames;
  for (std::size_t i = 0; i < o.frames.size(); ++i) {
    auto f = can::candump::parse_frame_spec(o.frames[i]);
    if (!f) {
      fmt::print(stderr, "hilbridge can send: frame {} '{}': {}\n", i + 1, o.frames[i], f.error().message());
      return 2;
    }
    frames.push_back({*f, std::chrono::duration_cast<Duration>(o.interval * static_cast<Duration::rep>(i))});
  }
  return send_all(o.bus, frames, "send", false);
}

struct ReplayOptions {
  std::string bus;
  std::string file;
  double speed = 1.0;
};

int run_replay(const ReplayOptions& o) {
  std::ifstream in(o.file);
  if (!in) {
    fmt::print(stderr, "hilbridge can replay: cannot open '{}': {}\n", o.file, std::strerror(errno));
    return 2;
  }
  std::vector<Timed> frames;
  std::string line;
  std::size_t line_no = 0;
  std::optional<can::socketcand::Timestamp> first;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line.front() == '#') continue;
    auto r = can::candump::parse_log_line(line);
    if (!r) {
      fmt::print(stderr, "hilbridge can replay: {}:{}: {}\n  {}\n", o.file, line_no, r.error().message(), line);
      return 2;
    }
    if (!first) first = r->time;
    const double rel_s = static_cast<double>(r->time.sec - first->sec) +
                         (static_cast<double>(r->time.usec) - static_cast<double>(first->usec)) * 1e-6;
    const double scaled = o.speed > 0 ? std::max(0.0, rel_s / o.speed) : 0.0;
    frames.push_back({r->frame, std::chrono::duration_cast<Duration>(std::chrono::duration<double>(scaled))});
  }
  return send_all(o.bus, frames, "replay", true);
}

}  // namespace

void add_send(CLI::App& can, Context& ctx) {
  auto o = std::make_shared<SendOptions>();
  auto* cmd = can.add_subcommand("send", "Send frames given in cansend syntax (123#DEADBEEF)");
  cmd->footer(
      "Send one or more frames, cansend syntax: 123#DEADBEEF (11-bit), 1F334455#11.22 (29-bit),\n"
      "705#R or 705#R1 (remote frame), 080# (no data). socketcand cannot carry remote frames.");
  cmd->add_option("--bus", o->bus, bus_help)->required();
  cmd->add_option("frames", o->frames, "Frames to send, in order")->required();
  add_duration_option(*cmd, "--interval", o->interval, "Pause between frames, e.g. 10ms (default 0: back to back)",
                      "ms");
  add_duration_alias(*cmd, "--interval-ms", "--interval", o->interval, "ms");
  cmd->callback([o, &ctx] { ctx.exit_code = run_send(*o); });
}

void add_replay(CLI::App& can, Context& ctx) {
  auto o = std::make_shared<ReplayOptions>();
  auto* cmd = can.add_subcommand("replay", "Send the frames of a candump log file with their original timing");
  cmd->footer(
      "Replay a candump -l / `hilbridge can dump --log` file onto a bus. The interface names in the\n"
      "file are ignored: every frame goes to --bus. --speed 2 plays twice as fast, 0 back to back.");
  cmd->add_option("--bus", o->bus, bus_help)->required();
  cmd->add_option("file", o->file, "candump log file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--speed", o->speed, "Time scale (1 = original timing, 0 = as fast as possible)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->callback([o, &ctx] { ctx.exit_code = run_replay(*o); });
}

}  // namespace hil::cli::can_cmd
