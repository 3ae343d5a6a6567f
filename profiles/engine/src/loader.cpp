// SPDX-License-Identifier: MIT
// YAML → Profile. Internally a hil::yaml::Failure carries a ConfigError up to the boundary (the
// same read_document as the scenario loader), where it becomes the std::expected error; nothing escapes.
#include "hil/profiles/loader.hpp"

#include "hil/config/yaml_config.hpp"
#include "hil/config/yaml_field.hpp"
#include "hil/core/data_dir.hpp"
#include "hil/core/text_file.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <unistd.h>
#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>

#include "hil/profiles/validation.hpp"
#include "hil/profiles/wire.hpp"

namespace hil::profiles {
namespace {

class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const YAML::Node& n, const std::string& key, const std::string& msg) const {
    // A null node (absent key) has no position of its own: the error then names the key only.
    throw hil::yaml::Failure{hil::yaml::error_at(!n.IsDefined() || n.IsNull() ? YAML::Node() : n, {file_, key}, msg)};
  }

  std::string str(const YAML::Node& n, const std::string& key, bool required = false) const {
    if (!n || n.IsNull()) {
      if (required) fail(n, key, "required key missing");
      return {};
    }
    if (!n.IsScalar()) fail(n, key, "expected a text value");
    return n.Scalar();
  }

  Decimal dec(const YAML::Node& n, const std::string& key) const {
    auto d = parse_decimal(str(n, key, true));
    if (!d) fail(n, key, d.error());
    return *d;
  }

  std::int64_t integer(const YAML::Node& n, const std::string& key) const {
    auto d = dec(n, key);
    auto i = d.to_integer();
    if (!i) fail(n, key, i.error());
    return *i;
  }

  Expression expr(const YAML::Node& n, const std::string& key) const {
    const std::string s = str(n, key);
    if (s.empty()) return {};
    auto e = Expression::parse(s);
    if (!e) fail(n, key, e.error());
    return *e;
  }

  ExprValue expr_value(const YAML::Node& n, const std::string& key) const {
    const std::string s = str(n, key, true);
    if (auto d = parse_decimal(s)) return d->to_long_double();
    return s;
  }

  Bound bound(const YAML::Node& n, const std::string& key) const {
    Bound b;
    if (!n || n.IsNull()) return b;
    const std::string s = str(n, key);
    if (auto d = parse_decimal(s)) {
      b.literal = *d;
      return b;
    }
    auto e = Expression::parse(s);
    if (!e) fail(n, key, fmt::format("neither a number nor an expression: {}", e.error()));
    b.expr = *e;
    return b;
  }

  std::vector<RangeRule> ranges(const YAML::Node& n, const std::string& key) const {
    std::vector<RangeRule> out;
    if (!n || n.IsNull()) return out;
    auto one = [&](const YAML::Node& m, const std::string& k) {
      RangeRule r;
      if (m.IsSequence()) {
        if (m.size() != 2) fail(m, k, "a range list needs exactly [min, max]");
        r.min = bound(m[0], k + "[0]");
        r.max = bound(m[1], k + "[1]");
      } else if (m.IsMap()) {
        r.when = expr(m["when"], k + ".when");
        r.min = bound(m["min"], k + ".min");
        r.max = bound(m["max"], k + ".max");
        if (m["values"]) {
          if (!m["values"].IsSequence()) fail(m["values"], k + ".values", "expected a list of numbers");
          for (std::size_t i = 0; i < m["values"].size(); ++i) r.allowed.push_back(dec(m["values"][i], k + ".values"));
        }
      } else {
        fail(m, k, "expected [min, max] or {min:, max:, when:, values:}");
      }
      return r;
    };
    if (n.IsSequence() && n.size() > 0 && n[0].IsMap()) {
      for (std::size_t i = 0; i < n.size(); ++i) out.push_back(one(n[i], fmt::format("{}[{}]", key, i)));
    } else {
      out.push_back(one(n, key));
    }
    return out;
  }

