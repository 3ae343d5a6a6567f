// SPDX-License-Identifier: MIT
#pragma once
// `hilbridge run --plot FILE.svg`: position (actual and command), velocity and following error
// over time, one row of three charts per axis, the controller's I/O bits as digital strips under
// the axis rows, and per coupling a row with the slave over the
// master, the master over time and the cam table position over time, drawn as a self-contained SVG (axes, ticks,
// labels, legend; no external plotting dependency).
//
// PlotRecorder keeps at most `max_points` samples per axis: when full it drops every second
// sample and halves its sampling rate, so memory stays bounded on long runs while the plot
// keeps the shape (min/max of a dropped pair are not preserved; the trace CSV has every cycle).

#include <string>
#include <vector>

#include "hil/runtime/run_observer.hpp"

namespace hil::runtime {

struct PlotSeries {
  std::string axis;
  std::string units;
  bool rotary = false;                  ///< positions wrap at the modulo (the plot breaks the line there)
  std::vector<double> t;                ///< s
  std::vector<double> position;         ///< units
  std::vector<double> command;          ///< units
  std::vector<double> velocity;         ///< units/s
  std::vector<double> following_error;  ///< units
};

/// One coupling (machine.couplings): master position, slave command and cam table position.
struct PlotCoupling {
  std::string slave_name, master_name;
  std::string slave_units, master_units;
  std::vector<double> t;       ///< s
  std::vector<double> master;  ///< master units
  std::vector<double> slave;   ///< slave command, slave units
  std::vector<double> cam;     ///< cam table position, master units (NaN: no cam running)
};
/// One analog value of the scenario's controller (Controller::trace_signals), e.g. the ELG's
/// "C_linkage_error_deg".
struct PlotSignal {
  std::string name;
  std::vector<double> t;      ///< s
  std::vector<double> value;  ///< in the unit its name ends with
};
/// One bit of the controller's I/O image (Machine::io_signals), kept as its edges: exact at any
/// run length (decimation would lose short pulses), at most `max_points` edges (then `truncated`).
struct PlotDigital {
  std::string name;
  char area = 'I';  ///< I input, Q output, M marker, D device data
  bool initial = false;
  std::vector<double> edges;  ///< s, the level toggles at each
  bool truncated = false;     ///< more edges than kept: the strip is hatched after the last one
};
struct PlotData {
  std::string title;
  std::vector<PlotSeries> axes;
  std::vector<PlotCoupling> couplings;  ///< one extra row each: slave vs master, master, cam position
  std::vector<PlotSignal> signals;      ///< the controller's values, three charts per row
  std::vector<PlotDigital> digital;     ///< one strip each under the axis rows
  double t_end = 0.0;                   ///< s, the last cycle recorded
};

class PlotRecorder final : public RunObserver {
 public:
  explicit PlotRecorder(std::size_t max_points = 4000) : max_points_(max_points < 16 ? 16 : max_points) {}
  void on_start(const Scenario& scenario, const Machine& machine) override;
  void on_cycle(Duration t, const Machine& machine) noexcept override;
  [[nodiscard]] const PlotData& data() const noexcept { return data_; }

 private:
  void decimate();
  PlotData data_;
  std::size_t max_points_;
  std::uint64_t stride_ = 1;
  std::uint64_t cycle_ = 0;
};

/// The SVG document (UTF-8 text).
[[nodiscard]] std::string render_svg(const PlotData& data);

/// "Nice" tick values covering [lo, hi] (steps of 1, 2 or 5 x 10^k), about `target` of them.
[[nodiscard]] std::vector<double> nice_ticks(double lo, double hi, int target = 6);

}  // namespace hil::runtime
