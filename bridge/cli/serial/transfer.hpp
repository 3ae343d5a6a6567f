// SPDX-License-Identifier: MIT
#pragma once
// `hilbridge upload` (device -> file) and `hilbridge download` (file -> device) per device; the
// verbs of CiA 301 and STEP 7 (docs/cli.md, "Transfer verbs").

#include <string>

#include "link_options.hpp"

namespace hil::cli::serial_cli {

struct TransferOptions {
  LinkOptions link;
  std::string device;       ///< clm14, elg, ip247, wf725
  std::string what;         ///< clm14: program | parameters; ip247: md | program; "" = from the file header
  std::string file;         ///< upload: the --out file written; download: the file sent
  int axes = 2;             ///< clm14 axes for parameter lists
  std::vector<int> blocks;  ///< ip247/wf725: DB numbers / data codes
  bool resume = false;
  bool yes = false;  ///< download: send without asking (the confirmation; docs/cli.md)
  bool verify = true;
  bool force = false;    ///< download even if the resume journal belongs to another file content
  bool replace = false;  ///< ip247: delete an existing DB before writing it (the module has no overwrite)
};

/// Return the process exit code (0 ok, 1 device/line error, 2 invalid input).
/// `upload`: read from the device into `file` (kept as file.bak before it is replaced).
int run_upload(const TransferOptions& o);
/// `download`: validate `file`, then send it to the device, confirm every item, read back.
int run_download(const TransferOptions& o);

int clm14_read(const TransferOptions& o);
int clm14_send(const TransferOptions& o);
int elg_read(const TransferOptions& o);
int elg_send(const TransferOptions& o);
int s5_read(const TransferOptions& o);
int s5_send(const TransferOptions& o);

}  // namespace hil::cli::serial_cli
