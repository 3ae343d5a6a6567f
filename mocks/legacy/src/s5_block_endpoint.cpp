// SPDX-License-Identifier: MIT
#include "hil/mocks/legacy/s5_block_endpoint.hpp"

#include <fmt/format.h>

#include <algorithm>

#include <nlohmann/json.hpp>

#include "hil/serial/s5/rk512_client.hpp"

namespace hil::mocks::legacy {

using serial::s5::Rk512Error;

S5BlockEndpoint::S5BlockEndpoint(std::unique_ptr<DbPolicy> policy, S5EndpointOptions o)
    : policy_(std::move(policy)), o_(o), proc_(o.procedure) {}

TimePoint S5BlockEndpoint::next_deadline() const {
  return std::min(proc_.next_deadline(), policy_->next_deadline());
}

std::string S5BlockEndpoint::drain(TimePoint now) {
  policy_->on_time(now);
  proc_.poll(now);
  while (auto blk = proc_.take_received()) {
    auto t = serial::s5::parse_rk512(*blk);
    if (!t) {
      last_error_ = t.error().message;
      assembler_.reset();
      for (auto& r : serial::s5::make_rk512_reaction(Rk512Error::header_error, {}, o_.max_data)) proc_.send(r);
      continue;
    }
    const auto st = assembler_.feed(*t);
    if (st == serial::s5::Rk512Assembler::Status::error) {
      last_error_ = assembler_.error();
      assembler_.reset();
      for (auto& r : serial::s5::make_rk512_reaction(Rk512Error::header_error, {}, o_.max_data)) proc_.send(r);
    } else if (st == serial::s5::Rk512Assembler::Status::complete) {
      const auto job = assembler_.job();
      assembler_.reset();
      execute(job);
    }
  }
  while (proc_.take_send_result()) {
  }
  proc_.poll(now);
  auto out = proc_.take_output();
  return std::string(out.begin(), out.end());
}

void S5BlockEndpoint::execute(const serial::s5::Rk512Telegram& job) {
  std::vector<std::uint8_t> data;
  Rk512Error err = Rk512Error::ok;
  if (job.kind != serial::s5::Rk512Telegram::Kind::command ||
      (job.header.data_type != 'D' && job.header.data_type != 'X')) {
    err = Rk512Error::header_error;
  } else if (job.header.command == serial::s5::Rk512Command::fetch) {
    std::vector<std::uint16_t> words;
    err = job.header.data_type == 'X'
              ? policy_->on_read_dx(store_, job.header.db, job.header.dw, job.header.length, words)
              : policy_->on_read(store_, job.header.db, job.header.dw, job.header.length, words);
    if (err == Rk512Error::ok) data = serial::s5::words_to_bytes(words);
  } else {
    const auto words = serial::s5::bytes_to_words(job.data);
    err = job.header.data_type == 'X' ? policy_->on_write_dx(store_, job.header.db, job.header.dw, words)
                                      : policy_->on_write(store_, job.header.db, job.header.dw, words);
    if (err == Rk512Error::ok) dirty_ = true;
  }
  if (err != Rk512Error::ok) last_error_ = make_error_code(err).message();
  for (auto& r : serial::s5::make_rk512_reaction(err, data, o_.max_data)) proc_.send(r);
}

std::string S5BlockEndpoint::on_bytes(std::span<const std::uint8_t> data, TimePoint now) {
  proc_.on_bytes(data, now);
  return drain(now);
}

std::string S5BlockEndpoint::on_line_error(std::error_code, TimePoint now) {
  // A damaged character inside a block: the BCC check will fail and we answer NAK; feed a
  // byte that cannot complete the block so the procedure sees the damage.
  const std::uint8_t poison = 0xFF;
  proc_.on_bytes(std::span(&poison, 1), now);
  return drain(now);
}

std::string S5BlockEndpoint::on_idle(TimePoint now) {
  return drain(now);
}

bool S5BlockEndpoint::take_dirty() {
  const bool device = policy_->take_dirty();  // always asked: it tracks what it reported
  return std::exchange(dirty_, false) || device;
}

std::string S5BlockEndpoint::save_state() const {
  nlohmann::json j;
  j["device"] = policy_->name();
  nlohmann::json dbs = nlohmann::json::object();
  for (const auto& [n, w] : store_) dbs[std::to_string(n)] = w;
  j["dbs"] = dbs;
  if (auto module = policy_->save_module_state(); !module.empty()) j["module"] = std::move(module);
  return j.dump();
}

std::expected<void, std::string> S5BlockEndpoint::load_state(const std::string& text) {
  const auto j = nlohmann::json::parse(text, nullptr, false);
  // "device" must be the string naming this device (value() throws for another type).
  if (j.is_discarded() || !j.is_object() || !j.contains("device") || !j.at("device").is_string() ||
      j.at("device").get<std::string>() != policy_->name())
    return std::unexpected(fmt::format("not a {} state file", policy_->name()));
  try {
    const nlohmann::json dbs = j.contains("dbs") ? j.at("dbs") : nlohmann::json::object();
    for (const auto& [k, v] : dbs.items()) {
      const int n = std::stoi(k);
      if (n < 0 || n > 255) return std::unexpected(fmt::format("DB number {} out of range", n));
      store_[static_cast<std::uint8_t>(n)] = v.get<std::vector<std::uint16_t>>();
    }
  } catch (const std::exception& e) {
    return std::unexpected(fmt::format("state file malformed: {}", e.what()));
  }
  if (j.contains("module")) {
    if (!j.at("module").is_string()) return std::unexpected("state file malformed: 'module' is not a text");
    return policy_->load_module_state(j.at("module").get<std::string>());
  }
  return {};
}

namespace {

class Ip247Policy final : public DbPolicy {
 public:
  explicit Ip247Policy(ImageCheck c) : check_(std::move(c)) {}
  std::string name() const override { return "ip247"; }

