// SPDX-License-Identifier: MIT
#pragma once
// The process-data layout of a CiA 402 axis, derived from what the node's EDS/DCF offers, and
// the node configuration the master downloads during boot-up to establish it.
//
// plan_axis_layout() decides, object by object, how the master reaches each object the axis uses:
// in a PDO (mapped by hilbridge with the CiA 301 sequence, or read from a fixed / DCF-given
// mapping), by SDO at a lower rate (polled feedback, set-points written when they change), or
// not at all (optional objects the drive lacks). Every decision is one line of text
// (AxisLayout::decisions) for the run log and `--json`. A mandatory object that is missing is a
// configuration error naming the object and the EDS file; so is a setup whose mode 0x6502 says
// the drive does not support.
//
// Wish lists, in priority order (the first ones get the PDO room):
//   node RPDOs (master -> node): controlword 0x6040, modes of operation 0x6060, target position
//     0x607A, target velocity 0x60FF; pp also profile velocity 0x6081, acceleration 0x6083,
//     deceleration 0x6084; last the digital outputs 0x60FE:1.
//   node TPDOs (node -> master): statusword 0x6041, position actual 0x6064, modes display 0x6061,
//     error code 0x603F, velocity actual 0x606C, digital inputs 0x60FD.
//   SDO-polled diagnostics when present: torque actual 0x6077, following error actual 0x60F4.
// Digital I/O that finds no PDO room goes by SDO like any optional object: 0x60FD polled,
// 0x60FE:1 written when it changes (both asynchronous: the cycle never waits). The 0x60FE:2 bit
// mask (AxisOptions::digital_output_mask) is written once in the configuration download.
// PDOs in use are synchronous (transmission type 1): set-points written in cycle k go out after
// SYNC k+1 and take effect at SYNC k+2 (CiA 402 CSP/CSV timing). Unused remappable PDOs are
// disabled (COB-ID bit 31).

#include <chrono>
#include <cstdint>
#include <expected>
#include <optional>
#include <string>
#include <vector>

#include "hil/canopen/eds.hpp"
#include "hil/canopen/master.hpp"
#include "hil/core/config_error.hpp"

namespace hil::cia402 {

/// How the drive is commanded (see cia402_drive.hpp).
enum class OperatingSetup : std::uint8_t { csp, csv, pp };
[[nodiscard]] std::string_view to_string(OperatingSetup s) noexcept;

/// How the master reaches one object of the axis.
enum class ObjectPath : std::uint8_t { pdo, sdo_poll, sdo_write, absent };

/// One object of the node: index and sub-index.
struct ObjectKey {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  friend bool operator==(const ObjectKey&, const ObjectKey&) = default;
};

struct ObjectRoute {
  std::uint16_t index = 0;
  std::uint8_t sub = 0;
  std::uint8_t bits = 0;
  bool to_node = false;  ///< a set-point (RPDO / SDO write) rather than feedback
  ObjectPath path = ObjectPath::absent;
};

/// One PDO of the node as the axis uses it. `number` is 0-based (PDO 1 = 0).
struct PlannedPdo {
  enum class Source : std::uint8_t { remapped, fixed, dcf, disabled };
  unsigned number = 0;
  Source source = Source::remapped;
  std::uint32_t cob_id = 0;            ///< without bit 31 for PDOs in use
  std::uint8_t transmission_type = 1;  ///< written for remapped / fixed PDOs when writable
  std::vector<canopen::PdoMappingEntry> mapping;
  std::vector<canopen::ParameterValue> dcf;  ///< Source::dcf: the DCF's own values for this PDO
  bool write_transmission_type = true;       ///< false: 0x1400/0x1800+n sub 2 is read-only
};

struct AxisLayout {
  std::vector<PlannedPdo> rpdos;  ///< node RPDOs (the master sends them)
  std::vector<PlannedPdo> tpdos;  ///< node TPDOs (the master receives them)
  std::vector<ObjectRoute> routes;
  std::vector<std::string> decisions;            ///< one line per decision
  std::optional<std::uint32_t> supported_modes;  ///< 0x6502 as the EDS declares it
  bool homing = true;                            ///< HM supported (0x6502 bit 5, or no 0x6502)
  /// The 0x60FE:1 bits the master drives (0 when the node has no 0x60FE:1): the options' mask,
  /// limited by a read-only 0x60FE:2.
  std::uint32_t digital_output_mask = 0;
  bool write_output_mask = false;  ///< 0x60FE:2 = digital_output_mask in the configuration download

