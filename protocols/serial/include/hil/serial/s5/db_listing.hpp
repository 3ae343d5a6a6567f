// SPDX-License-Identifier: MIT
#pragma once
// Data-block images as text, in the style of a STEP 5 DB listing (what a technician keeps):
//   ; comment
//   DB10
//     0: KF = +00070
//     1: KH = 0044
//     2: KY = 066,010
//     5: KH = 0000
// One data word per line, consecutive from 0; KH (hex), KF (signed decimal), KY (two bytes)
// accepted; written as KH. Pure codec.

#include <cstdint>
#include <expected>
#include <string>
#include <string_view>
#include <vector>

namespace hil::serial::s5 {

struct DbImage {
  std::uint8_t db = 0;
  std::vector<std::uint16_t> words;
  friend bool operator==(const DbImage&, const DbImage&) = default;
};

/// Every problem as "name:line: message".
[[nodiscard]] std::expected<std::vector<DbImage>, std::vector<std::string>> parse_db_listing(std::string_view text,
                                                                                             std::string_view name);
[[nodiscard]] std::string make_db_listing(const std::vector<DbImage>& dbs, std::string_view header_comment);

}  // namespace hil::serial::s5
