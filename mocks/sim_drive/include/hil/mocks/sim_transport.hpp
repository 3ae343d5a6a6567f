// SPDX-License-Identifier: MIT
#pragma once
// The `sim` transport: every axis gets a SimDrive on the plant model, configured from its `drive:`
// block (parse_sim_drive_config). The default for scenarios with no hardware; `hilbridge` registers
// it, and tests use the same factory.

#include <memory>

#include "hil/core/transport.hpp"

namespace hil::mocks {

/// A fresh `sim` TransportFactory (no per-run state: each axis is independent).
[[nodiscard]] std::unique_ptr<TransportFactory> make_sim_transport();

}  // namespace hil::mocks
