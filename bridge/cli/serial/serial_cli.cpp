// SPDX-License-Identifier: MIT
// CLI module `serial`: download / upload of programs and parameter sets of legacy controllers
// over V.24 / 20 mA lines, and their emulators (`hilbridge emulate clm14|elg-tape|ip247|wf725`).
#include <fmt/format.h>

#include "emulate.hpp"
#include "hil/cli/context.hpp"
#include "transfer.hpp"

namespace hil::cli {

namespace serial_cli {
void register_emulators(Context& ctx);  // emulate_devices.cpp

int run_download(const TransferOptions& o) {
  if (o.device == "clm14") return clm14_download(o);
  if (o.device == "elg") return elg_download(o);
  if (o.device == "ip247" || o.device == "wf725") return s5_download(o);
  fmt::print(stderr, "error: unknown device '{}': use clm14, elg, ip247 or wf725\n", o.device);
  return 2;
}

int run_upload(const TransferOptions& o) {
  if (o.device == "clm14") return clm14_upload(o);
  if (o.device == "elg") return elg_upload(o);
  if (o.device == "ip247" || o.device == "wf725") return s5_upload(o);
  fmt::print(stderr, "error: unknown device '{}': use clm14, elg, ip247 or wf725\n", o.device);
  return 2;
}
}  // namespace serial_cli

void register_serial(Context& ctx) {
  using serial_cli::TransferOptions;
  static const char* devices_help =
      "Device: clm14 (Rexroth CLM1.4 ASCII protocol), elg (SINUMERIK ELG machine/setting-data tapes), "
      "ip247 (SIMATIC S5 IP247 data blocks over 3964R/RK512), wf725 (WF 725/726 data codes over 3964R/RK512)";

  auto down_opts = std::make_shared<TransferOptions>();
  auto* down = ctx.app.add_subcommand("download",
                                      "Read a program or parameter set from a legacy controller over a serial line "
                                      "into a text file in the device's own "
                                      "format. An existing OUT is kept as OUT.bak before it is replaced.");
  down->add_option("DEVICE", down_opts->device, devices_help)
      ->required()
      ->check(CLI::IsMember({"clm14", "elg", "ip247", "wf725"}));
  down->add_option("OUT", down_opts->file, "File to write")->required();
  serial_cli::add_link_options(*down, down_opts->link, true);
  down->add_option(
      "--what,-w", down_opts->what,
      "clm14: program (3000 lines, trailing NOPs dropped) or parameters; ip247: md or program; elg: md, sd "
      "or both (default)");
  down->add_option("--axes", down_opts->axes, "clm14: axes whose A-parameters are read (B000 enables them)")
      ->check(CLI::Range(1, 4))
      ->capture_default_str();
  down->add_option("--db", down_opts->blocks, "ip247: DB numbers to read; wf725: data codes")->delimiter(',');
  down->footer(
      "Examples:\n"
      "  hilbridge download clm14 --port /dev/ttyUSB0 --baud 9600 --format 7E2 --what parameters clm.par\n"
      "  hilbridge download clm14 --port /dev/ttyUSB0 --station 5 --what program line5.prg\n"
      "  hilbridge download elg --port /dev/ttyS0 --baud 4800 --format 8N2 --flow xonxoff --xoff 0x93 elg.tape\n"
      "  hilbridge download ip247 --port /dev/ttyUSB1 --baud 9600 --format 8E1 --db 10 md10.s5db");
  down->callback([&ctx, down_opts] { ctx.exit_code = serial_cli::run_download(*down_opts); });

  auto up_opts = std::make_shared<TransferOptions>();
  auto* up = ctx.app.add_subcommand(
      "upload",
      "Send a program or parameter set from a text file to a legacy controller. The whole file is validated against "
      "the "
      "device profile first (an invalid file sends nothing), every item must be confirmed, the result is read back and "
      "every differing item is listed. An interrupted upload reports exactly what reached the device and can be "
      "resumed.");
  up->add_option("DEVICE", up_opts->device, devices_help)
      ->required()
      ->check(CLI::IsMember({"clm14", "elg", "ip247", "wf725"}));
  up->add_option("IN", up_opts->file, "File to send (as written by `hilbridge download`)")
      ->required()
      ->check(CLI::ExistingFile);
  serial_cli::add_link_options(*up, up_opts->link, true);
  up->add_option("--what,-w", up_opts->what, "clm14: program or parameters (default: from the file's header comment)");
  up->add_option("--axes", up_opts->axes, "clm14: axes the parameter file may address")
      ->check(CLI::Range(1, 4))
      ->capture_default_str();
  up->add_option("--db", up_opts->blocks, "ip247/wf725: DB numbers / data codes to send (default: all in the file)")
      ->delimiter(',');
  up->add_flag("--resume", up_opts->resume, "Continue an interrupted upload of the same file where it stopped");
  up->add_flag("--force", up_opts->force,
               "With --resume: continue even though the file changed since the interruption");
  up->add_flag("!--no-verify", up_opts->verify, "Skip the read-back verification");
  up->add_flag("--replace", up_opts->replace,
               "ip247: delete a DB that exists on the module before writing it (no overwrite mode)");
  up->footer(
      "Examples:\n"
      "  hilbridge upload clm14 --port /dev/ttyUSB0 --format 7E2 clm.par      (CLM in Parameter mode)\n"
      "  hilbridge upload clm14 --port /dev/ttyUSB0 --resume line5.prg\n"
      "Exit codes: 0 done and verified, 1 line/device error (the report says what reached the device), 2 invalid "
      "input.");
  up->callback([&ctx, up_opts] { ctx.exit_code = serial_cli::run_upload(*up_opts); });

  serial_cli::register_emulators(ctx);
}

}  // namespace hil::cli
