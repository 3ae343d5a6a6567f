// SPDX-License-Identifier: MIT
// SINUMERIK System 3 / ELG data tapes (9.3, 9.4): leader (ignored) up to the first '%', then
//   %TEA1 LF                     machine data section
//   N396=180000 LF               word MD, signed decimal (≤ 9 digits)
//   N5002=00100010 LF            bit MD, 8 binary digits bit 7 … bit 0
//   M02 LF                       end of section (M30 too)
//   %SEA LF … M02 LF             setting data section
// plus "R<n>=<value>" blocks (R parameters) in any section. "( … )" comments are removed. The
// input may be a plain text file or a raw ISO tape image with even parity in bit 7 (detected from
// the first '%' = A5h); then every character's parity is checked (alarm 23). Blocks longer than
// 254 characters raise alarm 29; a wrong digit count alarm 32.
#include <fmt/format.h>

#include <bit>
#include <cctype>

#include "parsers.hpp"

namespace hil::profiles::detail {
namespace {

class SinumerikParser final : public ParameterSetParser {
 public:
  explicit SinumerikParser(std::shared_ptr<const Profile> p) : p_(std::move(p)) {}
  std::string_view format_name() const noexcept override { return "sinumerik-md"; }

  ParseResult parse(std::string_view text) const override { return parse(text, Settings{}); }

  ParseResult parse(std::string_view text, const Settings& settings) const override {
    ParseResult r;
    r.set.device = p_->device;
    bool block_parity = false;
    if (auto it = settings.find("block_parity"); it != settings.end())
      if (const auto* d = std::get_if<long double>(&it->second)) block_parity = *d != 0;
    const auto first = text.find_first_of("\x25\xA5");
    if (first == std::string_view::npos) {
      r.problems.push_back({0, "", "", "", "%TEA1 / %SEA header", "no '%' found: not a SINUMERIK data tape"});
      return r;
    }
    const bool tape_image = static_cast<unsigned char>(text[first]) == 0xA5;
    int line = 1;
    for (std::size_t i = 0; i < first; ++i)
      if ((static_cast<unsigned char>(text[i]) & 0x7F) == '\n') ++line;
    std::string section;  // "MD", "SD" or "" (outside)
    std::string block;
    bool parity_error = false;
    auto finish_block = [&](int at) {
      if (parity_error) {
        r.problems.push_back({at, "", "", block, "ISO even character parity",
                              "V.24 CHARACTER PARITY ERROR (alarm 23): a character has odd parity"});
        parity_error = false;
        block.clear();
        return;
      }
      if (block_parity && ((block.size() + 1) % 2) != 0)
        r.problems.push_back(
            {at, "", "", block, "even block parity",
             "block has an odd number of characters including LF (block parity; reported as alarm 23)"});
      if (block.size() + 1 > 254) {
        r.problems.push_back({at, "", "", block.substr(0, 32) + "…", "≤ 254 characters per block",
                              "BLOCK TOO LONG (MAX. 254 CHARACTERS) V.24 (alarm 29)"});
        block.clear();
        return;
      }
      handle_block(r, section, block, at);
      block.clear();
    };
    bool in_comment = false;
    for (std::size_t i = first; i < text.size(); ++i) {
      auto c = static_cast<unsigned char>(text[i]);
      if (tape_image) {
        if (std::popcount(c) % 2 != 0) parity_error = true;
        c &= 0x7F;
      }
      if (c == '\n') {
        finish_block(line);
        ++line;
        in_comment = false;
        continue;
      }
      if (c == '\r' || c == 0) continue;
      if (c == '(') in_comment = true;
      if (!in_comment) block += static_cast<char>(c);
      if (c == ')') in_comment = false;
    }
    if (!detail::trim(block).empty()) finish_block(line);
    return r;
  }

  std::string write(const ParameterSet& set) const override {
    std::string md, sd;
    for (const auto& e : set.entries) {
      const auto& v = parse_variant(*p_, e.ref, set);
      const std::string id = e.ref.id();
      const std::string value = value_text(v, e.value);
      if (id.starts_with("MD"))
        md += fmt::format("N{}={}\n", id.substr(2), value);
      else if (id.starts_with("SD"))
        sd += fmt::format("N{}={}\n", id.substr(2), value);
      else if (id.starts_with("R"))
        sd += fmt::format("{}={}\n", id, value);
    }
    std::string out;
    if (!md.empty()) out += "%TEA1\n" + md + "M02\n";
    if (!sd.empty()) out += "%SEA\n" + sd + "M02\n";
    return out;
  }

