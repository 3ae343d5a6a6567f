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
#include <set>
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

std::optional<std::int64_t> parse_literal(std::string_view t) noexcept;

struct Entry {
  std::string value;
  int line = 0;
};
struct Section {
  std::string name;
  int line = 0;
  std::map<std::string, Entry> keys;  // normalised key: lower case, no blanks
  [[nodiscard]] const Entry* get(std::string_view key) const {
    auto it = keys.find(lower(key));
    return it == keys.end() ? nullptr : &it->second;
  }
};

/// Keys as CiA 306 spells them; other spellings are accepted with one warning per file.
constexpr std::string_view k_canonical_keys[] = {"ParameterName",
                                                 "ObjectType",
                                                 "DataType",
                                                 "AccessType",
                                                 "DefaultValue",
                                                 "ParameterValue",
                                                 "PDOMapping",
                                                 "LowLimit",
                                                 "HighLimit",
                                                 "SubNumber",
                                                 "CompactSubObj",
                                                 "ObjFlags",
                                                 "Denotation",
                                                 "SupportedObjects",
                                                 "VendorName",
                                                 "VendorNumber",
                                                 "ProductName",
                                                 "ProductNumber",
                                                 "RevisionNumber",
                                                 "OrderCode",
                                                 "NodeID",
                                                 "Granularity",
                                                 "NrOfRXPDO",
                                                 "NrOfTXPDO",
                                                 "NrOfEntries",
                                                 "FileName",
                                                 "FileVersion",
                                                 "FileRevision",
                                                 "EDSVersion",
                                                 "Description",
                                                 "CreationTime",
                                                 "CreationDate",
                                                 "CreatedBy",
                                                 "ModificationTime",
                                                 "ModificationDate",
                                                 "ModifiedBy",
                                                 "SimpleBootUpMaster",
                                                 "SimpleBootUpSlave",
                                                 "DynamicChannelsSupported",
                                                 "GroupMessaging",
                                                 "LSS_Supported",
                                                 "BaudRate_10",
                                                 "BaudRate_20",
                                                 "BaudRate_50",
                                                 "BaudRate_125",
                                                 "BaudRate_250",
                                                 "BaudRate_500",
                                                 "BaudRate_800",
                                                 "BaudRate_1000",
                                                 "Lines",
                                                 "NetNumber",
                                                 "NetworkName",
                                                 "CANopenManager",
                                                 "LSS_SerialNumber",
                                                 "ObjectLinks"};

std::string normalise_key(std::string_view k) {
  std::string out;
  for (char c : k)
    if (!std::isspace(static_cast<unsigned char>(c)))
      out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  return out;
}

bool is_hex(std::string_view s) {
  return !s.empty() &&
         std::all_of(s.begin(), s.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); });
}

class Parser {
 public:
  Parser(std::string_view text, std::string_view file, NodeId node) : text_(text), file_(file), node_(node) {}

  std::expected<DeviceDescription, ConfigError> run();

 private:
  ConfigError error(int line, std::string_view section, std::string_view key, std::string message) const {
    ConfigError e;
    e.file = std::string(file_);
    e.line = line;
    e.key = key.empty() ? (section.empty() ? std::string() : fmt::format("[{}]", section))
                        : fmt::format("[{}] {}", section, key);
    e.message = std::move(message);
    return e;
  }
  void warn(int line, std::string_view section, std::string_view key, std::string message) {
    out_.warnings.push_back(error(line, section, key, std::move(message)));
  }
  std::optional<ConfigError> split();
  const Section* section(std::string_view name) const {
    auto it = sections_.find(lower(name));
    return it == sections_.end() ? nullptr : &it->second;
  }
  std::expected<std::int64_t, ConfigError> integer(const Section& s, std::string_view key,
                                                   std::optional<std::int64_t> dflt) const;
  /// An optional integer key: a malformed value is a warning and gives `dflt`.
  std::int64_t lenient_integer(const Section& s, std::string_view key, std::int64_t dflt, std::string_view what);
  std::expected<std::vector<std::uint8_t>, ConfigError> encode(const Section& s, const Entry& e, std::string_view key,
                                                               DataType type) const;
  std::optional<ConfigError> add_var(const Section& s, std::uint16_t index, std::uint8_t sub, const Section* parent);
  std::optional<ConfigError> add_object(std::uint16_t index, const Section& s);
  std::optional<ConfigError> add_compact(std::uint16_t index, const Section& s, std::int64_t count);

