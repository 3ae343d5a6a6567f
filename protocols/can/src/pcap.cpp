// SPDX-License-Identifier: MIT
#include "hil/can/pcap.hpp"

namespace hil::can::pcap {

namespace {
void put_le32(std::uint8_t* p, std::uint32_t v) noexcept {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
void put_le16(std::uint8_t* p, std::uint16_t v) noexcept {
  p[0] = static_cast<std::uint8_t>(v);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
void put_be32(std::uint8_t* p, std::uint32_t v) noexcept {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * (3 - i)));
}
}  // namespace

std::array<std::uint8_t, global_header_size> make_global_header() noexcept {
  std::array<std::uint8_t, global_header_size> h{};
  put_le32(&h[0], 0xA1B2C3D4u);  // microsecond timestamps
  put_le16(&h[4], 2);
  put_le16(&h[6], 4);
  put_le32(&h[8], 0);   // thiszone
  put_le32(&h[12], 0);  // sigfigs
  put_le32(&h[16], snaplen);
  put_le32(&h[20], linktype_can_socketcan);
  return h;
}

std::array<std::uint8_t, record_header_size + frame_size> make_record(const Frame& frame,
                                                                      socketcand::Timestamp time) noexcept {
  std::array<std::uint8_t, record_header_size + frame_size> r{};
  put_le32(&r[0], static_cast<std::uint32_t>(time.sec));
  put_le32(&r[4], time.usec % 1000000u);
  put_le32(&r[8], frame_size);
  put_le32(&r[12], frame_size);
  std::uint8_t* f = &r[record_header_size];
  put_be32(&f[0], to_socketcan_id(frame));
  f[4] = frame.dlc > 8 ? std::uint8_t{8} : frame.dlc;  // payload length (RTR: requested length)
  // f[5] FD flags, f[6..7] reserved: zero
  for (std::size_t i = 0; i < frame.payload().size(); ++i) f[8 + i] = frame.data[i];
  if (frame.error)
    for (std::size_t i = 0; i < 8; ++i) f[8 + i] = frame.data[i];
  return r;
}

}  // namespace hil::can::pcap
