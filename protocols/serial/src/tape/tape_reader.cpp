// SPDX-License-Identifier: MIT
#include "hil/serial/tape/tape_reader.hpp"

#include <fmt/format.h>

namespace hil::serial::tape {

namespace {
class Category final : public std::error_category {
 public:
  const char* name() const noexcept override { return "tape"; }
  std::string message(int c) const override {
    switch (static_cast<TapeError>(c)) {
      case TapeError::character_parity:
        return "tape character parity error (ELG alarm 23)";
      case TapeError::eia_character:
        return "irrelevant EIA character / EIA not allowed here (ELG alarm 24)";
      case TapeError::block_too_long:
        return "block too long (ELG alarm 29)";
      case TapeError::data_format:
        return "tape data format error (ELG alarm 32)";
    }
    return fmt::format("tape error {}", c);
  }
};
}  // namespace

const std::error_category& tape_category() noexcept {
  static const Category c;
  return c;
}

void TapeReader::fail(TapeError e, std::string msg, std::vector<TapeEvent>& out) {
  done_ = true;
  out.push_back(TapeEvent{TapeEvent::Kind::error, block_, e, offset_, std::move(msg)});
}

void TapeReader::end_block(std::vector<TapeEvent>& out) {
  std::string text = block_;
  while (!text.empty() && (text.back() == '\r' || text.back() == ' ')) text.pop_back();
  while (!text.empty() && text.front() == '\r') text.erase(text.begin());
  const std::size_t chars = block_chars_;
  const bool header = header_block_;
  block_.clear();
  block_chars_ = 0;
  header_block_ = false;
  if (o_.even_block_check && (!header || o_.even_check_header) && (chars % 2) != 0) {
    fail(TapeError::character_parity,
         fmt::format("block '{}' has {} characters including LF: the count must be even", text, chars), out);
    return;
  }
  if (text.empty()) return;  // blank blocks (CR CR after LF, empty lines) carry nothing
  if (o_.end_at_m02_m30 && !header && (text == "M02" || text == "M30" || text == "M2")) {
    out.push_back(TapeEvent{TapeEvent::Kind::block, text, {}, offset_, {}});
    out.push_back(TapeEvent{TapeEvent::Kind::end, text, {}, offset_, {}});
    done_ = true;
    return;
  }
  out.push_back(TapeEvent{TapeEvent::Kind::block, std::move(text), {}, offset_, {}});
}

void TapeReader::feed(std::span<const std::uint8_t> bytes, std::vector<TapeEvent>& out) {
  for (std::uint8_t b : bytes) {
    if (done_) return;
    ++offset_;
    if (in_leader_) {
      // Leader: anything but '%' (ISO) or EOR (EIA); code detection on that character.
      const bool iso_percent = o_.parity_in_data ? b == make_iso('%') : (b & 0x7F) == '%';
      const bool eia_eor_seen = o_.parity_in_data && b == eia_eor;
      if (iso_percent && (!o_.code || *o_.code == Code::iso)) {
        code_ = Code::iso;
      } else if (eia_eor_seen && (!o_.code || *o_.code == Code::eia)) {
        if (!o_.accept_eia) {
          fail(TapeError::eia_character, "EIA tape (EOR found) where only ISO code is accepted", out);
          return;
        }
        code_ = Code::eia;
      } else {
        continue;
      }
      in_leader_ = false;
      block_ = "%";
      block_chars_ = 1;
      continue;
    }
    char c = 0;
    if (*code_ == Code::iso) {
      if (o_.parity_in_data) {
        auto d = parse_iso(b);
        if (!d) {
          fail(TapeError::character_parity,
               fmt::format("byte 0x{:02X} at offset {} has odd parity (ISO needs even)", b, offset_ - 1), out);
          return;
        }
        c = *d;
      } else {
        c = static_cast<char>(b & 0x7F);
      }
    } else {
      const auto d = parse_eia(b);
      if (!d.parity_ok) {
        fail(TapeError::character_parity,
             fmt::format("byte 0x{:02X} at offset {} has even parity (EIA needs odd)", b, offset_ - 1), out);
        return;
      }
      if (!d.c) {
        fail(TapeError::eia_character,
             fmt::format("byte 0x{:02X} at offset {} is not an EIA character", b, offset_ - 1), out);
        return;
      }
      c = *d.c;
    }
    if (c == '\0' || c == '\x7F') continue;  // feed holes and deleted characters do not count
    if (o_.end_character && c == *o_.end_character) {
      if (!block_.empty()) end_block(out);
      if (!done_) out.push_back(TapeEvent{TapeEvent::Kind::end, {}, {}, offset_, {}});
      done_ = true;
      return;
    }
    ++block_chars_;
    if (c == '\n') {
      end_block(out);
      continue;
    }
    if (c == '(') in_comment_ = true;
    if (c == ')') in_comment_ = false;
    if (c == '%' && !in_comment_) {
      // A new '%' starts the next section (MD tape followed by SD tape).
      if (!block_.empty() && block_ != "\r") {
        fail(TapeError::data_format, fmt::format("'%' inside block '{}'", block_), out);
        return;
      }
      block_ = "%";
      header_block_ = true;
      continue;
    }
    block_.push_back(c);
    if (block_chars_ > o_.max_block_length) {
      fail(TapeError::block_too_long, fmt::format("block longer than {} characters", o_.max_block_length), out);
      return;
    }
  }
}

TapeRead read_tape(std::span<const std::uint8_t> bytes, const TapeReaderOptions& o) {
  TapeReader r(o);
  std::vector<TapeEvent> ev;
  r.feed(bytes, ev);
  TapeRead out;
  out.code = r.code();
  for (auto& e : ev) {
    if (e.kind == TapeEvent::Kind::block)
      out.blocks.push_back(e.text);
    else if (e.kind == TapeEvent::Kind::end)
      out.ended = true;
    else
      out.error = e;
  }
  return out;
}

std::expected<std::vector<std::uint8_t>, std::string> make_tape(const std::vector<std::string>& blocks,
                                                                const TapeWriterOptions& o) {
  std::vector<std::uint8_t> out(o.leader, 0x00);
  const auto put = [&](char c) -> std::expected<void, std::string> {
    if (o.code == Code::iso) {
      out.push_back(o.parity_in_data ? make_iso(c) : static_cast<std::uint8_t>(c));
      return {};
    }
    auto b = make_eia(c);
    if (!b) return std::unexpected(fmt::format("character '{}' does not exist in EIA code", c));
    out.push_back(*b);
    return {};
  };
  for (const auto& blk : blocks) {
    std::string text = blk;
    std::string end;
    if (o.code == Code::eia)
      end = "\n";
    else if (o.block_end == TapeWriterOptions::BlockEnd::lf)
      end = "\n";
    else if (o.block_end == TapeWriterOptions::BlockEnd::cr_lf)
      end = "\r\n";
    else
      end = "\n\r\r";
    if (o.pad_even_blocks && ((text.size() + end.size()) % 2) != 0) text.push_back(' ');
    for (char c : text)
      if (auto r = put(c); !r) return std::unexpected(fmt::format("block '{}': {}", blk, r.error()));
    for (char c : end)
      if (auto r = put(c); !r) return std::unexpected(r.error());
  }
  out.insert(out.end(), o.trailer, 0x00);
  return out;
}

}  // namespace hil::serial::tape