  std::string_view text_;
  std::string_view file_;
  NodeId node_;
  std::map<std::string, Section> sections_;
  std::vector<const Section*> order_;  ///< sections in file order
  DeviceDescription out_;
};

std::optional<ConfigError> Parser::split() {
  Section* current = nullptr;
  int line_no = 0;
  std::size_t pos = 0;
  if (text_.starts_with("\xEF\xBB\xBF")) {
    pos = 3;
    warn(1, "", "", "UTF-8 byte-order mark at the start of the file: skipped");
  }
  std::optional<int> key_case_line;
  std::string key_case_example;
  int key_case_count = 0;
  std::optional<int> comment_line;
  int comment_count = 0;
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
      if (!trim(line.substr(close + 1)).empty() && trim(line.substr(close + 1))[0] != ';')
        warn(line_no, name, "",
             fmt::format("text after the section header ignored: '{}'", trim(line.substr(close + 1))));
      auto& sec = sections_[lower(name)];  // duplicate sections merge (seen in vendor files)
      if (sec.name.empty()) {
        sec.name = std::string(name);
        sec.line = line_no;
        order_.push_back(&sec);
      } else {
        warn(line_no, name, "",
             fmt::format("section appears again (first at line {}): its keys are merged, later values win", sec.line));
      }
      current = &sec;
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string_view::npos) return error(line_no, current ? current->name : "", line, "expected Key=Value");
    const auto raw_key = trim(line.substr(0, eq));
    if (current == nullptr) return error(line_no, "", raw_key, "key outside of any section");
    auto value = trim(line.substr(eq + 1));
    // Inline comments (" ; ...") as python-canopen's configparser strips them.
    for (std::size_t i = 1; i < value.size(); ++i) {
      if (value[i] == ';' && std::isspace(static_cast<unsigned char>(value[i - 1]))) {
        value = trim(value.substr(0, i));
        if (!comment_line) comment_line = line_no;
        ++comment_count;
        break;
      }
    }
    const auto key = normalise_key(raw_key);
    if (raw_key.empty()) return error(line_no, current->name, line, "expected Key=Value (the key is empty)");
    bool canonical = true;
    for (auto k : k_canonical_keys) {
      if (normalise_key(k) == key) {
        canonical = k == raw_key;
        break;
      }
    }
    if (!canonical) {
      if (!key_case_line) {
        key_case_line = line_no;
        key_case_example = fmt::format("[{}] {}", current->name, raw_key);
      }
      ++key_case_count;
    }
    if (auto it = current->keys.find(key); it != current->keys.end())
      warn(line_no, current->name, raw_key,
           fmt::format("key given again (first at line {}): the later value '{}' is used", it->second.line, value));
    current->keys[key] = Entry{std::string(value), line_no};
  }
  if (key_case_line)
    warn(*key_case_line, "", "",
         fmt::format("{} key(s) not spelled as CiA 306 writes them, first '{}': keys are read case- and "
                     "blank-insensitively",
                     key_case_count, key_case_example));
  if (comment_line)
    warn(*comment_line, "", "",
         fmt::format("{} value(s) carry an inline ';' comment (first here): the comment is ignored", comment_count));
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

