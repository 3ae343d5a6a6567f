// SPDX-License-Identifier: MIT
#pragma once
// The RK512 jobs of the S5 module endpoint fuzz targets: the input is a sequence of requests (SEND
// or FETCH of DB or DX, any block, start word and length, data words from the input, virtual time
// between them), each executed against a DbPolicy exactly as S5BlockEndpoint executes a complete
// job; the answer must be a reaction the PLC can parse: one of the RK512 error numbers, and on a
// successful FETCH exactly the words asked for. Anything else aborts.
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "hil/mocks/legacy/s5_block_endpoint.hpp"
#include "hil/serial/s5/rk512.hpp"
#include "hil/serial/s5/rk512_client.hpp"

namespace hil::fuzz {

/// Reads the input byte by byte (0 after its end).
struct Input {
  std::span<const std::uint8_t> data;
  std::size_t pos = 0;
  [[nodiscard]] bool more() const noexcept { return pos < data.size(); }
  int byte() noexcept { return pos < data.size() ? data[pos++] : 0; }
  std::uint16_t word() noexcept { return static_cast<std::uint16_t>(byte() << 8 | byte()); }
};

/// The reaction of `err` (and `out` for a FETCH) built and parsed back as the PLC would.
inline void check_reaction(serial::s5::Rk512Error err, bool fetch, std::uint16_t length,
                           const std::vector<std::uint16_t>& out) {
  using serial::s5::Rk512Error;
  static constexpr std::array known{
      Rk512Error::ok,           Rk512Error::processing_not_possible, Rk512Error::db_exists,
      Rk512Error::db_missing,   Rk512Error::wrong_identifier,        Rk512Error::target_too_small,
      Rk512Error::header_error, Rk512Error::image_rejected};
  bool valid = false;
  for (auto k : known) valid = valid || k == err;
  if (!valid) std::abort();
  if (fetch && err == Rk512Error::ok && out.size() != length) std::abort();
  const auto bytes = fetch && err == Rk512Error::ok ? serial::s5::words_to_bytes(out) : std::vector<std::uint8_t>{};
  std::size_t got = 0;
  bool first = true;
  for (const auto& t : serial::s5::make_rk512_reaction(err, bytes)) {
    const auto r = serial::s5::parse_rk512(t);
    if (!r) std::abort();
    using K = serial::s5::Rk512Telegram::Kind;
    if (r->kind != (first ? K::reaction : K::reaction_continuation)) std::abort();
    if (first && r->error != err) std::abort();
    got += r->data.size();
    first = false;
  }
  if (first || got != bytes.size()) std::abort();
}

/// Runs the requests of `in` against `policy` (its DB store `store`), calling `advance(ms)` for the
/// virtual time between requests.
template <class Advance>
void run_requests(Input& in, mocks::legacy::DbPolicy& policy, mocks::legacy::DbStore& store, Advance advance) {
  for (int job = 0; job < 64 && in.more(); ++job) {
    const int op = in.byte();
    const bool fetch = (op & 1) != 0;
    const bool dx = (op & 2) != 0;
    advance((op >> 2) & 0x3F);
    const auto db = static_cast<std::uint8_t>(in.byte());
    const auto dw = static_cast<std::uint8_t>(in.byte());
    auto length = static_cast<std::uint16_t>(in.byte() | ((in.byte() & 1) << 8));  // 0..511 words
    std::vector<std::uint16_t> out;
    serial::s5::Rk512Error err{};
    if (fetch) {
      err = dx ? policy.on_read_dx(store, db, dw, length, out) : policy.on_read(store, db, dw, length, out);
    } else {
      // The data: a pattern word from the input, or a copy of a block's image the input patches
      // (so the policies see well-formed images as well as noise).
      std::vector<std::uint16_t> w(length);
      const int kind = in.byte() & 3;
      for (std::size_t i = 0; i < w.size(); ++i) w[i] = kind == 0 ? in.word() : static_cast<std::uint16_t>(i);
      if (kind == 1 && !w.empty()) {
        if (const auto it = store.find(static_cast<std::uint8_t>(in.byte())); it != store.end()) w = it->second;
        if (!w.empty()) w[static_cast<std::size_t>(in.byte()) % w.size()] = in.word();
      }
      length = static_cast<std::uint16_t>(w.size());
      err = dx ? policy.on_write_dx(store, db, dw, w) : policy.on_write(store, db, dw, w);
    }
    check_reaction(err, fetch, length, out);
  }
}

}  // namespace hil::fuzz
