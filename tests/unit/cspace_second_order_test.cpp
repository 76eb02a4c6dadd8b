// CSpace::first_crossing's second-order (Taylor) exclusion of the stretches next to a sliding
// start (src/cspace/cspace_queries.cpp, MotionScanner::second_order_excludes; switch
// cspace::second_order() in src/cspace/angle_filter.hpp). It only adds certified exclusions,
// so on generated sliding starts — a point a few units in the last place (or 1e-15 ... 1e-9) off
// a contact edge, moving along the edge's tangent with the edge's curvature plus a margin toward
// either side, over 1e-6 ... 0.1 of a chart unit — every answer must be the one of the query
// without it (the exact path of the subdivision), field for field; and the free stretch it
// reports is checked against exact point locations along the path.
#include "cspace/angle_filter.hpp"
#include "cspace_point_of.hpp"
#include "cspace_test_support.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }
using Switch = test::FlagSwitch<&cspace::second_order>;
using test::describe_crossing;
using test::axis_path;
using test::point_of;


struct Tally {
  std::map<int, int> status;
  int motions = 0, helped = 0, sampled = 0, decided = 0;
  std::size_t exclusions = 0;
};

// The part coordinate's polynomial (ascending, degree 3) of a chart path t0 + t1 u + t2 u^2:
// angle = phase + 2 atan(t) to third order in u, or the offset itself.
std::vector<double> part_polynomial(AxisKind kind, bool half_turn, double t0, double t1, double t2) {
  if (kind == AxisKind::translation) return {t0, t1, t2, 0};
  double w = 1 + t0 * t0;
  double g1 = 2 / w, g2 = -4 * t0 / (w * w), g3 = (12 * t0 * t0 - 4) / (w * w * w);
  return {(half_turn ? std::numbers::pi : 0.0) + 2 * std::atan(t0), g1 * t1, g1 * t2 + g2 * t1 * t1 / 2,
          g2 * t1 * t2 + g3 * t1 * t1 * t1 / 6};
}


// With and without the second-order form: the same answer (both or neither throw). Where the
// motion is reported free up to u_lower (none: u_end), exact point locations at eight places of
// [u_begin, u_lower] must not contradict it: each one is in the start cell or undecided (a
// point within the resolution of a curve, reported as a grazing start in contact).
void compare_nested(const CSpace& space, const MotionPath& path, const std::string& what, Tally& tally);
bool nested_comparison = false;   // sliding_starts compares the nested form on and off (compare_nested)

void compare(const CSpace& space, const MotionPath& path, const std::string& what, Tally& tally) {
  if (nested_comparison) return compare_nested(space, path, what, tally);
  std::string with, without;
  MotionCrossing answer;
  std::size_t before = cspace::second_order_exclusions();
  {
    Switch on(true);
    try {
      answer = space.first_crossing(path);
      with = describe_crossing(space, answer);
    } catch (const Error& e) {
      with = std::string("error: ") + e.what();
    }
  }
  std::size_t used = cspace::second_order_exclusions() - before;
  {
    Switch off(false);
    try {
      without = describe_crossing(space, space.first_crossing(path));
    } catch (const Error& e) {
      without = std::string("error: ") + e.what();
    }
  }
  ASSERT_EQ(with, without) << what;
  ASSERT_EQ(cspace::second_order_exclusions() - before, used) << "the switch must turn the form off";
  ++tally.motions;
  ++tally.status[static_cast<int>(answer.status)];
  tally.exclusions += used;
  tally.helped += used > 0;
  if (used == 0 || (answer.status != CrossingStatus::none && answer.status != CrossingStatus::crossing)) return;
  for (int k = 1; k <= 8; ++k) {
    Rational u = path.u_begin + (answer.u_lower - path.u_begin) * Rational(k, 8);
    MotionCrossing at = space.first_crossing(point_of(path, u));
    ++tally.sampled;
    if (at.status == CrossingStatus::starts_in_contact && at.grazing) continue;
    ++tally.decided;
    ASSERT_EQ(static_cast<int>(at.status), static_cast<int>(CrossingStatus::none)) << what << " at u = " << u;
    ASSERT_EQ(at.cell_left.index(), answer.cell_left.index()) << what << " at u = " << u;
  }
}

