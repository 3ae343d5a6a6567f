// SPDX-License-Identifier: MIT
#pragma once
// Emulated S5 module with data blocks behind 3964R + RK512 (IP247 machine-data and traversing
// program DBs; WF 725/726 data codes). RK512 SEND writes a DB area, FETCH reads one; the
// device policy decides what a write means (whole-image checks, no overwrite, delete).
// The manuals give the block layouts but no serial framing: the mapping is ours (docs/serial.md).

#include <cstdint>
#include <expected>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "hil/mocks/legacy/endpoint.hpp"
#include "hil/serial/s5/procedure_3964r.hpp"
#include "hil/serial/s5/rk512.hpp"

namespace hil::mocks::legacy {

using DbStore = std::map<std::uint8_t, std::vector<std::uint16_t>>;

/// Device rules for DB access.
class DbPolicy {
 public:
  virtual ~DbPolicy() = default;
  /// A complete SEND job (all continuations assembled).
  virtual serial::s5::Rk512Error on_write(DbStore& store, std::uint8_t db, std::uint8_t dw,
                                          const std::vector<std::uint16_t>& words) = 0;
  /// A FETCH job; fills `out` with exactly `length` words on success.
  virtual serial::s5::Rk512Error on_read(const DbStore& store, std::uint8_t db, std::uint8_t dw, std::uint16_t length,
                                         std::vector<std::uint16_t>& out) = 0;
  [[nodiscard]] virtual std::string name() const = 0;
  /// DX blocks (RK512 data type 'X'); by default the same as DBs.
  virtual serial::s5::Rk512Error on_write_dx(DbStore& store, std::uint8_t dx, std::uint8_t dw,
                                             const std::vector<std::uint16_t>& words) {
    return on_write(store, dx, dw, words);
  }
  virtual serial::s5::Rk512Error on_read_dx(const DbStore& store, std::uint8_t dx, std::uint8_t dw,
                                            std::uint16_t length, std::vector<std::uint16_t>& out) {
    return on_read(store, dx, dw, length, out);
  }
  /// Module time for devices that run (called before every job and whenever the endpoint is
  /// idle); `next_deadline` = when the device needs its next call.
  virtual void on_time(TimePoint /*now*/) {}
  [[nodiscard]] virtual TimePoint next_deadline() const { return TimePoint::max(); }
  /// Device state beyond the DBs for the state file (e.g. a module's program memory): a text the
  /// device reads back, empty = none. Saved as the JSON string "module" next to "dbs".
  [[nodiscard]] virtual std::string save_module_state() const { return {}; }
  /// Restores what save_module_state wrote (after the DBs are loaded).
  virtual std::expected<void, std::string> load_module_state(const std::string& /*text*/) { return {}; }
  /// The device changed its own state since the last call (not by a SEND: e.g. a program stored
  /// by a data code at the module's cycle); the endpoint then saves its state file.
  [[nodiscard]] virtual bool take_dirty() { return false; }
};

/// Checks a complete image (e.g. an IP247 MD DB) against the device profile: 0 = valid, else
/// the device's error number (written into the image's error byte by the IP247).
using ImageCheck = std::function<int(std::uint8_t db, const std::vector<std::uint16_t>& words)>;

/// IP247 (digest ip247.md §2.2, §5.5): MD DB images of 70 words ("length 70, 00 'D', 'B' dbno"),
/// traversing-program DBs (length <= 512 words, '%' program text). No overwrite mode: a SEND to
/// an existing DB is refused (07) unless it is a delete request (one word 0000 at DW 0, our
/// mapping of job 21/23). A rejected MD image is refused with 10 and nothing is stored.
[[nodiscard]] std::unique_ptr<DbPolicy> make_ip247_policy(ImageCheck md_check);
/// WF 725/726: the DB number is the data code (digest wf725-726.md §6.4); data code 1 holds the
/// 50 machine data as 100 words (32-bit, high word first), writable by area (the resulting
/// image is checked as a whole); other known codes are read-only status values; 0 and unknown
/// codes are refused (WF errors 112/113 via 0C).
[[nodiscard]] std::unique_ptr<DbPolicy> make_wf725_policy(
    std::function<bool(const std::vector<std::uint16_t>& md_words)> md_image_ok);

struct S5EndpointOptions {
  serial::s5::ProcedureOptions procedure{.high_priority = false};  ///< the module yields to the PC
  std::size_t max_data = serial::s5::rk512_default_max_data;
};

class S5BlockEndpoint final : public Endpoint {
 public:
  S5BlockEndpoint(std::unique_ptr<DbPolicy> policy, S5EndpointOptions o = {});

  std::string on_bytes(std::span<const std::uint8_t> data, TimePoint now) override;
  std::string on_line_error(std::error_code ec, TimePoint now) override;
  std::string on_idle(TimePoint now) override;
  [[nodiscard]] TimePoint next_deadline() const override;
  bool take_dirty() override;
  std::string save_state() const override;
  std::expected<void, std::string> load_state(const std::string& text);

  [[nodiscard]] DbStore& store() noexcept { return store_; }
  [[nodiscard]] const std::string& last_error() const noexcept { return last_error_; }
  [[nodiscard]] serial::s5::Procedure3964& procedure() noexcept { return proc_; }

 private:
  std::string drain(TimePoint now);
  void execute(const serial::s5::Rk512Telegram& job);

  std::unique_ptr<DbPolicy> policy_;
  S5EndpointOptions o_;
  serial::s5::Procedure3964 proc_;
  serial::s5::Rk512Assembler assembler_;
  DbStore store_;
  std::string last_error_;
  bool dirty_ = false;
};

}  // namespace hil::mocks::legacy
