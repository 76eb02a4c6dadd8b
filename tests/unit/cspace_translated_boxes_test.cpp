// The exact bounding-box test in front of the overlap oracle for translating polygon pairs
// (src/cspace/translated_boxes.hpp, Session 75 poly75). Generated star-shaped polygons at
// scales 10^-300 ... 10^300, translating along generated rational directions; chart points drawn
// at random and made so that the moved boxes touch exactly on a coordinate, or miss by a hair
// either way. Checked against two oracles: the moved boxes computed from every posed vertex
// (world_map, an independent closed form: apart() is exactly "some coordinate has a positive
// gap"), and the exact overlap oracle (classify_overlap: wherever apart() answers, the parts are
// apart).
#include "cspace/translated_boxes.hpp"
#include "curves/pose.hpp"
#include "random_rationals.hpp"
#include "test_seed.hpp"

#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace hipair::cspace {
namespace {

using test_numbers::power_of_ten;
using test_numbers::random_rational;

// A star-shaped polygon about (cx, cy): n points on rational directions of increasing angle
// ((1 - t^2, 2t) / (1 + t^2) for increasing t in each half plane) at generated radii, scaled.
std::vector<Point> star(std::mt19937_64& random, int n, const Rational& cx, const Rational& cy, const Rational& scale) {
  std::vector<Rational> ts;
  for (int i = 0; i < n; ++i) ts.push_back(Rational(-1) + Rational(2 * i + 1, 2 * n) * 2);   // in (-1, 1): half a turn
  std::vector<Point> points;
  for (int half = 0; half < 2; ++half)
    for (int i = 0; i < n; ++i) {
      const Rational& t = ts[i];
      const Rational w = 1 + t * t;
      Rational ux = (1 - t * t) / w, uy = 2 * t / w;
      if (half == 1) ux = -ux, uy = -uy;   // the other half turn
      const Rational r = random_rational(random, Rational(1), Rational(3)) * scale;
      points.push_back(Point{Rational(cx + r * ux), Rational(cy + r * uy)});
    }
  return points;
}

std::string loop_json(const std::vector<Point>& points) {
  auto value = [](const Rational& q) { return "\"" + q.get_str() + "\""; };
  std::string text = "{ \"start\": [" + value(points[0].x) + ", " + value(points[0].y) + "], \"edges\": [";
  for (std::size_t i = 1; i <= points.size(); ++i) {
    const Point& p = points[i % points.size()];
    text += std::string(i > 1 ? ", " : "") + "{ \"line_to\": [" + value(p.x) + ", " + value(p.y) + "] }";
  }
  return text + "] }";
}

Model sliders(const std::vector<Point>& a, const std::vector<Point>& b, const Point& da, const Point& db) {
  auto direction = [](const Point& d) { return "[\"" + d.x.get_str() + "\", \"" + d.y.get_str() + "\"]"; };
  return read_model(R"({ "hipair": 1, "name": "boxes", "parts": [
    { "name": "a", "motion": { "translation": { "direction": )" + direction(da) + R"( } }, "loops": [ )" +
                    loop_json(a) + R"( ] },
    { "name": "b", "motion": { "translation": { "direction": )" + direction(db) + R"( } }, "loops": [ )" +
                    loop_json(b) + R"( ] } ] })");
}

// The moved boxes from every posed vertex: some coordinate with a positive gap.
bool boxes_apart_by_vertices(const Model& model, const PairAxes& axes, const ChartAxis& x, const ChartAxis& y,
                             const ChartPoint& q) {
  const RigidMap maps[2] = {world_map(model.parts[axes.first], axes.first_moves, x, q.x),
                            world_map(model.parts[axes.second], axes.second_moves, axes.first_moves ? y : x,
                                      axes.first_moves ? q.y : q.x)};
  Rational lo[2][2], hi[2][2];
  const std::size_t parts[2] = {axes.first, axes.second};
  for (int p = 0; p < 2; ++p) {
    bool first = true;
    for (const Loop& loop : model.parts[parts[p]].loops)
      for (const Edge& edge : loop.edges) {
        const Point w = maps[p].apply(edge.source);
        const Rational* c[2] = {&w.x, &w.y};
        for (int k = 0; k < 2; ++k) {
          if (first || *c[k] < lo[p][k]) lo[p][k] = *c[k];
          if (first || *c[k] > hi[p][k]) hi[p][k] = *c[k];
        }
        first = false;
      }
  }
  for (int k = 0; k < 2; ++k)
    if (hi[0][k] < lo[1][k] || hi[1][k] < lo[0][k]) return true;
  return false;
}

TEST(CSpaceTranslatedBoxes, ApartExactlyWhereTheMovedBoxesHaveAGapAndThereTheOracleSaysApart) {
  const std::uint64_t seed = test::test_seed(7575);
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 random(seed);
  const ChartAxis x{ChartAxis::Kind::translation, false, Rational(-1), Rational(1)};
  const ChartAxis y = x;
  int apart_count = 0, touching_boxes = 0, oracle_calls = 0;
  for (long exponent : {-300L, -30L, 0L, 30L, 300L})
    for (int round = 0; round < 4; ++round) {
      SCOPED_TRACE("scale 1e" + std::to_string(exponent) + " round " + std::to_string(round));
      const Rational scale = power_of_ten(exponent);
      const std::vector<Point> a = star(random, 2 + static_cast<int>(random() % 3), Rational(0), Rational(0), scale);
      const std::vector<Point> b = star(random, 2 + static_cast<int>(random() % 3), Rational(4) * scale,
                                        Rational(1) * scale, scale);
      // directions: the axes, or generated small rational ones (not parallel)
      Point da{Rational(1), Rational(0)}, db{Rational(0), Rational(1)};
      if (round >= 2) {
        da = Point{random_rational(random, Rational(1, 2), Rational(2)), random_rational(random, Rational(-1), Rational(1))};
        db = Point{random_rational(random, Rational(-1), Rational(1)), random_rational(random, Rational(1, 2), Rational(2))};
      }
      const Model model = sliders(a, b, da, db);
      const PairAxes axes = pair_axes(model, 0, 1);
      ASSERT_TRUE(axes.first_moves && axes.second_moves);
      const TranslatedBoxes boxes(model, axes);
      ASSERT_TRUE(boxes.applies());
      // chart points: generated, and made to close the gap between the boxes on x exactly
      // (part a's right side on part b's left side, both along their directions' x parts)
      std::vector<ChartPoint> points;
      for (int i = 0; i < 6; ++i)
        points.push_back(ChartPoint{random_rational(random, Rational(-12), Rational(12)) * scale,
                                    random_rational(random, Rational(-12), Rational(12)) * scale});
      Rational a_hi = a[0].x, b_lo = b[0].x;
      for (const Point& p : a) a_hi = std::max(a_hi, p.x);
      for (const Point& p : b) b_lo = std::min(b_lo, p.x);
      for (int i = 0; i < 3; ++i) {
        // s da.x + a_hi == r db.x + b_lo at a generated r: s = (r db.x + b_lo - a_hi) / da.x
        const Rational r = random_rational(random, Rational(-3), Rational(3)) * scale;
        const Rational s = (r * db.x + b_lo - a_hi) / da.x;
        const Rational hair = scale * Rational(1, 1 << 20) / da.x;
        for (const Rational& si : {s, Rational(s - hair), Rational(s + hair)}) points.push_back(ChartPoint{si, r});
      }
      for (const ChartPoint& q : points) {
        const bool apart = boxes.apart(q);
        ASSERT_EQ(apart, boxes_apart_by_vertices(model, axes, x, y, q)) << q.x << ", " << q.y;
        if (apart) {
          ++apart_count;
          ++oracle_calls;
          ASSERT_EQ(classify_overlap(model, axes, x, y, q), Overlap::apart) << q.x << ", " << q.y;
        } else {
          ++touching_boxes;
        }
      }
    }
  // both answers were exercised
  EXPECT_GT(apart_count, 20);
  EXPECT_GT(touching_boxes, 20);
  EXPECT_GT(oracle_calls, 0);
}

TEST(CSpaceTranslatedBoxes, NotForArcsOrRotation) {
  const Model arcs = read_model(R"({ "hipair": 1, "name": "arcs", "parts": [
    { "name": "a", "motion": { "translation": { "direction": [1, 0] } }, "loops": [ { "circle": { "center": [0, 0], "radius": 1 } } ] },
    { "name": "b", "motion": { "translation": { "direction": [0, 1] } }, "loops": [
      { "start": [5, 0], "edges": [ { "line_to": [6, 0] }, { "line_to": [6, 1] }, { "line_to": [5, 0] } ] } ] } ] })");
  const TranslatedBoxes boxes(arcs, pair_axes(arcs, 0, 1));
  EXPECT_FALSE(boxes.applies());
  EXPECT_FALSE(boxes.apart(ChartPoint{Rational(-100), Rational(100)}));
}

}  // namespace
}  // namespace hipair::cspace
