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
#include <vector>

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
  return serve_lines(
      {ServedLine{&endpoint, state}}, o,
      [&](std::span<mocks::legacy::Endpoint* const> e, const std::string& cmd) { return on_command(*e.front(), cmd); });
}

namespace {

/// One served line: its pty or TCP listener, the stream of the present client, the host.
struct LineState {
  mocks::legacy::Endpoint* endpoint = nullptr;
  std::filesystem::path state;
  std::unique_ptr<hil::serial::SerialStream> stream;
  std::optional<hil::serial::linux_io::PtyEndpoint> pty;
  std::unique_ptr<hil::serial::linux_io::TcpListener> listener;
  std::unique_ptr<mocks::legacy::EndpointHost> host;
  std::uint64_t errors_before = 0;  ///< listener->accept_errors() when the present run of failures began
  bool failing = false;
};

}  // namespace

int serve_lines(
    const std::vector<ServedLine>& served, const EmulateOptions& o,
    const std::function<std::string(std::span<mocks::legacy::Endpoint* const>, const std::string&)>& on_command) {
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
  std::vector<LineState> lines(served.size());
  std::vector<mocks::legacy::Endpoint*> endpoints;
  for (std::size_t i = 0; i < served.size(); ++i) {
    auto& l = lines[i];
    l.endpoint = served[i].endpoint;
    l.state = served[i].state;
    endpoints.push_back(l.endpoint);
    if (o.pty) {
      auto p = hil::serial::linux_io::PtyEndpoint::create();
      if (!p) {
        fmt::print(stderr, "error: {}\n", p.error().message);
        return 1;
      }
      l.pty.emplace(std::move(*p));
      l.stream = std::make_unique<hil::serial::SerialStream>(l.pty->take_master(), *fmt_ok, d, clock);
      fmt::print("{}\n", l.pty->slave_path());
    } else {
      // Line i on port + i (port 0: any free port for each).
      const int port = o.tcp_port == 0 ? 0 : o.tcp_port + static_cast<int>(i);
      if (port > 65535) {
        fmt::print(stderr, "error: --tcp {}: line {} would need port {}\n", o.tcp_port, i + 1, port);
        return 2;
      }
      auto listener = hil::serial::linux_io::TcpListener::create(o.bind, static_cast<std::uint16_t>(port));
      if (!listener) {
        fmt::print(stderr, "error: {}\n", listener.error().message);
        return 1;
      }
      l.listener = std::move(*listener);
      fmt::print("tcp:{}:{}\n", o.bind, l.listener->port());
    }
  }
  std::fflush(stdout);
  for (const auto& l : lines)
    if (!l.state.empty()) fmt::print(stderr, "state file: {}\n", l.state.string());

  // One thread serves every line in turn (a module's deadline bounds each wait to its cycle), so the
  // endpoints never run concurrently: endpoints that share data (the PLC's DBs of an S5 rack) need
  // no lock of their own. With several lines the waits are short so that no line starves.
  const bool several = lines.size() > 1;
  const Duration step_wait = several ? Duration(std::chrono::milliseconds(2)) : Duration(std::chrono::milliseconds(50));
  const Duration accept_wait =
      several ? Duration(std::chrono::milliseconds(5)) : Duration(std::chrono::milliseconds(200));
  std::atomic<bool> stop{false};
  std::mutex endpoint_mutex;  // guards the hosts between the line thread and stdin commands
  std::thread line([&] {
    while (!stop && !interrupted()) {
      for (auto& l : lines) {
        if (l.listener && !l.stream) {
          // A failed accept (out of file descriptors) returns after its whole wait: no busy loop.
          auto raw = l.listener->accept(accept_wait);
          const std::uint64_t errors = l.listener->accept_errors();
          if (!l.failing && errors != l.errors_before) {
            l.failing = true;
            fmt::print(stderr, "accepting a TCP client failed: {}; retrying every {}\n",
                       l.listener->last_accept_error().message(), format_duration(accept_wait));
          }
          if (!raw) continue;
          if (l.failing) {
            fmt::print(stderr, "accepted a TCP client after {} failed accepts\n", errors - l.errors_before);
            l.failing = false;
          }
          l.errors_before = errors;
          l.stream = std::make_unique<hil::serial::SerialStream>(std::move(raw), *fmt_ok, d, clock);
        }
        {
          std::lock_guard lock(endpoint_mutex);
          if (!l.host) l.host = std::make_unique<mocks::legacy::EndpointHost>(*l.endpoint, *l.stream, clock, l.state);
        }
        const auto ec = l.host->step(step_wait);
        const bool idle = l.listener && clock.now() - l.host->last_rx() > o.idle_timeout;
        if (idle)
          fmt::print(stderr, "closing the TCP client: nothing received for {}\n", format_duration(o.idle_timeout));
        if (l.listener && (ec == hil::serial::LineError::closed || idle)) {
          // The TCP client went away (or idles): keep the state, wait for the next one.
          std::lock_guard lock(endpoint_mutex);
          (void)l.host->persist();
          l.host.reset();
          l.stream.reset();
        }
      }
    }
    for (auto& l : lines)
      if (l.host) (void)l.host->persist();
  });

  // Runs `fn` with every endpoint locked (each under its host's lock, in line order).
  const std::function<void(std::size_t, const std::function<void()>&)> with_all = [&](std::size_t i,
                                                                                      const std::function<void()>& fn) {
    if (i == lines.size()) return fn();
    if (lines[i].host)
      lines[i].host->with_endpoint([&](mocks::legacy::Endpoint&) { with_all(i + 1, fn); });
    else
      with_all(i + 1, fn);
  };

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
      // Fault injection for tests: "drop AFTER COUNT" stops answering after AFTER replies (every line).
      int after = 0, count = 0;
      if (std::sscanf(cmd.c_str(), "drop %d %d", &after, &count) != 2 || after < 0 || count < 0) {
        fmt::print("error: usage: drop AFTER COUNT\n");
      } else {
        std::lock_guard lock(endpoint_mutex);
        bool any = false;
        for (auto& l : lines)
          if (l.host) {
            l.host->drop_replies(after, count);
            any = true;
          }
        fmt::print("{}\n", any ? "ok " + cmd : std::string("error: no line yet"));
      }
      std::fflush(stdout);
      continue;
    }
    {
      std::lock_guard lock(endpoint_mutex);
      with_all(0, [&] { reply = on_command(endpoints, cmd); });
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
  static std::vector<hil::serial::FileLock> held;  // one per state file (several lines: several files)
  auto lock = hil::serial::FileLock::acquire(p);
  if (!lock) return std::unexpected(lock.error());
  held.push_back(std::move(*lock));
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
