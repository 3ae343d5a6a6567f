// SPDX-License-Identifier: MIT
#include "hil/serial/clm14/serial_error.hpp"

#include <fmt/format.h>

namespace hil::serial::clm14 {

namespace {
class Category final : public std::error_category {
 public:
  const char* name() const noexcept override { return "clm14-serial"; }
  std::string message(int c) const override {
    return fmt::format("CLM1.4 serial error {:02d} (see the device profile's serial_errors for the device text)", c);
  }
};
}  // namespace

const std::error_category& serial_error_category() noexcept {
  static const Category c;
  return c;
}

std::string make_error_body(int code, std::string_view text20) {
  std::string t(text20.substr(0, 20));
  t.resize(20, ' ');
  return fmt::format("01 {:02d} {} ", code, t);
}

std::optional<ErrorReport> parse_error_body(std::string_view body) {
  // "01 ff text..." (the code is decimal as printed in the manual's table: 01..25)
  if (body.size() < 5 || body.substr(0, 3) != "01 ") return std::nullopt;
  const char a = body[3], b = body[4];
  if (a < '0' || a > '9' || b < '0' || b > '9') return std::nullopt;
  ErrorReport r;
  r.code = (a - '0') * 10 + (b - '0');
  std::string_view t = body.size() > 6 ? body.substr(6) : std::string_view{};
  while (!t.empty() && t.back() == ' ') t.remove_suffix(1);
  r.text = std::string(t);
  return r;
}

}  // namespace hil::serial::clm14
