// SPDX-License-Identifier: MIT
#pragma once
// CLM1.4 ASCII line protocol (Rexroth OptiFeed-FM CLM01.4 manual §9.2, digest clm14.md §2.2-2.3):
//   <lead><station><body>[$hh] CR LF
// lead: '?' query, '#' data, '!' control command, ':' RS-485 poll; replies also start with
// 'X' (status), 'V' (variable), 'P' (logic task), and a confirmation is "Y CR LF".
// station: ' ' on RS-232, '1'..'9','A'..'W' for RS-485 stations 1..32.
// Pure codec: no I/O, no clock.

#include <cstdint>
#include <expected>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace hil::serial::clm14 {

/// Checksum of the manual (Fig. 9-12): S = sum of the bytes from the lead character up to the
/// last byte before '$'; x = hi(S) + lo(S) mod 256; checksum = two's complement of x.
[[nodiscard]] constexpr std::uint8_t checksum(std::string_view text) noexcept {
  unsigned s = 0;
  for (char c : text) s += static_cast<std::uint8_t>(c);
  const auto x = static_cast<std::uint8_t>((s >> 8) + (s & 0xFFU));
  return static_cast<std::uint8_t>(-x);
}

/// RS-485 station character: 0 -> ' ' (RS-232 / broadcast), 1..9 -> '1'..'9', 10..32 -> 'A'..'W'.
[[nodiscard]] std::optional<char> station_char(int station) noexcept;
/// Inverse of station_char: ' ' -> 0.
[[nodiscard]] std::optional<int> parse_station(char c) noexcept;

struct Telegram {
  char lead = '#';                       ///< '?', '#', '!', ':', 'X', 'V', 'P', 'Y'
  char station = ' ';                    ///< station character (not present in a "Y" confirmation: ' ')
  std::string body;                      ///< everything after the station character up to '$' (or CR LF)
  std::optional<std::uint8_t> checksum;  ///< as received; nullopt when sent without "$hh"

  friend bool operator==(const Telegram&, const Telegram&) = default;
  [[nodiscard]] bool is_confirmation() const noexcept { return lead == 'Y'; }
};

/// Why a line is not a well-formed telegram. Values are the CLM serial error numbers the
/// device reports for the same fault (status 01), so the emulator can answer with them.
enum class SyntaxError : std::uint8_t {
  format = 2,    ///< "RS Format Error": unknown lead character, missing CR LF, too long
  checksum = 4,  ///< "RS Checksum Error": '$hh' present but wrong, or missing where required
};

struct ParseFailure {
  SyntaxError code;
  std::string message;  ///< what is wrong, with the offending text
};

/// Longest line accepted (lead..LF). The longest legal telegram is a program line (~60 chars).
inline constexpr std::size_t max_line_length = 128;

/// Build the bytes of a telegram: lead, station, body, and "$hh" when `with_checksum`, then CR LF.
/// A confirmation is "Y\r\n".
[[nodiscard]] std::string make_telegram(const Telegram& t, bool with_checksum = true);
/// Convenience: make_telegram({lead, station, body}).
[[nodiscard]] std::string make_telegram(char lead, char station, std::string_view body, bool with_checksum = true);

/// Parse one line (without the CR LF). `require_checksum`: a missing "$hh" is an error
/// (B003 H = 0/2, and always for '!' commands). A present checksum is always verified.
[[nodiscard]] std::expected<Telegram, ParseFailure> parse_telegram(std::string_view line, bool require_checksum);

/// Splits a byte stream into lines ended by LF (a preceding CR is dropped). Pure, incremental.
class LineSplitter {
 public:
  enum class Event { none, line, overflow };
  /// Feed one byte. On `line`, take_line() returns the line without CR LF.
  Event feed(char c);
  [[nodiscard]] std::string take_line() { return std::exchange(line_, {}); }
  void reset() noexcept {
    cur_.clear();
    line_.clear();
    overflow_ = false;
  }
  [[nodiscard]] bool mid_line() const noexcept { return !cur_.empty(); }

 private:
  std::string cur_;
  std::string line_;
  bool overflow_ = false;
};

}  // namespace hil::serial::clm14
