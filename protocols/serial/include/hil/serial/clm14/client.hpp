// SPDX-License-Identifier: MIT
#pragma once
// CLM1.4 serial client (PC side of manual §9.2): one telegram out, one reply in, with the
// response and inter-character timeouts measured on the injected clock, retries on a
// checksum error / corrupt reply / timeout, and the device's status-01 error reports turned
// into error codes (SerialError) with the device's own text.
// Blocking; one thread. Every call returns within (retries + 1) * (write + response timeout).

#include <chrono>
#include <expected>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>

#include "hil/core/clock.hpp"
#include "hil/serial/byte_stream.hpp"
#include "hil/serial/clm14/device_data.hpp"
#include "hil/serial/clm14/telegram.hpp"

namespace hil::serial::clm14 {

struct ClientOptions {
  int station = 0;                                              ///< 0 = RS-232, 1..32 = RS-485 station
  Duration response_timeout = std::chrono::milliseconds(1000);  ///< request sent -> first reply byte
  Duration char_timeout = std::chrono::milliseconds(200);       ///< between two reply bytes
  Duration write_timeout = std::chrono::seconds(5);             ///< incl. time held by XOFF
  int retries = 2;                                              ///< repeats after a checksum error/timeout
  bool expect_confirmation = true;                              ///< B003/B005 C = 1: writes answered by "Y"
};

struct ClientError {
  std::error_code code;  ///< SerialError (device's number), LineError, or SyntaxError
  std::string message;   ///< what, where, what to do
  int device_error = 0;  ///< the CLM serial error number when the device reported one
};

class Client {
 public:
  /// `stream`, `clock` and `data` must outlive the client. `data` may be null (no texts).
  Client(ByteStream& stream, const Clock& clock, ClientOptions options, std::shared_ptr<const DeviceData> data = {});

  /// Send `body` with `lead` and return the reply telegram (a data reply or "Y").
  [[nodiscard]] std::expected<Telegram, ClientError> transact(char lead, std::string_view body, bool expect_reply);

  /// Program line n (0..2999) as "MNE data" without trailing spaces.
  [[nodiscard]] std::expected<std::string, ClientError> read_program_line(int n);
  [[nodiscard]] std::expected<void, ClientError> write_program_line(int n, std::string_view text);
  /// Parameter data text ("019200 0 1 8 1") for number "B002".
  [[nodiscard]] std::expected<std::string, ClientError> read_parameter(std::string_view number);
  [[nodiscard]] std::expected<void, ClientError> write_parameter(std::string_view number, std::string_view data);
  [[nodiscard]] std::expected<std::string, ClientError> read_variable(int n);
  [[nodiscard]] std::expected<void, ClientError> write_variable(int n, std::string_view value);
  /// Status nn with optional argument; returns the reply body after "nn ".
  [[nodiscard]] std::expected<std::string, ClientError> read_status(int n, std::string_view arg = {});
  /// Interface command "START", "CNOPNC00002999", ... (always sent with checksum).
  [[nodiscard]] std::expected<void, ClientError> command(std::string_view name);

  [[nodiscard]] const ClientOptions& options() const noexcept { return options_; }
  /// Retries performed so far (for reports and tests).
  [[nodiscard]] int retries_used() const noexcept { return retries_used_; }

 private:
  [[nodiscard]] std::expected<std::string, ClientError> read_line(Duration first_byte_timeout);
  void drain();

  ByteStream& stream_;
  const Clock& clock_;
  ClientOptions options_;
  std::shared_ptr<const DeviceData> data_;
  char station_;
  int retries_used_ = 0;
};

}  // namespace hil::serial::clm14
