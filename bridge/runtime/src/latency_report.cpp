// SPDX-License-Identifier: MIT
#include "hil/runtime/latency_report.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace hil::runtime {
namespace {

using std::chrono::microseconds;
using std::chrono::milliseconds;

double us(Duration d) {
  return std::chrono::duration<double, std::micro>(d).count();
}

}  // namespace

std::vector<LatencyBin> latency_bins(const LatencyHistogram& h) {
  static const std::vector<Duration> edges = {
      microseconds(0),   microseconds(10),
      microseconds(20),  microseconds(50),
      microseconds(100), microseconds(200),
      microseconds(500), milliseconds(1),
      milliseconds(2),   milliseconds(5),
      milliseconds(10),  LatencyHistogram::bucket_width * static_cast<Duration::rep>(LatencyHistogram::bucket_count)};
  std::vector<LatencyBin> out;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i)
    out.push_back({edges[i], edges[i + 1], h.count_between(edges[i], edges[i + 1])});
  const Duration last = edges.back();
  out.push_back({last, std::nullopt, h.count() - h.count_between(Duration::zero(), last)});
  return out;
}

std::string format_latency_histogram(const LatencyHistogram& h, std::string_view indent) {
  const auto bins = latency_bins(h);
  std::size_t first = bins.size(), last = 0;
  std::uint64_t most = 0;
  for (std::size_t i = 0; i < bins.size(); ++i) {
    if (bins[i].count == 0) continue;
    first = std::min(first, i);
    last = i;
    most = std::max(most, bins[i].count);
  }
  std::string out;
  if (first == bins.size()) return out;
  const auto label = [](Duration d) {
    return d >= milliseconds(1) ? fmt::format("{:g} ms", us(d) / 1000.0) : fmt::format("{:g} us", us(d));
  };
  for (std::size_t i = first; i <= last; ++i) {
    const auto& b = bins[i];
    const std::string range = b.to ? fmt::format("{} - {}", label(b.from), label(*b.to)) : ">= " + label(b.from);
    const double pct = 100.0 * static_cast<double>(b.count) / static_cast<double>(h.count());
    // Bars on a log scale, so a handful of late wake-ups still shows next to millions of good ones.
    const std::size_t bar = b.count == 0
                                ? 0
                                : 1 + static_cast<std::size_t>(40.0 * std::log10(static_cast<double>(b.count)) /
                                                               std::max(1.0, std::log10(static_cast<double>(most))));
    out += fmt::format("{}{:>16} {:>10} {:>7.3f} %  {}\n", indent, range, b.count, pct, std::string(bar, '#'));
  }
  return out;
}

std::string latency_json(const LatencyHistogram& h) {
  std::string out = fmt::format(
      "{{\"samples\":{},\"min_us\":{:.3f},\"mean_us\":{:.3f},\"p50_us\":{:.3f},\"p99_us\":{:.3f},"
      "\"p999_us\":{:.3f},\"max_us\":{:.3f},\"bins\":[",
      h.count(), us(h.min()), us(h.mean()), us(h.percentile(0.5)), us(h.percentile(0.99)), us(h.percentile(0.999)),
      us(h.max()));
  bool first = true;
  for (const auto& b : latency_bins(h)) {
    out += fmt::format("{}{{\"from_us\":{:.0f},\"to_us\":{},\"count\":{}}}", first ? "" : ",", us(b.from),
                       b.to ? fmt::format("{:.0f}", us(*b.to)) : "null", b.count);
    first = false;
  }
  out += "]}";
  return out;
}

const std::vector<Duration>& standard_periods() {
  static const std::vector<Duration> periods = {
      microseconds(100), microseconds(125), microseconds(200),  microseconds(250), microseconds(500),
      milliseconds(1),   milliseconds(2),   microseconds(2500), milliseconds(4),   milliseconds(5),
      milliseconds(10),  milliseconds(20),  milliseconds(25),   milliseconds(50),  milliseconds(100),
      milliseconds(200), milliseconds(250), milliseconds(500),  milliseconds(1000)};
  return periods;
}

std::optional<Duration> recommended_min_period(const LatencyHistogram& h, Duration cycle_work) {
  if (h.count() == 0) return std::nullopt;
  const Duration need = 2 * (h.max() + std::max(cycle_work, Duration::zero()));
  for (const Duration p : standard_periods())
    if (p >= need) return p;
  return std::nullopt;
}

}  // namespace hil::runtime
