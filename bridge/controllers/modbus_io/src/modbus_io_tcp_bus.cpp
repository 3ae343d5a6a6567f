// SPDX-License-Identifier: MIT
#include "hil/controllers/modbus_io_tcp_bus.hpp"

#include <algorithm>
#include <cerrno>
#include <memory>

#include <fmt/format.h>
#include <modbus.h>

namespace hil::controllers {

namespace {

struct CtxDeleter {
  void operator()(modbus_t* ctx) const noexcept {
    modbus_close(ctx);
    modbus_free(ctx);
  }
};

bool is_link_error(modbus::ModbusError e) noexcept {
  return static_cast<int>(e) >= 0x100;
}

}  // namespace

TcpModbusIoBus::TcpModbusIoBus(TcpModbusIoBusConfig config, const modbus::BitPlan& reads, const modbus::BitPlan& writes,
                               const Clock& clock)
    : config_(std::move(config)),
      reads_(reads.blocks),
      writes_(writes.blocks),
      clock_(clock),
      describe_(fmt::format("tcp://{}:{} unit {}",
                            config_.host.find(':') != std::string::npos ? "[" + config_.host + "]" : config_.host,
                            config_.port, config_.unit)),
      created_(clock.now()),
      shared_inputs_(reads.bits, 0),
      shared_outputs_(writes.bits, 0) {
  thread_ = std::thread([this] { worker(); });
}

TcpModbusIoBus::~TcpModbusIoBus() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void TcpModbusIoBus::fetch(TimePoint, std::span<std::uint8_t> inputs, ModbusIoStatus& status) noexcept {
  const TimePoint now = clock_.now();
  std::lock_guard lock(mutex_);
  std::copy(shared_inputs_.begin(), shared_inputs_.end(), inputs.begin());
  status = shared_status_;
  status.age = now - (status.polls > 0 ? stamp_ : created_);
}

void TcpModbusIoBus::put(TimePoint, std::span<const std::uint8_t> outputs) noexcept {
  bool changed = false;
  {
    std::lock_guard lock(mutex_);
    changed = !outputs_given_ || !std::equal(outputs.begin(), outputs.end(), shared_outputs_.begin());
    if (changed) {
      std::copy(outputs.begin(), outputs.end(), shared_outputs_.begin());
      outputs_dirty_ = true;
      outputs_given_ = true;
    }
  }
  if (changed) cv_.notify_all();
}

TcpModbusIoStats TcpModbusIoBus::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

void TcpModbusIoBus::worker() {
  std::unique_ptr<modbus_t, CtxDeleter> ctx(
      modbus_new_tcp_pi(config_.host.c_str(), std::to_string(config_.port).c_str()));
  if (ctx) {
    const auto us = std::chrono::duration_cast<std::chrono::microseconds>(config_.response_timeout).count();
    const auto sec = static_cast<std::uint32_t>(us / 1000000);
    const auto usec = static_cast<std::uint32_t>(us % 1000000);
    modbus_set_response_timeout(ctx.get(), sec, usec);
    modbus_set_byte_timeout(ctx.get(), sec, usec);
    modbus_set_slave(ctx.get(), config_.unit);
    modbus_set_error_recovery(ctx.get(), MODBUS_ERROR_RECOVERY_NONE);
  }
  std::vector<std::uint8_t> inputs(shared_inputs_.size(), 0);
  std::vector<std::uint8_t> outputs(shared_outputs_.size(), 0);
  std::vector<std::uint8_t> written(shared_outputs_.size(), 0);
  bool connected = false;
  bool rewrite_all = true;
  bool have_outputs = false;
  Duration backoff = config_.backoff_min;
  auto next_attempt = std::chrono::steady_clock::now();
  auto next_poll = std::chrono::steady_clock::now();
  const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(config_.poll);

  for (;;) {
    {
      std::unique_lock lock(mutex_);
      cv_.wait_until(lock, next_poll, [&] { return stop_ || (outputs_dirty_ && connected); });
      if (stop_) return;
      if (outputs_dirty_) {
        outputs = shared_outputs_;  // sizes are equal: no allocation
        outputs_dirty_ = false;
        have_outputs = outputs_given_;
      }
    }
    const auto real_now = std::chrono::steady_clock::now();
    const bool poll_due = real_now >= next_poll;
    if (poll_due) next_poll = std::max(next_poll + period, real_now);  // never burst to catch up
    const TimePoint started = clock_.now();

    // Publish one attempt's outcome.
    auto finish = [&](modbus::ModbusError err, bool polled, std::uint64_t writes) {
      std::lock_guard lock(mutex_);
      shared_status_.connected = connected;
      stats_.write_requests += writes;
      if (err != modbus::ModbusError::none) {
        ++shared_status_.errors;
        ++stats_.errors;
        shared_status_.error = err;
        return;
      }
      if (!polled) return;
      std::copy(inputs.begin(), inputs.end(), shared_inputs_.begin());
      ++shared_status_.polls;
      ++stats_.polls;
      shared_status_.error = modbus::ModbusError::none;
      stamp_ = started;
    };
    auto link_down = [&] {
      modbus_close(ctx.get());
      connected = false;
      next_attempt = std::chrono::steady_clock::now() + backoff;
      backoff = std::min(backoff * 2, config_.backoff_max);
    };

    if (!ctx) {
      finish(modbus::ModbusError::connect_failed, false, 0);
      continue;
    }
    if (!connected) {
      if (real_now < next_attempt) continue;
      if (modbus_connect(ctx.get()) != 0) {
        const auto err = modbus::from_libmodbus_errno(errno);
        link_down();
        finish(err == modbus::ModbusError::connection_lost ? modbus::ModbusError::connect_failed : err, false, 0);
        continue;
      }
      connected = true;
      rewrite_all = true;
      {
        std::lock_guard lock(mutex_);
        ++stats_.connects;
        shared_status_.connected = true;
      }
    }

    modbus::ModbusError err = modbus::ModbusError::none;
    std::uint64_t writes = 0;
    if (have_outputs) {
      std::size_t at = 0;
      for (const auto& b : writes_) {
        const auto from = static_cast<std::ptrdiff_t>(at);
        at += b.count;
        if (!rewrite_all &&
            std::equal(outputs.begin() + from, outputs.begin() + from + b.count, written.begin() + from))
          continue;
        const int rc = b.count == 1 ? modbus_write_bit(ctx.get(), b.first, outputs[at - 1])
                                    : modbus_write_bits(ctx.get(), b.first, b.count, outputs.data() + from);
        if (rc != (b.count == 1 ? 1 : b.count)) {
          err = modbus::from_libmodbus_errno(errno);
          break;
        }
        ++writes;
        std::copy_n(outputs.begin() + from, b.count, written.begin() + from);
      }
      if (err == modbus::ModbusError::none) rewrite_all = false;
    }
    bool polled = false;
    if (err == modbus::ModbusError::none && poll_due) {
      std::size_t at = 0;
      for (const auto& b : reads_) {
        auto* dest = inputs.data() + at;
        at += b.count;
        const int rc = b.space == modbus::BitSpace::coil ? modbus_read_bits(ctx.get(), b.first, b.count, dest)
                                                         : modbus_read_input_bits(ctx.get(), b.first, b.count, dest);
        if (rc != b.count) {
          err = modbus::from_libmodbus_errno(errno);
          break;
        }
      }
      polled = err == modbus::ModbusError::none;
    }
    if (err != modbus::ModbusError::none && is_link_error(err)) {
      link_down();
    } else if (err == modbus::ModbusError::none) {
      backoff = config_.backoff_min;
    }
    finish(err, polled, writes);
  }
}

}  // namespace hil::controllers
