// SPDX-License-Identifier: MIT
#include "hil/controllers/s5/ip247_program_db.hpp"

namespace hil::controllers::s5 {

std::expected<std::vector<std::uint16_t>, std::string> make_ip247_vp_db(const Ip247VpImage& vp) {
  const std::size_t text_words = (vp.text.size() + 1) / 2;
  const std::size_t total = ip247_vp_header_words + text_words;
  if (total > ip247_vp_max_words) {
    return std::unexpected("program text of " + std::to_string(vp.text.size()) + " chars needs " +
                           std::to_string(total) + " words, a DB holds at most 512");
  }
  std::vector<std::uint16_t> w(total, 0);
  w[0] = static_cast<std::uint16_t>(total);
  w[1] = 0x0044;
  w[2] = static_cast<std::uint16_t>(0x4200 | vp.db);
  w[3] = static_cast<std::uint16_t>(vp.syntax_error);
  w[4] = static_cast<std::uint16_t>(vp.faulty_block);
  for (std::size_t i = 0; i < vp.text.size(); ++i) {
    const auto c = static_cast<std::uint8_t>(vp.text[i]);
    auto& word = w[ip247_vp_header_words + i / 2];
    word = static_cast<std::uint16_t>(i % 2 == 0 ? (word | (c << 8)) : (word | c));
  }
  return w;
}

std::expected<Ip247VpImage, std::string> parse_ip247_vp_db(const std::vector<std::uint16_t>& words) {
  if (words.size() < ip247_vp_header_words) return std::unexpected("VP DB shorter than its 5-word header");
  const std::size_t len = words[0];
  if (len < ip247_vp_header_words || len > words.size() || len > ip247_vp_max_words) {
    return std::unexpected("VP DB length word DW0 = " + std::to_string(len) + " does not match the image (" +
                           std::to_string(words.size()) + " words, at most 512)");
  }
  if (words[1] != 0x0044 || (words[2] >> 8) != 0x42) {
    return std::unexpected("VP DB identifier DW1/DW2 is not 00,'D' / 'B',dbno");
  }
  Ip247VpImage vp;
  vp.db = static_cast<std::uint8_t>(words[2] & 0xFF);
  vp.syntax_error = words[3];
  vp.faulty_block = words[4];
  for (std::size_t i = ip247_vp_header_words; i < len; ++i) {
    const char hi = static_cast<char>(words[i] >> 8);
    const char lo = static_cast<char>(words[i] & 0xFF);
    if (hi == '\0') break;
    vp.text += hi;
    if (lo == '\0') break;
    vp.text += lo;
  }
  return vp;
}

void set_ip247_vp_error(std::vector<std::uint16_t>& words, const Ip247SyntaxFault& f) {
  if (words.size() < ip247_vp_header_words) return;
  words[3] = static_cast<std::uint16_t>(f.code);
  words[4] = static_cast<std::uint16_t>(f.block_number);
}

}  // namespace hil::controllers::s5
