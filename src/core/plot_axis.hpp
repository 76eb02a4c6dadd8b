// A line plot's value axis: its drawn range, "nice" tick values (1, 2 or 5 x 10^k) and tick
// labels that tell the ticks apart at any scale. A picture only (nothing here is exact).
// In core because every layer that draws a plot uses it (render, and tolerance's pictures).
//
// Labels. A tick value is k * step with k an integer and step = m x 10^e (m in {1, 2, 5}); its
// label is written from the integers k * m and e, so it is exact and two ticks never share a
// label. When the labels would need more than six significant digits (a span tiny beside the
// values: about 1 um around 79 mm, 1e-9 rad around 1 rad), the ticks are labelled as offsets
// from a stated base value, as plotting libraries do: `base_label` is then e.g. "79 +" (drawn at
// the axis) and the tick labels read "-1e-06", "-5e-07", "+0", "+5e-07".
//
// Range. Non-finite bounds are skipped (a NaN or infinite bound is replaced by the other one, or
// by 0); an empty span (a constant signal c) is widened to c +- 10^(floor(log10 |c|) - 1), or
// -1..1 for c = 0; a span below 2^-50 of the values (a few units in the last place, where
// doubles cannot resolve the signal) is widened to that. Arithmetic is in long double, so
// bounds near +-1e308 and spans that overflow a double are drawn.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace hipair {

struct PlotAxis {
  long double lo = -1, hi = 1;          ///< drawn range; contains the data bounds given
  long double step = 1;                 ///< tick spacing: 1, 2 or 5 x 10^k
  std::vector<long double> ticks;       ///< increasing, within [lo, hi], at most max_ticks
  std::vector<std::string> labels;      ///< one per tick, pairwise distinct
  std::string base_label;               ///< non-empty in offset mode: "79 +" (labels are offsets)
  /// Where v lies across the axis: 0 at lo, 1 at hi.
  double fraction(long double v) const { return static_cast<double>((v - lo) / (hi - lo)); }
};

struct PlotAxisOptions {
  double pad = 0;           ///< fraction of the span added on each side of the data
  int max_ticks = 7;        ///< at most this many ticks (at least 2 kept)
  bool snap = false;        ///< extend the range outward to the nearest ticks
};

/// The axis for data within [data_lo, data_hi] (either order).
PlotAxis plot_axis(double data_lo, double data_hi, const PlotAxisOptions& options = {});

/// Smallest and largest finite value of `values` ({NaN, NaN} when there is none).
std::pair<double, double> finite_bounds(const std::vector<double>& values);

}  // namespace hipair
