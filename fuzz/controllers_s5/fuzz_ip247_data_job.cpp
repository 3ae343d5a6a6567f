// SPDX-License-Identifier: MIT
// IP247 data jobs (Ip247Module::data_job): any sequence of FB165 jobs against PLC DBs whose words
// come from the input (seeded with a valid MD image and a valid VP image the input mutates) never
// crashes, never changes the length of a PLC DB, and keeps the module's limits: at most 255
// programs and 6000 chars of program memory, an MD DB number only on an axis with an image.
#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "hil/controllers/s5/ip247_machine_data.hpp"
#include "hil/controllers/s5/ip247_module.hpp"
#include "hil/controllers/s5/ip247_program_db.hpp"

using namespace hil::controllers::s5;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::size_t pos = 0;
  const auto byte = [&]() -> int { return pos < size ? data[pos++] : 0; };
  Ip247Module m(static_cast<int>(byte() & 0x3) * 4);
  S5Blocks plc;
  Ip247MachineData md;
  md.db = 10;
  plc[1] = make_ip247_md_db(md);
  plc[2] = *make_ip247_vp_db({.db = 5, .text = "%5\nN10 X100 F1000 M10\nN20 M02\n"});
  // Four more PLC DBs of input-given lengths (up to 300 words), then the input patches words.
  for (int db = 3; db <= 6; ++db)
    plc[db].assign(static_cast<std::size_t>(byte()) + static_cast<std::size_t>(byte() & 0x3F), 0);
  const int patches = byte();
  for (int i = 0; i < patches; ++i) {
    auto& w = plc[1 + byte() % 6];
    if (w.empty()) continue;
    const auto at = static_cast<std::size_t>(byte() | (byte() << 8)) % w.size();
    w[at] = static_cast<std::uint16_t>(byte() << 8 | byte());
  }
  std::array<std::size_t, 7> lengths{};
  for (int db = 1; db <= 6; ++db) lengths[static_cast<std::size_t>(db)] = plc[db].size();
  static constexpr std::array<int, 14> bas{20, 21, 22, 23, 24, 64, 65, 66, 67, 68, 69, 70, 8, 71};
  const int jobs = 1 + byte() % 24;
  for (int j = 0; j < jobs && pos < size; ++j) {
    Ip247DataJob job;
    job.ba = bas[static_cast<std::size_t>(byte()) % bas.size()];
    job.bcd = (byte() & 1) != 0;
    job.q_db = byte() % 8;
    job.q_start = byte();
    job.z_db = byte() % 8;
    job.z_start = byte() | ((byte() & 1) << 8);
    job.tile = byte() % 16;
    (void)m.data_job(job, plc);
    if ((byte() & 7) == 0)
      m.command(1 + byte() % 3, {.ba = 1 + byte() % 17, .command = Ip247Command::start, .byte_param = byte()});
    for (int db = 1; db <= 6; ++db)
      if (plc[db].size() != lengths[static_cast<std::size_t>(db)]) std::abort();
    if (plc.size() != 6) std::abort();  // a job never creates a PLC DB
    if (m.programs().used_chars() > ip247_memory_chars || m.programs().directory().size() > ip247_max_programs)
      std::abort();
    for (int n = 1; n <= ip247_axes; ++n)
      if ((m.md_db(n) >= 0) != (m.md_image(n) != nullptr)) std::abort();
  }
  return 0;
}
