// SPDX-License-Identifier: MIT
// `hilbridge can dump`: candump -L style lines on stdout, optionally a log file (replayable with
// `hilbridge can replay` or canplayer) and a pcap file (LINKTYPE_CAN_SOCKETCAN, for Wireshark).
#include <cstdio>
#include <memory>

#include <fmt/format.h>
#include <asio/io_context.hpp>
#include <asio/signal_set.hpp>
#include <asio/steady_timer.hpp>

#include "commands.hpp"
#include "hil/can/candump.hpp"
#include "hil/can/io/make_channel.hpp"
#include "hil/can/pcap.hpp"
#include "hil/cli/duration_option.hpp"
#include "hil/cli/json_output.hpp"

namespace hil::cli::can_cmd {

namespace {

struct DumpOptions {
  std::string bus;
  std::string pcap;
  std::string log;
  std::uint64_t count = 0;
  Duration duration{};  ///< 0: until --count frames or SIGINT/SIGTERM
  bool quiet = false;
  bool jsonl = false;  ///< stdout: one JSON object per frame (docs/json.md) instead of candump lines
};

/// One frame as a JSON Lines record (docs/json.md): wall-clock time, bus, identifier, flags,
/// DLC and the payload as hex.
nlohmann::json frame_json(const can::Frame& f, std::int64_t time_us, const std::string& bus) {
  const auto payload = f.payload();
  return {{"time", static_cast<double>(time_us) / 1e6},
          {"time_us", time_us},
          {"bus", bus},
          {"id", f.id},
          {"id_hex", f.extended ? fmt::format("{:08X}", f.id) : fmt::format("{:03X}", f.id)},
          {"extended", f.extended},
          {"rtr", f.rtr},
          {"error", f.error},
          {"dlc", f.dlc},
          {"data", hex_bytes(payload.data(), payload.size())}};
}

struct FileCloser {
  void operator()(std::FILE* f) const noexcept {
    if (f) std::fclose(f);
  }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

int run_dump(const DumpOptions& o) {
  asio::io_context io;
  SteadyClock clock;
  const auto failed = [&](const std::string& what) { return report_error(o.jsonl, "hilbridge can dump: ", what, 2); };
  auto url = can::parse_bus_url(o.bus);
  if (!url) return failed(fmt::format("--bus: {}", url.error()));
  File log;
  File pcap;
  if (!o.log.empty() && !(log = File(std::fopen(o.log.c_str(), "w"))))
    return failed(fmt::format("cannot create log file '{}': {}", o.log, std::strerror(errno)));
  if (!o.pcap.empty()) {
    pcap = File(std::fopen(o.pcap.c_str(), "wb"));
    if (!pcap) return failed(fmt::format("cannot create pcap file '{}': {}", o.pcap, std::strerror(errno)));
    const auto header = can::pcap::make_global_header();
    std::fwrite(header.data(), 1, header.size(), pcap.get());
    std::fflush(pcap.get());
  }
  auto channel = can::make_channel(*url, {io.get_executor(), clock});
  if (!channel)  // the bus cannot be reached: 1, as sdo, scan, nmt (docs/cli.md)
    return report_error(o.jsonl, "hilbridge can dump: ", channel.error().message, 1);
  const auto wall_offset = std::chrono::duration_cast<Duration>(std::chrono::system_clock::now().time_since_epoch()) -
                           clock.now().time_since_epoch();
  std::uint64_t frames = 0;
  std::string line;
  const std::string iface = url->name;
  (*channel)->set_receive_handler([&](const can::Frame& f, TimePoint t) {
    const auto ns = (t.time_since_epoch() + wall_offset).count();
    const can::socketcand::Timestamp ts{ns / 1'000'000'000, static_cast<std::uint32_t>((ns % 1'000'000'000) / 1000)};
    line.clear();
    can::candump::format_log_line(line, {ts, iface, f});
    line.push_back('\n');
    if (!o.quiet && o.jsonl) {
      print_json(frame_json(f, ns / 1000, iface));
    } else if (!o.quiet) {
      std::fwrite(line.data(), 1, line.size(), stdout);
      std::fflush(stdout);
    }
    if (log) {
      std::fwrite(line.data(), 1, line.size(), log.get());
      std::fflush(log.get());
    }
    if (pcap) {
      const auto rec = can::pcap::make_record(f, ts);
      std::fwrite(rec.data(), 1, rec.size(), pcap.get());
      std::fflush(pcap.get());
    }
    if (++frames == o.count) io.stop();
  });
  fmt::print(stderr, "hilbridge can dump: listening on {}{}\n", url->to_string(),
             o.count ? fmt::format(" for {} frames", o.count) : std::string(" (Ctrl-C to stop)"));
  asio::signal_set signals(io, SIGINT, SIGTERM);
  signals.async_wait([&](const std::error_code&, int) { io.stop(); });
  asio::steady_timer deadline(io);
  if (o.duration > Duration::zero()) {
    deadline.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(o.duration));
    deadline.async_wait([&](const std::error_code& ec) {
      if (!ec) io.stop();
    });
  }
  io.run();
  const auto st = (*channel)->stats();
  fmt::print(stderr, "hilbridge can dump: {} frames ({} error frames, {} receive overruns)\n", frames, st.error_frames,
             st.rx_overruns);
  return 0;
}

}  // namespace

void add_dump(CLI::App& can, Context& ctx) {
  auto o = std::make_shared<DumpOptions>();
  auto* cmd = can.add_subcommand("dump", "Print received frames (candump -L lines); write a log and/or a pcap file");
  cmd->footer(
      "Print every received frame as `(SECONDS.MICROS) BUS ID#DATA` (candump -L format, wall-clock\n"
      "time). --log writes the same lines to a file that `hilbridge can replay` and canplayer read;\n"
      "--pcap writes LINKTYPE_CAN_SOCKETCAN (227) that Wireshark's CAN and CANopen dissectors open.");
  cmd->add_option("--bus", o->bus, bus_help)->required();
  cmd->add_option("--pcap", o->pcap, "Also write a pcap capture to FILE");
  cmd->add_option("--log", o->log, "Also write candump log lines to FILE");
  cmd->add_option("--count,-n", o->count, "Stop after N frames");
  add_duration_option(*cmd, "--duration", o->duration, "Stop after this long, e.g. 30s or 500ms", "s",
                      {std::chrono::microseconds(1)});
  cmd->add_flag("--quiet,-q", o->quiet, "Do not print frames on stdout (files only)");
  cmd->add_flag("--jsonl", o->jsonl,
                "Print JSON Lines on stdout instead of candump lines: one object per frame with time, id, "
                "extended/rtr/error flags, dlc and data as hex (docs/json.md); --log still writes candump lines");
  cmd->callback([o, &ctx] { ctx.exit_code = run_dump(*o); });
}

}  // namespace hil::cli::can_cmd
