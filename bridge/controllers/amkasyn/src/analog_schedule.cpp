// SPDX-License-Identifier: MIT
// The awN_message16 schedule text (analog_schedule.hpp).
#include "hil/controllers/amkasyn/analog_schedule.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cstdint>
#include <optional>

#include "text_trim.hpp"

namespace hil::controllers::amkasyn {
namespace {

using detail::trim;

std::optional<std::int64_t> whole(std::string_view text, int base = 10) {
  std::int64_t n = 0;
  if (text.empty() || text.front() == '-' || text.front() == '+') return std::nullopt;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n, base);
  if (ec != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return n;
}

std::optional<Duration> time_of(std::string_view t) {
  struct Unit {
    std::string_view suffix;
    std::int64_t ns;
  };
  // "ms" and "us" before "s": the longest suffix that matches.
  for (const auto& [suffix, ns] : {Unit{"ms", 1'000'000}, Unit{"us", 1'000}, Unit{"s", 1'000'000'000}}) {
    if (!t.ends_with(suffix)) continue;
    const auto n = whole(trim(t.substr(0, t.size() - suffix.size())));
    if (!n || *n > 86'400'000'000'000 / ns) return std::nullopt;  // at most a day
    return Duration(*n * ns);
  }
  return std::nullopt;
}

}  // namespace

std::expected<AnalogSchedule, std::string> parse_analog_schedule(std::string_view text) {
  AnalogSchedule out;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const auto comma = text.find(',', pos);
    const std::string_view item =
        trim(text.substr(pos, comma == std::string_view::npos ? std::string_view::npos : comma - pos));
    pos = comma == std::string_view::npos ? text.size() + 1 : comma + 1;
    if (item.empty()) continue;
    const auto eq = item.find('=');
    if (eq == std::string_view::npos)
      return std::unexpected(fmt::format("'{}': write TIME=WORD, e.g. \"0ms=2108, 3ms=2128\"", item));
    const auto t = time_of(trim(item.substr(0, eq)));
    if (!t)
      return std::unexpected(
          fmt::format("'{}': the time is a whole number of us, ms or s (at most a day), e.g. 3ms", item));
    const std::string_view w = trim(item.substr(eq + 1));
    const bool hex = w.starts_with("0x") || w.starts_with("0X");
    const auto word = hex ? whole(w.substr(2), 16) : whole(w);
    if (!word || *word > 0xFFFF)
      return std::unexpected(fmt::format(
          "'{}': the word is the raw 16-bit message16, 0..65535 or 0x0000..0xFFFF (2048 = 0 of the 12-bit offset "
          "binary analog input)",
          item));
    if (!out.empty() && *t <= out.back().from)
      return std::unexpected(
          fmt::format("'{}': the times must increase (the step before is at {} us)", item,
                      std::chrono::duration_cast<std::chrono::microseconds>(out.back().from).count()));
    out.push_back(AnalogStep{*t, static_cast<std::uint16_t>(*word)});
  }
  if (out.empty()) return std::unexpected("no step: write TIME=WORD, ..., e.g. \"0ms=2108, 3ms=2128\"");
  return out;
}

std::uint16_t analog_word_at(const AnalogSchedule& schedule, Duration t) noexcept {
  std::uint16_t word = 0;
  for (const auto& s : schedule) {
    if (s.from > t) break;
    word = s.word;
  }
  return word;
}

}  // namespace hil::controllers::amkasyn
