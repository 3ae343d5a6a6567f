// SPDX-License-Identifier: MIT
#pragma once
// Which requests one cyclic exchange makes for a profile: the command fields grouped into
// contiguous holding-register blocks (one FC 16 each, or one FC 6 per register), the feedback
// fields into contiguous blocks (FC 3 or FC 4), or a single FC 23 when the profile asks for it.
// Gaps are never bridged: a real drive may answer exception 02 for a register between fields.

#include <cstdint>
#include <expected>
#include <string>
#include <vector>

#include "hil/modbus/adu.hpp"
#include "hil/modbus/profile.hpp"

namespace hil::modbus {

struct RegisterBlock {
  RegisterSpace space = RegisterSpace::holding;
  std::uint16_t first = 0;
  std::uint16_t count = 0;
};

struct ExchangePlan {
  std::vector<RegisterBlock> writes;  ///< holding-register blocks, in address order
  std::vector<RegisterBlock> reads;   ///< feedback blocks, in address order
  std::uint8_t write_fc = 16;         ///< 6 or 16
  std::uint8_t read_fc = 3;           ///< 3 or 4
  bool read_write = false;            ///< one FC 23 (writes[0], reads[0]) per exchange
  [[nodiscard]] std::size_t requests_per_exchange() const noexcept {
    return read_write ? 1 : writes.size() + reads.size();
  }
};

/// Pure. Errors say why (e.g. "FC 23 needs the command fields in one contiguous block").
[[nodiscard]] std::expected<ExchangePlan, std::string> make_exchange_plan(const Profile& profile);

}  // namespace hil::modbus
