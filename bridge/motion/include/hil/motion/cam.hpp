// SPDX-License-Identifier: MIT
#pragma once
// Cam coupling: slave = base + cam(master - origin), with table switching. Pure, clock-free.
//
// u = master - origin (master increments or time units, see master.hpp).
//   periodic table:     k = floor(u / X), r = u - kX,  slave = base + k*Y + y(r)   (exact k*Y)
//   non-periodic table: slave = base + y(clamp(u, 0, X))   (held at the ends)
// A distance-time cam is the same with a TimeMaster.
//
// Switching tables (CamSwitch) happens at the current table's end (a period boundary or the
// end of a non-periodic table, in the direction of travel) or when the master reaches a given
// position. At the switch the new table starts at x = 0 and the slave continues from where it
// is (base := slave at the switch point, origin := switch point): a switch is continuous in
// position; it is continuous in velocity when the two tables' slopes match there
// (check_switch() tells).

#include <cstdint>
#include <optional>

#include "hil/motion/cam_table.hpp"

namespace hil::motion {

struct CamSwitch {
  const CamTable* table = nullptr;            ///< must outlive its use; nullptr = stop the cam (hold the slave)
  std::optional<std::int64_t> at_master_inc;  ///< switch when the master reaches this; else at the table end
};

class CamCoupling {
 public:
  /// `table` must outlive the coupling (or until switched away from).
  explicit CamCoupling(const CamTable* table = nullptr) noexcept : table_(table) {}

  /// Start the cam: the master is at `master_inc` now, which is table position `phase`
  /// (the SF "master offset angle"). `absolute` = false: the slave continues from `slave_inc`
  /// (no jump; base = slave - y(phase)); true: the slave is put where the table says
  /// (base = slave_inc, the SF "setting on"), so y(phase) appears at the first update.
  void start(std::int64_t master_inc, double slave_inc, std::int64_t phase = 0, bool absolute = false) noexcept;
  /// Queue a switch (replaces one not yet done).
  void queue(const CamSwitch& s) noexcept { pending_ = s; }
  void set_table(const CamTable* table) noexcept { table_ = table; }

  /// One cycle: new master position; returns the slave position (increments, fractional).
  double update(std::int64_t master_inc) noexcept;

  [[nodiscard]] double slave_position() const noexcept { return slave_; }
  /// dslave/dmaster and d2slave/dmaster2 at the current position.
  [[nodiscard]] double slope() const noexcept { return sample_.dy; }
  [[nodiscard]] double curvature() const noexcept { return sample_.d2y; }
  /// Table position x in [0, X] and the number of whole periods since the origin.
  [[nodiscard]] double table_position() const noexcept { return x_; }
  [[nodiscard]] std::int64_t periods() const noexcept { return k_; }
  [[nodiscard]] const CamTable* table() const noexcept { return table_; }
  [[nodiscard]] bool switch_pending() const noexcept { return pending_.has_value(); }
  [[nodiscard]] std::int64_t switches() const noexcept { return switches_; }  ///< done since start

 private:
  void evaluate(std::int64_t master_inc) noexcept;
  void switch_at(std::int64_t master_inc) noexcept;

  const CamTable* table_;
  std::optional<CamSwitch> pending_;
  std::int64_t origin_ = 0;
  std::int64_t master_ = 0;
  std::int64_t base_whole_ = 0;  ///< base = base_whole_ + base_frac_
  double base_frac_ = 0.0;
  std::int64_t k_ = 0;
  double x_ = 0.0;
  double slave_ = 0.0;
  CamSample sample_{};
  std::size_t hint_ = 0;
  std::int64_t switches_ = 0;
};

/// Velocity continuity of a switch from `from` (at its end) to `to` (at its start): |slope
/// difference| <= tolerance (slave increments per master increment).
[[nodiscard]] bool check_switch(const CamTable& from, const CamTable& to, double tolerance = 1e-9) noexcept;

}  // namespace hil::motion
