// SPDX-License-Identifier: MIT
#include "hil/drives/modbus_drive.hpp"

#include "hil/cia402/cia402.hpp"

#include <cerrno>
#include <cmath>

#include <fmt/format.h>
#include <modbus.h>

namespace hil::drives {

using modbus::FieldRole;

namespace {

struct ModbusCtxDeleter {
  void operator()(modbus_t* ctx) const noexcept {
    if (ctx) {
      modbus_close(ctx);
      modbus_free(ctx);
    }
  }
};

void set_timeouts(modbus_t* ctx, Duration timeout) {
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(timeout).count();
  const auto sec = static_cast<std::uint32_t>(us / 1000000);
  const auto usec = static_cast<std::uint32_t>(us % 1000000);
  modbus_set_response_timeout(ctx, sec, usec);
  modbus_set_byte_timeout(ctx, sec, usec);
}

bool is_link_error(modbus::ModbusError e) noexcept {
  return static_cast<int>(e) >= 0x100;
}

}  // namespace

ModbusDrive::ModbusDrive(ModbusDriveConfig config, const Clock& clock) : config_(std::move(config)), clock_(clock) {
  if (config_.unit_id < 0) config_.unit_id = config_.profile.unit_id;
  name_ = fmt::format("modbus:{}:{}/{}", config_.host, config_.port, config_.unit_id);
  auto plan = modbus::make_exchange_plan(config_.profile);
  if (plan) plan_ = std::move(*plan);  // the loader already checked it; an invalid plan exchanges nothing
  for (std::size_t i = 0; i < modbus::kFieldRoleCount; ++i) {
    const auto role = static_cast<FieldRole>(i);
    const auto& f = config_.profile.fields[i];
    if (!f.present) continue;
    const auto& blocks = modbus::is_command(role) ? plan_.writes : plan_.reads;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      if (f.address >= blocks[b].first && f.address + f.words() <= blocks[b].first + blocks[b].count) {
        slots_[i] = {true, b, static_cast<std::size_t>(f.address - blocks[b].first)};
        break;
      }
    }
  }
  for (const auto& b : plan_.writes) command_.emplace_back(b.count, 0);
  for (const auto& b : plan_.reads) local_image_.blocks.emplace_back(b.count, 0);
  shared_command_ = command_;
  shared_image_ = local_image_;
  thread_ = std::thread([this] { worker(); });
}

ModbusDrive::~ModbusDrive() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

DriveCapabilities ModbusDrive::capabilities() const noexcept {
  const bool vel =
      config_.profile.field(FieldRole::target_velocity).present && config_.profile.field(FieldRole::mode).present;
  const auto& p = config_.profile;
  const bool homing = p.mode_homing.has_value() && p.state_machine == modbus::StateMachineKind::cia402 &&
                      p.field(FieldRole::mode).present;
  return DriveCapabilities{.closed_loop = true, .velocity_mode = vel, .homing = homing, .min_period = {}};
}

std::int64_t ModbusDrive::field_value(FieldRole role) const noexcept {
  const auto& slot = slots_[static_cast<std::size_t>(role)];
  if (!slot.present) return 0;
  const auto& f = config_.profile.field(role);
  const auto& block = local_image_.blocks[slot.block];
  return modbus::unpack_value(std::span<const std::uint16_t>(block.data() + slot.offset, f.words()), f.format);
}

void ModbusDrive::put_field(FieldRole role, std::int64_t raw) noexcept {
  const auto& slot = slots_[static_cast<std::size_t>(role)];
  if (!slot.present) return;
  const auto& f = config_.profile.field(role);
  auto& block = command_[slot.block];
  modbus::pack_value(raw, f.format, std::span<std::uint16_t>(block.data() + slot.offset, f.words()));
}

