// SPDX-License-Identifier: MIT
// Coupling step 3: the cam coupling (periodic continuation, table switching). See cam.hpp.
#include "hil/motion/cam.hpp"

#include <cmath>

#include "hil/motion/gear_ratio.hpp"

namespace hil::motion {

void CamCoupling::start(std::int64_t master_inc, double slave_inc, std::int64_t phase, bool absolute) noexcept {
  master_ = master_inc;
  origin_ = master_inc - phase;
  const double y = (table_ && !absolute) ? table_->value(static_cast<double>(phase)) : 0.0;
  const double base = slave_inc - y;
  base_whole_ = static_cast<std::int64_t>(std::floor(base));
  base_frac_ = base - static_cast<double>(base_whole_);
  pending_.reset();
  switches_ = 0;
  hint_ = 0;
  evaluate(master_inc);
  if (!absolute) slave_ = slave_inc;  // exactly where it was
}

void CamCoupling::evaluate(std::int64_t m) noexcept {
  master_ = m;
  if (!table_) {
    slave_ = static_cast<double>(base_whole_) + base_frac_;
    sample_ = {};
    return;
  }
  const std::int64_t u = m - origin_;
  if (table_->periodic()) {
    const auto len = static_cast<std::int64_t>(table_->length());
    k_ = floor_div(u, len);
    const std::int64_t r = u - k_ * len;
    x_ = static_cast<double>(r);
    sample_ = table_->sample(x_, hint_);
    const auto lift = static_cast<std::int64_t>(table_->lift());
    slave_ = static_cast<double>(base_whole_ + k_ * lift) + (base_frac_ + sample_.y);
  } else {
    k_ = 0;
    x_ = static_cast<double>(u);
    sample_ = table_->sample(x_, hint_);
    x_ = x_ < 0 ? 0.0 : (x_ > table_->length() ? table_->length() : x_);
    slave_ = static_cast<double>(base_whole_) + (base_frac_ + sample_.y);
  }
}

void CamCoupling::switch_at(std::int64_t p) noexcept {
  evaluate(p);  // the slave at the switch point, on the old table
  const double base = slave_;
  base_whole_ = static_cast<std::int64_t>(std::floor(base));
  base_frac_ = base - static_cast<double>(base_whole_);
  // Whole-increment bases stay exact (a periodic table ends on whole increments).
  if (base_frac_ < 1e-9) base_frac_ = 0.0;
  if (base_frac_ > 1.0 - 1e-9) {
    base_frac_ = 0.0;
    ++base_whole_;
  }
  origin_ = p;
  table_ = pending_->table;
  pending_.reset();
  hint_ = 0;
  ++switches_;
}

double CamCoupling::update(std::int64_t m) noexcept {
  if (pending_ && table_) {
    const std::int64_t before = master_;
    std::optional<std::int64_t> p;
    if (pending_->at_master_inc) {
      const std::int64_t a = *pending_->at_master_inc;
      if (before == a || (before < a && m >= a) || (before > a && m <= a)) p = a;
    } else {
      // The current table's end in the direction of travel.
      const auto len = static_cast<std::int64_t>(table_->length());
      const std::int64_t u0 = before - origin_, u1 = m - origin_;
      if (table_->periodic()) {
        const std::int64_t k0 = floor_div(u0, len), k1 = floor_div(u1, len);
        if (k1 > k0)
          p = origin_ + (k0 + 1) * len;
        else if (k1 < k0 || (u1 < u0 && u1 - k1 * len == 0))
          p = origin_ + k0 * len;
      } else if ((u0 < len && u1 >= len) || u0 == len) {
        p = origin_ + len;
      }
    }
    if (p) switch_at(*p);
  } else if (pending_ && !table_) {
    // Starting from a held slave: at once (from the last master position) or at a position.
    const std::int64_t before = master_;
    std::optional<std::int64_t> p;
    if (!pending_->at_master_inc) {
      p = before;
    } else if (const std::int64_t a = *pending_->at_master_inc;
               before == a || (before < a && m >= a) || (before > a && m <= a)) {
      p = a;
    }
    if (p) {
      table_ = pending_->table;
      origin_ = *p;
      pending_.reset();
      hint_ = 0;
      ++switches_;
    }
  }
  evaluate(m);
  return slave_;
}

bool check_switch(const CamTable& from, const CamTable& to, double tolerance) noexcept {
  std::size_t h1 = 0, h2 = 0;
  // The slope just inside each table (sample() gives 0 outside).
  const double end = from.sample(from.length(), h1).dy;
  const double start = to.sample(0.0, h2).dy;
  return std::fabs(end - start) <= tolerance;
}

}  // namespace hil::motion
