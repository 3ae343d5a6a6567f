// SPDX-License-Identifier: MIT
#include "hil/mocks/modbus_responder.hpp"

#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <utility>

#include <modbus/modbus.h>

#include "hil/modbus/adu.hpp"

namespace hil::mocks {

ModbusResponder::ModbusResponder() {
  int fds[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0) return;
  ctx_ = modbus_new_tcp("127.0.0.1", MODBUS_TCP_DEFAULT_PORT);  // never connected: only its reply path is used
  if (ctx_ == nullptr || modbus_set_socket(ctx_, fds[0]) != 0) {
    if (ctx_ != nullptr) modbus_free(ctx_);
    ctx_ = nullptr;
    ::close(fds[0]);
    ::close(fds[1]);
    return;
  }
  reply_fd_ = fds[1];
}

ModbusResponder::~ModbusResponder() {
  release();
}

ModbusResponder::ModbusResponder(ModbusResponder&& other) noexcept
    : ctx_(std::exchange(other.ctx_, nullptr)), reply_fd_(std::exchange(other.reply_fd_, -1)) {}

ModbusResponder& ModbusResponder::operator=(ModbusResponder&& other) noexcept {
  if (this != &other) {
    release();
    ctx_ = std::exchange(other.ctx_, nullptr);
    reply_fd_ = std::exchange(other.reply_fd_, -1);
  }
  return *this;
}

void ModbusResponder::release() noexcept {
  if (ctx_ != nullptr) {
    ::close(modbus_get_socket(ctx_));
    modbus_free(ctx_);
    ctx_ = nullptr;
  }
  if (reply_fd_ >= 0) ::close(reply_fd_);
  reply_fd_ = -1;
}

modbus::HandleResult ModbusResponder::handle(std::span<const std::uint8_t> adu, modbus::RegisterTable& table,
                                             std::span<std::uint8_t> out,
                                             const modbus::HandlerOptions& options) noexcept {
  modbus::HandleResult result;
  const modbus::RequestCheck check = modbus::check_request(adu, table, options);
  result.function = check.function;
  result.error = check.error;
  if (check.error == modbus::ModbusError::invalid_request || out.size() < modbus::kMaxAduSize) {
    result.error = modbus::ModbusError::invalid_request;
    return result;
  }
  if (check.function & 0x80) {
    // libmodbus 3.1.6 builds an exception as function + 0x80 in 8 bits, which turns 0x83 into
    // 0x03: a request carrying an exception function code gets its 01 from us.
    result.size = modbus::make_exception_adu(out, modbus::check_frame(adu).header, check.function,
                                             static_cast<std::uint8_t>(result.error));
    return result;
  }
  if (ctx_ == nullptr) {  // no socket pair (fd exhaustion): answer, do not crash
    result.error = modbus::ModbusError::server_device_failure;
    result.size = modbus::make_exception_adu(out, modbus::check_frame(adu).header, check.function,
                                             static_cast<std::uint8_t>(result.error));
    return result;
  }
  // The mapping is laid over the table's own arrays: libmodbus reads and writes the device's registers.
  modbus_mapping_t mapping{};
  auto holding = table.values(modbus::RegisterSpace::holding);
  auto input = table.values(modbus::RegisterSpace::input);
  mapping.nb_registers = static_cast<int>(holding.size());
  mapping.tab_registers = holding.data();
  mapping.nb_input_registers = static_cast<int>(input.size());
  mapping.tab_input_registers = input.data();
  auto coils = table.values(modbus::BitSpace::coil);
  auto discrete = table.values(modbus::BitSpace::discrete_input);
  mapping.nb_bits = static_cast<int>(coils.size());
  mapping.tab_bits = coils.data();
  mapping.nb_input_bits = static_cast<int>(discrete.size());
  mapping.tab_input_bits = discrete.data();

  const int sent = check.error == modbus::ModbusError::none
                       ? modbus_reply(ctx_, adu.data(), static_cast<int>(adu.size()), &mapping)
                       : modbus_reply_exception(ctx_, adu.data(), static_cast<unsigned>(check.error));
  std::size_t got = 0;
  while (sent > 0 && got < static_cast<std::size_t>(sent)) {
    const ssize_t n = ::recv(reply_fd_, out.data() + got, out.size() - got, MSG_DONTWAIT);
    if (n > 0) {
      got += static_cast<std::size_t>(n);
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      break;  // cannot happen for a reply libmodbus reported as sent; never block the I/O thread
    }
  }
  if (sent <= 0 || got != static_cast<std::size_t>(sent)) {
    std::uint8_t sink[modbus::kMaxAduSize];
    while (::recv(reply_fd_, sink, sizeof sink, MSG_DONTWAIT) > 0) {
    }  // nothing of this reply may prefix the next one
    result.error = modbus::ModbusError::server_device_failure;
    result.size = modbus::make_exception_adu(out, modbus::check_frame(adu).header, check.function,
                                             static_cast<std::uint8_t>(result.error));
    return result;
  }
  result.size = got;
  if (check.error == modbus::ModbusError::none) {
    result.written_first = check.written_first;
    result.written_count = check.written_count;
    result.coils_written_first = check.coils_written_first;
    result.coils_written_count = check.coils_written_count;
  }
  return result;
}

}  // namespace hil::mocks
