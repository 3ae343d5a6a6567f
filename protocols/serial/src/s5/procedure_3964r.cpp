// SPDX-License-Identifier: MIT
#include "hil/serial/s5/procedure_3964r.hpp"

namespace hil::serial::s5 {

namespace {
class Category final : public std::error_category {
 public:
  const char* name() const noexcept override { return "3964r"; }
  std::string message(int c) const override {
    switch (static_cast<ProcedureError>(c)) {
      case ProcedureError::no_connection:
        return "3964R: partner did not answer STX with DLE (check cable, baud rate, partner running)";
      case ProcedureError::not_acknowledged:
        return "3964R: block not acknowledged after all attempts (noise or partner busy)";
      case ProcedureError::char_timeout:
        return "3964R: character delay time exceeded inside a block";
      case ProcedureError::bcc_error:
        return "3964R: block check character wrong";
      case ProcedureError::framing:
        return "3964R: DLE followed by an unexpected character";
      case ProcedureError::block_too_long:
        return "3964R: block longer than the receive buffer";
    }
    return "3964R error";
  }
};
}  // namespace

const std::error_category& procedure_category() noexcept {
  static const Category c;
  return c;
}

std::vector<std::uint8_t> make_block(const std::vector<std::uint8_t>& payload, bool with_bcc) {
  std::vector<std::uint8_t> w;
  w.reserve(payload.size() + 4);
  for (std::uint8_t b : payload) {
    w.push_back(b);
    if (b == dle) w.push_back(dle);
  }
  w.push_back(dle);
  w.push_back(etx);
  if (with_bcc) {
    std::uint8_t bcc = 0;
    for (std::uint8_t b : w) bcc ^= b;
    w.push_back(bcc);
  }
  return w;
}

void Procedure3964::send(std::vector<std::uint8_t> payload) {
  queue_.push_back(std::move(payload));
}

std::optional<std::vector<std::uint8_t>> Procedure3964::take_received() {
  if (received_.empty()) return std::nullopt;
  auto v = std::move(received_.front());
  received_.pop_front();
  return v;
}

std::optional<Procedure3964::SendResult> Procedure3964::take_send_result() {
  if (results_.empty()) return std::nullopt;
  auto r = results_.front();
  results_.pop_front();
  return r;
}

void Procedure3964::start_connect(TimePoint now) {
  out_.push_back(stx);
  state_ = State::tx_wait_dle;
  deadline_ = now + o_.ack_timeout;
  ++connect_tries_;
}

void Procedure3964::start_receive(TimePoint now) {
  out_.push_back(dle);
  state_ = State::rx_data;
  rx_.clear();
  rx_bcc_ = 0;
  rx_dle_ = false;
  deadline_ = now + o_.char_timeout;
}

void Procedure3964::rx_fail(ProcedureError e) {
  out_.push_back(nak);
  rx_errors_.push_back(e);
  state_ = State::idle;
  deadline_ = TimePoint::max();
}

void Procedure3964::tx_retry(TimePoint now, bool connect_phase) {
  const bool exhausted =
      connect_phase ? connect_tries_ >= o_.connect_attempts : transmit_tries_ >= o_.transmit_attempts;
  if (exhausted) {
    results_.push_back(
        SendResult{false, connect_phase ? ProcedureError::no_connection : ProcedureError::not_acknowledged});
    queue_.pop_front();
    connect_tries_ = 0;
    transmit_tries_ = 0;
    state_ = State::idle;
    deadline_ = TimePoint::max();
    return;
  }
  ++retries_;
  // Wait one character delay time before the next attempt (lets a receiver time out first).
  state_ = State::idle;
  deadline_ = now + o_.char_timeout;
}

void Procedure3964::on_bytes(std::span<const std::uint8_t> bytes, TimePoint now) {
  for (std::uint8_t b : bytes) {
    switch (state_) {
      case State::idle:
        if (b == stx) start_receive(now);
        // anything else on an idle line is noise: ignored
        break;
      case State::tx_wait_dle:
        if (b == dle) {
          const auto w = make_block(queue_.front(), o_.with_bcc);
          out_.insert(out_.end(), w.begin(), w.end());
          ++transmit_tries_;
          connect_tries_ = 0;
          state_ = State::tx_wait_ack;
          deadline_ = now + o_.ack_timeout;
        } else if (b == stx) {
          // Initialisation conflict: the lower priority side defers and receives first.
          if (!o_.high_priority) {
            --connect_tries_;
            start_receive(now);
          }
        } else {
          tx_retry(now, true);
        }
        break;
      case State::tx_wait_ack:
        if (b == dle) {
          results_.push_back(SendResult{true, {}});
          queue_.pop_front();
          connect_tries_ = 0;
          transmit_tries_ = 0;
          state_ = State::idle;
          deadline_ = TimePoint::max();
        } else {
          // NAK or garbage: repeat the whole block (connection set-up included).
          tx_retry(now, false);
        }
        break;
      case State::rx_data:
        deadline_ = now + o_.char_timeout;
        rx_bcc_ ^= b;
        if (rx_dle_) {
          rx_dle_ = false;
          if (b == dle) {
            rx_.push_back(dle);
          } else if (b == etx) {
            if (o_.with_bcc) {
              state_ = State::rx_bcc;
            } else {
              out_.push_back(dle);
              received_.push_back(std::exchange(rx_, {}));
              state_ = State::idle;
              deadline_ = TimePoint::max();
            }
          } else {
            rx_fail(ProcedureError::framing);
          }
        } else if (b == dle) {
          rx_dle_ = true;
        } else {
          rx_.push_back(b);
        }
        if (state_ == State::rx_data && rx_.size() > o_.max_block) rx_fail(ProcedureError::block_too_long);
        break;
      case State::rx_bcc:
        if (b == rx_bcc_) {
          out_.push_back(dle);
          received_.push_back(std::exchange(rx_, {}));
          state_ = State::idle;
          deadline_ = TimePoint::max();
        } else {
          rx_fail(ProcedureError::bcc_error);
        }
        break;
    }
  }
  poll(now);
}

void Procedure3964::poll(TimePoint now) {
  if (now >= deadline_) {
    switch (state_) {
      case State::tx_wait_dle:
        tx_retry(now, true);
        break;
      case State::tx_wait_ack:
        tx_retry(now, false);
        break;
      case State::rx_data:
      case State::rx_bcc:
        rx_fail(ProcedureError::char_timeout);
        break;
      case State::idle:
        deadline_ = TimePoint::max();
        break;  // retry delay over
    }
  }
  if (state_ == State::idle && !queue_.empty() && deadline_ == TimePoint::max()) start_connect(now);
}

}  // namespace hil::serial::s5
