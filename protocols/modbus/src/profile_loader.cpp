// SPDX-License-Identifier: MIT
// YAML -> Profile. Every error names the file, line, column and key, and says what is expected.
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "hil/config/yaml_config.hpp"
#include "hil/core/text_file.hpp"

#include "hil/modbus/exchange_plan.hpp"
#include "hil/modbus/profile.hpp"

namespace hil::modbus {
namespace {

class Loader {
 public:
  explicit Loader(std::string source) : source_(std::move(source)) {}

  std::unexpected<ConfigError> error(const YAML::Node& at, const std::string& key, std::string message) const {
    return std::unexpected(hil::yaml::error_at(at, {source_, key}, std::move(message)));
  }

  std::expected<void, ConfigError> only_keys(const YAML::Node& map, const std::string& where,
                                             std::initializer_list<std::string_view> allowed) const {
    return hil::yaml::check_keys(map, {source_, where}, allowed);
  }

  std::expected<std::int64_t, ConfigError> integer(const YAML::Node& n, const std::string& key, std::int64_t lo,
                                                   std::int64_t hi) const {
    std::int64_t v = 0;
    try {
      if (!n.IsScalar()) throw YAML::Exception(n.Mark(), "not a scalar");
      v = n.as<std::int64_t>();
    } catch (const YAML::Exception&) {
      return error(n, key,
                   fmt::format("expected an integer {}..{}, got '{}'", lo, hi, n.IsScalar() ? n.Scalar() : "?"));
    }
    if (v < lo || v > hi) return error(n, key, fmt::format("expected an integer {}..{}, got {}", lo, hi, v));
    return v;
  }

  std::expected<Profile, ConfigError> load(const YAML::Node& root) {
    Profile p;
    p.source = source_;
    if (!root.IsMap())
      return error(root, "", "a Modbus register profile must be a YAML map (name, state_machine, registers, ...)");
    if (auto r = only_keys(root, "",
                           {"name", "description", "state_machine", "unit", "function_codes", "modes", "registers",
                            "bits", "fault_texts"});
        !r)
      return std::unexpected(r.error());
    if (!root["name"] || !root["name"].IsScalar()) return error(root, "name", "missing: give the profile a name");
    p.name = root["name"].Scalar();
    if (root["description"]) p.description = root["description"].as<std::string>("");
    if (auto sm = root["state_machine"]) {
      const auto s = sm.as<std::string>("");
      if (s == "cia402")
        p.state_machine = StateMachineKind::cia402;
      else if (s == "vendor")
        p.state_machine = StateMachineKind::vendor;
      else
        return error(sm, "state_machine", fmt::format("expected 'cia402' or 'vendor', got '{}'", s));
    } else {
      return error(root, "state_machine", "missing: 'cia402' (control/status word per CiA 402) or 'vendor' (bits)");
    }
    if (auto u = root["unit"]) {
      auto v = integer(u, "unit", 0, 255);
      if (!v) return std::unexpected(v.error());
      p.unit_id = static_cast<std::uint8_t>(*v);
    }
    if (auto fcs = root["function_codes"]) {
      if (!fcs.IsMap())
        return error(fcs, "function_codes", "expected a map {read: 3|4, write: 6|16, read_write: true|false}");
      if (auto r = only_keys(fcs, "function_codes", {"read", "write", "read_write"}); !r)
        return std::unexpected(r.error());
      if (fcs["read"]) {
        auto v = integer(fcs["read"], "function_codes.read", 3, 4);
        if (!v) return std::unexpected(v.error());
        p.function_codes.read = static_cast<std::uint8_t>(*v);
      }
      if (fcs["write"]) {
        auto v = integer(fcs["write"], "function_codes.write", 6, 16);
        if (!v || (*v != 6 && *v != 16))
          return error(fcs["write"], "function_codes.write",
                       "expected 6 (write single register) or 16 (write multiple)");
        p.function_codes.write = static_cast<std::uint8_t>(*v);
      }
      if (fcs["read_write"]) {
        try {
          p.function_codes.read_write = fcs["read_write"].as<bool>();
        } catch (const YAML::Exception&) {
          return error(fcs["read_write"], "function_codes.read_write", "expected true (use FC 23) or false");
        }
      }
    }
    if (auto modes = root["modes"]) {
      if (auto r = only_keys(modes, "modes", {"position", "velocity", "homing"}); !r) return std::unexpected(r.error());
      if (modes["position"]) {
        auto v = integer(modes["position"], "modes.position", -32768, 65535);
        if (!v) return std::unexpected(v.error());
        p.mode_position = *v;
      }
      if (modes["velocity"]) {
        auto v = integer(modes["velocity"], "modes.velocity", -32768, 65535);
        if (!v) return std::unexpected(v.error());
        p.mode_velocity = *v;
      }
    }
    if (auto r = load_registers(root, p); !r) return std::unexpected(r.error());
    if (auto modes = root["modes"]; modes && modes["homing"]) {
      auto v = integer(modes["homing"], "modes.homing", -32768, 65535);
      if (!v) return std::unexpected(v.error());
      if (p.state_machine != StateMachineKind::cia402)
        return error(modes["homing"], "modes.homing",
                     "homing needs the cia402 state machine (bit 4 starts it, status bits 12/13 report it)");
      if (!p.field(FieldRole::mode).present)
        return error(modes["homing"], "modes.homing", "homing needs a `mode` register to select the homing mode");
      p.mode_homing = *v;
    }
    if (auto r = load_bits(root, p); !r) return std::unexpected(r.error());
    if (auto ft = root["fault_texts"]) {
      if (!ft.IsMap()) return error(ft, "fault_texts", "expected a map {code: text}");
      for (const auto& kv : ft) {
        auto code = integer(kv.first, "fault_texts", 0, 0xFFFFFFFF);
        if (!code) return std::unexpected(code.error());
        p.fault_texts[static_cast<std::uint32_t>(*code)] = kv.second.as<std::string>("");
      }
    }
    if (auto plan = make_exchange_plan(p); !plan)
      return error(root["function_codes"].IsDefined() ? root["function_codes"] : root, "function_codes", plan.error());
    return p;
  }

