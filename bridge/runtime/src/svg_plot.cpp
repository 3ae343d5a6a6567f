// SPDX-License-Identifier: MIT
#include "hil/runtime/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

#include <fmt/format.h>

#include "hil/runtime/xml_escape.hpp"

namespace hil::runtime {

void PlotRecorder::on_start(const Scenario& scenario, const Machine& machine) {
  data_.title = scenario.name.empty() ? scenario.file : scenario.name;
  data_.axes.clear();
  for (const auto& a : machine.axes()) {
    PlotSeries s;
    s.axis = a.spec->name;
    s.units = a.spec->units;
    s.rotary = a.spec->rotary;
    data_.axes.push_back(std::move(s));
  }
  data_.couplings.clear();
  for (const auto& c : machine.couplings().couplings()) {
    PlotCoupling p;
    p.slave_name = c->spec->slave;
    p.master_name = c->spec->source_kind == MasterSource::time ? "time" : c->spec->master;
    p.slave_units = machine.axes()[c->slave].spec->units;
    // Built apart and moved in: g++ 12 warns (-Wrestrict, a false positive) on assigning a short
    // literal to a member string here.
    std::string master_units(c->spec->source_kind == MasterSource::time ? "s" : "");
    if (c->master_axis) master_units = machine.axes()[*c->master_axis].spec->units;
    for (const auto& m : scenario.masters)
      if (m.name == c->spec->master) master_units = m.units;
    p.master_units = std::move(master_units);
    data_.couplings.push_back(std::move(p));
  }
  data_.signals.clear();
  data_.digital.clear();
  if (const auto* c = machine.controller()) {
    for (auto& name : c->trace_signals()) data_.signals.push_back(PlotSignal{std::move(name), {}, {}});
    for (const auto& [name, bit] : machine.io_signals()) {
      PlotDigital d;
      d.name = name;
      d.area = "IQMD"[static_cast<std::size_t>(bit.area) & 3];
      d.edges.reserve(std::min<std::size_t>(max_points_, 64));
      data_.digital.push_back(std::move(d));
    }
  }
}

void PlotRecorder::on_cycle(Duration t, const Machine& machine) noexcept {
  data_.t_end = to_seconds(t);
  try {
    // Every cycle, not decimated: a bit's edges are few and a pulse must not vanish.
    if (const auto* c = machine.controller()) {
      const auto& io = machine.io_signals();
      for (std::size_t i = 0; i < io.size() && i < data_.digital.size(); ++i) {
        auto& d = data_.digital[i];
        const bool v = c->io().get(io[i].second);
        if (cycle_ == 0) {
          d.initial = v;
        } else if (v != ((d.edges.size() % 2 == 1) != d.initial) && !d.truncated) {
          if (d.edges.size() >= max_points_)
            d.truncated = true;
          else
            d.edges.push_back(to_seconds(t));
        }
      }
    }
  } catch (...) {  // out of memory: stop recording edges rather than disturb the cycle
    for (auto& d : data_.digital) d.truncated = true;
  }
  if (cycle_++ % stride_ != 0) return;
  try {
    const auto& axes = machine.axes();
    for (std::size_t i = 0; i < axes.size() && i < data_.axes.size(); ++i) {
      const auto& st = axes[i].axis->status();
      auto& s = data_.axes[i];
      s.t.push_back(to_seconds(t));
      s.position.push_back(st.position);
      s.command.push_back(st.command_position);
      s.velocity.push_back(st.velocity);
      s.following_error.push_back(st.following_error);
    }
    const auto& cs = machine.couplings().couplings();
    for (std::size_t i = 0; i < cs.size() && i < data_.couplings.size(); ++i) {
      auto& p = data_.couplings[i];
      p.t.push_back(to_seconds(t));
      p.master.push_back(cs[i]->plot_master);
      p.slave.push_back(cs[i]->plot_slave);
      p.cam.push_back(cs[i]->plot_cam);
    }
    if (const auto* c = machine.controller()) {
      for (std::size_t i = 0; i < data_.signals.size(); ++i) {
        data_.signals[i].t.push_back(to_seconds(t));
        data_.signals[i].value.push_back(c->trace_value(i));
      }
    }
    if (!data_.axes.empty() && data_.axes.front().t.size() >= max_points_) decimate();
  } catch (...) {  // out of memory: stop recording rather than disturb the cycle
    stride_ = ~std::uint64_t{0};
  }
}

void PlotRecorder::decimate() {
  auto halve = [](std::vector<double>& v) {
    std::size_t j = 0;
    for (std::size_t i = 0; i < v.size(); i += 2) v[j++] = v[i];
    v.resize(j);
  };
  for (auto& s : data_.axes) {
    halve(s.t);
    halve(s.position);
    halve(s.command);
    halve(s.velocity);
    halve(s.following_error);
  }
  for (auto& p : data_.couplings) {
    halve(p.t);
    halve(p.master);
    halve(p.slave);
    halve(p.cam);
  }
  for (auto& s : data_.signals) {
    halve(s.t);
    halve(s.value);
  }
  stride_ *= 2;
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  std::vector<double> out;
  if (!std::isfinite(lo) || !std::isfinite(hi) || hi <= lo || target < 2) return out;
  const double raw = (hi - lo) / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * mag;
    if (step >= raw) break;
  }
  const double first = std::ceil(lo / step - 1e-9) * step;
  for (double v = first; v <= hi + step * 1e-9 && out.size() < 100; v += step)
    out.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
  return out;
}