 private:
  void handle_block(ParseResult& r, std::string& section, const std::string& raw, int line) const {
    std::string b;
    for (char c : raw)
      if (c != ' ' && c != '\t') b += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    auto problem = [&](std::string param, std::string value, std::string rule, std::string msg) {
      r.problems.push_back({line, std::move(param), "", std::move(value), std::move(rule), std::move(msg)});
    };
    if (b.empty()) return;
    if (b.starts_with("%")) {
      if (b == "%TEA1")
        section = "MD";
      else if (b == "%SEA")
        section = "SD";
      else {
        section.clear();
        problem("", raw, "%TEA1 or %SEA",
                fmt::format("unknown tape identification '{}' (machine data %TEA1, setting data %SEA)", b));
      }
      return;
    }
    if (b == "M02" || b == "M30" || b == "\x03") {
      section.clear();
      return;
    }
    const auto eq = b.find('=');
    if (eq == std::string::npos) {
      problem("", raw, "N<number>=<value>", "V.24 DATA FORMAT ERROR (alarm 32): expected N<number>=<value>");
      return;
    }
    std::string id;
    if (b.starts_with("R")) {
      id = b.substr(0, eq);
    } else if (b.starts_with("N")) {
      if (section.empty()) {
        problem(b.substr(0, eq), raw, "inside %TEA1 / %SEA", "data block outside a %TEA1 or %SEA section");
        return;
      }
      id = section + b.substr(1, eq - 1);
    } else {
      problem("", raw, "N<number>=<value>", "V.24 DATA FORMAT ERROR (alarm 32): a block starts with N or R");
      return;
    }
    const std::string value = b.substr(eq + 1);
    const auto ref = p_->resolve(id);
    if (!ref) {
      problem(id, value, "known MD/SD/R number",
              fmt::format("{} does not exist (data channel: DATUM NOT PRESENT, alarm 3018)", id));
      return;
    }
    const auto& v = parse_variant(*p_, *ref, r.set);
    // digit counts (alarm 32): bits exactly 8 binary digits, words at most 9 digits
    const auto& f = v.fields.front();
    if (f.type == FieldType::bits && f.binary_text &&
        (value.size() != f.bits.bits || value.find_first_not_of("01") != std::string::npos)) {
      problem(ref->id(), value, fmt::format("{} binary digits", f.bits.bits),
              "V.24 DATA FORMAT ERROR (alarm 32): wrong number of digits");
      return;
    }
    // Leading zeros of the integer part carry no digit of the value: "0.18511" and ".18511" are the
    // same 5 digits (the writer prints the first; found by fuzzing the write/parse round trip).
    std::size_t digits = 0;
    bool leading = true;
    for (char c : value) {
      if (!std::isdigit(static_cast<unsigned char>(c))) {
        if (c == '.') leading = false;
        continue;
      }
      if (leading && c == '0') continue;
      leading = false;
      ++digits;
    }
    if (f.type != FieldType::bits && f.type != FieldType::hex &&
        digits > static_cast<std::size_t>(f.text.int_digits + f.text.frac_digits)) {
      problem(ref->id(), value, fmt::format("at most {} digits", f.text.int_digits + f.text.frac_digits),
              "V.24 DATA FORMAT ERROR (alarm 32): wrong number of digits");
      return;
    }
    auto parsed = parse_value_input(v, value);
    if (!parsed) {
      problem(ref->id(), value, "value", parsed.error());
      return;
    }
    if (r.set.find(ref->id())) problem(ref->id(), value, "once per tape", "given twice; the later block wins");
    r.set.set({*ref, std::move(*parsed), line, value});
  }

  std::shared_ptr<const Profile> p_;
};

}  // namespace

std::unique_ptr<ParameterSetParser> make_sinumerik_parser(std::shared_ptr<const Profile> p) {
  return std::make_unique<SinumerikParser>(std::move(p));
}

}  // namespace hil::profiles::detail
