// SPDX-License-Identifier: MIT
// The rule language: parse arbitrary text and evaluate it against a fixed name table.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hil/profiles/expression.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto e = hil::profiles::Expression::parse(text);
  if (!e) return 0;
  const auto lookup = [](std::string_view n) -> std::optional<hil::profiles::ExprValue> {
    if (n == "MD11") return -24537.0L;
    if (n == "MD12") return -42728.0L;
    if (n == "encoder") return std::string("I");
    if (n.starts_with("A")) return 100.0L;
    return std::nullopt;
  };
  (void)e->evaluate(lookup);
  (void)e->test(lookup);
  (void)e->names();
  return 0;
}
