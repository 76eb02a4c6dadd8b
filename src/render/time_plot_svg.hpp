// Curves over time as an SVG line plot (simulation positions and velocities). A picture only.
#pragma once

#include <string>
#include <vector>

namespace hipair::render {

struct TimeSeries {
  std::string label;
  std::vector<double> values;   ///< one per time sample
  std::string unit;             ///< the series' unit ("rad", "mm per s"); empty: the plot's y_label
};

struct TimePlot {
  std::string title;
  std::string x_label;            ///< "t (s)"
  std::string y_label;            ///< "position (rad or mm)"
  std::vector<double> times;
  std::vector<TimeSeries> series;
  std::vector<double> event_times;   ///< drawn as thin vertical ticks at the bottom
};

/// The SVG document: one panel per series (stacked), shared time axis.
std::string time_plot_svg(const TimePlot& plot);

}  // namespace hipair::render
