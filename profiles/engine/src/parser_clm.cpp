// SPDX-License-Identifier: MIT
// CLM1.4 parameter sets: one K telegram per line as sent over X6/X8 (§9.2, Figs 9-14…16),
//   #␣K␣A112␣03000␣10.0$88     (checksum verified when present; '!' accepted for '#')
// or the bare form "A112 03000 10.0" / "A112 = 03000 10.0".
#include <fmt/format.h>

#include <cctype>

#include "parsers.hpp"

namespace hil::profiles::detail {
namespace {

class ClmParser final : public ParameterSetParser {
 public:
  explicit ClmParser(std::shared_ptr<const Profile> p) : p_(std::move(p)) {}

  std::string_view format_name() const noexcept override { return "clm-telegram"; }

  ParseResult parse(std::string_view text) const override {
    ParseResult r;
    r.set.device = p_->device;
    for (const auto& line : split_lines(text, false)) {
      std::string_view l = line.text;
      if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
      const std::string_view t = trim(l);
      if (t.starts_with(";") || t.starts_with("//")) continue;
      auto problem = [&](std::string param, std::string value, std::string rule, std::string msg) {
        r.problems.push_back({line.number, std::move(param), "", std::move(value), std::move(rule), std::move(msg)});
      };
      std::string_view id, data;
      if (t.starts_with("#") || t.starts_with("!")) {
        // <C1><station>K␣<id>␣<data>[$hh]
        std::string_view body = l.substr(l.find_first_of("#!"));
        std::string_view payload = body;
        if (const auto dollar = body.rfind('$'); dollar != std::string_view::npos) {
          payload = body.substr(0, dollar);
          const std::string_view cs = trim(body.substr(dollar + 1));
          unsigned v = 0;
          bool ok = cs.size() == 2;
          for (char c : cs) {
            if (!std::isxdigit(static_cast<unsigned char>(c)))
              ok = false;
            else
              v = v * 16 + static_cast<unsigned>(
                               std::isdigit(static_cast<unsigned char>(c)) ? c - '0' : (std::toupper(c) - 'A' + 10));
          }
          if (!ok) {
            problem("", std::string(cs), "checksum $hh",
                    "RS Format Error (serial error 02): checksum must be 2 hex digits");
            continue;
          }
          const auto want = clm_checksum(payload);
          if (v != want) {
            problem("", std::string(cs), fmt::format("checksum {:02X}", want),
                    fmt::format("RS Checksum Error (serial error 04): telegram says {:02X}, content gives {:02X}", v,
                                want));
            continue;
          }
        }
        const char station = payload.size() > 1 ? payload[1] : '?';
        if (!(station == ' ' || (station >= '1' && station <= '9') || (station >= 'A' && station <= 'W'))) {
          problem(
              "", std::string(1, station), "station ␣, 1-9, A-W",
              "RS Format Error (serial error 02): station must be a space (RS232) or 1-9/A-W (RS485 stations 1-32)");
          continue;
        }
        if (payload.size() < 5 || payload[2] != 'K' || payload[3] != ' ') {
          problem("", std::string(trim(payload)), "#sK␣xxyy␣data",
                  "RS Format Error (serial error 02): not a parameter telegram");
          continue;
        }
        std::string_view rest = payload.substr(4);
        id = rest.substr(0, 4);
        data = rest.size() > 5 ? rest.substr(5) : std::string_view{};
        if (rest.size() > 4 && rest[4] != ' ') {
          problem(std::string(rest), "", "#sK␣xxyy␣data",
                  "RS Format Error (serial error 02): space expected after the parameter number");
          continue;
        }
      } else {
        const auto sp = t.find_first_of(" \t=");
        id = t.substr(0, sp);
        data = sp == std::string_view::npos ? std::string_view{} : trim(t.substr(sp));
        if (data.starts_with("=")) data = trim(data.substr(1));
      }
      const auto ref = p_->resolve(id);
      if (!ref) {
        const bool block_ok = id.size() == 4 && (id.starts_with("B0") || id.starts_with("C0") ||
                                                 (id[0] == 'A' && id[1] >= '1' && id[1] <= '4'));
        const bool digits = id.size() == 4 && std::isdigit(static_cast<unsigned char>(id[2])) &&
                            std::isdigit(static_cast<unsigned char>(id[3]));
        problem(std::string(id), std::string(data), "known parameter",
                !block_ok ? "Invalid Param Block (serial error 11): block must be B0, A1..A4 or C0"
                : !digits ? "Wrong RS Param # (serial error 06): parameter number not decimal"
                          : "Param. # too large (serial error 07): no such parameter");
        continue;
      }
      const auto& v = parse_variant(*p_, *ref, r.set);
      auto value = decode_wire(*p_, v, data);
      if (!value) {
        problem(ref->id(), std::string(data), "template " + templ(v), value.error());
        continue;
      }
      if (r.set.find(ref->id()))
        problem(ref->id(), std::string(data), "once per set", "given twice; the later line wins");
      r.set.set({*ref, std::move(*value), line.number, std::string(data)});
    }
    return r;
  }

  std::string write(const ParameterSet& set) const override {
    std::string out;
    for (const auto& e : set.entries) {
      const auto& v = parse_variant(*p_, e.ref, set);
      auto img = encode_value(*p_, v, e.value);
      std::string data = img ? img->text : e.text;
      if (img) data = keep_negative_zeros(data, e.text);
      const std::string body = fmt::format("# K {} {}", e.ref.id(), data);
      out += fmt::format("{}${:02X}\n", body, clm_checksum(body));
    }
    return out;
  }

 private:
  /// "-00000.000" and "+00000.000" are the same value; keep the sign the source had (A125's
  /// manual string is "-00000.000") so an unchanged set is rewritten byte-exact.
  static std::string keep_negative_zeros(const std::string& canonical, std::string_view source) {
    auto split = [](std::string_view s) {
      std::vector<std::string_view> out;
      for (std::size_t i = 0; i < s.size();) {
        while (i < s.size() && s[i] == ' ') ++i;
        std::size_t j = i;
        while (j < s.size() && s[j] != ' ') ++j;
        if (j > i) out.push_back(s.substr(i, j - i));
        i = j;
      }
      return out;
    };
    auto c = split(canonical);
    const auto o = split(source);
    if (c.size() != o.size()) return canonical;
    std::string out;
    for (std::size_t i = 0; i < c.size(); ++i) {
      std::string tok(c[i]);
      if (tok.starts_with("+") && o[i].starts_with("-") && o[i].size() == tok.size() &&
          o[i].substr(1).find_first_not_of("0.") == std::string_view::npos &&
          tok.substr(1).find_first_not_of("0.") == std::string::npos)
        tok[0] = '-';
      out += (i ? " " : "") + tok;
    }
    return out;
  }
  static std::string templ(const ParamVariant& v) {
    std::string s;
    for (const auto& f : v.fields) {
      if (!s.empty()) s += ' ';
      switch (f.type) {
        case FieldType::io_address:
          s += "Ix.xx.x";
          break;
        case FieldType::hex:
          s += std::string(static_cast<std::size_t>(f.hex_digits), 'h');
          break;
        case FieldType::reserved:
          s += f.fixed_text.empty() ? "(empty)" : f.fixed_text;
          break;
        default:
          s += f.text.to_string();
      }
    }
    return s;
  }
  std::shared_ptr<const Profile> p_;
};

}  // namespace

std::unique_ptr<ParameterSetParser> make_clm_parser(std::shared_ptr<const Profile> p) {
  return std::make_unique<ClmParser>(std::move(p));
}

}  // namespace hil::profiles::detail
