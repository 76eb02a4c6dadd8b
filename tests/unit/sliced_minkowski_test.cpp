// 3-DOF pairs at rational rotations (src/sliced): every slice's blocked faces make up exactly
// the Minkowski sum A + (-R B) of the fixed part and the turned free part (empty symmetric
// difference with CGAL's minkowski_sum_2), for random polygon pairs and a plate with a hole, at
// rational half-angle tangents and the half turn. (Includes CGAL: its own translation unit.)
#include "cspace/builder_impl.hpp"
#include "cspace_minkowski_support.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/sliced.hpp>

#include <CGAL/Cartesian.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Polygon_set_2.h>
#include <CGAL/minkowski_sum_2.h>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace hipair {
namespace {

using namespace minkowski_support;

Polygon loop_polygon(const Loop& loop, const Point& pivot, const Rational& c, const Rational& s, bool negate) {
  Polygon p;
  for (const auto& e : loop.edges) {
    Rational dx = e.source.x - pivot.x, dy = e.source.y - pivot.y;
    Rational x = pivot.x + c * dx - s * dy, y = pivot.y + s * dx + c * dy;
    if (negate) {
      x = -(c * dx - s * dy) - pivot.x;   // -(p + R (b - p)): the turned part, negated
      y = -(s * dx + c * dy) - pivot.y;
    }
    p.push_back(Point2(gmpq(x), gmpq(y)));
  }
  if (p.is_clockwise_oriented()) p.reverse_orientation();
  return p;
}

// The blocked offsets d: A meets p + R (B - p) + d, i.e. d in A + (-(p + R (B - p))).
void expect_slice_is_minkowski(const Model& model, const SlicedSpace& space, const SlicedAngle& angle) {
  Rational c = -1, s = 0;
  if (!angle.half_turn) {
    Rational d = 1 + angle.t * angle.t;
    c = (1 - angle.t * angle.t) / d;
    s = 2 * angle.t / d;
  }
  const Part& a = model.parts[0];
  const Part& b = model.parts[1];
  const Point pivot = b.motion.pivot;
  ASSERT_EQ(b.loops.size(), 1u);
  Polygon minus_b = loop_polygon(b.loops[0], pivot, c, s, true);
  PolygonSet expected;
  // A: its outer loops with their holes
  for (const auto& outer : a.loops) {
    if (outer.is_hole) continue;
    PolygonWithHoles piece(loop_polygon(outer, Point{0, 0}, 1, 0, false));
    for (const auto& hole : a.loops)
      if (hole.is_hole) {
        Polygon h = loop_polygon(hole, Point{0, 0}, 1, 0, false);
        h.reverse_orientation();
        piece.add_hole(h);
      }
    expected.join(CGAL::minkowski_sum_2(piece, minus_b));
  }
  auto slice = space.slice(angle);
  PolygonSet difference = blocked_region(*slice);
  EXPECT_FALSE(difference.is_empty());
  difference.symmetric_difference(expected);
  EXPECT_TRUE(difference.is_empty()) << "slice t = " << (angle.half_turn ? "pi" : angle.t.get_str())
                                     << ": blocked faces differ from the Minkowski sum";
  EXPECT_EQ(slice->statistics().circle_segment_charts, 1u);
}

std::string text(const Rational& r) { return "\"" + to_exact_string(r) + "\""; }

std::string polygon_json(const std::vector<std::pair<Rational, Rational>>& p) {
  std::string loop = R"({ "start": [)" + text(p[0].first) + ", " + text(p[0].second) + R"(], "edges": [ )";
  for (std::size_t i = 1; i <= p.size(); ++i)
    loop += std::string(i > 1 ? ", " : "") + R"({ "line_to": [)" + text(p[i % p.size()].first) + ", " +
            text(p[i % p.size()].second) + "] }";
  return loop + " ] }";
}

std::vector<std::pair<Rational, Rational>> star(std::mt19937_64& random, int k, double cx, double cy, double radius) {
  std::vector<std::pair<Rational, Rational>> points;
  for (int i = 0; i < k; ++i) {
    double angle = 2 * std::numbers::pi * (i + 0.15 + 0.7 * static_cast<double>(random() % 1000) / 1000.0) / k;
    double r = radius * (0.45 + 0.55 * static_cast<double>(random() % 1000) / 1000.0);
    Rational x(static_cast<long>(std::lround(16 * (cx + r * std::cos(angle)))), 16);
    Rational y(static_cast<long>(std::lround(16 * (cy + r * std::sin(angle)))), 16);
    x.canonicalize();
    y.canonicalize();
    points.emplace_back(x, y);
  }
  return points;
}

Model pair_model(const std::string& fixed_loops, const std::string& free_loop, const std::string& pivot) {
  return read_model(R"({ "hipair": 1, "name": "three-dof", "parts": [
    { "name": "fixed", "motion": "fixed", "loops": [ )" + fixed_loops + R"( ] },
    { "name": "free", "motion": { "planar": { "pivot": )" + pivot + R"( } }, "loops": [ )" + free_loop + R"( ] } ] })");
}

const std::vector<SlicedAngle> angles = {SlicedAngle{0, false},
                                         SlicedAngle{Rational(1, 3), false},
                                         SlicedAngle{Rational(-7, 5), false},
                                         SlicedAngle{Rational(22, 7), false},
                                         SlicedAngle{0, true}};

TEST(SlicedMinkowski, RandomPolygonPairsAtRationalRotations) {
  std::mt19937_64 random(4242);
  int compared = 0;
  for (int instance = 0; instance < 8; ++instance) {
    auto a = star(random, 3 + static_cast<int>(random() % 6), 0, 0, 5);
    auto b = star(random, 3 + static_cast<int>(random() % 6), 2, 1, 3);
    Model model;
    try {
      model = pair_model(polygon_json(a), polygon_json(b), "[\"1/2\", \"1\"]");
    } catch (const ModelError&) {
      continue;
    }
    SCOPED_TRACE("instance " + std::to_string(instance));
    SlicedBuildOptions options;
    options.cell_structure = false;
    SlicedSpace space = SlicedSpace::build(model, "fixed", "free", options);
    for (const auto& angle : angles) expect_slice_is_minkowski(model, space, angle);
    ++compared;
  }
  EXPECT_GE(compared, 6);
}

TEST(SlicedMinkowski, PlateWithAHoleAndAnLPeg) {
  Model model = pair_model(
      polygon_json({{-20, -20}, {20, -20}, {20, 20}, {-20, 20}}) + ", " +
          polygon_json({{-8, -6}, {8, -6}, {8, 6}, {-8, 6}}),
      polygon_json({{0, 0}, {6, 0}, {6, 1}, {1, 1}, {1, 4}, {0, 4}}), "[\"1\", \"1\"]");
  SlicedBuildOptions options;
  options.cell_structure = false;
  SlicedSpace space = SlicedSpace::build(model, "fixed", "free", options);
  for (const auto& angle : angles) expect_slice_is_minkowski(model, space, angle);
}

}  // namespace
}  // namespace hipair
