// SPDX-License-Identifier: MIT
#include "hil/cia402/network.hpp"

#include "hil/cia402/cia402_drive.hpp"

namespace hil::cia402 {

Network::Network(can::Channel& channel, canopen::MasterOptions options)
    : channel_(channel),
      master_(
          [this](const can::Frame& f) {
            if (auto ec = channel_.send(f)) {
              ++stats_.tx_errors;
              stats_.last_tx_error = ec;
            }
          },
          options) {
  channel_.set_receive_handler([this](const can::Frame& f, TimePoint t) { master_.on_frame(f, t); });
  master_.on_boot = [this](canopen::NodeId id, std::error_code ec) {
    if (auto it = drives_.find(id); it != drives_.end()) it->second->on_boot(ec);
  };
  master_.on_emcy = [this](const canopen::EmcyMessage& m) {
    if (auto it = drives_.find(m.node); it != drives_.end()) it->second->on_emcy(m.code, m.error_register);
  };
  master_.on_heartbeat = [this](canopen::NodeId id, canopen::HeartbeatEvent e, canopen::NmtState) {
    auto it = drives_.find(id);
    if (it == drives_.end()) return;
    if (e == canopen::HeartbeatEvent::timeout) it->second->on_heartbeat_lost(Duration{});
    if (e == canopen::HeartbeatEvent::resumed) it->second->on_heartbeat_resumed();
  };
}

Network::~Network() {
  channel_.set_receive_handler({});
}

void Network::start(TimePoint now) {
  master_.start(now);
  master_.boot(0, now);
}

}  // namespace hil::cia402
