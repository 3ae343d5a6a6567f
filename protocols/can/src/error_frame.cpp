// SPDX-License-Identifier: MIT
#include "hil/can/error_frame.hpp"

namespace hil::can {

namespace {
constexpr std::uint32_t err_cnt = 0x200;  // CAN_ERR_CNT: data[6..7] hold TX/RX error counters
}

const char* to_string(BusState s) noexcept {
  switch (s) {
    case BusState::error_active:
      return "error-active";
    case BusState::error_warning:
      return "error-warning";
    case BusState::error_passive:
      return "error-passive";
    case BusState::bus_off:
      return "bus-off";
  }
  return "?";
}

ErrorFrameInfo decode_error_frame(const Frame& f) noexcept {
  ErrorFrameInfo info;
  if (!f.error) return info;
  const std::uint32_t cls = f.id;
  info.tx_timeout = (cls & error_class::tx_timeout) != 0;
  info.lost_arbitration = (cls & error_class::lost_arbitration) != 0;
  info.protocol_violation = (cls & error_class::protocol) != 0;
  info.transceiver = (cls & error_class::transceiver) != 0;
  info.no_ack = (cls & error_class::no_ack) != 0;
  info.bus_error = (cls & error_class::bus_error) != 0;
  if (cls & error_class::controller) {
    const std::uint8_t c = f.data[1];
    info.rx_overflow = (c & controller_status::rx_overflow) != 0;
    info.tx_overflow = (c & controller_status::tx_overflow) != 0;
    if (c & (controller_status::rx_passive | controller_status::tx_passive))
      info.state = BusState::error_passive;
    else if (c & (controller_status::rx_warning | controller_status::tx_warning))
      info.state = BusState::error_warning;
    else if (c & controller_status::active)
      info.state = BusState::error_active;
  }
  if (cls & error_class::restarted) info.state = BusState::error_active;
  if (cls & error_class::bus_off) info.state = BusState::bus_off;
  if (cls & err_cnt) {
    info.tx_error_count = f.data[6];
    info.rx_error_count = f.data[7];
  }
  return info;
}

std::string describe_error_frame(const Frame& f) {
  if (!f.error) return "not an error frame";
  const auto info = decode_error_frame(f);
  std::string s;
  auto add = [&s](const char* w) {
    if (!s.empty()) s += ", ";
    s += w;
  };
  if (info.state) add(to_string(*info.state));
  if (info.rx_overflow) add("rx-overflow");
  if (info.tx_overflow) add("tx-overflow");
  if (info.no_ack) add("no-ack");
  if (info.tx_timeout) add("tx-timeout");
  if (info.lost_arbitration) add("lost-arbitration");
  if (info.protocol_violation) add("protocol-violation");
  if (info.bus_error) add("bus-error");
  if (info.transceiver) add("transceiver");
  if (info.tx_error_count)
    s += " (tec " + std::to_string(*info.tx_error_count) + ", rec " + std::to_string(*info.rx_error_count) + ")";
  if (s.empty()) s = "error frame";
  return s;
}

}  // namespace hil::can
