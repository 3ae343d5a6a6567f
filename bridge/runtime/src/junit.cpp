// SPDX-License-Identifier: MIT
#include "hil/runtime/junit.hpp"

#include <fmt/format.h>

#include "hil/runtime/xml_escape.hpp"

namespace hil::runtime {

std::string make_junit_xml(const std::vector<ScenarioOutcome>& outcomes) {
  std::size_t tests = 0, failures = 0, errors = 0;
  double total = 0.0;
  std::string body;
  for (const auto& o : outcomes) {
    total += o.wall_s;
    const std::string suite = xml_escape(o.result && !o.result->scenario.empty() ? o.result->scenario : o.file);
    if (!o.result) {
      ++tests;
      ++errors;
      body += fmt::format(
          "  <testsuite name=\"{}\" file=\"{}\" tests=\"1\" failures=\"0\" errors=\"1\" "
          "time=\"{:.3f}\">\n"
          "    <testcase classname=\"{}\" name=\"load\" time=\"{:.3f}\">\n"
          "      <error message=\"{}\" type=\"ConfigError\">{}</error>\n"
          "    </testcase>\n  </testsuite>\n",
          suite, xml_escape(o.file), o.wall_s, suite, o.wall_s, xml_escape(o.error), xml_escape(o.error));
      continue;
    }
    const RunResult& r = *o.result;
    std::size_t suite_failures = 0;
    std::string cases;
    for (const auto& e : r.expectations) {
      cases += fmt::format("    <testcase classname=\"{}\" name=\"{}\" time=\"0\"", suite,
                           xml_escape(fmt::format("{}: {}", e.subject(), e.description)));
      if (e.passed) {
        cases += "/>\n";
      } else {
        ++suite_failures;
        const std::string msg = fmt::format("{}: expected {}, {}", e.subject(), e.description, e.detail);
        cases += fmt::format(
            ">\n      <failure message=\"{}\" type=\"expectation\">{} ({}:{} {})</failure>\n"
            "    </testcase>\n",
            xml_escape(msg), xml_escape(msg), xml_escape(r.file), e.line, xml_escape(e.path));
      }
    }
    // The run itself: program, timeout, unexpected faults, transport reports (expectation
    // failures are already their own cases).
    std::vector<std::string> run_failures;
    for (const auto& f : r.failures)
      if ((!f.starts_with("axis ") || f.find(": expected ") == std::string::npos) && !f.starts_with("I/O: expected "))
        run_failures.push_back(f);
    // Device errors the controller raised, with the device's number and text (docs/controllers.md).
    std::string device_errors;
    for (const auto& d : r.device_errors)
      device_errors += fmt::format("device error t={:.3f} s axis {}: {} (reaction {})\n", to_seconds(d.t), d.axis,
                                   d.describe(), d.reaction);
    const std::string system_out = device_errors.empty()
                                       ? std::string()
                                       : fmt::format("      <system-out>{}</system-out>\n", xml_escape(device_errors));
    cases += fmt::format("    <testcase classname=\"{}\" name=\"run\" time=\"{:.3f}\"", suite, o.wall_s);
    if (run_failures.empty()) {
      cases += system_out.empty() ? std::string("/>\n") : ">\n" + system_out + "    </testcase>\n";
    } else {
      ++suite_failures;
      std::string text;
      for (const auto& f : run_failures) text += f + "\n";
      cases += fmt::format(">\n      <failure message=\"{}\" type=\"run\">{}</failure>\n{}    </testcase>\n",
                           xml_escape(run_failures.front()), xml_escape(text), system_out);
    }
    const std::size_t suite_tests = r.expectations.size() + 1;
    tests += suite_tests;
    failures += suite_failures;
    body += fmt::format(
        "  <testsuite name=\"{}\" file=\"{}\" tests=\"{}\" failures=\"{}\" errors=\"0\" "
        "time=\"{:.3f}\">\n{}",
        suite, xml_escape(o.file), suite_tests, suite_failures, o.wall_s, cases);
    body += fmt::format(
        "    <system-out>{}</system-out>\n  </testsuite>\n",
        xml_escape(fmt::format("{:.3f} s simulated, {} cycles", to_seconds(r.simulated), r.scheduler.cycles)));
  }
  return fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<testsuites name=\"hilbridge test\" tests=\"{}\" failures=\"{}\" errors=\"{}\" time=\"{:.3f}\">\n"
      "{}</testsuites>\n",
      tests, failures, errors, total, body);
}

}  // namespace hil::runtime
