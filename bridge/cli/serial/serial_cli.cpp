// SPDX-License-Identifier: MIT
// CLI module `serial`: upload (device -> file) and download (file -> device) of programs and
// parameter sets of legacy controllers over V.24 / 20 mA lines, in the terms of CiA 301 and STEP 7
// (docs/cli.md, "Transfer verbs"), and their emulators (`hilbridge emulate clm14|elg-tape|ip247|wf725`).
//
// Before issue 11 the two verbs meant the opposite. So that an old script can never write a device
// by accident: `upload` takes its file only as `--out FILE` and refuses a positional file (an old
// `upload DEVICE FILE` meant "send FILE"); `download DEVICE FILE` refuses a FILE that does not exist
// (an old `download` created it) and sends only after a confirmation, `--yes` or `y` typed on a
// terminal (an old `download DEVICE FILE` over an existing backup meant "read into FILE").
#include <unistd.h>

#include <filesystem>
#include <iostream>

#include <fmt/format.h>

#include "emulate.hpp"
#include "hil/cli/context.hpp"
#include "transfer.hpp"

namespace hil::cli {

namespace serial_cli {
void register_emulators(Context& ctx);  // emulate_devices.cpp

namespace {

constexpr const char* k_swap_note =
    "note: since issue 11 the verbs follow CiA 301 and STEP 7 (docs/cli.md): `upload` reads from the device into "
    "a file (`hilbridge upload DEVICE --out FILE`), `download` sends a file to the device (`hilbridge download "
    "DEVICE FILE --yes`); before, they meant the opposite.";

/// Old scripts' spellings that the new `upload` refuses (see the file comment).
struct OldUploadSpelling {
  std::string file;  ///< a positional file: an old `upload DEVICE FILE` meant "send FILE"
  bool resume = false;
  bool force = false;
  bool no_verify = false;
  bool replace = false;
};

/// The send confirmation: --yes, or `y`/`yes` typed on a terminal. Prints why when refused.
bool confirmed(const TransferOptions& o) {
  if (o.yes) return true;
  if (isatty(STDIN_FILENO) == 0) {
    fmt::print(stderr,
               "hilbridge download: not sent: `download` writes {} to the {} on {} and needs --yes when not asked "
               "on a terminal.\n{}\n",
               o.file, o.device, o.link.port, k_swap_note);
    return false;
  }
  fmt::print(stderr, "{}\nSend {} to the {} on {} (this writes the device)? [y/N] ", k_swap_note, o.file, o.device,
             o.link.port);
  std::string answer;
  if (!std::getline(std::cin, answer)) answer.clear();
  if (answer == "y" || answer == "Y" || answer == "yes") return true;
  fmt::print(stderr, "hilbridge download: not confirmed; nothing was sent.\n");
  return false;
}

}  // namespace

int run_upload(const TransferOptions& o) {
  if (o.device == "clm14") return clm14_read(o);
  if (o.device == "elg") return elg_read(o);
  if (o.device == "ip247" || o.device == "wf725") return s5_read(o);
  fmt::print(stderr, "error: unknown device '{}': use clm14, elg, ip247 or wf725\n", o.device);
  return 2;
}

int run_download(const TransferOptions& o) {
  std::error_code ec;
  if (!std::filesystem::exists(o.file, ec)) {  // what is not a regular file is refused when it is read
    fmt::print(stderr,
               "hilbridge download: {} does not exist; nothing was sent.\n{}\nTo read the {} "
               "into {} write: hilbridge upload {} --port ... --out {}\n",
               o.file, k_swap_note, o.device, o.file, o.device, o.file);
    return 2;
  }
  if (!confirmed(o)) return 2;
  if (o.device == "clm14") return clm14_send(o);
  if (o.device == "elg") return elg_send(o);
  if (o.device == "ip247" || o.device == "wf725") return s5_send(o);
  fmt::print(stderr, "error: unknown device '{}': use clm14, elg, ip247 or wf725\n", o.device);
  return 2;
}
}  // namespace serial_cli

void register_serial(Context& ctx) {
  using serial_cli::TransferOptions;
  static const char* devices_help =
      "Device: clm14 (Rexroth CLM1.4 ASCII protocol), elg (SINUMERIK ELG machine/setting-data tapes), "
      "ip247 (SIMATIC S5 IP247 data blocks over 3964R/RK512), wf725 (WF 725/726 data codes over 3964R/RK512)";

  auto up_opts = std::make_shared<TransferOptions>();
  auto old_up = std::make_shared<serial_cli::OldUploadSpelling>();
  auto* up = ctx.app.add_subcommand(
      "upload",
      "Read a program or parameter set from a legacy controller over a serial line into a text file (--out) in the "
      "device's own format (device -> file, as in CiA 301 and STEP 7). An existing file is kept as FILE.bak before "
      "it is replaced.");
  up->add_option("DEVICE", up_opts->device, devices_help)
      ->required()
      ->check(CLI::IsMember({"clm14", "elg", "ip247", "wf725"}));
  up->add_option("--out,-o", up_opts->file, "File to write");
  serial_cli::add_link_options(*up, up_opts->link, true);
  up->add_option("--what,-w", up_opts->what,
                 "clm14: program (3000 lines, trailing NOPs dropped) or parameters; ip247: md or program; elg: md, sd "
                 "or both (default)");
  up->add_option("--axes", up_opts->axes, "clm14: axes whose A-parameters are read (B000 enables them)")
      ->check(CLI::Range(1, 4))
      ->capture_default_str();
  // One value per --db (7,9 or --db 7 --db 9), so `--db 7 FILE` never takes FILE as a DB number.
  up->add_option("--db", up_opts->blocks, "ip247: DB numbers to read, e.g. 7,9; wf725: data codes")
      ->delimiter(',')
      ->allow_extra_args(false);
  // The old `upload` (file -> device) spellings, hidden: refused with the explanation below.
  up->add_option("FILE", old_up->file, "")->group("");
  up->add_flag("--resume", old_up->resume, "")->group("");
  up->add_flag("--force", old_up->force, "")->group("");
  up->add_flag("--no-verify", old_up->no_verify, "")->group("");
  up->add_flag("--replace", old_up->replace, "")->group("");
  up->footer(
      "Examples:\n"
      "  hilbridge upload clm14 --port /dev/ttyUSB0 --baud 9600 --format 7E2 --what parameters --out clm.par\n"
      "  hilbridge upload clm14 --port /dev/ttyUSB0 --station 5 --what program --out line5.prg\n"
      "  hilbridge upload elg --port /dev/ttyS0 --baud 4800 --format 8N2 --flow xonxoff --xoff 0x93 --out elg.tape\n"
      "  hilbridge upload ip247 --port /dev/ttyUSB1 --baud 9600 --format 8E1 --db 10 --out md10.s5db\n"
      "The file is given only with --out: before issue 11 `upload DEVICE FILE` sent FILE to the device, so a\n"
      "positional file is refused (docs/cli.md). Exit codes: 0 read and written, 1 line/device error, 2 usage.");
  up->callback([&ctx, up_opts, old_up] {
    if (!old_up->file.empty() || old_up->resume || old_up->force || old_up->no_verify || old_up->replace) {
      fmt::print(stderr,
                 "hilbridge upload: refused, nothing was read or sent: {}\n{}\nTo send {} to the device write: "
                 "hilbridge download {} ... {} --yes\n",
                 old_up->file.empty()
                     ? std::string("--resume/--force/--no-verify/--replace belong to `download`")
                     : fmt::format("a positional file ({}); upload writes only the --out file", old_up->file),
                 serial_cli::k_swap_note, old_up->file.empty() ? "a file" : old_up->file, up_opts->device,
                 old_up->file.empty() ? "FILE" : old_up->file);
      ctx.exit_code = 2;
      return;
    }
    if (up_opts->file.empty()) {
      fmt::print(stderr, "hilbridge upload: --out FILE is required: the file the device's data is written to\n{}\n",
                 serial_cli::k_swap_note);
      ctx.exit_code = 2;
      return;
    }
    ctx.exit_code = serial_cli::run_upload(*up_opts);
  });

  auto down_opts = std::make_shared<TransferOptions>();
  auto* down = ctx.app.add_subcommand(
      "download",
      "Send a program or parameter set from a text file to a legacy controller (file -> device, as in CiA 301 and "
      "STEP 7). The whole file is validated against the device profile first (an invalid file sends nothing), every "
      "item must be confirmed, the result is read back and every differing item is listed. An interrupted download "
      "reports exactly what reached the device and can be resumed. Sends only with --yes or when confirmed on a "
      "terminal.");
  down->add_option("DEVICE", down_opts->device, devices_help)
      ->required()
      ->check(CLI::IsMember({"clm14", "elg", "ip247", "wf725"}));
  down->add_option("FILE", down_opts->file, "File to send (as written by `hilbridge upload --out`); must exist")
      ->required();
  serial_cli::add_link_options(*down, down_opts->link, true);
  down->add_flag("--yes,-y", down_opts->yes,
                 "Send without asking (needed when stdin is not a terminal: scripts, CI); see docs/cli.md");
  down->add_option("--what,-w", down_opts->what,
                   "clm14: program or parameters (default: from the file's header comment)");
  down->add_option("--axes", down_opts->axes, "clm14: axes the parameter file may address")
      ->check(CLI::Range(1, 4))
      ->capture_default_str();
  down->add_option("--db", down_opts->blocks,
                   "ip247/wf725: DB numbers / data codes to send, e.g. 7,9 (default: all in the file)")
      ->delimiter(',')
      ->allow_extra_args(false);
  down->add_flag("--resume", down_opts->resume, "Continue an interrupted download of the same file where it stopped");
  down->add_flag("--force", down_opts->force,
                 "With --resume: continue even though the file changed since the interruption");
  down->add_flag("!--no-verify", down_opts->verify, "Skip the read-back verification");
  down->add_flag("--replace", down_opts->replace,
                 "ip247: delete a DB that exists on the module before writing it (no overwrite mode)");
  down->footer(
      "Examples:\n"
      "  hilbridge download clm14 --port /dev/ttyUSB0 --format 7E2 clm.par --yes     (CLM in Parameter mode)\n"
      "  hilbridge download clm14 --port /dev/ttyUSB0 --resume line5.prg --yes\n"
      "Before issue 11 `download DEVICE FILE` read the device into FILE: a FILE that does not exist is refused,\n"
      "and nothing is sent without --yes or a `y` typed on a terminal (docs/cli.md).\n"
      "Exit codes: 0 done and verified, 1 line/device error (the report says what reached the device), 2 invalid "
      "input, usage, or not confirmed.");
  down->callback([&ctx, down_opts] { ctx.exit_code = serial_cli::run_download(*down_opts); });

  serial_cli::register_emulators(ctx);
}

}  // namespace hil::cli
