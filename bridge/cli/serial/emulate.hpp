// SPDX-License-Identifier: MIT
#pragma once
// `hilbridge emulate clm14|elg-tape|ip247|wf725`: emulated controllers on a pty or TCP port.

#include <expected>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hil/mocks/legacy/endpoint.hpp"
#include "link_options.hpp"

namespace hil::cli::serial_cli {

struct EmulateOptions {
  bool pty = false;
  int tcp_port = -1;  ///< >= 0: listen on this TCP port (0 = any free port)
  std::string bind = "127.0.0.1";
  LinkOptions link;        ///< baud/format/flow for the emulator's side of the line
  std::string state_file;  ///< "" = default path per device; "none" = no persistence
  Duration idle_timeout =
      std::chrono::seconds(60);  ///< TCP: a client that sends nothing this long is closed (frees the line)
};

void add_emulate_options(CLI::App& cmd, EmulateOptions& o);
/// Default state path: $XDG_STATE_HOME/hilbridge/<device>.json (or ~/.local/state/...).
[[nodiscard]] std::filesystem::path default_state_path(const std::string& device);

/// The state file of `device` (or --state), locked for the life of this emulator: a second
/// emulator on the same file is refused. Empty path for `--state none`.
[[nodiscard]] std::expected<std::filesystem::path, std::string> resolve_state(const EmulateOptions& o,
                                                                              const std::string& device);
/// The saved state at `p`, nullopt when there is none (a read error is a warning on stderr).
[[nodiscard]] std::optional<std::string> read_file(const std::filesystem::path& p);

/// Serve `endpoint` on the line `o` describes until SIGINT/SIGTERM. Prints the pty path or TCP
/// port on stdout (first line), then reads commands from stdin and hands them to `on_command`
/// (which returns a reply line, or an error text starting with "error:"). "drop AFTER COUNT"
/// (fault injection: stop answering after AFTER replies for COUNT replies) and "quit" are
/// handled here for every device.
int serve(mocks::legacy::Endpoint& endpoint, const EmulateOptions& o, const std::filesystem::path& state,
          const std::function<std::string(mocks::legacy::Endpoint&, const std::string&)>& on_command);

/// One line of serve_lines(): its endpoint and state file (empty: none).
struct ServedLine {
  mocks::legacy::Endpoint* endpoint = nullptr;
  std::filesystem::path state;
};
/// serve() for several endpoints, each on its own line (devices of one rack, e.g. several IP247
/// modules): `--pty` opens one pty per line (the slave paths on the first lines of stdout, in
/// order), `--tcp P` listens on P, P + 1, ... (0: any free port for each; one `tcp:` line each).
/// One thread serves the lines in turn, so the endpoints never run concurrently (they may share
/// data). `on_command` gets every endpoint (each under its host's lock); "drop" applies to every line.
int serve_lines(
    const std::vector<ServedLine>& lines, const EmulateOptions& o,
    const std::function<std::string(std::span<mocks::legacy::Endpoint* const>, const std::string&)>& on_command);

}  // namespace hil::cli::serial_cli