std::int64_t Parser::lenient_integer(const Section& s, std::string_view key, std::int64_t dflt, std::string_view what) {
  auto v = integer(s, key, dflt);
  if (v) return *v;
  warn(v.error().line, s.name, key, fmt::format("{}: {}", v.error().message, what));
  return dflt;
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
                                           const Section* parent) {
  Variable v;
  v.index = index;
  v.sub = sub;
  if (const auto* name = s.get("ParameterName"); name != nullptr && !name->value.empty()) {
    v.name = name->value;
  } else if (const auto* den = s.get("Denotation"); den != nullptr && !den->value.empty()) {
    v.name = den->value;
  } else {
    v.name = fmt::format("0x{:04X}:{}", index, sub);
    warn(s.line, s.name, "ParameterName", fmt::format("missing: the object is named '{}'", v.name));
  }
  const auto* dt = s.get("DataType");
  if (dt == nullptr && parent != nullptr) dt = parent->get("DataType");
  if (dt == nullptr) {
    warn(s.line, s.name, "DataType", fmt::format("missing: 0x{:04X}:{} skipped (its size is unknown)", index, sub));
    return std::nullopt;
  }
  auto code = eval_eds_integer(dt->value, 0);
  const auto type = code && *code >= 0 ? data_type_from_code(static_cast<std::uint32_t>(*code)) : std::nullopt;
  if (!type) {
    warn(dt->line, s.name, "DataType",
         code ? fmt::format("unsupported data type 0x{:04X}: 0x{:04X}:{} skipped", *code, index, sub)
              : fmt::format("'{}' is not a number: 0x{:04X}:{} skipped", dt->value, index, sub));
    return std::nullopt;
  }
  v.type = *type;
  const auto* acc = s.get("AccessType");
  if (acc == nullptr && parent != nullptr) acc = parent->get("AccessType");
  if (acc == nullptr || acc->value.empty()) {
    warn(s.line, s.name, "AccessType", "missing: taken as rw (as python-canopen does)");
    v.access = Access::rw;
  } else if (auto a = access_from_string(acc->value)) {
    v.access = *a;
  } else {
    warn(acc->line, s.name, "AccessType",
         fmt::format("'{}' is not one of ro, wo, rw, rwr, rww, const: taken as rw", acc->value));
    v.access = Access::rw;
  }
  v.pdo_mappable = lenient_integer(s, "PDOMapping", 0, "taken as 0 (not mappable)") != 0;
  for (const auto* key : {"LowLimit", "HighLimit"}) {
    if (const auto* e = s.get(key); e != nullptr && !e->value.empty() && is_integer(v.type)) {
      auto x = eval_eds_integer(e->value, node_);
      if (!x) {
        warn(e->line, s.name, key, fmt::format("'{}' is not an integer expression: no limit", e->value));
        continue;
      }
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
    if (!bytes) {
      // python-canopen keeps an unreadable default as text; only a value that cannot fit is an error.
      if (bytes.error().message.find("does not fit") != std::string::npos ||
          bytes.error().message.find("BOOLEAN") != std::string::npos)
        return bytes.error();
      warn(bytes.error().line, s.name, "DefaultValue", bytes.error().message + ": the default is 0");
    } else {
      v.value = std::move(*bytes);
    }
  }
  if (const auto* pv = s.get("ParameterValue"); pv != nullptr && !pv->value.empty()) {
    auto bytes = encode(s, *pv, "ParameterValue", v.type);
    if (!bytes) return bytes.error();
    v.value = *bytes;
    out_.parameter_values.push_back(ParameterValue{index, sub, std::move(*bytes)});
    out_.is_dcf = true;
  }
  out_.od.add(std::move(v));
  return std::nullopt;
}

std::optional<ConfigError> Parser::add_compact(std::uint16_t index, const Section& s, std::int64_t count) {
  Variable sub0;
  sub0.index = index;
  sub0.name = "Highest sub-index supported";
  sub0.type = DataType::unsigned8;
  sub0.access = Access::ro;
  sub0.value = {static_cast<std::uint8_t>(count)};
  out_.od.add(sub0);
  const auto* names = section(fmt::format("{:04X}Name", index));
  const auto* values = section(fmt::format("{:04X}Value", index));
  for (std::int64_t i = 1; i <= count; ++i) {
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

std::optional<ConfigError> Parser::add_object(std::uint16_t index, const Section& s) {
  std::int64_t ot = 7;
  if (const auto* e = s.get("ObjectType"); e == nullptr || e->value.empty()) {
    if (s.get("SubNumber") || s.get("CompactSubObj")) {
      ot = 9;
      warn(s.line, s.name, "ObjectType", "missing, but the object has sub-objects: taken as RECORD (0x9)");
    }
  } else if (auto v = eval_eds_integer(e->value, node_)) {
    ot = *v;
  } else {
    warn(e->line, s.name, "ObjectType", fmt::format("'{}' is not a number: 0x{:04X} skipped", e->value, index));
    return std::nullopt;
  }
  switch (ot) {
    case 0x7:
    case 0x2:  // DOMAIN
      return add_var(s, index, 0, nullptr);
    case 0x0:  // NULL
    case 0x5:  // DEFTYPE
    case 0x6:  // DEFSTRUCT
      return std::nullopt;
    case 0x8:
    case 0x9:
      break;
    default:
      warn(s.get("ObjectType")->line, s.name, "ObjectType",
           fmt::format("unsupported object type 0x{:X}: 0x{:04X} skipped", ot, index));
      return std::nullopt;
  }
  const auto compact = lenient_integer(s, "CompactSubObj", 0, "CompactSubObj ignored");
  if (compact > 0) {
    if (compact > 254) {
      warn(s.get("CompactSubObj")->line, s.name, "CompactSubObj",
           fmt::format("{} is not 1..254: 0x{:04X} skipped", compact, index));
      return std::nullopt;
    }
    return add_compact(index, s, compact);
  }
  const auto* sn = s.get("SubNumber");
  std::optional<std::int64_t> subnumber;
  if (sn == nullptr || sn->value.empty())
    warn(s.line, s.name, "SubNumber", "missing: every [xxxxsubN] section present is loaded");
  else if (auto v = eval_eds_integer(sn->value, node_))
    subnumber = *v;
  else
    warn(sn->line, s.name, "SubNumber",
         fmt::format("'{}' is not a number: every [xxxxsubN] section present is loaded", sn->value));
  int found = 0;
  int highest = -1;
  for (int sub = 0; sub <= 0xFF; ++sub) {
    const auto* ss = section(fmt::format("{:04X}sub{:X}", index, sub));
    if (ss == nullptr) continue;
    ++found;
    highest = sub;
    if (auto err = add_var(*ss, index, static_cast<std::uint8_t>(sub), &s)) return err;
  }
  if (subnumber && found != *subnumber)
    warn(sn->line, s.name, "SubNumber",
         fmt::format("says {} sub-objects but {} [{:04X}subN] sections exist: all {} are loaded", *subnumber, found,
                     index, found));
  if (found > 0 && out_.od.find(index, 0) == nullptr) {
    Variable sub0;
    sub0.index = index;
    sub0.name = "Highest sub-index supported";
    sub0.type = DataType::unsigned8;
    sub0.access = Access::ro;
    sub0.value = {static_cast<std::uint8_t>(highest)};
    out_.od.add(sub0);
    warn(s.line, s.name, "",
         fmt::format("no [{:04X}sub0] section: sub-index 0 is {} (the highest present)", index, highest));
  }
  return std::nullopt;
}

std::expected<DeviceDescription, ConfigError> Parser::run() {
  if (auto err = split()) return std::unexpected(*err);
  out_.file = std::string(file_);
  const Section* dc = section("DeviceComissioning");
  if (dc == nullptr && (dc = section("DeviceCommissioning")) != nullptr)
    warn(dc->line, dc->name, "", "CiA 306 spells it [DeviceComissioning]: read anyway");
  if (dc != nullptr) {
    out_.is_dcf = true;
    if (const auto* e = dc->get("NodeID"); e != nullptr && !e->value.empty()) {
      auto id = eval_eds_integer(e->value, 0);
      if (id && *id >= 1 && *id <= 127) {
        out_.dcf_node_id = static_cast<NodeId>(*id);
        if (node_ == 0) node_ = static_cast<NodeId>(*id);
      } else {
        warn(e->line, dc->name, "NodeID", fmt::format("'{}' is not a node-ID 1..127: ignored", e->value));
      }
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
    for (auto [key, dst] :
         {std::pair{"Granularity", &out_.info.granularity}, std::pair{"NrOfRXPDO", &out_.info.nr_of_rxpdo},
          std::pair{"NrOfTXPDO", &out_.info.nr_of_txpdo}}) {
      if (di->get(key) == nullptr) continue;
      const auto v = lenient_integer(*di, key, -1, "ignored");
      if (v >= 0) *dst = static_cast<int>(v);
    }
  } else {
    warn(0, "DeviceInfo", "", "missing: vendor, product and revision are unknown (no identity check)");
  }
  std::vector<std::pair<std::uint16_t, const Section*>> objects;
  std::set<std::uint16_t> listed_indices;
  bool listed = false;
  for (const auto* list_name : {"MandatoryObjects", "OptionalObjects", "ManufacturerObjects"}) {
    const auto* list = section(list_name);
    if (list == nullptr) continue;
    listed = true;
    std::vector<std::pair<std::int64_t, const Entry*>> entries;
    for (const auto& [k, e] : list->keys) {
      if (k == "supportedobjects") continue;
      const auto n = parse_literal(k);
      if (!n || *n < 1) {
        warn(e.line, list->name, k, "not a number of an entry: ignored");
        continue;
      }
      entries.emplace_back(*n, &e);
    }
    std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    const auto* so = list->get("SupportedObjects");
    if (so == nullptr) {
      warn(list->line, list->name, "SupportedObjects",
           fmt::format("missing: the {} entries present are used", entries.size()));
    } else if (auto count = eval_eds_integer(so->value, node_);
               !count || *count != static_cast<std::int64_t>(entries.size())) {
      warn(
          so->line, list->name, "SupportedObjects",
          fmt::format("says '{}' but {} entries are present: the entries present are used", so->value, entries.size()));
    }
    for (const auto& [n, e] : entries) {
      const auto key = std::to_string(n);
      auto idx = eval_eds_integer(e->value, node_);
      if (!idx || *idx < 1 || *idx > 0xFFFF) {
        warn(e->line, list->name, key, fmt::format("'{}' is not an object index 0x0001..0xFFFF: ignored", e->value));
        continue;
      }
      const auto* s = section(fmt::format("{:04X}", *idx));
      if (s == nullptr) {
        warn(e->line, list->name, key,
             fmt::format("object 0x{:04X} is listed but has no [{:04X}] section: ignored", *idx, *idx));
        continue;
      }
      if (!listed_indices.insert(static_cast<std::uint16_t>(*idx)).second) {
        warn(e->line, list->name, key, fmt::format("object 0x{:04X} is listed twice: loaded once", *idx));
        continue;
      }
      objects.emplace_back(static_cast<std::uint16_t>(*idx), s);
    }
  }
  // Every section, in file order: objects outside the lists are loaded (as python-canopen does),
  // anything unknown is reported.
  for (const Section* s : order_) {
    const auto key = lower(s->name);
    if (key.size() == 4 && is_hex(key)) {
      const auto idx = static_cast<std::uint16_t>(std::stoul(key, nullptr, 16));
      if (listed_indices.contains(idx)) continue;
      if (listed)
        warn(s->line, s->name, "",
             fmt::format("object 0x{:04X} is not in [MandatoryObjects], [OptionalObjects] or [ManufacturerObjects]: "
                         "loaded anyway",
                         idx));
      listed_indices.insert(idx);
      objects.emplace_back(idx, s);
      continue;
    }
    static const std::set<std::string> known = {"fileinfo",
                                                "deviceinfo",
                                                "dummyusage",
                                                "comments",
                                                "mandatoryobjects",
                                                "optionalobjects",
                                                "manufacturerobjects",
                                                "devicecomissioning",
                                                "devicecommissioning",
                                                "tools"};
    if (known.contains(key)) continue;
    if (key.size() > 4 && is_hex(key.substr(0, 4))) {
      const auto rest = key.substr(4);
      const auto parent = static_cast<std::uint16_t>(std::stoul(key.substr(0, 4), nullptr, 16));
      if (rest == "objectlinks" || rest == "name" || rest == "value") continue;
      if (rest.starts_with("sub") && is_hex(rest.substr(3))) {
        if (section(key.substr(0, 4)) == nullptr)
          warn(s->line, s->name, "",
               fmt::format("sub-object of 0x{:04X}, which has no [{:04X}] section: ignored", parent, parent));
        continue;
      }
    }
    if (key.starts_with("tool") || key == "supportedmodules" || key == "connectedmodules" ||
        (key.starts_with("m") && key.find("subext") != std::string::npos) ||
        (key.starts_with("m") && key.find("fixed") != std::string::npos)) {
      warn(s->line, s->name, "", "tool or modular-device section: ignored (modular devices are not supported)");
      continue;
    }
    warn(s->line, s->name, "", "unknown section: ignored");
  }
  for (const auto& [idx, s] : objects)
    if (auto err = add_object(idx, *s)) return std::unexpected(*err);
  if (out_.od.size() == 0) return std::unexpected(error(0, "", "", "no objects: not an EDS/DCF file?"));
  std::sort(out_.parameter_values.begin(), out_.parameter_values.end(),
            [](const auto& a, const auto& b) { return std::pair(a.index, a.sub) < std::pair(b.index, b.sub); });
  std::stable_sort(out_.warnings.begin(), out_.warnings.end(),
                   [](const ConfigError& a, const ConfigError& b) { return a.line < b.line; });
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
