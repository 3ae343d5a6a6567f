// SPDX-License-Identifier: MIT
#pragma once
// IP247 traversing-program syntax errors (manual 6ES5 998-5SB12 §7.2, digest ip247.md §6.3). The
// enum values ARE the module's numbers, written by the firmware into DW n+3 of the rejected VP DB
// (the faulty block number into DW n+4; module error 48 is reported).

#include <cstdint>
#include <string>
#include <system_error>

namespace hil::controllers::s5 {

enum class Ip247SyntaxError : int {
  none = 0,
  text_too_long = 1,           ///< program longer than 1023 chars, or <LF> missing after the header
  block_type = 2,              ///< wrong block type or N missing
  block_number_too_large = 3,  ///< N more than 3 digits
  subprogram_number = 4,       ///< L number more than 3 digits or > 255
  function_after_g = 5,        ///< function not allowed after G (G00 without X, G04 with X, G24 without F, ...)
  function_after_x = 6,        ///< function not allowed after X (X without F outside G00, F after G00 X)
  final_block_lf = 8,          ///< <LF> missing after the final block
  block_end = 9,               ///< block end: <LF> missing or a wrong function present (after L, G20, F, M)
  path_too_large = 10,         ///< X more than 5 integer digits
  f_too_large = 11,            ///< F more than 5 digits or > 65000 (or 0 where not allowed)
  too_many_decimals = 12,      ///< X with more than 3 decimals
  loop_end_missing = 13,       ///< G24 without G20
  loop_start_missing = 14,     ///< G20 without G24
  program_end_missing = 15,    ///< no final block with M02
  unknown_function = 16,       ///< a character that starts no function
  m_too_large = 17,            ///< M more than 2 digits
  block_after_final = 18,      ///< text after the final block
  block_too_long = 19,         ///< a block longer than 50 chars including <LF>
  g_not_implemented = 37,      ///< a G number not in §2.6.6
};

[[nodiscard]] const std::error_category& ip247_syntax_category() noexcept;
[[nodiscard]] inline std::error_code make_error_code(Ip247SyntaxError e) noexcept {
  return {static_cast<int>(e), ip247_syntax_category()};
}

/// A rejected program: the number, the faulty block's N number (0 for the header or when the
/// block has no N) and its line (1 = header), and what is wrong.
struct Ip247SyntaxFault {
  Ip247SyntaxError code = Ip247SyntaxError::none;
  int block_number = 0;
  int line = 0;
  std::string message;
};

}  // namespace hil::controllers::s5

template <>
struct std::is_error_code_enum<hil::controllers::s5::Ip247SyntaxError> : std::true_type {};
