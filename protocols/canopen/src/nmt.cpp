// SPDX-License-Identifier: MIT
#include "hil/canopen/nmt.hpp"

namespace hil::canopen {

std::string_view to_string(NmtCommand c) noexcept {
  switch (c) {
    case NmtCommand::start:
      return "start";
    case NmtCommand::stop:
      return "stop";
    case NmtCommand::enter_preoperational:
      return "enter pre-operational";
    case NmtCommand::reset_node:
      return "reset node";
    case NmtCommand::reset_communication:
      return "reset communication";
  }
  return "unknown";
}

std::string_view to_string(NmtState s) noexcept {
  switch (s) {
    case NmtState::initialising:
      return "initialising";
    case NmtState::stopped:
      return "stopped";
    case NmtState::operational:
      return "operational";
    case NmtState::preoperational:
      return "pre-operational";
  }
  return "unknown";
}

std::optional<NmtState> nmt_state_from_byte(std::uint8_t b) noexcept {
  switch (b) {
    case 0x00:
      return NmtState::initialising;
    case 0x04:
      return NmtState::stopped;
    case 0x05:
      return NmtState::operational;
    case 0x7F:
      return NmtState::preoperational;
    default:
      return std::nullopt;
  }
}

can::Frame make_nmt(NmtCommand cmd, NodeId node) noexcept {
  return frame_of(cob_nmt, {static_cast<std::uint8_t>(cmd), node});
}

std::optional<NmtRequest> parse_nmt(const can::Frame& f) noexcept {
  if (f.id != cob_nmt || f.extended || f.rtr || f.error || f.dlc < 2) return std::nullopt;
  const auto cs = f.data[0];
  if (cs != 0x01 && cs != 0x02 && cs != 0x80 && cs != 0x81 && cs != 0x82) return std::nullopt;
  if (f.data[1] > 127) return std::nullopt;
  return NmtRequest{static_cast<NmtCommand>(cs), f.data[1]};
}

can::Frame make_heartbeat(NodeId node, NmtState state) noexcept {
  return frame_of(cob_heartbeat_base + node, {static_cast<std::uint8_t>(state)});
}

can::Frame make_guard_response(NodeId node, NmtState state, bool toggle) noexcept {
  return frame_of(cob_heartbeat_base + node,
                  {static_cast<std::uint8_t>(static_cast<std::uint8_t>(state) | (toggle ? 0x80 : 0x00))});
}

can::Frame make_guard_request(NodeId node) noexcept {
  can::Frame f;
  f.id = cob_heartbeat_base + node;
  f.rtr = true;
  f.dlc = 1;
  return f;
}

std::optional<ErrorControlMessage> parse_error_control(const can::Frame& f) noexcept {
  if (f.extended || f.rtr || f.error || f.dlc < 1) return std::nullopt;
  if (f.id <= cob_heartbeat_base || f.id > cob_heartbeat_base + 127) return std::nullopt;
  const auto st = nmt_state_from_byte(static_cast<std::uint8_t>(f.data[0] & 0x7F));
  if (!st) return std::nullopt;
  return ErrorControlMessage{static_cast<NodeId>(f.id - cob_heartbeat_base), *st, (f.data[0] & 0x80) != 0};
}

}  // namespace hil::canopen