 private:
  std::expected<void, ConfigError> load_registers(const YAML::Node& root, Profile& p) {
    const YAML::Node regs = root["registers"];
    if (!regs || !regs.IsMap())
      return error(root, "registers",
                   "missing: map of control_word, status_word, target_position, actual_position, ...");
    static constexpr std::array<std::string_view, kFieldRoleCount> names = {
        "control_word",    "mode",      "target_position", "target_velocity", "status_word", "actual_position",
        "actual_velocity", "fault_code"};
    if (auto r = only_keys(regs, "registers",
                           {names[0], names[1], names[2], names[3], names[4], names[5], names[6], names[7]});
        !r)
      return std::unexpected(r.error());
    for (std::size_t i = 0; i < kFieldRoleCount; ++i) {
      const auto role = static_cast<FieldRole>(i);
      const std::string key = "registers." + std::string(names[i]);
      const YAML::Node n = regs[std::string(names[i])];
      if (!n) {
        if (role == FieldRole::control_word || role == FieldRole::status_word || role == FieldRole::target_position ||
            role == FieldRole::actual_position)
          return error(regs, key, "missing: this register is required");
        continue;
      }
      if (!n.IsMap())
        return error(n, key,
                     "expected a map {address: N, type: u16|s16|u32|s32, word_order: high_first|low_first, scale: X}");
      if (auto r = only_keys(n, key, {"address", "type", "word_order", "scale"}); !r) return std::unexpected(r.error());
      RegisterField f;
      f.present = true;
      if (!n["address"]) return error(n, key + ".address", "missing: the register's PDU address 0..65535");
      auto addr = integer(n["address"], key + ".address", 0, 65535);
      if (!addr) return std::unexpected(addr.error());
      f.address = static_cast<std::uint16_t>(*addr);
      const std::string type = n["type"] ? n["type"].as<std::string>("") : "u16";
      if (type == "u16")
        f.format = {1, false, WordOrder::high_first};
      else if (type == "i16" || type == "s16")  // i16: the CLI's type names (docs/cli.md); s16 as before
        f.format = {1, true, WordOrder::high_first};
      else if (type == "u32")
        f.format = {2, false, WordOrder::high_first};
      else if (type == "i32" || type == "s32")
        f.format = {2, true, WordOrder::high_first};
      else
        return error(n["type"], key + ".type", fmt::format("expected u16, i16, u32 or i32, got '{}'", type));
      if (auto wo = n["word_order"]) {
        const auto s = wo.as<std::string>("");
        if (s == "high_first")
          f.format.order = WordOrder::high_first;
        else if (s == "low_first")
          f.format.order = WordOrder::low_first;
        else
          return error(wo, key + ".word_order", fmt::format("expected high_first or low_first, got '{}'", s));
        if (f.format.words != 2)
          return error(wo, key + ".word_order", "word_order applies to 32-bit types (u32, s32) only");
      }
      if (auto sc = n["scale"]) {
        try {
          f.scale = sc.as<double>();
        } catch (const YAML::Exception&) {
          return error(sc, key + ".scale", "expected a number (drive increments per register unit)");
        }
        if (!(f.scale > 0.0) || f.scale > 1e9)
          return error(sc, key + ".scale", "expected a positive number (increments per register unit)");
        if (role == FieldRole::control_word || role == FieldRole::status_word || role == FieldRole::mode ||
            role == FieldRole::fault_code)
          return error(sc, key + ".scale", "scale applies to positions and velocities only");
      }
      if ((role == FieldRole::control_word || role == FieldRole::status_word) && f.format.words != 1)
        return error(n, key + ".type", "control and status words are 16-bit (u16)");
      if (std::uint32_t{f.address} + f.words() > 65536)
        return error(n, key + ".address", "field runs past address 65535");
      if (is_command(role) && f.words() == 2 && p.function_codes.write == 6)
        return error(n, key + ".type",
                     "32-bit command fields need FC 16 (two FC 6 writes are not atomic); set function_codes.write: 16");
      p.field(role) = f;
    }
    // Overlaps within one space.
    for (std::size_t i = 0; i < kFieldRoleCount; ++i)
      for (std::size_t j = i + 1; j < kFieldRoleCount; ++j) {
        const auto& a = p.fields[i];
        const auto& b = p.fields[j];
        if (!a.present || !b.present) continue;
        if (p.space_of(static_cast<FieldRole>(i)) != p.space_of(static_cast<FieldRole>(j))) continue;
        if (a.address < b.address + b.words() && b.address < a.address + a.words())
          return error(regs[std::string(names[j])], "registers." + std::string(names[j]),
                       fmt::format("overlaps registers.{} at address {}", names[i], a.address));
      }
    return {};
  }