void ModbusDrive::read(const CycleTime& cycle) {
  if (!have_created_) {
    created_ = cycle.now;
    have_created_ = true;
  }
  {
    std::lock_guard lock(mutex_);
    if (shared_image_.seq != local_image_.seq) {
      for (std::size_t b = 0; b < local_image_.blocks.size(); ++b)
        std::copy(shared_image_.blocks[b].begin(), shared_image_.blocks[b].end(), local_image_.blocks[b].begin());
      local_image_.stamp = shared_image_.stamp;
      local_image_.seq = shared_image_.seq;
    }
    local_link_ = shared_link_;
  }
  if (local_link_.error_seq != seen_error_seq_) {
    seen_error_seq_ = local_link_.error_seq;
    link_fault_ = local_link_.error;  // latch the newest error
    link_reset_armed_ = false;
    target_ = modbus::PowerTarget::disabled;  // a faulted axis is switched off; re-enable after the reset
  }
  clear_link_fault_if_reset();
  const auto& p = config_.profile;
  if (local_image_.seq == 0) {
    drive_state_ = DriveState::not_ready;
    feedback_.age = cycle.now - created_;
  } else {
    const auto sw = static_cast<std::uint16_t>(field_value(FieldRole::status_word));
    const auto info = modbus::decode_status(p, sw);
    drive_state_ = info.state;
    feedback_.referenced = info.referenced;
    feedback_.position_inc = std::llround(static_cast<double>(field_value(FieldRole::actual_position)) *
                                          p.field(FieldRole::actual_position).scale);
    feedback_.velocity_inc_per_s =
        static_cast<double>(field_value(FieldRole::actual_velocity)) * p.field(FieldRole::actual_velocity).scale;
    feedback_.age = cycle.now - local_image_.stamp;
    track_homing(sw, cycle.now);
  }
  feedback_.referenced = feedback_.referenced && !unreferenced_;
  feedback_.homing_active = homing_ != Homing::idle;
  if (link_fault_ != modbus::ModbusError::none) {
    feedback_.state = DriveState::fault;
    if (feedback_.fault.code != modbus::make_error_code(link_fault_)) {
      feedback_.fault.code = modbus::make_error_code(link_fault_);
      feedback_.fault.text = fmt::format("{} ({}): {}", feedback_.fault.code.message(), name_,
                                         is_link_error(link_fault_) ? "the axis faults; it reconnects by itself, then "
                                                                      "fault_reset clears this"
                                                                    : "the drive refused the cyclic exchange; check "
                                                                      "the profile against the drive's register map");
    }
    return;
  }
  feedback_.state = drive_state_;
  if (drive_state_ == DriveState::fault || drive_state_ == DriveState::fault_reaction_active) {
    // Latched: the drive is switched off and stays off, even if it leaves its fault state by
    // itself, until a fault reset is requested; then the program enables it again. (While a
    // requested reset is under way the drive may still show the fault for a few exchanges.)
    if (!reset_pending_) {
      drive_fault_latched_ = true;
      target_ = modbus::PowerTarget::disabled;
    }
    const auto code = static_cast<std::uint32_t>(field_value(FieldRole::fault_code));
    if (feedback_.fault.code != modbus::make_drive_fault_code(code)) {
      feedback_.fault.code = modbus::make_drive_fault_code(code);
      const std::string text = p.fault_text(code);
      feedback_.fault.text = fmt::format("drive fault 0x{:04X} {}({}); fault_reset acknowledges it", code,
                                         text.empty() ? std::string{} : text + " ", name_);
    }
  } else if (feedback_.fault && !drive_fault_latched_) {
    feedback_.fault = {};
  }
}

void ModbusDrive::write(const CycleTime& /*cycle*/, const DriveCommand& command) {
  const auto& p = config_.profile;
  // Fault reset: hold the bit low for two exchanges, then high until the fault clears (at most
  // 20 exchanges), so the drive sees a rising edge however cycles and exchanges interleave.
  bool reset_high = false;
  if (reset_pending_) {
    const std::uint64_t n = local_image_.seq - reset_start_seq_;
    if (n >= 2) reset_high = true;
    if (n >= 4 && drive_state_ != DriveState::fault && drive_state_ != DriveState::fault_reaction_active) {
      reset_pending_ = false;
      reset_high = false;
    }
    if (n >= 22) reset_pending_ = false;
  }
  // While a link fault is latched the drive is told to switch off (it may still be powered on
  // the far side after an outage); the control word gets there as soon as the link is back.
  const auto cw = link_fault_ != modbus::ModbusError::none
                      ? modbus::make_control_word(p, drive_state_, modbus::PowerTarget::disabled, false)
                      : modbus::make_control_word(p, drive_state_, target_, reset_high);
  put_field(FieldRole::control_word, cw);
  const bool velocity = command.mode == CommandMode::velocity && capabilities().velocity_mode;
  // While not following, the target is the actual position: enabling never jumps.
  const bool following = drive_state_ == DriveState::operation_enabled && link_fault_ == modbus::ModbusError::none;
  if (homing_ != Homing::idle && following) {
    // Select the homing mode; after two exchanges in it, raise bit 4 (the drive starts on its edge).
    put_field(FieldRole::mode, *p.mode_homing);
    if (homing_ == Homing::selecting && local_image_.seq >= homing_seq_ + 2) {
      homing_ = Homing::started;
      homing_seq_ = local_image_.seq;
    }
    if (homing_ == Homing::started) put_field(FieldRole::control_word, cw | cia402::cw::new_set_point);
  } else {
    put_field(FieldRole::mode, velocity ? p.mode_velocity : p.mode_position);
  }
  const double pos =
      following ? static_cast<double>(command.position_inc) : static_cast<double>(feedback_.position_inc);
  put_field(FieldRole::target_position, std::llround(pos / p.field(FieldRole::target_position).scale));
  const double vel = following && velocity ? command.velocity_inc_per_s : 0.0;
  if (p.field(FieldRole::target_velocity).present)
    put_field(FieldRole::target_velocity, std::llround(vel / p.field(FieldRole::target_velocity).scale));
  std::lock_guard lock(mutex_);
  for (std::size_t b = 0; b < command_.size(); ++b)
    std::copy(command_[b].begin(), command_[b].end(), shared_command_[b].begin());
}

