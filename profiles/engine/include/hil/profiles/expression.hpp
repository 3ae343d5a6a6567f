// SPDX-License-Identifier: MIT
#pragma once
// The small expression language of the profiles: applicability conditions ("encoder == 'I'"),
// range bounds that depend on other settings ("20000 * resolution") and cross-parameter rules
// ("MD12 < MD11 < MD13 < MD14", "Ax07 <= Ax06", "Ax06 <= Ax12.rpm / 60 * Ax01").
//
//   or:   a || b, a or b          and:  a && b, a and b         not:  !a, not a
//   comparison (chains like Python): a < b <= c, ==, !=, >, >=;  a in [1, 2, 4]
//   arithmetic: + - * / %, unary -, parentheses
//   literals: 12, -0.5, 0x1F, 'text';   names: MD49, Ax12.rpm, resolution, module
//   functions: if(cond, a, b), abs(x), min(a, b), max(a, b), defined(name), pow2(x) (x is 2^n),
//              digit(x, n) (n-th decimal digit from the right), bit(x, n)
//
// Numbers are long double (exact for the integers and short decimals of the manuals); strings compare
// by text. Pure: names are resolved through the caller's lookup.

#include <expected>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace hil::profiles {

using ExprValue = std::variant<long double, std::string>;

struct EvalError {
  bool undefined = false;  ///< a name had no value (parameter absent, no default): rule not evaluable
  std::string message;
};

class Expression {
 public:
  struct Node;
  using Lookup = std::function<std::optional<ExprValue>(std::string_view name)>;

  /// Parses `text`; the error names the position and what was expected.
  [[nodiscard]] static std::expected<Expression, std::string> parse(std::string_view text);

  [[nodiscard]] std::expected<ExprValue, EvalError> evaluate(const Lookup& lookup) const;
  /// Evaluates and converts to bool (number != 0, string non-empty).
  [[nodiscard]] std::expected<bool, EvalError> test(const Lookup& lookup) const;
  /// Every name the expression reads, in order of first use (for violation reports).
  [[nodiscard]] std::vector<std::string> names() const;
  [[nodiscard]] const std::string& text() const noexcept { return text_; }
  [[nodiscard]] bool empty() const noexcept { return root_ == nullptr; }

 private:
  std::shared_ptr<const Node> root_;
  std::string text_;
};

/// "12", "-0.5", "abc" for reports.
[[nodiscard]] std::string to_string(const ExprValue& v);

}  // namespace hil::profiles
