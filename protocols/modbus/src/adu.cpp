// SPDX-License-Identifier: MIT
#include "hil/modbus/adu.hpp"

namespace hil::modbus {

FrameCheck check_frame(std::span<const std::uint8_t> buffer) noexcept {
  FrameCheck r;
  if (buffer.size() < kMbapSize) return r;
  r.header.transaction_id = get_u16(buffer.data());
  r.header.protocol_id = get_u16(buffer.data() + 2);
  r.header.length = get_u16(buffer.data() + 4);
  r.header.unit_id = buffer[6];
  if (r.header.protocol_id != 0) {
    r.status = FrameStatus::bad_protocol_id;
    return r;
  }
  if (r.header.length < 2 || r.header.length > kMaxPduSize + 1) {
    r.status = FrameStatus::bad_length;
    return r;
  }
  const std::size_t total = 6 + std::size_t{r.header.length};
  if (buffer.size() < total) return r;
  r.status = FrameStatus::complete;
  r.size = total;
  return r;
}

void make_mbap(std::uint8_t* out, std::uint16_t transaction_id, std::uint8_t unit_id, std::size_t pdu_size) noexcept {
  put_u16(out, transaction_id);
  put_u16(out + 2, 0);
  put_u16(out + 4, static_cast<std::uint16_t>(pdu_size + 1));
  out[6] = unit_id;
}

std::size_t make_exception_adu(std::span<std::uint8_t> out, const MbapHeader& request_header, std::uint8_t function,
                               std::uint8_t code) noexcept {
  if (out.size() < kMbapSize + 2) return 0;
  make_mbap(out.data(), request_header.transaction_id, request_header.unit_id, 2);
  out[7] = static_cast<std::uint8_t>(function | 0x80);
  out[8] = code;
  return kMbapSize + 2;
}

}  // namespace hil::modbus
