// SPDX-License-Identifier: MIT
#pragma once
// RK512 jobs over 3964R on a byte stream (the PC side of an S5 computer link): SEND a DB
// image, FETCH a DB area, each answered by a reaction telegram within the response
// monitoring time. Blocking, one thread; time from the injected clock.

#include <cstdint>
#include <expected>
#include <string>
#include <system_error>
#include <vector>

#include "hil/core/clock.hpp"
#include "hil/serial/byte_stream.hpp"
#include "hil/serial/s5/procedure_3964r.hpp"
#include "hil/serial/s5/rk512.hpp"

namespace hil::serial::s5 {

struct LinkError {
  std::error_code code;  ///< ProcedureError, Rk512Error, LineError
  std::string message;
};

struct Rk512ClientOptions {
  ProcedureOptions procedure{};
  Duration reaction_timeout = std::chrono::seconds(5);  ///< response monitoring (5 s at 1200..19200 Bd)
  std::size_t max_data = rk512_default_max_data;
};

class Rk512Client {
 public:
  Rk512Client(ByteStream& stream, const Clock& clock, Rk512ClientOptions o = {});
  /// SEND `words` (big-endian data words) to DB `db` from data word `dw`.
  [[nodiscard]] std::expected<void, LinkError> send_db(std::uint8_t db, std::uint8_t dw,
                                                       const std::vector<std::uint16_t>& words);
  /// FETCH `length` words of DB `db` from data word `dw`.
  [[nodiscard]] std::expected<std::vector<std::uint16_t>, LinkError> fetch_db(std::uint8_t db, std::uint8_t dw,
                                                                              std::uint16_t length);
  [[nodiscard]] int procedure_retries() const noexcept { return proc_.retries(); }

 private:
  std::expected<void, LinkError> transmit(const std::vector<std::uint8_t>& telegram);
  std::expected<Rk512Telegram, LinkError> receive_reaction(std::size_t expected_bytes);
  void pump(Duration max_wait);

  ByteStream& stream_;
  const Clock& clock_;
  Rk512ClientOptions o_;
  Procedure3964 proc_;
};

/// Big-endian word packing of S5 data words.
[[nodiscard]] std::vector<std::uint8_t> words_to_bytes(const std::vector<std::uint16_t>& w);
[[nodiscard]] std::vector<std::uint16_t> bytes_to_words(std::span<const std::uint8_t> b);

}  // namespace hil::serial::s5
