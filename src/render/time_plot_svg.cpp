#include "render/time_plot_svg.hpp"

#include "io/svg.hpp"
#include "core/plot_axis.hpp"

#include <algorithm>
#include <cmath>

namespace hipair::render {
namespace {

const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b"};

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
  PlotAxis t_axis = plot_axis(t0, t1);
  auto X = [&](long double t) { return left + t_axis.fraction(t) * width; };
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const TimeSeries& s = plot.series[k];
    double base = height - top - (k + 1) * (panel + gap) + gap;   // bottom of the panel (y up)
    auto [lo, hi] = finite_bounds(s.values);   // NaN and inf samples are skipped
    PlotAxisOptions y_options;
    y_options.pad = 0.05;
    PlotAxis y_axis = plot_axis(lo, hi, y_options);
    auto Y = [&](long double v) { return base + y_axis.fraction(v) * panel; };
    io::SvgStyle frame;
    frame.stroke = "#888";
    svg.rectangle(left, base, width, panel, frame);
    io::SvgStyle grid;
    grid.stroke = "#ddd";
    grid.stroke_width = 0.5;
    for (std::size_t i = 0; i < y_axis.ticks.size(); ++i) {
      double y = Y(y_axis.ticks[i]);
      svg.line(left, y, left + width, y, grid);
      svg.text(left - 4, y - 3, y_axis.labels[i], 9, "end");
    }
    if (!y_axis.base_label.empty()) svg.text(left - 4, base + panel + 4, y_axis.base_label, 9, "end");
    for (std::size_t i = 0; i < t_axis.ticks.size(); ++i) {
      double x = X(t_axis.ticks[i]);
      svg.line(x, base, x, base + panel, grid);
      svg.text(x, base - 11, t_axis.labels[i], 9);
    }
    if (!t_axis.base_label.empty()) svg.text(left, base - 24, t_axis.base_label, 9, "start");
    io::SvgStyle tick;
    tick.stroke = "#999";
    tick.stroke_width = 0.5;
    for (double t : plot.event_times)
      if (std::isfinite(t)) svg.line(X(t), base, X(t), base + 6, tick);
    io::SvgPath curve;
    bool started = false;
    for (std::size_t i = 0; i < plot.times.size() && i < s.values.size(); ++i) {
      if (!std::isfinite(s.values[i]) || !std::isfinite(plot.times[i])) continue;
      if (!started) curve.move_to(X(plot.times[i]), Y(s.values[i]));
      else curve.line_to(X(plot.times[i]), Y(s.values[i]));
      started = true;
    }
    io::SvgStyle line;
    line.stroke = colours[k % 6];
    line.stroke_width = 1.2;
    if (!curve.empty()) svg.path(curve, line);
    svg.text(left + 6, base + panel - 14, s.label + " — " + (s.unit.empty() ? plot.y_label : s.unit), 11, "start", colours[k % 6], "bold");
    svg.text(left + width, base - 24, plot.x_label, 10, "end");
  }
  return svg.str();
}

}  // namespace hipair::render
