// SPDX-License-Identifier: MIT
#pragma once
// The SF types hilbridge implements (docs/amkasyn.md lists what each covers). Each is a
// FastFunction; make_fast_function() (sf_runtime.hpp) builds them by type.

#include <array>
#include <cstdint>
#include <memory>

#include "hil/controllers/amkasyn/fast_function.hpp"
#include "hil/motion/gear.hpp"
#include "hil/motion/master.hpp"

namespace hil::controllers::amkasyn {

/// SF COPY (type 0): DCOPY (fct 1, BA 0 absolute / BA 1 incremental), ECOPY (fct 2),
/// SIDIFF (fct 255: following-error monitor of up to 8 drives).
std::unique_ptr<FastFunction> make_copy();
/// SF FIPW (type 1): function interpolator, BA 2/26/82/98 (distance) and 4/132/84/100 (time),
/// on hil::motion cam tables; without printing mark control and external sync (refused).
std::unique_ptr<FastFunction> make_fipw();
/// SF FIPZ (type 2): time interpolator, BA 16 (Ek starts Tab k-1) and 17 (E1 + E2..E4 select).
std::unique_ptr<FastFunction> make_fipz();
/// SF STDFKT (type 3): VARSYNC (fct 1: electronic gear, BA 0..3, SAK) and DIGDREH (fct 2).
std::unique_ptr<FastFunction> make_stdfkt();
/// SF DFKT (type 4): speed function tables.
std::unique_ptr<FastFunction> make_dfkt();
/// SF FGEN (type 5): reference input variable generator (continuous / sequence, internal /
/// external velocity, override, 2 accelerations, feedback zeroing, position monitoring).
std::unique_ptr<FastFunction> make_fgen();
/// SF REGL (type 6): PID controller with switches S1..S3, feed-forward, limits and external sync.
std::unique_ptr<FastFunction> make_regl();
/// SF IMES (type 7): pulse distance measurement on a counter's zero-pulse input.
std::unique_ptr<FastFunction> make_imes();
/// SF XFIPW (type 9): extended function interpolator (Y and XY tables, table set switch-over,
/// retriggering, working table cycles, setting on, READ VALUE); without printing mark control and
/// external sync (refused).
std::unique_ptr<FastFunction> make_xfipw();
/// SF APSF (type 10): a user AWL FB (the subset of awl.hpp) every SF cycle with the SF-PAE/PAA.
std::unique_ptr<FastFunction> make_apsf();
/// SF EPOS (type 11): extended positioning (relative, retrigger, modulo, substitutional on the
/// drive's reference latch), velocity and acceleration override, stop.
std::unique_ptr<FastFunction> make_epos();
/// SF BINEA (type 8): table-based cam controller.
std::unique_ptr<FastFunction> make_binea();
/// SF CAM (type 12): on/off cam controller (without hysteresis: START refuses H != 0).
std::unique_ptr<FastFunction> make_cam();

/// The SAK following-error compensation factor (digest §2.1): 7680000/ID2/ID104 + 128(1 + 1/ID2)
/// for an internal master (position feedback of another AW), + 256 for an external one (pulse
/// generator input). ID 2 in ms, ID 104 in rpm. Rounded down as the manual's examples are.
[[nodiscard]] int sak_factor(double id2_ms, double id104_rpm, bool external) noexcept;
/// The SAK lead applied to a set-point: out = y + SAK/128 x (y - y_prev) (SAK/128 cycles of
/// velocity lead; [inferred], digest §2.1), rounded half away from zero.
[[nodiscard]] std::int64_t sak_lead(std::int64_t y, std::int64_t y_prev, int sak) noexcept;
/// The drive (0..7) an SF's sink commands (SWQ1/SWQ2 of AW1..AW8), or -1.
[[nodiscard]] inline int sink_drive(const InitDb& init) noexcept {
  return init.sink.address >= 1 && init.sink.address <= 8 ? init.sink.address - 1 : -1;
}
/// sak_lead(), and the lead recorded on the commanded drive (DriveChannels::sak_part) for SIDIFF.
std::int64_t apply_sak(SfIo& io, int drive, std::int64_t y, std::int64_t y_prev, int sak) noexcept;

}  // namespace hil::controllers::amkasyn
