// SPDX-License-Identifier: MIT
#pragma once
// hil::Drive over Modbus/TCP (libmodbus client), laid out by a register profile.
//
// Threads:
//  - the motion thread calls read(), write(), request(), feedback(): they never block on I/O,
//    never throw and never allocate; they exchange small fixed-size images with the worker under
//    a mutex held for a copy of a few dozen registers.
//  - one worker thread per drive owns the libmodbus context (libmodbus contexts are not thread
//    safe, upstream issue #246) and runs the exchange: write the command block(s) (FC 6/16),
//    read the feedback block(s) (FC 3/4), or one FC 23. It connects, and reconnects after a
//    link error with exponential back-off.
// Modes:
//  - free-running (real-time runs): the worker exchanges every `poll_period`, stamping images
//    with clock.now() (the clock must then be thread-safe: SteadyClock);
//  - lockstep (virtual-time runs and tests): the worker exchanges only when exchange_sync()
//    asks, stamping the image with the time it was given. Deterministic per cycle.
// Faults: exception responses (01..0B) and link errors (timeout, connection lost, connect
// failed, invalid response) latch a fault with category "modbus"; the drive's own fault shows as
// category "modbus-drive" with the fault-code register's value. fault_reset clears a link
// fault once the link delivers fresh data again, and sends the profile's fault-reset edge.
// Homing (profiles with `modes.homing`, CiA 402): request(home) writes the homing mode, raises
// control word bit 4 after two exchanges, and ends on status bits 12 + 10 (referenced) or 13 /
// `homing_timeout` (not referenced; the axis then reports that homing failed).

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "hil/core/clock.hpp"
#include "hil/core/drive.hpp"
#include "hil/modbus/drive_words.hpp"
#include "hil/modbus/error.hpp"
#include "hil/modbus/exchange_plan.hpp"
#include "hil/modbus/profile.hpp"

namespace hil::drives {

struct ModbusDriveConfig {
  std::string name = "modbus";  ///< axis name, for logs
  std::string host = "127.0.0.1";
  std::uint16_t port = 502;
  int unit_id = -1;  ///< -1: the profile's unit
  modbus::Profile profile;
  Duration response_timeout{std::chrono::milliseconds(100)};  ///< per request (libmodbus response + byte timeout)
  Duration poll_period{std::chrono::milliseconds(1)};         ///< free-running: time between exchange starts
  Duration backoff_min{std::chrono::milliseconds(100)};       ///< first reconnect delay after a link error
  Duration backoff_max{std::chrono::seconds(5)};              ///< back-off doubles up to this
  bool lockstep = false;
  Duration homing_timeout{std::chrono::seconds(30)};  ///< request(home) -> attained, else not referenced
};

struct ModbusLinkStats {
  std::uint64_t exchanges = 0;  ///< completed exchanges
  std::uint64_t errors = 0;     ///< failed exchanges / connects
  std::uint64_t connects = 0;   ///< successful connects
  bool connected = false;
  modbus::ModbusError last_error = modbus::ModbusError::none;
};

class ModbusDrive final : public Drive {
 public:
  /// Starts the worker thread. `clock` must outlive the drive. The profile must be valid
  /// (make_exchange_plan succeeds); load it with modbus::load_profile.
  ModbusDrive(ModbusDriveConfig config, const Clock& clock);
  ~ModbusDrive() override;
  ModbusDrive(const ModbusDrive&) = delete;
  ModbusDrive& operator=(const ModbusDrive&) = delete;

  [[nodiscard]] std::string_view name() const noexcept override { return name_; }
  [[nodiscard]] DriveCapabilities capabilities() const noexcept override;
  void read(const CycleTime& cycle) override;
  void write(const CycleTime& cycle, const DriveCommand& command) override;
  [[nodiscard]] const DriveFeedback& feedback() const noexcept override { return feedback_; }
  bool request(DriveRequest r) override;

