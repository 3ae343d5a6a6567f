// SPDX-License-Identifier: MIT
// CLI module `can`: CAN bus tools. `hilbridge can hub` serves an in-process virtual bus (or
// bridges a SocketCAN interface) over the socketcand protocol; dump/send/replay are the
// candump/cansend/canplayer of hilbridge and accept every bus URL.
#include "commands.hpp"

namespace hil::cli {

void register_can(Context& ctx) {
  auto* can = ctx.app.add_subcommand("can", "CAN bus tools: socketcand hub, dump (text/pcap), send, replay");
  can->require_subcommand(1);
  can->footer(
      "Bus URLs: vcan0 | can0 (SocketCAN), socketcand://HOST[:PORT]/BUS (default port 29536).\n"
      "Example without CAN hardware or kernel modules:\n"
      "  hilbridge can hub --listen 127.0.0.1:29536 &\n"
      "  hilbridge can dump --bus socketcand://127.0.0.1:29536/can0 --pcap can.pcap &\n"
      "  hilbridge can send --bus socketcand://127.0.0.1:29536/can0 123#DEADBEEF");
  can_cmd::add_hub(*can, ctx);
  can_cmd::add_dump(*can, ctx);
  can_cmd::add_send(*can, ctx);
  can_cmd::add_replay(*can, ctx);
}

}  // namespace hil::cli
