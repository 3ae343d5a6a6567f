// SPDX-License-Identifier: MIT
#include "hil/serial/serial_stream.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace hil::serial {

SerialStream::SerialStream(std::unique_ptr<RawLine> raw, LineFormat format, Discipline discipline, const Clock& clock)
    : raw_(std::move(raw)), format_(format), discipline_(discipline), clock_(clock) {}

void SerialStream::push_error(LineError e) {
  pending_.push_back(static_cast<std::uint16_t>(0x100U + static_cast<unsigned>(e)));
}

void SerialStream::decode(std::span<const std::uint8_t> raw) {
  const bool seven = format_.data_bits == 7;
  const bool sw_parity = discipline_.software_parity && seven && format_.parity != Parity::none;
  for (std::uint8_t b : raw) {
    if (discipline_.parmrk) {
      if (parmrk_state_ == 1) {
        if (b == 0xFF) {
          parmrk_state_ = 0;  // escaped literal 0xFF
        } else if (b == 0x00) {
          parmrk_state_ = 2;
          continue;
        } else {
          parmrk_state_ = 0;  // not a mark (cannot happen with PARMRK): keep both bytes
          pending_.push_back(0xFF);
        }
      } else if (parmrk_state_ == 2) {
        parmrk_state_ = 0;
        push_error(b == 0x00 ? LineError::break_received : LineError::parity);
        continue;
      } else if (b == 0xFF) {
        parmrk_state_ = 1;
        continue;
      }
    }
    // Flow control bytes are recognised on the wire byte, and for 7-bit formats also without
    // the parity bit, so a plain 0x13 and a parity-carrying 0x93 both stop us.
    if (format_.flow == FlowControl::xon_xoff) {
      const auto m = [&](std::uint8_t flow) { return b == flow || (seven && (b & 0x7F) == (flow & 0x7F)); };
      if (m(format_.xoff)) {
        paused_ = true;
        continue;
      }
      if (m(format_.xon)) {
        paused_ = false;
        continue;
      }
    }
    if (sw_parity && !parity7_ok(b, format_.parity)) {
      push_error(LineError::parity);
      continue;
    }
    pending_.push_back(seven ? static_cast<std::uint8_t>(b & 0x7F) : b);
  }
}

std::error_code SerialStream::fill(Duration timeout) {
  std::array<std::uint8_t, 512> buf{};
  const ReadResult r = raw_->read_some(buf, timeout);
  decode(std::span(buf.data(), r.size));
  const std::uint64_t ov = raw_->overrun_count();
  if (ov > overruns_seen_) {
    overruns_seen_ = ov;
    push_error(LineError::overrun);
  }
  return r.error;
}

ReadResult SerialStream::read_some(std::span<std::uint8_t> buf, Duration timeout) {
  ReadResult out;
  if (buf.empty()) return out;
  const TimePoint deadline = clock_.now() + timeout;
  while (pending_.empty()) {
    const Duration left = std::max(Duration::zero(), deadline - clock_.now());
    const std::error_code ec = fill(left);
    if (!pending_.empty()) break;
    if (ec) {
      out.error = ec;
      return out;
    }
    if (clock_.now() >= deadline) {
      out.error = LineError::timeout;
      return out;
    }
  }
  while (!pending_.empty() && out.size < buf.size()) {
    const std::uint16_t v = pending_.front();
    pending_.pop_front();
    if (v > 0xFF) {
      out.error = static_cast<LineError>(v - 0x100U);
      break;
    }
    buf[out.size++] = static_cast<std::uint8_t>(v);
  }
  received_ += out.size;
  return out;
}

std::uint8_t SerialStream::encode(std::uint8_t c) const noexcept {
  if (format_.data_bits == 7) {
    return discipline_.software_parity ? with_parity7(c, format_.parity) : static_cast<std::uint8_t>(c & 0x7F);
  }
  return c;
}

std::error_code SerialStream::send_flow(bool xon) {
  const std::uint8_t b = xon ? format_.xon : format_.xoff;
  return raw_->write(std::span(&b, 1), Duration{std::chrono::seconds(1)});
}

std::error_code SerialStream::write(std::span<const std::uint8_t> data, Duration timeout) {
  const TimePoint deadline = clock_.now() + timeout;
  if (format_.use_dtr_dsr && !raw_->dsr()) return LineError::dsr_low;
  std::vector<std::uint8_t> chunk;
  std::size_t pos = 0;
  while (pos < data.size()) {
    if (format_.flow == FlowControl::xon_xoff) {
      // Look for XOFF/XON that arrived meanwhile, then wait out a pause.
      if (auto ec = fill(Duration::zero()); ec && ec != LineError::timeout) return ec;
      while (paused_) {
        const TimePoint now = clock_.now();
        if (now >= deadline) return LineError::xoff_stalled;
        if (auto ec = fill(deadline - now); ec && ec != LineError::timeout) return ec;
      }
    }
    const std::size_t n = format_.flow == FlowControl::xon_xoff
                              ? std::min(discipline_.xoff_poll_chunk, data.size() - pos)
                              : data.size() - pos;
    chunk.resize(n);
    for (std::size_t i = 0; i < n; ++i) chunk[i] = encode(data[pos + i]);
    const Duration left = std::max(Duration::zero(), deadline - clock_.now());
    if (auto ec = raw_->write(chunk, left)) return ec;
    pos += n;
    written_ += n;
  }
  return {};
}

namespace {
class LineCategory final : public std::error_category {
 public:
  const char* name() const noexcept override { return "serial-line"; }
  std::string message(int c) const override {
    switch (static_cast<LineError>(c)) {
      case LineError::timeout:
        return "timeout: the device did not answer in time (check cable, baud rate, station)";
      case LineError::parity:
        return "parity error on a received character (check parity/data bits; on a tty also framing)";
      case LineError::framing:
        return "framing error on a received character (check baud rate and stop bits)";
      case LineError::overrun:
        return "overrun: characters were lost (lower the baud rate or enable flow control)";
      case LineError::break_received:
        return "break received: the line was held in the spacing state";
      case LineError::xoff_stalled:
        return "flow control stalled: the device sent XOFF and no XON within the timeout";
      case LineError::closed:
        return "the line was closed by the peer";
      case LineError::dsr_low:
        return "DSR is not asserted: the device is not ready (check cable and power)";
      case LineError::cts_stalled:
        return "CTS stayed low: the device did not accept data within the timeout";
      case LineError::io:
        return "I/O error on the serial port";
    }
    return "unknown serial line error";
  }
};
}  // namespace

const std::error_category& line_category() noexcept {
  static const LineCategory cat;
  return cat;
}

}  // namespace hil::serial
