// SPDX-License-Identifier: MIT
// S5 data-block listings (IP247 MD DB, §6.3.8.1): one data word per line, as a STEP 5 PG lists a DB:
//   0: KF = +00070        signed 16-bit decimal
//   1: KH = 0044          16-bit hex
//   2: KY = 066,001       two bytes, decimal, DL,DR
//   5: DH = 00001388      32-bit hex filling words 5 and 6 (convenience)
//   27: DD = -400000      32-bit decimal filling words 27 and 28 (convenience)
// "DW5" for "5" and a missing ':' / '=' are accepted. The image is then decoded field by field
// from each parameter's word offset.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <map>

#include "parsers.hpp"

namespace hil::profiles::detail {
namespace {

struct Word {
  std::uint16_t value = 0;
  int line = 0;
  std::string text;
};

std::optional<long long> parse_int(std::string_view s, int base) {
  long long v = 0;
  bool neg = false;
  if (!s.empty() && (s.front() == '+' || s.front() == '-')) {
    neg = s.front() == '-';
    s.remove_prefix(1);
  }
  if (s.empty()) return std::nullopt;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v, base);
  if (ec != std::errc{} || p != s.data() + s.size()) return std::nullopt;
  return neg ? -v : v;
}

class S5DbParser final : public ParameterSetParser {
 public:
  explicit S5DbParser(std::shared_ptr<const Profile> p) : p_(std::move(p)) {
    for (const auto& spec : p_->parameters)
      for (const auto& f : spec.variants.front().fields) {
        const Encoding e = f.encoding.value_or(p_->wire.encoding);
        const int n = e == Encoding::kd || (e == Encoding::fixed && f.fixed.word.bits == 32) ? 2 : 1;
        if (f.word >= 0) size_ = std::max(size_, f.word + n);
      }
  }
  std::string_view format_name() const noexcept override { return "s5-db"; }

