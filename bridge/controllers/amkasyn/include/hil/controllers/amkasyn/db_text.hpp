// SPDX-License-Identifier: MIT
#pragma once
// The AMKASYN data blocks as text (the profile's `amk-db` format, docs/profiles.md): one data
// item per line with its stored value, as the manual's examples write them,
//   INIT DR0 = 1        FB 207 init DB (10 words)
//   DL1 = 98            FB 208 commanding DB (34 words) of the same SF
//   DD10 = 20000        32-bit, low word first (DD n = DW n+1 << 16 | DW n)
//   DW4 = 0x10 ; text   decimal, 0x... or ...h; ';' or '#' starts a comment
// and the table DBs (FIPW/FIPZ Y tables, DFKT speed tables, BINEA output tables, CAM tables, the
// DFKT output table) in the same line syntax without INIT, DW0..DW4001. Pure: text in, DataBlocks
// or the line and item that is wrong out. The profile engine validates an SF file's meaning
// (ranges, START rules); this codec only makes the words the SF runtime reads.

#include <cstdint>
#include <expected>
#include <string>
#include <string_view>

#include "hil/controllers/amkasyn/data_block.hpp"

namespace hil::controllers::amkasyn {

/// Where and why a DB text is wrong.
struct DbTextError {
  int line = 0;         ///< 1-based
  std::string item;     ///< "DW40", "INIT DR2", or the text that is not an item
  std::string message;  ///< what is wrong and what is allowed
};

/// One SF: its FB 207 init DB and FB 208 commanding DB.
struct SfDbText {
  DataBlock init{10};
  DataBlock command{34};
  bool has_init = false;  ///< at least one INIT line
};

/// Largest table DB (XFIPW Y tables: DW0..DW4001).
inline constexpr std::size_t max_table_words = 4002;

/// Parses an SF file (INIT lines into the init DB, the others into the commanding DB).
[[nodiscard]] std::expected<SfDbText, DbTextError> parse_sf_db_text(std::string_view text);
/// Parses a table DB (no INIT lines); the block is as long as its highest word.
[[nodiscard]] std::expected<DataBlock, DbTextError> parse_table_db_text(std::string_view text);

}  // namespace hil::controllers::amkasyn
