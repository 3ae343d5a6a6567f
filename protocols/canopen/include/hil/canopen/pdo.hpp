// SPDX-License-Identifier: MIT
#pragma once
// Process data objects (CiA 301 §7.2.2): communication parameters (0x1400+n RPDO, 0x1800+n
// TPDO: COB-ID, transmission type, inhibit time, event timer, SYNC start value) and mapping
// parameters (0x1600+n / 0x1A00+n: entries index<<16 | sub<<8 | bit length).
//
// PdoEngine runs the PDOs of one node over an ObjectDictionary: TPDOs on SYNC (every n-th,
// acyclic), event-driven with inhibit time and event timer, on RTR; RPDOs written to the OD,
// synchronous ones at the next SYNC. On a slave it is configured from the OD (load_from_od) and
// enforces the CiA 301 dynamic-remapping rules on SDO writes; on a master it is configured
// programmatically against an image of the remote node's OD. Mapping granularity is bytes:
// entries whose bit length is not a multiple of 8 are rejected with 0x06040041.

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "hil/can/frame.hpp"
#include "hil/canopen/cob_id.hpp"
#include "hil/canopen/object_dictionary.hpp"
#include "hil/core/clock.hpp"

namespace hil::canopen {

inline constexpr std::uint32_t pdo_cob_invalid = 0x80000000u;   ///< COB-ID bit 31: PDO does not exist / not valid
inline constexpr std::uint32_t pdo_cob_no_rtr = 0x40000000u;    ///< bit 30: no RTR allowed
inline constexpr std::uint32_t pdo_cob_extended = 0x20000000u;  ///< bit 29: 29-bit identifier

struct PdoMappingEntry {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  std::uint8_t bits = 0;
  friend bool operator==(const PdoMappingEntry&, const PdoMappingEntry&) = default;
};
[[nodiscard]] constexpr std::uint32_t make_mapping_entry(PdoMappingEntry e) noexcept {
  return (std::uint32_t{e.index} << 16) | (std::uint32_t{e.sub} << 8) | e.bits;
}
[[nodiscard]] constexpr PdoMappingEntry parse_mapping_entry(std::uint32_t v) noexcept {
  return {static_cast<std::uint16_t>(v >> 16), static_cast<std::uint8_t>(v >> 8), static_cast<std::uint8_t>(v)};
}

struct PdoConfig {
  std::uint32_t cob_id = pdo_cob_invalid;  ///< with bits 31/30/29 as in 0x1400/0x1800 sub 1
  std::uint8_t transmission_type = 0xFF;   ///< 0 acyclic sync, 1..240 every n-th SYNC, 0xFC/0xFD RTR, 0xFE/0xFF event
  Duration inhibit{};                      ///< TPDO minimum gap (0x1800 sub 3, 100 µs units on the wire)
  Duration event_timer{};                  ///< TPDO: send period for event types; RPDO: deadline monitoring
  std::uint8_t sync_start = 0;             ///< TPDO: SYNC counter value of the first transmission (0 = any)
  std::vector<PdoMappingEntry> mapping;
};

/// Why a PDO was not processed (reported with the EMCY code the node should raise).
using PdoErrorHandler = std::function<void(std::uint16_t emcy_code, std::uint32_t cob_id)>;
/// An RPDO was received and written to the OD (`cob_id` without flag bits).
using RpdoHandler = std::function<void(std::uint32_t cob_id, TimePoint now)>;

class PdoEngine {
 public:
  PdoEngine(ObjectDictionary& od, FrameSink sink);

  /// Slave: build all PDOs from 0x1400..0x15FF / 0x1600.. / 0x1800.. / 0x1A00.. and install the
  /// remap validators; SDO writes to those objects reconfigure the PDOs automatically.
  void load_from_od();
  /// Master: add a PDO against the OD given at construction (an image of the remote node).
  /// Returns the abort code a slave would give for the same mapping.
  SdoAbort add_rpdo(const PdoConfig& cfg);
  SdoAbort add_tpdo(const PdoConfig& cfg);
  void clear();