  std::expected<void, ConfigError> load_bits(const YAML::Node& root, Profile& p) {
    const YAML::Node bits = root["bits"];
    if (bits) {
      if (!bits.IsMap()) return error(bits, "bits", "expected a map of bit numbers 0..15");
      if (auto r = only_keys(bits, "bits",
                             {"enable", "fault_reset", "quick_stop", "ready", "enabled", "fault", "referenced"});
          !r)
        return std::unexpected(r.error());
      auto get = [&](const char* k, int& out) -> std::expected<void, ConfigError> {
        if (!bits[k]) return {};
        auto v = integer(bits[k], std::string("bits.") + k, 0, 15);
        if (!v) return std::unexpected(v.error());
        out = static_cast<int>(*v);
        return {};
      };
      for (auto [k, ref] : std::initializer_list<std::pair<const char*, int*>>{{"enable", &p.bits.enable},
                                                                               {"fault_reset", &p.bits.fault_reset},
                                                                               {"quick_stop", &p.bits.quick_stop},
                                                                               {"ready", &p.bits.ready},
                                                                               {"enabled", &p.bits.enabled},
                                                                               {"fault", &p.bits.fault},
                                                                               {"referenced", &p.bits.referenced}})
        if (auto r = get(k, *ref); !r) return r;
      if (p.state_machine == StateMachineKind::cia402) {
        for (const auto& kv : bits)
          if (kv.first.as<std::string>() != "referenced")
            return error(kv.first, "bits." + kv.first.as<std::string>(),
                         "a cia402 profile uses the CiA 402 word layout; only bits.referenced may be set");
      }
    }
    if (p.state_machine == StateMachineKind::vendor) {
      for (auto [k, v] : std::initializer_list<std::pair<const char*, int>>{{"enable", p.bits.enable},
                                                                            {"fault_reset", p.bits.fault_reset},
                                                                            {"ready", p.bits.ready},
                                                                            {"enabled", p.bits.enabled},
                                                                            {"fault", p.bits.fault}})
        if (v < 0)
          return error(bits ? bits : root, std::string("bits.") + k,
                       "missing: a vendor state machine needs this bit number 0..15");
    }
    return {};
  }

  std::string source_;
};

}  // namespace

std::expected<Profile, ConfigError> parse_profile(const std::string& yaml_text, const std::string& source) {
  auto doc = hil::yaml::load_string(yaml_text, source);
  if (!doc) return std::unexpected(doc.error());
  const YAML::Node& root = *doc;
  try {
    return Loader(source).load(root);
  } catch (const YAML::Exception& e) {
    ConfigError err;
    err.file = source;
    err.line = e.mark.line >= 0 ? e.mark.line + 1 : 0;
    err.message = "unexpected YAML structure: " + e.msg;
    return std::unexpected(err);
  }
}

std::expected<Profile, ConfigError> load_profile(const std::string& path) {
  auto text = read_text_file(path);
  if (!text) {
    ConfigError err;
    err.file = path;
    err.message = text.error() + " (Modbus profiles: profiles/modbus/*.yaml)";
    return std::unexpected(err);
  }
  return parse_profile(*text, path);
}

}  // namespace hil::modbus
