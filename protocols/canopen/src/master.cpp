// SPDX-License-Identifier: MIT
#include "hil/canopen/master.hpp"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

namespace hil::canopen {
namespace {

class BootCategory final : public std::error_category {
 public:
  const char* name() const noexcept override { return "canopen.boot"; }
  std::string message(int v) const override {
    switch (static_cast<BootError>(v)) {
      case BootError::none:
        return "no error";
      case BootError::no_response:
        return "B: no boot-up message or no response to the 0x1000 upload";
      case BootError::device_type:
        return "C: device type (0x1000) differs from the configuration";
      case BootError::vendor_id:
        return "D: vendor-ID (0x1018:1) differs from the configuration";
      case BootError::heartbeat:
        return "E: heartbeat event during boot-up";
      case BootError::configuration:
        return "J: configuration download failed";
      case BootError::product_code:
        return "M: product code (0x1018:2) differs from the configuration";
      case BootError::revision:
        return "N: revision number (0x1018:3) differs from the configuration";
      case BootError::serial:
        return "O: serial number (0x1018:4) differs from the configuration";
    }
    return fmt::format("boot error {}", v);
  }
};

std::uint32_t as_u32(const std::vector<std::uint8_t>& d) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < d.size() && i < 4; ++i) v |= std::uint32_t{d[i]} << (8 * i);
  return v;
}

}  // namespace

const std::error_category& boot_category() noexcept {
  static const BootCategory c;
  return c;
}

Master::Master(FrameSink sink, MasterOptions options)
    : sink_(std::move(sink)),
      options_(options),
      heartbeat_([this](NodeId id, HeartbeatEvent e, NmtState s) {
        auto it = nodes_.find(id);
        if (it == nodes_.end()) return;
        auto& st = it->second.status;
        if (e != HeartbeatEvent::timeout) st.nmt = s;
        if (e == HeartbeatEvent::timeout) st.heartbeat_lost = true;
        if (e == HeartbeatEvent::resumed) st.heartbeat_lost = false;
        if (on_heartbeat) on_heartbeat(id, e, s);
      }),
      guard_(sink_,
             [this](NodeId id, NodeGuardMaster::Event e, NmtState s) {
               auto it = nodes_.find(id);
               if (it == nodes_.end()) return;
               auto& st = it->second.status;
               st.nmt = s;
               HeartbeatEvent he = HeartbeatEvent::state_changed;
               if (e == NodeGuardMaster::Event::lost || e == NodeGuardMaster::Event::toggle_error) {
                 if (st.heartbeat_lost) return;
                 st.heartbeat_lost = true;
                 he = HeartbeatEvent::timeout;
               } else if (e == NodeGuardMaster::Event::resumed) {
                 st.heartbeat_lost = false;
                 he = HeartbeatEvent::resumed;
               }
               if (on_heartbeat) on_heartbeat(id, he, s);
             }),
      sync_(sink_) {}

void Master::add_node(NodeConfig config) {
  if (!is_valid_node_id(config.id)) throw std::invalid_argument(fmt::format("node-ID {} is not 1..127", config.id));
  const NodeId id = config.id;
  Node n;
  n.sdo = std::make_unique<SdoClient>(id, sink_, options_.sdo);
  n.image = std::make_unique<ObjectDictionary>(std::move(config.image));
  n.pdo = std::make_unique<PdoEngine>(*n.image, sink_);
  for (const auto& p : config.rx_pdos) {
    n.pdo->add_rpdo(p);
    pdo_owner_[p.cob_id & 0x1FFFFFFF] = id;
  }
  for (const auto& p : config.tx_pdos) n.pdo->add_tpdo(p);
  n.pdo->set_rpdo_handler([this, id](std::uint32_t, TimePoint now) {
    auto& st = nodes_.at(id).status;
    ++st.rpdos;
    st.last_rpdo = now;
    if (on_rpdo) on_rpdo(id, now);
  });
  n.pdo->set_active(false);
  n.config = std::move(config);
  heartbeat_.set_consumer(id, n.config.heartbeat_consumer);
  nodes_.insert_or_assign(id, std::move(n));
}

Master::Node& Master::node(NodeId id) {
  auto it = nodes_.find(id);
  if (it == nodes_.end()) throw std::out_of_range(fmt::format("node {} is not configured on this master", id));
  return it->second;
}

