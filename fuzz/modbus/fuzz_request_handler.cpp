// SPDX-License-Identifier: MIT
// Fuzz the server's request processing: a byte stream (one or more request ADUs, possibly
// garbage) is framed with check_frame() exactly as a server connection does, each complete ADU
// goes through the simulated drive device (check_request, libmodbus' modbus_reply, the state
// machine), and every response must be a well-formed ADU that echoes the request's transaction
// and unit id. Each ADU is also served by the simulated I/O terminal (coils and discrete inputs:
// FC 1, 2, 5, 15 through the same checks and modbus_reply()).
#include <cstdint>
#include <cstdlib>
#include <span>

#include "hil/mocks/modbus_drive_device.hpp"
#include "hil/mocks/modbus_io_terminal.hpp"
#include "hil/modbus/adu.hpp"
#include "hil/modbus/profile.hpp"
#include "hil/modbus/request_handler.hpp"

namespace {

hil::mocks::DriveDevice& device() {
  static hil::mocks::DriveDevice d = [] {
    auto p = hil::modbus::load_profile(HIL_MODBUS_PROFILE_DIR "/cia402.yaml");
    if (!p) std::abort();
    return hil::mocks::DriveDevice(*p);
  }();
  return d;
}

hil::mocks::IoTerminal& terminal() {
  static hil::mocks::IoTerminal t{hil::mocks::IoTerminalConfig{.coils = 40, .discrete_inputs = 24}};
  return t;
}

void require(bool ok) {
  if (!ok) std::abort();
}

// A response to `request` (framed as `f`) must be a well-formed ADU echoing TID, unit and function.
void check_response(std::span<const std::uint8_t> request, const hil::modbus::FrameCheck& f,
                    const hil::modbus::HandleResult& r, const std::uint8_t* out) {
  using namespace hil::modbus;
  require(r.size >= kMbapSize + 2 && r.size <= kMaxAduSize);
  const FrameCheck rf = check_frame(std::span<const std::uint8_t>(out, r.size));
  require(rf.status == FrameStatus::complete && rf.size == r.size);
  require(rf.header.transaction_id == f.header.transaction_id && rf.header.unit_id == f.header.unit_id);
  const std::uint8_t fc = request[kMbapSize];
  require(out[kMbapSize] == fc || out[kMbapSize] == (fc | 0x80));
  if (out[kMbapSize] & 0x80) require(r.size == kMbapSize + 2 && is_exception_code(out[kMbapSize + 1]));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hil::modbus;
  auto& dev = device();
  HandlerOptions options;
  options.strict_unit = size > 0 && (data[0] & 1);
  std::uint8_t out[kMaxAduSize];
  std::span<const std::uint8_t> rest(data, size);
  while (!rest.empty()) {
    const FrameCheck f = check_frame(rest);
    if (f.status != FrameStatus::complete) break;  // need_more or a bad header: the server stops here
    require(f.size >= kMbapSize + 1 && f.size <= kMaxAduSize && f.size <= rest.size());
    const auto r = dev.handle(rest.first(f.size), out, options);
    check_response(rest, f, r, out);
    const auto t = terminal().handle(rest.first(f.size), out, options);
    check_response(rest, f, t, out);
    require(t.written_count == 0 && t.coils_written_first + std::uint32_t{t.coils_written_count} <= 40);
    rest = rest.subspan(f.size);
  }
  dev.step(std::chrono::milliseconds(1));
  return 0;
}
