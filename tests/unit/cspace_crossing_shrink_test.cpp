// CSpace::first_crossing's Newton shrink of the crossing bracket (src/cspace/cspace_queries.cpp,
// first_crossing's `shrink`; switches cspace::newton_shrink() and cspace::skip_left() in src/cspace/crossing_shrink.hpp).
// A proposal only skips nodes of the halving's tree that hold a root of the one curve left (the
// halving would only have halved them); their siblings are evaluated by the same tests, in path
// order. So on generated motions — crossings aimed through
// a contact edge from anywhere in a chart, starts a few units in the last place (or 1e-15 ... 1e-3)
// off a contact curve, along random directions or the curve's tangent, and each crossing motion
// again over parameter intervals that put its crossing a few cells after a node boundary of the
// subdivision's tree — the answer with it must
// be the halving's, field for field (the proposed stretches are nodes of the halving's tree, so
// the final bracket is one of its cells; the status, grazing flag, cell left, a bracket that
// meets the halving's and is no wider are asserted first, for the message), and the bracket's
// ends are checked by exact point locations: the motion is in the start cell at u_lower and
// (unless grazing) no longer in it at u_upper.
#include "cspace/crossing_shrink.hpp"
#include "cspace_point_of.hpp"
#include "cspace_test_support.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::filesystem::path example(const std::string& name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; }
// What `compare` switches on and off: the whole Newton shrink (the oracle is the plain halving),
// or only its skipping of the siblings the curve's certified bound keeps free (cspace::skip_left;
// the oracle is the shrink evaluating them), with the counter of what the switch does.
struct Toggled {
  bool& (*flag)();
  std::size_t& (*counter)();
};
Toggled toggled{&cspace::newton_shrink, &cspace::newton_steps};
struct Switch {
  explicit Switch(bool on) : old(toggled.flag()) { toggled.flag() = on; }
  ~Switch() { toggled.flag() = old; }
  Switch(const Switch&) = delete;
  Switch& operator=(const Switch&) = delete;
  bool old;
};
struct Toggling {
  explicit Toggling(Toggled t) : old(toggled) { toggled = t; }
  ~Toggling() { toggled = old; }
  Toggling(const Toggling&) = delete;
  Toggling& operator=(const Toggling&) = delete;
  Toggled old;
};
using test::describe_crossing;
using test::axis_path;
using test::part_value;
using test::point_of;

struct Tally {
  int motions = 0, crossings = 0, identical = 0, narrower = 0, helped = 0, ends_checked = 0, shifted_from = 0;
  std::size_t steps = 0;
};


void compare(const CSpace& space, const MotionPath& path, const std::string& what, Tally& tally, bool shifted = false);

