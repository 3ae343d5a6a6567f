// SPDX-License-Identifier: MIT
#pragma once
// A scenario's analog input of an AW drive (Config-AW message16, ID 32785 = analog input A1): the
// raw 16-bit words of the controller key `awN_message16: "0ms=2108, 3ms=2128"`, each held from its
// time (since the controller's first cycle) until the next. Pure: text in, schedule out.
#include <cstdint>
#include <expected>
#include <string>
#include <string_view>
#include <vector>

#include "hil/core/clock.hpp"

namespace hil::controllers::amkasyn {

struct AnalogStep {
  Duration from{};
  std::uint16_t word = 0;  ///< the raw message16 word (the drive's 12-bit offset binary: 2048 = 0)
};

/// Steps with strictly increasing times.
using AnalogSchedule = std::vector<AnalogStep>;

/// "T=WORD, ..." with T a whole number of us, ms or s and WORD 0..65535 (decimal or 0x hex), at
/// least one step, times strictly increasing. The error says which item and why.
[[nodiscard]] std::expected<AnalogSchedule, std::string> parse_analog_schedule(std::string_view text);

/// The word held at t: the last step at or before t, 0 before the first step (no input yet).
[[nodiscard]] std::uint16_t analog_word_at(const AnalogSchedule& schedule, Duration t) noexcept;

}  // namespace hil::controllers::amkasyn
