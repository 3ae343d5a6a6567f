// SPDX-License-Identifier: MIT
#pragma once
// The server's data model, the four tables of the Modbus data model (MB spec §4.3): holding
// registers (FC 3/6/16/22/23), input registers (FC 4), coils (FC 1/5/15) and discrete inputs
// (FC 2), each entry either absent, read-only or read-write. Absent entries answer exception 02;
// writes to read-only entries answer exception 02 as well (the address is not writable; see
// docs/modbus.md for why 02 and not 04). A device without any coil (discrete input) answers 01
// to their function codes: it does not have the table. Bits are stored one byte each (0/1), the
// layout of libmodbus' modbus_mapping_t. Plain data, not thread-safe: the server serialises access.

#include <cstdint>
#include <span>
#include <vector>

namespace hil::modbus {

enum class RegisterSpace : std::uint8_t { holding, input };
enum class BitSpace : std::uint8_t { coil, discrete_input };
enum class Access : std::uint8_t { absent = 0, read_only = 1, read_write = 2 };

class RegisterTable {
 public:
  RegisterTable();

  /// Define `count` registers from `first` (overwrites earlier definitions). Values start at 0.
  void define(RegisterSpace space, std::uint16_t first, std::uint16_t count, Access access);

  [[nodiscard]] Access access(RegisterSpace space, std::uint16_t address) const noexcept {
    return static_cast<Access>(bank(space).access[address]);
  }
  /// True when every register of [first, first+count) is present (and writable if asked).
  [[nodiscard]] bool range_ok(RegisterSpace space, std::uint16_t first, std::uint16_t count,
                              bool need_write) const noexcept;

  [[nodiscard]] std::uint16_t get(RegisterSpace space, std::uint16_t address) const noexcept {
    return bank(space).values[address];
  }
  /// Set a value regardless of access (the device model updates read-only registers this way).
  void set(RegisterSpace space, std::uint16_t address, std::uint16_t value) noexcept {
    bank(space).values[address] = value;
  }
  [[nodiscard]] std::span<const std::uint16_t> values(RegisterSpace space) const noexcept { return bank(space).values; }
  [[nodiscard]] std::span<std::uint16_t> values(RegisterSpace space) noexcept { return bank(space).values; }

  // --- bits: coils and discrete inputs ---------------------------------------------------
  /// Define `count` bits from `first` (overwrites earlier definitions). Values start at 0.
  void define(BitSpace space, std::uint16_t first, std::uint16_t count, Access access);
  [[nodiscard]] Access access(BitSpace space, std::uint16_t address) const noexcept {
    return static_cast<Access>(bits(space).access[address]);
  }
  /// True when at least one bit of this space is defined (else its function codes answer 01).
  [[nodiscard]] bool has(BitSpace space) const noexcept { return bits(space).defined > 0; }
  [[nodiscard]] bool range_ok(BitSpace space, std::uint16_t first, std::uint16_t count, bool need_write) const noexcept;
  [[nodiscard]] bool get(BitSpace space, std::uint16_t address) const noexcept {
    return bits(space).values[address] != 0;
  }
  /// Set a bit regardless of access (the device model sets its discrete inputs this way).
  void set(BitSpace space, std::uint16_t address, bool value) noexcept { bits(space).values[address] = value ? 1 : 0; }
  /// One byte per bit, 0 or 1 (modbus_mapping_t's tab_bits / tab_input_bits).
  [[nodiscard]] std::span<const std::uint8_t> values(BitSpace space) const noexcept { return bits(space).values; }
  [[nodiscard]] std::span<std::uint8_t> values(BitSpace space) noexcept { return bits(space).values; }

 private:
  struct Bank {
    std::vector<std::uint16_t> values;
    std::vector<std::uint8_t> access;
  };
  [[nodiscard]] const Bank& bank(RegisterSpace s) const noexcept {
    return s == RegisterSpace::holding ? holding_ : input_;
  }
  [[nodiscard]] Bank& bank(RegisterSpace s) noexcept { return s == RegisterSpace::holding ? holding_ : input_; }
  struct BitBank {
    std::vector<std::uint8_t> values;
    std::vector<std::uint8_t> access;
    std::uint32_t defined = 0;  ///< bits defined (not absent)
  };
  [[nodiscard]] const BitBank& bits(BitSpace s) const noexcept { return s == BitSpace::coil ? coils_ : inputs_; }
  [[nodiscard]] BitBank& bits(BitSpace s) noexcept { return s == BitSpace::coil ? coils_ : inputs_; }
  Bank holding_;
  Bank input_;
  BitBank coils_;
  BitBank inputs_;
};

}  // namespace hil::modbus