namespace {

constexpr double chart_w = 380, chart_h = 210;        // one chart, including its margins
constexpr double ml = 64, mr = 14, mt = 26, mb = 38;  // margins inside a chart
constexpr double title_h = 44;

struct Range {
  double lo, hi;
};

Range range_of(std::initializer_list<const std::vector<double>*> vs) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto* v : vs)
    for (double x : *v)
      if (std::isfinite(x)) {
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
  if (!std::isfinite(lo)) return {-1, 1};
  if (hi - lo < 1e-12) {
    const double pad = std::max(std::abs(lo) * 0.1, 1e-3);
    return {lo - pad, hi + pad};
  }
  const double pad = (hi - lo) * 0.05;
  return {lo - pad, hi + pad};
}

std::string tick_label(double v, double step) {
  const int decimals = step >= 1.0 ? 0 : std::min(6, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
  return fmt::format("{:.{}f}", v, decimals);
}

struct Line {
  const std::vector<double>* values;
  const char* label;
  const char* color;
  bool dashed;
  bool wraps = false;  ///< rotary position: break the line where it wraps
};

void chart(std::string& svg, double x0, double y0, const std::string& title, const std::vector<double>& t,
           const std::vector<Line>& lines, double t_end, Range x_range = {NAN, NAN}, const char* x_label = "t [s]") {
  const double pw = chart_w - ml - mr, ph = chart_h - mt - mb;
  const double px = x0 + ml, py = y0 + mt;
  Range yr{0, 1};
  if (lines.size() == 1)
    yr = range_of({lines[0].values});
  else
    yr = range_of({lines[0].values, lines[1].values});
  const Range tr = std::isfinite(x_range.lo) ? x_range : Range{0.0, std::max(t_end, 1e-3)};
  auto X = [&](double v) { return px + (v - tr.lo) / (tr.hi - tr.lo) * pw; };
  auto Y = [&](double v) { return py + ph - (v - yr.lo) / (yr.hi - yr.lo) * ph; };

  svg += fmt::format("<g class=\"chart\">\n<text x=\"{:.1f}\" y=\"{:.1f}\" class=\"ctitle\">{}</text>\n", px, y0 + 16,
                     xml_escape(title));
  svg += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" class=\"frame\"/>\n", px, py,
                     pw, ph);
  const auto yt = nice_ticks(yr.lo, yr.hi, 5);
  const double ystep = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
  for (double v : yt) {
    const double y = Y(v);
    svg += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" class=\"grid\"/>\n", px, y,
                       px + pw, y);
    svg += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" class=\"tick\"/>\n", px - 4, y,
                       px, y);
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" class=\"ylabel\">{}</text>\n", px - 6, y + 4,
                       tick_label(v, ystep));
  }
  const auto xt = nice_ticks(tr.lo, tr.hi, 6);
  const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1.0;
  for (double v : xt) {
    const double x = X(v);
    svg += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" class=\"grid\"/>\n", x, py, x,
                       py + ph);
    svg += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" class=\"tick\"/>\n", x, py + ph,
                       x, py + ph + 4);
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" class=\"xlabel\">{}</text>\n", x, py + ph + 16,
                       tick_label(v, xstep));
  }
  svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" class=\"xlabel\">{}</text>\n", px + pw / 2, py + ph + 32,
                     xml_escape(x_label));
  for (const auto& l : lines) {
    // A rotary position wraps (359.9 -> 0.1): break the line there instead of drawing a vertical
    // stroke across the chart.
    std::string pts;
    pts.reserve(t.size() * 16);
    double prev = NAN;
    auto flush = [&] {
      if (!pts.empty())
        svg += fmt::format("<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"{} points=\"{}\"/>\n", l.color,
                           l.dashed ? " stroke-dasharray=\"5,3\"" : "", pts);
      pts.clear();
    };
    for (std::size_t i = 0; i < t.size() && i < l.values->size(); ++i) {
      const double v = (*l.values)[i];
      if (!std::isfinite(v)) continue;
      if (l.wraps && std::isfinite(prev) && std::abs(v - prev) > 0.5 * (yr.hi - yr.lo)) flush();
      prev = v;
      fmt::format_to(std::back_inserter(pts), "{:.1f},{:.1f} ", X(t[i]), Y(v));
    }
    flush();
  }
  // Legend, top right inside the plot area.
  // Sized to the longest label (11px sans-serif: at most about 7px a character), so it stays inside the plot.
  std::size_t longest = 0;
  for (const auto& l : lines) longest = std::max(longest, std::string_view(l.label).size());
  const double legend_w = 34.0 + 7.0 * static_cast<double>(longest);
  double ly = py + 14;
  const double lx = px + pw - legend_w - 6;
  svg += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" class=\"legend\"/>\n", lx - 4,
                     py + 4, legend_w, 16.0 * static_cast<double>(lines.size()) + 4);
  for (const auto& l : lines) {
    svg += fmt::format(
        "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"{}\" "
        "stroke-width=\"2\"{}/>\n",
        lx, ly - 4, lx + 20, ly - 4, l.color, l.dashed ? " stroke-dasharray=\"5,3\"" : "");
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" class=\"ltext\">{}</text>\n", lx + 26, ly, l.label);
    ly += 16;
  }
  svg += "</g>\n";
}

