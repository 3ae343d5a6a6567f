// SPDX-License-Identifier: MIT
#include "hil/controllers/device_error.hpp"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>

namespace hil::controllers {
namespace {

bool contains_ci(std::string_view text, std::string_view word) noexcept {
  if (word.size() > text.size()) return false;
  for (std::size_t i = 0; i + word.size() <= text.size(); ++i) {
    bool eq = true;
    for (std::size_t k = 0; k < word.size() && eq; ++k) {
      eq = std::tolower(static_cast<unsigned char>(text[i + k])) == std::tolower(static_cast<unsigned char>(word[k]));
    }
    if (eq) return true;
  }
  return false;
}

bool starts_with_ci(std::string_view text, std::string_view word) noexcept {
  return text.size() >= word.size() && contains_ci(text.substr(0, word.size()), word);
}

}  // namespace

std::string_view to_string(AckRule r) noexcept {
  switch (r) {
    case AckRule::self_clearing:
      return "self_clearing";
    case AckRule::acknowledge:
      return "acknowledge";
    case AckRule::reset:
      return "reset";
    case AckRule::power_cycle:
      return "power_cycle";
  }
  return "?";
}

AckRule ack_rule_for(const profiles::ErrorEntry& entry) noexcept {
  const std::string_view ack = entry.acknowledge;
  // "POWER ON RESET only", "Power cycle; service", "Hardware fault: power cycle; ...".
  if (contains_ci(ack, "power on reset only") || starts_with_ci(ack, "power cycle") ||
      contains_ci(ack, "hardware fault: power cycle")) {
    return AckRule::power_cycle;
  }
  if (entry.reaction == profiles::Reaction::needs_reset) return AckRule::reset;
  if (starts_with_ci(ack, "self-") || starts_with_ci(ack, "nothing to acknowledge") ||
      starts_with_ci(ack, "warning/information")) {
    return AckRule::self_clearing;
  }
  if (starts_with_ci(ack, "reset")) return AckRule::reset;
  return AckRule::acknowledge;
}

std::string DeviceError::code_text() const {
  return catalogue != nullptr ? catalogue->format_code(code) : std::to_string(code);
}

std::string DeviceError::describe() const {
  const char* category = fault.code ? fault.code.category().name() : "device";
  return fmt::format("{} {} {}", category, code_text(), fault.text);
}

DeviceError make_device_error(const profiles::ErrorCatalogue& catalogue, int code, TimePoint now, int axis,
                              std::string_view context, std::optional<AckRule> ack) {
  DeviceError e;
  e.catalogue = &catalogue;
  e.code = code;
  e.fault = catalogue.make_fault(code, context);
  e.axis = axis;
  e.raised_at = now;
  if (const auto* entry = catalogue.find(code)) {
    e.reaction = entry->reaction;
    e.ack = ack.value_or(ack_rule_for(*entry));
  } else {
    e.reaction = profiles::Reaction::stop;
    e.ack = ack.value_or(AckRule::acknowledge);
  }
  return e;
}

bool DeviceErrorLatch::raise(DeviceError e) noexcept {
  if (std::ranges::any_of(active_, [&](const DeviceError& a) { return a.same(e); })) return false;
  history_.push_back(e);
  active_.push_back(std::move(e));
  return true;
}

std::size_t DeviceErrorLatch::acknowledge(Acknowledgement how) noexcept {
  const auto strength = static_cast<int>(how) + 1;  // acknowledge=1, reset=2, power_cycle=3 (AckRule values)
  return std::erase_if(active_, [&](const DeviceError& e) { return static_cast<int>(e.ack) <= strength; });
}

bool DeviceErrorLatch::clear(const profiles::ErrorCatalogue& catalogue, int code, int axis) noexcept {
  return std::erase_if(active_, [&](const DeviceError& e) {
           return e.catalogue == &catalogue && e.code == code && e.axis == axis && e.ack == AckRule::self_clearing;
         }) > 0;
}

namespace {
bool blocking(const DeviceError& e) noexcept {
  return e.reaction != profiles::Reaction::message;
}
}  // namespace

bool DeviceErrorLatch::blocks_motion() const noexcept {
  return std::ranges::any_of(active_, blocking);
}

bool DeviceErrorLatch::blocks_motion(int axis) const noexcept {
  return std::ranges::any_of(active_,
                             [&](const DeviceError& e) { return blocking(e) && (e.axis == axis || e.axis < 0); });
}

}  // namespace hil::controllers
