// SPDX-License-Identifier: MIT
#include "hil/modbus/request_handler.hpp"

namespace hil::modbus {
namespace {

struct Ctx {
  const MbapHeader& header;
  const std::uint8_t* pdu;
  std::size_t pdu_size;
  RegisterTable& table;
  std::span<std::uint8_t> out;
  HandleResult& result;
};

HandleResult& fail(Ctx& c, ModbusError e) {
  c.result.error = e;
  c.result.size = make_exception_adu(c.out, c.header, c.result.function, static_cast<std::uint8_t>(e));
  return c.result;
}

// Response PDU of `pdu_size` bytes has been written at out[7..]; add the header.
HandleResult& reply(Ctx& c, std::size_t pdu_size) {
  make_mbap(c.out.data(), c.header.transaction_id, c.header.unit_id, pdu_size);
  c.result.size = kMbapSize + pdu_size;
  return c.result;
}

void copy_registers_out(Ctx& c, RegisterSpace space, std::uint16_t first, std::uint16_t count, std::uint8_t* dst) {
  for (std::uint16_t i = 0; i < count; ++i) put_u16(dst + 2 * i, c.table.get(space, static_cast<std::uint16_t>(first + i)));
}

HandleResult& read_registers(Ctx& c, RegisterSpace space) {
  if (c.pdu_size != 5) return fail(c, ModbusError::illegal_data_value);
  const std::uint16_t addr = get_u16(c.pdu + 1);
  const std::uint16_t qty = get_u16(c.pdu + 3);
  if (qty < 1 || qty > kMaxReadRegisters) return fail(c, ModbusError::illegal_data_value);
  if (!c.table.range_ok(space, addr, qty, false)) return fail(c, ModbusError::illegal_data_address);
  std::uint8_t* r = c.out.data() + kMbapSize;
  r[0] = c.result.function;
  r[1] = static_cast<std::uint8_t>(2 * qty);
  copy_registers_out(c, space, addr, qty, r + 2);
  return reply(c, 2 + 2 * std::size_t{qty});
}

HandleResult& write_single(Ctx& c) {
  if (c.pdu_size != 5) return fail(c, ModbusError::illegal_data_value);
  const std::uint16_t addr = get_u16(c.pdu + 1);
  if (!c.table.range_ok(RegisterSpace::holding, addr, 1, true)) return fail(c, ModbusError::illegal_data_address);
  c.table.set(RegisterSpace::holding, addr, get_u16(c.pdu + 3));
  c.result.written_first = addr;
  c.result.written_count = 1;
  std::copy(c.pdu, c.pdu + 5, c.out.data() + kMbapSize);  // echo
  return reply(c, 5);
}

HandleResult& write_multiple(Ctx& c) {
  if (c.pdu_size < 6) return fail(c, ModbusError::illegal_data_value);
  const std::uint16_t addr = get_u16(c.pdu + 1);
  const std::uint16_t qty = get_u16(c.pdu + 3);
  const std::uint8_t bytes = c.pdu[5];
  if (qty < 1 || qty > kMaxWriteRegisters || bytes != 2 * qty || c.pdu_size != 6 + std::size_t{bytes})
    return fail(c, ModbusError::illegal_data_value);
  if (!c.table.range_ok(RegisterSpace::holding, addr, qty, true)) return fail(c, ModbusError::illegal_data_address);
  for (std::uint16_t i = 0; i < qty; ++i)
    c.table.set(RegisterSpace::holding, static_cast<std::uint16_t>(addr + i), get_u16(c.pdu + 6 + 2 * i));
  c.result.written_first = addr;
  c.result.written_count = qty;
  std::uint8_t* r = c.out.data() + kMbapSize;
  r[0] = c.result.function;
  put_u16(r + 1, addr);
  put_u16(r + 3, qty);
  return reply(c, 5);
}

HandleResult& mask_write(Ctx& c) {
  if (c.pdu_size != 7) return fail(c, ModbusError::illegal_data_value);
  const std::uint16_t addr = get_u16(c.pdu + 1);
  if (!c.table.range_ok(RegisterSpace::holding, addr, 1, true)) return fail(c, ModbusError::illegal_data_address);
  const std::uint16_t and_mask = get_u16(c.pdu + 3);
  const std::uint16_t or_mask = get_u16(c.pdu + 5);
  const std::uint16_t cur = c.table.get(RegisterSpace::holding, addr);
  c.table.set(RegisterSpace::holding, addr,
              static_cast<std::uint16_t>((cur & and_mask) | (or_mask & static_cast<std::uint16_t>(~and_mask))));
  c.result.written_first = addr;
  c.result.written_count = 1;
  std::copy(c.pdu, c.pdu + 7, c.out.data() + kMbapSize);
  return reply(c, 7);
}

HandleResult& read_write(Ctx& c) {
  if (c.pdu_size < 10) return fail(c, ModbusError::illegal_data_value);
  const std::uint16_t raddr = get_u16(c.pdu + 1);
  const std::uint16_t rqty = get_u16(c.pdu + 3);
  const std::uint16_t waddr = get_u16(c.pdu + 5);
  const std::uint16_t wqty = get_u16(c.pdu + 7);
  const std::uint8_t bytes = c.pdu[9];
  if (rqty < 1 || rqty > kMaxReadRegisters || wqty < 1 || wqty > kMaxRwWriteRegisters || bytes != 2 * wqty ||
      c.pdu_size != 10 + std::size_t{bytes})
    return fail(c, ModbusError::illegal_data_value);
  if (!c.table.range_ok(RegisterSpace::holding, waddr, wqty, true) ||
      !c.table.range_ok(RegisterSpace::holding, raddr, rqty, false))
    return fail(c, ModbusError::illegal_data_address);
  for (std::uint16_t i = 0; i < wqty; ++i)
    c.table.set(RegisterSpace::holding, static_cast<std::uint16_t>(waddr + i), get_u16(c.pdu + 10 + 2 * i));
  c.result.written_first = waddr;
  c.result.written_count = wqty;
  std::uint8_t* r = c.out.data() + kMbapSize;
  r[0] = c.result.function;
  r[1] = static_cast<std::uint8_t>(2 * rqty);
  copy_registers_out(c, RegisterSpace::holding, raddr, rqty, r + 2);
  return reply(c, 2 + 2 * std::size_t{rqty});
}

}  // namespace

HandleResult handle_request(std::span<const std::uint8_t> adu, RegisterTable& table, std::span<std::uint8_t> out,
                            const HandlerOptions& options) noexcept {
  HandleResult result;
  const FrameCheck frame = check_frame(adu);
  if (frame.status != FrameStatus::complete || frame.size != adu.size() || out.size() < kMaxAduSize) {
    result.error = ModbusError::invalid_request;
    return result;
  }
  const std::uint8_t* pdu = adu.data() + kMbapSize;
  const std::size_t pdu_size = adu.size() - kMbapSize;
  result.function = pdu[0];
  Ctx c{frame.header, pdu, pdu_size, table, out, result};
  if (result.function & 0x80) return fail(c, ModbusError::illegal_function);
  if (options.strict_unit && frame.header.unit_id != options.unit_id && frame.header.unit_id != 0 &&
      frame.header.unit_id != 0xFF)
    return fail(c, ModbusError::gateway_target_failed);
  switch (result.function) {
    case fc::read_holding_registers: return read_registers(c, RegisterSpace::holding);
    case fc::read_input_registers: return read_registers(c, RegisterSpace::input);
    case fc::write_single_register: return write_single(c);
    case fc::write_multiple_registers: return write_multiple(c);
    case fc::mask_write_register: return mask_write(c);
    case fc::read_write_registers: return read_write(c);
    default: return fail(c, ModbusError::illegal_function);
  }
}

}  // namespace hil::modbus
