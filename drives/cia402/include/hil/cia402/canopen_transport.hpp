// SPDX-License-Identifier: MIT
#pragma once
// The `canopen` transport of `hilbridge run` / `hilbridge test` scenarios: CiA 402 axes behind one
// CANopen master per bus (cia402::Network). An axis's drive block (docs/canopen.md):
//
//   drive:
//     transport: canopen
//     node: 1                  # node-ID 1..127
//     bus: vcan0               # optional: a real bus (vcan0, can0, socketcand://...; real-time runs
//                              # only); without it, or with virtual:NAME, the node is a simulated
//                              # CiA 402 drive (mocks::Cia402Node) on an in-process virtual bus,
//                              # deterministic on the run's clock
//     eds: my_drive.eds        # optional: the node's EDS/DCF (relative to the scenario)
//
// SYNC at the cycle period. In-process axes accept injected faults: the node's and
// `master_heartbeat_loss` (when the master produces a heartbeat).

#include <memory>

#include "hil/core/transport.hpp"

namespace hil::cia402 {

/// A fresh factory for one run: its buses (master, channels, simulated nodes) are shared by the
/// axes it builds.
[[nodiscard]] std::unique_ptr<TransportFactory> make_canopen_transport();

}  // namespace hil::cia402
