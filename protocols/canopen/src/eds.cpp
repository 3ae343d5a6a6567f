// SPDX-License-Identifier: MIT
#include "hil/canopen/eds.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "hil/core/text_file.hpp"

namespace hil::canopen {
namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (auto& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

struct Entry {
  std::string value;
  int line = 0;
};
struct Section {
  std::string name;
  int line = 0;
  std::map<std::string, Entry> keys;  // lower-case key
  [[nodiscard]] const Entry* get(std::string_view key) const {
    auto it = keys.find(lower(key));
    return it == keys.end() ? nullptr : &it->second;
  }
};

class Parser {
 public:
  Parser(std::string_view text, std::string_view file, NodeId node) : text_(text), file_(file), node_(node) {}

  std::expected<DeviceDescription, ConfigError> run();

 private:
  ConfigError error(int line, std::string_view section, std::string_view key, std::string message) const {
    ConfigError e;
    e.file = std::string(file_);
    e.line = line;
    e.key = key.empty() ? fmt::format("[{}]", section) : fmt::format("[{}] {}", section, key);
    e.message = std::move(message);
    return e;
  }
  std::optional<ConfigError> split();
  const Section* section(std::string_view name) const {
    auto it = sections_.find(lower(name));
    return it == sections_.end() ? nullptr : &it->second;
  }
  std::expected<std::int64_t, ConfigError> integer(const Section& s, std::string_view key,
                                                   std::optional<std::int64_t> dflt) const;
  std::expected<std::vector<std::uint8_t>, ConfigError> encode(const Section& s, const Entry& e, std::string_view key,
                                                               DataType type) const;
  std::optional<ConfigError> add_var(const Section& s, std::uint16_t index, std::uint8_t sub, const Section* parent,
                                     DataType* type_out = nullptr);
  std::optional<ConfigError> add_object(std::uint16_t index, const Section& s);

  std::string_view text_;
  std::string_view file_;
  NodeId node_;
  std::map<std::string, Section> sections_;
  DeviceDescription out_;
};

std::optional<ConfigError> Parser::split() {
  Section* current = nullptr;
  int line_no = 0;
  std::size_t pos = text_.starts_with("\xEF\xBB\xBF") ? 3 : 0;  // a UTF-8 byte-order mark is no content
  while (pos <= text_.size()) {
    auto end = text_.find('\n', pos);
    if (end == std::string_view::npos) end = text_.size();
    auto line = trim(text_.substr(pos, end - pos));
    pos = end + 1;
    ++line_no;
    if (line.empty() || line[0] == ';' || line[0] == '#') continue;
    if (line[0] == '[') {
      const auto close = line.find(']');
      if (close == std::string_view::npos || close < 2)
        return error(line_no, line, "", "malformed section header: expected [Name]");
      const auto name = trim(line.substr(1, close - 1));
      auto& sec = sections_[lower(name)];  // duplicate sections merge (seen in vendor files)
      if (sec.name.empty()) {
        sec.name = std::string(name);
        sec.line = line_no;
      }
      current = &sec;
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string_view::npos) return error(line_no, current ? current->name : "", line, "expected Key=Value");
    if (current == nullptr) return error(line_no, "", trim(line.substr(0, eq)), "key outside of any section");
    current->keys[lower(trim(line.substr(0, eq)))] = Entry{std::string(trim(line.substr(eq + 1))), line_no};
  }
  return std::nullopt;
}

std::expected<std::int64_t, ConfigError> Parser::integer(const Section& s, std::string_view key,
                                                         std::optional<std::int64_t> dflt) const {
  const auto* e = s.get(key);
  if (e == nullptr || e->value.empty()) {
    if (dflt) return *dflt;
    return std::unexpected(error(s.line, s.name, key, "missing; expected an integer"));
  }
  if (auto v = eval_eds_integer(e->value, node_)) return *v;
  return std::unexpected(error(e->line, s.name, key, fmt::format("'{}' is not an integer expression", e->value)));
}

std::expected<std::vector<std::uint8_t>, ConfigError> Parser::encode(const Section& s, const Entry& e,
                                                                     std::string_view key, DataType type) const {
  std::vector<std::uint8_t> out;
  const auto n = data_type_size(type);
  switch (type) {
    case DataType::visible_string:
    case DataType::unicode_string:
      out.assign(e.value.begin(), e.value.end());
      return out;
    case DataType::domain:
      return out;
    case DataType::octet_string: {
      std::string hex;
      for (char c : e.value)
        if (!std::isspace(static_cast<unsigned char>(c))) hex.push_back(c);
      if (hex.size() % 2 != 0)
        return std::unexpected(error(e.line, s.name, key, "OCTET_STRING needs an even number of hex digits"));
      for (std::size_t i = 0; i < hex.size(); i += 2) {
        unsigned b = 0;
        auto [p, ec] = std::from_chars(hex.data() + i, hex.data() + i + 2, b, 16);
        if (ec != std::errc{} || p != hex.data() + i + 2)
          return std::unexpected(error(e.line, s.name, key, fmt::format("'{}' is not hex", e.value)));
        out.push_back(static_cast<std::uint8_t>(b));
      }
      return out;
    }
    case DataType::real32:
    case DataType::real64: {
      double d = 0;
      std::istringstream is(e.value);
      is.imbue(std::locale::classic());
      if (!(is >> d)) return std::unexpected(error(e.line, s.name, key, fmt::format("'{}' is not a number", e.value)));
      out.resize(n);
      if (type == DataType::real32) {
        const auto bits = std::bit_cast<std::uint32_t>(static_cast<float>(d));
        encode_int(bits, 4, out.data());
      } else {
        encode_int(std::bit_cast<std::int64_t>(d), 8, out.data());
      }
      return out;
    }
    default:
      break;
  }
  auto v = eval_eds_integer(e.value, node_);
  if (!v) return std::unexpected(error(e.line, s.name, key, fmt::format("'{}' is not an integer expression", e.value)));
  if (n < 8) {
    const auto bits = 8 * n;
    const std::int64_t lo = is_signed(type) ? -(std::int64_t{1} << (bits - 1)) : 0;
    const std::int64_t hi = is_signed(type) ? (std::int64_t{1} << (bits - 1)) - 1 : (std::int64_t{1} << bits) - 1;
    if (*v < lo || *v > hi)
      return std::unexpected(error(e.line, s.name, key, fmt::format("{} does not fit {}", e.value, to_string(type))));
  }
  if (type == DataType::boolean && *v != 0 && *v != 1)
    return std::unexpected(error(e.line, s.name, key, "BOOLEAN must be 0 or 1"));
  out.resize(n);
  encode_int(*v, n, out.data());
  return out;
}

std::optional<ConfigError> Parser::add_var(const Section& s, std::uint16_t index, std::uint8_t sub,
                                           const Section* parent, DataType* type_out) {
  Variable v;
  v.index = index;
  v.sub = sub;
  const auto* name = s.get("ParameterName");
  v.name = name ? name->value : "";
  const auto* dt = s.get("DataType");
  if (dt == nullptr && parent != nullptr) dt = parent->get("DataType");
  if (dt == nullptr) return error(s.line, s.name, "DataType", "missing");
  auto code = eval_eds_integer(dt->value, 0);
  if (!code || *code < 0) return error(dt->line, s.name, "DataType", fmt::format("'{}' is not a number", dt->value));
  auto type = data_type_from_code(static_cast<std::uint32_t>(*code));
  if (!type) return error(dt->line, s.name, "DataType", fmt::format("unsupported data type 0x{:04X}", *code));
  v.type = *type;
  if (type_out) *type_out = *type;
  const auto* acc = s.get("AccessType");
  if (acc == nullptr && parent != nullptr) acc = parent->get("AccessType");
  if (acc == nullptr) return error(s.line, s.name, "AccessType", "missing");
  auto a = access_from_string(acc->value);
  if (!a)
    return error(acc->line, s.name, "AccessType",
                 fmt::format("'{}' is not one of ro, wo, rw, rwr, rww, const", acc->value));
  v.access = *a;
  auto pdo = integer(s, "PDOMapping", 0);
  if (!pdo) return pdo.error();
  v.pdo_mappable = *pdo != 0;
  for (const auto* key : {"LowLimit", "HighLimit"}) {
    if (const auto* e = s.get(key); e != nullptr && !e->value.empty() && is_integer(v.type)) {
      auto x = eval_eds_integer(e->value, node_);
      if (!x) return error(e->line, s.name, key, fmt::format("'{}' is not an integer expression", e->value));
      // Limits are written in the type's own representation (e.g. 0xFFFFFFFF for an INTEGER32 -1).
      std::vector<std::uint8_t> tmp(data_type_size(v.type));
      encode_int(*x, tmp.size(), tmp.data());
      const auto norm = decode_int(tmp, is_signed(v.type));
      (std::strcmp(key, "LowLimit") == 0 ? v.low : v.high) = norm;
    }
  }
  if (v.low && v.high && *v.low > *v.high)
    return error(s.line, s.name, "HighLimit", fmt::format("HighLimit {} is below LowLimit {}", *v.high, *v.low));
  const auto* dv = s.get("DefaultValue");
  if (dv != nullptr && !dv->value.empty()) {
    auto bytes = encode(s, *dv, "DefaultValue", v.type);
    if (!bytes) return bytes.error();
    v.value = std::move(*bytes);
  }
  if (const auto* pv = s.get("ParameterValue"); pv != nullptr && !pv->value.empty()) {
    auto bytes = encode(s, *pv, "ParameterValue", v.type);
    if (!bytes) return bytes.error();
    v.value = *bytes;
    out_.parameter_values.push_back(ParameterValue{index, sub, std::move(*bytes)});
  }
  out_.od.add(std::move(v));
  return std::nullopt;
}

std::optional<ConfigError> Parser::add_object(std::uint16_t index, const Section& s) {
  auto ot = integer(s, "ObjectType", 7);
  if (!ot) return ot.error();
  switch (*ot) {
    case 0x7:
    case 0x2:  // DOMAIN
      return add_var(s, index, 0, nullptr);
    case 0x5:  // DEFTYPE
    case 0x6:  // DEFSTRUCT
      return std::nullopt;
    case 0x8:
    case 0x9:
      break;
    default:
      return error(s.line, s.name, "ObjectType", fmt::format("unsupported object type 0x{:X}", *ot));
  }
  auto compact = integer(s, "CompactSubObj", 0);
  if (!compact) return compact.error();
  if (*compact < 0 || *compact > 254) return error(s.line, s.name, "CompactSubObj", "must be 0..254");
  if (*compact > 0) {
    Variable sub0;
    sub0.index = index;
    sub0.name = "Highest sub-index supported";
    sub0.type = DataType::unsigned8;
    sub0.access = Access::ro;
    sub0.value = {static_cast<std::uint8_t>(*compact)};
    out_.od.add(sub0);
    const auto* names = section(fmt::format("{:04X}Name", index));
    const auto* values = section(fmt::format("{:04X}Value", index));
    for (std::int64_t i = 1; i <= *compact; ++i) {
      Section synth = s;
      synth.keys.erase("parametervalue");
      const auto key = std::to_string(i);
      if (names) {
        if (const auto* n = names->get(key)) synth.keys["parametername"] = *n;
      } else if (const auto* n = s.get("ParameterName")) {
        synth.keys["parametername"] = Entry{fmt::format("{}{}", n->value, i), n->line};
      }
      if (values) {
        if (const auto* val = values->get(key)) synth.keys["parametervalue"] = *val;
      }
      if (auto err = add_var(synth, index, static_cast<std::uint8_t>(i), nullptr)) return err;
    }
    return std::nullopt;
  }
  auto subnumber = integer(s, "SubNumber", std::nullopt);
  if (!subnumber) return subnumber.error();
  int found = 0;
  for (int sub = 0; sub <= 0xFE && found < *subnumber; ++sub) {
    const auto* ss = section(fmt::format("{:04X}sub{:X}", index, sub));
    if (ss == nullptr) continue;
    ++found;
    if (auto err = add_var(*ss, index, static_cast<std::uint8_t>(sub), &s)) return err;
  }
  if (found != *subnumber)
    return error(s.get("SubNumber")->line, s.name, "SubNumber",
                 fmt::format("says {} sub-objects but {} [{:04X}subN] sections exist", *subnumber, found, index));
  return std::nullopt;
}

std::expected<DeviceDescription, ConfigError> Parser::run() {
  if (auto err = split()) return std::unexpected(*err);
  out_.file = std::string(file_);
  if (const auto* dc = section("DeviceComissioning")) {
    if (auto id = integer(*dc, "NodeID", 0); id && *id >= 1 && *id <= 127) {
      out_.dcf_node_id = static_cast<NodeId>(*id);
      if (node_ == 0) node_ = static_cast<NodeId>(*id);
    }
  }
  if (const auto* di = section("DeviceInfo")) {
    if (const auto* e = di->get("VendorName")) out_.info.vendor_name = e->value;
    if (const auto* e = di->get("ProductName")) out_.info.product_name = e->value;
    if (const auto* e = di->get("OrderCode")) out_.info.order_code = e->value;
    auto num = [&](std::string_view key, std::uint32_t& dst) -> std::optional<ConfigError> {
      auto v = integer(*di, key, 0);
      if (!v) return v.error();
      if (*v < 0 || *v > 0xFFFFFFFF)  // the identity object 0x1018 holds UNSIGNED32
        return error(di->get(key)->line, di->name, key,
                     fmt::format("'{}' must be 0..0xFFFFFFFF (UNSIGNED32, object 0x1018)", di->get(key)->value));
      dst = static_cast<std::uint32_t>(*v);
      return std::nullopt;
    };
    if (auto e = num("VendorNumber", out_.info.vendor_number)) return std::unexpected(*e);
    if (auto e = num("ProductNumber", out_.info.product_number)) return std::unexpected(*e);
    if (auto e = num("RevisionNumber", out_.info.revision_number)) return std::unexpected(*e);
  }
  std::vector<std::pair<std::uint16_t, const Section*>> objects;
  bool listed = false;
  for (const auto* list_name : {"MandatoryObjects", "OptionalObjects", "ManufacturerObjects"}) {
    const auto* list = section(list_name);
    if (list == nullptr) continue;
    listed = true;
    auto count = integer(*list, "SupportedObjects", std::nullopt);
    if (!count) return std::unexpected(count.error());
    if (*count < 0 || *count > 0xFFFF)
      return std::unexpected(error(list->get("SupportedObjects")->line, list->name, "SupportedObjects",
                                   fmt::format("{} objects: must be 0..65535", *count)));
    for (std::int64_t i = 1; i <= *count; ++i) {
      auto idx = integer(*list, std::to_string(i), std::nullopt);
      if (!idx) return std::unexpected(idx.error());
      if (*idx < 1 || *idx > 0xFFFF)
        return std::unexpected(
            error(list->get(std::to_string(i))->line, list->name, std::to_string(i), "index out of range"));
      const auto* s = section(fmt::format("{:04X}", *idx));
      if (s == nullptr)
        return std::unexpected(error(list->get(std::to_string(i))->line, list->name, std::to_string(i),
                                     fmt::format("object 0x{:04X} is listed but has no [{:04X}] section", *idx, *idx)));
      objects.emplace_back(static_cast<std::uint16_t>(*idx), s);
    }
  }
  if (!listed) {
    for (const auto& [key, s] : sections_) {
      if (key.size() != 4 ||
          !std::all_of(key.begin(), key.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); }))
        continue;
      objects.emplace_back(static_cast<std::uint16_t>(std::stoul(key, nullptr, 16)), &s);
    }
  }
  for (const auto& [idx, s] : objects)
    if (auto err = add_object(idx, *s)) return std::unexpected(*err);
  if (out_.od.size() == 0) return std::unexpected(error(0, "", "", "no objects: not an EDS/DCF file?"));
  std::sort(out_.parameter_values.begin(), out_.parameter_values.end(),
            [](const auto& a, const auto& b) { return std::pair(a.index, a.sub) < std::pair(b.index, b.sub); });
  return std::move(out_);
}

