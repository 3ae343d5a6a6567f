// SPDX-License-Identifier: MIT
#pragma once
// Coupled motion in a scenario (docs/coupling.md, docs/scenarios.md "Coupling"): virtual master
// axes, cam tables and couplings under `machine:`, and the `couple:` program step. Pure data;
// the loader (coupling_loader.cpp) fills it, the machine runs it.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hil/motion/cam_table.hpp"

namespace hil::runtime {

/// Where a coupling element came from (file line, key path), for messages.
struct CouplingSourceRef {
  int line = 0;
  std::string path;
};

/// `machine.masters[]`: a master axis that exists only in software (hil::motion::VirtualMaster).
struct VirtualMasterSpec {
  std::string name;
  std::string units = "mm";
  std::int64_t inc_per_unit_num = 1000;  ///< master increments per unit = num / den
  std::int64_t inc_per_unit_den = 1;
  CouplingSourceRef source;
};

/// `machine.cams[]`: a cam table in user units (master units -> slave units).
struct CamSpec {
  std::string name;
  motion::CamTableSpec table;  ///< points in master units / slave units
  CouplingSourceRef source;
};

enum class MasterSource : std::uint8_t { axis_command, axis_actual, virtual_axis, time };

/// `machine.couplings[]`: one slave axis following one master.
struct CouplingSpec {
  std::string slave;   ///< a machine axis
  std::string master;  ///< an axis name, a virtual master name, or "" for time
  MasterSource source_kind = MasterSource::axis_command;
  double velocity = 0.0;      ///< slave limit, units/s (0 = the slave axis' limit)
  double acceleration = 0.0;  ///< slave limit, units/s^2 (0 = the slave axis' limit)
  int acceleration_filter_cycles = 1;
  double following_error = 0.0;  ///< coupling window, slave units (0 = off)
  CouplingSourceRef source;
};

/// `couple:` step: what to do with one coupling.
struct CoupleStep {
  enum class Action : std::uint8_t { gear, cam, disengage, master_velocity, superimpose };
  Action action = Action::gear;
  std::string slave;           ///< the coupling (by its slave); master_velocity: the virtual master
  std::int64_t ratio_num = 1;  ///< gear: slave units per master unit = num / den (exact, as written)
  std::int64_t ratio_den = 1;
  std::string cam;            ///< cam: the table
  std::optional<double> at;   ///< master position (master units) where it takes effect
  double ramp = 0.0;          ///< gear/disengage: ramp length in master units
  double phase = 0.0;         ///< cam: table position at the start (master units)
  double velocity = 0.0;      ///< master_velocity: units/s; superimpose: units/s
  double acceleration = 0.0;  ///< master_velocity / superimpose: units/s^2
  double distance = 0.0;      ///< superimpose: slave units
};

}  // namespace hil::runtime