  std::vector<StepRule> steps(const YAML::Node& n, const std::string& key) const {
    std::vector<StepRule> out;
    if (!n || n.IsNull()) return out;
    if (n.IsSequence()) {
      for (std::size_t i = 0; i < n.size(); ++i) {
        const auto k = fmt::format("{}[{}]", key, i);
        if (!n[i].IsMap()) fail(n[i], k, "expected {when:, step:}");
        out.push_back({expr(n[i]["when"], k + ".when"), bound(n[i]["step"], k + ".step")});
      }
    } else {
      out.push_back({{}, bound(n, key)});
    }
    return out;
  }

  FieldSpec field(const YAML::Node& n, const std::string& key, const WireSpec& wire) const {
    FieldSpec f;
    f.name = str(n["name"], key + ".name");
    if (f.name.empty()) f.name = "value";
    f.meaning = str(n["meaning"], key + ".meaning");
    f.unit = str(n["unit"], key + ".unit");
    f.note = str(n["note"], key + ".note");
    const std::string type = str(n["type"], key + ".type");
    if (type.empty() || type == "number")
      f.type = FieldType::number;
    else if (type == "choice")
      f.type = FieldType::choice;
    else if (type == "io")
      f.type = FieldType::io_address;
    else if (type == "hex")
      f.type = FieldType::hex;
    else if (type == "bits")
      f.type = FieldType::bits;
    else if (type == "reserved")
      f.type = FieldType::reserved;
    else
      fail(n["type"], key + ".type", "expected number, choice, io, hex, bits or reserved");

    if (const std::string fmt_s = str(n["format"], key + ".format"); !fmt_s.empty()) {
      auto tf = DecimalTextFormat::parse(fmt_s);
      if (!tf) fail(n["format"], key + ".format", tf.error());
      f.text = *tf;
    } else {
      f.text = DecimalTextFormat{DecimalTextFormat::Sign::always, 17, 0};
      if (f.type == FieldType::number || f.type == FieldType::choice || f.type == FieldType::bits) {
        // no text template: a word-encoded value; keep a generous text form
        f.text = DecimalTextFormat{DecimalTextFormat::Sign::always, 17, 0};
      }
    }
    if (n["decimals"]) f.text.frac_digits = static_cast<int>(integer(n["decimals"], key + ".decimals"));
    if (f.type == FieldType::hex) {
      f.hex_digits = n["digits"] ? static_cast<int>(integer(n["digits"], key + ".digits")) : 4;
      if (f.hex_digits < 1 || f.hex_digits > 16) fail(n["digits"], key + ".digits", "hex fields have 1..16 digits");
    }
    if (f.type == FieldType::io_address) {
      const auto& io = n["io"];
      if (io && io.IsSequence())
        for (std::size_t i = 0; i < io.size(); ++i) f.io_types.push_back(str(io[i], key + ".io"));
      if (f.io_types.empty()) f.io_types = {"I", "Q", "M"};
      for (const auto& t : f.io_types)
        if (t != "I" && t != "Q" && t != "M") fail(io, key + ".io", "I/O types are I, Q and M");
    }
    if (f.type == FieldType::reserved) f.fixed_text = str(n["text"], key + ".text");
    f.ranges = ranges(n["range"], key + ".range");
    if (n["values"]) {
      RangeRule r;
      const auto& vs = n["values"];
      if (!vs.IsSequence()) fail(vs, key + ".values", "expected a list of numbers");
      for (std::size_t i = 0; i < vs.size(); ++i) r.allowed.push_back(dec(vs[i], key + ".values"));
      f.ranges.push_back(std::move(r));
    }
    f.steps = steps(n["step"], key + ".step");
    if (const auto& ch = n["choices"]; ch) {
      if (!ch.IsMap()) fail(ch, key + ".choices", "expected a map value: meaning");
      for (const auto& kv : ch) {
        Choice c;
        c.value = integer(kv.first, key + ".choices");
        c.meaning = str(kv.second, key + ".choices." + kv.first.Scalar());
        f.choices.push_back(std::move(c));
      }
    }
    if (const auto& b = n["bits"]; b) {
      if (!b.IsMap()) fail(b, key + ".bits", "expected {width:, fields: [...]}");
      f.bits.bits = b["width"] ? static_cast<unsigned>(integer(b["width"], key + ".bits.width")) : 16u;
      if (f.bits.bits < 1 || f.bits.bits > 64) fail(b["width"], key + ".bits.width", "1..64");
      f.bits.allow_unnamed = b["allow_unnamed"] && b["allow_unnamed"].as<bool>(false);
      const auto& fs = b["fields"];
      if (!fs || !fs.IsSequence()) fail(b, key + ".bits.fields", "expected a list of {name, bit, width}");
      for (std::size_t i = 0; i < fs.size(); ++i) {
        const auto k = fmt::format("{}.bits.fields[{}]", key, i);
        BitDef d;
        d.name = str(fs[i]["name"], k + ".name", true);
        d.first = static_cast<unsigned>(integer(fs[i]["bit"], k + ".bit"));
        d.width = fs[i]["width"] ? static_cast<unsigned>(integer(fs[i]["width"], k + ".width")) : 1u;
        d.meaning = str(fs[i]["meaning"], k + ".meaning");
        if (d.width < 1 || d.first + d.width > f.bits.bits) fail(fs[i], k, "bit group outside the word");
        f.bits.fields.push_back(std::move(d));
      }
    }
    if (n["binary"]) f.binary_text = n["binary"].as<bool>(false);
    if (const std::string e = str(n["encoding"], key + ".encoding"); !e.empty()) {
      f.encoding = parse_encoding(e);
      if (!f.encoding)
        fail(n["encoding"], key + ".encoding", "expected text, bcd_binary, KF, KH, KY, KD, DL, DR or fixed");
    }
    TwosComplementFormat word{16, true};
    if (n["word_bits"]) word.bits = static_cast<int>(integer(n["word_bits"], key + ".word_bits"));
    if (n["signed"]) word.is_signed = n["signed"].as<bool>(true);
    if (n["lsb"]) {
      auto fp = FixedPointFormat::parse_lsb(str(n["lsb"], key + ".lsb"), word);
      if (!fp) fail(n["lsb"], key + ".lsb", fp.error());
      f.fixed = *fp;
    } else {
      f.fixed.word = word;
    }
    if (n["word"]) f.word = static_cast<int>(integer(n["word"], key + ".word"));
    if (n["default"] && !n["default"].IsNull()) {
      auto v = parse_field_input(f, str(n["default"], key + ".default"));
      if (!v) fail(n["default"], key + ".default", v.error());
      f.default_value = *v;
    } else if (f.type == FieldType::io_address) {
      f.default_value = std::string("00.00.0");
    } else if (f.type == FieldType::reserved) {
      f.default_value = f.fixed_text;
    }
    (void)wire;
    return f;
  }

