// SPDX-License-Identifier: MIT
#include "hil/drives/stepdir/axis.hpp"

namespace hil::drives::stepdir {

void StepDirTransportFactory::Axis::wire_mock_switches(const StepDirConfig& cfg) {
  int i = 0;
  const bool nc = cfg.limits_normally_closed;
  // The level a switch shows: NO closes (1) when actuated, NC opens (0); a broken wire reads 0.
  auto level = [nc](bool actuated, bool broken) { return broken ? false : (nc ? !actuated : actuated); };
  if (cfg.ready) {
    mock_in->set_input_source(static_cast<std::size_t>(i++),
                              [this, r = cfg.mock.ready](std::int64_t) { return r && !not_ready; });
  }
  if (cfg.limit_start) {
    mock_in->set_input_source(static_cast<std::size_t>(i++),
                              [this, level, at = cfg.mock.limit_start_at](std::int64_t t) {
                                const bool act = force_start || (at && decoder->position_at(t) <= *at);
                                return level(act, broken_start);
                              });
  }
  if (cfg.limit_end) {
    mock_in->set_input_source(static_cast<std::size_t>(i++), [this, level, at = cfg.mock.limit_end_at](std::int64_t t) {
      const bool act = force_end || (at && decoder->position_at(t) >= *at);
      return level(act, broken_end);
    });
  }
  if (cfg.reference) {
    mock_in->set_input_source(static_cast<std::size_t>(i++), [this, cam = cfg.mock.cam](std::int64_t t) {
      if (cam_stuck) return true;
      if (!cam) return false;
      const auto p = decoder->position_at(t);
      return p >= cam->first && p <= cam->second;
    });
  }
}

bool StepDirTransportFactory::Axis::inject(std::string_view n, bool on) {
  if (n == "not_ready")
    not_ready = on;
  else if (n == "limit_start")
    force_start = on;
  else if (n == "limit_end")
    force_end = on;
  else if (n == "broken_wire_start")
    broken_start = on;
  else if (n == "broken_wire_end")
    broken_end = on;
  else if (n == "cam_stuck")
    cam_stuck = on;
  else
    return false;
  return true;
}

}  // namespace hil::drives::stepdir
