// SPDX-License-Identifier: MIT
// S5 DB listings (user files) and CLM program/parameter files: never crash; round trips hold.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "hil/serial/clm14/files.hpp"
#include "hil/serial/s5/db_listing.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto dbs = hil::serial::s5::parse_db_listing(text, "fuzz");
  if (dbs) {
    auto again = hil::serial::s5::parse_db_listing(hil::serial::s5::make_db_listing(*dbs, "x"), "fuzz");
    if (!again || *again != *dbs) std::abort();
  }
  static auto dd = hil::serial::clm14::load_device_data();
  if (!dd) std::abort();
  for (auto kind : {hil::serial::clm14::FileKind::program, hil::serial::clm14::FileKind::parameters}) {
    auto f = hil::serial::clm14::parse_device_file(text, kind, **dd, 4, "fuzz");
    if (f) {
      auto again =
          hil::serial::clm14::parse_device_file(hil::serial::clm14::make_device_file(*f, "x"), kind, **dd, 4, "fuzz");
      if (!again || again->items != f->items) std::abort();
    }
  }
  return 0;
}
