// PartLocator (oracle/overlap.hpp): a part prepared once and located at many points, as the
// blocked tester's certify_part locates its disks' centres. Oracle: locate_point at the identity,
// which prepares the part anew for every point. The same answer at every point of every example
// model's parts and of their copies scaled by 2^-1000 .. 2^1000: the parts' vertices, arc centres,
// points on edges (boundary), points a hair either side of a vertex, and random rationals with
// small and large denominators over the part's box.
#include "core/model_scale.hpp"
#include "oracle/overlap.hpp"
#include "test_paths.hpp"

#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

namespace hipair {
namespace {

using cspace::PointLocation;

// Points of interest of a part and random ones over its box.
std::vector<Point> probe_points(const Part& part, std::mt19937_64& random) {
  std::vector<Point> points;
  Rational lo_x, hi_x, lo_y, hi_y;
  bool first = true;
  std::size_t edges = 0;
  for (const Loop& loop : part.loops) edges += loop.edges.size();
  // about 24 edges' points per part (locate_point, the oracle, prepares the whole part per point)
  const std::size_t stride = edges / 24 + 1;
  std::size_t index = 0;
  for (const Loop& loop : part.loops)
    for (const Edge& edge : loop.edges) {
      const Point& a = edge.source;
      if (first || a.x < lo_x) lo_x = a.x;
      if (first || a.x > hi_x) hi_x = a.x;
      if (first || a.y < lo_y) lo_y = a.y;
      if (first || a.y > hi_y) hi_y = a.y;
      first = false;
      if (index++ % stride != random() % stride) continue;
      points.push_back(a);   // a vertex: boundary
      if (!edge.is_arc())
        points.push_back(Point{Rational((a.x + edge.target.x) / 2), Rational((a.y + edge.target.y) / 2)});   // boundary
      else
        points.push_back(edge.center);
      // a hair off the vertex, both ways, in both coordinates
      const Rational size = abs(edge.target.x - a.x) + abs(edge.target.y - a.y) + 1;
      const Rational hair = size / Rational(mpz_class(1) << 80);
      for (int sx : {-1, 0, 1})
        for (int sy : {-1, 0, 1})
          if (sx != 0 || sy != 0) points.push_back(Point{Rational(a.x + sx * hair), Rational(a.y + sy * hair)});
    }
  if (first) return points;
  const Rational width = hi_x - lo_x, height = hi_y - lo_y;
  for (int i = 0; i < 80; ++i) {
    const mpz_class denominator = i % 3 == 0 ? mpz_class(1000) : mpz_class(1) << 70;
    const Rational u(mpz_class(static_cast<unsigned long>(random() % 1200)) * denominator / 1000, denominator);
    const Rational v(mpz_class(static_cast<unsigned long>(random() % 1200)) * denominator / 1000, denominator);
    // [-0.1, 1.1] of the box in each coordinate
    points.push_back(Point{Rational(lo_x + (u - Rational(1, 10)) * width), Rational(lo_y + (v - Rational(1, 10)) * height)});
  }
  return points;
}

TEST(CSpacePartLocator, SameAsLocatePointOnEveryExamplePartAtEveryScale) {
  std::mt19937_64 random(32);
  std::size_t parts = 0, inside = 0, outside = 0, boundary = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(HIPAIR_EXAMPLES))) {
    if (entry.path().extension() != ".json") continue;
    Model model;
    try {
      model = read_model_file(entry.path());
    } catch (const std::exception&) {
      continue;   // templates that are not models by themselves
    }
    for (long shift : {0L, 1000L, -1000L, 37L}) {
      const Model scaled = shift == 0 ? model : scaled_model(model, shift);
      for (const Part& part : scaled.parts) {
        if (part.loops.empty()) continue;
        ++parts;
        const cspace::PartLocator locator(part);
        for (const Point& p : probe_points(part, random)) {
          const PointLocation expected = cspace::locate_point(part, cspace::RigidMap{}, p);
          ASSERT_EQ(locator.locate(p), expected) << entry.path() << " " << part.name << " shift " << shift << " at ("
                                                 << p.x << ", " << p.y << ")";
          inside += expected == PointLocation::inside;
          outside += expected == PointLocation::outside;
          boundary += expected == PointLocation::boundary;
        }
      }
    }
  }
  EXPECT_GT(parts, 100u);
  EXPECT_GT(inside, 1000u);
  EXPECT_GT(outside, 1000u);
  EXPECT_GT(boundary, 500u);
}

}  // namespace
}  // namespace hipair