constexpr double strip_h = 18, strip_gap = 4, strips_head = 30, strips_foot = 40;

double digital_height(std::size_t n) {
  return strips_head + static_cast<double>(n) * (strip_h + strip_gap) + strips_foot;
}

void digital_strips(std::string& svg, double y0, const std::vector<PlotDigital>& bits, double t_end) {
  // Room for the longest name (11px sans-serif: at most about 7px a character).
  std::size_t longest = 0;
  for (const auto& d : bits) longest = std::max(longest, d.name.size());
  const double label_w = std::clamp(7.0 * static_cast<double>(longest) + 12.0, ml, chart_w);
  const double px = 10 + label_w, pw = 3 * chart_w - label_w - mr;
  const double te = std::max(t_end, 1e-3);
  auto X = [&](double t) { return px + std::clamp(t / te, 0.0, 1.0) * pw; };
  svg += fmt::format(
      "<g class=\"digital\">\n<text x=\"{:.1f}\" y=\"{:.1f}\" class=\"ctitle\">controller I/O (inputs blue, outputs "
      "green, markers orange, device data grey)</text>\n",
      px, y0 + 16);
  double y = y0 + strips_head;
  for (const auto& d : bits) {
    const char* color = d.area == 'I' ? "#1f77b4" : d.area == 'Q' ? "#2ca02c" : d.area == 'M' ? "#ff7f0e" : "#7f7f7f";
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" class=\"ylabel\">{}</text>\n", px - 6, y + strip_h - 5,
                       xml_escape(d.name));
    svg += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" class=\"frame\"/>\n", px, y,
                       pw, strip_h);
    // The waveform: high segments filled, the level line drawn over the whole run.
    bool level = d.initial;
    double from = 0.0;
    std::string pts = fmt::format("{:.1f},{:.1f} ", X(0), level ? y + 2 : y + strip_h - 2);
    auto segment = [&](double to) {
      if (level && X(to) > X(from)) {
        svg += fmt::format(
            "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"{}\" "
            "fill-opacity=\"0.35\"/>\n",
            X(from), y + 2, std::max(X(to) - X(from), 0.6), strip_h - 4, color);
      }
    };
    for (double e : d.edges) {
      segment(e);
      fmt::format_to(std::back_inserter(pts), "{:.1f},{:.1f} ", X(e), level ? y + 2 : y + strip_h - 2);
      level = !level;
      fmt::format_to(std::back_inserter(pts), "{:.1f},{:.1f} ", X(e), level ? y + 2 : y + strip_h - 2);
      from = e;
    }
    const double end = d.truncated ? (d.edges.empty() ? 0.0 : d.edges.back()) : te;
    segment(end);
    fmt::format_to(std::back_inserter(pts), "{:.1f},{:.1f}", X(end), level ? y + 2 : y + strip_h - 2);
    svg += fmt::format("<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\" points=\"{}\"/>\n", color, pts);
    if (d.truncated) {
      svg += fmt::format(
          "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"#ccc\"/>\n"
          "<text x=\"{:.1f}\" y=\"{:.1f}\" class=\"ltext\">more edges than the plot keeps: see the trace</text>\n",
          X(end), y, px + pw - X(end), strip_h, X(end) + 4, y + strip_h - 5);
    }
    y += strip_h + strip_gap;
  }
  const auto xt = nice_ticks(0.0, te, 8);
  const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1.0;
  for (double v : xt) {
    svg += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\" class=\"tick\"/>\n", X(v), y,
                       y + 4);
    svg +=
        fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" class=\"xlabel\">{}</text>\n", X(v), y + 16, tick_label(v, xstep));
  }
  svg += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" class=\"xlabel\">t [s]</text>\n</g>\n", px + pw / 2, y + 32);
}

}  // namespace

