// SPDX-License-Identifier: MIT
#include "hil/cia402/layout.hpp"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

namespace hil::cia402 {
namespace {

using canopen::DeviceDescription;
using canopen::ParameterValue;
using canopen::PdoConfig;
using canopen::PdoMappingEntry;

std::vector<std::uint8_t> le(std::uint64_t v, std::size_t n) {
  std::vector<std::uint8_t> b(n);
  for (std::size_t i = 0; i < n; ++i) b[i] = static_cast<std::uint8_t>(v >> (8 * i));
  return b;
}

struct Wish {
  std::uint16_t index;
  const char* name;
  bool required;
  std::uint8_t sub = 0;
};

/// An object's place in the `covered` / `placed` lists: index and sub-index.
constexpr std::uint32_t key_of(std::uint16_t index, std::uint8_t sub) noexcept {
  return (std::uint32_t{index} << 8) | sub;
}

const char* object_name(std::uint16_t index) {
  switch (index) {
    case 0x603F:
      return "error code";
    case 0x6040:
      return "controlword";
    case 0x6041:
      return "statusword";
    case 0x6060:
      return "modes of operation";
    case 0x6061:
      return "modes of operation display";
    case 0x6064:
      return "position actual value";
    case 0x606C:
      return "velocity actual value";
    case 0x6077:
      return "torque actual value";
    case 0x607A:
      return "target position";
    case 0x6081:
      return "profile velocity";
    case 0x6083:
      return "profile acceleration";
    case 0x6084:
      return "profile deceleration";
    case 0x60F4:
      return "following error actual value";
    case 0x60FD:
      return "digital inputs";
    case 0x60FE:
      return "digital outputs";
    case 0x60FF:
      return "target velocity";
    default:
      return "object";
  }
}

std::string describe_object(std::uint16_t index, std::uint8_t sub = 0) {
  if (sub == 0) return fmt::format("0x{:04X} {}", index, object_name(index));
  const std::string_view name = object_name(index);
  return name == "object" ? fmt::format("0x{:04X}:{}", index, sub) : fmt::format("0x{:04X}:{} {}", index, sub, name);
}

/// The node's PDO `n` of one direction as its EDS/DCF declares it.
struct Resource {
  unsigned n = 0;
  std::uint16_t comm = 0;
  std::uint16_t map = 0;
  std::size_t max_entries = 0;
  bool fixed = false;
  std::string why_fixed;
  bool dcf = false;
  bool cob_writable = true;
  bool tt_writable = true;
  std::uint32_t cob = 0;  ///< the EDS/DCF value (with bit 31 as declared)
  std::vector<PdoMappingEntry> declared;
};

std::vector<Resource> resources(const DeviceDescription& eds, bool rx, canopen::NodeId node) {
  std::vector<Resource> out;
  const auto& od = eds.od;
  for (unsigned n = 0; n < 512; ++n) {
    Resource r;
    r.n = n;
    r.comm = static_cast<std::uint16_t>((rx ? 0x1400 : 0x1800) + n);
    r.map = static_cast<std::uint16_t>((rx ? 0x1600 : 0x1A00) + n);
    const auto* cob = od.find(r.comm, 1);
    if (cob == nullptr || !od.has_object(r.map)) continue;
    for (std::uint8_t s = 1; s <= 8; ++s)
      if (od.find(r.map, s) != nullptr) r.max_entries = s;
    if (r.max_entries == 0) continue;
    r.cob = static_cast<std::uint32_t>(cob->as_uint());
    if ((r.cob & 0x7FF) == 0 && n < 4)
      r.cob = (r.cob & canopen::pdo_cob_invalid) | ((rx ? 0x200u : 0x180u) + 0x100u * n + node);
    r.cob_writable = canopen::writable(cob->access);
    const auto* tt = od.find(r.comm, 2);
    r.tt_writable = tt != nullptr && canopen::writable(tt->access);
    const auto* sub0 = od.find(r.map, 0);
    if (eds.info.granularity && *eds.info.granularity == 0) {
      r.fixed = true;
      r.why_fixed = "[DeviceInfo] Granularity=0";
    } else if (sub0 == nullptr || !canopen::writable(sub0->access)) {
      r.fixed = true;
      r.why_fixed = fmt::format("0x{:04X}:0 is {}", r.map, sub0 ? canopen::to_string(sub0->access) : "missing");
    } else {
      for (std::uint8_t s = 1; s <= r.max_entries; ++s) {
        const auto* e = od.find(r.map, s);
        if (e != nullptr && !canopen::writable(e->access)) {
          r.fixed = true;
          r.why_fixed = fmt::format("0x{:04X}:{} is {}", r.map, s, canopen::to_string(e->access));
          break;
        }
      }
    }
    const auto count = sub0 ? std::min<std::uint64_t>(sub0->as_uint(), 8) : 0;
    for (std::uint8_t s = 1; s <= count; ++s)
      if (const auto* e = od.find(r.map, s))
        r.declared.push_back(canopen::parse_mapping_entry(static_cast<std::uint32_t>(e->as_uint())));
    for (const auto& pv : eds.parameter_values)
      if (pv.index == r.comm || pv.index == r.map) r.dcf = true;
    out.push_back(std::move(r));
  }
  return out;
}

std::string pdo_name(bool rx, unsigned n) {
  return fmt::format("{}PDO{}", rx ? "R" : "T", n + 1);
}

std::string list_mapping(const std::vector<PdoMappingEntry>& m) {
  std::string s;
  for (const auto& e : m) {
    if (!s.empty()) s += ", ";
    s += e.sub == 0 ? fmt::format("0x{:04X} {} ({} bit)", e.index, object_name(e.index), e.bits)
                    : fmt::format("{} ({} bit)", describe_object(e.index, e.sub), e.bits);
  }
  return s.empty() ? "nothing" : s;
}

ConfigError layout_error(const DeviceDescription& eds, std::string message) {
  ConfigError e;
  e.file = eds.file;
  e.message = std::move(message);
  return e;
}

/// Plan one direction. `wishes` in priority order; returns the error text or empty.
std::string plan_direction(const DeviceDescription& eds, const AxisOptions& o, bool rx, const std::vector<Wish>& wishes,
                           const std::optional<std::vector<std::vector<PdoMappingEntry>>>& override_,
                           AxisLayout& layout) {
  const auto& od = eds.od;
  auto res = resources(eds, rx, o.node);
  auto& pdos = rx ? layout.rpdos : layout.tpdos;
  const char* dir = rx ? "RPDO" : "TPDO";
  std::vector<std::uint32_t> covered;  ///< key_of(index, sub)
  auto is_covered = [&](std::uint16_t idx, std::uint8_t sub) {
    return std::find(covered.begin(), covered.end(), key_of(idx, sub)) != covered.end();
  };
  auto bits_of = [&](std::uint16_t idx, std::uint8_t sub) -> std::uint8_t {
    const auto* v = od.find(idx, sub);
    return v ? static_cast<std::uint8_t>(8 * canopen::data_type_size(v->type)) : 0;
  };
  auto use_declared = [&](const Resource& r, PlannedPdo::Source src, const char* why) {
    PlannedPdo p;
    p.number = r.n;
    p.source = src;
    p.cob_id = r.cob & ~canopen::pdo_cob_invalid;
    p.mapping = r.declared;
    p.write_transmission_type = r.tt_writable;
    if (src == PlannedPdo::Source::dcf) {
      for (const auto& pv : eds.parameter_values)
        if (pv.index == r.comm || pv.index == r.map) p.dcf.push_back(pv);
    }
    const bool enabled = (r.cob & canopen::pdo_cob_invalid) == 0 || r.cob_writable;
    if (!enabled) {
      layout.decisions.push_back(
          fmt::format("{} 0x{:03X} ({}) is disabled in the EDS and its COB-ID is read-only: unused", pdo_name(rx, r.n),
                      p.cob_id, why));
      return;
    }
    for (const auto& e : p.mapping) covered.push_back(key_of(e.index, e.sub));
    layout.decisions.push_back(
        fmt::format("{} 0x{:03X} {}: {}", pdo_name(rx, r.n), p.cob_id, why, list_mapping(p.mapping)));
    pdos.push_back(std::move(p));
  };

  std::vector<const Resource*> free;
  for (const auto& r : res) {
    if (r.dcf) {
      use_declared(r, PlannedPdo::Source::dcf, "as the DCF maps it (written with the CiA 301 sequence)");
    } else if (r.fixed) {
      if (override_ || std::any_of(r.declared.begin(), r.declared.end(), [&](const PdoMappingEntry& e) {
            return std::any_of(wishes.begin(), wishes.end(),
                               [&](const Wish& w) { return w.index == e.index && w.sub == e.sub; });
          }))
        use_declared(r, PlannedPdo::Source::fixed, fmt::format("fixed ({}), read from the EDS", r.why_fixed).c_str());
    } else {
      free.push_back(&r);
    }
  }
  if (res.empty())
    layout.decisions.push_back(fmt::format("the EDS declares no {}s (0x{:04X}.. with 0x{:04X}..)", dir,
                                           rx ? 0x1400 : 0x1800, rx ? 0x1600 : 0x1A00));

  std::vector<std::vector<PdoMappingEntry>> planned(free.size());
  if (override_) {
    if (override_->size() > free.size())
      return fmt::format("the scenario maps {} {}s, but the node has only {} remappable one(s) in {}",
                         override_->size(), dir, free.size(), eds.file);
    for (std::size_t k = 0; k < override_->size(); ++k) {
      const auto& want = (*override_)[k];
      if (want.size() > free[k]->max_entries)
        return fmt::format("scenario {} {}: {} entries, but 0x{:04X} has room for {} in {}", dir, k + 1, want.size(),
                           free[k]->map, free[k]->max_entries, eds.file);
      unsigned total = 0;
      for (const auto& e : want) {
        const auto* v = od.find(e.index, e.sub);
        if (v == nullptr)
          return fmt::format("scenario {} {}: 0x{:04X}:{} is not in {}", dir, k + 1, e.index, e.sub, eds.file);
        if (!v->pdo_mappable)
          return fmt::format("scenario {} {}: 0x{:04X}:{} is not PDO-mappable in {} (PDOMapping=0)", dir, k + 1,
                             e.index, e.sub, eds.file);
        total += e.bits;
        covered.push_back(key_of(e.index, e.sub));
      }
      if (total > 64) return fmt::format("scenario {} {}: {} bits exceed the 64 bits of a PDO", dir, k + 1, total);
      planned[k] = want;
    }
    layout.decisions.push_back(fmt::format("{}s: the scenario's mapping is used", dir));
  } else {
    // First fit in the wish order; if a required object finds no room that way, again with the
    // required objects first.
    auto pack = [&](const std::vector<Wish>& order, std::vector<std::uint32_t>& placed) {
      std::vector<std::vector<PdoMappingEntry>> plan(free.size());
      for (const auto& w : order) {
        if (is_covered(w.index, w.sub)) continue;
        const auto* v = od.find(w.index, w.sub);
        if (v == nullptr || !v->pdo_mappable) continue;
        const auto b = bits_of(w.index, w.sub);
        if (b == 0 || b % 8 != 0) continue;
        for (std::size_t k = 0; k < free.size(); ++k) {
          unsigned total = 0;
          for (const auto& e : plan[k]) total += e.bits;
          if (plan[k].size() < free[k]->max_entries && total + b <= 64) {
            plan[k].push_back({w.index, w.sub, b});
            placed.push_back(key_of(w.index, w.sub));
            break;
          }
        }
      }
      return plan;
    };
    auto all_required = [&](const std::vector<std::uint32_t>& placed) {
      for (const auto& w : wishes) {
        const auto* v = od.find(w.index, w.sub);
        if (!w.required || v == nullptr || !v->pdo_mappable) continue;
        if (!is_covered(w.index, w.sub) &&
            std::find(placed.begin(), placed.end(), key_of(w.index, w.sub)) == placed.end())
          return false;
      }
      return true;
    };
    std::vector<std::uint32_t> placed;
    planned = pack(wishes, placed);
    if (!all_required(placed)) {
      std::vector<Wish> order;
      for (const auto& w : wishes)
        if (w.required) order.push_back(w);
      for (const auto& w : wishes)
        if (!w.required) order.push_back(w);
      placed.clear();
      planned = pack(order, placed);
    }
    covered.insert(covered.end(), placed.begin(), placed.end());
  }
  for (std::size_t k = 0; k < free.size(); ++k) {
    const auto& r = *free[k];
    PlannedPdo p;
    p.number = r.n;
    p.cob_id = r.cob & ~canopen::pdo_cob_invalid;
    p.write_transmission_type = r.tt_writable;
    p.mapping = planned[k];
    if (p.mapping.empty()) {
      p.source = PlannedPdo::Source::disabled;
      layout.decisions.push_back(fmt::format("{} 0x{:03X}: not needed, disabled", pdo_name(rx, r.n), p.cob_id));
    } else {
      p.source = PlannedPdo::Source::remapped;
      layout.decisions.push_back(fmt::format("{} 0x{:03X} mapped by hilbridge (up to {} entries): {}",
                                             pdo_name(rx, r.n), p.cob_id, r.max_entries, list_mapping(p.mapping)));
    }
    pdos.push_back(std::move(p));
  }
  std::sort(pdos.begin(), pdos.end(), [](const PlannedPdo& a, const PlannedPdo& b) { return a.number < b.number; });

  // Every wished object: in a PDO, by SDO, or absent.
  std::vector<std::string> missing;
  for (const auto& w : wishes) {
    ObjectRoute route;
    route.index = w.index;
    route.sub = w.sub;
    route.to_node = rx;
    route.bits = bits_of(w.index, w.sub);
    const auto* v = od.find(w.index, w.sub);
    if (is_covered(w.index, w.sub)) {
      route.path = ObjectPath::pdo;
    } else if (v == nullptr) {
      route.path = ObjectPath::absent;
      if (!w.required)
        layout.decisions.push_back(fmt::format("{}: not in the EDS, left out{}", describe_object(w.index, w.sub),
                                               w.index == 0x603F   ? " (fault codes come from EMCY)"
                                               : w.index == 0x6061 ? " (the commanded mode is assumed in effect)"
                                               : w.index == 0x606C ? " (velocity feedback is 0)"
                                               : w.index == 0x60FD ? " (the axis has no digital inputs)"
                                               : w.index == 0x60FE ? " (the axis has no digital outputs)"
                                                                   : ""));
    } else if (w.required && (w.index == 0x6040 || w.index == 0x6041 || w.index == 0x6064 || w.index == 0x607A ||
                              w.index == 0x60FF)) {
      missing.push_back(fmt::format("{} is {} ", describe_object(w.index),
                                    v->pdo_mappable ? "not in any PDO (no room left)" : "not PDO-mappable"));
      continue;
    } else {
      route.path = rx ? ObjectPath::sdo_write : ObjectPath::sdo_poll;
      layout.decisions.push_back(fmt::format("{}: {}, {}", describe_object(w.index, w.sub),
                                             v->pdo_mappable ? "no room in the PDOs" : "not PDO-mappable",
                                             rx ? "written by SDO when it changes" : "read by SDO every 100 ms"));
    }
    layout.routes.push_back(route);
  }
  if (!missing.empty()) {
    std::string text;
    for (const auto& m : missing) text += (text.empty() ? "" : "; ") + m;
    return fmt::format("{} in {}: the cyclic {} needs it in a {}", text, eds.file, rx ? "set-point" : "feedback", dir);
  }
  return {};
}

/// Which 0x60FE:1 bits the master drives: the scenario's mask, written once to 0x60FE:2 during
/// the configuration download where the drive has a writable bit mask.
void plan_output_mask(const DeviceDescription& eds, const AxisOptions& o, AxisLayout& layout) {
  if (layout.path(0x60FE, 1) == ObjectPath::absent) return;
  const auto* mask = eds.od.find(0x60FE, 2);
  if (mask == nullptr) {
    layout.digital_output_mask = o.digital_output_mask;
    layout.decisions.push_back(fmt::format(
        "no 0x60FE:2 bit mask in the EDS: the master writes 0x60FE:1 with the bits of 0x{:08X} and 0 elsewhere",
        o.digital_output_mask));
  } else if (!canopen::writable(mask->access)) {
    layout.digital_output_mask = o.digital_output_mask & static_cast<std::uint32_t>(mask->as_uint());
    layout.decisions.push_back(
        fmt::format("0x60FE:2 bit mask is {} = 0x{:08X}: the outputs the master drives are 0x{:08X}",
                    canopen::to_string(mask->access), mask->as_uint(), layout.digital_output_mask));
  } else {
    layout.digital_output_mask = o.digital_output_mask;
    layout.write_output_mask = true;
    layout.decisions.push_back(
        fmt::format("0x60FE:2 bit mask = 0x{:08X}, written once at boot-up: the master drives these 0x60FE:1 outputs",
                    o.digital_output_mask));
  }
}

}  // namespace

std::string_view to_string(OperatingSetup s) noexcept {
  switch (s) {
    case OperatingSetup::csp:
      return "csp";
    case OperatingSetup::csv:
      return "csv";
    case OperatingSetup::pp:
      return "pp";
  }
  return "?";
}

ObjectPath AxisLayout::path(std::uint16_t index, std::uint8_t sub) const noexcept {
  for (const auto& r : routes)
    if (r.index == index && r.sub == sub) return r.path;
  return ObjectPath::absent;
}

std::vector<ObjectKey> AxisLayout::polled() const {
  std::vector<ObjectKey> out;
  for (const auto& r : routes)
    if (r.path == ObjectPath::sdo_poll) out.push_back({r.index, r.sub});
  return out;
}

std::vector<ObjectKey> AxisLayout::written() const {
  std::vector<ObjectKey> out;
  for (const auto& r : routes)
    if (r.path == ObjectPath::sdo_write) out.push_back({r.index, r.sub});
  return out;
}

std::expected<AxisLayout, ConfigError> plan_axis_layout(const DeviceDescription& eds, const AxisOptions& o) {
  AxisLayout layout;
  const auto& od = eds.od;
  const auto setup = o.setup;
  // Mandatory objects of a CiA 402 axis in this setup: all missing ones in one message.
  std::vector<std::uint16_t> mandatory = {0x6040, 0x6041, 0x6060, 0x6064};
  if (setup == OperatingSetup::csv)
    mandatory.push_back(0x60FF);
  else
    mandatory.push_back(0x607A);
  if (setup == OperatingSetup::pp) mandatory.push_back(0x6081);
  std::sort(mandatory.begin(), mandatory.end());
  std::string missing;
  for (auto idx : mandatory)
    if (od.find(idx, 0) == nullptr) missing += (missing.empty() ? "" : ", ") + describe_object(idx);
  if (!missing.empty()) {
    const auto device_type = od.find(0x1000, 0) ? static_cast<std::uint32_t>(od.get_int(0x1000, 0)) : 0u;
    return std::unexpected(layout_error(
        eds, fmt::format("not usable as a CiA 402 axis in mode {}: the EDS lacks {} (device type 0x{:08X}{}); give "
                         "the drive's EDS, or another `mode:`",
                         to_string(setup), missing, device_type,
                         (device_type & 0xFFFF) == 402 ? "" : ", not a CiA 402 device")));
  }
  // Supported modes (0x6502): the setup's mode must be there; homing only when HM is.
  if (const auto* modes = od.find(0x6502, 0)) {
    const auto m = static_cast<std::uint32_t>(modes->as_uint());
    layout.supported_modes = m;
    static constexpr std::pair<std::uint32_t, const char*> names[] = {
        {1u << 0, "PP"}, {1u << 1, "VL"},  {1u << 2, "PV"},  {1u << 3, "TQ"}, {1u << 5, "HM"},
        {1u << 6, "IP"}, {1u << 7, "CSP"}, {1u << 8, "CSV"}, {1u << 9, "CST"}};
    std::string list;
    for (auto [bit, name] : names)
      if (m & bit) list += (list.empty() ? "" : ", ") + std::string(name);
    const std::uint32_t need = setup == OperatingSetup::csp ? 1u << 7 : setup == OperatingSetup::csv ? 1u << 8 : 1u;
    if ((m & need) == 0)
      return std::unexpected(layout_error(
          eds, fmt::format("0x6502 supported drive modes = 0x{:08X} ({}): mode {} is not supported by this drive; "
                           "choose a `mode:` it has",
                           m, list.empty() ? "none" : list, to_string(setup))));
    layout.homing = (m & (1u << 5)) != 0;
    layout.decisions.push_back(fmt::format("0x6502 supported drive modes 0x{:08X}: {}; using {}{}", m, list,
                                           to_string(setup), layout.homing ? "" : "; no HM, homing is off"));
  } else {
    layout.decisions.push_back(fmt::format("no 0x6502 in the EDS: mode {} is assumed supported", to_string(setup)));
  }
  std::vector<Wish> rx = {{0x6040, "", true}, {0x6060, "", true}};
  if (setup == OperatingSetup::csv) {
    rx.push_back({0x60FF, "", true});
  } else {
    rx.push_back({0x607A, "", true});
    if (setup == OperatingSetup::pp) {
      rx.push_back({0x6081, "", true});
      rx.push_back({0x6083, "", false});
      rx.push_back({0x6084, "", false});
      rx.push_back({0x60FF, "", false});
    } else {
      rx.push_back({0x60FF, "", false});
    }
  }
  // Digital I/O last: optional, in a PDO where there is room, else by SDO (never blocking the cycle).
  rx.push_back({0x60FE, "", false, 1});
  const std::vector<Wish> tx = {{0x6041, "", true}, {0x6061, "", false}, {0x603F, "", false},
                                {0x6064, "", true}, {0x606C, "", false}, {0x60FD, "", false}};
  if (auto err = plan_direction(eds, o, true, rx, o.mapping.rpdo, layout); !err.empty())
    return std::unexpected(layout_error(eds, err));
  if (auto err = plan_direction(eds, o, false, tx, o.mapping.tpdo, layout); !err.empty())
    return std::unexpected(layout_error(eds, err));
  for (std::uint16_t idx : {std::uint16_t{0x6077}, std::uint16_t{0x60F4}}) {
    if (od.find(idx, 0) == nullptr) {
      layout.decisions.push_back(fmt::format("{}: not in the EDS, not read", describe_object(idx)));
      continue;
    }
    layout.routes.push_back({idx, 0, static_cast<std::uint8_t>(8 * canopen::data_type_size(od.find(idx, 0)->type)),
                             false, ObjectPath::sdo_poll});
    layout.decisions.push_back(fmt::format("{}: read by SDO every 100 ms (diagnostics)", describe_object(idx)));
  }
  plan_output_mask(eds, o, layout);
  return layout;
}

namespace {

void write_pdo(std::vector<ParameterValue>& out, bool rx, const PlannedPdo& p) {
  const auto comm = static_cast<std::uint16_t>((rx ? 0x1400 : 0x1800) + p.number);
  const auto map = static_cast<std::uint16_t>((rx ? 0x1600 : 0x1A00) + p.number);
  using Source = PlannedPdo::Source;
  switch (p.source) {
    case Source::disabled:
      out.push_back({comm, 1, le(p.cob_id | canopen::pdo_cob_invalid, 4)});
      return;
    case Source::remapped:
      out.push_back({comm, 1, le(p.cob_id | canopen::pdo_cob_invalid, 4)});  // 1. disable
      out.push_back({map, 0, le(0, 1)});                                     // 2. sub 0 = 0
      for (std::size_t i = 0; i < p.mapping.size(); ++i)                     // 3. entries
        out.push_back({map, static_cast<std::uint8_t>(i + 1), le(canopen::make_mapping_entry(p.mapping[i]), 4)});
      out.push_back({map, 0, le(p.mapping.size(), 1)});  // 4. count
      if (p.write_transmission_type) out.push_back({comm, 2, le(p.transmission_type, 1)});
      out.push_back({comm, 1, le(p.cob_id, 4)});  // 5. enable
      return;
    case Source::fixed:
      out.push_back({comm, 1, le(p.cob_id | canopen::pdo_cob_invalid, 4)});
      if (p.write_transmission_type) out.push_back({comm, 2, le(p.transmission_type, 1)});
      out.push_back({comm, 1, le(p.cob_id, 4)});
      return;
    case Source::dcf: {
      // The DCF's values, in the CiA 301 order: COB-ID invalid, mapping (sub 0 = 0, entries,
      // sub 0 = n), the other communication parameters, then the DCF's COB-ID.
      std::optional<ParameterValue> cob, count;
      std::vector<ParameterValue> entries, comm_rest;
      for (const auto& pv : p.dcf) {
        if (pv.index == comm && pv.sub == 1)
          cob = pv;
        else if (pv.index == comm)
          comm_rest.push_back(pv);
        else if (pv.sub == 0)
          count = pv;
        else
          entries.push_back(pv);
      }
      out.push_back({comm, 1, le(p.cob_id | canopen::pdo_cob_invalid, 4)});
      if (count || !entries.empty()) {
        out.push_back({map, 0, le(0, 1)});
        for (const auto& e : entries) out.push_back(e);
        out.push_back(count ? *count : ParameterValue{map, 0, le(p.mapping.size(), 1)});
      }
      for (const auto& c : comm_rest) out.push_back(c);
      out.push_back(cob ? *cob : ParameterValue{comm, 1, le(p.cob_id, 4)});
      return;
    }
  }
}

PdoConfig master_pdo(const PlannedPdo& p, std::uint8_t tt) {
  PdoConfig c;
  c.cob_id = p.cob_id;
  c.transmission_type = tt;
  c.mapping = p.mapping;
  return c;
}

}  // namespace

std::expected<AxisConfig, ConfigError> make_axis_config(const DeviceDescription& eds, const AxisOptions& o) {
  auto layout = plan_axis_layout(eds, o);
  if (!layout) return std::unexpected(layout.error());
  AxisConfig out;
  out.layout = std::move(*layout);
  auto& c = out.node;
  const auto& od = eds.od;
  const auto id = o.node;
  c.id = id;
  if (o.check_identity) {
    if (od.find(0x1000, 0)) c.device_type = static_cast<std::uint32_t>(od.get_int(0x1000, 0));
    if (eds.info.vendor_number != 0) c.vendor_id = eds.info.vendor_number;
    if (eds.info.product_number != 0) c.product_code = eds.info.product_number;
    if (eds.info.revision_number != 0) c.revision = eds.info.revision_number;
  }
  // The DCF's other ParameterValues first, in object order (eds.parameter_values is sorted).
  for (const auto& pv : eds.parameter_values)
    if (pv.index < 0x1400 || pv.index > 0x1BFF) c.configuration.push_back(pv);
  auto& decisions = out.layout.decisions;
  if (od.find(0x1017, 0) != nullptr) {
    const auto hb_ms = std::chrono::duration_cast<std::chrono::milliseconds>(o.heartbeat_producer).count();
    c.configuration.push_back({0x1017, 0, le(static_cast<std::uint64_t>(hb_ms), 2)});
    c.heartbeat_consumer = o.heartbeat_consumer;
    decisions.push_back(
        fmt::format("heartbeat: the node produces every {} ms (0x1017), the master expects it within {} ms", hb_ms,
                    std::chrono::duration_cast<std::chrono::milliseconds>(o.heartbeat_consumer).count()));
  } else if (od.find(0x100C, 0) != nullptr && od.find(0x100D, 0) != nullptr &&
             o.heartbeat_consumer > Duration::zero()) {
    // A legacy node: guard it instead. Guard time = the heartbeat period asked for, life-time
    // factor so that a loss is seen within about the heartbeat consumer time.
    const auto guard_ms =
        std::max<long long>(1, std::chrono::duration_cast<std::chrono::milliseconds>(o.heartbeat_producer).count());
    const auto factor = static_cast<std::uint8_t>(std::clamp<long long>(
        std::chrono::duration_cast<std::chrono::milliseconds>(o.heartbeat_consumer).count() / guard_ms, 2, 255));
    c.configuration.push_back({0x100C, 0, le(static_cast<std::uint64_t>(guard_ms), 2)});
    c.configuration.push_back({0x100D, 0, le(factor, 1)});
    c.guard_time = std::chrono::milliseconds(guard_ms);
    c.life_time_factor = factor;
    decisions.push_back(
        fmt::format("no 0x1017 heartbeat producer in the EDS: node guarding instead (0x100C guard "
                    "time {} ms, 0x100D life-time factor {}; needs RTR frames: SocketCAN or the "
                    "in-process bus, not socketcand)",
                    guard_ms, factor));
  } else {
    c.heartbeat_consumer = Duration::zero();
    decisions.push_back(
        "no 0x1017 heartbeat producer and no 0x100C/0x100D node guarding in the EDS: the node is not supervised; "
        "stale PDOs still fault the axis");
  }
  if (o.master_node != 0) {
    if (od.find(0x1016, 1) != nullptr) {
      const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(o.master_heartbeat_timeout).count();
      c.configuration.push_back(
          {0x1016, 1, le((std::uint64_t{o.master_node} << 16) | (static_cast<std::uint64_t>(ms) & 0xFFFF), 4)});
      decisions.push_back(
          fmt::format("the node watches the master's heartbeat (0x1016:1, node {}, {} ms)", o.master_node, ms));
    } else {
      decisions.push_back("no 0x1016:1 heartbeat consumer in the EDS: the node cannot watch the master's heartbeat");
    }
  }
  if (out.layout.write_output_mask) c.configuration.push_back({0x60FE, 2, le(out.layout.digital_output_mask, 4)});
  for (const auto& p : out.layout.rpdos) write_pdo(c.configuration, true, p);
  for (const auto& p : out.layout.tpdos) write_pdo(c.configuration, false, p);
  c.image = od;
  // A fixed or DCF-given mapping is the device's word: its entries are mappable in the image.
  for (const auto* list : {&out.layout.rpdos, &out.layout.tpdos})
    for (const auto& p : *list)
      for (const auto& e : p.mapping)
        if (auto* v = c.image.find(e.index, e.sub)) v->pdo_mappable = true;
  // The master applies received PDOs at once (0xFF) and sends its own on every SYNC (1).
  for (const auto& p : out.layout.tpdos)
    if (p.source != PlannedPdo::Source::disabled && !p.mapping.empty()) c.rx_pdos.push_back(master_pdo(p, 0xFF));
  for (const auto& p : out.layout.rpdos)
    if (p.source != PlannedPdo::Source::disabled && !p.mapping.empty()) c.tx_pdos.push_back(master_pdo(p, 1));
  return out;
}

canopen::NodeConfig make_axis_node_config(const DeviceDescription& eds, const AxisOptions& options) {
  auto c = make_axis_config(eds, options);
  if (!c) throw std::invalid_argument(c.error().describe());
  return std::move(c->node);
}

}  // namespace hil::cia402
