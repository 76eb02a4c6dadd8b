// Point location at the ends of a 1-D C-space's charts (session 32, hunt32b). A contact point
// exactly on a chart's end (a rotation charts' seam, a translation's motion limit) was answered
// as a contact (a vertex outside every cell) whatever the parts did there: where another feature
// pair overlaps at that configuration the answer claimed a contact inside blocked space. The
// location there is now the exact overlap oracle's answer at the (rational) chart end, kept by
// the build: a contact where the parts touch, the blocked cell where they overlap.
//
// The cases: a double-ended pointed arm turning about the origin whose tips graze a fixed stop
// exactly at 90 and 270 degrees (the seams t = +-1 of the two rotation charts), and a square
// peg translating along x whose right side meets a fixed wall exactly at its upper motion limit.
// Half of the frames hold also a small bump that the moving part overlaps at that chart end by a
// sliver (1e-20 of the sizes: no culling can certify it blocked, the contact point is kept).
// Generated sizes at scales 10^-300, 1 and 10^300; every chart end and every exact vertex is
// located and compared with the exact oracle. Mutation: the chart-end decision in locate_1d
// removed (the code before hunt32b) fails every bumped case (the ends located as contacts).
#include "curves/contact_curves.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using Random = std::mt19937_64;

Rational random_rational(Random& random, const Rational& lo, const Rational& hi, long den = 97) {
  long q = 1 + static_cast<long>(random() % static_cast<unsigned long>(den));
  long p = static_cast<long>(random() % static_cast<unsigned long>(q + 1));
  Rational u(p, q);
  u.canonicalize();
  Rational value = lo + u * (hi - lo);
  value.canonicalize();
  return value;
}

std::string text(const Rational& r) { return "\"" + r.get_str() + "\""; }
std::string point(const Rational& x, const Rational& y) { return "[" + text(x) + ", " + text(y) + "]"; }
// an axis-aligned box, counter-clockwise
std::string box(const Rational& x0, const Rational& y0, const Rational& x1, const Rational& y1) {
  return "{ \"start\": " + point(x0, y0) + ", \"edges\": [ { \"line_to\": " + point(x1, y0) + " }, { \"line_to\": " + point(x1, y1) +
         " }, { \"line_to\": " + point(x0, y1) + " }, { \"line_to\": " + point(x0, y0) + " } ] }";
}

std::vector<Rational> one_tiny_huge() {
  const mpz_class huge("1" + std::string(300, '0'));
  return {Rational(1), Rational(mpz_class(1), huge), Rational(huge)};
}

cspace::Overlap oracle(const Model& model, const CSpace& space, const ChartPoint& q) {
  std::size_t first = *model.find_part(space.first_part()), second = *model.find_part(space.second_part());
  cspace::PairAxes axes = cspace::pair_axes(model, first, second);
  cspace::ChartLayout layout = cspace::chart_layout(model, axes);
  layout.y_charts = {cspace::ChartAxis{cspace::ChartAxis::Kind::translation, false, Rational(0), Rational(0)}};
  return cspace::classify_overlap(model, axes, layout.x_charts[q.chart], layout.y_charts[0], cspace::ChartPoint{q.x, q.y});
}

struct Seen {
  std::size_t end_contacts = 0, end_overlaps = 0, end_points = 0;
};

// Location at q agrees with the oracle: blocked (a blocked cell, or a point inside one) where the
// parts overlap, a contact (a vertex outside every cell) or touching cell where they touch, free
// where they are apart. Returns the oracle's answer.
cspace::Overlap check(const Model& model, const CSpace& space, const ChartPoint& q, const std::string& where) {
  const Location location = space.locate(q);
  const cspace::Overlap truth = oracle(model, space, q);
  const bool in_cell = location.cell != no_index;
  const bool blocked = location.kind == Location::Kind::blocked || (in_cell && space.cells()[location.cell].kind == CellKind::blocked);
  const bool free = location.kind == Location::Kind::free || (in_cell && space.cells()[location.cell].kind == CellKind::free);
  const bool contact = location.kind == Location::Kind::touching ||
                       ((location.kind == Location::Kind::vertex || location.kind == Location::Kind::edge) && !in_cell);
  if (truth == cspace::Overlap::overlapping) EXPECT_TRUE(blocked && !contact) << where << " kind " << static_cast<int>(location.kind);
  if (truth == cspace::Overlap::touching) EXPECT_TRUE(contact) << where << " kind " << static_cast<int>(location.kind);
  if (truth == cspace::Overlap::apart) EXPECT_TRUE(free && !contact) << where << " kind " << static_cast<int>(location.kind);
  return truth;
}

// Every chart end and every exact vertex of `space`; counts the chart ends that are contact points.
void check_ends(const Model& model, const CSpace& space, Seen& seen) {
  for (std::size_t c = 0; c < space.charts().size(); ++c)
    for (const Rational& end : {space.charts()[c].x_lo, space.charts()[c].x_hi}) {
      bool contact_point = false;
      for (const CSpaceVertex& vertex : space.vertices())
        contact_point = contact_point || (vertex.chart == c && vertex.x.exact && vertex.x.lower == end);
      const cspace::Overlap truth = check(model, space, ChartPoint{c, end, Rational(0)}, "chart " + std::to_string(c) + " end " + end.get_str());
      if (!contact_point) continue;
      ++seen.end_points;
      seen.end_contacts += truth == cspace::Overlap::touching;
      seen.end_overlaps += truth == cspace::Overlap::overlapping;
    }
  for (const CSpaceVertex& vertex : space.vertices())
    if (vertex.x.exact)
      check(model, space, ChartPoint{vertex.chart, vertex.x.lower, Rational(0)},
            "vertex of chart " + std::to_string(vertex.chart) + " at " + vertex.x.lower.get_str().substr(0, 40));
}

