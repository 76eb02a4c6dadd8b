// Value axes of line plots (src/render/plot_axis): nice ticks and distinct labels at every
// scale, for spans from 1e-15 of the values up to 1e15 times them, values up to 1e300.
#include "core/plot_axis.hpp"
#include "render/time_plot_svg.hpp"

#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <regex>
#include <set>
#include <string>

namespace hipair::render {
namespace {

long double parse(const std::string& text) {
  char* end = nullptr;
  long double v = std::strtold(text.c_str(), &end);
  EXPECT_EQ(*end, '\0') << "label '" << text << "' is not a number";
  return v;
}

// Every property the plots rely on, for data in [a, b] (either order).
::testing::AssertionResult sane_axis(double a, double b, const PlotAxisOptions& options) {
  PlotAxis axis = plot_axis(a, b, options);
  long double lo = std::min<long double>(a, b), hi = std::max<long double>(a, b);
  auto fail = [&]() {
    return ::testing::AssertionFailure() << "data [" << static_cast<double>(lo) << ", " << static_cast<double>(hi)
                                         << "] (span " << static_cast<double>(hi - lo) << "), max_ticks "
                                         << options.max_ticks << ", snap " << options.snap << ": ";
  };
  if (!(axis.lo <= lo && axis.hi >= hi && axis.lo < axis.hi)) return fail() << "range does not contain the data";
  std::size_t n = axis.ticks.size();
  if (n < 1 || n > static_cast<std::size_t>(std::max(options.max_ticks, 4))) return fail() << n << " ticks";
  if (axis.labels.size() != n) return fail() << "labels and ticks differ in number";
  // the step is 1, 2 or 5 x 10^k (to long double rounding of the power of ten)
  long double power = std::pow(10.0L, std::floor(std::log10(axis.step)));
  long double mantissa = axis.step / power;
  bool nice = false;
  for (long double m : {1.0L, 2.0L, 5.0L, 10.0L}) nice = nice || std::fabs(mantissa - m) < 1e-12L;
  if (!nice) return fail() << "step " << static_cast<double>(axis.step) << " is not nice";
  std::set<std::string> distinct(axis.labels.begin(), axis.labels.end());
  if (distinct.size() != n) return fail() << "repeated labels";
  long double base = 0;
  if (!axis.base_label.empty()) {
    std::string text = axis.base_label;
    if (text.size() < 3 || text.substr(text.size() - 2) != " +") return fail() << "base label '" << text << "'";
    base = parse(text.substr(0, text.size() - 2));
  }
  // A label parsed back is its tick to long double precision: parsing rounds each number and
  // the sum once, half a unit each, of a number at most max(|lo|, |hi|) of the axis.
  long double size = std::max(std::fabs(axis.lo), std::fabs(axis.hi));
  long double tolerance = 4 * LDBL_EPSILON * size;
  long double previous_offset = -std::numeric_limits<long double>::infinity();
  long double previous = previous_offset;
  for (std::size_t i = 0; i < n; ++i) {
    const std::string& label = axis.labels[i];
    if (label.size() > 24) return fail() << "label '" << label << "' too long";
    long double offset = parse(label);
    long double value = base + offset;
    if (!(offset > previous_offset)) return fail() << "labels not increasing at '" << label << "'";
    if (!(value > previous)) return fail() << "parsed ticks not increasing at '" << label << "'";
    if (!(value >= axis.lo - tolerance && value <= axis.hi + tolerance)) return fail() << "label '" << label << "' outside the axis";
    if (!(std::fabs(value - axis.ticks[i]) <= tolerance)) return fail() << "label '" << label << "' is not its tick";
    if (!(axis.ticks[i] >= axis.lo && axis.ticks[i] <= axis.hi)) return fail() << "tick outside the axis";
    if (i > 0 && !(axis.ticks[i] > axis.ticks[i - 1])) return fail() << "ticks not increasing";
    double f = axis.fraction(axis.ticks[i]);
    if (!(f >= 0 && f <= 1)) return fail() << "tick drawn outside the panel";
    previous_offset = offset;
    previous = value;
  }
  return ::testing::AssertionSuccess();
}

TEST(PlotAxis, LabelsDistinctAcrossScales) {
  std::mt19937_64 random(20261128);
  std::uniform_real_distribution<double> unit(0, 1);
  const double centre_exponents[] = {-300, -150, -20, -5, 0, 1.9, 5, 20, 150, 300};
  int checked = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    double centre = 0, span = 0;
    double relative = std::pow(10.0, -15 + 30 * unit(random));   // 1e-15 .. 1e15
    if (trial % 11 == 0) {                                         // centre 0: absolute spans
      span = std::pow(10.0, -300 + 600 * unit(random));
    } else {
      double e = centre_exponents[trial % 10];
      centre = (trial % 3 == 0 ? -1 : 1) * (1 + 9 * unit(random)) * std::pow(10.0, e);
      span = relative * std::fabs(centre);
    }
    double a = centre - span / 2, b = centre + span / 2;
    if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(span)) continue;   // beyond double
    PlotAxisOptions options;
    options.max_ticks = 4 + trial % 9;   // 4 .. 12
    options.snap = trial % 5 == 0;
    options.pad = trial % 2 ? 0.05 : 0;
    ASSERT_TRUE(sane_axis(trial % 7 ? a : b, trial % 7 ? b : a, options));
    ++checked;
  }
  EXPECT_GT(checked, 15000);
}

