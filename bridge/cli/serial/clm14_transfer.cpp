// SPDX-License-Identifier: MIT
// hilbridge upload/download clm14: programs and parameter sets over the CLM1.4 ASCII protocol.
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "hil/cli/progress.hpp"
#include "hil/core/text_file.hpp"
#include "hil/serial/clm14/client.hpp"
#include "hil/serial/clm14/files.hpp"
#include "hil/serial/clm14/item_devices.hpp"
#include "hil/serial/clm14/serial_error.hpp"
#include "hil/serial/item_transfer.hpp"
#include "transfer.hpp"

namespace hil::cli::serial_cli {

namespace clm = hil::serial::clm14;

namespace {

std::string header_for(clm::FileKind k, int axes) {
  return k == clm::FileKind::program
             ? "hilbridge clm14 program\nCLM1.4 NC program: one instruction per line, \"NNNN MNEMONIC operands\" "
               "(fixed field widths as the device lists them)"
             : fmt::format(
                   "hilbridge clm14 parameters ({} axes)\nCLM1.4 parameters: \"NUMBER data\" as in the K telegram",
                   axes);
}

std::expected<clm::FileKind, std::string> kind_of(const TransferOptions& o, std::string_view text) {
  if (!o.what.empty()) return clm::parse_file_kind(o.what);
  if (text.find("; hilbridge clm14 parameters") != std::string_view::npos) return clm::FileKind::parameters;
  if (text.find("; hilbridge clm14 program") != std::string_view::npos) return clm::FileKind::program;
  return std::unexpected(std::string("cannot tell program from parameters: give --what program|parameters"));
}

clm::ClientOptions clm14_client_options(const LinkOptions& l) {
  clm::ClientOptions c;
  c.station = l.station;
  c.response_timeout = l.timeout;
  c.retries = l.retries;
  return c;
}

}  // namespace

int clm14_read(const TransferOptions& o) {
  auto data = clm::load_device_data();
  if (!data) {
    fmt::print(stderr, "error: device profile clm14: {}\n", data.error());
    return 2;
  }
  auto kind = clm::parse_file_kind(o.what.empty() ? "program" : o.what);
  if (!kind) {
    fmt::print(stderr, "error: --what: {}\n", kind.error());
    return 2;
  }
  SteadyClock clock;
  auto link = open_link(o.link, clock);
  if (!link) {
    fmt::print(stderr, "error: {}\n", link.error());
    return 1;
  }
  clm::Client client(**link, clock, clm14_client_options(o.link), *data);
  std::vector<std::string> keys =
      *kind == clm::FileKind::program ? clm::ProgramDevice::all_keys() : (*data)->parameter_numbers(o.axes);
  clm::ProgramDevice prog(client);
  clm::ParameterDevice par(client);
  hil::serial::ItemDevice& dev = *kind == clm::FileKind::program ? static_cast<hil::serial::ItemDevice&>(prog) : par;
  install_interrupt_handler();
  ProgressBar bar(fmt::format("upload {}", *kind == clm::FileKind::program ? "program" : "parameters"), keys.size(),
                  *kind == clm::FileKind::program ? "lines" : "params", clock);
  auto items = hil::serial::read_items(
      dev, keys, [&](std::size_t d, std::size_t) { bar.update(d); }, &interrupted());
  if (!items) {
    bar.finish("failed");
    fmt::print(stderr, "error: {}\n{} was not written.\n", items.error().message, o.file);
    return 1;
  }
  bar.finish("done");
  clm::DeviceFile file{*kind, {}};
  if (*kind == clm::FileKind::program) {
    file = clm::program_from_items(*items);
  } else {
    for (auto& i : *items) file.items.push_back(clm::FileItem{i.key, i.text, 0});
  }
  const std::string text = clm::make_device_file(file, header_for(*kind, o.axes));
  auto w = hil::serial::write_with_backup(o.file, text);
  if (!w) {
    fmt::print(stderr, "error: writing {}: {}\n", o.file, w.error().message());
    return 1;
  }
  fmt::print("{}: {} {} written{}\n", o.file, file.items.size(),
             *kind == clm::FileKind::program ? "program lines" : "parameters",
             w->empty() ? std::string{} : fmt::format(" (previous content kept as {})", w->string()));
  return 0;
}

int clm14_send(const TransferOptions& o) {
  auto data = clm::load_device_data();
  if (!data) {
    fmt::print(stderr, "error: device profile clm14: {}\n", data.error());
    return 2;
  }
  const auto input = read_text_file(o.file);
  if (!input) {
    fmt::print(stderr, "error: {}\nNothing was sent.\n", input.error());
    return 2;
  }
  const std::string& text = *input;
  auto kind = kind_of(o, text);
  if (!kind) {
    fmt::print(stderr, "error: {}: {}\n", o.file, kind.error());
    return 2;
  }
  // Validate the whole file against the profile before anything is sent.
  auto file = clm::parse_device_file(text, *kind, **data, o.axes, o.file);
  if (!file) {
    for (const auto& p : file.error()) fmt::print(stderr, "{}\n", p);
    fmt::print(stderr, "error: {} problem(s) in {}; nothing was sent.\n", file.error().size(), o.file);
    return 2;
  }
  const auto items = clm::to_items(*file);
  hil::serial::ResumeJournal journal{
      fmt::format("clm14 {} on {} station {}", *kind == clm::FileKind::program ? "program" : "parameters", o.link.port,
                  o.link.station),
      hil::serial::content_hash(text), 0};
  if (o.resume) {
    if (auto j = hil::serial::ResumeJournal::load(o.file)) {
      if (j->hash != journal.hash && !o.force) {
        fmt::print(stderr,
                   "error: {} changed since the interrupted download; resume would mix two versions. Download from the "
                   "start (without --resume) or give --force.\n",
                   o.file);
        return 2;
      }
      journal.next = std::min(j->next, items.size());
      fmt::print("resuming at item {} of {} ({})\n", journal.next, items.size(), j->device);
    } else {
      fmt::print("no interrupted download of {} recorded; starting at the beginning\n", o.file);
    }
  }
  SteadyClock clock;
  auto link = open_link(o.link, clock);
  if (!link) {
    fmt::print(stderr, "error: {}\nNothing was sent.\n", link.error());
    return 1;
  }
  clm::Client client(**link, clock, clm14_client_options(o.link), *data);
  clm::ProgramDevice prog(client);
  clm::ParameterDevice par(client);
  hil::serial::ItemDevice& dev = *kind == clm::FileKind::program ? static_cast<hil::serial::ItemDevice&>(prog) : par;
  install_interrupt_handler();
  ProgressBar bar(fmt::format("download {}", o.file), items.size(), "items", clock);
  bar.update(journal.next);
  std::size_t since_save = 0;
  auto report = hil::serial::send_items(
      dev, items, journal.next, [&](std::size_t d, std::size_t) { bar.update(d); }, &interrupted(),
      [&](std::size_t idx) {
        journal.next = idx + 1;
        if (++since_save >= 25) {  // a crash loses at most 25 confirmed items of progress
          since_save = 0;
          (void)journal.save(o.file);
        }
      });
  if (!report.ok()) {
    bar.finish(report.cancelled ? "interrupted" : "failed");
    (void)journal.save(o.file);
    fmt::print(stderr, "download of {} incomplete: {}\n", o.file, report.describe());
    if (report.error && report.error->code == clm::SerialError::invalid_mode)
      fmt::print(stderr,
                 "The CLM accepts parameters only in Parameter mode: set input X3/1 (Parameter) and clear X3/2 (Auto), "
                 "or I2.00.0 over the fieldbus, then resume.\n");
    fmt::print(stderr, "Resume with the same command plus --resume.\n");
    return 1;
  }
  bar.finish("done");
  hil::serial::ResumeJournal::remove(o.file);
  fmt::print("{}: {} items confirmed by the device\n", o.file, report.total);
  if (!o.verify) return 0;
  ProgressBar vbar("verify", items.size(), "items", clock);
  auto diffs = hil::serial::verify_items(dev, items, [&](std::size_t d, std::size_t) { vbar.update(d); });
  if (!diffs) {
    vbar.finish("failed");
    fmt::print(stderr, "error: read-back failed: {}\n", diffs.error().message);
    return 1;
  }
  vbar.finish(diffs->empty() ? "identical" : "differences");
  for (const auto& d : *diffs) fmt::print(stderr, "differs {}: file '{}' device '{}'\n", d.key, d.expected, d.actual);
  if (!diffs->empty()) {
    fmt::print(stderr, "error: {} item(s) differ after download\n", diffs->size());
    return 1;
  }
  fmt::print("verified: the device holds exactly {}\n", o.file);
  return 0;
}

}  // namespace hil::cli::serial_cli