std::optional<std::int64_t> parse_literal(std::string_view t) noexcept {
  t = trim(t);
  bool neg = false;
  if (!t.empty() && (t[0] == '-' || t[0] == '+')) {
    neg = t[0] == '-';
    t.remove_prefix(1);
  }
  if (t.empty()) return std::nullopt;
  int base = 10;
  if (t.size() > 2 && t[0] == '0' && (t[1] == 'x' || t[1] == 'X')) {
    base = 16;
    t.remove_prefix(2);
  } else if (t.size() > 1 && t[0] == '0') {
    base = 8;  // CiA 306 §4.6.4: a leading 0 means octal
    t.remove_prefix(1);
  }
  std::uint64_t v = 0;
  auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v, base);
  if (ec != std::errc{} || p != t.data() + t.size()) return std::nullopt;
  // INTEGER64 range: -2^63 .. 2^63 - 1; beyond it is no number (never a wrapped one).
  constexpr std::uint64_t max = std::numeric_limits<std::int64_t>::max();
  if (v > max + (neg ? 1u : 0u)) return std::nullopt;
  if (neg) return v == max + 1u ? std::numeric_limits<std::int64_t>::min() : -static_cast<std::int64_t>(v);
  return static_cast<std::int64_t>(v);
}

}  // namespace

