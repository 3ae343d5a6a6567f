// SPDX-License-Identifier: MIT
#pragma once
// NMT (CiA 301 §7.2.8): node-control commands on COB-ID 0x000, the NMT states as the heartbeat
// and boot-up protocol carries them (0x700+id, DLC 1), and node guarding's toggle bit.
// Pure codecs: make_* build frames, parse_* read them and reject anything malformed.

#include <cstdint>
#include <optional>
#include <string_view>

#include "hil/can/frame.hpp"
#include "hil/canopen/cob_id.hpp"

namespace hil::canopen {

/// Command specifier of an NMT node-control frame (CiA 301 §7.2.8.3.1).
enum class NmtCommand : std::uint8_t {
  start = 0x01,
  stop = 0x02,
  enter_preoperational = 0x80,
  reset_node = 0x81,
  reset_communication = 0x82,
};

/// NMT state as coded in heartbeat / boot-up / guarding responses (CiA 301 §7.2.8.3.2).
enum class NmtState : std::uint8_t {
  initialising = 0x00,  ///< only ever sent as the boot-up message
  stopped = 0x04,
  operational = 0x05,
  preoperational = 0x7F,
};

[[nodiscard]] std::string_view to_string(NmtCommand c) noexcept;
[[nodiscard]] std::string_view to_string(NmtState s) noexcept;
[[nodiscard]] std::optional<NmtState> nmt_state_from_byte(std::uint8_t b) noexcept;

struct NmtRequest {
  NmtCommand command;
  NodeId node;  ///< 0 = all nodes
};

/// `000#<cs><node>`; node 0 addresses all nodes.
[[nodiscard]] can::Frame make_nmt(NmtCommand cmd, NodeId node) noexcept;
/// Frame on 0x000 with DLC 2 (longer DLCs accepted, extra bytes ignored), known command
/// specifier and node 0..127; nullopt otherwise.
[[nodiscard]] std::optional<NmtRequest> parse_nmt(const can::Frame& f) noexcept;

/// Heartbeat / boot-up: `7xx#<state>`.
[[nodiscard]] can::Frame make_heartbeat(NodeId node, NmtState state) noexcept;
/// Node-guarding response: state with bit 7 = toggle.
[[nodiscard]] can::Frame make_guard_response(NodeId node, NmtState state, bool toggle) noexcept;
/// Node-guarding request: RTR on 0x700+id, DLC 1.
[[nodiscard]] can::Frame make_guard_request(NodeId node) noexcept;

struct ErrorControlMessage {
  NodeId node;
  NmtState state;
  bool toggle;  ///< bit 7 (guarding responses only; false in heartbeats)
};
/// A data frame on 0x701..0x77F with DLC >= 1 and a known state; nullopt otherwise.
[[nodiscard]] std::optional<ErrorControlMessage> parse_error_control(const can::Frame& f) noexcept;

}  // namespace hil::canopen