  ParseResult parse(std::string_view text) const override {
    ParseResult r;
    r.set.device = p_->device;
    std::map<int, Word> words;
    for (const auto& line : split_lines(text)) {
      auto problem = [&](std::string msg) {
        r.problems.push_back(
            {line.number, "", "", std::string(trim(line.text)), "n: KF|KH|KY|DH|DD = value", std::move(msg)});
      };
      std::string_view t = trim(line.text);
      // The header line of a STEP 5 DB listing ("DB1"): the DB number travels with the transfer.
      if ((t.starts_with("DB") || t.starts_with("db")) && t.size() > 2 &&
          std::all_of(t.begin() + 2, t.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }))
        continue;
      if (t.starts_with("DW") || t.starts_with("dw")) t.remove_prefix(2);
      t = trim(t);
      std::size_t i = 0;
      while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) ++i;
      auto n = parse_int(t.substr(0, i), 10);
      if (!n) {
        problem("expected a data word number at the start of the line");
        continue;
      }
      t = trim(t.substr(i));
      if (t.starts_with(":")) t = trim(t.substr(1));
      const std::string fmt_s(t.substr(0, 2));
      t = trim(t.substr(std::min<std::size_t>(2, t.size())));
      if (t.starts_with("=")) t = trim(t.substr(1));
      if (t.ends_with(";")) t = trim(t.substr(0, t.size() - 1));
      const int w = static_cast<int>(*n);
      if (w < 0 || w >= size_) {
        problem(fmt::format("DW {} is outside the {}-word block", w, size_));
        continue;
      }
      auto put = [&](int at, std::uint16_t v) {
        if (words.count(at)) problem(fmt::format("DW {} given twice; the later line wins", at));
        words[at] = Word{v, line.number, std::string(t)};
      };
      if (fmt_s == "KF" || fmt_s == "kf") {
        auto v = parse_int(t, 10);
        if (!v || *v < -32768 || *v > 32767) {
          problem(fmt::format("KF '{}' is not a 16-bit signed decimal", t));
          continue;
        }
        put(w, static_cast<std::uint16_t>(*v));
      } else if (fmt_s == "KH" || fmt_s == "kh") {
        auto v = parse_int(t, 16);
        if (!v || *v < 0 || *v > 0xFFFF || t.size() > 4) {
          problem(fmt::format("KH '{}' is not 1-4 hex digits", t));
          continue;
        }
        put(w, static_cast<std::uint16_t>(*v));
      } else if (fmt_s == "KY" || fmt_s == "ky") {
        const auto comma = t.find(',');
        auto hi = comma == std::string_view::npos ? std::nullopt : parse_int(trim(t.substr(0, comma)), 10);
        auto lo = comma == std::string_view::npos ? std::nullopt : parse_int(trim(t.substr(comma + 1)), 10);
        if (!hi || !lo || *hi < 0 || *hi > 255 || *lo < 0 || *lo > 255) {
          problem(fmt::format("KY '{}' is not two bytes 0..255 'DL,DR'", t));
          continue;
        }
        put(w, static_cast<std::uint16_t>((*hi << 8) | *lo));
      } else if (fmt_s == "DH" || fmt_s == "dh" || fmt_s == "DD" || fmt_s == "dd") {
        const bool hex = fmt_s[1] == 'H' || fmt_s[1] == 'h';
        std::string digits(t);
        std::erase(digits, ' ');
        auto v = parse_int(digits, hex ? 16 : 10);
        if (!v || (hex && (*v < 0 || *v > 0xFFFFFFFFLL || digits.size() > 8)) ||
            (!hex && (*v < INT32_MIN || *v > INT32_MAX))) {
          problem(fmt::format("{} '{}' is not a 32-bit value", fmt_s, t));
          continue;
        }
        if (w + 1 >= size_) {
          problem(fmt::format("a double word at DW {} leaves the block", w));
          continue;
        }
        const auto u = static_cast<std::uint32_t>(*v);
        put(w, static_cast<std::uint16_t>(u >> 16));
        put(w + 1, static_cast<std::uint16_t>(u & 0xFFFFu));
      } else {
        problem(fmt::format("unknown data format '{}' (expected KF, KH, KY, DH or DD)", fmt_s));
      }
    }
    // decode every parameter whose words are all present
    for (const auto& spec : p_->parameters) {
      const ParamRef ref{&spec, std::nullopt};
      const auto& v = parse_variant(*p_, ref, r.set);
      std::string wire;
      bool complete = true, any = false;
      int line = 0;
      std::string src;
      for (const auto& f : v.fields) {
        const Encoding e = f.encoding.value_or(p_->wire.encoding);
        const int n = e == Encoding::kd || (e == Encoding::fixed && f.fixed.word.bits == 32) ? 2 : 1;
        for (int k = 0; k < n; ++k) {
          auto it = words.find(f.word + k);
          if (it == words.end()) {
            complete = false;
            continue;
          }
          any = true;
          if (!line) line = it->second.line;
          wire += fmt::format("{:04X} ", it->second.value);
        }
      }
      if (!any) continue;
      if (!complete) {
        r.problems.push_back({line, spec.id, "", "", "all words of the field",
                              fmt::format("{} ({}) is incomplete: a data word is missing", spec.id, v.name)});
        continue;
      }
      auto value = decode_wire(*p_, v, wire);
      if (!value) {
        r.problems.push_back({line, spec.id, "", wire, "word encoding", value.error()});
        continue;
      }
      std::string shown = value_text(v, *value);
      r.set.set({ref, std::move(*value), line, std::move(shown)});
    }
    return r;
  }

  std::string write(const ParameterSet& set) const override {
    std::map<int, std::uint16_t> words;
    std::map<int, Encoding> kinds;
    for (const auto& e : set.entries) {
      const auto& v = parse_variant(*p_, e.ref, set);
      auto img = encode_value(*p_, v, e.value);
      if (!img) continue;
      std::size_t wi = 0;
      for (const auto& f : v.fields) {
        const Encoding enc = f.encoding.value_or(p_->wire.encoding);
        const int n = enc == Encoding::kd || (enc == Encoding::fixed && f.fixed.word.bits == 32) ? 2 : 1;
        for (int k = 0; k < n && wi < img->words.size(); ++k, ++wi) {
          words[f.word + k] |= img->words[wi];
          if (!kinds.count(f.word + k)) kinds[f.word + k] = enc;
        }
      }
    }
    std::string out;
    for (const auto& [w, value] : words) {
      switch (kinds[w]) {
        case Encoding::kf:
          out += fmt::format("{}: KF = {:+06d}\n", w, static_cast<std::int16_t>(value));
          break;
        case Encoding::byte_l:
        case Encoding::byte_r:
        case Encoding::ky:
          out += fmt::format("{}: KY = {:03d},{:03d}\n", w, value >> 8, value & 0xFF);
          break;
        default:
          out += fmt::format("{}: KH = {:04X}\n", w, value);
      }
    }
    return out;
  }

 private:
  std::shared_ptr<const Profile> p_;
  int size_ = 0;
};

}  // namespace

std::unique_ptr<ParameterSetParser> make_s5db_parser(std::shared_ptr<const Profile> p) {
  return std::make_unique<S5DbParser>(std::move(p));
}

}  // namespace hil::profiles::detail