  [[nodiscard]] ObjectPath path(std::uint16_t index, std::uint8_t sub = 0) const noexcept;
  [[nodiscard]] bool has(std::uint16_t index, std::uint8_t sub = 0) const noexcept {
    return path(index, sub) != ObjectPath::absent;
  }
  [[nodiscard]] std::vector<ObjectKey> polled() const;   ///< read by SDO at a lower rate
  [[nodiscard]] std::vector<ObjectKey> written() const;  ///< written by SDO when they change
};

/// An explicit mapping from the scenario: PDO 1, 2, ... of each direction in order. An empty
/// optional leaves that direction to the planner.
struct LayoutOverride {
  std::optional<std::vector<std::vector<canopen::PdoMappingEntry>>> rpdo;
  std::optional<std::vector<std::vector<canopen::PdoMappingEntry>>> tpdo;
};

struct AxisOptions {
  canopen::NodeId node = 0;
  Duration heartbeat_producer{std::chrono::milliseconds(20)};  ///< written to the node's 0x1017
  Duration heartbeat_consumer{std::chrono::milliseconds(60)};  ///< master-side supervision (0 = off)
  bool check_identity = true;                                  ///< compare 0x1000 / 0x1018:1..3 with the EDS
  canopen::NodeId master_node =
      0;  ///< the master's node-ID when it produces a heartbeat (0 = node does not monitor it)
  Duration master_heartbeat_timeout{std::chrono::milliseconds(100)};  ///< node's consumer time 0x1016:1
  OperatingSetup setup = OperatingSetup::csp;
  LayoutOverride mapping;  ///< explicit RPDO/TPDO mapping (scenario `rpdo:` / `tpdo:`)
  /// 0x60FE:1 bits the master drives (0x60FE:2 bit mask). By default the manufacturer-specific
  /// outputs 16..31 only: bit 0 "set brake" is the drive's own unless the scenario asks for it,
  /// since a master whose outputs start at 0 would otherwise release a holding brake.
  std::uint32_t digital_output_mask = 0xFFFF0000u;
};

/// Decide the layout for `eds` (see the file comment). Errors: a mandatory object missing or
/// not mappable, an unsupported mode, an override that names a missing / unmappable object or
/// a fixed PDO, or more PDOs than the node has. ConfigError::file is the EDS file.
[[nodiscard]] std::expected<AxisLayout, ConfigError> plan_axis_layout(const canopen::DeviceDescription& eds,
                                                                      const AxisOptions& options);

struct AxisConfig {
  canopen::NodeConfig node;  ///< for Master::add_node
  AxisLayout layout;         ///< for the drive (DriveOptions::layout) and the run log
};

/// Node configuration for `Master::add_node`: identity expectations, the DCF's other
/// ParameterValues in object order, heartbeat producer / consumer where the EDS has the objects,
/// every PDO with the CiA 301 sequence (COB-ID bit 31 set, sub 0 = 0, entries, sub 0 = n,
/// COB-ID enabled), the master's image (the EDS's OD) and its PDOs.
[[nodiscard]] std::expected<AxisConfig, ConfigError> make_axis_config(const canopen::DeviceDescription& eds,
                                                                      const AxisOptions& options);

/// make_axis_config(...).node for an EDS known to fit (the simulated drive's); throws
/// std::invalid_argument with the error text otherwise.
[[nodiscard]] canopen::NodeConfig make_axis_node_config(const canopen::DeviceDescription& eds,
                                                        const AxisOptions& options);

}  // namespace hil::cia402
