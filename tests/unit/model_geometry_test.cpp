// Exact geometric validation of loops: what is accepted (tangent joins, annuli, two-arc
// circles, collinear continuations) and what is rejected (touching, crossing, overlapping),
// decided exactly even where intersection points are irrational.
#include "model/validate_geometry.hpp"

#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace {

using hipair::Edge;
using hipair::Loop;
using hipair::Part;
using hipair::Point;
using hipair::Rational;

Point p(Rational x, Rational y) { return Point{x, y}; }

// Builds loops from a compact description: segments and arcs, with pointers "/l<i>/e<j>".
class LoopBuilder {
 public:
  explicit LoopBuilder(Point start) : current_(start) {
    loop_.pointer = "/l";
  }
  LoopBuilder& line(Point to) {
    Edge edge;
    edge.kind = Edge::Kind::segment;
    edge.source = current_;
    edge.target = to;
    push(edge);
    return *this;
  }
  LoopBuilder& arc(Point to, Point center, bool ccw) {
    Edge edge;
    edge.kind = Edge::Kind::arc;
    edge.source = current_;
    edge.target = to;
    edge.center = center;
    edge.ccw = ccw;
    Rational dx = current_.x - center.x, dy = current_.y - center.y;
    edge.radius_squared = dx * dx + dy * dy;
    push(edge);
    return *this;
  }
  Loop build(const std::string& pointer) {
    loop_.pointer = pointer;
    for (std::size_t i = 0; i < loop_.edges.size(); ++i) loop_.edges[i].pointer = pointer + "/" + std::to_string(i);
    return loop_;
  }

 private:
  void push(Edge edge) {
    current_ = edge.target;
    loop_.edges.push_back(edge);
  }
  Point current_;
  Loop loop_;
};

Loop circle(Point center, Rational radius, const std::string& pointer) {
  return LoopBuilder(p(center.x + radius, center.y)).arc(p(center.x + radius, center.y), center, true).build(pointer);
}

Loop rectangle(Rational x0, Rational y0, Rational x1, Rational y1, const std::string& pointer) {
  return LoopBuilder(p(x0, y0)).line(p(x1, y0)).line(p(x1, y1)).line(p(x0, y1)).line(p(x0, y0)).build(pointer);
}

// "" when valid, else "<pointer> | <reason>".
std::string check(std::vector<Loop> loops) {
  Part part;
  part.name = "part";
  part.loops = std::move(loops);
  try {
    hipair::model_detail::validate_part_geometry(part);
  } catch (const hipair::ModelError& error) {
    return error.pointer() + " | " + error.reason();
  }
  return "";
}

bool contains(const std::string& text, const std::string& fragment) {
  return text.find(fragment) != std::string::npos;
}

TEST(Geometry, AcceptsTangentJoinsBetweenSegmentsAndArcs) {
  // A stadium (slot): straight sides tangent to semicircular ends.
  Loop stadium = LoopBuilder(p(0, 0)).line(p(10, 0)).arc(p(10, 4), p(10, 2), true).line(p(0, 4))
                     .arc(p(0, 0), p(0, 2), true).build("/stadium");
  EXPECT_EQ(check({stadium}), "");
}

TEST(Geometry, AcceptsTwoArcCirclesAnnuliAndCollinearContinuations) {
  Loop two_arcs = LoopBuilder(p(5, 0)).arc(p(-5, 0), p(0, 0), true).arc(p(5, 0), p(0, 0), true).build("/c");
  EXPECT_EQ(check({two_arcs}), "");
  EXPECT_EQ(check({circle(p(0, 0), 5, "/outer"), circle(p(0, 0), 3, "/inner")}), "");
  Loop collinear = LoopBuilder(p(0, 0)).line(p(5, 0)).line(p(10, 0)).line(p(10, 10)).line(p(0, 0)).build("/t");
  EXPECT_EQ(check({collinear}), "");
  // Two separate pieces of one part are fine.
  EXPECT_EQ(check({rectangle(0, 0, 1, 1, "/a"), rectangle(2, 0, 3, 1, "/b")}), "");
}