  void variant_body(const YAML::Node& n, const std::string& key, ParamVariant& v, const WireSpec& wire) const {
    if (n["when"]) v.when = expr(n["when"], key + ".when");
    if (n["name"]) v.name = str(n["name"], key + ".name");
    if (n["meaning"]) v.meaning = str(n["meaning"], key + ".meaning");
    if (n["note"]) v.note = str(n["note"], key + ".note");
    if (n["takes_effect"]) {
      const auto t = str(n["takes_effect"], key + ".takes_effect");
      if (t == "immediately")
        v.takes_effect = TakesEffect::immediately;
      else if (t == "leaving_parameter_mode")
        v.takes_effect = TakesEffect::leaving_parameter_mode;
      else if (t == "after_reset")
        v.takes_effect = TakesEffect::after_reset;
      else if (t == "after_power_cycle")
        v.takes_effect = TakesEffect::after_power_cycle;
      else
        fail(n["takes_effect"], key + ".takes_effect",
             "expected immediately, leaving_parameter_mode, after_reset or after_power_cycle");
    }
    if (n["protection"]) {
      const auto t = str(n["protection"], key + ".protection");
      if (t == "none")
        v.protection = Protection::none;
      else if (t == "machine_builder")
        v.protection = Protection::machine_builder;
      else if (t == "read_only")
        v.protection = Protection::read_only;
      else if (t == "system")
        v.protection = Protection::system;
      else
        fail(n["protection"], key + ".protection", "expected none, machine_builder, read_only or system");
    }
    if (const auto& fs = n["fields"]; fs) {
      if (!fs.IsSequence()) fail(fs, key + ".fields", "expected a list of fields");
      v.fields.clear();
      for (std::size_t i = 0; i < fs.size(); ++i)
        v.fields.push_back(field(fs[i], fmt::format("{}.fields[{}]", key, i), wire));
    } else if (n["type"] || n["format"] || n["range"] || n["unit"] || n["default"] || n["choices"] || n["bits"] ||
               n["values"] || n["lsb"] || n["encoding"] || n["word"]) {
      v.fields = {field(n, key, wire)};
    }
  }

