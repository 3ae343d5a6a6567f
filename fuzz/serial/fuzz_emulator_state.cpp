// SPDX-License-Identifier: MIT
// The emulators' state loader (the JSON state file of `hilbridge emulate clm14|elg-tape|ip247|
// wf725`, which a user may have edited or truncated): any bytes load or give an error text, never
// a crash or an escaping exception; a state that loads saves again, and what it saves loads to the
// same state (save -> load -> save is a fixed point).
#include <cstdint>
#include <cstdlib>
#include <string>

#include "hil/mocks/legacy/clm14_line.hpp"
#include "hil/mocks/legacy/elg_tape_endpoint.hpp"
#include "hil/mocks/legacy/s5_block_endpoint.hpp"
#include "hil/serial/profile_checks.hpp"

namespace {
template <class Endpoint, class Make>
void round_trip(const std::string& text, Make make) {
  Endpoint first = make();
  auto r = first.load_state(text);
  if (!r) {
    if (r.error().empty()) std::abort();  // an error says what is wrong
    return;
  }
  const std::string saved = first.save_state();
  Endpoint second = make();
  if (!second.load_state(saved)) std::abort();  // what we save, we load
  if (second.save_state() != saved) std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hil::mocks::legacy;
  static auto dd = hil::serial::clm14::load_device_data();
  static auto elg = hil::serial::load_elg_check();
  if (!dd || !elg) std::abort();
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  switch (data[0] % 4) {
    case 0:
      round_trip<Clm14Line>(text, [] { return Clm14Line(*dd, 2); });
      break;
    case 1:
      round_trip<ElgTapeEndpoint>(text, [] { return ElgTapeEndpoint(*elg); });
      break;
    case 2:
      round_trip<S5BlockEndpoint>(text, [] { return S5BlockEndpoint(make_ip247_policy({})); });
      break;
    default:
      round_trip<S5BlockEndpoint>(text, [] { return S5BlockEndpoint(make_wf725_policy({})); });
      break;
  }
  return 0;
}
