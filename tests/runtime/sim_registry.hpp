// SPDX-License-Identifier: MIT
#pragma once
// Test helpers: a TransportRegistry with the real `sim` transport (hil::mocks::make_sim_transport,
// the one the CLI registers), and a transport that logs the cycle order.
#include <memory>
#include <string>
#include <vector>

#include "hil/core/forwarding_drive.hpp"
#include "hil/core/transport.hpp"
#include "hil/mocks/sim_drive.hpp"
#include "hil/mocks/sim_transport.hpp"

namespace hil::testing {

/// Wraps a SimDrive and logs read/write, so tests see the order of a cycle.
class LoggingDrive final : public ForwardingDrive, public FaultInjectable {
 public:
  LoggingDrive(DrivePtr inner, std::string axis, std::vector<std::string>& log)
      : ForwardingDrive(std::move(inner)), axis_(std::move(axis)), log_(log) {}
  void read(const CycleTime& c) override {
    log_.push_back("read " + axis_);
    ForwardingDrive::read(c);
  }
  void write(const CycleTime& c, const DriveCommand& cmd) override {
    log_.push_back("write " + axis_);
    ForwardingDrive::write(c, cmd);
  }
  std::vector<std::string> injectable_faults() const override { return inner_faults()->injectable_faults(); }
  bool inject_fault(std::string_view n, bool a) override { return inner_faults()->inject_fault(n, a); }

 private:
  std::string axis_;
  std::vector<std::string>& log_;
};

class LoggingFactory final : public TransportFactory {
 public:
  explicit LoggingFactory(std::vector<std::string>& log, bool report_ok = true) : log_(log), report_ok_(report_ok) {}
  std::expected<DrivePtr, ConfigError> make_drive(const std::string& axis, const YAML::Node& node,
                                                  RunEnvironment& env) override {
    YAML::Node plain = YAML::Clone(node);
    plain.remove("transport");
    plain["transport"] = "sim";
    auto d = mocks::make_sim_transport()->make_drive(axis, plain, env);
    if (!d) return d;
    return std::make_unique<LoggingDrive>(std::move(*d), axis, log_);
  }
  void begin_cycle(const CycleTime&) override { log_.push_back("begin"); }
  void end_cycle(const CycleTime&) override { log_.push_back("end"); }
  TransportReport finish(const CycleTime&) override {
    log_.push_back("finish");
    return TransportReport{{"logged " + std::to_string(log_.size()) + " events"}, report_ok_};
  }

 private:
  std::vector<std::string>& log_;
  bool report_ok_;
};

inline TransportRegistry sim_registry() {
  TransportRegistry r;
  r.add("sim", [] { return mocks::make_sim_transport(); });
  return r;
}

}  // namespace hil::testing
