// SPDX-License-Identifier: MIT
#include "hil/modbus/request_handler.hpp"

namespace hil::modbus {
namespace {

RequestCheck& fail(RequestCheck& r, ModbusError e) {
  r.error = e;
  return r;
}

}  // namespace

RequestCheck check_request(std::span<const std::uint8_t> adu, const RegisterTable& table,
                           const HandlerOptions& options) noexcept {
  RequestCheck r;
  const FrameCheck frame = check_frame(adu);
  if (frame.status != FrameStatus::complete || frame.size != adu.size()) return fail(r, ModbusError::invalid_request);
  const std::uint8_t* pdu = adu.data() + kMbapSize;
  const std::size_t n = adu.size() - kMbapSize;
  r.function = pdu[0];
  if (r.function & 0x80) return fail(r, ModbusError::illegal_function);
  if (options.strict_unit && frame.header.unit_id != options.unit_id && frame.header.unit_id != 0 &&
      frame.header.unit_id != 0xFF)
    return fail(r, ModbusError::gateway_target_failed);
  const auto u16 = [&](std::size_t at) { return get_u16(pdu + at); };
  switch (r.function) {
    case fc::read_coils:
    case fc::read_discrete_inputs: {
      const auto space = r.function == fc::read_coils ? BitSpace::coil : BitSpace::discrete_input;
      if (!table.has(space)) return fail(r, ModbusError::illegal_function);
      if (n != 5) return fail(r, ModbusError::illegal_data_value);
      const std::uint16_t qty = u16(3);
      if (qty < 1 || qty > kMaxReadBits) return fail(r, ModbusError::illegal_data_value);
      if (!table.range_ok(space, u16(1), qty, false)) return fail(r, ModbusError::illegal_data_address);
      return r;
    }
    case fc::write_single_coil: {
      if (!table.has(BitSpace::coil)) return fail(r, ModbusError::illegal_function);
      if (n != 5) return fail(r, ModbusError::illegal_data_value);
      if (u16(3) != 0x0000 && u16(3) != 0xFF00) return fail(r, ModbusError::illegal_data_value);  // MB spec §6.5
      if (!table.range_ok(BitSpace::coil, u16(1), 1, true)) return fail(r, ModbusError::illegal_data_address);
      r.coils_written_first = u16(1);
      r.coils_written_count = 1;
      return r;
    }
    case fc::write_multiple_coils: {
      if (!table.has(BitSpace::coil)) return fail(r, ModbusError::illegal_function);
      if (n < 6) return fail(r, ModbusError::illegal_data_value);
      const std::uint16_t qty = u16(3);
      const std::uint8_t bytes = pdu[5];
      if (qty < 1 || qty > kMaxWriteBits || bytes != (qty + 7) / 8 || n != 6 + std::size_t{bytes})
        return fail(r, ModbusError::illegal_data_value);
      if (!table.range_ok(BitSpace::coil, u16(1), qty, true)) return fail(r, ModbusError::illegal_data_address);
      r.coils_written_first = u16(1);
      r.coils_written_count = qty;
      return r;
    }
    case fc::read_holding_registers:
    case fc::read_input_registers: {
      if (n != 5) return fail(r, ModbusError::illegal_data_value);
      const std::uint16_t qty = u16(3);
      if (qty < 1 || qty > kMaxReadRegisters) return fail(r, ModbusError::illegal_data_value);
      const auto space = r.function == fc::read_input_registers ? RegisterSpace::input : RegisterSpace::holding;
      if (!table.range_ok(space, u16(1), qty, false)) return fail(r, ModbusError::illegal_data_address);
      return r;
    }
    case fc::write_single_register:
    case fc::mask_write_register: {
      if (n != (r.function == fc::write_single_register ? 5u : 7u)) return fail(r, ModbusError::illegal_data_value);
      if (!table.range_ok(RegisterSpace::holding, u16(1), 1, true)) return fail(r, ModbusError::illegal_data_address);
      r.written_first = u16(1);
      r.written_count = 1;
      return r;
    }
    case fc::write_multiple_registers: {
      if (n < 6) return fail(r, ModbusError::illegal_data_value);
      const std::uint16_t qty = u16(3);
      const std::uint8_t bytes = pdu[5];
      if (qty < 1 || qty > kMaxWriteRegisters || bytes != 2 * qty || n != 6 + std::size_t{bytes})
        return fail(r, ModbusError::illegal_data_value);
      if (!table.range_ok(RegisterSpace::holding, u16(1), qty, true)) return fail(r, ModbusError::illegal_data_address);
      r.written_first = u16(1);
      r.written_count = qty;
      return r;
    }
    case fc::read_write_registers: {
      if (n < 10) return fail(r, ModbusError::illegal_data_value);
      const std::uint16_t rqty = u16(3);
      const std::uint16_t wqty = u16(7);
      const std::uint8_t bytes = pdu[9];
      if (rqty < 1 || rqty > kMaxReadRegisters || wqty < 1 || wqty > kMaxRwWriteRegisters || bytes != 2 * wqty ||
          n != 10 + std::size_t{bytes})
        return fail(r, ModbusError::illegal_data_value);
      if (!table.range_ok(RegisterSpace::holding, u16(5), wqty, true) ||
          !table.range_ok(RegisterSpace::holding, u16(1), rqty, false))
        return fail(r, ModbusError::illegal_data_address);
      r.written_first = u16(5);
      r.written_count = wqty;
      return r;
    }
    default:
      return fail(r, ModbusError::illegal_function);
  }
}

}  // namespace hil::modbus
