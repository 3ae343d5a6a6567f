// SPDX-License-Identifier: MIT
// WF 725/726 machine data sets (§4.3): one MD per line, in engineering units or in either of
// the two transfer formats of the manual:
//   MD 11 = -24537          value in the MD's unit (µm, 10^-2 mm/min, ...)
//   MD 11 BCD 8002 4537     "decimal" format: packed BCD, bit 31 = sign
//   MD 11 HEX FFFF A027     binary format: 32-bit two's complement
#include <fmt/format.h>

#include <cctype>

#include "parsers.hpp"

namespace hil::profiles::detail {
namespace {

class WfParser final : public ParameterSetParser {
 public:
  explicit WfParser(std::shared_ptr<const Profile> p) : p_(std::move(p)) {}
  std::string_view format_name() const noexcept override { return "wf-md"; }

  ParseResult parse(std::string_view text) const override {
    ParseResult r;
    r.set.device = p_->device;
    for (const auto& line : split_lines(text)) {
      std::string_view t = trim(line.text);
      auto problem = [&](std::string param, std::string value, std::string rule, std::string msg) {
        r.problems.push_back({line.number, std::move(param), "", std::move(value), std::move(rule), std::move(msg)});
      };
      if (!(t.starts_with("MD") || t.starts_with("md"))) {
        problem("", std::string(t), "MD <n> = <value>",
                "expected 'MD <number> = <value>', 'MD <n> BCD <hex>' or 'MD <n> HEX <hex>'");
        continue;
      }
      t.remove_prefix(2);
      t = trim(t);
      std::size_t i = 0;
      while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) ++i;
      const std::string number(t.substr(0, i));
      std::string_view rest = trim(t.substr(i));
      if (number.empty()) {
        problem("", std::string(t), "MD <n>", "error 121: machine-data number missing or not decimal");
        continue;
      }
      const std::string id = "MD" + number;
      const auto ref = p_->resolve(id);
      if (!ref) {
        problem(id, std::string(rest), "MD 1..50",
                fmt::format("error 121: machine-data number {} is 0 or above 50", number));
        continue;
      }
      const auto& v = parse_variant(*p_, *ref, r.set);
      std::expected<ParamValue, std::string> value;
      std::string value_text_in(rest);
      if (rest.starts_with("=") || rest.starts_with(":")) {
        rest = trim(rest.substr(1));
        value_text_in = std::string(rest);
        value = parse_value_input(v, rest);
      } else if (rest.starts_with("BCD") || rest.starts_with("bcd") || rest.starts_with("HEX") ||
                 rest.starts_with("hex") || rest.starts_with("BIN") || rest.starts_with("bin")) {
        value = decode_wire(*p_, v, rest);
      } else {
        value = parse_value_input(v, rest);
      }
      if (!value) {
        problem(id, value_text_in, "MD value", value.error());
        continue;
      }
      if (r.set.find(id)) problem(id, value_text_in, "once per set", "given twice; the later line wins");
      r.set.set({*ref, std::move(*value), line.number, value_text_in});
    }
    return r;
  }

  std::string write(const ParameterSet& set) const override {
    std::string out;
    for (const auto& e : set.entries) {
      const auto& v = parse_variant(*p_, e.ref, set);
      out += fmt::format("MD {} = {}\n", e.ref.spec->number, value_text(v, e.value));
    }
    return out;
  }

 private:
  std::shared_ptr<const Profile> p_;
};

}  // namespace

std::unique_ptr<ParameterSetParser> make_wf_parser(std::shared_ptr<const Profile> p) {
  return std::make_unique<WfParser>(std::move(p));
}

}  // namespace hil::profiles::detail
