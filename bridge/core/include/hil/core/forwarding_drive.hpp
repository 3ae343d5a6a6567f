// SPDX-License-Identifier: MIT
#pragma once
// The one forwarding Drive. A drive that adds something to another drive (fault injection into
// its in-process far end, a log of the cycle order) derives from it and overrides only what it
// adds; every other call goes to the inner drive unchanged.
//
// It also carries the transports' teardown rule (docs/ARCHITECTURE.md, "Teardown"): `needs` is
// what the inner drive refers to (its bus and master, its in-process server, its lines), shared
// with the factory that built it. The inner drive is destroyed first, then `needs` is released,
// so a drive never outlives what it uses, whatever order a run destroys its axes and factories in.

#include <memory>
#include <string_view>
#include <utility>

#include "hil/core/drive.hpp"
#include "hil/core/fault_injection.hpp"

namespace hil {

class ForwardingDrive : public Drive {
 public:
  /// `inner` must not be null. `needs` (may be empty) is released only after `inner` is destroyed.
  explicit ForwardingDrive(DrivePtr inner, std::shared_ptr<void> needs = {}) noexcept
      : needs_(std::move(needs)), inner_(std::move(inner)) {}
  ~ForwardingDrive() override { inner_.reset(); }  // the drive first, then what it uses (needs_)
  ForwardingDrive(const ForwardingDrive&) = delete;
  ForwardingDrive& operator=(const ForwardingDrive&) = delete;

  [[nodiscard]] std::string_view name() const noexcept override { return inner_->name(); }
  [[nodiscard]] DriveCapabilities capabilities() const noexcept override { return inner_->capabilities(); }
  void read(const CycleTime& cycle) override { inner_->read(cycle); }
  void write(const CycleTime& cycle, const DriveCommand& command) override { inner_->write(cycle, command); }
  [[nodiscard]] const DriveFeedback& feedback() const noexcept override { return inner_->feedback(); }
  bool request(DriveRequest r) override { return inner_->request(r); }

 protected:
  [[nodiscard]] Drive& inner() noexcept { return *inner_; }
  [[nodiscard]] const Drive& inner() const noexcept { return *inner_; }
  /// The inner drive's fault injection, or nullptr: for a wrapper that passes faults on.
  [[nodiscard]] FaultInjectable* inner_faults() const noexcept { return dynamic_cast<FaultInjectable*>(inner_.get()); }

 private:
  std::shared_ptr<void> needs_;  ///< released after inner_ (see the destructor)
  DrivePtr inner_;
};

}  // namespace hil
