// SPDX-License-Identifier: MIT
#pragma once
// Validation of ELG tape data, IP247 MD images and WF 725/726 machine data against the device
// profiles (profiles/devices/*.yaml through hil::profiles). The profiles are the single source
// of parameter definitions; these adapters only translate between wire images and the profile.

#include <cstdint>
#include <expected>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "hil/serial/tape/elg_tape.hpp"

namespace hil::serial {

/// ELG datum check: empty = valid, else what is wrong (MD/SD number unknown, value out of range).
using ElgCheck = std::function<std::optional<std::string>(tape::ElgSectionKind, int number, const std::string& value)>;
/// IP247 MD image check: empty = valid, else the problems (each with the MD error number).
using Ip247Check = std::function<std::vector<std::string>(const std::vector<std::uint16_t>& md_db)>;
/// WF 725/726 check of the complete MD image (data code 1: MD1..MD50, 2 words each, binary):
/// empty = valid, else every problem (ranges, variant applicability, cross-MD rules).
using Wf725Check = std::function<std::vector<std::string>(const std::vector<std::uint16_t>& md_words)>;

[[nodiscard]] std::expected<ElgCheck, std::string> load_elg_check();
[[nodiscard]] std::expected<Ip247Check, std::string> load_ip247_check();
[[nodiscard]] std::expected<Wf725Check, std::string> load_wf725_check();
/// The WF 725/726 machine data defaults of the profile as the data-code-1 image: MD1..MD50, two
/// words each (binary, high word first); 0 where the profile has no default.
[[nodiscard]] std::expected<std::vector<std::uint16_t>, std::string> load_wf725_default_image();

}  // namespace hil::serial
