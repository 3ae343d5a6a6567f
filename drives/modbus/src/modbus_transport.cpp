// SPDX-License-Identifier: MIT
#include "hil/drives/modbus_transport.hpp"

#include <charconv>
#include <filesystem>
#include <vector>

#include <fmt/format.h>

#include "hil/config/yaml_config.hpp"
#include "hil/core/data_dir.hpp"
#include "hil/core/fault_injection.hpp"
#include "hil/core/forwarding_drive.hpp"
#include "hil/drives/modbus_drive.hpp"
#include "hil/mocks/modbus_server.hpp"
#include "hil/mocks/sim_drive.hpp"
#include "hil/modbus/profile.hpp"

namespace hil::drives {
namespace {

namespace fs = std::filesystem;

// An axis whose far end is our in-process server: the Modbus drive plus fault injection into
// the server (plant faults and link faults). Motion thread only. It shares the server with the
// factory (which steps it): the drive and its worker go first, then the server (ForwardingDrive).
class InProcessModbusDrive final : public ForwardingDrive, public FaultInjectable {
 public:
  InProcessModbusDrive(std::unique_ptr<ModbusDrive> drive, std::shared_ptr<mocks::ModbusDriveServer> server)
      : ForwardingDrive(std::move(drive), server), server_(*server) {}

  [[nodiscard]] std::vector<std::string> injectable_faults() const override {
    return {"encoder", "not_ready", "following_blowup", "server_down", "slow_response", "busy"};
  }
  bool inject_fault(std::string_view fault, bool active) override {
    if (fault == "encoder")
      server_.inject(PlantFault::encoder, active);
    else if (fault == "not_ready")
      server_.inject(PlantFault::not_ready, active);
    else if (fault == "following_blowup")
      server_.inject(PlantFault::following_blowup, active);
    else if (fault == "server_down") {
      if (active)
        server_.stop();
      else if (auto ec = server_.start())
        return false;
    } else if (fault == "slow_response") {
      server_.set_response_delay(active ? 3 * timeout_ : Duration{});
    } else if (fault == "busy") {
      server_.fail_next(active ? 0xFFFFFFFFu : 0, modbus::ModbusError::server_device_busy);
    } else {
      return false;
    }
    return true;
  }
  void set_timeout(Duration t) { timeout_ = t; }
  ModbusDrive& drive() { return static_cast<ModbusDrive&>(inner()); }

 private:
  mocks::ModbusDriveServer& server_;
  Duration timeout_{std::chrono::milliseconds(100)};
};

// Teardown by ownership (docs/ARCHITECTURE.md, "Teardown"): each in-process server is shared by
// the factory and its drive and stops in its destructor, after the drive's worker has gone; the
// factory's pointers to its drives are for the cycle work only and never used in its destructor.
class ModbusTransport final : public TransportFactory {
 public:
  std::expected<DrivePtr, ConfigError> make_drive(const std::string& axis_name, const YAML::Node& node,
                                                  RunEnvironment& env) override {
    const yaml::Where where{env.source_file, env.drive_path(axis_name)};
    if (auto k = yaml::check_keys(node, where,
                                  {"transport", "profile", "host", "port", "unit", "response_timeout", "poll_period",
                                   "backoff_min", "backoff_max", "homing_timeout", "plant"});
        !k)
      return std::unexpected(k.error());
    auto profile_name = yaml::get_string(node, where, "profile");
    if (!profile_name) return std::unexpected(profile_name.error());
    if (!profile_name->has_value())
      return std::unexpected(yaml::error_at(node, where.key("profile"),
                                            "missing: the register profile (e.g. cia402, vendor_simple, or a path)"));
    const std::string scenario_dir = env.source_file.empty() ? "." : fs::path(env.source_file).parent_path().string();
    const std::string path = resolve_modbus_profile(**profile_name, scenario_dir);
    auto profile = modbus::load_profile(path);
    if (!profile) {
      ConfigError e = profile.error();
      e.message += fmt::format(" (profile '{}' of {})", **profile_name, where.path);
      return std::unexpected(e);
    }
    ModbusDriveConfig config;
    config.name = axis_name;
    config.profile = std::move(*profile);
    config.lockstep = env.virtual_time;
    auto seconds = [&](std::string_view key, Duration& out) -> std::expected<void, ConfigError> {
      auto v = yaml::get_double(node, where, key);
      if (!v) return std::unexpected(v.error());
      if (!v->has_value()) return {};
      if (!(**v > 0.0) || **v > 3600.0)
        return std::unexpected(
            yaml::error_at(node[std::string(key)], where.key(key), fmt::format("expected seconds > 0, got {}", **v)));
      out = from_seconds(**v);
      return {};
    };
    for (auto r : {seconds("response_timeout", config.response_timeout), seconds("poll_period", config.poll_period),
                   seconds("backoff_min", config.backoff_min), seconds("backoff_max", config.backoff_max),
                   seconds("homing_timeout", config.homing_timeout)})
      if (!r) return std::unexpected(r.error());
    if (config.backoff_min > config.backoff_max) {
      const char* key = node["backoff_max"] ? "backoff_max" : "backoff_min";
      return std::unexpected(yaml::error_at(
          node[key], where.key(key),
          fmt::format("backoff_min {} s is longer than backoff_max {} s: the reconnect back-off grows from min to max",
                      to_seconds(config.backoff_min), to_seconds(config.backoff_max))));
    }
    auto unit = yaml::get_int(node, where, "unit");
    if (!unit) return std::unexpected(unit.error());
    if (unit->has_value()) {
      if (**unit < 0 || **unit > 255)
        return std::unexpected(yaml::error_at(node["unit"], where.key("unit"), "expected a unit id 0..255"));
      config.unit_id = static_cast<int>(**unit);
    }
    auto host = yaml::get_string(node, where, "host");
    if (!host) return std::unexpected(host.error());
    auto port = yaml::get_int(node, where, "port");
    if (!port) return std::unexpected(port.error());

    if (host->has_value()) {
      if (node["plant"])
        return std::unexpected(
            yaml::error_at(node["plant"], where.key("plant"),
                           "plant: configures the in-process simulated drive; remove it or remove host:"));
      std::string h = **host;
      long long p = port->value_or(modbus::kDefaultPort);
      if (auto colon = h.rfind(':'); colon != std::string::npos && h.find(':') == colon) {
        const std::string digits = h.substr(colon + 1);
        const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), p);
        if (ec != std::errc{} || end != digits.data() + digits.size())
          return std::unexpected(yaml::error_at(node["host"], where.key("host"), "expected HOST or HOST:PORT"));
        h = h.substr(0, colon);
      }
      if (p < 1 || p > 65535)
        return std::unexpected(yaml::error_at(node["host"], where.key("host"), "port must be 1..65535"));
      config.host = h;
      config.port = static_cast<std::uint16_t>(p);
      auto drive = std::make_unique<ModbusDrive>(std::move(config), env.clock);
      drives_.push_back(drive.get());
      return drive;
    }

