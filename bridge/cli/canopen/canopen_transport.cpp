// SPDX-License-Identifier: MIT
// The `canopen` transport for `hilbridge run`: CiA 402 axes behind one CANopen master per bus.
// Without `bus:` (or with `bus: virtual:NAME`) the nodes are simulated CiA 402 drives on an
// in-process virtual bus, deterministic on the run's clock; with `bus: vcan0` / `can0` /
// `socketcand://...` the master talks to real nodes (real-time runs only). SYNC at the cycle period.
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <asio/io_context.hpp>
#include <fmt/format.h>

#include "hil/can/make_channel.hpp"
#include "hil/can/virtual_bus.hpp"
#include "hil/canopen/eds.hpp"
#include "hil/cia402/cia402_drive.hpp"
#include "hil/cia402/layout.hpp"
#include "hil/cli/context.hpp"
#include "hil/core/fault_injection.hpp"
#include "hil/core/yaml_config.hpp"
#include "hil/mocks/cia402_node.hpp"

namespace hil::cli::canopen_cli {
namespace {

namespace fs = std::filesystem;

/// An axis whose node is simulated in this process: the Drive plus fault injection on the node.
class InProcessAxis final : public Drive, public FaultInjectable {
public:
  InProcessAxis(std::unique_ptr<cia402::Cia402Drive> drive, mocks::Cia402Node& node, const Clock& clock)
      : drive_(std::move(drive)), node_(node), clock_(clock) {}
  std::string_view name() const noexcept override { return drive_->name(); }
  DriveCapabilities capabilities() const noexcept override { return drive_->capabilities(); }
  void read(const CycleTime& c) override { drive_->read(c); }
  void write(const CycleTime& c, const DriveCommand& cmd) override { drive_->write(c, cmd); }
  const DriveFeedback& feedback() const noexcept override { return drive_->feedback(); }
  bool request(DriveRequest r) override { return drive_->request(r); }
  std::vector<std::string> injectable_faults() const override { return mocks::Cia402Node::fault_names(); }
  bool inject_fault(std::string_view name, bool active) override { return node_.inject_fault(name, active, clock_.now()); }

private:
  std::unique_ptr<cia402::Cia402Drive> drive_;
  mocks::Cia402Node& node_;
  const Clock& clock_;
};

struct Bus {
  std::string name;
  bool simulated = false;
  can::VirtualBus* vbus = nullptr;
  std::unique_ptr<can::Channel> master_channel;
  std::unique_ptr<cia402::Network> network;
  std::vector<std::unique_ptr<can::Channel>> node_channels;
  std::vector<std::unique_ptr<mocks::Cia402Node>> nodes;
  std::map<int, std::string> axis_of_node;
  bool started = false;
};

class CanopenTransport final : public TransportFactory {
public:
  std::expected<DrivePtr, ConfigError> make_drive(const std::string& axis_name, const YAML::Node& node,
                                                  RunEnvironment& env) override {
    const yaml::Where where{env.source_file, env.drive_path(axis_name)};
    if (auto k = yaml::check_keys(node, where,
                                  {"transport", "node", "bus", "eds", "heartbeat", "heartbeat_timeout", "sdo_timeout", "kv",
                                   "max_velocity", "velocity_lag", "feedforward", "homing", "check_identity", "mode",
                                   "position_gain"});
        !k)
      return std::unexpected(k.error());
    auto id = yaml::get_int(node, where, "node");
    if (!id) return std::unexpected(id.error());
    if (!id->has_value()) return std::unexpected(yaml::error_at(node, where.key("node"), "missing: the node-ID 1..127 of the drive"));
    if (**id < 1 || **id > 127)
      return std::unexpected(yaml::error_at(node["node"], where.key("node"), fmt::format("node-ID must be 1..127, got {}", **id)));
    const int nid = static_cast<int>(**id);
    auto bus_name = yaml::get_string(node, where, "bus");
    if (!bus_name) return std::unexpected(bus_name.error());
    const std::string url = bus_name->value_or("virtual:canopen");
    auto parsed = can::parse_bus_url(url);
    if (!parsed) return std::unexpected(yaml::error_at(node["bus"], where.key("bus"), parsed.error()));
    const bool simulated = parsed->kind == can::BusUrl::Kind::virtual_bus;
    if (!simulated && env.virtual_time)
      return std::unexpected(yaml::error_at(node["bus"], where.key("bus"),
                                            fmt::format("'{}' is a real CAN bus: it needs a real-time run (hilbridge run without "
                                                        "--virtual); leave `bus:` out to simulate the nodes",
                                                        url)));
    if (!simulated && env.io == nullptr)
      return std::unexpected(yaml::error_at(node["bus"], where.key("bus"), "a real CAN bus needs the run's I/O context"));
    auto ms = [&](std::string_view key, long long dflt) -> std::expected<Duration, ConfigError> {
      auto v = yaml::get_int(node, where, key);
      if (!v) return std::unexpected(v.error());
      const auto x = v->value_or(dflt);
      if (x < 0 || x > 65535)
        return std::unexpected(yaml::error_at(node[std::string(key)], where.key(key), fmt::format("must be 0..65535 ms, got {}", x)));
      return std::chrono::milliseconds(x);
    };
    auto hb = ms("heartbeat", 20);
    auto hb_timeout = ms("heartbeat_timeout", 100);
    auto sdo_timeout = ms("sdo_timeout", 100);
    for (auto* r : {&hb, &hb_timeout, &sdo_timeout})
      if (!*r) return std::unexpected(r->error());
    auto homing = yaml::get_bool(node, where, "homing");
    auto check_identity = yaml::get_bool(node, where, "check_identity");
    if (!homing) return std::unexpected(homing.error());
    if (!check_identity) return std::unexpected(check_identity.error());
    auto mode_name = yaml::get_string(node, where, "mode");
    if (!mode_name) return std::unexpected(mode_name.error());
    cia402::OperatingSetup setup = cia402::OperatingSetup::csp;
    if (mode_name->has_value()) {
      if (**mode_name == "csp") setup = cia402::OperatingSetup::csp;
      else if (**mode_name == "csv") setup = cia402::OperatingSetup::csv;
      else if (**mode_name == "pp") setup = cia402::OperatingSetup::pp;
      else
        return std::unexpected(yaml::error_at(node["mode"], where.key("mode"),
                                              fmt::format("unknown mode '{}': csp (cyclic position), csv (cyclic velocity, "
                                                          "hilbridge closes the position loop) or pp (the drive's own profile "
                                                          "position / profile velocity)",
                                                          **mode_name)));
    }
    auto gain = yaml::get_double(node, where, "position_gain");
    if (!gain) return std::unexpected(gain.error());
    if (gain->has_value() && (setup != cia402::OperatingSetup::csv || !(**gain > 0.0) || **gain > 10000.0))
      return std::unexpected(yaml::error_at(node["position_gain"], where.key("position_gain"),
                                            setup != cia402::OperatingSetup::csv
                                                ? std::string("position_gain is the csv position loop: set `mode: csv` or leave it out")
                                                : fmt::format("must be > 0 and <= 10000 1/s, got {}", **gain)));

    // The node's EDS: a file (relative to the scenario) or the simulated drive's.
    auto eds_path = yaml::get_string(node, where, "eds");
    if (!eds_path) return std::unexpected(eds_path.error());
    std::expected<canopen::DeviceDescription, ConfigError> eds;
    if (eds_path->has_value()) {
      fs::path p = **eds_path;
      if (p.is_relative() && !env.source_file.empty()) p = fs::path(env.source_file).parent_path() / p;
      eds = canopen::load_eds(p, static_cast<canopen::NodeId>(nid));
    } else {
      eds = canopen::parse_eds(mocks::cia402_node_eds(), "hil_cia402_drive.eds", static_cast<canopen::NodeId>(nid));
    }
    if (!eds) {
      auto e = eds.error();
      if (e.key.empty()) e.key = where.key("eds").path;
      return std::unexpected(e);
    }

    auto& bus = get_bus(url, simulated, *sdo_timeout, env);
    if (!bus.network) return std::unexpected(yaml::error_at(node["bus"], where.key("bus"), bus_error_));
    if (bus.axis_of_node.contains(nid))
      return std::unexpected(yaml::error_at(node["node"], where.key("node"),
                                            fmt::format("node {} on {} is already used by axis '{}'", nid, url, bus.axis_of_node[nid])));
    bus.axis_of_node[nid] = axis_name;

    mocks::Cia402Node* sim = nullptr;
    if (simulated) {
      mocks::Cia402NodeOptions o;
      o.node = static_cast<canopen::NodeId>(nid);
      auto plant = [&](std::string_view key, double& out) -> std::expected<void, ConfigError> {
        auto v = yaml::get_double(node, where, key);
        if (!v) return std::unexpected(v.error());
        if (v->has_value()) {
          if (**v < 0) return std::unexpected(yaml::error_at(node[std::string(key)], where.key(key), "must be >= 0"));
          out = **v;
        }
        return {};
      };
      for (auto r : {plant("kv", o.plant.kv_per_s), plant("max_velocity", o.plant.max_velocity_inc_per_s),
                     plant("velocity_lag", o.plant.velocity_lag_s), plant("feedforward", o.plant.velocity_feedforward)})
        if (!r) return std::unexpected(r.error());
      can::ParticipantOptions po;
      po.filters = mocks::predefined_filters(static_cast<canopen::NodeId>(nid));  // like the node's CAN controller
      bus.node_channels.push_back(bus.vbus->attach(fmt::format("node{}", nid), po));
      bus.nodes.push_back(std::make_unique<mocks::Cia402Node>(*bus.node_channels.back(), o));
      sim = bus.nodes.back().get();
    }
    cia402::AxisOptions ao;
    ao.node = static_cast<canopen::NodeId>(nid);
    ao.heartbeat_producer = *hb;
    ao.heartbeat_consumer = *hb_timeout;
    ao.check_identity = check_identity->value_or(true);
    ao.profile_objects = setup == cia402::OperatingSetup::pp;
    bus.network->master().add_node(cia402::make_axis_node_config(*eds, ao));
    cia402::DriveOptions dopt;
    dopt.name = fmt::format("canopen:{}/{}", url, nid);
    dopt.homing = homing->value_or(true);
    dopt.setup = setup;
    if (gain->has_value()) dopt.csv_position_gain_per_s = **gain;
    auto drive = std::make_unique<cia402::Cia402Drive>(*bus.network, static_cast<canopen::NodeId>(nid), dopt);
    if (sim != nullptr) return std::make_unique<InProcessAxis>(std::move(drive), *sim, env.clock);
    return drive;
  }