// Generated sliding starts on one space (see the file comment). 2-D: along a real edge's
// tangent with its certified curvature plus a margin; 1-D: from next to a contact value with a
// tiny velocity and an acceleration either way (f' near 0 at the start as well).
// `along`: also accelerate along the edge (x'' != 0; not on the degenerate spaces, where a motion
// along a straight contact edge at zero clearance keeps the first-order subdivision at its finest
// stretches over the whole step: millions of them, too slow for the comparison).
void sliding_starts(const CSpace& space, int count, std::uint64_t seed, Tally& tally, bool along = true) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  const std::vector<CSpaceChart>& charts = space.charts();
  const std::vector<std::size_t> real_edges = test::real_edges(space);
  if (real_edges.empty()) return;
  const bool two = space.dimension() == 2;
  for (int i = 0; i < count; ++i) {
    std::size_t e = real_edges[random() % real_edges.size()];
    const CSpaceEdge& edge = space.edges()[e];
    const CSpaceChart& chart = charts[edge.chart];
    double scale = std::pow(10.0, -6 + 5 * unit(random));
    // a few ulps off, either way, or 1e-15 ... 1e-9 off
    auto moved = [&](double v) {
      if (random() % 2 == 0) {
        int k = static_cast<int>(random() % 13) - 6;
        for (int j = 0; j < std::abs(k); ++j) v = std::nextafter(v, k > 0 ? 1e300 : -1e300);
        return v;
      }
      return v + sym(random) * std::pow(10.0, -15 + 6 * unit(random));
    };
    MotionPath path;
    if (two) {
      double xa = edge.x_chart.lower, xb = edge.x_chart.upper;
      double x0 = xa + (xb - xa) * (0.02 + 0.96 * unit(random));
      double y0 = 0, slope = 0, bend = 0;
      try {
        y0 = space.evaluate(e, x0).value;
        EdgeDerivatives d = space.derivatives(EdgeId(e), Rational(x0));
        slope = 0.5 * (d.dy.lower + d.dy.upper);
        bend = 0.5 * (d.d2y.lower + d.d2y.upper);
      } catch (const GeometryError&) {
        continue;
      }
      if (!std::isfinite(slope) || !std::isfinite(bend)) continue;
      y0 = moved(y0);
      double direction = random() % 2 == 0 ? 1 : -1;
      // the edge's own second-order term plus a margin toward either side (or none)
      double margin = random() % 4 == 0 ? 0.0 : sym(random) * std::pow(10.0, -3 + 4 * unit(random)) * (1 + std::abs(bend));
      // x = x0 + t1 u + c u^2 (c: an acceleration along the edge, or none), y along the edge to
      // second order: y0 + slope (t1 u + c u^2) + (bend / 2 + margin) t1^2 u^2
      double t1 = direction * scale;
      double c = !along || random() % 2 == 0 ? 0.0 : sym(random) * scale;
      path.x = axis_path(chart.x_kind, part_polynomial(chart.x_kind, chart.x_half_turn, x0, t1, c));
      path.y = axis_path(chart.y_kind, part_polynomial(chart.y_kind, chart.y_half_turn, y0, slope * t1,
                                                       slope * c + (bend / 2 + margin) * t1 * t1));
    } else {
      double x0 = moved(random() % 2 == 0 ? edge.x_chart.lower : edge.x_chart.upper);
      double v = sym(random) * scale * std::pow(10.0, -8 * unit(random));
      double w = sym(random) * scale;
      path.x = axis_path(chart.x_kind, part_polynomial(chart.x_kind, chart.x_half_turn, x0, v, w));
    }
    std::ostringstream what;
    what.precision(17);
    what << space.first_part() << ":" << space.second_part() << " motion " << i << " edge " << e << " chart "
         << edge.chart << " scale " << scale;
    compare(space, path, what.str(), tally);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

// The exact point locations at eight places of [u_begin, answer.u_lower]: each in the answer's
// start cell or undecided (a point within the resolution of a curve, a grazing start)
void check_free_before(const CSpace& space, const MotionPath& path, const MotionCrossing& answer, const std::string& what,
                       Tally& tally) {
  for (int k = 1; k <= 8; ++k) {
    Rational u = path.u_begin + (answer.u_lower - path.u_begin) * Rational(k, 8);
    MotionCrossing at = space.first_crossing(point_of(path, u));
    ++tally.sampled;
    if (at.status == CrossingStatus::starts_in_contact && at.grazing) continue;
    ++tally.decided;
    ASSERT_EQ(static_cast<int>(at.status), static_cast<int>(CrossingStatus::none)) << what << " at u = " << u;
    ASSERT_EQ(at.cell_left.index(), answer.cell_left.index()) << what << " at u = " << u;
  }
}

// The summed second-order form with and without the nested one (cspace::nested_taylor): the
// same answer, or — where the nested form excludes a stretch the summed one reported as a
// grazing bracket (a possible touch the subdivision could not decide) — a later answer from the
// same start cell, free before it by exact point locations. `tally.helped` counts the later ones.
void compare_nested(const CSpace& space, const MotionPath& path, const std::string& what, Tally& tally) {
  MotionCrossing with, without;
  bool with_error = false, without_error = false;
  const std::size_t before = cspace::nested_taylor_exclusions();
  {
    test::FlagSwitch<&cspace::nested_taylor> on(true);
    try {
      with = space.first_crossing(path);
    } catch (const Error&) {
      with_error = true;
    }
  }
  const std::size_t used = cspace::nested_taylor_exclusions() - before;
  {
    test::FlagSwitch<&cspace::nested_taylor> off(false);
    try {
      without = space.first_crossing(path);
    } catch (const Error&) {
      without_error = true;
    }
  }
  ASSERT_EQ(cspace::nested_taylor_exclusions() - before, used) << "the switch must turn the nested form off";
  ASSERT_EQ(with_error, without_error) << what;
  ++tally.motions;
  tally.exclusions += used;
  if (with_error) return;
  ++tally.status[static_cast<int>(with.status)];
  const std::string a = describe_crossing(space, with), b = describe_crossing(space, without);
  if (a == b) return;
  ASSERT_GT(used, 0u) << what << ": answers differ without a nested exclusion";
  ASSERT_EQ(static_cast<int>(without.status), static_cast<int>(CrossingStatus::crossing)) << what << "\n" << a << "\n" << b;
  ASSERT_TRUE(without.grazing) << what << "\n" << a << "\n" << b;
  ASSERT_TRUE(with.status == CrossingStatus::none || with.status == CrossingStatus::crossing) << what << "\n" << a;
  ASSERT_EQ(with.cell_left.index(), without.cell_left.index()) << what;
  ASSERT_GE(with.u_lower, without.u_upper) << what << "\n" << a << "\n" << b;
  ++tally.helped;
  check_free_before(space, path, with, what, tally);
}

void report(Tally tally) {
  std::printf("motions %d (second-order exclusions in %d, %zu curves) crossing %d none %d in contact %d; "
              "sampled %d, decided %d\n",
              tally.motions, tally.helped, tally.exclusions, tally.status[1], tally.status[0], tally.status[2],
              tally.sampled, tally.decided);
  ::testing::Test::RecordProperty("motions", tally.motions);
  ::testing::Test::RecordProperty("helped", tally.helped);
  ::testing::Test::RecordProperty("decided_samples", tally.decided);
}

TEST(CSpaceSecondOrder, SlidingStartsGiveTheAnswersOfTheFirstOrderSubdivision) {
  Tally tally;
  test::on_example_spaces({{1000, 19}, {500, 23}, {300, 29}},
                          [&](const CSpace& space, const test::ExampleSamples& run) { sliding_starts(space, run.samples, run.seed, tally); });
  ASSERT_FALSE(HasFatalFailure());
  report(tally);
  EXPECT_GE(tally.motions, 2000);
  EXPECT_GE(tally.helped, 320);   // the form is exercised
  EXPECT_GE(tally.status[static_cast<int>(CrossingStatus::crossing)], 200);
  EXPECT_GE(tally.status[static_cast<int>(CrossingStatus::none)], 200);
  EXPECT_GE(tally.decided, 2500);
}

// (the summed Taylor form alone: session 63's nested form, cspace::nested_taylor, also excludes
// the first cell of some starts at a vertex of vertex-on-vertex.json, where the first-order
// subdivision reports a grazing touch — CSpaceNestedTaylor.DegenerateStartsAreTheAnswersWithoutIt
// checks those answers by exact point locations)
TEST(CSpaceSecondOrder, SlidingStartsOnDegenerateSpaces) {
  test::FlagSwitch<&cspace::nested_taylor> summed(false);
  Tally tally;
  for (const test::NamedSpace& named : test::degenerate_spaces()) {
    sliding_starts(*named.space, 200, 31, tally, false);
    ASSERT_FALSE(HasFatalFailure()) << named.file;
  }
  report(tally);
  EXPECT_GE(tally.motions, 650);
  EXPECT_GE(tally.helped, 45);
}

// The nested Taylor form on the degenerate spaces' sliding starts (the motions of
// SlidingStartsOnDegenerateSpaces): answers as without it, or later ones from grazing brackets,
// checked free by exact point locations (compare_nested).
TEST(CSpaceNestedTaylor, DegenerateStartsAreTheAnswersWithoutIt) {
  nested_comparison = true;
  Tally tally;
  for (const test::NamedSpace& named : test::degenerate_spaces()) {
    sliding_starts(*named.space, 200, 31, tally, false);
    if (HasFatalFailure()) break;
  }
  nested_comparison = false;
  ASSERT_FALSE(HasFatalFailure());
  std::printf("motions %d, nested exclusions %zu, later answers from grazing brackets %d (points sampled %d, decided %d)\n",
              tally.motions, tally.exclusions, tally.helped, tally.sampled, tally.decided);
  EXPECT_GE(tally.motions, 650);
  EXPECT_GE(tally.exclusions, 1u);
}

}  // namespace
}  // namespace hipair
