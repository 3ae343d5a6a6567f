// SPDX-License-Identifier: MIT
#include "hil/modbus/register_table.hpp"

namespace hil::modbus {

RegisterTable::RegisterTable() {
  for (Bank* b : {&holding_, &input_}) {
    b->values.assign(65536, 0);
    b->access.assign(65536, static_cast<std::uint8_t>(Access::absent));
  }
  for (BitBank* b : {&coils_, &inputs_}) {
    b->values.assign(65536, 0);
    b->access.assign(65536, static_cast<std::uint8_t>(Access::absent));
  }
}

void RegisterTable::define(BitSpace space, std::uint16_t first, std::uint16_t count, Access access) {
  BitBank& b = bits(space);
  for (std::uint32_t a = first; a < std::uint32_t{first} + count && a < 65536; ++a) {
    const bool was = b.access[a] != static_cast<std::uint8_t>(Access::absent);
    const bool is = access != Access::absent;
    if (was != is) b.defined = is ? b.defined + 1 : b.defined - 1;
    b.access[a] = static_cast<std::uint8_t>(access);
  }
}

bool RegisterTable::range_ok(BitSpace space, std::uint16_t first, std::uint16_t count, bool need_write) const noexcept {
  const BitBank& b = bits(space);
  if (std::uint32_t{first} + count > 65536) return false;
  for (std::uint32_t a = first; a < std::uint32_t{first} + count; ++a) {
    const auto acc = static_cast<Access>(b.access[a]);
    if (acc == Access::absent) return false;
    if (need_write && acc != Access::read_write) return false;
  }
  return true;
}

void RegisterTable::define(RegisterSpace space, std::uint16_t first, std::uint16_t count, Access access) {
  Bank& b = bank(space);
  for (std::uint32_t a = first; a < std::uint32_t{first} + count && a < 65536; ++a)
    b.access[a] = static_cast<std::uint8_t>(access);
}

bool RegisterTable::range_ok(RegisterSpace space, std::uint16_t first, std::uint16_t count,
                             bool need_write) const noexcept {
  const Bank& b = bank(space);
  if (std::uint32_t{first} + count > 65536) return false;
  for (std::uint32_t a = first; a < std::uint32_t{first} + count; ++a) {
    const auto acc = static_cast<Access>(b.access[a]);
    if (acc == Access::absent) return false;
    if (need_write && acc != Access::read_write) return false;
  }
  return true;
}

}  // namespace hil::modbus
