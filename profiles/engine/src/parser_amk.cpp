// SPDX-License-Identifier: MIT
// AMKASYN SF parameter sets: the FB 207 init DB and the FB 208 commanding DB of one SF, one data
// item per line with its stored (raw) value, as the manual's examples write them:
//   INIT DR0 = 1        init DB: SF type 1 (FIPW)
//   DL1 = 2             commanding DB: SFKMD-BA
//   DW3 = 4             SF cycle time 4 × 0.5 ms = 2 ms
//   DD10 = 20000        32-bit value (low word first in the DB)
// Values are decimal (KF/KD) or hex with 0x / a trailing 'h'. The meaning of commanding-DB
// addresses depends on the SF type, fct and BA, so the header is read before the rest.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "hil/profiles/db_integer_text.hpp"
#include "parsers.hpp"

namespace hil::profiles::detail {
namespace {

struct RawItem {
  std::string id;
  std::int64_t raw = 0;
  int line = 0;
  std::string text;
};

bool is_header(std::string_view id) {
  return id.starts_with("INIT") || id == "DR0" || id == "DL0" || id == "DR1" || id == "DL1";
}

class AmkParser final : public ParameterSetParser {
 public:
  explicit AmkParser(std::shared_ptr<const Profile> p) : p_(std::move(p)) {}
  std::string_view format_name() const noexcept override { return "amk-db"; }

  ParseResult parse(std::string_view text) const override { return parse(text, Settings{}); }

  ParseResult parse(std::string_view text, const Settings& settings) const override {
    ParseResult r;
    r.set.device = p_->device;
    std::vector<RawItem> items;
    for (const auto& line : split_lines(text)) {
      std::string_view t = trim(line.text);
      auto problem = [&](std::string param, std::string value, std::string msg) {
        r.problems.push_back(
            {line.number, std::move(param), "", std::move(value), "[INIT] DRn|DLn|DWn|DDn = value", std::move(msg)});
      };
      bool init = false;
      if (t.size() > 4 && (t.starts_with("INIT") || t.starts_with("init")) &&
          (t[4] == ' ' || t[4] == '\t' || t[4] == '_')) {
        init = true;
        t = trim(t.substr(5));
      }
      std::size_t i = 0;
      while (i < t.size() && std::isalnum(static_cast<unsigned char>(t[i]))) ++i;
      std::string addr(t.substr(0, i));
      for (auto& c : addr) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      t = trim(t.substr(i));
      if (t.starts_with("=") || t.starts_with(":")) t = trim(t.substr(1));
      const bool shape =
          addr.size() >= 3 &&
          (addr.starts_with("DR") || addr.starts_with("DL") || addr.starts_with("DW") || addr.starts_with("DD")) &&
          addr.find_first_not_of("0123456789", 2) == std::string::npos;
      if (!shape) {
        problem(addr, std::string(t),
                "expected a data address DRn, DLn, DWn or DDn (INIT prefix for the FB 207 init DB)");
        continue;
      }
      // Digits only (checked above), but any number of them: "DR99999999999" must be a problem, not
      // std::stoi's out_of_range (found by fuzzing). Five digits already exceed every DB.
      const std::string digits = addr.substr(2);
      const int word = digits.size() > 5 ? 99999 : std::stoi(digits);
      if (word > (init ? 9 : 33) || (addr.starts_with("DD") && word > (init ? 8 : 32))) {
        problem(addr, std::string(t),
                fmt::format("{} is outside the {} DB", addr, init ? "10-word init" : "34-word commanding"));
        continue;
      }
      auto raw = parse_db_integer(t);
      if (!raw) {
        problem(addr, std::string(t), fmt::format("'{}' is not an integer (decimal, 0x… or …h)", t));
        continue;
      }
      items.push_back({init ? "INIT_" + addr : addr, *raw, line.number, std::string(t)});
    }
    // header first so that the SF type / fct / BA select the meanings of the other addresses
    for (int pass = 0; pass < 2; ++pass)
      for (const auto& it : items) {
        if (is_header(it.id) != (pass == 0)) continue;
        add(r, it, settings);
      }
    std::stable_sort(r.problems.begin(), r.problems.end(),
                     [](const Problem& a, const Problem& b) { return a.line < b.line; });
    return r;
  }

  std::string write(const ParameterSet& set) const override { return write(set, Settings{}); }

  std::string write(const ParameterSet& set, const Settings& settings) const override {
    std::string init, cmd;
    const Scope scope(*p_, &set, settings);
    for (const auto& e : set.entries) {
      const ParamVariant* vp = select_variant(e.ref, scope);
      const auto& v = vp ? *vp : e.ref.spec->variants.front();
      if (v.fields.empty() || e.value.empty()) continue;
      const auto* d = std::get_if<Decimal>(&e.value[0]);
      if (!d) continue;
      const FixedPointFormat wide{TwosComplementFormat{64, true}, v.fields[0].fixed.lsb_num, v.fields[0].fixed.lsb_den};
      auto raw = make_fixed_point(*d, wide);
      if (!raw) continue;
      const std::string id = e.ref.id();
      if (id.starts_with("INIT_"))
        init += fmt::format("INIT {} = {}\n", id.substr(5), *raw);
      else
        cmd += fmt::format("{} = {}\n", id, *raw);
    }
    return init + cmd;
  }

 private:
  void add(ParseResult& r, const RawItem& it, const Settings& settings) const {
    auto problem = [&](std::string rule, std::string msg) {
      r.problems.push_back({it.line, it.id, "", it.text, std::move(rule), std::move(msg)});
    };
    const auto ref = p_->resolve(it.id);
    if (!ref) {
      problem("defined address", fmt::format("{} is not a data item of the {} DB", it.id,
                                             it.id.starts_with("INIT") ? "init" : "commanding"));
      return;
    }
    const Scope scope(*p_, &r.set, settings);
    const ParamVariant* v = select_variant(*ref, scope);
    if (!v) {
      problem("address used by this SF",
              fmt::format("{} is not used by SF type {} (fct/BA as given): use the addresses of its commanding DB",
                          it.id, scope.lookup("sf_type") ? to_string(*scope.lookup("sf_type")) : "?"));
      return;
    }
    const auto& f = v->fields.front();
    const Encoding enc = f.encoding.value_or(p_->wire.encoding);
    TwosComplementFormat word = f.fixed.word;
    if (enc == Encoding::byte_l || enc == Encoding::byte_r) word = {8, false};
    if (auto w = make_twos_complement(it.raw, word); !w) {
      problem(fmt::format("{}-bit {} value", word.bits, word.is_signed ? "signed" : "unsigned"), w.error().message);
      return;
    }
    auto value =
        parse_fixed_point(it.raw, FixedPointFormat{TwosComplementFormat{64, true}, f.fixed.lsb_num, f.fixed.lsb_den});
    if (!value) {
      problem("value", value.error().message);
      return;
    }
    if (r.set.find(it.id)) problem("once per set", "given twice; the later line wins");
    r.set.set({*ref, ParamValue{*value}, it.line, it.text});
  }

  std::shared_ptr<const Profile> p_;
};

}  // namespace

std::unique_ptr<ParameterSetParser> make_amk_parser(std::shared_ptr<const Profile> p) {
  return std::make_unique<AmkParser>(std::move(p));
}

}  // namespace hil::profiles::detail
