// SPDX-License-Identifier: MIT
#pragma once
// One serial line with 1 (RS-232) or up to 32 (RS-485 multi-drop) emulated CLM1.4 stations.
// Splits the byte stream into telegrams, hands each line to every station (only the addressed
// one answers), and turns character errors (parity, framing, overrun) into the device's
// "RS Format Error" (02) for the telegram they hit. An RS-485 station holds its answer for its
// B005 response delay (DDD ms); answers leave in the order the requests came.

#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "hil/mocks/legacy/clm14_station.hpp"
#include "hil/mocks/legacy/endpoint.hpp"

namespace hil::mocks::legacy {

class Clm14Line final : public Endpoint {
 public:
  /// `stations` = 0: one RS-232 station; 1..32: RS-485 stations 1..N on one line.
  Clm14Line(std::shared_ptr<const serial::clm14::DeviceData> data, int stations, int axes = 2);

  std::string on_bytes(std::span<const std::uint8_t> data, TimePoint now) override;
  std::string on_line_error(std::error_code ec, TimePoint now) override;
  std::string on_idle(TimePoint now) override;
  [[nodiscard]] TimePoint next_deadline() const override;
  bool take_dirty() override;
  std::string save_state() const override;
  /// Restore from save_state() text; on error the stations keep their defaults.
  std::expected<void, std::string> load_state(const std::string& text);

  void set_mode(ClmMode m);
  [[nodiscard]] std::size_t size() const noexcept { return stations_.size(); }
  [[nodiscard]] Clm14Station& station(std::size_t i) { return *stations_.at(i); }
  /// Lines received in total (for tests and the emulator's log).
  [[nodiscard]] std::uint64_t lines() const noexcept { return lines_; }

 private:
  std::vector<std::unique_ptr<Clm14Station>> stations_;
  serial::clm14::LineSplitter splitter_;
  bool line_corrupt_ = false;
  std::uint64_t lines_ = 0;
  struct Held {
    TimePoint due;
    std::string bytes;
  };
  std::deque<Held> held_;  ///< answers waiting for their station's response delay, in order
  /// `bytes` from `station` answering at `now`: out now, or held behind earlier ones.
  void answer(const Clm14Station& station, std::string bytes, TimePoint now, std::string& out);
};

}  // namespace hil::mocks::legacy
