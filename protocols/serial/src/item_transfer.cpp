// SPDX-License-Identifier: MIT
#include "hil/serial/item_transfer.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "hil/core/text_file.hpp"

#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <fstream>
#include <sstream>

namespace hil::serial {

std::string SendReport::describe() const {
  std::string s;
  if (confirmed == 0) {
    s = "nothing confirmed by the device";
  } else {
    s = fmt::format("confirmed {}..{} ({} items)", confirmed_keys.front(), confirmed_keys.back(), confirmed);
  }
  if (start > 0) s += fmt::format(" after resuming at item {}", start);
  if (in_doubt) s += fmt::format("; {} was sent but not confirmed (it may or may not be stored)", *in_doubt);
  const std::size_t next = start + confirmed + (in_doubt ? 1 : 0);
  if (next < total) s += fmt::format("; {} item(s) not sent", total - next);
  if (cancelled) s += "; interrupted by the user";
  if (error) s += fmt::format("; stopped by: {}", error->message);
  return s;
}

SendReport send_items(ItemDevice& device, const std::vector<Item>& items, std::size_t start, const ProgressFn& progress,
                      const std::atomic<bool>* cancel, const std::function<void(std::size_t)>& on_confirmed) {
  SendReport r;
  r.total = items.size();
  r.start = std::min(start, items.size());
  for (std::size_t i = r.start; i < items.size(); ++i) {
    if (cancel != nullptr && cancel->load()) {
      r.cancelled = true;
      break;
    }
    auto w = device.write_item(items[i]);
    if (!w) {
      r.in_doubt = items[i].key;
      r.error = w.error();
      break;
    }
    ++r.confirmed;
    r.confirmed_keys.push_back(items[i].key);
    if (on_confirmed) on_confirmed(i);
    if (progress) progress(i + 1, items.size());
  }
  return r;
}

std::expected<std::vector<Item>, ItemError> read_items(ItemDevice& device, const std::vector<std::string>& keys,
                                                       const ProgressFn& progress, const std::atomic<bool>* cancel) {
  std::vector<Item> out;
  out.reserve(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (cancel != nullptr && cancel->load())
      return std::unexpected(
          ItemError{std::make_error_code(std::errc::operation_canceled),
                    fmt::format("interrupted after {} of {} items; nothing was written", i, keys.size())});
    auto t = device.read_item(keys[i]);
    if (!t) return std::unexpected(t.error());
    out.push_back(Item{keys[i], *t});
    if (progress) progress(i + 1, keys.size());
  }
  return out;
}

std::expected<std::vector<Difference>, ItemError> verify_items(ItemDevice& device, const std::vector<Item>& items,
                                                               const ProgressFn& progress) {
  std::vector<Difference> diffs;
  for (std::size_t i = 0; i < items.size(); ++i) {
    auto t = device.read_item(items[i].key);
    if (!t) return std::unexpected(t.error());
    if (device.normalise(items[i].key, *t) != device.normalise(items[i].key, items[i].text))
      diffs.push_back(Difference{items[i].key, items[i].text, *t});
    if (progress) progress(i + 1, items.size());
  }
  return diffs;
}

std::uint64_t content_hash(std::string_view text) noexcept {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (char c : text) {
    h ^= static_cast<std::uint8_t>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

namespace {

std::error_code last_error() {
  return {errno, std::system_category()};
}

/// Write all of `text` to `fd`, then flush it to the disk.
std::error_code write_all(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return last_error();
    done += static_cast<std::size_t>(n);
  }
  return ::fsync(fd) == 0 ? std::error_code{} : last_error();
}

}  // namespace

std::error_code write_atomically(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  // The target's mode is kept; a new file gets 0666 less the umask, as any new file does.
  struct stat st {};
  const bool existed = ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
  // A fresh name in the same folder (same file system, so the rename is atomic), created with
  // O_EXCL | O_NOFOLLOW: never a user's file, never through a symlink.
  static std::atomic<unsigned> counter{0};
  int fd = -1;
  std::filesystem::path tmp;
  for (int attempt = 0; fd < 0; ++attempt) {
    tmp = dir / fmt::format(".{}.{}-{}-{:x}.tmp", path.filename().string(), ::getpid(), counter++,
                            static_cast<unsigned>(std::chrono::steady_clock::now().time_since_epoch().count()));
    fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, existed ? 0600 : 0666);
    if (fd < 0 && (errno != EEXIST || attempt >= 100)) return last_error();
  }
  std::error_code ec;
  if (existed && ::fchmod(fd, st.st_mode & 07777) != 0) ec = last_error();
  if (!ec) ec = write_all(fd, text);
  if (::close(fd) != 0 && !ec) ec = last_error();
  if (!ec && ::rename(tmp.c_str(), path.c_str()) != 0) ec = last_error();
  if (ec) {
    ::unlink(tmp.c_str());
    return ec;
  }
  // The rename is durable once the folder is on the disk too.
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd < 0) return last_error();
  if (::fsync(dfd) != 0 && errno != EINVAL) ec = last_error();
  ::close(dfd);
  return ec;
}

