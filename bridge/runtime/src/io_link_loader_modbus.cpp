// SPDX-License-Identifier: MIT
// The `modbus:` kind of an `io_links:` entry (docs/scenarios.md), loaded apart from the rest of
// the scenario loader.
#include <fmt/format.h>

#include "hil/modbus/bus_address.hpp"
#include "io_link_loader.hpp"

namespace hil::runtime::detail {

// `modbus: {bus, unit, poll, timeout, stale_after, listen, status}` (docs/scenarios.md).
ModbusLinkDevice load_modbus_device(const Field& m) {
  ModbusLinkDevice d;
  if (!m.node().IsMap())
    m.fail(fmt::format("expected a map {{bus: sim | \"tcp://HOST:PORT\", ...}}, got {}", m.describe()));
  m.expect_map({"bus", "unit", "poll", "timeout", "stale_after", "listen", "status"});
  if (auto b = m.child("bus"); b.present()) {
    d.bus = b.as_string("sim or tcp://HOST[:PORT]");
    if (auto parsed = modbus::parse_bus_address(d.bus); !parsed) b.fail(parsed.error());
  }
  const bool sim = d.bus == "sim";
  if (auto u = m.child("unit"); u.present()) {
    const double v = u.as_number("a unit id 0..255");
    if (v < 0 || v > 255 || v != static_cast<int>(v))
      u.fail(fmt::format("expected a unit id 0..255, got {}", u.describe()));
    d.unit = static_cast<int>(v);
  }
  const auto duration = [&](const char* key, Duration min, Duration max, Duration& out) {
    const Field f = m.child(key);
    if (!f.present()) return;
    out = f.as_duration();
    if (out < min || out > max)
      f.fail(fmt::format("expected {} .. {} ms, got {}", to_seconds(min) * 1e3, to_seconds(max) * 1e3, f.describe()));
  };
  duration("poll", std::chrono::milliseconds(1), std::chrono::seconds(10), d.poll);
  duration("timeout", std::chrono::milliseconds(1), std::chrono::seconds(10), d.timeout);
  if (m.child("stale_after").present()) {
    Duration st{};
    duration("stale_after", std::chrono::milliseconds(1), std::chrono::seconds(60), st);
    if (st < d.poll)
      m.child("stale_after")
          .fail(fmt::format("stale_after must be at least the poll period ({} ms): every input "
                            "would be stale between two polls",
                            to_seconds(d.poll) * 1e3));
    d.stale_after = st;
  }
  if (auto l = m.child("listen"); l.present()) {
    if (!sim) l.fail("'listen' serves the simulated terminal to peers: it needs 'bus: sim'");
    d.listen = l.as_string("HOST:PORT (port 0: any free port)");
    if (auto ep = modbus::parse_endpoint(d.listen, true, 502, true); !ep) l.fail(ep.error());
  }
  if (auto st = m.child("status"); st.present()) {
    d.status = st.as_string("a signal (an input bit) set to 1 while the terminal answers");
    d.status_source = {st.line(), st.path()};
  }
  return d;
}

// A Modbus bit: {discrete_input: N} or {coil: N} (0-based protocol addresses); outputs: coils.
ModbusLinkBit load_modbus_bit(const Field& f, bool input) {
  if (!f.node().IsMap())
    f.fail(fmt::format("expected {{{}: ADDRESS}} (0-based protocol address), got {}",
                       input ? "discrete_input | coil" : "coil", f.describe()));
  const auto keys = f.expect_map({"discrete_input", "coil"});
  if (keys.size() != 1) f.fail("give exactly one of 'discrete_input' or 'coil'");
  ModbusLinkBit b;
  b.coil = keys[0] == "coil";
  const Field a = f.child(keys[0]);
  if (!b.coil && !input) a.fail("a discrete input is read-only (function 02): outputs are written to coils");
  const double v = a.as_number("a 0-based protocol address 0..65535");
  if (v < 0 || v > 65535 || v != static_cast<double>(static_cast<long>(v)))
    a.fail(fmt::format("expected a 0-based protocol address 0..65535, got {}", a.describe()));
  b.address = static_cast<std::uint16_t>(v);
  return b;
}

}  // namespace hil::runtime::detail