  ParamSpec param(const YAML::Node& n, const std::string& key, const WireSpec& wire) const {
    if (!n.IsMap()) fail(n, key, "expected a parameter map");
    ParamSpec p;
    p.id = str(n["id"], key + ".id", true);
    p.pattern = str(n["pattern"], key + ".pattern");
    if (const auto& al = n["aliases"]; al) {
      if (!al.IsSequence()) fail(al, key + ".aliases", "expected a list of names");
      for (std::size_t i = 0; i < al.size(); ++i) p.aliases.push_back(str(al[i], key + ".aliases"));
    }
    p.group = str(n["group"], key + ".group");
    p.source = str(n["source"], key + ".source");
    if (n["number"]) p.number = static_cast<int>(integer(n["number"], key + ".number"));
    if (const auto& r = n["required"]; r) {
      const auto s = str(r, key + ".required");
      if (s == "true")
        p.required = *Expression::parse("1");
      else if (s != "false")
        p.required = expr(r, key + ".required");
    }
    if (const auto& in = n["instances"]; in) {
      if (!in.IsMap() || in.size() != 1) fail(in, key + ".instances", "expected {axis: [1, 2, ...]}");
      for (const auto& kv : in) {
        p.instance_key = kv.first.Scalar();
        if (!kv.second.IsSequence()) fail(kv.second, key + ".instances", "expected a list of numbers");
        for (std::size_t i = 0; i < kv.second.size(); ++i)
          p.instances.push_back(integer(kv.second[i], key + ".instances"));
      }
      if (p.pattern.empty()) fail(n, key + ".pattern", "instanced parameters need a pattern like \"A{axis}06\"");
      if (p.pattern.find("{" + p.instance_key + "}") == std::string::npos)
        fail(n["pattern"], key + ".pattern", fmt::format("pattern must contain {{{}}}", p.instance_key));
    }
    ParamVariant base;
    variant_body(n, key, base, wire);
    if (const auto& vs = n["variants"]; vs) {
      if (!vs.IsSequence() || vs.size() == 0) fail(vs, key + ".variants", "expected a non-empty list");
      for (std::size_t i = 0; i < vs.size(); ++i) {
        ParamVariant v = base;
        v.when = {};
        variant_body(vs[i], fmt::format("{}.variants[{}]", key, i), v, wire);
        if (v.fields.empty()) fail(vs[i], fmt::format("{}.variants[{}]", key, i), "variant has no fields");
        p.variants.push_back(std::move(v));
      }
    } else {
      if (base.fields.empty()) fail(n, key, "parameter has no fields (give fields: or type/format/range)");
      p.variants.push_back(std::move(base));
    }
    return p;
  }