  /// Lockstep only: run one exchange (or connect attempt) stamped `now` and wait for it, at
  /// most `wait` of real time. Blocks the caller; returns false on timeout or when not lockstep.
  /// Thread: the thread that drives the cycle (e.g. TransportFactory::begin_cycle).
  bool exchange_sync(TimePoint now, std::chrono::milliseconds wait = std::chrono::milliseconds(2000));
  /// The two halves of exchange_sync(), so a transport can start the exchanges of all its
  /// drives before waiting for any (they run in parallel on their workers). Lockstep only.
  void exchange_start(TimePoint now);
  bool exchange_wait(std::chrono::milliseconds wait = std::chrono::milliseconds(2000));

  [[nodiscard]] ModbusLinkStats link_stats() const;
  [[nodiscard]] const modbus::Profile& profile() const noexcept { return config_.profile; }

 private:
  struct FieldSlot {
    bool present = false;
    std::size_t block = 0;
    std::size_t offset = 0;
  };
  struct Image {
    std::vector<std::vector<std::uint16_t>> blocks;  ///< one per plan read block
    TimePoint stamp{};
    std::uint64_t seq = 0;  ///< completed exchanges
  };
  struct LinkState {
    std::uint64_t error_seq = 0;
    modbus::ModbusError error = modbus::ModbusError::none;
    std::uint64_t error_at_image_seq = 0;
    bool connected = false;
  };

  void worker();
  bool exchange_once(void* ctx, const std::vector<std::vector<std::uint16_t>>& command,
                     std::vector<std::vector<std::uint16_t>>& image) noexcept;
  void clear_link_fault_if_reset() noexcept;
  /// Homing progress from a fresh status word (see the file comment).
  void track_homing(std::uint16_t status_word, TimePoint now) noexcept;
  [[nodiscard]] std::int64_t field_value(modbus::FieldRole role) const noexcept;
  void put_field(modbus::FieldRole role, std::int64_t raw) noexcept;

  ModbusDriveConfig config_;
  const Clock& clock_;
  std::string name_;
  modbus::ExchangePlan plan_;
  std::array<FieldSlot, modbus::kFieldRoleCount> slots_{};

  // Motion thread state.
  DriveFeedback feedback_;
  Image local_image_;                                ///< latest copy of the worker's image
  std::vector<std::vector<std::uint16_t>> command_;  ///< packed command blocks
  LinkState local_link_;
  std::uint64_t seen_error_seq_ = 0;
  modbus::ModbusError link_fault_ = modbus::ModbusError::none;  ///< latched
  bool link_reset_armed_ = false;  ///< fault_reset given while connected; clears at the next fresh image
  modbus::PowerTarget target_ = modbus::PowerTarget::disabled;
  bool reset_pending_ = false;
  bool drive_fault_latched_ = false;  ///< the drive reported a fault: switched off and reported until fault_reset
  std::uint64_t reset_start_seq_ = 0;
  DriveState drive_state_ = DriveState::not_ready;  ///< from the status word (without link fault)
  enum class Homing : std::uint8_t { idle, selecting, started };
  Homing homing_ = Homing::idle;
  std::uint64_t homing_seq_ = 0;  ///< image seq when the mode was selected / bit 4 raised
  std::optional<TimePoint> homing_deadline_;
  bool unreferenced_ = false;  ///< homing was asked for and has not succeeded
  TimePoint created_{};
  bool have_created_ = false;

  // Shared with the worker (mutex_).
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::vector<std::vector<std::uint16_t>> shared_command_;
  Image shared_image_;
  LinkState shared_link_;
  bool stop_ = false;
  std::uint64_t trigger_seq_ = 0;
  std::uint64_t done_seq_ = 0;
  TimePoint trigger_now_{};

  std::atomic<std::uint64_t> exchanges_{0}, errors_{0}, connects_{0};
  std::thread thread_;
};

}  // namespace hil::drives
