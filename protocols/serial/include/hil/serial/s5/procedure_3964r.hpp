// SPDX-License-Identifier: MIT
#pragma once
// Siemens 3964 / 3964R transmission procedure (notes §4.1): STX / DLE handshake, DLE doubling,
// DLE ETX end, BCC (3964R: XOR of every byte after STX incl. doubled DLEs and DLE ETX, the BCC
// itself not doubled), acknowledgement delay (QVZ), character delay (ZVZ), connection and
// transmission retries, and priority on an initialisation conflict (both sides send STX).
// Pure state machine: bytes and `now` in, bytes to send and received blocks out. No I/O.

#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "hil/core/clock.hpp"

namespace hil::serial::s5 {

inline constexpr std::uint8_t stx = 0x02;
inline constexpr std::uint8_t etx = 0x03;
inline constexpr std::uint8_t dle = 0x10;
inline constexpr std::uint8_t nak = 0x15;

/// Why a block could not be sent or received (values are ours; the manuals number none).
enum class ProcedureError : std::uint8_t {
  no_connection = 1,     ///< no DLE after STX within QVZ on every connection attempt
  not_acknowledged = 2,  ///< NAK or no DLE after the block on every transmission attempt
  char_timeout = 3,      ///< receiving: gap longer than ZVZ inside a block (we answered NAK)
  bcc_error = 4,         ///< receiving: BCC wrong (we answered NAK)
  framing = 5,           ///< receiving: DLE followed by neither DLE nor ETX (we answered NAK)
  block_too_long = 6,    ///< receiving: more than max_block bytes (we answered NAK)
};
[[nodiscard]] const std::error_category& procedure_category() noexcept;
[[nodiscard]] inline std::error_code make_error_code(ProcedureError e) noexcept {
  return {static_cast<int>(e), procedure_category()};
}

struct ProcedureOptions {
  bool with_bcc = true;                                    ///< 3964R (true) or 3964 (false)
  Duration ack_timeout = std::chrono::milliseconds(2000);  ///< QVZ: 2 s for 3964R, 550 ms (or 500) for 3964
  Duration char_timeout = std::chrono::milliseconds(220);  ///< ZVZ
  int connect_attempts = 6;                                ///< STX tries per block
  int transmit_attempts = 6;                               ///< block tries per block
  bool high_priority = true;                               ///< wins an initialisation conflict
  std::size_t max_block = 1024;                            ///< payload bytes accepted per block
};

/// Wire form of a block: escaped payload, DLE ETX, BCC (if 3964R). Without the leading STX.
[[nodiscard]] std::vector<std::uint8_t> make_block(const std::vector<std::uint8_t>& payload, bool with_bcc);

class Procedure3964 {
 public:
  explicit Procedure3964(ProcedureOptions o = {}) : o_(o) {}

  /// Queue a payload to send. Sending starts at the next poll().
  void send(std::vector<std::uint8_t> payload);
  /// Bytes received from the line.
  void on_bytes(std::span<const std::uint8_t> bytes, TimePoint now);
  /// Advance timers and start queued sends. Call after on_bytes and at next_deadline().
  void poll(TimePoint now);
  [[nodiscard]] TimePoint next_deadline() const noexcept { return deadline_; }

  /// Bytes to write to the line now (moved out).
  [[nodiscard]] std::vector<std::uint8_t> take_output() { return std::exchange(out_, {}); }
  /// Payloads received completely and acknowledged.
  [[nodiscard]] std::optional<std::vector<std::uint8_t>> take_received();
  struct SendResult {
    bool ok = false;
    std::error_code error;
  };
  /// Results of queued sends, in order.
  [[nodiscard]] std::optional<SendResult> take_send_result();
  /// Receive-side errors (each answered with NAK), for logs and tests.
  [[nodiscard]] std::vector<std::error_code> take_receive_errors() { return std::exchange(rx_errors_, {}); }
  [[nodiscard]] bool idle() const noexcept { return state_ == State::idle && queue_.empty(); }
  /// Counters for reports.
  [[nodiscard]] int retries() const noexcept { return retries_; }

 private:
  enum class State { idle, tx_wait_dle, tx_wait_ack, rx_data, rx_bcc };
  void start_receive(TimePoint now);
  void start_connect(TimePoint now);
  void rx_fail(ProcedureError e);
  void tx_retry(TimePoint now, bool connect_phase);

  ProcedureOptions o_;
  State state_ = State::idle;
  TimePoint deadline_ = TimePoint::max();
  std::deque<std::vector<std::uint8_t>> queue_;
  int connect_tries_ = 0;
  int transmit_tries_ = 0;
  int retries_ = 0;
  bool defer_once_ = false;
  std::vector<std::uint8_t> rx_;
  std::uint8_t rx_bcc_ = 0;
  bool rx_dle_ = false;
  std::vector<std::uint8_t> out_;
  std::deque<std::vector<std::uint8_t>> received_;
  std::deque<SendResult> results_;
  std::vector<std::error_code> rx_errors_;
};

}  // namespace hil::serial::s5

template <>
struct std::is_error_code_enum<hil::serial::s5::ProcedureError> : std::true_type {};
