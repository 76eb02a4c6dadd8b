// hipair::slice_near (session 21): the part of a chart's slice around one coordinate, located
// only as far as its nearest cell boundaries. Oracle: the whole slice (CSpace::slice). On the
// Geneva drive, the escapement's built pairs, the cam and the ratchet, at random rational slice
// values along both axes of every chart, around random coordinates, on slice points that are
// rational (the cam's follower heights at rational half-angle tangents: the `at` on a root
// case), and at both ends of every irrational point's isolating interval (a hair either side of
// it): the window's points are consecutive points of the slice, equal exactly (values and
// features), its intervals have the slice's cells and kinds, and it holds exactly the nearest
// `boundaries` points on either side of the coordinate and the point at it, if any.
#include <hipair/cspace.hpp>
#include <hipair/cspace_slice.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include "cspace_test_support.hpp"
#include "test_paths.hpp"
#include "tolerance/exact_order.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }


Rational random_in(std::mt19937_64& random, const Rational& lo, const Rational& hi) {
  Rational u(static_cast<long>(random() % 1000003), 1000003);
  Rational r = lo + (hi - lo) * u;
  r.canonicalize();
  return r;
}

struct Counts {
  std::size_t windows = 0, on_point = 0, empty = 0, truncated = 0, points_checked = 0;
};

// slice_near(chart, axis, value, at, boundaries) against the whole slice.
void expect_window(const CSpace& space, const Slice& full, const Rational& at, std::size_t boundaries, Counts& counts,
                   const std::string& where) {
  SCOPED_TRACE(where + ", at " + at.get_str() + ", boundaries " + std::to_string(boundaries));
  std::optional<Slice> near = slice_near(space, full.chart, full.axis, full.value, at, boundaries);
  ASSERT_TRUE(near);
  ++counts.windows;
  EXPECT_EQ(near->chart, full.chart);
  EXPECT_EQ(near->lower, full.lower);
  EXPECT_EQ(near->upper, full.upper);
  ASSERT_EQ(near->intervals.size(), near->points.size() + 1);
  std::size_t below = 0, above = 0;
  bool on = false;
  for (const Slice::Point& p : full.points) {
    int c = tolerance_detail::compare(p.at, at);
    below += c < 0;
    above += c > 0;
    on = on || c == 0;
  }
  std::size_t keep_below = std::min(boundaries, below), keep_above = std::min(boundaries, above);
  ASSERT_EQ(near->points.size(), keep_below + (on ? 1 : 0) + keep_above);
  counts.on_point += on;
  counts.empty += near->points.empty();
  counts.truncated += keep_below < below || keep_above < above;
  std::size_t first = below - keep_below;   // the window's first point in the whole slice
  for (std::size_t m = 0; m < near->points.size(); ++m) {
    const Slice::Point &p = near->points[m], &q = full.points[first + m];
    EXPECT_EQ(tolerance_detail::compare(p.at, q.at), 0) << "point " << m;
    EXPECT_EQ(p.features, q.features) << "point " << m;
    ++counts.points_checked;
  }
  for (std::size_t m = 0; m < near->intervals.size(); ++m) {
    const Slice::Interval &a = near->intervals[m], &b = full.intervals[first + m];
    EXPECT_EQ(a.cell, b.cell) << "interval " << m;
    EXPECT_EQ(a.kind, b.kind) << "interval " << m;
    // the sample lies inside the slice's interval
    if (first + m > 0) EXPECT_LT(tolerance_detail::compare(full.points[first + m - 1].at, a.sample), 0) << "interval " << m;
    if (first + m < full.points.size()) EXPECT_GT(tolerance_detail::compare(full.points[first + m].at, a.sample), 0) << "interval " << m;
  }
}

TEST(CSpaceSliceNear, WindowsAreTheWholeSlicesPointsAndCellsAroundTheCoordinate) {
  auto spaces = test::example_spaces();
  spaces.push_back(std::make_unique<CSpace>(CSpace::build(read_model_file(example("ratchet.json")), "wheel", "pawl")));
  ASSERT_GE(spaces.size(), 4u);
  std::mt19937_64 random(2111);
  Counts counts;
  for (std::size_t k = 0; k < spaces.size(); ++k) {
    const CSpace& space = *spaces[k];
    if (space.dimension() != 2) continue;
    for (std::size_t c = 0; c < space.charts().size(); ++c) {
      const CSpaceChart& chart = space.charts()[c];
      for (int trial = 0; trial < 10; ++trial) {
        SliceAxis axis = trial % 3 == 2 ? SliceAxis::y : SliceAxis::x;
        Rational value = axis == SliceAxis::x ? random_in(random, chart.x_lo, chart.x_hi) : random_in(random, chart.y_lo, chart.y_hi);
        std::vector<Slice> slices = space.slice(axis, value);
        const Slice* full = nullptr;
        for (const Slice& s : slices)
          if (s.chart == c) full = &s;
        ASSERT_NE(full, nullptr);
        std::string where = "space " + std::to_string(k) + " chart " + std::to_string(c) + (axis == SliceAxis::x ? " x = " : " y = ") +
                            value.get_str();
        std::size_t boundaries = 1 + random() % 3;
        for (int j = 0; j < 4; ++j) expect_window(space, *full, random_in(random, full->lower, full->upper), boundaries, counts, where);
        for (const Slice::Point& p : full->points) {
          if (p.at.exact) {
            expect_window(space, *full, p.at.lower, boundaries, counts, where);
          } else {
            expect_window(space, *full, p.at.lower, boundaries, counts, where);
            expect_window(space, *full, p.at.upper, boundaries, counts, where);
          }
        }
        expect_window(space, *full, full->lower, boundaries, counts, where);
        expect_window(space, *full, full->upper, boundaries, counts, where);
      }
    }
  }
  std::cout << "[ slice near ] " << counts.windows << " windows, " << counts.points_checked << " points checked, "
            << counts.on_point << " on a point, " << counts.empty << " without points, " << counts.truncated
            << " narrower than the slice\n";
  EXPECT_GE(counts.on_point, 8u);   // the cam's rational follower heights (the generator gives 13)
  EXPECT_GT(counts.truncated, 100u);
  EXPECT_GT(counts.empty, 0u);
}

TEST(CSpaceSliceNear, OutsideTheChartIsNulloptAndBadArgumentsAreErrors) {
  CSpace space = CSpace::build(read_model_file(example("cam-follower.json")), "cam", "follower");
  const CSpaceChart& chart = space.charts()[0];
  EXPECT_FALSE(slice_near(space, 0, SliceAxis::x, chart.x_hi + 1, chart.y_lo, 2));
  EXPECT_FALSE(slice_near(space, 0, SliceAxis::x, chart.x_lo, chart.y_hi + 1, 2));
  EXPECT_THROW(slice_near(space, space.charts().size(), SliceAxis::x, chart.x_lo, chart.y_lo, 2), GeometryError);
  EXPECT_THROW(slice_near(space, 0, SliceAxis::x, chart.x_lo, chart.y_lo, 0), GeometryError);
}

}  // namespace
}  // namespace hipair