  /// PDOs are only exchanged in NMT Operational. Entering it again (false -> true) restarts every
  /// TPDO as on the first entry (as CANopenNode does): event-driven TPDOs go out at the next
  /// step() whether or not their data changed, SYNC TPDOs count from the next SYNC again.
  void set_active(bool active) noexcept;
  [[nodiscard]] bool active() const noexcept { return active_; }

  bool on_frame(const can::Frame& f, TimePoint now);
  /// A SYNC was received (slave) or sent (master): synchronous TPDOs go out, synchronous RPDO
  /// data buffered since the previous SYNC is written to the OD.
  void on_sync(std::optional<std::uint8_t> counter, TimePoint now) {
    apply_sync_rpdos(now);
    send_sync_tpdos(counter, now);
  }
  /// The two halves of on_sync(), for a device that runs its application in between
  /// (RPDO set-points in, application step, TPDO actual values out).
  void apply_sync_rpdos(TimePoint now);
  void send_sync_tpdos(std::optional<std::uint8_t> counter, TimePoint now);
  /// Event-driven TPDOs (change of a mapped value, event timer, inhibit) and RPDO deadlines.
  void step(TimePoint now);
  /// Application event for TPDO `n` (0-based): sent at the next step (event types) or next SYNC (type 0).
  void trigger(std::size_t n) noexcept;

  void set_error_handler(PdoErrorHandler h) { on_error_ = std::move(h); }
  void set_rpdo_handler(RpdoHandler h) { on_rpdo_ = std::move(h); }
  [[nodiscard]] std::size_t tpdo_count() const noexcept { return tpdos_.size(); }
  [[nodiscard]] std::size_t rpdo_count() const noexcept { return rpdos_.size(); }

  /// Check a mapping against `od` (CiA 301 rules); `receive` = RPDO (objects must be writable).
  /// `check_access` false: a master's image of a remote node (directions are mirrored there).
  [[nodiscard]] static SdoAbort check_mapping(const ObjectDictionary& od, const std::vector<PdoMappingEntry>& m,
                                              bool receive, bool check_access = true);

 private:
  struct Slot {
    Variable* var = nullptr;  ///< nullptr: dummy entry (skipped bytes)
    std::size_t bytes = 0;
  };
  struct Pdo {
    PdoConfig cfg;
    std::vector<Slot> slots;
    std::size_t length = 0;
    // TPDO state
    std::uint8_t sync_count = 0;
    bool started = false;
    bool event = false;
    std::optional<TimePoint> last_tx;
    TimePoint next_timer{};
    std::array<std::uint8_t, 8> last_payload{};
    bool has_last = false;
    // RPDO state
    std::array<std::uint8_t, 8> pending{};
    bool has_pending = false;
    std::optional<TimePoint> last_rx;
    bool deadline_reported = false;
  };
  [[nodiscard]] bool valid(const Pdo& p) const noexcept { return (p.cfg.cob_id & pdo_cob_invalid) == 0; }
  [[nodiscard]] std::uint32_t can_id(const Pdo& p) const noexcept { return p.cfg.cob_id & 0x1FFFFFFF; }
  bool build(Pdo& p, bool receive, bool check_access = true);
  void send_tpdo(Pdo& p, TimePoint now);
  void apply(Pdo& p, std::span<const std::uint8_t> data, TimePoint now);
  void ensure_loaded();
  void install_validators();
  std::optional<PdoConfig> read_config(std::uint16_t comm, std::uint16_t map) const;

  ObjectDictionary& od_;
  FrameSink sink_;
  std::vector<Pdo> rpdos_;
  std::vector<Pdo> tpdos_;
  PdoErrorHandler on_error_;
  RpdoHandler on_rpdo_;
  bool active_ = true;
  bool from_od_ = false;
  bool dirty_ = false;
  bool in_reload_ = false;
  bool validators_installed_ = false;
};

}  // namespace hil::canopen
