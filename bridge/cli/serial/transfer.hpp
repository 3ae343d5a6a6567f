// SPDX-License-Identifier: MIT
#pragma once
// download / upload command implementations per device.

#include <string>

#include "link_options.hpp"

namespace hil::cli::serial_cli {

struct TransferOptions {
  LinkOptions link;
  std::string device;       ///< clm14, elg, ip247, wf725
  std::string what;         ///< clm14: program | parameters; ip247: md | program; "" = from the file header
  std::string file;         ///< OUT (download) or IN (upload)
  int axes = 2;             ///< clm14 axes for parameter lists
  std::vector<int> blocks;  ///< ip247/wf725: DB numbers / data codes
  bool resume = false;
  bool verify = true;
  bool force = false;    ///< upload even if the resume journal belongs to another file content
  bool replace = false;  ///< ip247: delete an existing DB before writing it (the module has no overwrite)
};

/// Return the process exit code (0 ok, 1 device/line error, 2 invalid input).
int run_download(const TransferOptions& o);
int run_upload(const TransferOptions& o);

int clm14_download(const TransferOptions& o);
int clm14_upload(const TransferOptions& o);
int elg_download(const TransferOptions& o);
int elg_upload(const TransferOptions& o);
int s5_download(const TransferOptions& o);
int s5_upload(const TransferOptions& o);

}  // namespace hil::cli::serial_cli