// The same motion over other parameter intervals [u_begin, u_begin + w], placed so that the
// crossing found falls k = -3 ... 4 cells of the new resolution after a node boundary
// u_begin + (j / 2^r) w of the subdivision's tree (r = 1 ... 24): a root just past a node's end
// is where a proposal must not skip nodes that do not hold it.
void shifted_motions(const CSpace& space, const MotionPath& path, const MotionCrossing& crossing,
                     const std::string& what, Tally& tally, std::mt19937_64& random) {
  Rational l = crossing.u_lower;
  Rational w = std::min(Rational(l - path.u_begin), Rational(path.u_end - l));
  if (w <= 0) return;
  const Rational cells = Rational(mpz_class(1) << 44);
  for (int trial = 0; trial < 6; ++trial) {
    int r = 1 + static_cast<int>(random() % 24);
    long j = 2 * static_cast<long>(random() % (1UL << std::min(r - 1, 20))) + 1;
    if (j >= (1L << r)) j = 1;
    int k = static_cast<int>(random() % 8) - 3;
    MotionPath moved = path;
    Rational width = w / 2;
    Rational at = Rational(j) / Rational(mpz_class(1) << r);
    moved.u_begin = l - at * width - Rational(k) * width / cells;
    moved.u_end = moved.u_begin + width;
    moved.u_begin.canonicalize();
    moved.u_end.canonicalize();
    if (moved.u_begin < path.u_begin || moved.u_end > path.u_end) continue;
    compare(space, moved, what + " shifted r " + std::to_string(r) + " k " + std::to_string(k), tally, true);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

void compare(const CSpace& space, const MotionPath& path, const std::string& what, Tally& tally, bool shifted) {
  MotionCrossing with, without;
  bool with_error = false, without_error = false;
  std::size_t before = toggled.counter();
  {
    Switch on(true);
    try {
      with = space.first_crossing(path);
    } catch (const Error&) {
      with_error = true;
    }
  }
  std::size_t used = toggled.counter() - before;
  {
    Switch off(false);
    try {
      without = space.first_crossing(path);
    } catch (const Error&) {
      without_error = true;
    }
  }
  ASSERT_EQ(toggled.counter() - before, used) << "the switch must turn the shrink (or its skip) off";
  ASSERT_EQ(with_error, without_error) << what;
  ++tally.motions;
  if (with_error) return;
  tally.steps += used;
  tally.helped += used > 0;
  ASSERT_EQ(static_cast<int>(with.status), static_cast<int>(without.status)) << what;
  ASSERT_EQ(with.grazing, without.grazing) << what;
  ASSERT_EQ(with.cell_left.valid(), without.cell_left.valid()) << what;
  if (with.cell_left.valid()) ASSERT_EQ(with.cell_left.index(), without.cell_left.index()) << what;
  // the final bracket is a cell of the same tree as the halving's: the same answer, field for field
  ASSERT_EQ(describe_crossing(space, with), describe_crossing(space, without)) << what;
  ++tally.identical;
  if (with.status != CrossingStatus::crossing) {
    ASSERT_EQ(with.u_lower, without.u_lower) << what;
    ASSERT_EQ(with.u_upper, without.u_upper) << what;
    return;
  }
  ++tally.crossings;
  // both brackets hold the first crossing: they meet; the new one is no wider
  ASSERT_LE(std::max(with.u_lower, without.u_lower), std::min(with.u_upper, without.u_upper)) << what;
  Rational width = with.u_upper - with.u_lower, old_width = without.u_upper - without.u_lower;
  ASSERT_LE(width, old_width) << what << "\n" << describe_crossing(space, with) << "\n" << describe_crossing(space, without);
  tally.narrower += width < old_width;
  if (!shifted && !with.grazing) {
    std::mt19937_64 random(tally.motions);
    shifted_motions(space, path, with, what, tally, random);
    if (::testing::Test::HasFatalFailure()) return;
    ++tally.shifted_from;
  }
  if (used == 0) return;
  // the ends by exact point location
  MotionCrossing at = space.first_crossing(point_of(path, with.u_lower));
  if (!(at.status == CrossingStatus::starts_in_contact && at.grazing)) {
    ASSERT_EQ(static_cast<int>(at.status), static_cast<int>(CrossingStatus::none)) << what << " at u_lower";
    ASSERT_EQ(at.cell_left.index(), with.cell_left.index()) << what << " at u_lower";
    ++tally.ends_checked;
  }
  if (!with.grazing) {
    MotionCrossing end = space.first_crossing(point_of(path, with.u_upper));
    ASSERT_FALSE(end.status == CrossingStatus::none && end.cell_left.index() == with.cell_left.index())
        << what << " at u_upper: still in the start cell";
    ++tally.ends_checked;
  }
}

// Generated motions on one space. Kind 0: from a random point of a real edge's chart toward a
// point of the edge and past it (a transversal crossing, cubic in u); kind 1: from a few ulps (or
// 1e-15 ... 1e-3) off a real edge, in a random direction or along its tangent; kind 2: from
// anywhere in a chart, in a random direction.
void generated_motions(const CSpace& space, int count, std::uint64_t seed, Tally& tally) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  const std::vector<CSpaceChart>& charts = space.charts();
  const std::vector<std::size_t> real_edges = test::real_edges(space);
  const bool two = space.dimension() == 2;
  for (int i = 0; i < count; ++i) {
    int kind = real_edges.empty() ? 2 : static_cast<int>(random() % 3);
    std::size_t c = random() % charts.size();
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool tangent = false;
    if (kind != 2) {
      std::size_t e = real_edges[random() % real_edges.size()];
      const CSpaceEdge& edge = space.edges()[e];
      c = edge.chart;
      double xa = edge.x_chart.lower, xb = edge.x_chart.upper;
      double x = xa + (xb - xa) * (0.02 + 0.96 * unit(random));
      double y = 0, slope = 0;
      if (two) {
        try {
          y = space.evaluate(e, x).value;
          EdgeDerivatives d = space.derivatives(EdgeId(e), Rational(x));
          slope = 0.5 * (d.dy.lower + d.dy.upper);
        } catch (const GeometryError&) {
          kind = 2;
        }
      } else {
        x = edge.x_chart.lower;
      }
      if (kind == 0) {
        const CSpaceChart& chart = charts[c];
        x0 = chart.x_lo.get_d() + (chart.x_hi.get_d() - chart.x_lo.get_d()) * unit(random);
        if (two) y0 = chart.y_lo.get_d() + (chart.y_hi.get_d() - chart.y_lo.get_d()) * unit(random);
        double past = 1 + 0.5 * unit(random);
        x1 = x0 + (x - x0) * past;
        y1 = y0 + (y - y0) * past;
      } else if (kind == 1) {
        x0 = x;
        y0 = y;
        double* moved = two ? &y0 : &x0;
        if (random() % 2 == 0) {
          int k = static_cast<int>(random() % 9) - 4;
          for (int j = 0; j < std::abs(k); ++j) *moved = std::nextafter(*moved, k > 0 ? 1e300 : -1e300);
        } else {
          *moved += sym(random) * std::pow(10.0, -15 + 12 * unit(random));
        }
        tangent = two && std::isfinite(slope) && random() % 2 == 0;
        double scale = std::pow(10.0, -6 + 5 * unit(random));
        double dx = tangent ? 1 : sym(random), dy = tangent ? slope : sym(random);
        x1 = x0 + dx * scale;
        y1 = y0 + dy * scale;
      }
    }
    const CSpaceChart& chart = charts[c];
    if (kind == 2) {
      x0 = chart.x_lo.get_d() + (chart.x_hi.get_d() - chart.x_lo.get_d()) * unit(random);
      if (two) y0 = chart.y_lo.get_d() + (chart.y_hi.get_d() - chart.y_lo.get_d()) * unit(random);
      double scale = std::pow(10.0, -2 + 2 * unit(random));
      x1 = x0 + sym(random) * scale;
      y1 = y0 + sym(random) * scale;
    }
    // chart values to part coordinates; a cubic through both, with a random bend
    double qx0 = part_value(chart.x_kind, chart.x_half_turn, x0), qx1 = part_value(chart.x_kind, chart.x_half_turn, x1);
    double qy0 = two ? part_value(chart.y_kind, chart.y_half_turn, y0) : 0;
    double qy1 = two ? part_value(chart.y_kind, chart.y_half_turn, y1) : 0;
    double bend = (random() % 3 == 0) ? 0.0 : 0.3 * sym(random);
    MotionPath path;
    double vx = qx1 - qx0, vy = qy1 - qy0;
    path.x = axis_path(chart.x_kind, {qx0, vx * (1 - bend), vx * bend, 0});
    if (two) path.y = axis_path(chart.y_kind, {qy0, vy * (1 + bend), -vy * bend * 0.5, -vy * bend * 0.5});
    std::ostringstream what;
    what.precision(17);
    what << space.first_part() << ":" << space.second_part() << " motion " << i << " kind " << kind << " chart " << c
         << " from " << x0 << ", " << y0 << " to " << x1 << ", " << y1 << " tangent " << tangent;
    compare(space, path, what.str(), tally);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

void report(const Tally& tally) {
  std::printf("motions %d crossings %d identical %d narrower %d helped %d steps %zu ends checked %d shifted from %d\n",
              tally.motions, tally.crossings, tally.identical, tally.narrower, tally.helped, tally.steps, tally.ends_checked,
              tally.shifted_from);
  ::testing::Test::RecordProperty("motions", tally.motions);
  ::testing::Test::RecordProperty("crossings", tally.crossings);
  ::testing::Test::RecordProperty("helped", tally.helped);
}

void generated_on_examples(Tally& tally) {
  test::on_example_spaces({{900, 41}, {400, 43}, {300, 47}},
                          [&](const CSpace& space, const test::ExampleSamples& run) { generated_motions(space, run.samples, run.seed, tally); });
  ASSERT_FALSE(::testing::Test::HasFatalFailure());
}

void generated_on_degenerate_spaces(Tally& tally) {
  for (const test::NamedSpace& named : test::degenerate_spaces()) {
    generated_motions(*named.space, 120, 53, tally);
    ASSERT_FALSE(::testing::Test::HasFatalFailure()) << named.file;
  }
}

// The generated motions of `generate` compared and reported.
Tally compared(void (*generate)(Tally&)) {
  Tally tally;
  generate(tally);
  if (!::testing::Test::HasFatalFailure()) report(tally);
  return tally;
}

// (the proposals without session 63's narrowing, cspace::newton_refine: with it a proposal goes
// deeper at once and fewer are taken — RefinedProposalsLeaveTheAnswerOnGeneratedMotions below
// compares the shrink with and without it on these motions)
TEST(CSpaceCrossingShrink, AnswersEqualTheHalvingsOnGeneratedMotions) {
  test::FlagSwitch<&cspace::newton_refine> unrefined(false);
  Tally tally = compared(generated_on_examples);
  ASSERT_FALSE(HasFatalFailure());
  EXPECT_GE(tally.motions, 4000);
  EXPECT_GE(tally.crossings, 1800);
  EXPECT_GE(tally.helped, 1700);   // the shrink is exercised
  EXPECT_GE(tally.steps, 5500);
  EXPECT_GE(tally.ends_checked, 3000);
}

TEST(CSpaceCrossingShrink, AnswersEqualTheHalvingsOnDegenerateSpaces) {
  Tally tally = compared(generated_on_degenerate_spaces);
  ASSERT_FALSE(HasFatalFailure());
  EXPECT_GE(tally.motions, 1500);
  EXPECT_GE(tally.helped, 300);
}

// The skip alone (cspace::skip_left, on by default in the tests above): the siblings left of a
// proposed node, and a halving's first half, that the one curve's certified mean-value bound
// keeps free are not evaluated. Against the shrink that evaluates them, on the same generated
// motions: the same answer field for field (no crossing lies in a skipped stretch, and the
// shrink's evaluation excludes every one of them here), the brackets' ends located exactly.
TEST(CSpaceCrossingShrink, SkippedSiblingsLeaveTheAnswerOnGeneratedMotions) {
  Toggling skip(Toggled{&cspace::skip_left, &cspace::skipped_left});
  Tally tally;
  generated_on_examples(tally);
  ASSERT_FALSE(HasFatalFailure());
  generated_on_degenerate_spaces(tally);
  ASSERT_FALSE(HasFatalFailure());
  report(tally);
  EXPECT_GE(tally.motions, 5500);
  EXPECT_GE(tally.crossings, 2500);
  EXPECT_GE(tally.helped, 1000);   // motions with a stretch skipped
  EXPECT_GE(tally.steps, 3000);    // stretches skipped
}

// Session 63's narrowing of the proposals (cspace::newton_refine: Newton steps from anchors
// inside the proposed cells, and the left siblings up to the last anchor skipped as certified
// free). Against the shrink without it, on the same generated motions (and their shifted
// copies, whose roots lie a few cells past a node boundary): the same answer field for field,
// the brackets' ends located exactly.
TEST(CSpaceCrossingShrink, RefinedProposalsLeaveTheAnswerOnGeneratedMotions) {
  Toggling refine(Toggled{&cspace::newton_refine, &cspace::newton_refine_steps});
  Tally tally;
  generated_on_examples(tally);
  ASSERT_FALSE(HasFatalFailure());
  generated_on_degenerate_spaces(tally);
  ASSERT_FALSE(HasFatalFailure());
  report(tally);
  EXPECT_GE(tally.motions, 5500);
  EXPECT_GE(tally.crossings, 2500);
  EXPECT_GE(tally.helped, 300);   // motions with a Newton step from an anchor
  EXPECT_GE(tally.ends_checked, 3000);
}

}  // namespace
}  // namespace hipair
