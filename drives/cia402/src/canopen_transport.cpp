// SPDX-License-Identifier: MIT
#include "hil/cia402/canopen_transport.hpp"

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <asio/io_context.hpp>

#include "hil/can/io/make_channel.hpp"
#include "hil/can/virtual_bus.hpp"
#include "hil/canopen/eds.hpp"
#include "hil/cia402/cia402_drive.hpp"
#include "hil/cia402/layout.hpp"
#include "hil/config/yaml_config.hpp"
#include "hil/core/fault_injection.hpp"
#include "hil/core/forwarding_drive.hpp"
#include "hil/mocks/cia402_node.hpp"
#include "hil/mocks/key_range.hpp"
#include "hil/mocks/switches.hpp"

namespace hil::cia402 {
namespace {

namespace fs = std::filesystem;

/// An axis whose node is simulated in this process: the Drive plus fault injection on the node.
class InProcessAxis final : public ForwardingDrive, public FaultInjectable {
 public:
  /// `master_node` != 0: the master produces a heartbeat the node watches, and the fault
  /// `master_heartbeat_loss` drops it on the bus (the node faults with 0x8130 after its consumer time).
  /// `needs` keeps `node` and `bus` (and the master the drive is attached to) alive.
  InProcessAxis(std::unique_ptr<cia402::Cia402Drive> drive, std::shared_ptr<void> needs, mocks::Cia402Node& node,
                const Clock& clock, can::VirtualBus& bus, canopen::NodeId master_node)
      : ForwardingDrive(std::move(drive), std::move(needs)),
        node_(node),
        clock_(clock),
        bus_(bus),
        master_node_(master_node) {}
  std::vector<std::string> injectable_faults() const override {
    auto names = mocks::Cia402Node::fault_names();
    // SDO faults act on SDO transfers; the run's exchange is PDOs only once the node has booted,
    // so in a scenario they would do nothing: refused (the node itself still offers them).
    std::erase_if(names, [](const std::string& n) { return n == "sdo_slow" || n == "sdo_timeout"; });
    if (master_node_ != 0) names.emplace_back("master_heartbeat_loss");
    return names;
  }
  bool inject_fault(std::string_view name, bool active) override {
    if (name != "master_heartbeat_loss") return node_.inject_fault(name, active, clock_.now());
    if (master_node_ == 0) return false;
    if (active && !master_drop_) {
      const std::uint32_t id = 0x700u + master_node_;
      master_drop_ = bus_.inject(
          can::FrameFault{.action = can::FaultAction::drop, .match = [id](const can::Frame& f) { return f.id == id; }});
    } else if (!active && master_drop_) {
      bus_.remove_fault(*master_drop_);
      master_drop_.reset();
    }
    return true;
  }