std::optional<std::int64_t> eval_eds_integer(std::string_view text, NodeId node_id) noexcept {
  text = trim(text);
  if (text.empty()) return std::nullopt;
  std::int64_t sum = 0;
  std::size_t pos = 0;
  bool first = true;
  int sign = 1;
  while (pos < text.size()) {
    // Find the end of this term: the next + or - that is not a leading sign.
    std::size_t end = pos;
    if (first && (text[end] == '-' || text[end] == '+')) ++end;
    while (end < text.size() && text[end] != '+' && text[end] != '-') ++end;
    auto term = trim(text.substr(pos, end - pos));
    std::int64_t value = 0;
    if (term.size() == 7 && lower(term) == "$nodeid") {
      value = node_id;
    } else {
      auto v = parse_literal(term);
      if (!v) return std::nullopt;
      value = *v;
    }
    if (sign < 0 ? __builtin_sub_overflow(sum, value, &sum) : __builtin_add_overflow(sum, value, &sum))
      return std::nullopt;  // beyond INTEGER64
    first = false;
    if (end >= text.size()) break;
    sign = text[end] == '-' ? -1 : 1;
    pos = end + 1;
    if (pos >= text.size()) return std::nullopt;  // trailing operator
  }
  return sum;
}

std::expected<DeviceDescription, ConfigError> parse_eds(std::string_view text, std::string_view file_name,
                                                        NodeId node_id) {
  return Parser(text, file_name, node_id).run();
}

std::expected<DeviceDescription, ConfigError> load_eds(const std::filesystem::path& path, NodeId node_id) {
  auto text = read_text_file(path);
  if (!text) {
    ConfigError e;
    e.file = path.string();
    e.message = text.error();
    return std::unexpected(e);
  }
  return parse_eds(*text, path.string(), node_id);
}

}  // namespace hil::canopen
