// SPDX-License-Identifier: MIT
// Scenario key `io: - {analog: ...}` (docs/scenarios.md "Analog inputs").
#include "analog_stimulus_loader.hpp"

namespace hil::runtime::detail {

AnalogStimulus load_analog_stimulus(const yaml::Field& f) {
  f.expect_map({"analog", "value", "at", "ramp"});
  AnalogStimulus a;
  a.source = {f.line(), f.path()};
  a.input = f.child("analog").as_string("the device's analog input (e.g. AE1)");
  a.value = f.required("value", "the input's value in its unit (the CLM1.4: volts)").as_number("a number");
  a.at = f.required("at", "when the input starts to change").as_duration();
  if (auto r = f.optional_duration("ramp")) a.ramp = *r;
  return a;
}

}  // namespace hil::runtime::detail
