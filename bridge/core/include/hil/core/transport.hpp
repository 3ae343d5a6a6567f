// SPDX-License-Identifier: MIT
#pragma once
// How a scenario's `drive:` block becomes a Drive. Each transport (sim, canopen, modbus,
// stepdir, ...) provides a TransportFactory; the application (a command-line tool, a test, an
// embedding program) registers one creator per transport in a TransportRegistry (no process-wide
// singleton). A run creates fresh factory instances, so a
// factory may keep per-run state shared by its axes (one CANopen master for all nodes on a bus).

#include <expected>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "hil/core/clock.hpp"
#include "hil/core/config_error.hpp"
#include "hil/core/drive.hpp"

namespace asio {
class io_context;
}
namespace YAML {
class Node;  // the drive block; factories read it with hil::yaml (hil::config)
}

namespace hil {

/// What a run gives its transports.
struct RunEnvironment {
  const Clock& clock;
  bool virtual_time = true;        ///< true: the clock is simulated; no real I/O may block
  asio::io_context* io = nullptr;  ///< real-time runs: the I/O context for sockets and serial ports
  std::string source_file;         ///< scenario path, for ConfigError and relative paths
  Duration period{std::chrono::milliseconds(1)};
  /// Transports that generate pulse streams (step/dir) check every edge they emit against the
  /// timing rules of their line and the plan's position, and report a violation in their
  /// TransportReport (ok == false). Other transports ignore it.
  bool verify_edge_streams = false;
  /// Key path of the `drive:` block being built ("machine.axes[2].drive"), set by the runner before
  /// each make_drive so that transports' errors use the same paths as the scenario loader.
  std::string drive_key;

  /// `drive_key`, or "axes.<axis>.drive" when a caller outside the runner left it empty.
  [[nodiscard]] std::string drive_path(const std::string& axis_name) const {
    return drive_key.empty() ? "axes." + axis_name + ".drive" : drive_key;
  }
};

/// What a transport says about a finished run (printed in the summary). `ok == false` makes the
/// run fail (e.g. an edge stream that broke a timing rule).
struct TransportReport {
  std::vector<std::string> lines;
  bool ok = true;
};

class TransportFactory {
 public:
  virtual ~TransportFactory() = default;
  /// Build the drive for one axis from its `drive:` node. Errors carry file/line/key.
  virtual std::expected<DrivePtr, ConfigError> make_drive(const std::string& axis_name, const YAML::Node& drive_node,
                                                          RunEnvironment& env) = 0;
  /// Bus-level work before the axes read (deliver frames, step in-process mocks, SYNC).
  virtual void begin_cycle(const CycleTime&) {}
  /// Bus-level work after the axes wrote (flush frames, step in-process mocks).
  virtual void end_cycle(const CycleTime&) {}
  /// Once, after the last cycle of a run.
  virtual TransportReport finish(const CycleTime&) { return {}; }
};

class TransportRegistry {
 public:
  using Creator = std::function<std::unique_ptr<TransportFactory>()>;
  void add(std::string name, Creator creator) { creators_[std::move(name)] = std::move(creator); }
  [[nodiscard]] std::unique_ptr<TransportFactory> create(const std::string& name) const {
    auto it = creators_.find(name);
    return it == creators_.end() ? nullptr : it->second();
  }
  [[nodiscard]] std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& [n, c] : creators_) out.push_back(n);
    return out;
  }

 private:
  std::map<std::string, Creator> creators_;
};

}  // namespace hil
