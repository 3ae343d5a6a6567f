// SPDX-License-Identifier: MIT
#include "hil/canopen/sdo_server.hpp"

#include <algorithm>

#include "hil/canopen/crc16.hpp"

namespace hil::canopen {
namespace {

std::uint8_t clamp_blksize(std::uint8_t b) noexcept {
  return b < 1 ? 1 : (b > 127 ? 127 : b);
}

}  // namespace

SdoServer::SdoServer(ObjectDictionary& od, NodeId node, FrameSink sink, SdoServerOptions options)
    : od_(od),
      sink_(std::move(sink)),
      options_(options),
      rx_cob_(cob_sdo_rx_base + node),
      tx_cob_(cob_sdo_tx_base + node) {
  options_.block_size = clamp_blksize(options_.block_size);
}

void SdoServer::set_node(NodeId node) noexcept {
  rx_cob_ = cob_sdo_rx_base + node;
  tx_cob_ = cob_sdo_tx_base + node;
  state_ = State::idle;
}

void SdoServer::send(const can::Frame& f, TimePoint now) {
  if (muted_) return;
  if (delay_ > Duration::zero()) {
    delayed_.emplace_back(now + delay_, f);
    return;
  }
  sink_(f);
}

void SdoServer::respond(std::initializer_list<std::uint8_t> bytes, TimePoint now) {
  can::Frame f = frame_of(tx_cob_, bytes);
  f.dlc = 8;
  send(f, now);
}

void SdoServer::abort(SdoAbort code, TimePoint now) {
  can::Frame f;
  f.id = tx_cob_;
  f.dlc = 8;
  f.data[0] = 0x80;
  put_le16(&f.data[1], index_);
  f.data[3] = sub_;
  put_le32(&f.data[4], static_cast<std::uint32_t>(code));
  send(f, now);
  state_ = State::idle;
  buffer_.clear();
}

void SdoServer::step(TimePoint now) {
  while (!delayed_.empty() && delayed_.front().first <= now) {
    sink_(delayed_.front().second);
    delayed_.pop_front();
  }
  if (state_ != State::idle && now - last_ > options_.timeout) abort(SdoAbort::timeout, now);
}

bool SdoServer::on_frame(const can::Frame& f, TimePoint now) {
  if (f.id != rx_cob_ || f.extended || f.rtr || f.error) return false;
  if (f.dlc == 0) return true;  // nothing to answer to: not even a multiplexer
  last_ = now;
  if (f.dlc < 8) {
    // CiA 301 fixes SDO frames at 8 bytes; a short one is a protocol error.
    if (f.dlc >= 4 && state_ == State::idle) {
      index_ = get_le16(&f.data[1]);
      sub_ = f.data[3];
    }
    abort(SdoAbort::command_specifier, now);
    return true;
  }
  const std::uint8_t b0 = f.data[0];
  const std::uint8_t ccs = b0 >> 5;
  if (b0 == 0x80 && state_ != State::block_download) {  // abort from the client: no answer
    state_ = State::idle;
    buffer_.clear();
    return true;
  }
  switch (state_) {
    case State::block_download:
      on_block_segment(f, now);
      return true;
    case State::block_download_end:
      on_block_download_end(f, now);
      return true;
    case State::download_segment:
      if (ccs == 0) {
        on_download_segment(f, now);
        return true;
      }
      break;
    case State::upload_segment:
      if (ccs == 3) {
        on_upload_segment(f, now);
        return true;
      }
      break;
    case State::block_upload_start:
    case State::block_upload_ack:
    case State::block_upload_end:
      if (ccs == 5) {
        on_block_upload(f, now);
        return true;
      }
      break;
    case State::idle:
      break;
  }
  // Idle, or a new initiate request inside a transfer (the client restarted, e.g. after its own
  // timeout): start over.
  index_ = get_le16(&f.data[1]);
  sub_ = f.data[3];
  switch (ccs) {
    case 1:
      start_download(f, now);
      break;
    case 2:
      start_upload(f, now);
      break;
    case 5:
      if ((b0 & 0x03) == 0)
        start_block_upload(f, now);
      else
        abort(SdoAbort::command_specifier, now);
      break;
    case 6:
      if ((b0 & 0x01) == 0)
        start_block_download(f, now);
      else
        abort(SdoAbort::command_specifier, now);
      break;
    default:
      abort(SdoAbort::command_specifier, now);
      break;
  }
  return true;
}

void SdoServer::start_download(const can::Frame& f, TimePoint now) {
  const std::uint8_t b0 = f.data[0];
  const bool expedited = (b0 & 0x02) != 0;
  const bool sized = (b0 & 0x01) != 0;
  const auto* var = od_.find(index_, sub_);
  if (var == nullptr) return abort(od_.has_object(index_) ? SdoAbort::no_sub_index : SdoAbort::no_object, now);
  if (!writable(var->access)) return abort(SdoAbort::read_only, now);
  const auto fixed = data_type_size(var->type);
  if (expedited) {
    std::size_t n = sized ? 4u - ((b0 >> 2) & 0x03) : (fixed != 0 && fixed < 4 ? fixed : 4u);
    const auto a = od_.write(index_, sub_, std::span<const std::uint8_t>(&f.data[4], n));
    if (a != SdoAbort::none) return abort(a, now);
    state_ = State::idle;
    return respond({0x60, f.data[1], f.data[2], sub_, 0, 0, 0, 0}, now);
  }
  size_indicated_ = sized;
  size_ = sized ? get_le32(&f.data[4]) : 0;
  if (sized && fixed != 0 && size_ != fixed)
    return abort(size_ > fixed ? SdoAbort::length_too_high : SdoAbort::length_too_low, now);
  if (sized && size_ > od_.max_value_size()) return abort(SdoAbort::out_of_memory, now);
  buffer_.clear();
  toggle_ = false;
  state_ = State::download_segment;
  respond({0x60, f.data[1], f.data[2], sub_, 0, 0, 0, 0}, now);
}

void SdoServer::on_download_segment(const can::Frame& f, TimePoint now) {
  const std::uint8_t b0 = f.data[0];
  const bool t = (b0 & 0x10) != 0;
  if (t != toggle_) return abort(SdoAbort::toggle_bit, now);
  const std::size_t len = 7u - ((b0 >> 1) & 0x07);
  const bool last = (b0 & 0x01) != 0;
  if (size_indicated_ && buffer_.size() + len > size_) return abort(SdoAbort::length_too_high, now);
  if (buffer_.size() + len > od_.max_value_size()) return abort(SdoAbort::out_of_memory, now);
  buffer_.insert(buffer_.end(), &f.data[1], &f.data[1 + len]);
  const std::uint8_t rsp = static_cast<std::uint8_t>(0x20 | (t ? 0x10 : 0x00));
  toggle_ = !toggle_;
  if (!last) return respond({rsp, 0, 0, 0, 0, 0, 0, 0}, now);
  if (size_indicated_ && buffer_.size() != size_) return abort(SdoAbort::length_too_low, now);
  const auto a = od_.write(index_, sub_, buffer_);
  if (a != SdoAbort::none) return abort(a, now);
  state_ = State::idle;
  buffer_.clear();
  respond({rsp, 0, 0, 0, 0, 0, 0, 0}, now);
}

void SdoServer::start_upload(const can::Frame& f, TimePoint now) {
  const auto data = od_.read(index_, sub_);
  if (!data) return abort(data.error(), now);
  const auto& d = *data;
  if (d.size() <= 4 && !d.empty()) {
    const auto n = static_cast<std::uint8_t>(4 - d.size());
    can::Frame r =
        frame_of(tx_cob_, {static_cast<std::uint8_t>(0x43 | (n << 2)), f.data[1], f.data[2], sub_, 0, 0, 0, 0});
    std::copy(d.begin(), d.end(), r.data.begin() + 4);
    state_ = State::idle;
    return send(r, now);
  }
  buffer_.assign(d.begin(), d.end());
  offset_ = 0;
  toggle_ = false;
  state_ = State::upload_segment;
  can::Frame r = frame_of(tx_cob_, {0x41, f.data[1], f.data[2], sub_, 0, 0, 0, 0});
  put_le32(&r.data[4], static_cast<std::uint32_t>(buffer_.size()));
  send(r, now);
}

void SdoServer::on_upload_segment(const can::Frame& f, TimePoint now) {
  const bool t = (f.data[0] & 0x10) != 0;
  if ((f.data[0] & 0x0F) != 0) return abort(SdoAbort::command_specifier, now);
  if (t != toggle_) return abort(SdoAbort::toggle_bit, now);
  const std::size_t len = std::min<std::size_t>(7, buffer_.size() - offset_);
  const bool last = offset_ + len >= buffer_.size();
  can::Frame r;
  r.id = tx_cob_;
  r.dlc = 8;
  r.data[0] = static_cast<std::uint8_t>((t ? 0x10 : 0x00) | ((7 - len) << 1) | (last ? 1 : 0));
  std::copy_n(buffer_.begin() + static_cast<std::ptrdiff_t>(offset_), len, r.data.begin() + 1);
  offset_ += len;
  toggle_ = !toggle_;
  if (last) {
    state_ = State::idle;
    buffer_.clear();
  }
  send(r, now);
}

void SdoServer::start_block_download(const can::Frame& f, TimePoint now) {
  const std::uint8_t b0 = f.data[0];
  const auto* var = od_.find(index_, sub_);
  if (var == nullptr) return abort(od_.has_object(index_) ? SdoAbort::no_sub_index : SdoAbort::no_object, now);
  if (!writable(var->access)) return abort(SdoAbort::read_only, now);
  client_crc_ = (b0 & 0x04) != 0;
  size_indicated_ = (b0 & 0x02) != 0;
  size_ = size_indicated_ ? get_le32(&f.data[4]) : 0;
  const auto fixed = data_type_size(var->type);
  if (size_indicated_ && fixed != 0 && size_ != fixed)
    return abort(size_ > fixed ? SdoAbort::length_too_high : SdoAbort::length_too_low, now);
  if (size_indicated_ && size_ > od_.max_value_size()) return abort(SdoAbort::out_of_memory, now);
  buffer_.clear();
  blksize_ = options_.block_size;
  expected_seq_ = 1;
  seq_error_ = false;
  last_segment_ = false;
  state_ = State::block_download;
  respond({static_cast<std::uint8_t>(0xA0 | (options_.block_crc ? 0x04 : 0x00)), f.data[1], f.data[2], sub_, blksize_,
           0, 0, 0},
          now);
}

void SdoServer::on_block_segment(const can::Frame& f, TimePoint now) {
  const std::uint8_t b0 = f.data[0];
  const std::uint8_t seq = b0 & 0x7F;
  const bool last = (b0 & 0x80) != 0;
  if (seq == 0) {
    if (b0 == 0x80) {  // abort from the client
      state_ = State::idle;
      buffer_.clear();
      return;
    }
  }
  if (seq == 0 || seq > blksize_) return abort(SdoAbort::sequence_number, now);
  if (!seq_error_ && seq == expected_seq_) {
    if (buffer_.size() >= od_.max_value_size() + 7) return abort(SdoAbort::out_of_memory, now);
    const std::size_t allowed_segments = size_ == 0 ? 1 : (size_ + 6) / 7;
    if (size_indicated_ && buffer_.size() / 7 + 1 > allowed_segments) return abort(SdoAbort::length_too_high, now);
    buffer_.insert(buffer_.end(), &f.data[1], &f.data[8]);
    ++expected_seq_;
    last_segment_ = last;
  } else {
    seq_error_ = true;  // ignore the rest of this block; the ack asks for a retransmission
  }
  if (seq == blksize_ || last) {
    const auto ackseq = static_cast<std::uint8_t>(expected_seq_ - 1);
    const bool done = last_segment_ && !seq_error_;
    expected_seq_ = 1;
    seq_error_ = false;
    if (done) state_ = State::block_download_end;
    respond({0xA2, ackseq, blksize_, 0, 0, 0, 0, 0}, now);
  }
}

void SdoServer::on_block_download_end(const can::Frame& f, TimePoint now) {
  const std::uint8_t b0 = f.data[0];
  if ((b0 & 0xE3) != 0xC1) return abort(SdoAbort::command_specifier, now);
  const std::size_t unused = (b0 >> 2) & 0x07;
  if (unused > buffer_.size()) return abort(SdoAbort::length_too_low, now);
  buffer_.erase(buffer_.end() - static_cast<std::ptrdiff_t>(unused), buffer_.end());  // shrinks, never fills
  if (size_indicated_ && buffer_.size() != size_)
    return abort(buffer_.size() > size_ ? SdoAbort::length_too_high : SdoAbort::length_too_low, now);
  if (client_crc_ && options_.block_crc && crc16_ccitt(buffer_) != get_le16(&f.data[1]))
    return abort(SdoAbort::crc, now);
  const auto a = od_.write(index_, sub_, buffer_);
  if (a != SdoAbort::none) return abort(a, now);
  state_ = State::idle;
  buffer_.clear();
  respond({0xA1, 0, 0, 0, 0, 0, 0, 0}, now);
}

void SdoServer::start_block_upload(const can::Frame& f, TimePoint now) {
  const std::uint8_t blksize = f.data[4];
  const std::uint8_t pst = f.data[5];
  if (blksize < 1 || blksize > 127) return abort(SdoAbort::block_size, now);
  const auto data = od_.read(index_, sub_);
  if (!data) return abort(data.error(), now);
  if (pst != 0 && data->size() <= pst) return start_upload(f, now);  // protocol switch (CiA 301 §7.2.4.3.13)
  client_crc_ = (f.data[0] & 0x04) != 0;
  buffer_.assign(data->begin(), data->end());
  blksize_ = blksize;
  block_start_ = 0;
  state_ = State::block_upload_start;
  can::Frame r = frame_of(tx_cob_, {static_cast<std::uint8_t>(0xC2 | (options_.block_crc ? 0x04 : 0x00)), f.data[1],
                                    f.data[2], sub_, 0, 0, 0, 0});
  put_le32(&r.data[4], static_cast<std::uint32_t>(buffer_.size()));
  send(r, now);
}

void SdoServer::send_upload_block(TimePoint now) {
  sent_in_block_ = 0;
  std::size_t off = block_start_;
  for (std::uint8_t seq = 1; seq <= blksize_; ++seq) {
    const std::size_t len = std::min<std::size_t>(7, buffer_.size() - off);
    const bool last = off + len >= buffer_.size();
    can::Frame r;
    r.id = tx_cob_;
    r.dlc = 8;
    r.data[0] = static_cast<std::uint8_t>(seq | (last ? 0x80 : 0x00));
    std::copy_n(buffer_.begin() + static_cast<std::ptrdiff_t>(off), len, r.data.begin() + 1);
    off += len;
    sent_in_block_ = seq;
    send(r, now);
    if (last) break;
  }
  state_ = State::block_upload_ack;
}

void SdoServer::on_block_upload(const can::Frame& f, TimePoint now) {
  const std::uint8_t cs = f.data[0] & 0x03;
  switch (state_) {
    case State::block_upload_start:
      if (cs != 3) return abort(SdoAbort::command_specifier, now);
      return send_upload_block(now);
    case State::block_upload_ack: {
      if (cs != 2) return abort(SdoAbort::command_specifier, now);
      const std::uint8_t ackseq = f.data[1];
      const std::uint8_t next_blksize = f.data[2];
      if (ackseq > sent_in_block_) return abort(SdoAbort::sequence_number, now);
      if (next_blksize < 1 || next_blksize > 127) return abort(SdoAbort::block_size, now);
      block_start_ = std::min(buffer_.size(), block_start_ + std::size_t{ackseq} * 7);
      blksize_ = next_blksize;
      if (block_start_ < buffer_.size() || ackseq < sent_in_block_) return send_upload_block(now);
      // Everything acknowledged: end with the unused byte count of the last segment and the CRC.
      const std::size_t rem = buffer_.size() % 7;
      const auto unused = static_cast<std::uint8_t>(buffer_.empty() ? 7 : (rem == 0 ? 0 : 7 - rem));
      const std::uint16_t crc = options_.block_crc && client_crc_ ? crc16_ccitt(buffer_) : 0;
      state_ = State::block_upload_end;
      return respond({static_cast<std::uint8_t>(0xC1 | (unused << 2)), static_cast<std::uint8_t>(crc),
                      static_cast<std::uint8_t>(crc >> 8), 0, 0, 0, 0, 0},
                     now);
    }
    case State::block_upload_end:
      if (cs != 1) return abort(SdoAbort::command_specifier, now);
      state_ = State::idle;
      buffer_.clear();
      return;
    default:
      return abort(SdoAbort::command_specifier, now);
  }
}

}  // namespace hil::canopen
