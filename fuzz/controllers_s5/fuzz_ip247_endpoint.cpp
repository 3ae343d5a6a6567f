// SPDX-License-Identifier: MIT
// `hilbridge emulate ip247`'s RK512 request mapping (Ip247ModulePolicy): any sequence of SEND and
// FETCH jobs on DB 0..255 (MD and VP images) and DX 0..255 (axis DBs, the data-job block, the
// PLC's DBs), with the module's axes stepping in virtual time between them, never crashes and
// always answers with a valid RK512 reaction (rk512_requests.hpp). The module starts with a valid
// MD DB (axis 1) and a program, so the input also reaches commands, motion and the data jobs.
#include <chrono>

#include "hil/controllers/s5/ip247_machine_data.hpp"
#include "hil/controllers/s5/ip247_module_endpoint.hpp"
#include "hil/controllers/s5/ip247_program_db.hpp"
#include "rk512_requests.hpp"

using namespace hil::controllers::s5;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  hil::fuzz::Input in{{data, size}};
  Ip247ModuleOptions o;
  o.tile = (in.byte() & 3) * 4;
  o.switches[0].limit_end_at = 6'000;
  o.switches[1].cam = std::pair<std::int64_t, std::int64_t>{-200, 200};
  Ip247ModulePolicy policy(o);
  hil::mocks::legacy::DbStore store;
  Ip247MachineData md;
  md.limits_normally_closed = false;
  (void)policy.on_write(store, 1, 0, make_ip247_md_db(md));
  (void)policy.on_write(store, 10, 0,
                        *make_ip247_vp_db({.db = 10, .text = "%10\nN10 X50 F3000 M10\nN20 G04 F2\nN30 M02\n"}));
  hil::TimePoint now{};
  policy.on_time(now);
  hil::fuzz::run_requests(in, policy, store, [&](int ms) {
    now += std::chrono::milliseconds(ms);
    policy.on_time(now);
  });
  return 0;
}