  Rk512Error on_write(DbStore& store, std::uint8_t db, std::uint8_t dw, const std::vector<std::uint16_t>& w) override {
    if (dw == 0 && w.size() == 1 && w[0] == 0) {  // delete request
      if (!store.contains(db)) return Rk512Error::db_missing;
      store.erase(db);
      return Rk512Error::ok;
    }
    if (dw != 0) return Rk512Error::processing_not_possible;  // images are written whole
    if (store.contains(db)) return Rk512Error::db_exists;
    if (w.size() < 5) return Rk512Error::wrong_identifier;
    if (w[1] != 0x0044 || (w[2] >> 8) != 'B' || (w[2] & 0xFF) != db) return Rk512Error::wrong_identifier;
    if (w[0] != w.size()) return Rk512Error::wrong_identifier;
    if (w[0] == 70) {  // MD DB
      const int axis = w[3] & 0xFF;
      if (axis < 1 || axis > 3) return Rk512Error::image_rejected;
      if (check_) {
        if (const int e = check_(db, w); e != 0) return Rk512Error::image_rejected;
      }
    } else if (w[0] > 512) {
      return Rk512Error::target_too_small;
    }
    store[db] = w;
    return Rk512Error::ok;
  }

  Rk512Error on_read(const DbStore& store, std::uint8_t db, std::uint8_t dw, std::uint16_t length,
                     std::vector<std::uint16_t>& out) override {
    const auto it = store.find(db);
    if (it == store.end()) return Rk512Error::db_missing;
    if (std::size_t{dw} + length > it->second.size()) return Rk512Error::target_too_small;
    out.assign(it->second.begin() + dw, it->second.begin() + dw + length);
    return Rk512Error::ok;
  }

 private:
  ImageCheck check_;
};

class Wf725Policy final : public DbPolicy {
 public:
  explicit Wf725Policy(std::function<bool(const std::vector<std::uint16_t>&)> c) : check_(std::move(c)) {}
  std::string name() const override { return "wf725"; }

  Rk512Error on_write(DbStore& store, std::uint8_t code, std::uint8_t dw,
                      const std::vector<std::uint16_t>& w) override {
    if (code != 1) return Rk512Error::header_error;  // only the MD area is writable (112/113 otherwise)
    if ((dw % 2) != 0 || (w.size() % 2) != 0) return Rk512Error::wrong_identifier;
    if (std::size_t{dw} + w.size() > 100) return Rk512Error::target_too_small;  // MD number > 50: WF error 121
    std::vector<std::uint16_t> md = store.contains(1) ? store.at(1) : std::vector<std::uint16_t>(100, 0);
    md.resize(100, 0);
    std::copy(w.begin(), w.end(), md.begin() + dw);
    if (check_ && !check_(md)) return Rk512Error::image_rejected;  // nothing stored (WF 121 / MD errors)
    store[1] = std::move(md);
    return Rk512Error::ok;
  }

  Rk512Error on_read(const DbStore& store, std::uint8_t code, std::uint8_t dw, std::uint16_t length,
                     std::vector<std::uint16_t>& out) override {
    if (code == 0) return Rk512Error::header_error;
    if (code == 1) {
      if (std::size_t{dw} + length > 100) return Rk512Error::target_too_small;
      const auto it = store.find(1);
      out.assign(length, 0);
      if (it != store.end()) std::copy(it->second.begin() + dw, it->second.begin() + dw + length, out.begin());
      return Rk512Error::ok;
    }
    // Read-only status codes (3 speed, 4 pulse difference, B Kv, 29 DAC factor, 30 split
    // difference, 32 latched position): 32-bit values; the emulated axis stands still.
    static constexpr std::uint8_t status_codes[] = {0x03, 0x04, 0x0B, 0x29, 0x30, 0x32};
    if (std::find(std::begin(status_codes), std::end(status_codes), code) == std::end(status_codes))
      return Rk512Error::header_error;
    if (std::size_t{dw} + length > 2) return Rk512Error::target_too_small;
    out.assign(length, 0);
    return Rk512Error::ok;
  }

 private:
  std::function<bool(const std::vector<std::uint16_t>&)> check_;
};

}  // namespace

std::unique_ptr<DbPolicy> make_ip247_policy(ImageCheck md_check) {
  return std::make_unique<Ip247Policy>(std::move(md_check));
}
std::unique_ptr<DbPolicy> make_wf725_policy(std::function<bool(const std::vector<std::uint16_t>&)> md_check) {
  return std::make_unique<Wf725Policy>(std::move(md_check));
}

}  // namespace hil::mocks::legacy
