// SPDX-License-Identifier: MIT
#pragma once
// CANopen master (CiA 301 NMT master + CiA 302-2 style boot-up): per node an SDO client, the
// boot-up sequence (identity check against the configuration, configuration download, start),
// heartbeat consumer, EMCY consumer, a SYNC producer with counter, and a process image per node
// (an ObjectDictionary image of the remote node) exchanged through PDOs.
// Step function on injected time; frames out through the sink. Thread: one owner; callbacks
// run synchronously inside on_frame()/step() and may call back into the master.
//
// Cycle: step(now) sends SYNC when due, then (same call) the master's synchronous TPDOs
// (set-points written into the images since the previous SYNC); nodes answer with their TPDOs
// (actual values), which on_frame() writes into the images.

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <unordered_map>
#include <vector>

#include "hil/canopen/eds.hpp"
#include "hil/canopen/emcy.hpp"
#include "hil/canopen/heartbeat.hpp"
#include "hil/canopen/nmt.hpp"
#include "hil/canopen/object_dictionary.hpp"
#include "hil/canopen/pdo.hpp"
#include "hil/canopen/sdo_client.hpp"
#include "hil/canopen/sync.hpp"

namespace hil::canopen {

/// CiA 302-2 boot-up error status letters (0x1F82 / NMT boot errors); the enum value is the letter.
enum class BootError : int {
  none = 0,
  no_response = 'B',    ///< no boot-up / no answer to the 0x1000 upload
  device_type = 'C',    ///< 0x1000 differs from the configured device type
  vendor_id = 'D',      ///< 0x1018:1 differs
  heartbeat = 'E',      ///< heartbeat event during boot
  configuration = 'J',  ///< configuration download failed
  product_code = 'M',   ///< 0x1018:2 differs
  revision = 'N',       ///< 0x1018:3 differs
  serial = 'O',         ///< 0x1018:4 differs
};
const std::error_category& boot_category() noexcept;
inline std::error_code make_error_code(BootError e) noexcept {
  return {static_cast<int>(e), boot_category()};
}

struct NodeConfig {
  NodeId id = 0;
  std::optional<std::uint32_t> device_type;   ///< expected 0x1000 (0x1F84)
  std::optional<std::uint32_t> vendor_id;     ///< expected 0x1018:1 (0x1F85)
  std::optional<std::uint32_t> product_code;  ///< 0x1018:2 (0x1F86)
  std::optional<std::uint32_t> revision;      ///< 0x1018:3 (0x1F87)
  std::optional<std::uint32_t> serial;        ///< 0x1018:4 (0x1F88)
  std::vector<ParameterValue> configuration;  ///< SDO downloads in order (DCF ParameterValues, PDO remap)
  Duration heartbeat_consumer{};              ///< monitor the node's heartbeat (0 = off)
  /// Node guarding (legacy nodes without a heartbeat producer): an RTR every guard time once the
  /// node is started; no (or an untoggled) answer for life_time_factor x guard time is reported
  /// like a heartbeat timeout. 0 = off. The node's 0x100C / 0x100D go in `configuration`.
  Duration guard_time{};
  std::uint8_t life_time_factor = 0;
  bool reset_communication = true;  ///< send NMT reset communication and wait for boot-up first
  bool start = true;                ///< NMT start after a successful boot
  /// Image of the node's OD for PDO exchange (usually from its EDS). Empty = no PDOs.
  ObjectDictionary image;
  std::vector<PdoConfig> rx_pdos;  ///< node TPDOs the master receives (mapping into `image`)
  std::vector<PdoConfig> tx_pdos;  ///< node RPDOs the master sends (from `image`)
};

struct MasterOptions {
  NodeId node_id = 0;              ///< the master's own node-ID (0 = none: no heartbeat)
  Duration heartbeat_period{};     ///< master heartbeat (nodes may monitor it)
  Duration sync_period{};          ///< 0 = no SYNC
  std::uint8_t sync_overflow = 0;  ///< 0x1019 of the master
  SdoClientOptions sdo{};
  Duration boot_timeout{std::chrono::seconds(2)};  ///< wait for boot-up after reset communication
  int boot_retries = 2;                            ///< extra reset-communication attempts without boot-up
};

enum class NodeBootState : std::uint8_t { idle, waiting_boot_up, identifying, configuring, started, failed };

struct NodeStatus {
  NodeBootState boot = NodeBootState::idle;
  std::error_code boot_error;  ///< BootError, with the SDO abort in `detail` when one caused it
  std::string detail;
  std::optional<NmtState> nmt;  ///< last state seen in a heartbeat
  bool heartbeat_lost = false;
  std::uint64_t rpdos = 0;  ///< PDOs received from the node
  std::optional<TimePoint> last_rpdo;
};

class Master {
 public:
  Master(FrameSink sink, MasterOptions options = {});
  Master(const Master&) = delete;
  Master& operator=(const Master&) = delete;

  /// Register a node. Its SDO client, image and PDOs exist from now on; boot(node) starts it.
  void add_node(NodeConfig config);
  [[nodiscard]] bool has_node(NodeId id) const noexcept { return nodes_.contains(id); }
  /// Start the master: SYNC and heartbeat production begin at `now`.
  void start(TimePoint now);
  /// Boot one node (or all with 0) through the sequence; progress via on_boot.
  void boot(NodeId id, TimePoint now);

  bool on_frame(const can::Frame& f, TimePoint now);
  void step(TimePoint now);

  void send_nmt(NmtCommand cmd, NodeId node);
  [[nodiscard]] SdoClient& sdo(NodeId id);
  [[nodiscard]] ObjectDictionary& image(NodeId id);
  [[nodiscard]] const NodeStatus& status(NodeId id) const;
  [[nodiscard]] std::vector<NodeId> nodes() const;
  [[nodiscard]] const MasterOptions& options() const noexcept { return options_; }

  /// Boot finished (ec empty) or failed.
  std::function<void(NodeId, std::error_code)> on_boot;
  std::function<void(const EmcyMessage&)> on_emcy;
  std::function<void(NodeId, HeartbeatEvent, NmtState)> on_heartbeat;
  /// A PDO from the node was written into its image.
  std::function<void(NodeId, TimePoint)> on_rpdo;
  /// Right after a SYNC was sent (before the synchronous TPDOs): update set-points here.
  std::function<void(TimePoint)> on_sync;

 private:
  struct Node {
    NodeConfig config;
    NodeStatus status;
    std::unique_ptr<SdoClient> sdo;
    std::unique_ptr<ObjectDictionary> image;
    std::unique_ptr<PdoEngine> pdo;
    TimePoint boot_deadline{};
    int boot_attempts = 0;
    std::size_t config_step = 0;
  };
  Node& node(NodeId id);
  void fail(Node& n, BootError e, std::string detail, TimePoint now);
  void identify(Node& n, TimePoint now);
  void check_identity(Node& n, std::size_t which, TimePoint now);
  void configure(Node& n, TimePoint now);
  void finish_boot(Node& n, TimePoint now);

  FrameSink sink_;
  MasterOptions options_;
  std::map<NodeId, Node> nodes_;
  std::unordered_map<std::uint32_t, NodeId> pdo_owner_;  ///< received PDO COB-ID -> node
  HeartbeatConsumer heartbeat_;
  NodeGuardMaster guard_;
  std::optional<HeartbeatProducer> producer_;
  SyncProducer sync_;
  bool started_ = false;
  TimePoint last_now_{};
};

}  // namespace hil::canopen

template <>
struct std::is_error_code_enum<hil::canopen::BootError> : std::true_type {};
