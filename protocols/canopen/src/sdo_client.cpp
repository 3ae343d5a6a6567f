// SPDX-License-Identifier: MIT
#include "hil/canopen/sdo_client.hpp"

#include <algorithm>

#include "hil/canopen/crc16.hpp"

namespace hil::canopen {

SdoClient::SdoClient(NodeId server, FrameSink sink, SdoClientOptions options)
    : node_(server),
      sink_(std::move(sink)),
      options_(options),
      tx_cob_(cob_sdo_rx_base + server),
      rx_cob_(cob_sdo_tx_base + server) {}

void SdoClient::async_upload(std::uint16_t index, std::uint8_t sub, TimePoint now, SdoCompletion done) {
  queue_.push_back(Request{true, index, sub, {}, std::move(done)});
  start(now);
}

void SdoClient::async_download(std::uint16_t index, std::uint8_t sub, std::vector<std::uint8_t> data, TimePoint now,
                               SdoCompletion done) {
  queue_.push_back(Request{false, index, sub, std::move(data), std::move(done)});
  start(now);
}

void SdoClient::start(TimePoint now) {
  if (active_ || queue_.empty()) return;
  current_ = std::move(queue_.front());
  queue_.pop_front();
  active_ = true;
  attempts_left_ = options_.retries;
  restart_current(now);
}

void SdoClient::send(std::initializer_list<std::uint8_t> bytes, TimePoint now) {
  can::Frame f = frame_of(tx_cob_, bytes);
  f.dlc = 8;
  deadline_ = now + options_.timeout;
  sink_(f);
}

void SdoClient::send_abort(SdoAbort code) {
  can::Frame f;
  f.id = tx_cob_;
  f.dlc = 8;
  f.data[0] = 0x80;
  put_le16(&f.data[1], current_.index);
  f.data[3] = current_.sub;
  put_le32(&f.data[4], static_cast<std::uint32_t>(code));
  sink_(f);
}

void SdoClient::restart_current(TimePoint now) {
  toggle_ = false;
  offset_ = 0;
  size_ = 0;
  size_known_ = false;
  rx_.clear();
  seq_error_ = false;
  last_segment_ = false;
  expected_seq_ = 1;
  sent_in_block_ = 0;
  const auto lo = static_cast<std::uint8_t>(current_.index);
  const auto hi = static_cast<std::uint8_t>(current_.index >> 8);
  const auto sub = current_.sub;
  if (current_.upload) {
    if (options_.block) {
      phase_ = Phase::block_upload_initiate;
      const auto pst = static_cast<std::uint8_t>(std::min<std::size_t>(options_.block_threshold, 255));
      const auto blk = static_cast<std::uint8_t>(std::clamp<int>(options_.block_size, 1, 127));
      return send({0xA4, lo, hi, sub, blk, pst, 0, 0}, now);
    }
    phase_ = Phase::upload_initiate;
    return send({0x40, lo, hi, sub, 0, 0, 0, 0}, now);
  }
  const auto& d = current_.data;
  size_ = d.size();
  if (!d.empty() && d.size() <= 4) {
    phase_ = Phase::download_initiate;
    can::Frame f =
        frame_of(tx_cob_, {static_cast<std::uint8_t>(0x23 | ((4 - d.size()) << 2)), lo, hi, sub, 0, 0, 0, 0});
    std::copy(d.begin(), d.end(), f.data.begin() + 4);
    deadline_ = now + options_.timeout;
    return sink_(f);
  }
  can::Frame f = frame_of(tx_cob_, {0x21, lo, hi, sub, 0, 0, 0, 0});
  if (options_.block && d.size() > options_.block_threshold) {
    phase_ = Phase::block_download_initiate;
    f.data[0] = 0xC6;
  } else {
    phase_ = Phase::download_initiate;
  }
  put_le32(&f.data[4], static_cast<std::uint32_t>(d.size()));
  deadline_ = now + options_.timeout;
  sink_(f);
}

void SdoClient::complete(std::error_code ec, TimePoint now) {
  Request req = std::move(current_);
  current_ = Request{};
  active_ = false;
  std::vector<std::uint8_t> data;
  if (req.upload && !ec) data = std::move(rx_);
  rx_.clear();
  if (req.done) req.done(ec, std::move(data));
  start(now);
}

void SdoClient::fail(std::error_code ec, bool send_abort_frame, SdoAbort code, TimePoint now) {
  if (send_abort_frame) send_abort(code);
  complete(ec, now);
}

void SdoClient::cancel_all(SdoAbort reason, TimePoint now) {
  auto pending = std::move(queue_);
  queue_.clear();
  if (active_) {
    send_abort(reason);
    Request req = std::move(current_);
    active_ = false;
    if (req.done) req.done(make_error_code(reason), {});
  }
  for (auto& r : pending)
    if (r.done) r.done(make_error_code(reason), {});
  (void)now;
}

void SdoClient::step(TimePoint now) {
  if (!active_ || now < deadline_) return;
  send_abort(SdoAbort::timeout);
  if (attempts_left_ > 0) {
    --attempts_left_;
    return restart_current(now);
  }
  complete(make_error_code(SdoAbort::timeout), now);
}

void SdoClient::report_progress() {
  if (progress_) progress_(current_.upload ? rx_.size() : offset_, size_known_ || !current_.upload ? size_ : 0);
}

bool SdoClient::on_frame(const can::Frame& f, TimePoint now) {
  if (f.id != rx_cob_ || f.extended || f.rtr || f.error) return false;
  if (!active_ || f.dlc == 0) return true;
  const std::uint8_t b0 = f.data[0];
  if (b0 == 0x80) {
    // Abort from the server. A short abort frame still aborts, with a general error.
    const std::uint32_t code = f.dlc >= 8 ? get_le32(&f.data[4]) : static_cast<std::uint32_t>(SdoAbort::general);
    complete(std::error_code(static_cast<int>(code), sdo_category()), now);
    return true;
  }
  switch (phase_) {
    case Phase::upload_initiate:
    case Phase::upload_segment:
      on_upload(f, now);
      break;
    case Phase::download_initiate:
    case Phase::download_segment:
      on_download(f, now);
      break;
    case Phase::block_download_initiate:
    case Phase::block_download_ack:
    case Phase::block_download_end:
      on_block_download(f, now);
      break;
    case Phase::block_upload_initiate:
    case Phase::block_upload_data:
    case Phase::block_upload_end:
      on_block_upload(f, now);
      break;
  }
  return true;
}

namespace {
bool mux_matches(const can::Frame& f, std::uint16_t index, std::uint8_t sub) {
  return f.dlc >= 4 && get_le16(&f.data[1]) == index && f.data[3] == sub;
}
}  // namespace

void SdoClient::on_upload(const can::Frame& f, TimePoint now) {
  const std::uint8_t b0 = f.data[0];
  const auto protocol_error = [&] {
    fail(make_error_code(SdoAbort::command_specifier), true, SdoAbort::command_specifier, now);
  };
  if (phase_ == Phase::upload_initiate) {
    if ((b0 >> 5) != 2) return protocol_error();
    if (!mux_matches(f, current_.index, current_.sub)) return;  // stale answer of an earlier attempt
    if (b0 & 0x02) {
      std::size_t n = (b0 & 0x01) ? 4u - ((b0 >> 2) & 0x03) : std::min<std::size_t>(4, f.dlc - 4u);
      if (f.dlc < 4 + n) return protocol_error();
      rx_.assign(f.data.begin() + 4, f.data.begin() + 4 + static_cast<std::ptrdiff_t>(n));
      return complete({}, now);
    }
    if (f.dlc < 8) return protocol_error();
    size_known_ = (b0 & 0x01) != 0;
    size_ = size_known_ ? get_le32(&f.data[4]) : 0;
    phase_ = Phase::upload_segment;
    toggle_ = false;
    return send({0x60, 0, 0, 0, 0, 0, 0, 0}, now);
  }
  if ((b0 >> 5) != 0) return protocol_error();
  const bool t = (b0 & 0x10) != 0;
  if (t != toggle_) return fail(make_error_code(SdoAbort::toggle_bit), true, SdoAbort::toggle_bit, now);
  const std::size_t len = 7u - ((b0 >> 1) & 0x07);
  if (f.dlc < 1 + len) return protocol_error();
  rx_.insert(rx_.end(), f.data.begin() + 1, f.data.begin() + 1 + static_cast<std::ptrdiff_t>(len));
  if (size_known_ && rx_.size() > size_)
    return fail(make_error_code(SdoAbort::length_too_high), true, SdoAbort::length_too_high, now);
  report_progress();
  if (b0 & 0x01) {
    if (size_known_ && rx_.size() != size_)
      return fail(make_error_code(SdoAbort::length_too_low), true, SdoAbort::length_too_low, now);
    return complete({}, now);
  }
  toggle_ = !toggle_;
  send({static_cast<std::uint8_t>(0x60 | (toggle_ ? 0x10 : 0x00)), 0, 0, 0, 0, 0, 0, 0}, now);
}

void SdoClient::send_download_segment(TimePoint now) {
  const auto& d = current_.data;
  const std::size_t len = std::min<std::size_t>(7, d.size() - offset_);
  const bool last = offset_ + len >= d.size();
  can::Frame f;
  f.id = tx_cob_;
  f.dlc = 8;
  f.data[0] = static_cast<std::uint8_t>((toggle_ ? 0x10 : 0x00) | ((7 - len) << 1) | (last ? 1 : 0));
  std::copy_n(d.begin() + static_cast<std::ptrdiff_t>(offset_), len, f.data.begin() + 1);
  offset_ += len;
  last_segment_ = last;
  deadline_ = now + options_.timeout;
  sink_(f);
}

void SdoClient::on_download(const can::Frame& f, TimePoint now) {
  const std::uint8_t b0 = f.data[0];
  if (phase_ == Phase::download_initiate) {
    if (b0 != 0x60) return fail(make_error_code(SdoAbort::command_specifier), true, SdoAbort::command_specifier, now);
    if (!mux_matches(f, current_.index, current_.sub)) return;
    if (!current_.data.empty() && current_.data.size() <= 4) return complete({}, now);
    phase_ = Phase::download_segment;
    toggle_ = false;
    return send_download_segment(now);
  }
  if ((b0 & 0xEF) != 0x20)
    return fail(make_error_code(SdoAbort::command_specifier), true, SdoAbort::command_specifier, now);
  if (((b0 & 0x10) != 0) != toggle_)
    return fail(make_error_code(SdoAbort::toggle_bit), true, SdoAbort::toggle_bit, now);
  report_progress();
  if (last_segment_) return complete({}, now);
  toggle_ = !toggle_;
  send_download_segment(now);
}

void SdoClient::send_download_block(TimePoint now) {
  const auto& d = current_.data;
  std::size_t off = offset_;
  sent_in_block_ = 0;
  last_segment_ = false;
  for (std::uint8_t seq = 1; seq <= blksize_; ++seq) {
    const std::size_t len = std::min<std::size_t>(7, d.size() - off);
    const bool last = off + len >= d.size();
    can::Frame f;
    f.id = tx_cob_;
    f.dlc = 8;
    f.data[0] = static_cast<std::uint8_t>(seq | (last ? 0x80 : 0x00));
    std::copy_n(d.begin() + static_cast<std::ptrdiff_t>(off), len, f.data.begin() + 1);
    off += len;
    sent_in_block_ = seq;
    sink_(f);
    if (last) {
      last_segment_ = true;
      break;
    }
  }
  deadline_ = now + options_.timeout;
}

void SdoClient::on_block_download(const can::Frame& f, TimePoint now) {
  const std::uint8_t b0 = f.data[0];
  const auto protocol_error = [&] {
    fail(make_error_code(SdoAbort::command_specifier), true, SdoAbort::command_specifier, now);
  };
  switch (phase_) {
    case Phase::block_download_initiate:
      if ((b0 & 0xFB) != 0xA0) return protocol_error();
      if (!mux_matches(f, current_.index, current_.sub)) return;
      server_crc_ = (b0 & 0x04) != 0;
      blksize_ = f.data[4];
      if (blksize_ < 1 || blksize_ > 127)
        return fail(make_error_code(SdoAbort::block_size), true, SdoAbort::block_size, now);
      offset_ = 0;
      phase_ = Phase::block_download_ack;
      return send_download_block(now);
    case Phase::block_download_ack: {
      if (b0 != 0xA2) return protocol_error();
      const std::uint8_t ackseq = f.data[1];
      if (ackseq > sent_in_block_)
        return fail(make_error_code(SdoAbort::sequence_number), true, SdoAbort::sequence_number, now);
      if (f.data[2] < 1 || f.data[2] > 127)
        return fail(make_error_code(SdoAbort::block_size), true, SdoAbort::block_size, now);
      const bool all = last_segment_ && ackseq == sent_in_block_;
      offset_ = std::min(current_.data.size(), offset_ + std::size_t{ackseq} * 7);
      blksize_ = f.data[2];
      report_progress();
      if (!all) return send_download_block(now);
      const auto& d = current_.data;
      const std::size_t rem = d.size() % 7;
      const auto unused = static_cast<std::uint8_t>(d.empty() ? 7 : (rem == 0 ? 0 : 7 - rem));
      const std::uint16_t crc = server_crc_ ? crc16_ccitt(d) : 0;
      phase_ = Phase::block_download_end;
      return send({static_cast<std::uint8_t>(0xC1 | (unused << 2)), static_cast<std::uint8_t>(crc),
                   static_cast<std::uint8_t>(crc >> 8), 0, 0, 0, 0, 0},
                  now);
    }
    case Phase::block_download_end:
      if (b0 != 0xA1) return protocol_error();
      return complete({}, now);
    default:
      return protocol_error();
  }
}

void SdoClient::on_block_upload(const can::Frame& f, TimePoint now) {
  const std::uint8_t b0 = f.data[0];
  const auto protocol_error = [&] {
    fail(make_error_code(SdoAbort::command_specifier), true, SdoAbort::command_specifier, now);
  };
  switch (phase_) {
    case Phase::block_upload_initiate:
      if ((b0 >> 5) == 2) {  // the server switched to the normal upload protocol (pst)
        phase_ = Phase::upload_initiate;
        return on_upload(f, now);
      }
      if ((b0 & 0xF9) != 0xC0) return protocol_error();
      if (!mux_matches(f, current_.index, current_.sub)) return;
      server_crc_ = (b0 & 0x04) != 0;
      size_known_ = (b0 & 0x02) != 0;
      size_ = size_known_ ? get_le32(&f.data[4]) : 0;
      blksize_ = static_cast<std::uint8_t>(std::clamp<int>(options_.block_size, 1, 127));
      expected_seq_ = 1;
      phase_ = Phase::block_upload_data;
      return send({0xA3, 0, 0, 0, 0, 0, 0, 0}, now);
    case Phase::block_upload_data: {
      const std::uint8_t seq = b0 & 0x7F;
      const bool last = (b0 & 0x80) != 0;
      if (seq == 0 || seq > blksize_)
        return fail(make_error_code(SdoAbort::sequence_number), true, SdoAbort::sequence_number, now);
      deadline_ = now + options_.timeout;
      if (!seq_error_ && seq == expected_seq_) {
        rx_.insert(rx_.end(), f.data.begin() + 1, f.data.begin() + 8);
        if (size_known_ && rx_.size() > (size_ == 0 ? 7 : (size_ + 6) / 7 * 7))
          return fail(make_error_code(SdoAbort::length_too_high), true, SdoAbort::length_too_high, now);
        ++expected_seq_;
        last_segment_ = last;
      } else {
        seq_error_ = true;
      }
      if (seq == blksize_ || last) {
        const auto ackseq = static_cast<std::uint8_t>(expected_seq_ - 1);
        if (last_segment_ && !seq_error_) phase_ = Phase::block_upload_end;
        expected_seq_ = 1;
        seq_error_ = false;
        report_progress();
        send({0xA2, ackseq, blksize_, 0, 0, 0, 0, 0}, now);
      }
      return;
    }
    case Phase::block_upload_end: {
      if ((b0 & 0xE3) != 0xC1) return protocol_error();
      const std::size_t unused = (b0 >> 2) & 0x07;
      if (unused > rx_.size())
        return fail(make_error_code(SdoAbort::length_too_low), true, SdoAbort::length_too_low, now);
      rx_.resize(rx_.size() - unused);
      if (size_known_ && rx_.size() != size_) {
        const auto a = rx_.size() > size_ ? SdoAbort::length_too_high : SdoAbort::length_too_low;
        return fail(make_error_code(a), true, a, now);
      }
      if (server_crc_ && crc16_ccitt(rx_) != get_le16(&f.data[1]))
        return fail(make_error_code(SdoAbort::crc), true, SdoAbort::crc, now);
      can::Frame r = frame_of(tx_cob_, {0xA1, 0, 0, 0, 0, 0, 0, 0});
      sink_(r);
      return complete({}, now);
    }
    default:
      return protocol_error();
  }
}

}  // namespace hil::canopen
