// SPDX-License-Identifier: MIT
#include "hil/serial/s5/rk512_client.hpp"

#include <fmt/format.h>

#include <array>

namespace hil::serial::s5 {

std::vector<std::uint8_t> words_to_bytes(const std::vector<std::uint16_t>& w) {
  std::vector<std::uint8_t> b;
  b.reserve(w.size() * 2);
  for (auto x : w) {
    b.push_back(static_cast<std::uint8_t>(x >> 8));
    b.push_back(static_cast<std::uint8_t>(x & 0xFF));
  }
  return b;
}

std::vector<std::uint16_t> bytes_to_words(std::span<const std::uint8_t> b) {
  std::vector<std::uint16_t> w;
  for (std::size_t i = 0; i + 1 < b.size(); i += 2) w.push_back(static_cast<std::uint16_t>((b[i] << 8) | b[i + 1]));
  return w;
}

Rk512Client::Rk512Client(ByteStream& stream, const Clock& clock, Rk512ClientOptions o)
    : stream_(stream), clock_(clock), o_(o), proc_(o.procedure) {}

void Rk512Client::pump(Duration max_wait) {
  proc_.poll(clock_.now());
  if (auto out = proc_.take_output(); !out.empty()) (void)stream_.write(out, std::chrono::seconds(5));
  const TimePoint dl = proc_.next_deadline();
  Duration wait = max_wait;
  if (dl != TimePoint::max()) wait = std::max(Duration::zero(), std::min(wait, dl - clock_.now()));
  std::array<std::uint8_t, 512> buf{};
  const ReadResult r = stream_.read_some(buf, wait);
  proc_.on_bytes(std::span(buf.data(), r.size), clock_.now());
  if (auto out = proc_.take_output(); !out.empty()) (void)stream_.write(out, std::chrono::seconds(5));
}

std::expected<void, LinkError> Rk512Client::transmit(const std::vector<std::uint8_t>& telegram) {
  proc_.send(telegram);
  for (;;) {
    if (auto res = proc_.take_send_result()) {
      if (res->ok) return {};
      return std::unexpected(LinkError{res->error, res->error.message()});
    }
    pump(std::chrono::milliseconds(100));
  }
}

std::expected<Rk512Telegram, LinkError> Rk512Client::receive_reaction(std::size_t expected_bytes) {
  Rk512Assembler as;
  as.expect(expected_bytes);
  TimePoint deadline = clock_.now() + o_.reaction_timeout;
  while (clock_.now() < deadline) {
    while (auto blk = proc_.take_received()) {
      auto t = parse_rk512(*blk);
      if (!t)
        return std::unexpected(LinkError{Rk512Error::header_error, "reaction telegram unusable: " + t.error().message});
      const auto st = as.feed(*t);
      if (st == Rk512Assembler::Status::error)
        return std::unexpected(LinkError{Rk512Error::header_error, "reaction: " + as.error()});
      if (st == Rk512Assembler::Status::complete) {
        if (as.job().kind != Rk512Telegram::Kind::reaction)
          return std::unexpected(LinkError{Rk512Error::header_error, "expected a reaction telegram, got a command"});
        if (as.job().error != Rk512Error::ok)
          return std::unexpected(LinkError{as.job().error, make_error_code(as.job().error).message()});
        return as.job();
      }
      deadline = clock_.now() + o_.reaction_timeout;
    }
    pump(std::min<Duration>(deadline - clock_.now(), std::chrono::milliseconds(100)));
  }
  return std::unexpected(
      LinkError{LineError::timeout,
                fmt::format("no reaction telegram within {} ms",
                            std::chrono::duration_cast<std::chrono::milliseconds>(o_.reaction_timeout).count())});
}

std::expected<void, LinkError> Rk512Client::send_db(std::uint8_t db, std::uint8_t dw,
                                                    const std::vector<std::uint16_t>& words) {
  Rk512Header h;
  h.command = Rk512Command::send_db;
  h.data_type = 'D';
  h.db = db;
  h.dw = dw;
  h.length = static_cast<std::uint16_t>(words.size());
  const auto data = words_to_bytes(words);
  for (const auto& t : make_rk512_request(h, data, o_.max_data)) {
    if (auto r = transmit(t); !r) return r;
  }
  auto reaction = receive_reaction(0);
  if (!reaction) return std::unexpected(reaction.error());
  return {};
}

std::expected<std::vector<std::uint16_t>, LinkError> Rk512Client::fetch_db(std::uint8_t db, std::uint8_t dw,
                                                                           std::uint16_t length) {
  Rk512Header h;
  h.command = Rk512Command::fetch;
  h.data_type = 'D';
  h.db = db;
  h.dw = dw;
  h.length = length;
  for (const auto& t : make_rk512_request(h, {}, o_.max_data)) {
    if (auto r = transmit(t); !r) return std::unexpected(r.error());
  }
  auto reaction = receive_reaction(std::size_t{length} * 2U);
  if (!reaction) return std::unexpected(reaction.error());
  return bytes_to_words(reaction->data);
}

}  // namespace hil::serial::s5
