// SPDX-License-Identifier: MIT
#include "emulate.hpp"

#include <poll.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <mutex>
#include <optional>
#include <thread>

#include "hil/cli/duration_option.hpp"
#include "hil/core/text_file.hpp"
#include "hil/serial/file_lock.hpp"
#include "hil/serial/linux/ports.hpp"
#include "hil/serial/serial_stream.hpp"

namespace hil::cli::serial_cli {

void add_emulate_options(CLI::App& cmd, EmulateOptions& o) {
  cmd.add_flag("--pty", o.pty, "Serve on a new pseudo-terminal; its slave path is printed on the first line of stdout");
  cmd.add_option("--tcp", o.tcp_port, "Serve on this TCP port instead (0 = any free port, printed on stdout)")
      ->check(CLI::Range(0, 65535));
  cmd.add_option("--bind", o.bind, "Address to listen on with --tcp")->capture_default_str();
  cmd.add_option("--baud,-b", o.link.baud, "Baud rate the emulated device is set to")->capture_default_str();
  cmd.add_option("--format,-f", o.link.format, "Character format, e.g. 7E2 (parity is carried in bit 7 on a pty/TCP)")
      ->capture_default_str();
  cmd.add_option("--flow", o.link.flow, "Flow control: none, rtscts or xonxoff")->capture_default_str();
  cmd.add_option("--xon", o.link.xon, "XON byte")->capture_default_str();
  cmd.add_option("--xoff", o.link.xoff, "XOFF byte")->capture_default_str();
  add_duration_option(cmd, "--idle-timeout", o.idle_timeout,
                      "With --tcp: close a client that sends nothing for this long, so an idle or half-open client "
                      "does not hold the line (default 60s; 100ms .. 24h)",
                      "s", {std::chrono::milliseconds(100), std::chrono::hours(24)});
  cmd.add_option("--state", o.state_file,
                 "State file (saved atomically whenever the line is quiet after a change); default "
                 "$XDG_STATE_HOME/hilbridge/<device>.json; 'none' keeps nothing");
}

std::filesystem::path default_state_path(const std::string& device) {
  std::filesystem::path base;
  if (const char* x = std::getenv("XDG_STATE_HOME"); x != nullptr && *x != '\0')
    base = x;
  else if (const char* h = std::getenv("HOME"); h != nullptr)
    base = std::filesystem::path(h) / ".local" / "state";
  else
    base = std::filesystem::temp_directory_path();
  return base / "hilbridge" / (device + ".json");
}

int serve(mocks::legacy::Endpoint& endpoint, const EmulateOptions& o, const std::filesystem::path& state,
          const std::function<std::string(mocks::legacy::Endpoint&, const std::string&)>& on_command) {
  auto fmt_ok = line_format(o.link);
  if (!fmt_ok) {
    fmt::print(stderr, "error: {}\n", fmt_ok.error());
    return 2;
  }
  if (!o.pty && o.tcp_port < 0) {
    fmt::print(stderr, "error: give --pty or --tcp PORT\n");
    return 2;
  }
  install_interrupt_handler();
  SteadyClock clock;
  hil::serial::Discipline d;
  d.software_parity = true;
  std::unique_ptr<hil::serial::SerialStream> stream;
  std::optional<hil::serial::linux_io::PtyEndpoint> pty;
  std::unique_ptr<hil::serial::linux_io::TcpListener> listener;
  if (o.pty) {
    auto p = hil::serial::linux_io::PtyEndpoint::create();
    if (!p) {
      fmt::print(stderr, "error: {}\n", p.error().message);
      return 1;
    }
    pty.emplace(std::move(*p));
    stream = std::make_unique<hil::serial::SerialStream>(pty->take_master(), *fmt_ok, d, clock);
    fmt::print("{}\n", pty->slave_path());
  } else {
    auto l = hil::serial::linux_io::TcpListener::create(o.bind, static_cast<std::uint16_t>(o.tcp_port));
    if (!l) {
      fmt::print(stderr, "error: {}\n", l.error().message);
      return 1;
    }
    listener = std::move(*l);
    fmt::print("tcp:{}:{}\n", o.bind, listener->port());
  }
  std::fflush(stdout);
  if (!state.empty()) fmt::print(stderr, "state file: {}\n", state.string());

  std::atomic<bool> stop{false};
  std::mutex endpoint_mutex;  // guards the endpoint between the line thread and stdin commands
  std::unique_ptr<mocks::legacy::EndpointHost> host;
  std::thread line([&] {
    // Failed accepts: one line when they start, one when a client is accepted again.
    std::uint64_t errors_before = 0;  // listener->accept_errors() when the present run of failures began
    bool failing = false;
    while (!stop && !interrupted()) {
      if (listener && !stream) {
        // A failed accept (out of file descriptors) returns after its whole 200 ms: no busy loop.
        auto raw = listener->accept(std::chrono::milliseconds(200));
        const std::uint64_t errors = listener->accept_errors();
        if (!failing && errors != errors_before) {
          failing = true;
          fmt::print(stderr, "accepting a TCP client failed: {}; retrying every 200 ms\n",
                     listener->last_accept_error().message());
        }
        if (!raw) continue;
        if (failing) {
          fmt::print(stderr, "accepted a TCP client after {} failed accepts\n", errors - errors_before);
          failing = false;
        }
        errors_before = errors;
        stream = std::make_unique<hil::serial::SerialStream>(std::move(raw), *fmt_ok, d, clock);
      }
      {
        std::lock_guard lock(endpoint_mutex);
        if (!host) host = std::make_unique<mocks::legacy::EndpointHost>(endpoint, *stream, clock, state);
      }
      const auto ec = host->step(std::chrono::milliseconds(50));
      const bool idle = listener && clock.now() - host->last_rx() > o.idle_timeout;
      if (idle)
        fmt::print(stderr, "closing the TCP client: nothing received for {}\n", format_duration(o.idle_timeout));
      if (listener && (ec == hil::serial::LineError::closed || idle)) {
        // The TCP client went away (or idles): keep the state, wait for the next one.
        std::lock_guard lock(endpoint_mutex);
        (void)host->persist();
        host.reset();
        stream.reset();
      }
    }
    if (host) (void)host->persist();
  });

  std::string cmd;
  bool stdin_open = true;
  while (!interrupted()) {
    if (!stdin_open) {
      ::poll(nullptr, 0, 200);
      continue;
    }
    pollfd p{0, POLLIN, 0};
    if (::poll(&p, 1, 200) <= 0) continue;
    if (!std::getline(std::cin, cmd)) {
      stdin_open = false;  // keep serving without a console (run in the background)
      continue;
    }
    if (cmd.empty()) continue;
    if (cmd == "quit" || cmd == "exit") break;
    std::string reply;
    if (cmd.starts_with("drop ")) {
      // Fault injection for tests: "drop AFTER COUNT" stops answering after AFTER replies.
      int after = 0, count = 0;
      if (std::sscanf(cmd.c_str(), "drop %d %d", &after, &count) != 2 || after < 0 || count < 0) {
        fmt::print("error: usage: drop AFTER COUNT\n");
      } else {
        std::lock_guard lock(endpoint_mutex);
        if (host) host->drop_replies(after, count);
        fmt::print("{}\n", host ? "ok " + cmd : std::string("error: no line yet"));
      }
      std::fflush(stdout);
      continue;
    }
    {
      std::lock_guard lock(endpoint_mutex);
      if (host)
        host->with_endpoint([&](mocks::legacy::Endpoint& e) { reply = on_command(e, cmd); });
      else
        reply = on_command(endpoint, cmd);
    }
    fmt::print("{}\n", reply);
    std::fflush(stdout);
  }
  stop = true;
  line.join();
  return 0;
}

/// The state file, locked for the life of this emulator: a second emulator on the same file
/// (the default path is per device, so two `emulate clm14` share it) is refused.
std::expected<std::filesystem::path, std::string> resolve_state(const EmulateOptions& o, const std::string& device) {
  if (o.state_file == "none") return std::filesystem::path{};
  const std::filesystem::path p =
      o.state_file.empty() ? default_state_path(device) : std::filesystem::path(o.state_file);
  std::error_code ec;
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path(), ec);
  static std::optional<hil::serial::FileLock> held;
  auto lock = hil::serial::FileLock::acquire(p);
  if (!lock) return std::unexpected(lock.error());
  held.emplace(std::move(*lock));
  return p;
}

std::optional<std::string> read_file(const std::filesystem::path& p) {
  if (p.empty()) return std::nullopt;
  std::error_code ec;
  if (!std::filesystem::exists(p, ec)) return std::nullopt;
  auto text = read_text_file(p);
  if (!text) {
    fmt::print(stderr, "warning: {}; starting from defaults\n", text.error());
    return std::nullopt;
  }
  return *text;
}

}  // namespace hil::cli::serial_cli