TEST(PlotAxis, ConstantAndExtremeValues) {
  const double values[] = {0, 1, -79, 1e-300, -1e-300, 4.9e-324, 1e300, -1e300, DBL_MAX, -DBL_MAX, DBL_MIN};
  for (double v : values) {
    for (bool snap : {false, true}) {
      PlotAxisOptions options;
      options.snap = snap;
      EXPECT_TRUE(sane_axis(v, v, options)) << v;
      EXPECT_GE(plot_axis(v, v, options).ticks.size(), 2u) << v;
      EXPECT_TRUE(sane_axis(v, std::nextafter(v, DBL_MAX), options)) << v;   // one unit in the last place
    }
  }
  EXPECT_TRUE(sane_axis(-DBL_MAX, DBL_MAX, {}));   // a span that overflows a double
  EXPECT_TRUE(sane_axis(0, DBL_MAX, {}));
}

TEST(PlotAxis, NonFiniteBoundsAreSkipped) {
  double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const double pairs[][2] = {{nan, nan}, {nan, 5}, {-3, nan}, {-inf, inf}, {inf, inf}, {-inf, 2}, {nan, -inf}};
  for (const auto& p : pairs) {
    PlotAxis axis = plot_axis(p[0], p[1]);
    EXPECT_TRUE(std::isfinite(axis.lo) && std::isfinite(axis.hi) && axis.lo < axis.hi);
    EXPECT_GE(axis.ticks.size(), 2u);
  }
  auto [lo, hi] = finite_bounds({nan, 3, inf, -2, -inf});
  EXPECT_EQ(lo, -2);
  EXPECT_EQ(hi, 3);
  auto [none_lo, none_hi] = finite_bounds({nan, inf});
  EXPECT_TRUE(std::isnan(none_lo) && std::isnan(none_hi));
}

// The reported case: a position within 1 um of 79 mm was labelled "79" at every tick.
TEST(PlotAxis, MicrometreAboutSeventyNineIsLabelledAsOffsets) {
  PlotAxis axis = plot_axis(79 - 5e-7, 79 + 5e-7);
  EXPECT_EQ(axis.base_label, "79 +");
  std::vector<std::string> expected = {"-4e-7", "-2e-7", "0", "+2e-7", "+4e-7"};
  EXPECT_EQ(axis.labels, expected);
  // ordinary spans keep plain labels with a common number of decimals
  PlotAxis plain = plot_axis(0, 1.5);
  EXPECT_TRUE(plain.base_label.empty());
  EXPECT_EQ(plain.labels.front(), "0.0");
  EXPECT_EQ(plain.labels.back(), "1.5");
}

