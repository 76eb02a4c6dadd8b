// The reader orients every loop (outlines counter-clockwise, holes clockwise) by the sign of its
// enclosed area: exact for the polygon, a certified enclosure where arcs contribute
// (src/model/validate_geometry.cpp). Session 37 (tol37) takes that sign from 64-bit enclosures
// first and from the working precision (256 bits) only where they leave it open. Generated
// cases on both sides of that line: thin circular segments (an arc of half-angle about 2t and
// its chord; area about (2/3) r^2 (2t)^3, the arc and chord terms cancelling to a relative 4t^2)
// with t from 1/2 down to 10^-13 (below 2^-32 the 64-bit enclosures cannot decide), at scales
// 10^-30 ... 10^30, moved off the origin, written counter-clockwise and clockwise, alone and as a
// hole in a square. Oracle: the orientation the loop was written with (known by construction).
// Mutation (run and reverted): no working-precision pass (the 64-bit sign or "encloses no
// area") -> the thinnest segments are refused ("cannot decide the loop's orientation").
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <gmpxx.h>

#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

std::string text(const mpq_class& q) { return "\"" + q.get_str() + "\""; }
std::string point(const mpq_class& x, const mpq_class& y) { return "[" + text(x) + ", " + text(y) + "]"; }

// A thin circular segment about (cx, cy): the arc from P- = r((1 - t^2), -2t) / (1 + t^2) to
// P+ = r((1 - t^2), 2t) / (1 + t^2) counter-clockwise and its chord (or the same loop written
// clockwise from P+).
std::string segment_loop(const mpq_class& r, const mpq_class& t, const mpq_class& cx, const mpq_class& cy, bool ccw) {
  mpq_class d = 1 + t * t;
  mpq_class x = r * (1 - t * t) / d + cx, y = r * 2 * t / d;
  mpq_class lo = cy - y, hi = cy + y;
  const mpq_class& y0 = ccw ? lo : hi;
  const mpq_class& y1 = ccw ? hi : lo;
  return "{ \"start\": " + point(x, y0) + ", \"edges\": [ { \"arc_to\": " + point(x, y1) + ", \"center\": " +
         point(cx, cy) + ", \"dir\": \"" + (ccw ? "ccw" : "cw") + "\" }, { \"line_to\": " + point(x, y0) + " } ] }";
}

std::string model(const std::vector<std::string>& loops) {
  std::string joined;
  for (const std::string& loop : loops) joined += (joined.empty() ? "" : ", ") + loop;
  return "{ \"hipair\": 1, \"name\": \"thin\", \"parts\": [ { \"name\": \"plate\", \"motion\": \"fixed\", \"loops\": [ " +
         joined + " ] } ] }";
}

TEST(ModelOrientation, ThinArcSegmentsAreOrientedAtEveryScale) {
  std::mt19937 rng(37);
  const long inverse_t[] = {2, 10, 1000, 100000, 100000000, 10000000000L, 1000000000000L, 10000000000000L};
  const int scales[] = {-30, -3, 0, 3, 30};
  int cases = 0;
  for (long q : inverse_t)
    for (int e : scales)
      for (int hole = 0; hole < 2; ++hole)
        for (int ccw = 0; ccw < 2; ++ccw) {
          mpz_class ten = 1;
          for (int i = 0; i < (e < 0 ? -e : e); ++i) ten *= 10;
          mpq_class r = e < 0 ? mpq_class(mpz_class(1), ten) : mpq_class(ten);
          r *= mpq_class(static_cast<long>(rng() % 900 + 100), 97);
          mpq_class t(1, q);
          mpq_class cx = r * mpq_class(static_cast<long>(rng() % 2001) - 1000, 7);
          mpq_class cy = r * mpq_class(static_cast<long>(rng() % 2001) - 1000, 11);
          mpq_class t_moved = t * mpq_class(static_cast<long>(rng() % 50 + 50), 61);
          t_moved.canonicalize();
          std::vector<std::string> loops;
          if (hole) {
            // a square around the segment (its own loop written counter-clockwise)
            mpq_class s = 4 * r;
            loops.push_back("{ \"start\": " + point(cx - s, cy - s) + ", \"edges\": [ { \"line_to\": " +
                            point(cx + s, cy - s) + " }, { \"line_to\": " + point(cx + s, cy + s) +
                            " }, { \"line_to\": " + point(cx - s, cy + s) + " }, { \"line_to\": " +
                            point(cx - s, cy - s) + " } ] }");
          }
          loops.push_back(segment_loop(r, t_moved, cx, cy, ccw == 1));
          SCOPED_TRACE("1/t = " + std::to_string(q) + ", scale 10^" + std::to_string(e) +
                       (hole ? ", a hole" : ", an outline") + (ccw ? ", written ccw" : ", written cw"));
          Model m = read_model(model(loops));
          ASSERT_EQ(m.parts.size(), 1u);
          const Loop& loop = m.parts[0].loops.back();
          EXPECT_EQ(loop.is_hole, hole == 1);
          // the stored arc runs counter-clockwise for an outline, clockwise for a hole
          bool found = false;
          for (const Edge& edge : loop.edges)
            if (edge.is_arc()) {
              found = true;
              EXPECT_EQ(edge.ccw, hole == 0);
            }
          EXPECT_TRUE(found);
          // written in the wanted direction: kept as written; otherwise reversed
          bool kept = (ccw == 1) == (hole == 0);
          EXPECT_EQ(loop.edges.front().is_arc(), kept);
          ++cases;
        }
  EXPECT_EQ(cases, 160);
}

}  // namespace
}  // namespace hipair
