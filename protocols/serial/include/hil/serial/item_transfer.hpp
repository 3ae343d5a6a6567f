// SPDX-License-Identifier: MIT
#pragma once
// Device-independent sending (file -> device: the CLI's `download`), reading (device -> file: the
// CLI's `upload`, CiA 301 / STEP 7 terms, docs/cli.md) and read-back verification of keyed text items (program
// lines, parameters, data blocks), with progress, cancellation, an exact report of what
// reached the device, and a resume journal. The device side is an ItemDevice adapter
// (CLM1.4 client, ELG tape, IP247 blocks).

#include <atomic>
#include <cstdint>
#include <expected>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace hil::serial {

struct Item {
  std::string key;   ///< "0101", "B002", "DB10"
  std::string text;  ///< device text of the item
  friend bool operator==(const Item&, const Item&) = default;
};

struct ItemError {
  std::error_code code;
  std::string message;
};

/// One device, item by item. Blocking; one thread.
class ItemDevice {
 public:
  virtual ~ItemDevice() = default;
  /// Write one item; success means the device confirmed it.
  virtual std::expected<void, ItemError> write_item(const Item& item) = 0;
  /// Read one item's current text back.
  virtual std::expected<std::string, ItemError> read_item(const std::string& key) = 0;
  /// Normalise a text for comparison (e.g. trailing spaces, ',' vs '.').
  [[nodiscard]] virtual std::string normalise(const std::string& key, const std::string& text) const {
    (void)key;
    return text;
  }
};

/// done/total items, called after every item.
using ProgressFn = std::function<void(std::size_t done, std::size_t total)>;

struct SendReport {
  std::size_t total = 0;                ///< items in the file
  std::size_t start = 0;                ///< index the send started at (resume)
  std::size_t confirmed = 0;            ///< items [start, start + confirmed) confirmed by the device
  std::optional<std::string> in_doubt;  ///< key sent but not confirmed (may or may not be stored)
  std::vector<std::string> confirmed_keys;
  bool cancelled = false;
  std::optional<ItemError> error;
  [[nodiscard]] bool ok() const noexcept { return !error && !cancelled && start + confirmed == total; }
  /// Exactly what reached the device: "confirmed 0000..0123 (124 items); 0124 sent, not confirmed; 0125.. not sent".
  [[nodiscard]] std::string describe() const;
};

/// Write items[start..] in order; stops at the first error or when `cancel` becomes true.
/// `on_confirmed(index)` runs after each confirmed item (resume journal).
[[nodiscard]] SendReport send_items(ItemDevice& device, const std::vector<Item>& items, std::size_t start,
                                    const ProgressFn& progress, const std::atomic<bool>* cancel,
                                    const std::function<void(std::size_t)>& on_confirmed = {});

/// Read the given keys.
[[nodiscard]] std::expected<std::vector<Item>, ItemError> read_items(ItemDevice& device,
                                                                     const std::vector<std::string>& keys,
                                                                     const ProgressFn& progress,
                                                                     const std::atomic<bool>* cancel);

struct Difference {
  std::string key;
  std::string expected;  ///< in the file
  std::string actual;    ///< on the device
};
/// Read every item back and list every one that differs.
[[nodiscard]] std::expected<std::vector<Difference>, ItemError> verify_items(ItemDevice& device,
                                                                             const std::vector<Item>& items,
                                                                             const ProgressFn& progress);

/// FNV-1a 64 of a text (stable content hash for the resume journal).
[[nodiscard]] std::uint64_t content_hash(std::string_view text) noexcept;

/// Resume journal "<file>.hilbridge-resume": which send (`hilbridge download`) of which file content to which
/// device reached which index. Written atomically; removed after a complete send.
struct ResumeJournal {
  std::string device;      ///< "clm14 program on /dev/ttyUSB0 station 0"
  std::uint64_t hash = 0;  ///< content_hash of the file
  std::size_t next = 0;    ///< first item not confirmed

  [[nodiscard]] static std::filesystem::path path_for(const std::filesystem::path& file);
  [[nodiscard]] static std::optional<ResumeJournal> load(const std::filesystem::path& file);
  /// The journal in `text` (what text() wrote), or nullopt for anything else.
  [[nodiscard]] static std::optional<ResumeJournal> parse(std::string_view text);
  [[nodiscard]] std::string text() const;
  std::error_code save(const std::filesystem::path& file) const;
  static void remove(const std::filesystem::path& file);
};

/// Write `text` to `path` atomically: a fresh temporary file beside it (O_EXCL, never through a
/// symlink, never a user's file), fsync, rename over `path`, fsync the folder. A crash leaves the
/// old file or the new one, never half of either; `path` keeps its mode (a new file: 0666 less
/// the umask); on an error no temporary file is left.
[[nodiscard]] std::error_code write_atomically(const std::filesystem::path& path, const std::string& text);

/// Write `text` to `path` atomically; when `path` exists and differs, keep the old content as
/// `path.bak` (or .bak.1, .bak.2 ... if that exists too). Returns the backup path ("" if none).
[[nodiscard]] std::expected<std::filesystem::path, std::error_code> write_with_backup(const std::filesystem::path& path,
                                                                                      const std::string& text);

}  // namespace hil::serial