  /// Deliver everything due now. On real time the clock moves while handlers send, so repeat
  /// until the bus is quiet (bounded: every pass delivers at least one frame).
  void flush(Bus& bus) {
    if (bus.vbus == nullptr) return;
    for (int i = 0; i < 64 && bus.vbus->deliver(clock_->now()) > 0; ++i) {
    }
  }

  void begin_cycle(const CycleTime& cycle) override {
    for (auto& [name, bus] : buses_) {
      if (!bus.started) {
        for (auto& n : bus.nodes) n->start(cycle.now);
        bus.network->start(cycle.now);
        bus.started = true;
      }
      bus.network->step(cycle.now);
      flush(bus);
    }
  }

  void end_cycle(const CycleTime& cycle) override {
    for (auto& [name, bus] : buses_) {
      for (auto& n : bus.nodes) n->step(cycle.now);
      flush(bus);
    }
  }

  TransportReport finish(const CycleTime&) override {
    TransportReport r;
    for (auto& [name, bus] : buses_) {
      auto& m = bus.network->master();
      int started = 0;
      for (auto id : m.nodes()) {
        const auto& st = m.status(id);
        if (st.boot == canopen::NodeBootState::started) ++started;
        else if (st.boot_error) {
          r.lines.push_back(fmt::format("canopen {}: node {} boot failed: {} {}", name, id, st.boot_error.message(), st.detail));
          r.ok = false;
        }
      }
      r.lines.push_back(fmt::format("canopen {}: {} of {} node(s) started{}, {} transmit error(s)", name, started, m.nodes().size(),
                                    bus.simulated ? " (simulated CiA 402 nodes)" : "", bus.network->stats().tx_errors));
    }
    return r;
  }

private:
  Bus& get_bus(const std::string& url, bool simulated, Duration sdo_timeout, RunEnvironment& env) {
    auto it = buses_.find(url);
    if (it != buses_.end()) return it->second;
    auto& bus = buses_[url];
    bus.name = url;
    bus.simulated = simulated;
    canopen::MasterOptions mo;
    mo.sync_period = env.period;
    mo.sdo.timeout = sdo_timeout;
    mo.sdo.retries = 1;
    mo.boot_timeout = std::chrono::seconds(1);
    clock_ = &env.clock;
    if (!registry_) registry_ = std::make_unique<can::VirtualBusRegistry>(env.clock);
    if (simulated) {
      auto parsed = can::parse_bus_url(url);
      bus.vbus = &registry_->get(parsed->name);
      bus.master_channel = bus.vbus->attach("master");
    } else {
      auto ch = can::make_channel(url, can::ChannelRequest{env.io->get_executor(), env.clock, registry_.get(), "hilbridge-master"});
      if (!ch) {
        bus_error_ = fmt::format("cannot open CAN bus '{}': {}", url, ch.error().message);
        buses_.erase(url);
        static Bus empty;
        return empty;
      }
      bus.master_channel = std::move(*ch);
    }
    bus.network = std::make_unique<cia402::Network>(*bus.master_channel, mo);
    return bus;
  }

  const Clock* clock_ = nullptr;
  std::unique_ptr<can::VirtualBusRegistry> registry_;
  std::map<std::string, Bus> buses_;
  std::string bus_error_;
};

}  // namespace

void register_canopen_transport(Context& ctx) {
  ctx.transports.add("canopen", [] { return std::make_unique<CanopenTransport>(); });
}

}  // namespace hil::cli::canopen_cli