bool ModbusDrive::request(DriveRequest r) {
  switch (r) {
    case DriveRequest::enable:
      target_ = modbus::PowerTarget::enabled;
      return true;
    case DriveRequest::disable:
      target_ = modbus::PowerTarget::disabled;
      return true;
    case DriveRequest::quick_stop:
      target_ = modbus::PowerTarget::quick_stop;
      return true;
    case DriveRequest::fault_reset:
      // A link fault clears when the link delivers an image after the error. Only a reset given
      // while connected counts: a reset during an outage must not clear a later reconnect's fault.
      link_reset_armed_ = link_fault_ != modbus::ModbusError::none && local_link_.connected;
      clear_link_fault_if_reset();
      target_ = modbus::PowerTarget::disabled;  // a reset never re-enables by itself
      drive_fault_latched_ = false;
      reset_pending_ = true;
      reset_start_seq_ = local_image_.seq;
      return true;
    case DriveRequest::home:
      if (!capabilities().homing) return false;
      homing_ = Homing::selecting;
      homing_seq_ = local_image_.seq;
      homing_deadline_.reset();
      unreferenced_ = true;
      return true;
  }
  return false;
}

void ModbusDrive::track_homing(std::uint16_t status_word, TimePoint now) noexcept {
  if (homing_ == Homing::idle) return;
  if (!homing_deadline_) homing_deadline_ = now + config_.homing_timeout;
  // Status bits 12/13 mean "homing attained / error" only in images taken after bit 4 went out.
  if (homing_ == Homing::started && local_image_.seq > homing_seq_) {
    if ((status_word & cia402::sw::op_specific_13) != 0) {
      homing_ = Homing::idle;  // stays unreferenced: the axis reports a failed homing
      return;
    }
    if ((status_word & cia402::sw::op_specific_12) != 0 && (status_word & cia402::sw::target_reached) != 0) {
      homing_ = Homing::idle;
      unreferenced_ = false;
      return;
    }
  }
  if (now > *homing_deadline_ || drive_state_ == DriveState::fault || drive_state_ == DriveState::fault_reaction_active)
    homing_ = Homing::idle;  // timed out or faulted: not referenced
}

void ModbusDrive::clear_link_fault_if_reset() noexcept {
  if (!link_reset_armed_ || link_fault_ == modbus::ModbusError::none) return;
  if (local_link_.connected && local_image_.seq > local_link_.error_at_image_seq) {
    link_fault_ = modbus::ModbusError::none;
    link_reset_armed_ = false;
    feedback_.fault = {};
    feedback_.state = drive_state_;
  }
}

bool ModbusDrive::exchange_sync(TimePoint now, std::chrono::milliseconds wait) {
  if (!config_.lockstep) return false;
  exchange_start(now);
  return exchange_wait(wait);
}

void ModbusDrive::exchange_start(TimePoint now) {
  if (!config_.lockstep) return;
  {
    std::lock_guard lock(mutex_);
    trigger_now_ = now;
    ++trigger_seq_;
  }
  cv_.notify_all();
}

bool ModbusDrive::exchange_wait(std::chrono::milliseconds wait) {
  if (!config_.lockstep) return false;
  std::unique_lock lock(mutex_);
  const std::uint64_t want = trigger_seq_;
  return cv_.wait_for(lock, wait, [&] { return done_seq_ >= want || stop_; }) && done_seq_ >= want;
}

ModbusLinkStats ModbusDrive::link_stats() const {
  std::lock_guard lock(mutex_);
  return {exchanges_.load(), errors_.load(), connects_.load(), shared_link_.connected, shared_link_.error};
}