std::filesystem::path ResumeJournal::path_for(const std::filesystem::path& file) {
  return file.string() + ".hilbridge-resume";
}

std::optional<ResumeJournal> ResumeJournal::load(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(path_for(file), ec)) return std::nullopt;
  const auto text = read_text_file(path_for(file), 64 * 1024);
  if (!text) return std::nullopt;
  return parse(*text);
}

std::string ResumeJournal::text() const {
  return fmt::format("hash {:016x}\nnext {}\ndevice {}\n", hash, next, device);
}

std::optional<ResumeJournal> ResumeJournal::parse(std::string_view text) {
  // Exactly the lines text() writes: "hash <16 hex digits>", "next <decimal>", "device <text>".
  // Anything else (truncated, edited, binary) is no journal: the send starts from the beginning.
  ResumeJournal j;
  bool hash = false, next = false, device = false;
  while (!text.empty()) {
    const auto eol = text.find('\n');
    if (eol == std::string_view::npos) return std::nullopt;  // every line ends with a newline
    const std::string_view line = text.substr(0, eol);
    text.remove_prefix(eol + 1);
    const auto sp = line.find(' ');
    if (sp == std::string_view::npos) return std::nullopt;
    const std::string_view key = line.substr(0, sp), value = line.substr(sp + 1);
    auto number = [&](int base, auto& out) {
      const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), out, base);
      return ec == std::errc{} && end == value.data() + value.size() && !value.empty();
    };
    if (key == "hash" && !hash && value.size() == 16 && number(16, j.hash)) {
      hash = true;
    } else if (key == "next" && !next && value.size() <= 9 && number(10, j.next)) {
      next = true;
    } else if (key == "device" && !device) {
      j.device = std::string(value);
      device = true;
    } else {
      return std::nullopt;
    }
  }
  if (!hash || !next || !device) return std::nullopt;
  return j;
}

std::error_code ResumeJournal::save(const std::filesystem::path& file) const {
  return write_atomically(path_for(file), text());
}

void ResumeJournal::remove(const std::filesystem::path& file) {
  std::error_code ec;
  std::filesystem::remove(path_for(file), ec);
}

std::expected<std::filesystem::path, std::error_code> write_with_backup(const std::filesystem::path& path,
                                                                        const std::string& text) {
  std::filesystem::path backup;
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    if (ss.str() != text) {
      backup = path.string() + ".bak";
      for (int i = 1; std::filesystem::exists(backup, ec); ++i) backup = fmt::format("{}.bak.{}", path.string(), i);
      std::filesystem::copy_file(path, backup, ec);
      if (ec) return std::unexpected(ec);
    }
  }
  if (auto w = write_atomically(path, text)) return std::unexpected(w);
  return backup;
}

}  // namespace hil::serial