  std::unique_ptr<ErrorCatalogue> catalogue(const YAML::Node& n, const std::string& key,
                                            const std::string& device) const {
    if (!n.IsMap()) fail(n, key, "expected a catalogue map");
    const auto id = str(n["id"], key + ".id", true);
    const auto title = str(n["title"], key + ".title");
    const auto code_format = n["code_format"] ? str(n["code_format"], key + ".code_format") : std::string("dec");
    const auto& defs = n["defaults"];
    std::vector<ErrorEntry> entries;
    const auto& es = n["entries"];
    if (!es || !es.IsSequence()) fail(n, key + ".entries", "expected a list of entries");
    for (std::size_t i = 0; i < es.size(); ++i) {
      const auto k = fmt::format("{}.entries[{}]", key, i);
      const auto& e = es[i];
      if (!e.IsMap()) fail(e, k, "expected an entry map");
      ErrorEntry base;
      auto get = [&](const char* name) {
        if (e[name]) return str(e[name], k + "." + name);
        if (defs && defs[name]) return str(defs[name], key + ".defaults." + name);
        return std::string();
      };
      base.text = get("text");
      base.text_de = get("text_de");
      base.cause = get("cause");
      base.remedy = get("remedy");
      base.acknowledge = get("acknowledge");
      base.group = get("group");
      base.note = get("note");
      const auto reaction = get("reaction");
      if (reaction.empty())
        fail(e, k + ".reaction", "every error needs a reaction (message, stop, drive_off, needs_reset)");
      auto r = parse_reaction(reaction);
      if (!r)
        fail(e["reaction"] ? e["reaction"] : e, k + ".reaction", "expected message, stop, drive_off or needs_reset");
      base.reaction = *r;
      auto code_of = [&](const YAML::Node& c, const std::string& ck) {
        const std::string s = str(c, ck, true);
        const int b = code_format.starts_with("hex") ? 16 : 10;
        char* end = nullptr;
        std::string digits = s;
        if (digits.starts_with("0x") || digits.starts_with("0X")) digits = digits.substr(2);
        const long v = std::strtol(digits.c_str(), &end, b);
        if (digits.empty() || *end != '\0') fail(c, ck, fmt::format("'{}' is not a {} code", s, code_format));
        return std::pair<int, std::string>{static_cast<int>(v), digits};
      };
      if (const auto& series = e["series"]; series) {
        if (!series.IsSequence()) fail(series, k + ".series", "expected a list of codes, one per axis");
        for (std::size_t a = 0; a < series.size(); ++a) {
          ErrorEntry x = base;
          auto [v, t] = code_of(series[a], k + ".series");
          x.code = v;
          x.code_text = t;
          const std::string axis = std::to_string(a + 1);
          for (auto* s : {&x.text, &x.text_de, &x.cause, &x.group})
            for (auto p = s->find("{axis}"); p != std::string::npos; p = s->find("{axis}")) s->replace(p, 6, axis);
          entries.push_back(std::move(x));
        }
      } else {
        if (e["value"]) {
          base.code = static_cast<int>(integer(e["value"], k + ".value"));
          base.code_text = str(e["code"], k + ".code", true);
        } else {
          auto [v, t] = code_of(e["code"], k + ".code");
          base.code = v;
          base.code_text = t;
        }
        entries.push_back(std::move(base));
      }
    }
    std::set<int> seen;
    for (const auto& x : entries)
      if (!seen.insert(x.code).second) fail(n, key, fmt::format("code {} appears twice", x.code_text));
    return std::make_unique<ErrorCatalogue>(device, id, title, code_format, std::move(entries));
  }

