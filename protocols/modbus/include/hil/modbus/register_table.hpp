// SPDX-License-Identifier: MIT
#pragma once
// The server's data model: holding registers (FC 3/6/16/22/23) and input registers (FC 4), each
// register either absent, read-only or read-write. Absent registers answer exception 02;
// writes to read-only holding registers answer exception 02 as well (the address is not a
// writable register; see docs/modbus.md for why 02 and not 04). Plain data, not thread-safe: the
// server serialises access.

#include <cstdint>
#include <span>
#include <vector>

namespace hil::modbus {

enum class RegisterSpace : std::uint8_t { holding, input };
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

 private:
  struct Bank {
    std::vector<std::uint16_t> values;
    std::vector<std::uint8_t> access;
  };
  [[nodiscard]] const Bank& bank(RegisterSpace s) const noexcept {
    return s == RegisterSpace::holding ? holding_ : input_;
  }
  [[nodiscard]] Bank& bank(RegisterSpace s) noexcept { return s == RegisterSpace::holding ? holding_ : input_; }
  Bank holding_;
  Bank input_;
};

}  // namespace hil::modbus
