// SPDX-License-Identifier: MIT
// The controller runtime's cyclic cost: one I/O image cycle with 1024 bits and 64 sources, and
// one controller cycle (Controller::step) with 8 axes and no program (target < 1 µs).
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "hil/controllers/controller.hpp"
#include "hil/mocks/sim_drive.hpp"
#include "hil/profiles/loader.hpp"

namespace {

using namespace hil::controllers;

/// Writes two input bytes (16 bits) per cycle from a counter.
struct CounterSource final : IoSource {
  std::uint32_t byte;
  std::uint8_t n = 0;
  explicit CounterSource(std::uint32_t b) : byte(b) {}
  void read(hil::TimePoint, IoImage& image) noexcept override {
    ++n;
    image.set(ByteAddress{IoArea::input, byte}, n);
    image.set(BitAddress{IoArea::input, byte + 1, 3}, (n & 1U) != 0);
  }
};

struct Xor final : IoSink {
  std::uint8_t acc = 0;
  void write(hil::TimePoint, const IoImage& image) noexcept override {
    for (auto b : image.bytes(IoArea::output)) acc = static_cast<std::uint8_t>(acc ^ b);
  }
};

void BM_IoImageCycle_1024bits_64sources(benchmark::State& state) {
  IoImage io(IoLayout{{64, 32, 32, 0}});  // 128 bytes = 1024 bits
  std::vector<std::unique_ptr<CounterSource>> sources;
  for (std::uint32_t i = 0; i < 64; ++i) {
    sources.push_back(std::make_unique<CounterSource>((i * 2) % 64));
    io.attach(*sources.back());
  }
  Xor sink;
  io.attach(sink);
  hil::TimePoint now{};
  for (auto _ : state) {
    now += std::chrono::milliseconds(1);
    io.read_inputs(now);
    if (io.rising(BitAddress{IoArea::input, 1, 3})) io.set(BitAddress{IoArea::output, 0, 0}, true);
    io.write_outputs(now);
  }
  benchmark::DoNotOptimize(sink.acc);
}
BENCHMARK(BM_IoImageCycle_1024bits_64sources);

class NoProgram final : public Controller {
 public:
  explicit NoProgram(std::shared_ptr<const hil::profiles::Profile> p)
      : Controller(std::move(p), {}, IoLayout{{8, 8, 1, 0}}, std::chrono::milliseconds(4)) {
    for (int i = 0; i < 8; ++i) {
      ControllerAxis a;
      a.name = std::to_string(i);
      a.config.name = a.name;
      a.config.inc_per_unit = {1000, 1};
      a.config.limits = {100.0, 1000.0};
      a.config.quick_stop_deceleration = 5000.0;
      a.config.jog_velocity = 10.0;
      a.config.following_error.static_window = 5.0;
      a.config.standstill_window = 1.0;
      a.config.in_position_window = 0.1;
      const auto byte = static_cast<std::uint32_t>(i);
      a.limit_switches = {BitAddress{IoArea::input, byte, 0}, BitAddress{IoArea::input, byte, 1}, false};
      add_axis(std::move(a));
    }
  }

 protected:
  void on_cycle(const hil::CycleTime&) noexcept override {}
  std::optional<DeviceErrorCode> map_axis_fault(std::size_t, const hil::Fault&,
                                                const hil::motion::AxisStatus&) const noexcept override {
    return std::nullopt;
  }
};

void BM_ControllerCycle_8axes_noprogram(benchmark::State& state) {
  auto profile = hil::profiles::find_profile("wf725-726");
  if (!profile) {
    state.SkipWithError("wf725-726 profile not found");
    return;
  }
  NoProgram ctl(*profile);
  std::vector<std::unique_ptr<hil::motion::Axis>> axes;
  std::vector<hil::motion::Axis*> raw;
  for (const auto& spec : ctl.axis_specs()) {
    axes.push_back(std::make_unique<hil::motion::Axis>(
        spec.config, std::make_unique<hil::mocks::SimDrive>(hil::mocks::SimDriveConfig{})));
    raw.push_back(axes.back().get());
  }
  if (!ctl.bind_axes(raw)) {
    state.SkipWithError("bind_axes failed");
    return;
  }
  hil::TimePoint now{};
  for (auto _ : state) {
    now += std::chrono::milliseconds(4);
    benchmark::DoNotOptimize(ctl.step(hil::CycleTime{now, std::chrono::milliseconds(4)}));
  }
}
BENCHMARK(BM_ControllerCycle_8axes_noprogram);

}  // namespace