  void document(const YAML::Node& doc, Profile& p, bool top, std::vector<std::string>& includes) const {
    if (!doc.IsMap()) fail(doc, "", "a profile is a YAML map");
    if (top) {
      p.device = str(doc["device"], "device", true);
      p.title = str(doc["title"], "title");
      p.manual = str(doc["manual"], "manual");
      p.description = str(doc["description"], "description");
      p.text_format = str(doc["text_format"], "text_format");
      if (const auto& w = doc["wire"]; w) {
        if (const auto e = str(w["encoding"], "wire.encoding"); !e.empty()) {
          auto enc = parse_encoding(e);
          if (!enc) fail(w["encoding"], "wire.encoding", "unknown encoding");
          p.wire.encoding = *enc;
        }
        if (w["separator"]) p.wire.separator = str(w["separator"], "wire.separator");
        if (const auto& b = w["bcd"]; b) {
          if (b["digits"]) p.wire.bcd.digits = static_cast<int>(integer(b["digits"], "wire.bcd.digits"));
          const auto s = str(b["sign"], "wire.bcd.sign");
          if (s == "none")
            p.wire.bcd.sign = BcdSign::none;
          else if (s == "bit31")
            p.wire.bcd.sign = BcdSign::bit31;
          else if (s == "nibble")
            p.wire.bcd.sign = BcdSign::nibble;
          else if (!s.empty())
            fail(b["sign"], "wire.bcd.sign", "expected none, bit31 or nibble");
        }
        if (w["binary_bits"]) p.wire.binary_bits = static_cast<int>(integer(w["binary_bits"], "wire.binary_bits"));
        if (const auto o = str(w["word_order"], "wire.word_order"); !o.empty()) {
          if (o != "high_first" && o != "low_first")
            fail(w["word_order"], "wire.word_order", "expected high_first or low_first");
          p.wire.low_word_first = o == "low_first";
        }
      }
    } else if (doc["device"] && str(doc["device"], "device") != p.device) {
      fail(doc["device"], "device",
           fmt::format("included file belongs to '{}', not '{}'", str(doc["device"], "device"), p.device));
    }
    if (const auto& inc = doc["include"]; inc) {
      if (!inc.IsSequence()) fail(inc, "include", "expected a list of file names");
      for (std::size_t i = 0; i < inc.size(); ++i) includes.push_back(str(inc[i], "include"));
    }
    if (const auto& ss = doc["settings"]; ss) {
      if (!ss.IsSequence()) fail(ss, "settings", "expected a list");
      for (std::size_t i = 0; i < ss.size(); ++i) {
        const auto k = fmt::format("settings[{}]", i);
        SettingSpec s;
        s.name = str(ss[i]["name"], k + ".name", true);
        s.meaning = str(ss[i]["meaning"], k + ".meaning");
        s.note = str(ss[i]["note"], k + ".note");
        if (const auto& vs = ss[i]["values"]; vs) {
          if (!vs.IsSequence()) fail(vs, k + ".values", "expected a list");
          for (std::size_t j = 0; j < vs.size(); ++j) s.values.push_back(expr_value(vs[j], k + ".values"));
        }
        if (ss[i]["default"]) s.default_value = expr_value(ss[i]["default"], k + ".default");
        s.from = expr(ss[i]["from"], k + ".from");
        p.settings.push_back(std::move(s));
      }
    }
    if (const auto& ps = doc["parameters"]; ps) {
      if (!ps.IsSequence()) fail(ps, "parameters", "expected a list");
      for (std::size_t i = 0; i < ps.size(); ++i)
        p.parameters.push_back(param(ps[i], fmt::format("parameters[{}]", i), p.wire));
    }
    if (const auto& cs = doc["constraints"]; cs) {
      if (!cs.IsSequence()) fail(cs, "constraints", "expected a list");
      for (std::size_t i = 0; i < cs.size(); ++i) {
        const auto k = fmt::format("constraints[{}]", i);
        Constraint c;
        c.id = str(cs[i]["id"], k + ".id", true);
        c.rule = expr(cs[i]["rule"], k + ".rule");
        if (c.rule.empty()) fail(cs[i], k + ".rule", "required key missing");
        c.when = expr(cs[i]["when"], k + ".when");
        c.message = str(cs[i]["message"], k + ".message");
        c.source = str(cs[i]["source"], k + ".source");
        if (const auto& fe = cs[i]["for_each"]; fe) {
          if (!fe.IsMap() || fe.size() != 1) fail(fe, k + ".for_each", "expected {axis: [1, 2, ...]}");
          for (const auto& kv : fe) {
            c.for_each = kv.first.Scalar();
            for (std::size_t j = 0; j < kv.second.size(); ++j)
              c.instances.push_back(integer(kv.second[j], k + ".for_each"));
          }
        }
        p.constraints.push_back(std::move(c));
      }
    }
    if (const auto& cs = doc["catalogues"]; cs) {
      if (!cs.IsSequence()) fail(cs, "catalogues", "expected a list");
      for (std::size_t i = 0; i < cs.size(); ++i)
        p.catalogues.push_back(catalogue(cs[i], fmt::format("catalogues[{}]", i), p.device));
    }
    if (const auto& ds = doc["decisions"]; ds) {
      if (!ds.IsSequence()) fail(ds, "decisions", "expected a list");
      for (std::size_t i = 0; i < ds.size(); ++i) {
        const auto k = fmt::format("decisions[{}]", i);
        p.decisions.push_back({str(ds[i]["topic"], k + ".topic", true), str(ds[i]["choice"], k + ".choice", true),
                               str(ds[i]["configurable"], k + ".configurable")});
      }
    }
    if (const auto& ts = doc["tables"]; ts) {
      if (!ts.IsMap()) fail(ts, "tables", "expected a map of name: [rows]");
      for (const auto& kv : ts) {
        const auto name = kv.first.Scalar();
        if (!kv.second.IsSequence()) fail(kv.second, "tables." + name, "expected a list of rows");
        Table t;
        for (std::size_t i = 0; i < kv.second.size(); ++i) {
          const auto& row = kv.second[i];
          if (!row.IsMap()) fail(row, fmt::format("tables.{}[{}]", name, i), "expected a row map");
          std::map<std::string, std::string> r;
          for (const auto& c : row) {
            if (c.second.IsScalar())
              r[c.first.Scalar()] = c.second.Scalar();
            else if (c.second.IsSequence()) {
              std::string joined;
              for (std::size_t j = 0; j < c.second.size(); ++j)
                joined += (j ? ", " : "") + (c.second[j].IsScalar() ? c.second[j].Scalar() : std::string("?"));
              r[c.first.Scalar()] = joined;
            } else if (!c.second.IsNull()) {
              fail(c.second, fmt::format("tables.{}[{}].{}", name, i, c.first.Scalar()), "expected text or a list");
            }
          }
          t.push_back(std::move(r));
        }
        p.tables[name] = std::move(t);
      }
    }
  }

