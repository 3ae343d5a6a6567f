// SPDX-License-Identifier: MIT
#include "hil/mocks/legacy/endpoint.hpp"

#include <array>

#include "hil/serial/item_transfer.hpp"

namespace hil::mocks::legacy {

EndpointHost::EndpointHost(Endpoint& endpoint, serial::ByteStream& stream, const Clock& clock,
                           std::filesystem::path state_file)
    : endpoint_(endpoint), stream_(stream), clock_(clock), state_file_(std::move(state_file)), last_rx_(clock.now()) {}

void EndpointHost::send(const std::string& bytes) {
  if (bytes.empty()) return;
  if (drop_after_ > 0) {
    --drop_after_;
  } else if (drop_replies_ > 0) {
    --drop_replies_;
    return;
  }
  const auto* p = reinterpret_cast<const std::uint8_t*>(bytes.data());
  (void)stream_.write(std::span(p, bytes.size()), std::chrono::seconds(5));
}

std::error_code EndpointHost::step(Duration max_wait) {
  std::array<std::uint8_t, 1024> buf{};
  Duration wait = max_wait;
  {
    std::lock_guard lock(mutex_);
    const TimePoint deadline = endpoint_.next_deadline();
    if (deadline != TimePoint::max()) wait = std::max(Duration::zero(), std::min(wait, deadline - clock_.now()));
  }
  const serial::ReadResult r = stream_.read_some(buf, wait);
  if (r.size > 0) last_rx_ = clock_.now();
  std::string out;
  bool save = false;
  {
    std::lock_guard lock(mutex_);
    if (r.size > 0) out += endpoint_.on_bytes(std::span(buf.data(), r.size), clock_.now());
    if (r.error && r.error != serial::LineError::timeout && r.error != serial::LineError::closed)
      out += endpoint_.on_line_error(r.error, clock_.now());
    if (clock_.now() >= endpoint_.next_deadline()) out += endpoint_.on_idle(clock_.now());
    if (endpoint_.take_dirty()) pending_save_ = true;
    save = pending_save_;  // read under the lock: with_endpoint() sets it from the console thread
  }
  send(out);
  if (r.size == 0 && save) (void)persist();
  return r.error;
}

void EndpointHost::run() {
  while (!stop_) step(std::chrono::milliseconds(50));
  (void)persist();
}

void EndpointHost::with_endpoint(const std::function<void(Endpoint&)>& fn) {
  std::lock_guard lock(mutex_);
  fn(endpoint_);
  if (endpoint_.take_dirty()) pending_save_ = true;
}

std::error_code EndpointHost::persist() {
  std::string text;
  {
    std::lock_guard lock(mutex_);
    if (state_file_.empty() || !pending_save_) return {};
    pending_save_ = false;
    text = endpoint_.save_state();
  }
  return serial::write_atomically(state_file_, text);
}

}  // namespace hil::mocks::legacy