const Rational sliver_ratio = Rational(mpz_class(1), mpz_class("100000000000000000000"));   // 1e-20

TEST(CSpaceLocateChartEnd, AnArmGrazingItsStopOnTheSeamsIsAContactOnlyWhereNothingElseOverlaps) {
  Random random(3232);
  Seen seen;
  for (int instance = 0; instance < 12; ++instance) {
    const Rational k = one_tiny_huge()[static_cast<std::size_t>(instance) % 3];
    const bool bump = instance % 2 == 1;
    const Rational w = random_rational(random, Rational(1, 2), Rational(2)) * k;
    const Rational L = random_rational(random, Rational(8), Rational(20)) * k;
    const Rational R = L + w + random_rational(random, Rational(1, 10), Rational(3)) * k;   // tips beyond the corners' circle
    const Rational a = random_rational(random, Rational(1), Rational(4)) * k;
    const std::string arm = "{ \"start\": " + point(-L, -w) + ", \"edges\": [ { \"line_to\": " + point(L, -w) + " }, { \"line_to\": " +
                            point(R, 0) + " }, { \"line_to\": " + point(L, w) + " }, { \"line_to\": " + point(-L, w) +
                            " }, { \"line_to\": " + point(-R, 0) + " }, { \"line_to\": " + point(-L, -w) + " } ] }";
    std::string frame = box(-a, R, a, R + 3 * k);   // the tips graze its lower side at 90 and 270 degrees
    if (bump) {   // the arm's side x = w at 90 degrees enters it by a sliver
      const Rational sliver = w * sliver_ratio, y = L * random_rational(random, Rational(1, 4), Rational(3, 4));
      frame += ", " + box(w - sliver, y, w + k / 2, y + k / 2);
    }
    const std::string json = R"({ "hipair": 1, "name": "arm-grazing-on-the-seams", "parts": [
        { "name": "arm", "motion": { "rotation": { "pivot": [0, 0] } }, "loops": [ )" + arm + R"( ] },
        { "name": "frame", "motion": "fixed", "loops": [ )" + frame + R"( ] } ],
      "pairs": [ { "parts": ["arm", "frame"] } ] })";
    SCOPED_TRACE("instance " + std::to_string(instance) + (bump ? " with a bump" : "") + " L " + L.get_str().substr(0, 30));
    Model model = read_model(json);
    CSpace space = CSpace::build(model, "arm", "frame");
    ASSERT_EQ(space.dimension(), 1);
    check_ends(model, space, seen);
  }
  EXPECT_GE(seen.end_contacts, 12u);   // 6 unbumped arms x 2 seams (on one chart's end or both)
  EXPECT_GE(seen.end_overlaps, 12u);
}

TEST(CSpaceLocateChartEnd, APegMeetingAWallAtItsMotionLimitIsAContactOnlyWhereNothingElseOverlaps) {
  Random random(3233);
  Seen seen;
  for (int instance = 0; instance < 12; ++instance) {
    const Rational k = one_tiny_huge()[static_cast<std::size_t>(instance) % 3];
    const bool bump = instance % 2 == 1;
    const Rational h = random_rational(random, Rational(1, 2), Rational(2)) * k;
    const Rational limit = random_rational(random, Rational(1, 2), Rational(3)) * k;
    const std::string peg = box(-h, -h, h, h);
    std::string frame = box(limit + h, -2 * h, limit + h + 3 * k, 2 * h);   // its left side: the peg's right side at the limit
    if (bump) {   // just inside the peg's top side at the limit, by a sliver, over its last eighth
      const Rational sliver = h * sliver_ratio, d = h / 8;
      frame += ", " + box(limit + h - 2 * d, h - sliver, limit + h - d, h + k);
    }
    const std::string json = R"({ "hipair": 1, "name": "peg-at-its-limit", "parts": [
        { "name": "frame", "motion": "fixed", "loops": [ )" + frame + R"( ] },
        { "name": "peg", "motion": { "translation": { "direction": [1, 0], "limits": [)" + text(-limit) + ", " + text(limit) +
                             R"(] } }, "loops": [ )" + peg + R"( ] } ],
      "pairs": [ { "parts": ["frame", "peg"] } ] })";
    SCOPED_TRACE("instance " + std::to_string(instance) + (bump ? " with a bump" : "") + " h " + h.get_str().substr(0, 30));
    Model model = read_model(json);
    CSpace space = CSpace::build(model, "frame", "peg");
    ASSERT_EQ(space.dimension(), 1);
    check_ends(model, space, seen);
  }
  EXPECT_GE(seen.end_contacts, 6u);
  EXPECT_GE(seen.end_overlaps, 6u);
}

}  // namespace
}  // namespace hipair
