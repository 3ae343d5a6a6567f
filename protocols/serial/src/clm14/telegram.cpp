// SPDX-License-Identifier: MIT
#include "hil/serial/clm14/telegram.hpp"

#include <fmt/format.h>

namespace hil::serial::clm14 {

std::optional<char> station_char(int station) noexcept {
  if (station == 0) return ' ';
  if (station >= 1 && station <= 9) return static_cast<char>('0' + station);
  if (station >= 10 && station <= 32) return static_cast<char>('A' + (station - 10));
  return std::nullopt;
}

std::optional<int> parse_station(char c) noexcept {
  if (c == ' ') return 0;
  if (c >= '1' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'W') return 10 + (c - 'A');
  return std::nullopt;
}

std::string make_telegram(const Telegram& t, bool with_checksum) {
  if (t.lead == 'Y') return "Y\r\n";
  std::string s;
  s.reserve(t.body.size() + 8);
  s.push_back(t.lead);
  s.push_back(t.station);
  s += t.body;
  if (with_checksum) s += fmt::format("${:02X}", checksum(s));
  s += "\r\n";
  return s;
}

std::string make_telegram(char lead, char station, std::string_view body, bool with_checksum) {
  return make_telegram(Telegram{lead, station, std::string(body), std::nullopt}, with_checksum);
}

namespace {
int hex_digit(char c) noexcept {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}
bool known_lead(char c) noexcept {
  return c == '?' || c == '#' || c == '!' || c == ':' || c == 'X' || c == 'V' || c == 'P';
}
std::string printable(std::string_view s) {
  std::string out;
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7F)
      out.push_back(c);
    else
      out += fmt::format("<{:02X}>", u);
  }
  return out;
}
}  // namespace

std::expected<Telegram, ParseFailure> parse_telegram(std::string_view line, bool require_checksum) {
  if (line == "Y") return Telegram{'Y', ' ', {}, std::nullopt};
  if (line.size() > max_line_length)
    return std::unexpected(ParseFailure{
        SyntaxError::format, fmt::format("telegram of {} characters is longer than {}", line.size(), max_line_length)});
  if (line.size() < 2)
    return std::unexpected(ParseFailure{SyntaxError::format, fmt::format("telegram '{}' too short: expected "
                                                                         "<lead><station>...",
                                                                         printable(line))});
  if (!known_lead(line[0]))
    return std::unexpected(
        ParseFailure{SyntaxError::format, fmt::format("telegram '{}' starts with '{}': expected one of "
                                                      "? # ! : X V P",
                                                      printable(line), printable(line.substr(0, 1)))});
  Telegram t;
  t.lead = line[0];
  t.station = line[1];
  std::string_view body = line.substr(2);
  const std::size_t dollar = line.size() >= 5 ? line.size() - 3 : std::string_view::npos;
  if (dollar != std::string_view::npos && line[dollar] == '$') {
    const int hi = hex_digit(line[dollar + 1]);
    const int lo = hex_digit(line[dollar + 2]);
    if (hi < 0 || lo < 0)
      return std::unexpected(ParseFailure{
          SyntaxError::checksum,
          fmt::format("checksum '{}' is not two hex digits in '{}'", printable(line.substr(dollar)), printable(line))});
    t.checksum = static_cast<std::uint8_t>(hi * 16 + lo);
    const std::uint8_t expect = checksum(line.substr(0, dollar));
    if (*t.checksum != expect)
      return std::unexpected(ParseFailure{
          SyntaxError::checksum,
          fmt::format("checksum ${:02X} wrong in '{}': computed ${:02X}", *t.checksum, printable(line), expect)});
    body = line.substr(2, dollar - 2);
  } else if (require_checksum) {
    return std::unexpected(
        ParseFailure{SyntaxError::checksum, fmt::format("telegram '{}' has no $hh checksum", printable(line))});
  } else if (line.size() + 3 > max_line_length) {
    // Without a checksum the body may not take the room of one: the answer to it is made with
    // "$hh" and must fit the same limit (found by fuzzing the parse/make round trip).
    return std::unexpected(
        ParseFailure{SyntaxError::format, fmt::format("telegram of {} characters without a checksum is longer than {}",
                                                      line.size(), max_line_length - 3)});
  }
  for (char c : body) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u >= 0x7F)
      return std::unexpected(ParseFailure{SyntaxError::format,
                                          fmt::format("control or 8-bit character in telegram '{}'", printable(line))});
  }
  t.body = std::string(body);
  return t;
}

LineSplitter::Event LineSplitter::feed(char c) {
  if (c == '\n') {
    if (overflow_) {
      overflow_ = false;
      cur_.clear();
      return Event::none;  // the overflow was already reported
    }
    if (!cur_.empty() && cur_.back() == '\r') cur_.pop_back();
    line_ = std::exchange(cur_, {});
    return Event::line;
  }
  if (overflow_) return Event::none;
  cur_.push_back(c);
  if (cur_.size() > max_line_length + 1) {
    overflow_ = true;
    cur_.clear();
    return Event::overflow;
  }
  return Event::none;
}

}  // namespace hil::serial::clm14
