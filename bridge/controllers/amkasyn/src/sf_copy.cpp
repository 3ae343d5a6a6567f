// SPDX-License-Identifier: MIT
// SF COPY (type 0, manual §3.1): DCOPY, ECOPY, SIDIFF.
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>

#include "hil/controllers/amkasyn/sf_types.hpp"

namespace hil::controllers::amkasyn {
namespace {

class Copy final : public FastFunction {
 public:
  std::optional<SfFault> start(const DataBlock& cmd, const InitDb& init, SfIo& io) override {
    fct_ = cmd.dl(0);
    ba_ = cmd.dl(1);
    switch (fct_) {
      case 1:  // DCOPY
        if (ba_ > 1) return start_error("DCOPY", "DL1 BA", ba_, "must be 0 (absolute) or 1 (incremental, from V02.11)");
        if (init.sink.address == 0) return start_error("DCOPY", "sink address", 0, "DCOPY needs a sink");
        acc_ = io.sink_now;  // incremental copy sums from the sink value at START
        prev_lo_ = static_cast<std::int16_t>(io.source.value & 0xFFFF);
        // A 32-bit AZ message copied into an MD takes its zero-pulse latch along.
        latch_from_ = init.source.address == 0 && init.source.offset >= 16 && init.source.offset <= 22
                          ? (init.source.offset - 16) / 2
                          : -1;
        latch_to_ = init.sink.address == 129 && ba_ == 0 ? init.sink.offset / 4 : -1;
        return std::nullopt;
      case 2:  // ECOPY
        if (ba_ > 3) return start_error("ECOPY", "DL1 BA", ba_, "bit0/bit1 select parameter copying: 0..3");
        value0_ = cmd.dd(2);
        value1_ = cmd.dd(4);
        return std::nullopt;
      case 255:  // SIDIFF
        return start_sidiff(cmd, io);
      default:
        return start_error("COPY", "DL0 fct", fct_, "must be 1 DCOPY, 2 ECOPY or 255 SIDIFF");
    }
  }

  std::optional<SfFault> value_new(const DataBlock& cmd, SfIo& io) override {
    if (fct_ == 2) {
      value0_ = cmd.dd(2);
      value1_ = cmd.dd(4);
      return std::nullopt;
    }
    if (fct_ == 255) {
      if (auto f = start_sidiff(cmd, io)) return f;
      return std::nullopt;
    }
    return FastFunction::value_new(cmd, io);
  }

  void step(SfIo& io) noexcept override {
    switch (fct_) {
      case 1:
        if (ba_ == 0) {
          io.sink = io.source.value;
          if (latch_from_ >= 0 && latch_to_ >= 0)
            io.image.md_zero[static_cast<std::size_t>(latch_to_)] =
                io.image.az_zero[static_cast<std::size_t>(latch_from_)];
        } else {
          const auto lo = static_cast<std::int16_t>(io.source.value & 0xFFFF);
          acc_ += static_cast<std::int16_t>(static_cast<std::uint16_t>(lo - prev_lo_));
          prev_lo_ = lo;
          io.sink = static_cast<std::int32_t>(acc_);
        }
        break;
      case 2: {
        const bool e1 = io.e(1);
        io.a(1, e1);  // A1 = E1, output together with the copied value
        const bool use_param = e1 ? (ba_ & 2) != 0 : (ba_ & 1) != 0;
        io.sink = use_param ? (e1 ? value1_ : value0_) : io.source.value;
        break;
      }
      case 255:
        step_sidiff(io);
        break;
      default:
        break;
    }
  }

 private:
  std::optional<SfFault> start_sidiff(const DataBlock& cmd, SfIo& io) {
    aw_mask_ = cmd.dr(2);
    display_ = cmd.dr(3);
    if (display_ > 8) return start_error("SIDIFF", "DR3 AW number", display_, "0 (no display) or 1..8");
    mean_n_ = cmd.dr(4) == 0 ? 10 : cmd.dr(4);
    agree_ = cmd.dr(5) == 0 ? 5 : cmd.dr(5);
    sixteen_ = (cmd.dl(1) & 1) != 0;
    const DataBlock* tab0 = (*io.tables)[0];
    for (int n = 0; n < 8; ++n) {
      auto& m = mon_[static_cast<std::size_t>(n)];
      m = Monitor{};
      m.threshold = 100;  // without Tab0: 100 increments, ratio 1:1 (§3.1.4)
      if (tab0) {
        const std::size_t b = static_cast<std::size_t>(6 * n);
        m.threshold = tab0->dw(b);
        if (m.threshold < 0) return start_error("SIDIFF", "Tab0 threshold", m.threshold, "0..32767 increments");
        const std::int64_t div = tab0->dd(b + 2), mul = tab0->dd(b + 4);
        if (div != 0 && div < 65536)
          return start_error("SIDIFF", "Tab0 command value divider", div, "0 (= 1) or 2^16..2^31-1 (as ID 32892)");
        m.divider = div == 0 ? 1 : div;
        m.multiplier = mul == 0 ? 1 : mul;
      }
    }
    return std::nullopt;
  }

  void step_sidiff(SfIo& io) noexcept {
    // Output bits are fixed: AW1..AW8 -> bit 0..7 of the output byte (whatever the mask); the
    // runtime writes the SF's bits from A1 on, so the mask must be bit 0 for a faithful mapping.
    for (int n = 0; n < 8; ++n) {
      if (((aw_mask_ >> n) & 1) == 0) continue;
      auto& m = mon_[static_cast<std::size_t>(n)];
      const std::int32_t raw = io.image.aw[static_cast<std::size_t>(n)].message32;  // ID 32786 = 32824
      const std::int32_t fe = sixteen_ ? static_cast<std::int16_t>(raw & 0xFFFF) : raw;
      // Remove the part of the following error the SAK lead of the commanding FIPW/FIPZ/VARSYNC
      // put there (command units, through the drive's synchronous ratio).
      const std::int64_t sak = io.image.aw[static_cast<std::size_t>(n)].sak_part;
      const std::int64_t part = sak * m.multiplier / m.divider;
      const auto e = static_cast<std::int64_t>(fe) - part;
      m.sum += e - m.hist[m.i];
      m.hist[m.i] = e;
      m.i = (m.i + 1) % mean_n_;
      if (m.filled < mean_n_) ++m.filled;
      const double mean = static_cast<double>(m.sum) / m.filled;
      const bool exceed = std::fabs(mean) > m.threshold;
      if (exceed != m.bit) {
        if (++m.count >= agree_) {
          m.bit = exceed;
          m.count = 0;
        }
      } else {
        m.count = 0;
      }
      io.a(n + 1, m.bit);
      if (display_ == n + 1) io.sink = static_cast<std::int32_t>(std::lround(mean));
    }
  }

  struct Monitor {
    std::int64_t hist[255] = {};
    std::int64_t sum = 0;
    int i = 0, filled = 0, count = 0;
    int threshold = 100;
    std::int64_t divider = 1, multiplier = 1;
    bool bit = false;
  };
  int fct_ = 0, ba_ = 0, latch_from_ = -1, latch_to_ = -1;
  std::int64_t acc_ = 0;
  std::int16_t prev_lo_ = 0;
  std::int32_t value0_ = 0, value1_ = 0;
  std::uint8_t aw_mask_ = 0;
  int display_ = 0, mean_n_ = 10, agree_ = 5;
  bool sixteen_ = false;
  std::array<Monitor, 8> mon_{};
};

}  // namespace

std::unique_ptr<FastFunction> make_copy() {
  return std::make_unique<Copy>();
}

}  // namespace hil::controllers::amkasyn