TEST(Geometry, RejectsTouchingAtASinglePoint) {
  // Squares sharing a corner.
  EXPECT_TRUE(contains(check({rectangle(0, 0, 1, 1, "/a"), rectangle(1, 1, 2, 2, "/b")}), "cross or touch"));
  // A vertex of one loop on the side of another (T junction).
  Loop triangle = LoopBuilder(p(1, 1)).line(p(2, 0)).line(p(2, 2)).line(p(1, 1)).build("/t");
  EXPECT_TRUE(contains(check({rectangle(0, 0, 1, 2, "/a"), triangle}), "cross or touch"));
  // Circles tangent internally and externally.
  EXPECT_TRUE(contains(check({circle(p(0, 0), 5, "/a"), circle(p(3, 0), 2, "/b")}), "(5, 0)"));
  EXPECT_TRUE(contains(check({circle(p(0, 0), 5, "/a"), circle(p(7, 0), 2, "/b")}), "cross or touch"));
  // A segment tangent to a circle.
  EXPECT_TRUE(contains(check({rectangle(0, 0, 10, 2, "/a"), circle(p(5, 5), 3, "/b")}), "cross or touch"));
  // A loop touching itself at a vertex (two triangles joined at their tips).
  Loop bowtie_vertex = LoopBuilder(p(0, 0)).line(p(2, 1)).line(p(4, 0)).line(p(4, 2)).line(p(2, 1)).line(p(0, 2))
                           .line(p(0, 0)).build("/v");
  EXPECT_TRUE(contains(check({bowtie_vertex}), "intersects itself"));
}

TEST(Geometry, DecidesIrrationalCrossingsExactly) {
  // Unit circles about (0,0) and (1,1) meet at (0,1) and (1,0).
  EXPECT_TRUE(contains(check({circle(p(0, 0), 1, "/a"), circle(p(1, 1), 1, "/b")}), "cross or touch"));
  // A circle of radius 1 and a segment y = 1/2 crossing at x = +-sqrt(3)/2 (irrational).
  EXPECT_TRUE(contains(check({circle(p(0, 0), 1, "/a"), rectangle(-2, Rational(1, 2), 2, 3, "/b")}), "cross or touch"));
  // A segment that stops 1e-20 short of the circle does not touch it.
  Rational gap = hipair::parse_rational("1e-20");
  EXPECT_EQ(check({circle(p(0, 0), 10, "/a"), rectangle(10 + gap, -1, 20, 1, "/b")}), "");
  // ...and an arc spanning only the far side of the circle misses a segment crossing the near side.
  Loop right_half = LoopBuilder(p(0, -5)).arc(p(0, 5), p(0, 0), true).line(p(0, -5)).build("/h");
  EXPECT_EQ(check({right_half, rectangle(-6, -1, -4, 1, "/r")}), "");
  // A chord 1e-20 inside the circle is a crossing.
  EXPECT_TRUE(contains(check({circle(p(0, 0), 10, "/a"), rectangle(10 - gap, -1, 20, 1, "/b")}), "cross or touch"));
}

TEST(Geometry, RejectsOverlapsAndSpikes) {
  Loop spike = LoopBuilder(p(0, 0)).line(p(10, 0)).line(p(5, 0)).line(p(5, 5)).line(p(0, 0)).build("/s");
  EXPECT_TRUE(contains(check({spike}), "/s/1 | "));
  EXPECT_TRUE(contains(check({spike}), "zero-area spike"));
  // Two arcs of the same circle overlapping.
  Loop overlapping = LoopBuilder(p(5, 0)).arc(p(0, 5), p(0, 0), true).arc(p(5, 0), p(0, 0), false).build("/o");
  EXPECT_TRUE(contains(check({overlapping}), "runs back along"));
  // A loop whose side lies along another loop's side.
  std::string sides = check({rectangle(0, 0, 2, 2, "/a"), rectangle(2, 0, 4, 1, "/b")});
  EXPECT_TRUE(contains(sides, "overlap") || contains(sides, "cross or touch")) << sides;
  // A degenerate two-segment loop.
  Loop back_and_forth = LoopBuilder(p(0, 0)).line(p(1, 0)).line(p(0, 0)).build("/d");
  EXPECT_TRUE(contains(check({back_and_forth}), "zero-area spike"));
}

