// SPDX-License-Identifier: MIT
#pragma once
// The process-data layout hilbridge uses for a CiA 402 axis, and the node configuration the
// master downloads during boot-up to establish it (CiA 301 remapping sequence per PDO):
//   node RPDO1 0x200+id  controlword 0x6040 (16) + modes of operation 0x6060 (8)      SYNC
//   node RPDO2 0x300+id  target position 0x607A (32) + target velocity 0x60FF (32)     SYNC
//   node TPDO1 0x180+id  statusword 0x6041 (16) + modes display 0x6061 (8) + error code 0x603F (16)  SYNC
//   node TPDO2 0x280+id  position actual 0x6064 (32) + velocity actual 0x606C (32)     SYNC
// With `profile_objects` (the pp setup) two more, else PDOs 3 and 4 are disabled:
//   node RPDO3 0x400+id  profile velocity 0x6081 (32) + profile acceleration 0x6083 (32)  SYNC
//   node RPDO4 0x500+id  profile deceleration 0x6084 (32)                                 SYNC
// All synchronous (transmission type 1): set-points written in cycle
// k go out after SYNC k+1 and take effect at SYNC k+2 (CiA 402 CSP/CSV timing).

#include <chrono>

#include "hil/canopen/eds.hpp"
#include "hil/canopen/master.hpp"

namespace hil::cia402 {

struct AxisOptions {
  canopen::NodeId node = 0;
  Duration heartbeat_producer{std::chrono::milliseconds(20)};  ///< written to the node's 0x1017
  Duration heartbeat_consumer{std::chrono::milliseconds(60)};  ///< master-side supervision (0 = off)
  bool check_identity = true;                                  ///< compare 0x1000 / 0x1018:1..3 with the EDS
  canopen::NodeId master_node =
      0;  ///< the master's node-ID when it produces a heartbeat (0 = node does not monitor it)
  Duration master_heartbeat_timeout{std::chrono::milliseconds(100)};  ///< node's consumer time 0x1016:1
  bool profile_objects = false;  ///< map 0x6081/0x6083/0x6084 into RPDO3/4 (profile position / velocity)
};

/// Node configuration for `Master::add_node` from the node's EDS/DCF: identity expectations,
/// DCF ParameterValues, heartbeat, the remap writes for the layout above, the master's image
/// (the EDS's OD) and its PDOs.
[[nodiscard]] canopen::NodeConfig make_axis_node_config(const canopen::DeviceDescription& eds,
                                                        const AxisOptions& options);

}  // namespace hil::cia402
