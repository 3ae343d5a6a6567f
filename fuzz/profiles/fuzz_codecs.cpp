// SPDX-License-Identifier: MIT
// Every value codec's parse on arbitrary input, and make(parse(x)) == x where parse succeeds.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "hil/profiles/bcd.hpp"
#include "hil/profiles/bit_field.hpp"
#include "hil/profiles/decimal_text.hpp"
#include "hil/profiles/fixed_point.hpp"
#include "hil/profiles/twos_complement.hpp"

namespace hp = hil::profiles;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::uint8_t sel = data[0];
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  std::uint64_t word = 0;
  std::memcpy(&word, data + 1, std::min<std::size_t>(8, size - 1));
  // decimal text fields
  static const char* formats[] = {"+6.3", "4.5", "5", "+5.3", "2.2", "1.3", "+3", "1"};
  const auto f = *hp::DecimalTextFormat::parse(formats[sel % 8]);
  if (auto d = hp::parse_decimal_text(text, f)) {
    auto t = hp::make_decimal_text(*d, f);
    if (!t) {
      std::fprintf(stderr, "make failed for [%.*s] units=%lld scale=%d: %s\n", static_cast<int>(text.size()),
                   text.data(), static_cast<long long>(d->units), d->scale, t.error().message.c_str());
      std::abort();
    }
    auto back = hp::parse_decimal_text(*t, f);
    if (!back || *back != *d) std::abort();
  }
  if (auto d = hp::parse_decimal(text)) (void)d->to_string();
  (void)hp::DecimalTextFormat::parse(text);
  // BCD
  for (auto sign : {hp::BcdSign::none, hp::BcdSign::bit31, hp::BcdSign::nibble}) {
    const hp::BcdFormat bf{1 + sel % 8, sign};
    if (auto v = hp::parse_bcd(static_cast<std::uint32_t>(word), bf)) {
      auto w = hp::make_bcd(*v, bf);
      if (!w) std::abort();
      if (*v != 0 && *w != static_cast<std::uint32_t>(word)) {
        std::fprintf(stderr, "bcd %08X -> %lld -> %08X (digits %d sign %d)\n", static_cast<unsigned>(word),
                     static_cast<long long>(*v), *w, bf.digits, static_cast<int>(sign));
        std::abort();
      }
    }
  }
  // two's complement
  const int bits = (sel % 4 == 0) ? 8 : (sel % 4 == 1) ? 16 : (sel % 4 == 2) ? 32 : 64;
  if (auto v = hp::parse_twos_complement(word, {bits, true})) {
    auto w = hp::make_twos_complement(*v, {bits, true});
    if (!w || *w != word) std::abort();
  }
  // bit fields
  const hp::BitFieldFormat bff{16, {{"a", 0, 1, ""}, {"b", 1, 3, ""}, {"c", 8, 4, ""}}, (sel & 0x10) != 0};
  if (auto b = hp::parse_bit_field(word & 0xFFFFFu, bff)) (void)hp::bit_field_text(*b, bff);
  if (auto b = hp::parse_bit_field_text(text, bff)) (void)hp::make_bit_field(*b, bff);
  // fixed point
  if (auto fp = hp::FixedPointFormat::parse_lsb(text, {16, true})) (void)hp::parse_fixed_point(1, *fp);
  const auto q8 = *hp::FixedPointFormat::parse_lsb("1/256", {16, true});
  if (auto v = hp::parse_fixed_point(static_cast<std::int16_t>(word), q8)) {
    auto raw = hp::make_fixed_point(*v, q8);
    if (!raw || *raw != static_cast<std::int16_t>(word)) std::abort();
  }
  return 0;
}