  /// Checks after loading: unique ids, constraints/conditions name known things.
  void check(Profile& p, const YAML::Node& root) const {
    std::set<std::string> ids;
    for (const auto& r : p.all_refs())
      if (!ids.insert(normalise_id(r.id())).second)
        fail(root, "parameters", fmt::format("parameter {} defined twice", r.id()));
    std::set<std::string> catalogue_ids;
    for (const auto& c : p.catalogues)
      if (!catalogue_ids.insert(c->id()).second)
        fail(root, "catalogues", fmt::format("catalogue {} defined twice", c->id()));
  }

  std::string file_;
};

std::shared_ptr<Profile> load_impl(const YAML::Node& root, const std::string& name, const std::filesystem::path* base,
                                   int depth = 0) {
  Reader rd(name);
  auto p = std::make_shared<Profile>();
  p->source_file = name;
  std::vector<std::string> includes;
  rd.document(root, *p, true, includes);
  std::set<std::string> done;
  while (!includes.empty()) {
    const auto inc = includes.front();
    includes.erase(includes.begin());
    if (!base) continue;
    if (!done.insert(inc).second || ++depth > 32) continue;
    const auto path = base->parent_path() / inc;
    YAML::Node doc;
    try {
      const auto text = hil::read_text_file(path);
      if (!text) rd.fail(root["include"], "include", fmt::format("cannot read included file: {}", text.error()));
      doc = YAML::Load(*text);
    } catch (const YAML::Exception& e) {
      hil::ConfigError ce{path.string(), e.mark.line + 1, e.mark.column + 1, "", e.msg};
      throw hil::yaml::Failure{ce};
    }
    Reader ri(path.string());
    ri.document(doc, *p, false, includes);
  }
  p->index();
  rd.check(*p, root);
  return p;
}

}  // namespace