SdoClient& Master::sdo(NodeId id) {
  return *node(id).sdo;
}
ObjectDictionary& Master::image(NodeId id) {
  return *node(id).image;
}
const NodeStatus& Master::status(NodeId id) const {
  return nodes_.at(id).status;
}

std::vector<NodeId> Master::nodes() const {
  std::vector<NodeId> out;
  for (const auto& [id, n] : nodes_) out.push_back(id);
  return out;
}

void Master::send_nmt(NmtCommand cmd, NodeId id) {
  sink_(make_nmt(cmd, id));
  for (auto& [nid, n] : nodes_) {
    if (id != 0 && nid != id) continue;
    n.pdo->set_active(cmd == NmtCommand::start);
    if (cmd == NmtCommand::reset_node || cmd == NmtCommand::reset_communication) heartbeat_.rearm(nid);
  }
}

void Master::start(TimePoint now) {
  started_ = true;
  if (options_.sync_period > Duration::zero()) sync_.configure(options_.sync_period, options_.sync_overflow, now);
  if (options_.node_id != 0 && options_.heartbeat_period > Duration::zero()) {
    producer_.emplace(options_.node_id, sink_);
    producer_->set_period(options_.heartbeat_period, now);
  }
}

void Master::boot(NodeId id, TimePoint now) {
  if (id == 0) {
    for (auto& [nid, n] : nodes_) boot(nid, now);
    return;
  }
  auto& n = node(id);
  n.status = NodeStatus{};
  n.boot_attempts = 0;
  n.config_step = 0;
  n.pdo->set_active(false);
  guard_.guard(id, Duration::zero(), 0, now);  // guarding starts again after this boot
  if (n.config.reset_communication) {
    n.status.boot = NodeBootState::waiting_boot_up;
    n.boot_deadline = now + options_.boot_timeout;
    heartbeat_.rearm(id);
    sink_(make_nmt(NmtCommand::reset_communication, id));
    return;
  }
  identify(n, now);
}

void Master::fail(Node& n, BootError e, std::string detail, TimePoint now) {
  n.status.boot = NodeBootState::failed;
  n.status.boot_error = make_error_code(e);
  n.status.detail = std::move(detail);
  (void)now;
  if (on_boot) on_boot(n.config.id, n.status.boot_error);
}

void Master::identify(Node& n, TimePoint now) {
  n.status.boot = NodeBootState::identifying;
  check_identity(n, 0, now);
}

void Master::check_identity(Node& n, std::size_t which, TimePoint now) {
  const NodeId id = n.config.id;
  const std::optional<std::uint32_t>* expected[] = {&n.config.device_type, &n.config.vendor_id, &n.config.product_code,
                                                    &n.config.revision, &n.config.serial};
  constexpr BootError errors[] = {BootError::device_type, BootError::vendor_id, BootError::product_code,
                                  BootError::revision, BootError::serial};
  while (which < 5 && which != 0 && !expected[which]->has_value()) ++which;
  if (which >= 5) return configure(n, now);
  const std::uint16_t index = which == 0 ? 0x1000 : 0x1018;
  const auto sub = static_cast<std::uint8_t>(which == 0 ? 0 : which);
  n.sdo->async_upload(
      index, sub, now, [this, id, which, index, sub, errors](std::error_code ec, std::vector<std::uint8_t> d) {
        auto& nn = nodes_.at(id);
        if (nn.status.boot != NodeBootState::identifying) return;
        const TimePoint t = nn.boot_deadline;  // completion time is not needed beyond ordering
        if (ec) {
          return fail(nn, which == 0 ? BootError::no_response : errors[which],
                      fmt::format("upload of 0x{:04X}:{} failed: {}", index, sub, ec.message()), t);
        }
        const std::optional<std::uint32_t>* exp[] = {&nn.config.device_type, &nn.config.vendor_id,
                                                     &nn.config.product_code, &nn.config.revision, &nn.config.serial};
        const auto value = as_u32(d);
        if (exp[which]->has_value() && **exp[which] != value) {
          return fail(
              nn, errors[which],
              fmt::format("0x{:04X}:{} is 0x{:08X}, configuration expects 0x{:08X}", index, sub, value, **exp[which]),
              t);
        }
        check_identity(nn, which + 1, last_now_);
      });
}

