#include "render/time_plot_svg.hpp"

#include "io/svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace hipair::render {
namespace {

const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b"};

std::string tick_text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", v);
  return buffer;
}

// about 5 round tick values over [lo, hi]
std::vector<double> ticks(double lo, double hi) {
  double span = hi - lo;
  if (!(span > 0)) return {lo};
  double step = std::pow(10.0, std::floor(std::log10(span / 5)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (span / (step * m) <= 6) {
      step *= m;
      break;
    }
  std::vector<double> out;
  double first = std::ceil(lo / step) * step;
  for (int i = 0; i < 20; ++i) {
    double v = first + i * step;
    if (v > hi + step * 1e-9) break;
    out.push_back(std::abs(v) < step * 1e-9 ? 0 : v);
  }
  return out;
}

}  // namespace

std::string time_plot_svg(const TimePlot& plot) {
  const double width = 600, panel = 150, gap = 40, left = 80, top = 40;
  std::size_t n = std::max<std::size_t>(plot.series.size(), 1);
  double height = top + n * (panel + gap) + 20;
  io::SvgBox box{0, 0, left + width + 30, height};
  io::SvgWriter svg(box, 900);
  svg.set_default_stroke_width(1);
  svg.text(box.width() / 2, height - 18, plot.title, 14, "middle", "black", "bold");
  double t0 = plot.times.empty() ? 0 : plot.times.front();
  double t1 = plot.times.empty() ? 1 : plot.times.back();
  if (!(t1 > t0)) t1 = t0 + 1;
  auto X = [&](double t) { return left + (t - t0) / (t1 - t0) * width; };
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const TimeSeries& s = plot.series[k];
    double base = height - top - (k + 1) * (panel + gap) + gap;   // bottom of the panel (y up)
    double lo = 0, hi = 0;
    bool any = false;
    for (double v : s.values)
      if (std::isfinite(v)) {
        lo = any ? std::min(lo, v) : v;
        hi = any ? std::max(hi, v) : v;
        any = true;
      }
    if (!(hi - lo > 1e-9 * std::max({1.0, std::abs(lo), std::abs(hi)}))) {   // constant (to rounding)
      lo -= 1;
      hi += 1;
    }
    double pad = 0.05 * (hi - lo);
    lo -= pad;
    hi += pad;
    auto Y = [&](double v) { return base + (v - lo) / (hi - lo) * panel; };
    io::SvgStyle frame;
    frame.stroke = "#888";
    svg.rectangle(left, base, width, panel, frame);
    io::SvgStyle grid;
    grid.stroke = "#ddd";
    grid.stroke_width = 0.5;
    for (double v : ticks(lo, hi)) {
      svg.line(left, Y(v), left + width, Y(v), grid);
      svg.text(left - 4, Y(v) - 3, tick_text(v), 9, "end");
    }
    for (double t : ticks(t0, t1)) {
      svg.line(X(t), base, X(t), base + panel, grid);
      svg.text(X(t), base - 11, tick_text(t), 9);
    }
    io::SvgStyle tick;
    tick.stroke = "#999";
    tick.stroke_width = 0.5;
    for (double t : plot.event_times) svg.line(X(t), base, X(t), base + 6, tick);
    io::SvgPath curve;
    bool started = false;
    for (std::size_t i = 0; i < plot.times.size() && i < s.values.size(); ++i) {
      if (!std::isfinite(s.values[i])) continue;
      if (!started) curve.move_to(X(plot.times[i]), Y(s.values[i]));
      else curve.line_to(X(plot.times[i]), Y(s.values[i]));
      started = true;
    }
    io::SvgStyle line;
    line.stroke = colours[k % 6];
    line.stroke_width = 1.2;
    if (!curve.empty()) svg.path(curve, line);
    svg.text(left + 6, base + panel - 14, s.label + " — " + plot.y_label, 11, "start", colours[k % 6], "bold");
    svg.text(left + width, base - 24, plot.x_label, 10, "end");
  }
  return svg.str();
}

}  // namespace hipair::render
