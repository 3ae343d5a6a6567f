// SPDX-License-Identifier: MIT
#pragma once
// Test helpers: frames from candump-style text ("602#4018100100000000") and a recording sink.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "hil/can/frame.hpp"
#include "hil/canopen/cob_id.hpp"

namespace hil::canopen::test {

inline can::Frame f(std::string_view text) {
  const auto hash = text.find('#');
  can::Frame fr;
  fr.id = static_cast<std::uint32_t>(std::stoul(std::string(text.substr(0, hash)), nullptr, 16));
  auto data = text.substr(hash + 1);
  if (!data.empty() && data[0] == 'R') {
    fr.rtr = true;
    fr.dlc = data.size() > 1 ? static_cast<std::uint8_t>(data[1] - '0') : 0;
    return fr;
  }
  std::string hex;
  for (char c : data)
    if (c != ' ' && c != '.') hex.push_back(c);
  fr.dlc = static_cast<std::uint8_t>(hex.size() / 2);
  for (std::size_t i = 0; i < fr.dlc; ++i)
    fr.data[i] = static_cast<std::uint8_t>(std::stoul(hex.substr(2 * i, 2), nullptr, 16));
  return fr;
}

inline std::string str(const can::Frame& fr) {
  std::string s = fmt::format("{:03X}#", fr.id);
  if (fr.rtr) return s + fmt::format("R{}", fr.dlc);
  for (std::size_t i = 0; i < fr.dlc; ++i) s += fmt::format("{:02X}", fr.data[i]);
  return s;
}

struct Recorder {
  std::vector<can::Frame> frames;
  FrameSink sink() {
    return [this](const can::Frame& fr) { frames.push_back(fr); };
  }
  std::vector<std::string> take() {
    std::vector<std::string> out;
    for (const auto& fr : frames) out.push_back(str(fr));
    frames.clear();
    return out;
  }
};

}  // namespace hil::canopen::test
