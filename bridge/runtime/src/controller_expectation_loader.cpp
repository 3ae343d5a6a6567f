// SPDX-License-Identifier: MIT
#include "controller_expectation_loader.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>

#include <fmt/format.h>

#include "hil/runtime/scenario_loader.hpp"

namespace hil::runtime::detail {

std::optional<double> parse_expected_value(std::string_view text) {
  bool negative = false;
  std::string_view t = text;
  if (!t.empty() && (t.front() == '-' || t.front() == '+')) {
    negative = t.front() == '-';
    t.remove_prefix(1);
  }
  int base = 0;
  if (t.size() > 2 && t[0] == '0' && (t[1] == 'x' || t[1] == 'X')) base = 16;
  if (t.size() > 2 && t[0] == '0' && (t[1] == 'b' || t[1] == 'B')) base = 2;
  if (base == 0) return std::nullopt;
  std::string digits;
  for (char c : t.substr(2))
    if (c != '_') digits += c;
  if (digits.empty() || t.back() == '_') return std::nullopt;
  std::uint64_t v = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v, base);
  if (ec != std::errc{} || end != digits.data() + digits.size() || v > (std::uint64_t{1} << 53)) return std::nullopt;
  const double d = static_cast<double>(v);
  return negative ? -d : d;
}

ControllerExpectation load_controller_expectation(const yaml::Field& f) {
  ControllerExpectation e;
  e.source = {f.line(), f.path()};
  if (f.child("device_error").present()) {
    (void)f.expect_map({"device_error", "by"});
    const yaml::Field x = f.child("device_error");
    const std::string code = x.as_string("a device error code as the manual writes it (clm14.diagnostic:0E)");
    const auto c = parse_fault_code(code);
    if (!c || c->value >= 0)
      x.fail(
          fmt::format("expected a device error 'catalogue:code' as the manual writes it, such as "
                      "clm14.diagnostic:0E or wf725-726.traversing:96; got {}",
                      x.describe()));
    e.kind = ControllerExpectation::Kind::device_error;
    e.code = code;
    e.by = f.optional_duration("by");
    return e;
  }
  (void)f.expect_map({"controller", "value", "tolerance", "at", "by"});
  e.kind = ControllerExpectation::Kind::value;
  e.name = f.child("controller").as_string("the name of a value the controller shows (V600, task1.line)");
  const yaml::Field v = f.required("value", "the expected value: a number, 0x.. or 0b..");
  if (!v.node().IsScalar()) v.fail(fmt::format("expected a number, 0x.. or 0b..; got {}", v.describe()));
  e.value_text = v.node().Scalar();
  if (auto n = parse_expected_value(v.node().Scalar())) {
    e.value = *n;
  } else {
    e.value = v.as_number("a number, an integer 0x.. (hex) or 0b.. (binary)");
  }
  if (auto t = f.child("tolerance"); t.present()) e.tolerance = t.as_non_negative("a tolerance in the value's units");
  e.at = f.optional_duration("at");
  e.by = f.optional_duration("by");
  if (e.at && e.by) f.child("by").fail("use either 'at' (checked at that instant) or 'by' (reached no later than)");
  return e;
}

}  // namespace hil::runtime::detail
