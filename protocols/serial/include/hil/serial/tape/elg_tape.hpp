// SPDX-License-Identifier: MIT
#pragma once
// SINUMERIK System 3 ELG machine-data (%TEA1) and setting-data (%SEA) tapes (manual §9.4,
// digest sinumerik-elg.md §7.10). Layout (reconstructed, see docs/serial.md):
//   %TEA1            header: machine data     %SEA    header: setting data
//   N396=180000      word datum, signed decimal, at most 9 digits
//   N5002=00100010   bit datum as 8 binary digits, bit 7 .. bit 0
//   M02              end (or M30)
// Pure codec between tape blocks (see tape_reader.hpp) and typed sections.

#include <expected>
#include <string>
#include <string_view>
#include <vector>

#include "hil/serial/tape/tape_reader.hpp"

namespace hil::serial::tape {

enum class ElgSectionKind { machine_data, setting_data };

struct ElgEntry {
  int number = 0;     ///< MD / SD number (e.g. 396, 5011)
  std::string value;  ///< "180000", "-25", "00100010"
  friend bool operator==(const ElgEntry&, const ElgEntry&) = default;
};

struct ElgSection {
  ElgSectionKind kind = ElgSectionKind::machine_data;
  std::vector<ElgEntry> entries;
  friend bool operator==(const ElgSection&, const ElgSection&) = default;
};

struct ElgTapeError {
  std::error_code code;  ///< TapeError (ELG alarm number)
  std::string block;     ///< the offending block text
  std::string message;
};

/// Header text of a section: "%TEA1" / "%SEA".
[[nodiscard]] std::string_view elg_header(ElgSectionKind k) noexcept;

/// Sections from the blocks of one or more tapes (each starting with its '%' header and
/// ending with M02/M30). Comments "( ... )" are removed. Alarm 32 for a malformed datum.
[[nodiscard]] std::expected<std::vector<ElgSection>, ElgTapeError> parse_elg_blocks(
    const std::vector<std::string>& blocks);
/// Blocks of one section: header, one block per entry, "M02".
[[nodiscard]] std::vector<std::string> make_elg_blocks(const ElgSection& s);

/// The tape as text (what a technician keeps in version control): blocks separated by LF,
/// no leader/trailer, no parity. parse_elg_text(make_elg_text(x)) == x.
[[nodiscard]] std::string make_elg_text(const std::vector<ElgSection>& sections);
[[nodiscard]] std::expected<std::vector<ElgSection>, ElgTapeError> parse_elg_text(std::string_view text);

}  // namespace hil::serial::tape