std::string render_svg(const PlotData& data) {
  const double width = 3 * chart_w + 20;
  const std::size_t signal_rows = (data.signals.size() + 2) / 3;
  const double height =
      title_h +
      chart_h * static_cast<double>(std::max<std::size_t>(1, data.axes.size() + data.couplings.size() + signal_rows)) +
      (data.digital.empty() ? 0.0 : digital_height(data.digital.size())) + 10;
  double t_end = 0.0;
  for (const auto& s : data.axes)
    if (!s.t.empty()) t_end = std::max(t_end, s.t.back());
  if (!data.digital.empty()) t_end = std::max(t_end, data.t_end);
  std::string svg = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0:.0f}\" height=\"{1:.0f}\" viewBox=\"0 0 {0:.0f} {1:.0f}\" "
      "font-family=\"sans-serif\">\n"
      "<style>\n"
      ".title{{font-size:18px;font-weight:bold}} .ctitle{{font-size:13px;font-weight:bold}}\n"
      ".frame{{fill:#fff;stroke:#333;stroke-width:1}} .grid{{stroke:#ddd;stroke-width:0.7}}\n"
      ".tick{{stroke:#333;stroke-width:1}} .xlabel{{font-size:11px;text-anchor:middle}}\n"
      ".ylabel{{font-size:11px;text-anchor:end}} .legend{{fill:#fff;fill-opacity:0.85;stroke:#999}}\n"
      ".ltext{{font-size:11px}}\n"
      "</style>\n"
      "<rect width=\"100%\" height=\"100%\" fill=\"#fafafa\"/>\n"
      "<text x=\"10\" y=\"28\" class=\"title\">{2}</text>\n",
      width, height, xml_escape(data.title.empty() ? "hilbridge run" : "hilbridge run: " + data.title));
  double y = title_h;
  for (const auto& s : data.axes) {
    chart(svg, 10, y, fmt::format("{}: position [{}]", s.axis, s.units), s.t,
          {{&s.position, "actual", "#1f77b4", false, s.rotary}, {&s.command, "command", "#ff7f0e", true, s.rotary}},
          t_end);
    chart(svg, 10 + chart_w, y, fmt::format("{}: velocity [{}/s]", s.axis, s.units), s.t,
          {{&s.velocity, "actual", "#2ca02c", false}}, t_end);
    chart(svg, 10 + 2 * chart_w, y, fmt::format("{}: following error [{}]", s.axis, s.units), s.t,
          {{&s.following_error, "command - actual", "#d62728", false}}, t_end);
    y += chart_h;
  }
  for (const auto& c : data.couplings) {
    const std::string xl = fmt::format("{} [{}]", c.master_name, c.master_units);
    chart(svg, 10, y, fmt::format("{} over {} [{}]", c.slave_name, c.master_name, c.slave_units), c.master,
          {{&c.slave, "slave command", "#9467bd", false}}, t_end, range_of({&c.master}), xl.c_str());
    chart(svg, 10 + chart_w, y, fmt::format("master {} [{}]", c.master_name, c.master_units), c.t,
          {{&c.master, "master", "#8c564b", false}}, t_end);
    chart(svg, 10 + 2 * chart_w, y, fmt::format("{}: cam table position [{}]", c.slave_name, c.master_units), c.t,
          {{&c.cam, "x in table", "#17becf", false, true}}, t_end);
    y += chart_h;
  }
  // The controller's I/O bits: one strip each (filled while 1), inputs blue, outputs green,
  // markers orange, device data grey; the time axis is the charts'.
  if (!data.digital.empty()) {
    digital_strips(svg, y, data.digital, t_end);
    y += digital_height(data.digital.size());
  }
  // The controller's analog values ("C_linkage_error_deg" -> "controller: C linkage error [deg]").
  for (std::size_t i = 0; i < data.signals.size(); ++i) {
    const auto& s = data.signals[i];
    std::string label = s.name, unit;
    if (const auto u = label.rfind('_'); u != std::string::npos && u + 1 < label.size()) {
      unit = label.substr(u + 1);
      label.resize(u);
    }
    std::ranges::replace(label, '_', ' ');
    chart(svg, 10 + static_cast<double>(i % 3) * chart_w, y,
          unit.empty() ? fmt::format("controller: {}", label) : fmt::format("controller: {} [{}]", label, unit), s.t,
          {{&s.value, "value", "#e377c2", false}}, t_end);
    if (i % 3 == 2 || i + 1 == data.signals.size()) y += chart_h;
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace hil::runtime
