// SPDX-License-Identifier: MIT
#pragma once
// The FB 207 initialisation DB (digest §1.5): SF type and slot, E/A-M mode, cycle factor, source
// and sink data holders, the binary I/O bytes and masks, and the table DBs Tab0..Tab7.

#include <array>
#include <cstdint>
#include <expected>

#include "hil/controllers/amkasyn/data_block.hpp"
#include "hil/controllers/amkasyn/process_image.hpp"
#include "hil/controllers/amkasyn/sf_error.hpp"

namespace hil::controllers::amkasyn {

enum class SfType : std::uint8_t {
  copy = 0,
  fipw = 1,
  fipz = 2,
  stdfkt = 3,
  dfkt = 4,
  fgen = 5,
  regl = 6,
  imes = 7,
  binea = 8,
  xfipw = 9,
  apsf = 10,
  epos = 11,
  cam = 12,
};
[[nodiscard]] const char* to_string(SfType t) noexcept;

struct InitDb {
  SfType type = SfType::copy;               ///< DR0
  std::uint8_t number = 0;                  ///< DL0, 0..15
  bool inputs_from_m = false;               ///< DR1 bit0
  bool outputs_to_m = false;                ///< DR1 bit1
  std::uint8_t cycle_factor = 1;            ///< DL1 (0 -> 1)
  Holder source{};                          ///< DL2 address, DR2 offset
  Holder sink{};                            ///< DL3 address, DR3 offset
  std::uint8_t in_mask = 0, in_byte = 0;    ///< DR4 (one bit = E1), DL4
  std::uint8_t out_mask = 0, out_byte = 0;  ///< DR5 (one bit = A1), DL5
  std::array<std::uint8_t, 8> tables{};     ///< DR6, DL6, ..., DL9: DB numbers of Tab0..Tab7 (0 = none)

  /// Decode and check an init DB (SF number <= 15, type 0..12, data holders of the manual's
  /// tables, masks with at most one bit, table DBs 0..63).
  [[nodiscard]] static std::expected<InitDb, SfFault> parse(const DataBlock& db);
  /// Bit position of E1 / A1 in their byte (0..7), and how many logical bits fit (8 - position).
  [[nodiscard]] int in_bit() const noexcept;
  [[nodiscard]] int out_bit() const noexcept;
};

}  // namespace hil::controllers::amkasyn