 private:
  mocks::Cia402Node& node_;
  const Clock& clock_;
  can::VirtualBus& bus_;
  canopen::NodeId master_node_;
  std::optional<std::size_t> master_drop_;  ///< the bus fault that drops the master's heartbeat
};

/// What the one master of a bus is set up with (from the first axis on it; the others must agree).
struct BusMaster {
  Duration sdo_timeout{};
  Duration heartbeat{};         ///< 0 = the master produces no heartbeat
  canopen::NodeId node_id = 0;  ///< the master's node-ID when it produces one
  bool operator==(const BusMaster&) const = default;
};

/// One CAN bus of a run: its master, channels and simulated nodes. Shared (std::shared_ptr) by the
/// factory and by every drive on it, so it outlives the last of them whatever order a run destroys
/// its axes and factories in (docs/ARCHITECTURE.md, "Teardown"); it tears itself down in the one
/// safe order: the nodes, their channels, the master, its channel, then the virtual bus.
struct Bus {
  Bus() = default;
  Bus(const Bus&) = delete;
  Bus& operator=(const Bus&) = delete;
  ~Bus() {
    nodes.clear();
    node_channels.clear();
    network.reset();  // after the drives (they detach from it), before its channel
    master_channel.reset();
    registry.reset();  // the virtual buses (vbus) the channels were attached to
  }
  std::string name;
  BusMaster master;
  bool simulated = false;
  std::shared_ptr<can::VirtualBusRegistry> registry;  ///< owns *vbus; shared by the factory's buses
  can::VirtualBus* vbus = nullptr;
  std::unique_ptr<can::Channel> master_channel;
  std::unique_ptr<cia402::Network> network;
  std::vector<std::unique_ptr<can::Channel>> node_channels;
  std::vector<std::unique_ptr<mocks::Cia402Node>> nodes;
  std::map<int, std::string> axis_of_node;
  std::vector<std::string> lines;  ///< EDS warnings and layout decisions, per node
  bool started = false;
};

class CanopenTransport final : public TransportFactory {
 public:
  std::expected<DrivePtr, ConfigError> make_drive(const std::string& axis_name, const YAML::Node& node,
                                                  RunEnvironment& env) override {
    const yaml::Where where{env.source_file, env.drive_path(axis_name)};
    if (auto k = yaml::check_keys(node, where,
                                  {"transport",
                                   "node",
                                   "bus",
                                   "eds",
                                   "heartbeat",
                                   "heartbeat_timeout",
                                   "sdo_timeout",
                                   "kv",
                                   "max_velocity",
                                   "velocity_lag",
                                   "feedforward",
                                   "homing",
                                   "check_identity",
                                   "mode",
                                   "position_gain",
                                   "master_heartbeat",
                                   "master_heartbeat_timeout",
                                   "master_node",
                                   "rpdo",
                                   "tpdo",
                                   "output_mask",
                                   "switches"});
        !k)
      return std::unexpected(k.error());
    auto id = yaml::get_int(node, where, "node");
    if (!id) return std::unexpected(id.error());
    if (!id->has_value())
      return std::unexpected(yaml::error_at(node, where.key("node"), "missing: the node-ID 1..127 of the drive"));
    if (**id < 1 || **id > 127)
      return std::unexpected(
          yaml::error_at(node["node"], where.key("node"), fmt::format("node-ID must be 1..127, got {}", **id)));
    const int nid = static_cast<int>(**id);
    auto bus_name = yaml::get_string(node, where, "bus");
    if (!bus_name) return std::unexpected(bus_name.error());
    const std::string url = bus_name->value_or("virtual:canopen");
    auto parsed = can::parse_bus_url(url);
    if (!parsed) return std::unexpected(yaml::error_at(node["bus"], where.key("bus"), parsed.error()));
    const bool simulated = parsed->kind == can::BusUrl::Kind::virtual_bus;
    if (!simulated && env.virtual_time)
      return std::unexpected(
          yaml::error_at(node["bus"], where.key("bus"),
                         fmt::format("'{}' is a real CAN bus: it needs a real-time run (hilbridge run without "
                                     "--virtual); leave `bus:` out to simulate the nodes",
                                     url)));
    if (!simulated && env.io == nullptr)
      return std::unexpected(
          yaml::error_at(node["bus"], where.key("bus"), "a real CAN bus needs the run's I/O context"));
    auto ms = [&](std::string_view key, long long dflt) -> std::expected<Duration, ConfigError> {
      auto v = yaml::get_int(node, where, key);
      if (!v) return std::unexpected(v.error());
      const auto x = v->value_or(dflt);
      if (x < 0 || x > 65535)
        return std::unexpected(
            yaml::error_at(node[std::string(key)], where.key(key), fmt::format("must be 0..65535 ms, got {}", x)));
      return std::chrono::milliseconds(x);
    };
    auto hb = ms("heartbeat", 20);
    auto hb_timeout = ms("heartbeat_timeout", 100);
    auto sdo_timeout = ms("sdo_timeout", 100);
    auto master_hb = ms("master_heartbeat", 0);
    for (auto* r : {&hb, &hb_timeout, &sdo_timeout, &master_hb})
      if (!*r) return std::unexpected(r->error());
    if (sdo_timeout->count() == 0)
      return std::unexpected(yaml::error_at(node["sdo_timeout"], where.key("sdo_timeout"),
                                            "must be 1..65535 ms: an SDO transfer needs time to answer"));
    // The node produces its heartbeat every `heartbeat` ms and the master watches it with
    // `heartbeat_timeout` (0 = not watched): a timeout not longer than the period faults at once.
    if (hb->count() > 0 && hb_timeout->count() > 0 && *hb_timeout <= *hb)
      return std::unexpected(
          yaml::error_at(node["heartbeat_timeout"] ? node["heartbeat_timeout"] : node["heartbeat"],
                         where.key(node["heartbeat_timeout"] ? "heartbeat_timeout" : "heartbeat"),
                         fmt::format("heartbeat_timeout {} ms must be longer than heartbeat {} ms (one late "
                                     "heartbeat must not fault the drive)",
                                     std::chrono::duration_cast<std::chrono::milliseconds>(*hb_timeout).count(),
                                     std::chrono::duration_cast<std::chrono::milliseconds>(*hb).count())));
    // The master's own heartbeat, watched by the node (0x1016:1): a drive whose master dies stops.
    auto master_hb_timeout =
        ms("master_heartbeat_timeout", 3 * std::chrono::duration_cast<std::chrono::milliseconds>(*master_hb).count());
    if (!master_hb_timeout) return std::unexpected(master_hb_timeout.error());
    auto master_node = yaml::get_int(node, where, "master_node");
    if (!master_node) return std::unexpected(master_node.error());
    const long long master_id = master_node->value_or(127);
    if (master_id < 1 || master_id > 127)
      return std::unexpected(yaml::error_at(node["master_node"], where.key("master_node"),
                                            fmt::format("the master's node-ID must be 1..127, got {}", master_id)));
    if (master_hb->count() == 0 && (node["master_heartbeat_timeout"] || node["master_node"]))
      return std::unexpected(
          yaml::error_at(node, where.key(node["master_node"] ? "master_node" : "master_heartbeat_timeout"),
                         "set `master_heartbeat` (ms) for the master to produce a heartbeat the node watches"));
    if (master_hb->count() > 0 && *master_hb_timeout <= *master_hb)
      return std::unexpected(
          yaml::error_at(node["master_heartbeat_timeout"], where.key("master_heartbeat_timeout"),
                         "must be longer than master_heartbeat (one missed heartbeat must not fault the drive)"));
    auto homing = yaml::get_bool(node, where, "homing");
    auto check_identity = yaml::get_bool(node, where, "check_identity");
    if (!homing) return std::unexpected(homing.error());
    if (!check_identity) return std::unexpected(check_identity.error());
    auto mode_name = yaml::get_string(node, where, "mode");
    if (!mode_name) return std::unexpected(mode_name.error());
    cia402::OperatingSetup setup = cia402::OperatingSetup::csp;
    if (mode_name->has_value()) {
      if (**mode_name == "csp")
        setup = cia402::OperatingSetup::csp;
      else if (**mode_name == "csv")
        setup = cia402::OperatingSetup::csv;
      else if (**mode_name == "pp")
        setup = cia402::OperatingSetup::pp;
      else
        return std::unexpected(
            yaml::error_at(node["mode"], where.key("mode"),
                           fmt::format("unknown mode '{}': csp (cyclic position), csv (cyclic velocity, "
                                       "hilbridge closes the position loop) or pp (the drive's own profile "
                                       "position / profile velocity)",
                                       **mode_name)));
    }
    auto gain = yaml::get_double(node, where, "position_gain");
    if (!gain) return std::unexpected(gain.error());
    if (gain->has_value() && (setup != cia402::OperatingSetup::csv || !(**gain > 0.0) || **gain > 10000.0))
      return std::unexpected(
          yaml::error_at(node["position_gain"], where.key("position_gain"),
                         setup != cia402::OperatingSetup::csv
                             ? std::string("position_gain is the csv position loop: set `mode: csv` or leave it out")
                             : fmt::format("must be > 0 and <= 10000 1/s, got {}", **gain)));

    // The node's EDS: a file (relative to the scenario) or the simulated drive's.
    auto eds_path = yaml::get_string(node, where, "eds");
    if (!eds_path) return std::unexpected(eds_path.error());
    std::expected<canopen::DeviceDescription, ConfigError> eds;
    std::string eds_text;
    std::string eds_name = "hil_cia402_drive.eds";
    if (eds_path->has_value()) {
      fs::path p = **eds_path;
      if (p.is_relative() && !env.source_file.empty()) p = fs::path(env.source_file).parent_path() / p;
      eds_name = p.string();
      std::ifstream in(p, std::ios::binary);
      if (!in)
        return std::unexpected(yaml::error_at(
            node["eds"], where.key("eds"), fmt::format("cannot open the EDS/DCF file '{}': check the path", eds_name)));
      std::ostringstream ss;
      ss << in.rdbuf();
      eds_text = ss.str();
      eds = canopen::parse_eds(eds_text, eds_name, static_cast<canopen::NodeId>(nid));
    } else {
      eds = canopen::parse_eds(mocks::cia402_node_eds(), eds_name, static_cast<canopen::NodeId>(nid));
    }
    if (!eds) {
      auto e = eds.error();
      if (e.key.empty()) e.key = where.key("eds").path;
      return std::unexpected(e);
    }
    // Explicit PDO mapping: `rpdo: [[0x6040, 0x607A], ...]`, entries "0xIIII" or "0xIIII:S".
    cia402::LayoutOverride mapping;
    for (const char* key : {"rpdo", "tpdo"}) {
      const auto list = node[key];
      if (!list) continue;
      auto bad = [&](const YAML::Node& at, std::string msg) {
        return std::unexpected(yaml::error_at(at, where.key(key), std::move(msg)));
      };
      if (!list.IsSequence())
        return bad(list, fmt::format("expected a list of PDOs, each a list of objects: {}: [[0x6041, 0x6064]]", key));
      std::vector<std::vector<canopen::PdoMappingEntry>> pdos;
      for (const auto& pdo : list) {
        if (!pdo.IsSequence()) return bad(pdo, "each PDO is a list of objects, e.g. [0x6041, \"0x6064:0\"]");
        std::vector<canopen::PdoMappingEntry> entries;
        for (const auto& obj : pdo) {
          const auto text = obj.IsScalar() ? obj.Scalar() : std::string();
          const auto colon = text.find(':');
          const auto idx = canopen::eval_eds_integer(text.substr(0, colon), 0);
          const auto sub = colon == std::string::npos ? std::optional<std::int64_t>(0)
                                                      : canopen::eval_eds_integer(text.substr(colon + 1), 0);
          if (!idx || !sub || *idx < 1 || *idx > 0xFFFF || *sub < 0 || *sub > 0xFF)
            return bad(obj, fmt::format("'{}' is not an object: write 0xIIII or 0xIIII:S", text));
          const auto* v = eds->od.find(static_cast<std::uint16_t>(*idx), static_cast<std::uint8_t>(*sub));
          if (v == nullptr) return bad(obj, fmt::format("0x{:04X}:{} is not in {}", *idx, *sub, eds->file));
          entries.push_back({static_cast<std::uint16_t>(*idx), static_cast<std::uint8_t>(*sub),
                             static_cast<std::uint8_t>(8 * canopen::data_type_size(v->type))});
        }
        pdos.push_back(std::move(entries));
      }
      (std::string_view(key) == "rpdo" ? mapping.rpdo : mapping.tpdo) = std::move(pdos);
    }

    const BusMaster wanted{*sdo_timeout, *master_hb,
                           master_hb->count() > 0 ? static_cast<canopen::NodeId>(master_id) : canopen::NodeId{0}};
    const auto shared_bus = get_bus(url, simulated, wanted, env);
    if (!shared_bus) return std::unexpected(yaml::error_at(node["bus"], where.key("bus"), bus_error_));
    Bus& bus = *shared_bus;
    if (bus.master != wanted) {
      const char* key = bus.master.sdo_timeout != wanted.sdo_timeout ? "sdo_timeout"
                        : bus.master.heartbeat != wanted.heartbeat   ? "master_heartbeat"
                                                                     : "master_node";
      return std::unexpected(yaml::error_at(node[key] ? node[key] : node, where.key(key),
                                            fmt::format("{} differs from axis '{}' on {}: one master serves the bus, "
                                                        "so every axis on it must give the same value",
                                                        key, bus.axis_of_node.begin()->second, url)));
    }
    if (wanted.node_id != 0 && nid == wanted.node_id)
      return std::unexpected(yaml::error_at(node["node"], where.key("node"),
                                            fmt::format("node-ID {} is the master's own (master_node)", nid)));
    if (bus.axis_of_node.contains(nid))
      return std::unexpected(
          yaml::error_at(node["node"], where.key("node"),
                         fmt::format("node {} on {} is already used by axis '{}'", nid, url, bus.axis_of_node[nid])));
    bus.axis_of_node[nid] = axis_name;

    cia402::AxisOptions ao;
    ao.node = static_cast<canopen::NodeId>(nid);
    ao.heartbeat_producer = *hb;
    ao.heartbeat_consumer = *hb_timeout;
    ao.check_identity = check_identity->value_or(true);
    ao.master_node = wanted.node_id;
    ao.master_heartbeat_timeout = *master_hb_timeout;
    ao.setup = setup;
    ao.mapping = std::move(mapping);
    auto output_mask = yaml::get_int(node, where, "output_mask");
    if (!output_mask) return std::unexpected(output_mask.error());
    if (output_mask->has_value()) {
      if (**output_mask < 0 || **output_mask > 0xFFFFFFFFLL)
        return std::unexpected(
            yaml::error_at(node["output_mask"], where.key("output_mask"),
                           fmt::format("the 0x60FE:2 bit mask is 32 bits: 0 .. 0xFFFFFFFF, got {}", **output_mask)));
      ao.digital_output_mask = static_cast<std::uint32_t>(**output_mask);
    }
    if (node["switches"] && !simulated)
      return std::unexpected(yaml::error_at(node["switches"], where.key("switches"),
                                            "switches belong to a simulated node: a real drive reads its own switches "
                                            "into 0x60FD; leave `switches:` out"));
    auto axis = cia402::make_axis_config(*eds, ao);
    if (!axis) {
      // Point at the scenario key (eds:, or the override); the text names the EDS file.
      const char* key = node["rpdo"] ? "rpdo" : node["tpdo"] ? "tpdo" : "eds";
      return std::unexpected(yaml::error_at(node[key] ? node[key] : node, where.key(key),
                                            fmt::format("{}: {}", axis.error().file, axis.error().message)));
    }
    mocks::Cia402Node* sim = nullptr;
    if (simulated) {
      mocks::Cia402NodeOptions o;
      o.node = static_cast<canopen::NodeId>(nid);
      auto plant = [&](std::string_view key, double& out) -> std::expected<void, ConfigError> {
        auto v = yaml::get_double(node, where, key);
        if (!v) return std::unexpected(v.error());
        if (v->has_value()) {
          if (auto bad = mocks::plant_key_range(key)->check(**v); !bad.empty())
            return std::unexpected(yaml::error_at(node[std::string(key)], where.key(key), bad));
          out = **v;
        }
        return {};
      };
      for (auto r : {plant("kv", o.plant.kv_per_s), plant("max_velocity", o.plant.max_velocity_inc_per_s),
                     plant("velocity_lag", o.plant.velocity_lag_s), plant("feedforward", o.plant.velocity_feedforward)})
        if (!r) return std::unexpected(r.error());
      if (const auto sw = node["switches"]) {
        auto switches = mocks::parse_switches(sw, where.key("switches"));
        if (!switches) return std::unexpected(switches.error());
        o.switches = *switches;
      }
      can::ParticipantOptions po;
      po.filters = mocks::predefined_filters(static_cast<canopen::NodeId>(nid));  // like the node's CAN controller
      if (wanted.node_id != 0)
        po.filters.filters.push_back(can::Filter::exact(0x700u + wanted.node_id));  // the master's heartbeat
      o.eds_text = eds_text;  // the user's drive, rehearsed: its OD, PDO defaults and identity
      o.eds_name = eds_name;
      if (!eds_text.empty()) {
        if (auto check = mocks::load_node_eds(eds_text, eds_name, o.node); !check)
          return std::unexpected(yaml::error_at(node["eds"], where.key("eds"), check.error().describe()));
      }
      bus.node_channels.push_back(bus.vbus->attach(fmt::format("node{}", nid), po));
      bus.nodes.push_back(std::make_unique<mocks::Cia402Node>(*bus.node_channels.back(), o));
      sim = bus.nodes.back().get();
    }
    for (const auto& w : eds->warnings) bus.lines.push_back(fmt::format("node {}: EDS warning: {}", nid, w.describe()));
    for (const auto& d : axis->layout.decisions) bus.lines.push_back(fmt::format("node {}: {}", nid, d));
    bus.network->master().add_node(std::move(axis->node));
    cia402::DriveOptions dopt;
    dopt.layout = axis->layout;
    dopt.name = fmt::format("canopen:{}/{}", url, nid);
    dopt.homing = homing->value_or(true);
    dopt.setup = setup;
    if (gain->has_value()) dopt.csv_position_gain_per_s = **gain;
    auto drive = std::make_unique<cia402::Cia402Drive>(*bus.network, static_cast<canopen::NodeId>(nid), dopt);
    // The drive holds its bus (master, channels, node): it goes before them (ForwardingDrive).
    if (sim != nullptr)
      return std::make_unique<InProcessAxis>(std::move(drive), shared_bus, *sim, env.clock, *bus.vbus, wanted.node_id);
    return std::make_unique<ForwardingDrive>(std::move(drive), shared_bus);
  }

