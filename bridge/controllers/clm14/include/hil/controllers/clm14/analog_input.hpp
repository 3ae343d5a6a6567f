// SPDX-License-Identifier: MIT
#pragma once
// One analog input AE1..AE4 of the CLM1.4 (digest §1: 4 inputs ±10 V; §5.6 override; B017 first
// digit: averaging): a moving average over 2^(code + 3) samples (code 0: 8, 1: 16 ... 8: 2048,
// 9: 4096 [decided: the manual's "0: none / 8 values" read as the progression's first step]), one
// sample per NC cycle [decided], in mV. Pure: the caller pushes one sample per cycle. Sums are
// exact integers, so a steady input reads exactly its value and a step reads k/N of it after k
// samples.

#include <cstdint>
#include <vector>

namespace hil::controllers::clm14 {

class AnalogAverage {
 public:
  /// B017 averaging code 0..9 (clamped); the history is filled with `millivolts` (a steady input).
  void reset(int code, int millivolts);
  /// One NC cycle's sample, mV.
  void push(int millivolts) noexcept;
  /// The average of the last N samples, mV.
  [[nodiscard]] double millivolts() const noexcept;
  [[nodiscard]] int code() const noexcept { return code_; }
  [[nodiscard]] std::size_t samples() const noexcept { return history_.size(); }

 private:
  int code_ = -1;
  std::vector<int> history_;  ///< ring buffer of the last N samples
  std::size_t next_ = 0;
  std::int64_t sum_ = 0;
};

/// The override factor of an analog input (§5.6: F = 0 … 1 for 0 … 10 V): clamp(mV / 10000, 0, 1);
/// a negative voltage is 0 [decided].
[[nodiscard]] double analog_override(double millivolts) noexcept;

}  // namespace hil::controllers::clm14
