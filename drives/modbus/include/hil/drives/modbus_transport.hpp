// SPDX-License-Identifier: MIT
#pragma once
// The `modbus` transport for `hilbridge run` / `hilbridge test` scenarios. An axis's drive block:
//
//   drive:
//     transport: modbus
//     profile: cia402          # name in profiles/modbus/ or a path (relative to the scenario)
//     host: 192.168.0.20:502   # optional: a real drive; without it an in-process simulated drive
//                              # server is started on an ephemeral 127.0.0.1 port
//     unit: 1                  # optional, default: the profile's unit
//     response_timeout: 0.1    # [s] per request
//     poll_period: 0.001       # [s] free-running exchange period (real-time runs)
//     backoff_min: 0.1         # [s] first reconnect delay; doubles up to backoff_max
//     backoff_max: 5
//     plant: {kv: 50, max_velocity: 5e6, ...}   # in-process server only: the simulated plant
//
// Virtual-time runs exchange in lockstep (one exchange per cycle in begin_cycle, deterministic);
// real-time runs let each drive's worker free-run. In-process servers are stepped in
// begin_cycle on the cycle's time. In-process axes accept injected faults: the plant's
// ("encoder", "not_ready", "following_blowup") and the link's ("server_down" stops/starts the
// server, "slow_response" delays replies past the timeout, "busy" answers exception 06).

#include <memory>
#include <string>

#include "hil/core/transport.hpp"

namespace hil::drives {

/// Where `profile:` names are looked up when they are not a path: hil::find_data_dir("profiles/modbus")
/// (<prefix>/share/hilbridge/profiles/modbus of an installed tree, else the source tree's).
[[nodiscard]] std::string default_modbus_profile_dir();

/// Resolve a profile name or path: as given (relative to `scenario_dir` first), then
/// `<default dir>/<name>.yaml`.
[[nodiscard]] std::string resolve_modbus_profile(const std::string& name_or_path, const std::string& scenario_dir);

[[nodiscard]] std::unique_ptr<TransportFactory> make_modbus_transport();

}  // namespace hil::drives