bool ModbusDrive::exchange_once(void* vctx, const std::vector<std::vector<std::uint16_t>>& command,
                                std::vector<std::vector<std::uint16_t>>& image) noexcept {
  auto* ctx = static_cast<modbus_t*>(vctx);
  if (plan_.read_write) {
    const auto& w = plan_.writes[0];
    const auto& r = plan_.reads[0];
    return modbus_write_and_read_registers(ctx, w.first, w.count, command[0].data(), r.first, r.count,
                                           image[0].data()) == r.count;
  }
  for (std::size_t b = 0; b < plan_.writes.size(); ++b) {
    const auto& w = plan_.writes[b];
    const int rc = plan_.write_fc == 6 ? modbus_write_register(ctx, w.first, command[b][0])
                                       : modbus_write_registers(ctx, w.first, w.count, command[b].data());
    if (rc < 0) return false;
  }
  for (std::size_t b = 0; b < plan_.reads.size(); ++b) {
    const auto& r = plan_.reads[b];
    const int rc = plan_.read_fc == 4 ? modbus_read_input_registers(ctx, r.first, r.count, image[b].data())
                                      : modbus_read_registers(ctx, r.first, r.count, image[b].data());
    if (rc != r.count) return false;
  }
  return true;
}

void ModbusDrive::worker() {
  std::unique_ptr<modbus_t, ModbusCtxDeleter> ctx(
      modbus_new_tcp_pi(config_.host.c_str(), std::to_string(config_.port).c_str()));
  if (ctx) {
    set_timeouts(ctx.get(), config_.response_timeout);
    modbus_set_slave(ctx.get(), config_.unit_id);
    modbus_set_error_recovery(ctx.get(), MODBUS_ERROR_RECOVERY_NONE);
  }
  // Worker-local buffers sized like the shared ones (copied under the lock: the motion thread
  // may already be writing commands).
  std::vector<std::vector<std::uint16_t>> command;
  std::vector<std::vector<std::uint16_t>> image;
  {
    std::lock_guard lock(mutex_);
    command = shared_command_;
    image = shared_image_.blocks;
  }
  bool connected = false;
  TimePoint next_attempt{};
  Duration backoff = config_.backoff_min;
  std::uint64_t handled_trigger = 0;
  auto next_free_run = std::chrono::steady_clock::now();

  for (;;) {
    TimePoint now;
    {
      std::unique_lock lock(mutex_);
      if (config_.lockstep) {
        cv_.wait(lock, [&] { return stop_ || trigger_seq_ != handled_trigger; });
        if (stop_) return;
        handled_trigger = trigger_seq_;
        now = trigger_now_;
      } else {
        cv_.wait_until(lock, next_free_run, [&] { return stop_; });
        if (stop_) return;
        next_free_run += std::chrono::duration_cast<std::chrono::steady_clock::duration>(config_.poll_period);
        const auto real_now = std::chrono::steady_clock::now();
        if (next_free_run < real_now) next_free_run = real_now;  // never burst to catch up
        now = clock_.now();
      }
      command = shared_command_;
    }
    // Publish the outcome: fresh data (ok), an error, or nothing (waiting out the back-off).
    auto finish = [&](bool ok, modbus::ModbusError err, TimePoint stamp) {
      std::lock_guard lock(mutex_);
      if (ok && err == modbus::ModbusError::none) {
        for (std::size_t b = 0; b < image.size(); ++b)
          std::copy(image[b].begin(), image[b].end(), shared_image_.blocks[b].begin());
        shared_image_.stamp = stamp;
        ++shared_image_.seq;
      } else if (!ok) {
        shared_link_.error = err;
        ++shared_link_.error_seq;
        shared_link_.error_at_image_seq = shared_image_.seq;
      }
      shared_link_.connected = connected;
      done_seq_ = handled_trigger;
      cv_.notify_all();
    };
    if (!ctx) {
      errors_.fetch_add(1);
      finish(false, modbus::ModbusError::connect_failed, now);
      continue;
    }
    if (!connected) {
      if (now < next_attempt) {
        finish(true, modbus::ModbusError::connect_failed, now);  // nothing new: still backing off
        continue;
      }
      if (modbus_connect(ctx.get()) != 0) {
        const auto err = modbus::from_libmodbus_errno(errno);
        modbus_close(ctx.get());
        errors_.fetch_add(1);
        next_attempt = now + backoff;
        backoff = std::min(backoff * 2, config_.backoff_max);
        finish(false, err == modbus::ModbusError::connection_lost ? modbus::ModbusError::connect_failed : err, now);
        continue;
      }
      connected = true;
      connects_.fetch_add(1);
    }
    if (exchange_once(ctx.get(), command, image)) {
      backoff = config_.backoff_min;
      exchanges_.fetch_add(1);
      finish(true, modbus::ModbusError::none, config_.lockstep ? now : clock_.now());
      continue;
    }
    const auto err = modbus::from_libmodbus_errno(errno);
    errors_.fetch_add(1);
    if (is_link_error(err)) {
      // After a timeout a late reply would be taken for the next one (upstream issue #451):
      // drop the connection and start clean.
      modbus_close(ctx.get());
      connected = false;
      next_attempt = now + backoff;
      backoff = std::min(backoff * 2, config_.backoff_max);
    }
    finish(false, err, now);
  }
}

}  // namespace hil::drives
