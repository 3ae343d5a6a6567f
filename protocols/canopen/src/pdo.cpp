// SPDX-License-Identifier: MIT
#include "hil/canopen/pdo.hpp"

#include <cstring>

#include "hil/canopen/emcy.hpp"

namespace hil::canopen {
namespace {

constexpr std::uint16_t k_rpdo_comm = 0x1400;
constexpr std::uint16_t k_rpdo_map = 0x1600;
constexpr std::uint16_t k_tpdo_comm = 0x1800;
constexpr std::uint16_t k_tpdo_map = 0x1A00;
constexpr int k_max_pdos = 512;

bool is_dummy(const PdoMappingEntry& e) noexcept {
  return e.index >= 0x0001 && e.index <= 0x0007 && e.sub == 0;
}

/// CiA 301 §7.3.5 restricted COB-IDs: not usable for PDOs.
bool restricted_cob(std::uint32_t id) noexcept {
  return id == 0x000 || (id >= 0x001 && id <= 0x07F) || (id >= 0x101 && id <= 0x180) || (id >= 0x581 && id <= 0x5FF) ||
         (id >= 0x601 && id <= 0x67F) || (id >= 0x6E0 && id <= 0x6FF) || (id >= 0x701 && id <= 0x77F) ||
         (id >= 0x780 && id <= 0x7FF);
}

}  // namespace

PdoEngine::PdoEngine(ObjectDictionary& od, FrameSink sink) : od_(od), sink_(std::move(sink)) {}

SdoAbort PdoEngine::check_mapping(const ObjectDictionary& od, const std::vector<PdoMappingEntry>& m, bool receive,
                                  bool check_access) {
  if (m.size() > 8) return SdoAbort::value_too_high;
  unsigned total = 0;
  for (const auto& e : m) {
    if (e.bits == 0 || e.bits % 8 != 0) return SdoAbort::not_mappable;
    total += e.bits;
    if (is_dummy(e)) {
      const auto t = data_type_from_code(e.index);
      if (!receive || !t || data_type_size(*t) * 8 != e.bits) return SdoAbort::not_mappable;
      continue;
    }
    const auto* v = od.find(e.index, e.sub);
    if (v == nullptr) return od.has_object(e.index) ? SdoAbort::no_sub_index : SdoAbort::no_object;
    if (!v->pdo_mappable) return SdoAbort::not_mappable;
    if (check_access && (receive ? !writable(v->access) : !readable(v->access))) return SdoAbort::not_mappable;
    if (data_type_size(v->type) * 8 != e.bits) return SdoAbort::not_mappable;
  }
  if (total > 64) return SdoAbort::pdo_length;
  return SdoAbort::none;
}

bool PdoEngine::build(Pdo& p, bool receive, bool check_access) {
  p.slots.clear();
  p.length = 0;
  if (check_mapping(od_, p.cfg.mapping, receive, check_access) != SdoAbort::none) {
    p.cfg.cob_id |= pdo_cob_invalid;  // an inconsistent mapping never goes on the bus
    return false;
  }
  for (const auto& e : p.cfg.mapping) {
    Slot s;
    s.bytes = e.bits / 8u;
    if (!is_dummy(e)) s.var = od_.find(e.index, e.sub);
    p.slots.push_back(s);
    p.length += s.bytes;
  }
  return true;
}

std::optional<PdoConfig> PdoEngine::read_config(std::uint16_t comm, std::uint16_t map) const {
  if (!od_.has_object(comm)) return std::nullopt;
  PdoConfig c;
  c.cob_id = static_cast<std::uint32_t>(od_.get_int(comm, 1));
  c.transmission_type = od_.find(comm, 2) ? static_cast<std::uint8_t>(od_.get_int(comm, 2)) : 0xFF;
  c.inhibit = std::chrono::microseconds(100 * od_.get_int(comm, 3));
  c.event_timer = std::chrono::milliseconds(od_.get_int(comm, 5));
  c.sync_start = static_cast<std::uint8_t>(od_.get_int(comm, 6));
  const auto n = od_.get_int(map, 0);
  for (std::int64_t i = 1; i <= n && i <= 8; ++i)
    c.mapping.push_back(
        parse_mapping_entry(static_cast<std::uint32_t>(od_.get_int(map, static_cast<std::uint8_t>(i)))));
  return c;
}

void PdoEngine::load_from_od() {
  clear();
  from_od_ = true;
  in_reload_ = true;
  for (int n = 0; n < k_max_pdos; ++n) {
    if (auto c = read_config(static_cast<std::uint16_t>(k_rpdo_comm + n), static_cast<std::uint16_t>(k_rpdo_map + n))) {
      Pdo p;
      p.cfg = std::move(*c);
      build(p, true);
      rpdos_.push_back(std::move(p));
    }
    if (auto c = read_config(static_cast<std::uint16_t>(k_tpdo_comm + n), static_cast<std::uint16_t>(k_tpdo_map + n))) {
      Pdo p;
      p.cfg = std::move(*c);
      build(p, false);
      tpdos_.push_back(std::move(p));
    }
  }
  in_reload_ = false;
  dirty_ = false;
  if (!validators_installed_) {
    install_validators();
    validators_installed_ = true;
  }
}

void PdoEngine::ensure_loaded() {
  if (from_od_ && dirty_ && !in_reload_) load_from_od();
}

void PdoEngine::install_validators() {
  for (int n = 0; n < k_max_pdos; ++n) {
    for (const bool receive : {true, false}) {
      const auto comm = static_cast<std::uint16_t>((receive ? k_rpdo_comm : k_tpdo_comm) + n);
      const auto map = static_cast<std::uint16_t>((receive ? k_rpdo_map : k_tpdo_map) + n);
      if (od_.has_object(comm)) {
        od_.set_validator(comm, [this, comm, receive](const Variable& v, std::span<const std::uint8_t> b) -> SdoAbort {
          const auto value = static_cast<std::uint32_t>(decode_int(b, false));
          const auto cob = static_cast<std::uint32_t>(od_.get_int(comm, 1));
          const bool is_valid = (cob & pdo_cob_invalid) == 0;
          switch (v.sub) {
            case 1: {
              const bool new_valid = (value & pdo_cob_invalid) == 0;
              if (!new_valid) return SdoAbort::none;
              if (value & pdo_cob_extended) return SdoAbort::invalid_value;  // 29-bit PDOs not supported
              if (restricted_cob(value & 0x7FF)) return SdoAbort::invalid_value;
              if (is_valid && (value & 0x1FFFFFFF) != (cob & 0x1FFFFFFF)) return SdoAbort::invalid_value;
              return SdoAbort::none;
            }
            case 2:
              if (value >= 241 && value <= 251) return SdoAbort::invalid_value;
              if (receive && (value == 0xFC || value == 0xFD)) return SdoAbort::invalid_value;
              return SdoAbort::none;
            case 3:
            case 6:
              return is_valid ? SdoAbort::invalid_value : SdoAbort::none;
            default:
              return SdoAbort::none;
          }
        });
        od_.add_observer(comm, [this](const Variable&) { dirty_ = true; });
      }
      if (od_.has_object(map)) {
        od_.set_validator(
            map, [this, comm, map, receive](const Variable& v, std::span<const std::uint8_t> b) -> SdoAbort {
              const auto value = static_cast<std::uint32_t>(decode_int(b, false));
              const bool is_valid = (static_cast<std::uint32_t>(od_.get_int(comm, 1)) & pdo_cob_invalid) == 0;
              if (is_valid) return SdoAbort::unsupported_access;  // CiA 301 step 1: disable the PDO first
              if (v.sub == 0) {
                if (value > 8) return SdoAbort::value_too_high;
                std::vector<PdoMappingEntry> m;
                for (std::uint32_t i = 1; i <= value; ++i)
                  m.push_back(
                      parse_mapping_entry(static_cast<std::uint32_t>(od_.get_int(map, static_cast<std::uint8_t>(i)))));
                return check_mapping(od_, m, receive);
              }
              if (od_.get_int(map, 0) != 0) return SdoAbort::unsupported_access;  // step 2: sub 0 = 0 first
              if (value == 0) return SdoAbort::none;
              return check_mapping(od_, {parse_mapping_entry(value)}, receive);
            });
        od_.add_observer(map, [this](const Variable&) { dirty_ = true; });
      }
    }
  }
}

SdoAbort PdoEngine::add_rpdo(const PdoConfig& cfg) {
  const auto a = check_mapping(od_, cfg.mapping, true, false);
  if (a != SdoAbort::none) return a;
  Pdo p;
  p.cfg = cfg;
  build(p, true, false);
  rpdos_.push_back(std::move(p));
  return SdoAbort::none;
}

SdoAbort PdoEngine::add_tpdo(const PdoConfig& cfg) {
  const auto a = check_mapping(od_, cfg.mapping, false, false);
  if (a != SdoAbort::none) return a;
  Pdo p;
  p.cfg = cfg;
  build(p, false, false);
  tpdos_.push_back(std::move(p));
  return SdoAbort::none;
}

void PdoEngine::set_active(bool active) noexcept {
  if (active && !active_) {
    for (auto& p : tpdos_) {
      p.has_last = false;
      p.started = false;
      p.sync_count = 0;
      p.last_tx.reset();
    }
  }
  active_ = active;
}

void PdoEngine::clear() {
  rpdos_.clear();
  tpdos_.clear();
}

void PdoEngine::send_tpdo(Pdo& p, TimePoint now) {
  can::Frame f;
  f.id = can_id(p);
  f.extended = (p.cfg.cob_id & pdo_cob_extended) != 0;
  f.dlc = static_cast<std::uint8_t>(p.length);
  std::size_t off = 0;
  for (const auto& s : p.slots) {
    if (s.var != nullptr) std::memcpy(&f.data[off], s.var->value.data(), s.bytes);
    off += s.bytes;
  }
  p.last_payload = f.data;
  p.has_last = true;
  p.last_tx = now;
  p.next_timer = now + p.cfg.event_timer;
  p.event = false;
  sink_(f);
}

void PdoEngine::apply(Pdo& p, std::span<const std::uint8_t> data, TimePoint now) {
  std::size_t off = 0;
  for (const auto& s : p.slots) {
    if (s.var != nullptr) od_.write_mapped(*s.var, data.subspan(off, s.bytes));
    off += s.bytes;
  }
  if (on_rpdo_) on_rpdo_(can_id(p), now);
}

bool PdoEngine::on_frame(const can::Frame& f, TimePoint now) {
  ensure_loaded();
  if (!active_ || f.error) return false;
  if (f.rtr) {
    for (auto& p : tpdos_) {
      if (valid(p) && can_id(p) == f.id && (p.cfg.cob_id & pdo_cob_no_rtr) == 0) {
        send_tpdo(p, now);
        return true;
      }
    }
    return false;
  }
  for (auto& p : rpdos_) {
    if (!valid(p) || can_id(p) != f.id || f.extended != ((p.cfg.cob_id & pdo_cob_extended) != 0)) continue;
    if (f.dlc < p.length) {
      if (on_error_) on_error_(emcy_code::pdo_length, f.id);
      return true;
    }
    if (f.dlc > p.length && on_error_) on_error_(emcy_code::pdo_length_exceeded, f.id);
    p.last_rx = now;
    p.deadline_reported = false;
    if (p.cfg.transmission_type <= 240) {
      p.pending = f.data;
      p.has_pending = true;
    } else {
      apply(p, std::span<const std::uint8_t>(f.data.data(), p.length), now);
    }
    return true;
  }
  return false;
}

void PdoEngine::apply_sync_rpdos(TimePoint now) {
  ensure_loaded();
  if (!active_) return;
  for (auto& p : rpdos_) {
    if (p.has_pending) {
      p.has_pending = false;
      apply(p, std::span<const std::uint8_t>(p.pending.data(), p.length), now);
    }
  }
}

void PdoEngine::send_sync_tpdos(std::optional<std::uint8_t> counter, TimePoint now) {
  ensure_loaded();
  if (!active_) return;
  for (auto& p : tpdos_) {
    if (!valid(p)) continue;
    const auto tt = p.cfg.transmission_type;
    if (tt == 0) {
      if (p.event) send_tpdo(p, now);
    } else if (tt <= 240) {
      if (!p.started) {
        if (p.cfg.sync_start != 0 && counter && *counter != p.cfg.sync_start) continue;
        p.started = true;
        p.sync_count = p.cfg.sync_start != 0 && counter ? static_cast<std::uint8_t>(tt - 1) : 0;
      }
      if (++p.sync_count >= tt) {
        p.sync_count = 0;
        send_tpdo(p, now);
      }
    }
  }
}

void PdoEngine::step(TimePoint now) {
  ensure_loaded();
  if (!active_) return;
  for (auto& p : tpdos_) {
    if (!valid(p) || p.cfg.transmission_type < 0xFE) continue;
    if (p.last_tx && now - *p.last_tx < p.cfg.inhibit) continue;
    bool due = p.event || !p.has_last;
    if (!due && p.cfg.event_timer > Duration::zero() && now >= p.next_timer) due = true;
    if (!due) {
      std::size_t off = 0;
      for (const auto& s : p.slots) {
        if (s.var != nullptr && std::memcmp(&p.last_payload[off], s.var->value.data(), s.bytes) != 0) {
          due = true;
          break;
        }
        off += s.bytes;
      }
    }
    if (due) send_tpdo(p, now);
  }
  for (auto& p : rpdos_) {
    if (!valid(p) || p.cfg.event_timer <= Duration::zero() || !p.last_rx || p.deadline_reported) continue;
    if (now - *p.last_rx > p.cfg.event_timer) {
      p.deadline_reported = true;
      if (on_error_) on_error_(emcy_code::rpdo_timeout, can_id(p));
    }
  }
}

void PdoEngine::trigger(std::size_t n) noexcept {
  if (n < tpdos_.size()) tpdos_[n].event = true;
}

}  // namespace hil::canopen
