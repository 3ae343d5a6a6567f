// SPDX-License-Identifier: MIT
#pragma once
// SDO server (CiA 301 §7.2.4): expedited, segmented and block download/upload (with CRC-16)
// against an ObjectDictionary, every failure answered with its CiA 301 abort code.
// Pure state machine: on_frame(frame, now) and step(now) emit frames through the sink.
// Thread: one owner; not thread-safe. Handlers are called synchronously.

#include <cstdint>
#include <deque>
#include <vector>

#include "hil/can/frame.hpp"
#include "hil/canopen/cob_id.hpp"
#include "hil/canopen/object_dictionary.hpp"
#include "hil/core/clock.hpp"

namespace hil::canopen {

struct SdoServerOptions {
  Duration timeout{std::chrono::seconds(1)};  ///< idle time inside a transfer before abort 0x05040000
  std::uint8_t block_size = 127;              ///< segments per block the server asks for (1..127)
  bool block_crc = true;                      ///< server supports CRC in block transfers
};

class SdoServer {
 public:
  SdoServer(ObjectDictionary& od, NodeId node, FrameSink sink, SdoServerOptions options = {});

  /// Handle a frame; returns true when it was addressed to this server (COB-ID 0x600+node by
  /// default). Malformed requests are answered with an abort frame, never a crash.
  bool on_frame(const can::Frame& f, TimePoint now);
  /// Transfer timeouts and delayed responses.
  void step(TimePoint now);
  /// Change the COB-IDs (object 0x1200 sub 1/2).
  void set_cob_ids(std::uint32_t rx, std::uint32_t tx) noexcept {
    rx_cob_ = rx;
    tx_cob_ = tx;
  }
  void set_node(NodeId node) noexcept;
  [[nodiscard]] bool busy() const noexcept { return state_ != State::idle; }

  /// Fault injection: hold every response for `delay` (slow server) / drop them all (mute).
  void set_response_delay(Duration delay) noexcept { delay_ = delay; }
  void set_muted(bool muted) noexcept { muted_ = muted; }

 private:
  enum class State : std::uint8_t {
    idle,
    download_segment,
    upload_segment,
    block_download,
    block_download_end,
    block_upload_start,
    block_upload_ack,
    block_upload_end,
  };
  void send(const can::Frame& f, TimePoint now);
  void respond(std::initializer_list<std::uint8_t> bytes, TimePoint now);
  void abort(SdoAbort code, TimePoint now);
  void start_download(const can::Frame& f, TimePoint now);
  void start_upload(const can::Frame& f, TimePoint now);
  void start_block_download(const can::Frame& f, TimePoint now);
  void start_block_upload(const can::Frame& f, TimePoint now);
  void on_download_segment(const can::Frame& f, TimePoint now);
  void on_upload_segment(const can::Frame& f, TimePoint now);
  void on_block_segment(const can::Frame& f, TimePoint now);
  void on_block_download_end(const can::Frame& f, TimePoint now);
  void on_block_upload(const can::Frame& f, TimePoint now);
  void send_upload_block(TimePoint now);
  void finish_download(TimePoint now, bool block);

  ObjectDictionary& od_;
  FrameSink sink_;
  SdoServerOptions options_;
  std::uint32_t rx_cob_;
  std::uint32_t tx_cob_;
  State state_ = State::idle;
  TimePoint last_{};
  std::uint16_t index_ = 0;
  std::uint8_t sub_ = 0;
  bool toggle_ = false;
  bool size_indicated_ = false;
  std::size_t size_ = 0;
  std::size_t offset_ = 0;
  std::vector<std::uint8_t> buffer_;
  // block transfer
  std::uint8_t blksize_ = 0;
  std::uint8_t expected_seq_ = 1;
  bool seq_error_ = false;
  bool last_segment_ = false;
  bool client_crc_ = false;
  std::size_t block_start_ = 0;
  std::uint8_t sent_in_block_ = 0;
  // fault injection
  Duration delay_{};
  bool muted_ = false;
  std::deque<std::pair<TimePoint, can::Frame>> delayed_;
};

}  // namespace hil::canopen
