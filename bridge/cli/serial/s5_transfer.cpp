// SPDX-License-Identifier: MIT
// hilbridge upload/download ip247|wf725: data-block images over 3964R + RK512.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <fstream>
#include <sstream>

#include "hil/cli/progress.hpp"
#include "hil/core/text_file.hpp"
#include "hil/serial/item_transfer.hpp"
#include "hil/serial/profile_checks.hpp"
#include "hil/serial/s5/db_listing.hpp"
#include "hil/serial/s5/rk512_client.hpp"
#include "transfer.hpp"

namespace hil::cli::serial_cli {

namespace s5 = hil::serial::s5;

namespace {

s5::Rk512ClientOptions rk512_client_options(const LinkOptions& l) {
  s5::Rk512ClientOptions c;
  c.procedure.transmit_attempts = l.retries + 1;
  c.procedure.connect_attempts = l.retries + 1;
  c.reaction_timeout = std::max<Duration>(l.timeout, std::chrono::seconds(1));
  return c;
}

std::expected<s5::DbImage, std::string> fetch_image(s5::Rk512Client& c, const std::string& device, std::uint8_t db) {
  std::uint16_t length = 100;  // WF data code 1: 50 MD x 2 words
  if (device == "ip247") {
    auto head = c.fetch_db(db, 0, 1);
    if (!head) return std::unexpected(fmt::format("DB{}: {}", db, head.error().message));
    length = (*head)[0];
    if (length == 0 || length > 512)
      return std::unexpected(fmt::format("DB{}: length word {} is not a valid image length", db, length));
  }
  std::vector<std::uint16_t> words;
  // FETCH in chunks the data word byte can address (DW 0..255).
  for (std::uint16_t start = 0; start < length;) {
    if (start > 255) return std::unexpected(fmt::format("DB{}: images beyond DW 255 cannot be addressed by RK512", db));
    const auto n = static_cast<std::uint16_t>(std::min<int>(length - start, 64));
    auto part = c.fetch_db(db, static_cast<std::uint8_t>(start), n);
    if (!part) return std::unexpected(fmt::format("DB{} DW{}: {}", db, start, part.error().message));
    words.insert(words.end(), part->begin(), part->end());
    start = static_cast<std::uint16_t>(start + n);
  }
  return s5::DbImage{db, words};
}

}  // namespace

int s5_read(const TransferOptions& o) {
  std::vector<int> dbs = o.blocks;
  if (dbs.empty()) {
    if (o.device == "wf725")
      dbs = {1};
    else {
      fmt::print(stderr, "error: give the DB numbers to read with --db (e.g. --db 10,11)\n");
      return 2;
    }
  }
  for (int d : dbs)
    if (d < 0 || d > 255) {
      fmt::print(stderr, "error: --db {}: DB numbers are 0..255\n", d);
      return 2;
    }
  SteadyClock clock;
  auto link = open_link(o.link, clock);
  if (!link) {
    fmt::print(stderr, "error: {}\n", link.error());
    return 1;
  }
  s5::Rk512Client client(**link, clock, rk512_client_options(o.link));
  ProgressBar bar(fmt::format("upload {}", o.device), dbs.size(), "DBs", clock);
  std::vector<s5::DbImage> images;
  for (std::size_t i = 0; i < dbs.size(); ++i) {
    auto img = fetch_image(client, o.device, static_cast<std::uint8_t>(dbs[i]));
    if (!img) {
      bar.finish("failed");
      fmt::print(stderr, "error: {}\n{} was not written.\n", img.error(), o.file);
      return 1;
    }
    images.push_back(*img);
    bar.update(i + 1);
  }
  bar.finish("done");
  const std::string text = s5::make_db_listing(
      images, fmt::format("hilbridge {} data blocks (S5 DB images, one data word per line)", o.device));
  auto w = hil::serial::write_with_backup(o.file, text);
  if (!w) {
    fmt::print(stderr, "error: writing {}: {}\n", o.file, w.error().message());
    return 1;
  }
  fmt::print("{}: {} DB(s) written{}\n", o.file, images.size(),
             w->empty() ? std::string{} : fmt::format(" (previous content kept as {})", w->string()));
  return 0;
}

int s5_send(const TransferOptions& o) {
  const auto input = read_text_file(o.file);
  if (!input) {
    fmt::print(stderr, "error: {}\nNothing was sent.\n", input.error());
    return 2;
  }
  const std::string& text = *input;
  auto images = s5::parse_db_listing(text, o.file);
  if (!images) {
    for (const auto& p : images.error()) fmt::print(stderr, "{}\n", p);
    fmt::print(stderr, "error: nothing was sent.\n");
    return 2;
  }
  if (!o.blocks.empty()) {
    // Every DB asked for must be in the file: sending less than asked is no success.
    std::vector<std::string> missing;
    for (const auto b : o.blocks)
      if (std::none_of(images->begin(), images->end(), [&](const s5::DbImage& d) { return d.db == b; }))
        missing.push_back(fmt::format("DB{}", b));
    if (!missing.empty()) {
      fmt::print(stderr, "error: --db: {} not in {}; nothing was sent.\n", fmt::join(missing, ", "), o.file);
      return 2;
    }
    std::erase_if(*images, [&](const s5::DbImage& d) {
      return std::find(o.blocks.begin(), o.blocks.end(), d.db) == o.blocks.end();
    });
  }
  if (images->empty()) {
    fmt::print(stderr, "error: {} holds no data block; nothing was sent.\n", o.file);
    return 2;
  }
  // Validate every image against the profile before anything is sent.
  std::vector<std::string> problems;
  if (o.device == "ip247") {
    auto check = hil::serial::load_ip247_check();
    if (!check) {
      fmt::print(stderr, "error: device profile ip247: {}\n", check.error());
      return 2;
    }
    for (const auto& img : *images) {
      if (img.words.size() < 5 || img.words[0] != img.words.size() || img.words[1] != 0x0044 ||
          (img.words[2] >> 8) != 'B' || (img.words[2] & 0xFF) != img.db) {
        problems.push_back(
            fmt::format("{}: DB{}: header words must be <length in words>, 0044, 42<db number>", o.file, img.db));
        continue;
      }
      if (img.words[0] == 70)
        for (const auto& p : (*check)(img.words)) problems.push_back(fmt::format("{}: DB{}: {}", o.file, img.db, p));
    }
  } else {
    auto check = hil::serial::load_wf725_check();
    if (!check) {
      fmt::print(stderr, "error: device profile wf725: {}\n", check.error());
      return 2;
    }
    for (const auto& img : *images) {
      if (img.db != 1 || img.words.size() != 100) {
        problems.push_back(
            fmt::format("{}: DB{}: the WF machine data are data code 1 with 100 words (MD1..MD50)", o.file, img.db));
        continue;
      }
      for (const auto& why : (*check)(img.words)) problems.push_back(fmt::format("{}: {}", o.file, why));
    }
  }
  if (!problems.empty()) {
    for (const auto& p : problems) fmt::print(stderr, "{}\n", p);
    fmt::print(stderr, "error: {} problem(s); nothing was sent.\n", problems.size());
    return 2;
  }
  hil::serial::ResumeJournal journal{fmt::format("{} on {}", o.device, o.link.port), hil::serial::content_hash(text),
                                     0};
  if (o.resume) {
    if (auto j = hil::serial::ResumeJournal::load(o.file); j && (j->hash == journal.hash || o.force))
      journal.next = j->next;
  }
  SteadyClock clock;
  auto link = open_link(o.link, clock);
  if (!link) {
    fmt::print(stderr, "error: {}\nNothing was sent.\n", link.error());
    return 1;
  }
  s5::Rk512Client client(**link, clock, rk512_client_options(o.link));
  install_interrupt_handler();
  ProgressBar bar(fmt::format("download {}", o.file), images->size(), "DBs", clock);
  std::vector<std::string> done;
  for (std::size_t i = journal.next; i < images->size(); ++i) {
    const auto& img = (*images)[i];
    if (interrupted()) break;
    auto r = client.send_db(img.db, 0, img.words);
    if (!r && r.error().code == s5::Rk512Error::db_exists && o.replace) {
      auto del = client.send_db(img.db, 0, {0x0000});
      if (del)
        r = client.send_db(img.db, 0, img.words);
      else
        r = std::unexpected(del.error());
    }
    if (!r) {
      bar.finish("failed");
      (void)journal.save(o.file);
      fmt::print(stderr, "download of {} stopped at DB{}: {}\n", o.file, img.db, r.error().message);
      if (r.error().code == s5::Rk512Error::db_exists)
        fmt::print(stderr, "The IP247 has no overwrite: add --replace to delete DB{} first.\n", img.db);
      fmt::print(stderr, "Confirmed by the module: {}. DB{} {}. Resume with --resume.\n",
                 done.empty() ? std::string("nothing") : fmt::format("{}", fmt::join(done, ", ")), img.db,
                 r.error().code.category() == s5::rk512_category() ? "was refused and is not stored"
                                                                   : "may or may not be stored");
      return 1;
    }
    done.push_back(fmt::format("DB{}", img.db));
    journal.next = i + 1;
    (void)journal.save(o.file);
    bar.update(i + 1);
  }
  if (journal.next < images->size()) {
    bar.finish("interrupted");
    fmt::print(stderr, "interrupted: {} of {} DBs confirmed ({}); resume with --resume\n", journal.next, images->size(),
               fmt::join(done, ", "));
    return 1;
  }
  bar.finish("done");
  hil::serial::ResumeJournal::remove(o.file);
  if (!o.verify) return 0;
  int diffs = 0;
  for (const auto& img : *images) {
    auto back = fetch_image(client, o.device, img.db);
    if (!back) {
      fmt::print(stderr, "error: read-back: {}\n", back.error());
      return 1;
    }
    for (std::size_t w = 0; w < std::max(img.words.size(), back->words.size()); ++w) {
      const auto a = w < img.words.size() ? fmt::format("{:04X}", img.words[w]) : std::string("-");
      const auto b = w < back->words.size() ? fmt::format("{:04X}", back->words[w]) : std::string("-");
      if (a != b) {
        ++diffs;
        fmt::print(stderr, "differs DB{} DW{}: file {} device {}\n", img.db, w, a, b);
      }
    }
  }
  if (diffs > 0) {
    fmt::print(stderr, "error: {} data word(s) differ after download\n", diffs);
    return 1;
  }
  fmt::print("verified: the module holds exactly {}\n", o.file);
  return 0;
}

}  // namespace hil::cli::serial_cli
