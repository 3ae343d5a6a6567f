// SPDX-License-Identifier: MIT
#include "hil/modbus/bit_plan.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "hil/modbus/adu.hpp"

namespace hil::modbus {

std::string_view to_string(BitSpace space) noexcept {
  return space == BitSpace::coil ? "coil" : "discrete_input";
}

std::expected<BitPlan, std::string> make_bit_plan(std::span<const BitRef> bits, bool writes) {
  const auto key = [](const BitRef& b) {
    return (std::uint32_t{static_cast<std::uint8_t>(b.space)} << 16) | b.address;
  };
  std::vector<std::uint32_t> keys;
  keys.reserve(bits.size());
  for (const auto& b : bits) {
    if (writes && b.space != BitSpace::coil)
      return std::unexpected(fmt::format("discrete input {} cannot be written (only coils are outputs)", b.address));
    keys.push_back(key(b));
  }
  std::ranges::sort(keys);
  if (writes) {
    if (const auto dup = std::ranges::adjacent_find(keys); dup != keys.end())
      return std::unexpected(fmt::format("coil {} is written twice", *dup & 0xFFFF));
  }
  const auto [first_dup, last_dup] = std::ranges::unique(keys);
  keys.erase(first_dup, last_dup);

  const std::uint16_t limit = writes ? kMaxWriteBits : kMaxReadBits;
  BitPlan plan;
  for (const std::uint32_t k : keys) {
    const auto space = static_cast<BitSpace>(k >> 16);
    const auto address = static_cast<std::uint16_t>(k & 0xFFFF);
    if (!plan.blocks.empty()) {
      auto& last = plan.blocks.back();
      if (last.space == space && std::uint32_t{last.first} + last.count == address && last.count < limit) {
        ++last.count;
        continue;
      }
    }
    plan.blocks.push_back({space, address, 1});
  }
  std::vector<std::size_t> base(plan.blocks.size());
  for (std::size_t i = 0; i < plan.blocks.size(); ++i) {
    base[i] = plan.bits;
    plan.bits += plan.blocks[i].count;
  }
  plan.slots.reserve(bits.size());
  for (const auto& b : bits) {
    for (std::size_t i = 0; i < plan.blocks.size(); ++i) {
      const auto& blk = plan.blocks[i];
      if (blk.space == b.space && b.address >= blk.first && b.address < std::uint32_t{blk.first} + blk.count) {
        plan.slots.push_back(base[i] + (b.address - blk.first));
        break;
      }
    }
  }
  return plan;
}

}  // namespace hil::modbus
