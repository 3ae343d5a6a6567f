// SPDX-License-Identifier: MIT
#include "hil/serial/s5/rk512.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace hil::serial::s5 {

namespace {
class Category final : public std::error_category {
 public:
  const char* name() const noexcept override { return "rk512"; }
  std::string message(int c) const override {
    switch (static_cast<Rk512Error>(c)) {
      case Rk512Error::ok:
        return "no error";
      case Rk512Error::processing_not_possible:
        return "RK512 reaction 06: processing currently not possible";
      case Rk512Error::db_exists:
        return "RK512 reaction 07: DB already exists (delete it first, no overwrite)";
      case Rk512Error::db_missing:
        return "RK512 reaction 08: DB does not exist";
      case Rk512Error::wrong_identifier:
        return "RK512 reaction 09: wrong block identifier in the image";
      case Rk512Error::target_too_small:
        return "RK512 reaction 0A: area outside the DB / image too long";
      case Rk512Error::header_error:
        return "RK512 reaction 0C: illegal command, data type or telegram sequence";
      case Rk512Error::image_rejected:
        return "RK512 reaction 10: the device rejected the data (see its error number)";
    }
    return fmt::format("RK512 reaction {:02X}", c);
  }
};
}  // namespace

const std::error_category& rk512_category() noexcept {
  static const Category c;
  return c;
}

std::vector<std::vector<std::uint8_t>> make_rk512_request(const Rk512Header& h, std::span<const std::uint8_t> data,
                                                          std::size_t max_data) {
  std::vector<std::vector<std::uint8_t>> out;
  const auto cmd = static_cast<std::uint8_t>(h.command);
  std::vector<std::uint8_t> first{0x00,
                                  0x00,
                                  cmd,
                                  static_cast<std::uint8_t>(h.data_type),
                                  h.db,
                                  h.dw,
                                  static_cast<std::uint8_t>(h.length >> 8),
                                  static_cast<std::uint8_t>(h.length & 0xFF),
                                  h.coord_flag_byte,
                                  h.coord_flag_bit_cpu};
  std::size_t pos = std::min(max_data, data.size());
  first.insert(first.end(), data.begin(), data.begin() + static_cast<std::ptrdiff_t>(pos));
  out.push_back(std::move(first));
  while (pos < data.size()) {
    const std::size_t n = std::min(max_data, data.size() - pos);
    std::vector<std::uint8_t> c{0xFF, 0x00, cmd, static_cast<std::uint8_t>(h.data_type)};
    c.insert(c.end(), data.begin() + static_cast<std::ptrdiff_t>(pos),
             data.begin() + static_cast<std::ptrdiff_t>(pos + n));
    out.push_back(std::move(c));
    pos += n;
  }
  return out;
}

std::vector<std::vector<std::uint8_t>> make_rk512_reaction(Rk512Error err, std::span<const std::uint8_t> data,
                                                           std::size_t max_data) {
  std::vector<std::vector<std::uint8_t>> out;
  std::size_t pos = 0;
  do {
    const std::size_t n = std::min(max_data, data.size() - pos);
    std::vector<std::uint8_t> t{static_cast<std::uint8_t>(pos == 0 ? 0x00 : 0xFF), 0x00, 0x00,
                                static_cast<std::uint8_t>(err)};
    t.insert(t.end(), data.begin() + static_cast<std::ptrdiff_t>(pos),
             data.begin() + static_cast<std::ptrdiff_t>(pos + n));
    out.push_back(std::move(t));
    pos += n;
  } while (pos < data.size());
  return out;
}

std::expected<Rk512Telegram, Rk512ParseError> parse_rk512(std::span<const std::uint8_t> t) {
  if (t.size() < 4)
    return std::unexpected(Rk512ParseError{fmt::format("RK512 telegram of {} bytes: at least 4 expected", t.size())});
  if ((t[0] != 0x00 && t[0] != 0xFF) || t[1] != 0x00)
    return std::unexpected(
        Rk512ParseError{fmt::format("RK512 telegram starts {:02X} {:02X}: expected 00 00 or FF 00", t[0], t[1])});
  Rk512Telegram r;
  const bool cont = t[0] == 0xFF;
  if (t[2] == 0x00) {
    r.kind = cont ? Rk512Telegram::Kind::reaction_continuation : Rk512Telegram::Kind::reaction;
    r.error = static_cast<Rk512Error>(t[3]);
    r.data.assign(t.begin() + 4, t.end());
    return r;
  }
  if (t[2] != 'A' && t[2] != 'O' && t[2] != 'E')
    return std::unexpected(
        Rk512ParseError{fmt::format("RK512 command byte {:02X} unknown: expected 'A', 'O' or 'E'", t[2])});
  r.header.command = static_cast<Rk512Command>(t[2]);
  r.header.data_type = static_cast<char>(t[3]);
  if (std::string_view("DXEAMTZ").find(r.header.data_type) == std::string_view::npos)
    return std::unexpected(Rk512ParseError{fmt::format("RK512 data type {:02X} unknown", t[3])});
  if (cont) {
    r.kind = Rk512Telegram::Kind::continuation;
    r.data.assign(t.begin() + 4, t.end());
    return r;
  }
  if (t.size() < 10)
    return std::unexpected(Rk512ParseError{fmt::format("RK512 command header of {} bytes: 10 expected", t.size())});
  r.header.db = t[4];
  r.header.dw = t[5];
  r.header.length = static_cast<std::uint16_t>((t[6] << 8) | t[7]);
  r.header.coord_flag_byte = t[8];
  r.header.coord_flag_bit_cpu = t[9];
  r.data.assign(t.begin() + 10, t.end());
  if (r.header.command != Rk512Command::fetch && r.header.data_type != 'D' && r.header.data_type != 'X')
    return std::unexpected(Rk512ParseError{"RK512 SEND allows only data types 'D' and 'X'"});
  if (r.header.command == Rk512Command::fetch && !r.data.empty())
    return std::unexpected(Rk512ParseError{"RK512 FETCH request carries data"});
  return r;
}

Rk512Assembler::Status Rk512Assembler::feed(const Rk512Telegram& t) {
  using K = Rk512Telegram::Kind;
  if (!started_) {
    if (t.kind == K::continuation || t.kind == K::reaction_continuation) {
      error_ = "continuation telegram without a first telegram";
      return Status::error;
    }
    job_ = t;
    started_ = true;
    if (t.kind == K::command)
      expected_ = t.header.command == Rk512Command::fetch ? 0 : std::size_t{t.header.length} * 2U;
    if (t.kind == K::reaction && t.error != Rk512Error::ok) return Status::complete;
  } else {
    const bool cont_ok =
        (job_.kind == K::command && t.kind == K::continuation && t.header.command == job_.header.command) ||
        (job_.kind == K::reaction && t.kind == K::reaction_continuation);
    if (!cont_ok) {
      error_ = "telegram does not continue the running job";
      return Status::error;
    }
    job_.data.insert(job_.data.end(), t.data.begin(), t.data.end());
  }
  if (job_.data.size() > expected_) {
    error_ = fmt::format("{} data bytes received, {} announced", job_.data.size(), expected_);
    return Status::error;
  }
  return job_.data.size() == expected_ ? Status::complete : Status::need_more;
}

}  // namespace hil::serial::s5