std::expected<std::shared_ptr<const Profile>, hil::ConfigError> load_profile_text(std::string_view yaml,
                                                                                  std::string_view name) {
  const std::string file(name);
  try {
    return hil::yaml::read_document(
        file, [&] { return std::shared_ptr<const Profile>(load_impl(YAML::Load(std::string(yaml)), file, nullptr)); });
  } catch (const std::exception& e) {
    return std::unexpected(hil::ConfigError{file, 0, 0, "", e.what()});
  }
}

std::expected<std::shared_ptr<const Profile>, hil::ConfigError> load_profile(const std::filesystem::path& file) {
  const auto text = hil::read_text_file(file);
  if (!text) return std::unexpected(hil::ConfigError{file.string(), 0, 0, "", text.error()});
  try {
    return hil::yaml::read_document(file.string(), [&] {
      return std::shared_ptr<const Profile>(load_impl(YAML::Load(*text), file.string(), &file));
    });
  } catch (const std::exception& e) {
    return std::unexpected(hil::ConfigError{file.string(), 0, 0, "", e.what()});
  }
}

std::vector<std::filesystem::path> profile_search_path() {
  std::vector<std::filesystem::path> dirs;
  std::error_code ec;
  auto add = [&](const std::filesystem::path& d) {
    if (d.empty() || !std::filesystem::is_directory(d, ec)) return;
    const auto c = std::filesystem::weakly_canonical(d, ec);
    if (std::find(dirs.begin(), dirs.end(), c) == dirs.end()) dirs.push_back(c);
  };
  if (const char* env = std::getenv("HILBRIDGE_PROFILES"); env && *env) {
    std::string_view s = env;
    while (!s.empty()) {
      const auto c = s.find(':');
      add(std::filesystem::path(std::string(s.substr(0, c))));
      if (c == std::string_view::npos) break;
      s.remove_prefix(c + 1);
    }
  }
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    add(exe.parent_path() / ".." / "profiles" / "devices");
    add(exe.parent_path() / "profiles" / "devices");
  }
  for (const auto& d : hil::data_dirs("profiles/devices")) add(d);
  return dirs;
}

std::vector<std::string> list_profiles() {
  std::set<std::string> names;
  for (const auto& d : profile_search_path()) {
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(d, ec)) {
      if (!e.is_regular_file() || e.path().extension() != ".yaml") continue;
      // Only top-level profile files name a device; included parts live in sub-folders.
      names.insert(e.path().stem().string());
    }
  }
  return {names.begin(), names.end()};
}

std::expected<std::shared_ptr<const Profile>, hil::ConfigError> find_profile(std::string_view device) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const Profile>, std::less<>> cache;
  std::lock_guard lock(mutex);
  if (auto it = cache.find(device); it != cache.end()) return it->second;
  for (const auto& d : profile_search_path()) {
    const auto f = d / (std::string(device) + ".yaml");
    std::error_code ec;
    if (!std::filesystem::is_regular_file(f, ec)) continue;
    auto p = load_profile(f);
    if (!p) return p;
    cache.emplace(std::string(device), *p);
    return *p;
  }
  std::string searched;
  for (const auto& d : profile_search_path()) searched += (searched.empty() ? "" : ", ") + d.string();
  return std::unexpected(
      hil::ConfigError{"", 0, 0, std::string(device),
                       fmt::format("no profile '{}.yaml' found (searched: {}); set HILBRIDGE_PROFILES to its folder",
                                   device, searched.empty() ? "nothing" : searched)});
}

}  // namespace hil::profiles