TEST(PlotAxis, TimePlotOfTinySpanAndNonFiniteSeries) {
  TimePlot plot;
  plot.title = "t";
  plot.x_label = "t (s)";
  plot.y_label = "mm";
  double nan = std::numeric_limits<double>::quiet_NaN();
  TimeSeries tiny{"tiny", {}}, constant{"constant", {}}, missing{"missing", {}};
  for (int i = 0; i <= 100; ++i) {
    plot.times.push_back(i * 1e-4);
    tiny.values.push_back(79 + 1e-6 * std::sin(i * 0.1));
    constant.values.push_back(79);
    missing.values.push_back(i % 2 ? nan : std::numeric_limits<double>::infinity());
  }
  plot.series = {tiny, constant, missing};
  std::string svg = time_plot_svg(plot);
  EXPECT_NE(svg.find(">79 +<"), std::string::npos);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
}

// The tolerance band picture (variation.svg) over a driver range of 1e-7 mm at 100 mm with
// deviations of a few nm: every axis label of the picture is distinct.
TEST(PlotAxis, ToleranceBandOfTinyRangesHasDistinctLabels) {
  ToleranceResult r;
  r.model_name = "tiny";
  r.driver = "slider";
  r.follower = "block";
  r.driver_rotates = r.follower_rotates = false;
  for (int i = 0; i <= 50; ++i) {
    VariationSample s;
    s.driver = 100 + i * 2e-9;
    s.contact = true;
    s.nominal = 79;
    s.linear_lower = 79 - 1e-9 * (1 + i % 3);
    s.linear_upper = 79 + 1e-9 * (1 + i % 3);
    s.rss_lower = 79 - 5e-10;
    s.rss_upper = 79 + 5e-10;
    s.certified.lower = 79 - 2e-9 * (1 + i % 3);
    s.certified.upper = 79 + 2e-9 * (1 + i % 3);
    r.samples.push_back(s);
  }
  std::string svg = tolerance_band_svg(r);
  for (std::string anchor : {"middle", "end"}) {   // x labels, y labels
    std::regex label("text-anchor=\"" + anchor + "\" font-family=\"sans-serif\" font-size=\"11\">([^<]*)<");
    std::vector<std::string> labels;
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), label); it != std::sregex_iterator(); ++it)
      labels.push_back((*it)[1]);
    std::set<std::string> distinct(labels.begin(), labels.end());
    EXPECT_GE(labels.size(), 3u) << anchor;
    EXPECT_EQ(distinct.size(), labels.size()) << anchor << ": " << ::testing::PrintToString(labels);
  }
  EXPECT_NE(svg.find(">100 +<"), std::string::npos);   // the driver axis labelled as offsets
  EXPECT_EQ(svg.find("unbounded"), std::string::npos);

  // Positions without a certified band (an infinite end) are a gap in the picture; a line under
  // the title counts them among the positions in contact (one out of contact is not counted).
  for (std::size_t i = 0; i < r.samples.size(); i += 7) r.samples[i].certified.upper = std::numeric_limits<double>::infinity();
  for (std::size_t i = 3; i < r.samples.size(); i += 7) r.samples[i].certified.lower = -std::numeric_limits<double>::infinity();
  r.samples[1].contact = false;
  r.samples[2].contact = false;
  r.samples[2].certified.upper = std::numeric_limits<double>::infinity();
  svg = tolerance_band_svg(r);
  EXPECT_NE(svg.find(">certified band unbounded at 15 of 49 positions in contact (gaps in the red curves; the notes say why)<"),
            std::string::npos)
      << svg;
}

}  // namespace
}  // namespace hipair::render
