// SPDX-License-Identifier: MIT
#pragma once
// The data jobs of the IP247 (manual §4.3.11-4.3.23, §6.3; digest ip247.md §4.4, §4.12, §5.5):
// BA20/21 MD write/delete, BA22/23 VP write/delete, BA24 SYS-ID write, BA64 MD directory, BA65 VP
// directory, BA66 actual values, BA67 read MD, BA68 MD overview, BA69 read VP, BA70 read SYS-ID, as
// FB165 "PER:PDAT" sends them, and the job block through which a PLC (or a scenario's `plc:` steps)
// gives them: FB165's indirect parameter block (15 words from DW n):
//   DW n    BA (KY x,y): y = job, x > 0 = binary -> BCD conversion (BA66 only). The PLC writes it
//           last (our start edge, FB165's ANST); the module writes 0000h when the job is done
//           (FB165's handshake)
//   DW n+1  Q-DB   DW n+2 QANF   DW n+3 Z-DB   DW n+4 ZANF   DW n+5 SSNR (tile)
//   DW n+6  result flags: bit 0 = BFEH (module error), bit 1 = PAFE (interface error)
//   DW n+7  DL = MB250 interface error (Ip247InterfaceError), DR = MB251 module error
//   DW n+8  MB249 (BA66: bit 0 actual value, bit 1 remaining distance not BCD-convertible)
//   DW n+9  words transferred into the AG (reads) or taken from it (writes) (our decision: FB165's
//           length word)
//   DW n+10..14 0
// Writes (20/22/24) take Q-DB/QANF in the AG and Z-DB on the IP247; reads (64-70) take Q-DB on
// the IP247 (67/69) and Z-DB/ZANF in the AG; deletes (21/23) take Z-DB on the IP247. Pure codec.

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "hil/stepdir/ip247_error.hpp"

namespace hil::controllers::s5 {

inline constexpr std::size_t ip247_data_job_words = 15;

/// MB250, the interface error of the handling blocks (manual §7.2, digest §5.6). Values are the
/// manual's numbers.
enum class Ip247InterfaceError : std::uint8_t {
  none = 0,
  htb = 1,     ///< error in the HTB PAFE byte (here: SSNR is no tile of this module)
  module = 2,  ///< error in the module error byte (MB251)
  offset_too_large = 5,
  not_possible = 6,      ///< processing currently not possible
  db_exists = 7,         ///< DB already exists (no overwrite: delete first)
  db_missing = 8,        ///< DB does not exist (in the AG)
  wrong_identifier = 9,  ///< wrong ORG identifier: the image is not 70/len, 0044h, 'B' + Z-DB
  target_too_small = 0xA,
  source_too_small = 0xB,
  source_too_large = 0xC,
  area_too_small = 0xD,
};

/// The PLC's data blocks (number -> words; a DB's length is fixed as the PLC created it).
using S5Blocks = std::map<int, std::vector<std::uint16_t>>;

struct Ip247DataJob {
  int ba = 0;        ///< 20..24, 64..70
  bool bcd = false;  ///< KY x,y with x > 0 (BA66)
  int q_db = 0, q_start = 0;
  int z_db = 0, z_start = 0;
  int tile = 0;  ///< SSNR
};

struct Ip247DataResult {
  Ip247InterfaceError interface_error = Ip247InterfaceError::none;
  stepdir::Ip247Error module_error = stepdir::Ip247Error::none;
  int words = 0;               ///< words transferred
  std::uint8_t bcd_flags = 0;  ///< MB249
  friend bool operator==(const Ip247DataResult&, const Ip247DataResult&) = default;
};

/// The job of a job block whose DW0 is non-zero (nullopt: no job).
[[nodiscard]] std::optional<Ip247DataJob> take_ip247_data_job(const std::vector<std::uint16_t>& block);
/// The result into the block (DW6..DW14) and DW0 = 0000h (done).
void write_ip247_data_result(std::vector<std::uint16_t>& block, const Ip247DataResult& r);

}  // namespace hil::controllers::s5
