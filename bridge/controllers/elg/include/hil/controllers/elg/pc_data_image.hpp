// SPDX-License-Identifier: MIT
// The ELG's own data as the PC data channel sees it (12.5), around a running Gearbox:
// R0..R99 (R20 Z0, R21 Z2, R40 TOLER, R60 TANG, R61 AXIAL reach the gearbox, 5.1), MD and SD as
// tape text (the store the V.24 interface reads and punches), the actual values of the declared
// axes, the pending alarms, and service datum 8000 (C's following error).
//
// Decisions (docs/elg.md, "PC data channel"): R20/R21/R60/R61 written while coupled are kept and
// reach the gearbox at Gearing OFF (the gearbox refuses input parameters while coupled); an R40
// below MD 169 is kept as R40 but not accepted as the limit (5.2); service data 8001/8002 (DAC
// speed value, adaptive precontrol) are not modelled and answer 3018.
#pragma once

#include <array>
#include <functional>
#include <map>

#include "hil/controllers/elg/gearbox.hpp"
#include "hil/controllers/elg/pc_data_target.hpp"

namespace hil::controllers::elg {

/// Checks an MD/SD value (tape text) against the device profile: empty = valid, else the reason.
using DatumCheck = std::function<std::optional<std::string>(DatumKind kind, int number, const std::string& value)>;

struct ElgAxisDeclaration {
  /// Axis numbers 1..4 of B, C, Z, Y (MD 5020/5021; 0 = none).
  int b = 1, c = 2, z = 3, y = 0;
};

class PcDataImage final : public PcDataTarget {
 public:
  /// `md`/`sd`: the MD and SD store (number -> tape text), owned by the caller; `check` validates
  /// a written value (may be empty: everything valid). Thread: the caller's (the ELG cycle).
  PcDataImage(Gearbox& gearbox, std::map<int, std::string>& md, std::map<int, std::string>& sd, DatumCheck check,
              ElgAxisDeclaration axes = {});

  /// Once per ELG cycle after Gearbox::step: the axes' actual values (counts) and the input
  /// parameters still waiting for Gearing OFF.
  void update(const AxisFeedback& axes);

  /// One request of the PC; raises 3016/3018 on the gearbox's alarm list as the manual's
  /// "message only" when it is refused.
  PcReply request(const PcRequest& request);

  // PcDataTarget
  [[nodiscard]] bool coupled() const override { return gearbox_.status().coupled; }
  [[nodiscard]] std::optional<std::string> datum(DatumKind kind, int number) const override;
  std::expected<void, std::string> store_datum(DatumKind kind, int number, const std::string& value) override;
  [[nodiscard]] std::optional<PcValue> r_parameter(int number) const override;
  std::expected<void, std::string> store_r_parameter(int number, const PcValue& value) override;
  [[nodiscard]] std::optional<PcValue> actual_value(int axis) const override;
  [[nodiscard]] std::vector<int> alarms() const override;
  [[nodiscard]] std::optional<PcValue> service_datum(int number) const override;

 private:
  void push_input();

  Gearbox& gearbox_;
  std::map<int, std::string>& md_;
  std::map<int, std::string>& sd_;
  DatumCheck check_;
  ElgAxisDeclaration declaration_;
  std::array<PcValue, 100> r_{};
  AxisFeedback axes_{};
  bool input_pending_ = false;
};

}  // namespace hil::controllers::elg
