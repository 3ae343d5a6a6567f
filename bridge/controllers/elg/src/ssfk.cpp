// SPDX-License-Identifier: MIT
#include "hil/controllers/elg/ssfk.hpp"

#include <algorithm>

namespace hil::controllers::elg {

Ssfk::Ssfk(const SsfkData& data) : data_(data) {
  active_ = data_.active && data_.distance > 0;
  plus_ = prefix(data_.pointer_plus);
  minus_ = data_.direction_dependent ? prefix(data_.pointer_minus) : plus_;
}

int Ssfk::point(int k) const noexcept {
  if (k < 1 || k > 1000) return 0;
  const auto byte = data_.flags[static_cast<std::size_t>((k - 1) / 4)];
  const int pair = (k - 1) % 4;
  if ((byte >> (2 * pair)) & 1) return 0;  // "no"
  return (byte >> (2 * pair + 1)) & 1 ? 1 : -1;
}

std::vector<std::int64_t> Ssfk::prefix(std::int64_t pointer) const {
  int first = 0;
  if (pointer == 0)
    first = 1;
  else if (pointer >= 1 && pointer <= 1000)
    first = static_cast<int>(pointer);
  else if (pointer >= 6000 && pointer <= 6249)
    first = static_cast<int>(pointer - 6000) * 4 + 1;
  std::vector<std::int64_t> sums{0};
  if (first == 0) return sums;  // no table for this direction
  for (int k = first; k <= 1000; ++k) sums.push_back(sums.back() + point(k));
  return sums;
}

std::int64_t Ssfk::compensation(std::int64_t from_reference, int direction) const noexcept {
  if (!active_) return 0;
  std::int64_t p = from_reference;
  if (data_.revolution > 0) {
    p %= data_.revolution;
    if (p < 0) p += data_.revolution;
  }
  const auto& sums = direction < 0 ? minus_ : plus_;
  const auto passed =
      static_cast<std::size_t>(std::min<std::int64_t>(p / data_.distance, static_cast<std::int64_t>(sums.size()) - 1));
  return sums[passed] * data_.step;
}

}  // namespace hil::controllers::elg
