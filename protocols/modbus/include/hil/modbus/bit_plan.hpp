// SPDX-License-Identifier: MIT
#pragma once
// Which requests one poll of a digital I/O terminal makes: the coils and discrete inputs a link
// uses, grouped into runs of consecutive addresses per table (one FC 1 / FC 2 read or one
// FC 5 / FC 15 write each). Gaps are never bridged: a terminal may answer exception 02 for an
// address between two used ones. Pure: no sockets, no clock.

#include <cstddef>
#include <cstdint>
#include <expected>
#include <span>
#include <string>
#include <vector>

#include "hil/modbus/register_table.hpp"

namespace hil::modbus {

struct BitRef {
  BitSpace space = BitSpace::coil;
  std::uint16_t address = 0;  ///< 0-based protocol address (PDU address)
};

struct BitBlock {
  BitSpace space = BitSpace::coil;
  std::uint16_t first = 0;
  std::uint16_t count = 0;
};

struct BitPlan {
  std::vector<BitBlock> blocks;  ///< coils first, then discrete inputs, each in address order
  /// Per entry of the input list: its index in the flattened values of all blocks (block 0's
  /// bits, then block 1's, ...). Entries naming the same bit share an index.
  std::vector<std::size_t> slots;
  std::size_t bits = 0;  ///< total bits of all blocks
};

/// Plan the reads (`writes == false`: coils and discrete inputs, at most 2000 bits per block,
/// MB spec §6.1/6.2) or the writes (`writes == true`: coils only, at most 1968 per block, §6.11).
/// Errors: a discrete input among writes, or (writes) the same coil twice.
[[nodiscard]] std::expected<BitPlan, std::string> make_bit_plan(std::span<const BitRef> bits, bool writes);

[[nodiscard]] std::string_view to_string(BitSpace space) noexcept;

}  // namespace hil::modbus