  /// Deliver everything due now. On real time the clock moves while handlers send, so repeat
  /// until the bus is quiet (bounded: every pass delivers at least one frame).
  void flush(Bus& bus) {
    if (bus.vbus == nullptr) return;
    for (int i = 0; i < 64 && bus.vbus->deliver(clock_->now()) > 0; ++i) {
    }
  }

  void begin_cycle(const CycleTime& cycle) override {
    for (auto& [name, shared_bus] : buses_) {
      Bus& bus = *shared_bus;
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
    for (auto& [name, shared_bus] : buses_) {
      Bus& bus = *shared_bus;
      for (auto& n : bus.nodes) n->step(cycle.now);
      flush(bus);
    }
  }

  TransportReport finish(const CycleTime&) override {
    TransportReport r;
    for (auto& [name, shared_bus] : buses_) {
      const Bus& bus = *shared_bus;
      auto& m = bus.network->master();
      int started = 0;
      for (auto id : m.nodes()) {
        const auto& st = m.status(id);
        if (st.boot == canopen::NodeBootState::started)
          ++started;
        else if (st.boot_error) {
          r.lines.push_back(
              fmt::format("canopen {}: node {} boot failed: {} {}", name, id, st.boot_error.message(), st.detail));
          r.ok = false;
        }
      }
      for (const auto& l : bus.lines) r.lines.push_back(fmt::format("canopen {}: {}", name, l));
      // What each simulated node's I/O shows at the end (0x60FD, and 0x60FE:1 through its 0x60FE:2 mask).
      for (const auto& n : bus.nodes) {
        const auto& od = n->od();
        if (od.find(0x60FD, 0) == nullptr && od.find(0x60FE, 1) == nullptr) continue;
        r.lines.push_back(fmt::format(
            "canopen {}: node {} (simulated) at the end: digital inputs 0x60FD = 0x{:08X}, outputs 0x60FE = 0x{:08X}",
            name, n->node_id(), static_cast<std::uint32_t>(od.get_int(0x60FD, 0)), n->digital_outputs()));
      }
      r.lines.push_back(fmt::format("canopen {}: {} of {} node(s) started{}, {} transmit error(s)", name, started,
                                    m.nodes().size(), bus.simulated ? " (simulated CiA 402 nodes)" : "",
                                    bus.network->stats().tx_errors));
    }
    return r;
  }

 private:
  /// The bus `url`, opened on first use; nullptr (bus_error_ says why) when it cannot be opened.
  std::shared_ptr<Bus> get_bus(const std::string& url, bool simulated, const BusMaster& master, RunEnvironment& env) {
    if (auto it = buses_.find(url); it != buses_.end()) return it->second;
    auto bus = std::make_shared<Bus>();
    bus->name = url;
    bus->simulated = simulated;
    bus->master = master;
    canopen::MasterOptions mo;
    mo.sync_period = env.period;
    mo.node_id = master.node_id;
    mo.heartbeat_period = master.heartbeat;
    mo.sdo.timeout = master.sdo_timeout;
    mo.sdo.retries = 1;
    mo.boot_timeout = std::chrono::seconds(1);
    clock_ = &env.clock;
    if (!registry_) registry_ = std::make_shared<can::VirtualBusRegistry>(env.clock);
    bus->registry = registry_;
    if (simulated) {
      auto parsed = can::parse_bus_url(url);
      bus->vbus = &registry_->get(parsed->name);
      bus->master_channel = bus->vbus->attach("master");
    } else {
      auto ch = can::make_channel(
          url, can::ChannelRequest{env.io->get_executor(), env.clock, registry_.get(), "hilbridge-master"});
      if (!ch) {
        bus_error_ = fmt::format("cannot open CAN bus '{}': {}", url, ch.error().message);
        return nullptr;
      }
      bus->master_channel = std::move(*ch);
    }
    bus->network = std::make_unique<cia402::Network>(*bus->master_channel, mo);
    buses_[url] = bus;
    return bus;
  }

  const Clock* clock_ = nullptr;
  std::shared_ptr<can::VirtualBusRegistry> registry_;  ///< shared with every Bus (their vbus)
  std::map<std::string, std::shared_ptr<Bus>> buses_;  ///< shared with the drives on each bus
  std::string bus_error_;
};

}  // namespace

std::unique_ptr<TransportFactory> make_canopen_transport() {
  return std::make_unique<CanopenTransport>();
}

}  // namespace hil::cia402
