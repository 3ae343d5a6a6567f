// SPDX-License-Identifier: MIT
#include "hil/serial/memory_line.hpp"

#include <condition_variable>
#include <deque>
#include <mutex>

namespace hil::serial {

namespace {

struct Pipe {
  std::mutex m;
  std::condition_variable cv;
  std::deque<std::uint8_t> q;
};

class MemoryEnd final : public RawLine {
 public:
  MemoryEnd(std::shared_ptr<Pipe> rx, std::shared_ptr<Pipe> tx, std::shared_ptr<LineFilter> filter,
            VirtualClock* vclock)
      : rx_(std::move(rx)), tx_(std::move(tx)), filter_(std::move(filter)), vclock_(vclock) {}

  ReadResult read_some(std::span<std::uint8_t> buf, Duration timeout) override {
    ReadResult r;
    std::unique_lock lock(rx_->m);
    if (rx_->q.empty()) {
      if (vclock_ != nullptr) {
        vclock_->advance(timeout);
      } else if (timeout > Duration::zero()) {
        rx_->cv.wait_for(lock, timeout, [&] { return !rx_->q.empty(); });
      }
    }
    while (!rx_->q.empty() && r.size < buf.size()) {
      buf[r.size++] = rx_->q.front();
      rx_->q.pop_front();
    }
    if (r.size == 0) r.error = LineError::timeout;
    return r;
  }

  std::error_code write(std::span<const std::uint8_t> data, Duration) override {
    std::vector<std::uint8_t> bytes(data.begin(), data.end());
    if (filter_ && *filter_) (*filter_)(bytes);
    {
      std::lock_guard lock(tx_->m);
      tx_->q.insert(tx_->q.end(), bytes.begin(), bytes.end());
    }
    tx_->cv.notify_all();
    return {};
  }

 private:
  std::shared_ptr<Pipe> rx_, tx_;
  std::shared_ptr<LineFilter> filter_;
  VirtualClock* vclock_;
};

}  // namespace

MemoryLinePair make_memory_line(VirtualClock* vclock) {
  auto ab = std::make_shared<Pipe>();
  auto ba = std::make_shared<Pipe>();
  MemoryLinePair p;
  p.a_to_b = std::make_shared<LineFilter>();
  p.b_to_a = std::make_shared<LineFilter>();
  p.a = std::make_unique<MemoryEnd>(ba, ab, p.a_to_b, vclock);
  p.b = std::make_unique<MemoryEnd>(ab, ba, p.b_to_a, vclock);
  return p;
}

}  // namespace hil::serial
