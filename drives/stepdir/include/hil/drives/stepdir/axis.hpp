// SPDX-License-Identifier: MIT
#pragma once
// Per-axis resources of the stepdir transport: the lines (mock or libgpiod), the verifying sink,
// the mock switches wired to the steps output (closed loop in simulation).

#include <memory>
#include <string>

#include "hil/drives/stepdir/config.hpp"
#include "hil/drives/stepdir/transport_factory.hpp"
#include "hil/gpio/edge_sink.hpp"
#include "hil/gpio/io/edge_writer.hpp"
#include "hil/gpio/line_bank.hpp"
#include "hil/mocks/gpio/mock_lines.hpp"
#include "hil/stepdir/verifier.hpp"

namespace hil::drives::stepdir {

class StepDirDrive;

/// Feeds every edge to a verifier, then forwards it.
struct VerifyingSink final : gpio::EdgeSink {
  explicit VerifyingSink(const hil::stepdir::StepTiming& t) : verifier(t, {out_step, out_dir}) {}
  void output(std::span<const gpio::Edge> edges) noexcept override;
  hil::stepdir::StepVerifier verifier;
  gpio::EdgeSink* next = nullptr;
};

struct StepDirTransportFactory::Axis {
  explicit Axis(const hil::stepdir::StepTiming& t) : sink(t) {}
  std::string name;
  VerifyingSink sink;
  std::unique_ptr<gpio::mock::MockLines> mock_out, mock_in;
  std::unique_ptr<gpio::mock::StepDirDecoder> decoder;
  std::unique_ptr<gpio::LineBank> real_out, real_in;
  SteadyClock steady;
  std::unique_ptr<gpio::AsyncEdgeWriter> writer;
  double late_us = 50.0;
  StepDirDrive* drive = nullptr;  ///< not owned: the run's axis holds it (and this Axis); finish() only
  // Mock fault state.
  bool not_ready = false, force_start = false, force_end = false, broken_start = false, broken_end = false,
       cam_stuck = false;

  void wire_mock_switches(const StepDirConfig& cfg);
  bool inject(std::string_view name, bool on);
};

}  // namespace hil::drives::stepdir
