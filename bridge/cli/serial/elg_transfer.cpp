// SPDX-License-Identifier: MIT
// hilbridge upload/download elg: SINUMERIK ELG machine-data (%TEA1) and setting-data (%SEA) tapes.
#include <fmt/format.h>

#include <array>
#include <fstream>
#include <sstream>

#include "hil/cli/progress.hpp"
#include "hil/core/text_file.hpp"
#include "hil/serial/item_transfer.hpp"
#include "hil/serial/profile_checks.hpp"
#include "hil/serial/tape/elg_tape.hpp"
#include "transfer.hpp"

namespace hil::cli::serial_cli {

namespace tp = hil::serial::tape;

namespace {

/// Ask for one section (DC2 = Data Start, our convention) and read the tape until M02/M30.
std::expected<std::vector<tp::ElgSection>, std::string> read_section(hil::serial::ByteStream& s, const Clock& clock,
                                                                     Duration char_timeout, ProgressBar& bar) {
  const std::uint8_t dc2 = 0x12;
  if (auto ec = s.write(std::span(&dc2, 1), std::chrono::seconds(5)))
    return std::unexpected("sending Data Start: " + ec.message());
  tp::TapeReader reader(tp::TapeReaderOptions{.accept_eia = false});
  std::vector<std::string> blocks;
  std::vector<tp::TapeEvent> ev;
  std::array<std::uint8_t, 256> buf{};
  // The first character may take as long as the ELG's own time monitoring (60 s).
  TimePoint deadline = clock.now() + std::max<Duration>(char_timeout, std::chrono::seconds(60));
  std::uint64_t got = 0;
  while (!reader.finished()) {
    const TimePoint now = clock.now();
    if (now >= deadline) return std::unexpected("the ELG stopped sending before M02/M30 (V.24 time monitoring)");
    const auto r = s.read_some(buf, deadline - now);
    if (r.size > 0) {
      deadline = clock.now() + char_timeout;
      got += r.size;
      bar.update(got);
      ev.clear();
      reader.feed(std::span(buf.data(), r.size), ev);
      for (const auto& e : ev) {
        if (e.kind == tp::TapeEvent::Kind::block) blocks.push_back(e.text);
        if (e.kind == tp::TapeEvent::Kind::error)
          return std::unexpected(fmt::format("tape error at byte {}: {} ({})", e.offset, e.message, e.error.message()));
      }
    }
    if (r.error && r.error != hil::serial::LineError::timeout)
      return std::unexpected(fmt::format("line error while reading the tape: {}", r.error.message()));
  }
  auto sections = tp::parse_elg_blocks(blocks);
  if (!sections)
    return std::unexpected(fmt::format("tape content: {}: {}", sections.error().block, sections.error().message));
  return *sections;
}

std::expected<std::vector<tp::ElgSection>, std::string> read_device(hil::serial::ByteStream& s, const Clock& clock,
                                                                    const TransferOptions& o) {
  std::vector<tp::ElgSection> all;
  const bool want_sd = o.what.empty() || o.what == "both" || o.what == "sd";
  ProgressBar bar("upload elg tape", 0, "bytes", clock);
  // The ELG outputs MD on the first Data Start and SD on the second.
  auto md = read_section(s, clock, o.link.timeout, bar);
  if (!md) return std::unexpected(md.error());
  if (o.what.empty() || o.what == "both" || o.what == "md") all.insert(all.end(), md->begin(), md->end());
  if (want_sd) {
    auto sd = read_section(s, clock, o.link.timeout, bar);
    if (!sd) return std::unexpected(sd.error());
    all.insert(all.end(), sd->begin(), sd->end());
  }
  bar.finish("done");
  return all;
}

}  // namespace

int elg_read(const TransferOptions& o) {
  if (!o.what.empty() && o.what != "md" && o.what != "sd" && o.what != "both") {
    fmt::print(stderr, "error: --what for elg: md, sd or both\n");
    return 2;
  }
  SteadyClock clock;
  auto link = open_link(o.link, clock);
  if (!link) {
    fmt::print(stderr, "error: {}\n", link.error());
    return 1;
  }
  auto sections = read_device(**link, clock, o);
  if (!sections) {
    fmt::print(stderr, "error: {}\n{} was not written.\n", sections.error(), o.file);
    return 1;
  }
  const std::string text = "; hilbridge elg tape (SINUMERIK ELG machine data %TEA1 / setting data %SEA, ISO code)\n" +
                           tp::make_elg_text(*sections);
  auto w = hil::serial::write_with_backup(o.file, text);
  if (!w) {
    fmt::print(stderr, "error: writing {}: {}\n", o.file, w.error().message());
    return 1;
  }
  std::size_t n = 0;
  for (const auto& s : *sections) n += s.entries.size();
  fmt::print("{}: {} data in {} section(s) written{}\n", o.file, n, sections->size(),
             w->empty() ? std::string{} : fmt::format(" (previous content kept as {})", w->string()));
  return 0;
}

int elg_send(const TransferOptions& o) {
  const auto text = read_text_file(o.file);
  if (!text) {
    fmt::print(stderr, "error: {}\nNothing was sent.\n", text.error());
    return 2;
  }
  auto sections = tp::parse_elg_text(*text);
  if (!sections) {
    fmt::print(stderr, "{}: block '{}': {} ({})\nerror: nothing was sent.\n", o.file, sections.error().block,
               sections.error().message, sections.error().code.message());
    return 2;
  }
  auto check = hil::serial::load_elg_check();
  if (!check) {
    fmt::print(stderr, "error: device profile: {}\n", check.error());
    return 2;
  }
  std::vector<std::string> problems;
  for (const auto& s : *sections)
    for (const auto& e : s.entries)
      if (auto why = (*check)(s.kind, e.number, e.value))
        problems.push_back(fmt::format("{}: {} N{}={}: {}", o.file, tp::elg_header(s.kind), e.number, e.value, *why));
  if (!problems.empty()) {
    for (const auto& p : problems) fmt::print(stderr, "{}\n", p);
    fmt::print(stderr, "error: {} invalid datum/data; nothing was sent.\n", problems.size());
    return 2;
  }
  std::vector<std::string> blocks;
  for (const auto& s : *sections) {
    auto b = tp::make_elg_blocks(s);
    blocks.insert(blocks.end(), b.begin(), b.end());
  }
  auto tape = tp::make_tape(blocks, tp::TapeWriterOptions{});
  if (!tape) {
    fmt::print(stderr, "error: {}\n", tape.error());
    return 2;
  }
  SteadyClock clock;
  auto link = open_link(o.link, clock);
  if (!link) {
    fmt::print(stderr, "error: {}\nNothing was sent.\n", link.error());
    return 1;
  }
  install_interrupt_handler();
  ProgressBar bar(fmt::format("download {}", o.file), tape->size(), "bytes", clock);
  std::size_t pos = 0;
  while (pos < tape->size()) {
    if (interrupted()) break;
    const std::size_t n = std::min<std::size_t>(64, tape->size() - pos);
    // The ELG's time monitoring allows 60 s of XOFF.
    if (auto ec = (*link)->write(std::span(tape->data() + pos, n), std::chrono::seconds(60))) {
      bar.finish("failed");
      fmt::print(
          stderr,
          "download of {} stopped after {} of {} tape bytes: {}\nThe ELG takes over a tape only when it was read "
          "completely: its data are unchanged. Send the tape again.\n",
          o.file, pos, tape->size(), ec.message());
      return 1;
    }
    pos += n;
    bar.update(pos);
  }
  if (pos < tape->size()) {
    bar.finish("interrupted");
    fmt::print(stderr, "download interrupted after {} of {} tape bytes; the ELG discards an incomplete tape.\n", pos,
               tape->size());
    return 1;
  }
  bar.finish("done");
  if (!o.verify) return 0;
  auto back = read_device(**link, clock, TransferOptions{o.link, "elg", "both", o.file, 0, {}, false, true, false});
  if (!back) {
    fmt::print(stderr, "error: read-back failed: {}\n", back.error());
    return 1;
  }
  int diffs = 0;
  for (const auto& s : *sections) {
    for (const auto& e : s.entries) {
      std::optional<std::string> actual;
      for (const auto& b : *back)
        if (b.kind == s.kind)
          for (const auto& be : b.entries)
            if (be.number == e.number) actual = be.value;
      if (actual != e.value) {
        ++diffs;
        fmt::print(stderr, "differs {} N{}: file '{}' device '{}'\n", tp::elg_header(s.kind), e.number, e.value,
                   actual.value_or("<missing>"));
      }
    }
  }
  if (diffs > 0) {
    fmt::print(stderr, "error: {} datum/data differ after download (the ELG rejected the tape? check its alarm)\n",
               diffs);
    return 1;
  }
  fmt::print("verified: the ELG holds every datum of {}\n", o.file);
  return 0;
}

}  // namespace hil::cli::serial_cli
