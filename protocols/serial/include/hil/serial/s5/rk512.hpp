// SPDX-License-Identifier: MIT
#pragma once
// RK 512 computer link telegrams carried in 3964R blocks (notes §4.2; Siemens CP 341 p.51):
// 10-byte command header (continuation frames: 4 bytes, first byte FFh), data at most
// `max_data` bytes per telegram, reaction telegrams "00 00 00 <error>" (+ data for FETCH).
// Pure codec: telegram images in, typed values out.

#include <cstdint>
#include <expected>
#include <span>
#include <string>
#include <system_error>
#include <vector>

namespace hil::serial::s5 {

enum class Rk512Command : std::uint8_t { send_db = 'A', send_dx = 'O', fetch = 'E' };

/// Reaction-telegram error numbers. Values follow the S5 interface error byte (IP247 MB250,
/// digest ip247.md §5.6) where one fits; the CP manuals' own list was not available.
enum class Rk512Error : std::uint8_t {
  ok = 0x00,
  processing_not_possible = 0x06,  ///< busy / state does not allow the job
  db_exists = 0x07,                ///< no overwrite: delete first
  db_missing = 0x08,               ///< FETCH / delete of a DB that does not exist
  wrong_identifier = 0x09,         ///< header words of the image wrong (length, 'DB', number)
  target_too_small = 0x0A,         ///< area exceeds the DB / image longer than allowed
  header_error = 0x0C,             ///< bad command, data type or continuation sequence
  image_rejected = 0x10,           ///< device validation failed (MD error written into the image)
};
[[nodiscard]] const std::error_category& rk512_category() noexcept;
[[nodiscard]] inline std::error_code make_error_code(Rk512Error e) noexcept {
  return {static_cast<int>(e), rk512_category()};
}

struct Rk512Header {
  Rk512Command command = Rk512Command::send_db;
  char data_type = 'D';      ///< 'D' DB, 'X' DX, 'E' inputs, 'A' outputs, 'M' flags, 'T', 'Z'
  std::uint8_t db = 0;       ///< DB number (byte 5)
  std::uint8_t dw = 0;       ///< start data word (byte 6)
  std::uint16_t length = 0;  ///< words for DB/DX
  std::uint8_t coord_flag_byte = 0xFF;
  std::uint8_t coord_flag_bit_cpu = 0xFF;
  friend bool operator==(const Rk512Header&, const Rk512Header&) = default;
};

inline constexpr std::size_t rk512_default_max_data = 128;

/// Telegrams of a SEND (header + data, then continuations) or of a FETCH request (one header).
[[nodiscard]] std::vector<std::vector<std::uint8_t>> make_rk512_request(const Rk512Header& h,
                                                                        std::span<const std::uint8_t> data,
                                                                        std::size_t max_data = rk512_default_max_data);
/// Reaction telegram(s): "00 00 00 err" + data; continuations "FF 00 00 err" + data.
[[nodiscard]] std::vector<std::vector<std::uint8_t>> make_rk512_reaction(Rk512Error err,
                                                                         std::span<const std::uint8_t> data,
                                                                         std::size_t max_data = rk512_default_max_data);

struct Rk512ParseError {
  std::string message;
};

/// A telegram as received: a command (first or continuation) or a reaction.
struct Rk512Telegram {
  enum class Kind { command, continuation, reaction, reaction_continuation } kind = Kind::command;
  Rk512Header header;                 ///< command: full; continuation: command + type only
  Rk512Error error = Rk512Error::ok;  ///< reaction
  std::vector<std::uint8_t> data;
};
[[nodiscard]] std::expected<Rk512Telegram, Rk512ParseError> parse_rk512(std::span<const std::uint8_t> telegram);

/// Collects the telegrams of one job (command + continuations, or reaction + continuations)
/// until `expected_bytes` data bytes arrived.
class Rk512Assembler {
 public:
  enum class Status { need_more, complete, error };
  /// Feed one telegram. For a command, the expected size comes from its header (SEND: length
  /// words * 2; FETCH: 0). For reactions call expect() first with the FETCH size.
  Status feed(const Rk512Telegram& t);
  void expect(std::size_t bytes) { expected_ = bytes; }
  [[nodiscard]] const Rk512Telegram& job() const noexcept { return job_; }
  [[nodiscard]] const std::string& error() const noexcept { return error_; }
  void reset() { *this = Rk512Assembler{}; }

 private:
  Rk512Telegram job_;
  std::size_t expected_ = 0;
  bool started_ = false;
  std::string error_;
};

}  // namespace hil::serial::s5

template <>
struct std::is_error_code_enum<hil::serial::s5::Rk512Error> : std::true_type {};
