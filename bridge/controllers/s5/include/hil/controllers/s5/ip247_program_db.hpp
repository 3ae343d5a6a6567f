// SPDX-License-Identifier: MIT
#pragma once
// The traversing-program DB image (BA22 write / BA69 read; manual §6.3.8.2, digest ip247.md
// §5.5 b), the form in which programs travel over RK512:
//   DW0 length in words from DW0 through the word holding the final <LF>; DW1 0044h (00,'D');
//   DW2 'B',dbno; DW3 syntax error number (written by the firmware); DW4 number of the faulty
//   block; DW5.. the program text, two chars per word, high byte first, padded with 00h.
// Pure codec.

#include <cstdint>
#include <expected>
#include <string>
#include <string_view>
#include <vector>

#include "hil/controllers/s5/ip247_syntax_error.hpp"

namespace hil::controllers::s5 {

inline constexpr std::size_t ip247_vp_header_words = 5;
inline constexpr std::size_t ip247_vp_max_words = 512;  ///< an S5 DB holds at most 512 words

struct Ip247VpImage {
  std::uint8_t db = 0;
  std::string text{};
  int syntax_error = 0;  ///< DW3
  int faulty_block = 0;  ///< DW4
  friend bool operator==(const Ip247VpImage&, const Ip247VpImage&) = default;
};

/// Build the DB image. Fails when the text does not fit into 512 words.
[[nodiscard]] std::expected<std::vector<std::uint16_t>, std::string> make_ip247_vp_db(const Ip247VpImage& vp);
/// Read an image (DW0 must not claim more words than present or than 512; DW1/DW2 must be the
/// 'DB' identifier). The text ends at the pad byte or at the length.
[[nodiscard]] std::expected<Ip247VpImage, std::string> parse_ip247_vp_db(const std::vector<std::uint16_t>& words);
/// Write the firmware's verdict into an image (DW3/DW4), as the module does with a rejected VP.
void set_ip247_vp_error(std::vector<std::uint16_t>& words, const Ip247SyntaxFault& f);

}  // namespace hil::controllers::s5