TEST(Geometry, ChecksClosureArcsAndEdges) {
  Loop open = LoopBuilder(p(0, 0)).line(p(1, 0)).line(p(1, 1)).build("/open");
  EXPECT_TRUE(contains(check({open}), "/open | open loop"));
  Loop inconsistent = LoopBuilder(p(0, 0)).line(p(3, 0)).arc(p(0, 4), p(0, 0), true).line(p(0, 0)).build("/i");
  inconsistent.edges[1].target = p(0, 3);
  inconsistent.edges[2].source = p(0, 3);
  EXPECT_EQ(check({inconsistent}), "");
  inconsistent.edges[1].target = p(Rational(1, 1000000), 3);
  inconsistent.edges[2].source = inconsistent.edges[1].target;
  EXPECT_TRUE(contains(check({inconsistent}), "/i/1 | inconsistent arc"));
  Loop broken = rectangle(0, 0, 1, 1, "/b");
  broken.edges[2].source = p(2, 2);
  EXPECT_TRUE(contains(check({broken}), "does not start where the previous edge ends"));
  Loop zero = rectangle(0, 0, 1, 1, "/z");
  zero.edges[1].radius_squared = 0;
  zero.edges[1].kind = Edge::Kind::arc;
  zero.edges[1].center = zero.edges[1].source;
  EXPECT_TRUE(contains(check({zero}), "zero radius"));
  EXPECT_TRUE(contains(check({Loop{}}), "at least one edge"));
}

TEST(Geometry, OrientsHolesInsideArcBoundedParts) {
  // A disc with a square hole containing a small disc (island): depth 0, 1, 2.
  std::vector<Loop> loops{circle(p(0, 0), 10, "/disc"), rectangle(-5, -5, 5, 5, "/hole"), circle(p(0, 0), 1, "/island")};
  Part part;
  part.loops = loops;
  hipair::model_detail::validate_part_geometry(part);
  EXPECT_FALSE(part.loops[0].is_hole);
  EXPECT_TRUE(part.loops[0].edges[0].ccw);
  EXPECT_TRUE(part.loops[1].is_hole);
  // The hole is now clockwise: (-5,-5) -> (-5,5) -> (5,5) ...
  EXPECT_EQ(part.loops[1].edges[0].source, p(-5, -5));
  EXPECT_EQ(part.loops[1].edges[0].target, p(-5, 5));
  EXPECT_FALSE(part.loops[2].is_hole);
  EXPECT_TRUE(part.loops[2].edges[0].ccw);
  // A square hole in a disc, where the hole's corners come within 1e-15 of the rim.
  Rational r = hipair::parse_rational("7.07106781186548");  // just over 5 sqrt(2) = 7.0710678118654752...
  std::vector<Loop> tight{circle(p(0, 0), r, "/disc"), rectangle(-5, -5, 5, 5, "/hole")};
  EXPECT_EQ(check(tight), "");
  std::vector<Loop> too_tight{circle(p(0, 0), hipair::parse_rational("7.0710678118"), "/disc"), rectangle(-5, -5, 5, 5, "/hole")};
  EXPECT_TRUE(contains(check(too_tight), "cross or touch"));
}

TEST(Geometry, ManyEdgesStayFast) {
  // A 720-gon inscribed exactly in the circle of radius 100 (rational half-angle tangents).
  const int n = 720;
  std::vector<Point> vertices;
  for (int k = 0; k < n; ++k) {
    double theta = -M_PI + 2 * M_PI * (k + 0.5) / n;
    Rational t(static_cast<long>(std::llround(std::tan(theta / 2) * 1e6)), 1000000);
    t.canonicalize();
    Rational w = 1 + t * t;
    vertices.push_back(p(Rational(100 * (1 - t * t) / w), Rational(200 * t / w)));
  }
  LoopBuilder builder(vertices[0]);
  for (int k = 1; k < n; ++k) builder.line(vertices[k]);
  builder.line(vertices[0]);
  std::vector<Loop> loops{builder.build("/outline")};
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      loops.push_back(rectangle(-50 + 10 * i, -50 + 10 * j, -45 + 10 * i, -45 + 10 * j, "/h" + std::to_string(i * 10 + j)));
  EXPECT_EQ(check(loops), "");
}

}  // namespace