void Master::configure(Node& n, TimePoint now) {
  n.status.boot = NodeBootState::configuring;
  const NodeId id = n.config.id;
  if (n.config_step >= n.config.configuration.size()) return finish_boot(n, now);
  const auto& pv = n.config.configuration[n.config_step];
  n.sdo->async_download(pv.index, pv.sub, pv.bytes, now, [this, id](std::error_code ec, std::vector<std::uint8_t>) {
    auto& nn = nodes_.at(id);
    if (nn.status.boot != NodeBootState::configuring) return;
    if (ec) {
      const auto& p = nn.config.configuration[nn.config_step];
      std::string value;
      if (p.bytes.size() <= 8) {
        std::uint64_t v = 0;
        for (std::size_t i = 0; i < p.bytes.size(); ++i) v |= std::uint64_t{p.bytes[i]} << (8 * i);
        value = fmt::format("0x{:0{}X}", v, std::max<std::size_t>(2, 2 * p.bytes.size()));
      } else {
        value = fmt::format("{} bytes", p.bytes.size());
      }
      return fail(nn, BootError::configuration,
                  fmt::format("write of 0x{:04X}:{} = {} (step {} of {}) failed: SDO abort {}", p.index, p.sub, value,
                              nn.config_step + 1, nn.config.configuration.size(), ec.message()),
                  last_now_);
    }
    ++nn.config_step;
    configure(nn, last_now_);
  });
}

void Master::finish_boot(Node& n, TimePoint now) {
  if (n.config.start) {
    sink_(make_nmt(NmtCommand::start, n.config.id));
    n.pdo->set_active(true);
  }
  guard_.guard(n.config.id, n.config.guard_time, n.config.life_time_factor, now);
  n.status.boot = NodeBootState::started;
  if (on_boot) on_boot(n.config.id, {});
}

bool Master::on_frame(const can::Frame& f, TimePoint now) {
  last_now_ = now;
  if (f.error || f.extended) return false;
  const std::uint32_t id = f.id;
  if (id > cob_heartbeat_base && id <= cob_heartbeat_base + 127 && !f.rtr) {
    const auto nid = static_cast<NodeId>(id - cob_heartbeat_base);
    auto it = nodes_.find(nid);
    if (it == nodes_.end()) return false;
    heartbeat_.on_frame(f, now);
    auto& n = it->second;
    if (f.dlc >= 1 && f.data[0] == 0x00 && n.status.boot == NodeBootState::waiting_boot_up) identify(n, now);
    (void)guard_.on_frame(f, now);
    return true;
  }
  if (id > cob_sdo_tx_base && id <= cob_sdo_tx_base + 127) {
    auto it = nodes_.find(static_cast<NodeId>(id - cob_sdo_tx_base));
    return it != nodes_.end() && it->second.sdo->on_frame(f, now);
  }
  if (id > cob_emcy_base && id <= cob_emcy_base + 127) {
    if (auto m = parse_emcy(f)) {
      if (on_emcy) on_emcy(*m);
      return true;
    }
    return false;
  }
  if (auto it = pdo_owner_.find(id); it != pdo_owner_.end()) {
    auto n = nodes_.find(it->second);
    return n != nodes_.end() && n->second.pdo->on_frame(f, now);
  }
  return false;
}

void Master::step(TimePoint now) {
  last_now_ = now;
  if (!started_) return;
  if (producer_) producer_->step(now, NmtState::operational);
  for (auto& [id, n] : nodes_) {
    n.sdo->step(now);
    if (n.status.boot == NodeBootState::waiting_boot_up && now >= n.boot_deadline) {
      if (n.boot_attempts < options_.boot_retries) {
        ++n.boot_attempts;
        n.boot_deadline = now + options_.boot_timeout;
        sink_(make_nmt(NmtCommand::reset_communication, id));
      } else {
        fail(n, BootError::no_response,
             fmt::format("no boot-up message within {} ms after {} reset-communication attempt(s)",
                         std::chrono::duration_cast<std::chrono::milliseconds>(options_.boot_timeout).count(),
                         n.boot_attempts + 1),
             now);
      }
    }
  }
  heartbeat_.step(now);
  guard_.step(now);
  if (sync_.step(now)) {
    const auto counter = options_.sync_overflow >= 2 ? std::optional<std::uint8_t>(sync_.last_counter()) : std::nullopt;
    if (on_sync) on_sync(now);
    for (auto& [id, n] : nodes_) n.pdo->on_sync(counter, now);
  }
  for (auto& [id, n] : nodes_) n.pdo->step(now);
}

}  // namespace hil::canopen