    // In-process simulated drive server on an ephemeral loopback port.
    auto plant = mocks::parse_sim_drive_config(node["plant"], where.key("plant"));
    if (!plant) return std::unexpected(plant.error());
    mocks::DriveDeviceConfig device_config;
    device_config.plant = plant->plant;
    device_config.quick_stop_deceleration_inc_per_s2 = plant->quick_stop_deceleration_inc_per_s2;
    mocks::ModbusServerConfig server_config;
    server_config.handler.unit_id = config.profile.unit_id;
    auto server =
        std::make_shared<mocks::ModbusDriveServer>(mocks::DriveDevice(config.profile, device_config), server_config);
    if (auto ec = server->start())
      return std::unexpected(yaml::error_at(
          node, where, fmt::format("cannot start the in-process Modbus drive server: {}", ec.message())));
    config.host = "127.0.0.1";
    config.port = server->port();
    const Duration timeout = config.response_timeout;
    auto drive =
        std::make_unique<InProcessModbusDrive>(std::make_unique<ModbusDrive>(std::move(config), env.clock), server);
    drive->set_timeout(timeout);
    drives_.push_back(&drive->drive());
    servers_.push_back(std::move(server));
    return drive;
  }

  void begin_cycle(const CycleTime& cycle) override {
    const Duration dt = started_ ? cycle.now - last_ : cycle.period;
    started_ = true;
    last_ = cycle.now;
    if (dt.count() > 0)
      for (auto& s : servers_) s->step(dt);
    // Lockstep (virtual time): all drives exchange in parallel, then the axes read. No-op otherwise.
    for (ModbusDrive* d : drives_) d->exchange_start(cycle.now);
    for (ModbusDrive* d : drives_) d->exchange_wait();
  }

  TransportReport finish(const CycleTime&) override {
    TransportReport report;
    for (ModbusDrive* d : drives_) {
      const auto s = d->link_stats();
      report.lines.push_back(fmt::format("{}: {} exchanges, {} errors, {} connects{}", d->name(), s.exchanges, s.errors,
                                         s.connects,
                                         s.last_error == modbus::ModbusError::none
                                             ? std::string{}
                                             : ", last error: " + modbus::make_error_code(s.last_error).message()));
    }
    return report;
  }

 private:
  std::vector<std::shared_ptr<mocks::ModbusDriveServer>> servers_;  // shared with their drives
  std::vector<ModbusDrive*> drives_;                                // owned by the run's axes; begin_cycle/finish only
  bool started_ = false;
  TimePoint last_{};
};

}  // namespace

std::string default_modbus_profile_dir() {
  return hil::find_data_dir("profiles/modbus").string();
}

std::string resolve_modbus_profile(const std::string& name_or_path, const std::string& scenario_dir) {
  std::error_code ec;
  const fs::path given(name_or_path);
  if (given.is_absolute()) return name_or_path;
  if (const auto rel = fs::path(scenario_dir) / given; fs::is_regular_file(rel, ec)) return rel.string();
  if (fs::is_regular_file(given, ec)) return given.string();
  const fs::path by_name = fs::path(default_modbus_profile_dir()) / (name_or_path + ".yaml");
  if (fs::is_regular_file(by_name, ec)) return by_name.string();
  return (fs::path(scenario_dir) / given).string();  // load_profile reports "cannot open"
}

std::unique_ptr<TransportFactory> make_modbus_transport() {
  return std::make_unique<ModbusTransport>();
}

}  // namespace hil::drives
