// SPDX-License-Identifier: MIT
#pragma once
// Incremental punched-tape text reader (ISO 840 / EIA RS-244 tapes, SINUMERIK ELG §9.3-9.4):
// skips the leader up to the first '%' (ISO) or EOR (EIA, with code detection), checks the
// character parity from there, splits blocks at LF (ISO) / EOB (EIA), enforces the block length
// limit and the optional even-character-count check, and stops at M02/M30 or at a configured
// end character (ETX). Pure: bytes in, events out; no I/O, no clock.
// Error values are the SINUMERIK ELG alarm numbers for the same condition (manual §11).

#include <cstdint>
#include <expected>
#include <optional>
#include <span>
#include <string>
#include <system_error>
#include <vector>

#include "hil/serial/tape/tape_code.hpp"

namespace hil::serial::tape {

enum class TapeError : std::uint16_t {
  character_parity = 23,  ///< "V.24 CHARACTER PARITY ERROR" (also a block with an odd count)
  eia_character = 24,     ///< "IRRELEVANT EIA CHARACTER V.24" (good parity, no meaning; or EIA where ISO is required)
  block_too_long = 29,    ///< "BLOCK TOO LONG (MAX. 254 CHARACTERS) V.24"
  data_format = 32,       ///< "V.24 DATA FORMAT ERROR"
};
[[nodiscard]] const std::error_category& tape_category() noexcept;
[[nodiscard]] inline std::error_code make_error_code(TapeError e) noexcept {
  return {static_cast<int>(e), tape_category()};
}

struct TapeReaderOptions {
  std::optional<Code> code{};           ///< nullopt = detect from the first '%' / EOR
  bool accept_eia = true;               ///< false: an EIA tape is rejected (ELG MD/SD: ISO only)
  bool parity_in_data = true;           ///< the bytes carry the ISO/EIA parity bit (8-bit reader)
  std::size_t max_block_length = 254;   ///< characters incl. CR and LF
  bool even_block_check = false;        ///< count of characters per block incl. LF must be even
  bool even_check_header = false;       ///< apply the even check to the '%' header block too
  bool end_at_m02_m30 = true;           ///< a block "M02"/"M30" ends the tape
  std::optional<char> end_character{};  ///< e.g. ETX (0x03) ends the tape (SD 5016 bit 3)
};

struct TapeEvent {
  enum class Kind { block, end, error } kind = Kind::block;
  std::string text;  ///< block text without CR/LF (the '%' header block is "%TEA1")
  std::error_code error;
  std::size_t offset = 0;  ///< byte offset in the stream where the event happened
  std::string message;
};

class TapeReader {
 public:
  explicit TapeReader(TapeReaderOptions o = {}) : o_(o) {}
  /// Feed bytes; events are appended to `out`. After `end` or `error` further bytes are ignored.
  void feed(std::span<const std::uint8_t> bytes, std::vector<TapeEvent>& out);
  [[nodiscard]] bool finished() const noexcept { return done_; }
  [[nodiscard]] std::optional<Code> code() const noexcept { return code_; }

 private:
  void fail(TapeError e, std::string msg, std::vector<TapeEvent>& out);
  void end_block(std::vector<TapeEvent>& out);

  TapeReaderOptions o_;
  std::optional<Code> code_;
  bool in_leader_ = true;
  bool done_ = false;
  bool in_comment_ = false;
  bool header_block_ = true;
  std::string block_;
  std::size_t block_chars_ = 0;
  std::size_t offset_ = 0;
};

/// Convenience: read a whole tape image. Returns the blocks up to the end, or the first error.
struct TapeRead {
  std::vector<std::string> blocks;
  bool ended = false;  ///< end condition seen (M02/M30/end character)
  std::optional<TapeEvent> error;
  std::optional<Code> code;
};
[[nodiscard]] TapeRead read_tape(std::span<const std::uint8_t> bytes, const TapeReaderOptions& o);

struct TapeWriterOptions {
  Code code = Code::iso;
  bool parity_in_data = true;
  std::size_t leader = 20;   ///< NUL feed holes before the first '%'
  std::size_t trailer = 20;  ///< NUL feed holes after the end (ELG: unless SD 5016 bit 1)
  enum class BlockEnd { lf, cr_lf, lf_cr_cr } block_end = BlockEnd::lf;
  bool pad_even_blocks = false;  ///< add a space where a block would have an odd character count
};
/// Punch blocks ("%TEA1", "N396=180000", "M02") as a tape image. Fails on a character the code
/// cannot carry (e.g. '=' in EIA).
[[nodiscard]] std::expected<std::vector<std::uint8_t>, std::string> make_tape(const std::vector<std::string>& blocks,
                                                                              const TapeWriterOptions& o);

}  // namespace hil::serial::tape

template <>
struct std::is_error_code_enum<hil::serial::tape::TapeError> : std::true_type {};
