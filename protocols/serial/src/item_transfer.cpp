// SPDX-License-Identifier: MIT
#include "hil/serial/item_transfer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cerrno>
#include <fstream>
#include <sstream>

namespace hil::serial {

std::string UploadReport::describe() const {
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

UploadReport upload_items(ItemDevice& device, const std::vector<Item>& items, std::size_t start,
                          const ProgressFn& progress, const std::atomic<bool>* cancel,
                          const std::function<void(std::size_t)>& on_confirmed) {
  UploadReport r;
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

std::expected<std::vector<Item>, ItemError> download_items(ItemDevice& device, const std::vector<std::string>& keys,
                                                           const ProgressFn& progress,
                                                           const std::atomic<bool>* cancel) {
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

std::error_code write_atomically(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return {errno, std::system_category()};
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::error_code ec(errno, std::system_category());
      ::close(fd);
      return ec;
    }
    done += static_cast<std::size_t>(n);
  }
  const bool synced = ::fsync(fd) == 0;
  const std::error_code ec = synced ? std::error_code{} : std::error_code(errno, std::system_category());
  ::close(fd);
  if (ec) return ec;
  std::error_code rec;
  std::filesystem::rename(tmp, path, rec);
  return rec;
}

std::filesystem::path ResumeJournal::path_for(const std::filesystem::path& file) {
  return file.string() + ".hilbridge-resume";
}

std::optional<ResumeJournal> ResumeJournal::load(const std::filesystem::path& file) {
  std::ifstream in(path_for(file));
  if (!in) return std::nullopt;
  ResumeJournal j;
  std::string key;
  while (in >> key) {
    if (key == "device") {
      in >> std::ws;
      std::getline(in, j.device);
    } else if (key == "hash") {
      in >> std::hex >> j.hash >> std::dec;
    } else if (key == "next") {
      in >> j.next;
    }
  }
  return j;
}

std::error_code ResumeJournal::save(const std::filesystem::path& file) const {
  return write_atomically(path_for(file), fmt::format("hash {:016x}\nnext {}\ndevice {}\n", hash, next, device));
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
