// SPDX-License-Identifier: MIT
#pragma once
// SDO client (CiA 301 §7.2.4): queued uploads and downloads to one server, expedited, segmented
// or block transfer with CRC-16, configurable timeout and retries. Pure state machine on
// injected time: async_* queue a transfer, on_frame()/step() progress it; the completion
// handler runs synchronously inside those calls and may queue further transfers.
//
// Timeout/retry policy: when the server does not answer within `timeout`, the client sends
// abort 0x05040000 (so a server stuck mid-transfer is released) and, if retries remain,
// restarts the whole transfer from its initiate request; otherwise it completes with
// SdoAbort::timeout.

#include <cstdint>
#include <deque>
#include <functional>
#include <system_error>
#include <vector>

#include "hil/can/frame.hpp"
#include "hil/canopen/cob_id.hpp"
#include "hil/canopen/sdo_abort.hpp"
#include "hil/core/clock.hpp"

namespace hil::canopen {

struct SdoClientOptions {
  Duration timeout{std::chrono::milliseconds(500)};  ///< per answer
  int retries = 0;                                   ///< extra attempts after a timeout
  bool block = false;                                ///< use block transfer for large values
  std::size_t block_threshold = 28;                  ///< values above this many bytes go by block when `block`
  std::uint8_t block_size = 127;                     ///< segments per block asked for in block uploads
};

/// `data` is the uploaded value (empty for downloads); `ec` is an SdoAbort from the server or
/// from this client (timeout, toggle, CRC, protocol).
using SdoCompletion = std::function<void(std::error_code ec, std::vector<std::uint8_t> data)>;
/// Progress of the active transfer: bytes done, total (0 when the size is unknown).
using SdoProgress = std::function<void(std::size_t done, std::size_t total)>;

class SdoClient {
 public:
  SdoClient(NodeId server, FrameSink sink, SdoClientOptions options = {});

  void async_upload(std::uint16_t index, std::uint8_t sub, TimePoint now, SdoCompletion done);
  void async_download(std::uint16_t index, std::uint8_t sub, std::vector<std::uint8_t> data, TimePoint now,
                      SdoCompletion done);
  /// Feed a frame; true when it was this server's response COB-ID (0x580+node).
  bool on_frame(const can::Frame& f, TimePoint now);
  /// Timeouts and retries.
  void step(TimePoint now);
  /// Fail every queued and active transfer with `reason` (sends an abort for the active one).
  void cancel_all(SdoAbort reason, TimePoint now);

  [[nodiscard]] bool busy() const noexcept { return active_; }
  [[nodiscard]] std::size_t queued() const noexcept { return queue_.size(); }
  void set_options(const SdoClientOptions& o) noexcept { options_ = o; }
  [[nodiscard]] const SdoClientOptions& options() const noexcept { return options_; }
  void set_progress(SdoProgress p) { progress_ = std::move(p); }
  [[nodiscard]] NodeId server() const noexcept { return node_; }

 private:
  enum class Phase : std::uint8_t {
    upload_initiate,
    upload_segment,
    download_initiate,
    download_segment,
    block_download_initiate,
    block_download_ack,
    block_download_end,
    block_upload_initiate,
    block_upload_data,
    block_upload_end,
  };
  struct Request {
    bool upload;
    std::uint16_t index;
    std::uint8_t sub;
    std::vector<std::uint8_t> data;
    SdoCompletion done;
  };
  void start(TimePoint now);
  void restart_current(TimePoint now);
  void send(std::initializer_list<std::uint8_t> bytes, TimePoint now);
  void send_abort(SdoAbort code);
  void fail(std::error_code ec, bool send_abort_frame, SdoAbort code, TimePoint now);
  void complete(std::error_code ec, TimePoint now);
  void send_download_segment(TimePoint now);
  void send_download_block(TimePoint now);
  void on_upload(const can::Frame& f, TimePoint now);
  void on_download(const can::Frame& f, TimePoint now);
  void on_block_download(const can::Frame& f, TimePoint now);
  void on_block_upload(const can::Frame& f, TimePoint now);
  void report_progress();

  NodeId node_;
  FrameSink sink_;
  SdoClientOptions options_;
  std::uint32_t tx_cob_;
  std::uint32_t rx_cob_;
  std::deque<Request> queue_;
  Request current_{};
  bool active_ = false;
  Phase phase_ = Phase::upload_initiate;
  TimePoint deadline_{};
  int attempts_left_ = 0;
  bool toggle_ = false;
  std::size_t offset_ = 0;
  std::size_t size_ = 0;
  bool size_known_ = false;
  std::vector<std::uint8_t> rx_;
  // block transfer
  std::uint8_t blksize_ = 0;
  std::uint8_t expected_seq_ = 1;
  std::uint8_t sent_in_block_ = 0;
  bool server_crc_ = false;
  bool last_segment_ = false;
  bool seq_error_ = false;
  SdoProgress progress_;
};

}  // namespace hil::canopen
