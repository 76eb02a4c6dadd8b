// The curve generator's chart-independent data for translating pairs (docs/performance.md,
// session 23): the features' projections on the axes from each point's enclosures
// (axis_ranges, axis_projection), the negated axes by the negated enclosure (enclose_dot,
// projection_range), and part_features with each edge's tangent taken once. Each against an
// oracle written here: the certified enclosure of the exact rational dot product, and an
// independent walk over the loops for the features and their strictly reflex vertices.
#include "curves/contact_curves.hpp"
#include "curves/pose.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include "test_paths.hpp"
#include "random_rationals.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using cspace::BodyFeature;
using cspace::FeatureRef;
using kernels::Interval;

// A rational n / d with n in [-range, range], d in [1, dmax], times `scale`.
Rational random_rational(std::mt19937_64& random, long range, long dmax, const Rational& scale) {
  long n = static_cast<long>(random() % static_cast<unsigned long>(2 * range + 1)) - range;
  long d = 1 + static_cast<long>(random() % static_cast<unsigned long>(dmax));
  Rational q(n, d);
  q.canonicalize();
  return Rational(q * scale);
}

using test_numbers::power_of_ten;

// The oracle: the certified enclosure of the exact rational u . p (no axis case).
Interval exact_dot(const Point& u, const Point& p) { return Interval::enclose(Rational(u.x * p.x + u.y * p.y)); }

Interval oracle_range(const BodyFeature& feature, const Point& u) {
  if (feature.ref.kind == FeatureRef::Kind::vertex) return exact_dot(u, feature.edge->source);
  return kernels::hull(exact_dot(u, feature.edge->source), exact_dot(u, feature.edge->target));
}

void expect_same(const Interval& got, const Interval& want, const std::string& what) {
  EXPECT_EQ(got.lo, want.lo) << what;
  EXPECT_EQ(got.hi, want.hi) << what;
}

TEST(CSpaceFrontEndFixedCosts, AxisProjectionsEqualTheEnclosedExactDotProductOnGeneratedFeatures) {
  std::mt19937_64 random(23);
  const std::vector<Point> axes{{Rational(1), Rational(0)}, {Rational(-1), Rational(0)}, {Rational(0), Rational(1)},
                                {Rational(0), Rational(-1)}};
  const std::vector<Point> others{{Rational(3, 5), Rational(4, 5)}, {Rational(-1, 2), Rational(7, 3)},
                                  {Rational(0), Rational(2)}, {Rational(-3), Rational(0)}};
  // scales: ordinary, tiny and huge (subnormal and infinite double conversions), and exact zeros
  const std::vector<int> exponents{0, 0, 0, -40, 40, -330, 330, -400, 400};
  int features = 0, negative_axis = 0, beyond_doubles = 0;
  for (int round = 0; round < 60; ++round) {
    const Rational scale = power_of_ten(exponents[static_cast<std::size_t>(round) % exponents.size()]);
    const long range = round % 5 == 0 ? 1 : 1000;   // (range 1: many zero coordinates)
    Edge edge;
    edge.source = Point{random_rational(random, range, 97, scale), random_rational(random, range, 97, scale)};
    edge.target = Point{random_rational(random, range, 89, scale), random_rational(random, range, 89, scale)};
    if (round % 7 == 3) edge.target.x = edge.source.x;   // vertical and horizontal segments
    if (round % 7 == 5) edge.target.y = edge.source.y;
    for (FeatureRef::Kind kind : {FeatureRef::Kind::vertex, FeatureRef::Kind::segment}) {
      BodyFeature feature;
      feature.ref = FeatureRef{0, 0, 0, kind};
      feature.edge = &edge;
      ++features;
      const cspace::AxisRanges ranges = cspace::axis_ranges(feature);
      for (const Point& u : axes) {
        const std::string what = "round " + std::to_string(round) + " kind " + std::to_string(static_cast<int>(kind)) +
                                 " u (" + u.x.get_str() + ", " + u.y.get_str() + ")";
        const Interval want = oracle_range(feature, u);
        expect_same(cspace::projection_range(feature, u), want, what + " projection_range");
        expect_same(cspace::axis_projection(ranges, u), want, what + " axis_projection");
        if (kind == FeatureRef::Kind::vertex) expect_same(cspace::enclose_dot(u, feature.point()), want, what + " enclose_dot");
        if (sgn(u.x) < 0 || sgn(u.y) < 0) negative_axis += want.lo != -want.hi;   // not symmetric about 0
        if (std::isinf(want.lo) || std::isinf(want.hi)) ++beyond_doubles;
      }
      for (const Point& u : others)
        expect_same(cspace::projection_range(feature, u), oracle_range(feature, u),
                    "round " + std::to_string(round) + " general unit");
    }
  }
  EXPECT_EQ(features, 120);
  EXPECT_GT(negative_axis, 100);   // the negated enclosures were exercised on non-trivial values
  EXPECT_GT(beyond_doubles, 0);    // and beyond the doubles' range
}

// ------------------------------------------------------------------ part_features

// The oracle's tangent of an edge at one of its points (material on the left).
Point oracle_tangent(const Edge& edge, const Point& at) {
  if (!edge.is_arc()) return Point{Rational(edge.target.x - edge.source.x), Rational(edge.target.y - edge.source.y)};
  Rational rx = at.x - edge.center.x, ry = at.y - edge.center.y;
  return edge.ccw ? Point{Rational(-ry), rx} : Point{ry, Rational(-rx)};
}

// part_features written out independently: per loop and edge, the vertex at its source unless
// the edge is a full circle or the vertex strictly reflex (cross(in, out) < 0), then the edge.
void expect_features_of(const Model& model, std::size_t part_index, const std::string& name, int& reflex_seen,
                        int& arcs_seen) {
  const Part& part = model.parts.at(part_index);
  std::vector<BodyFeature> want;
  std::size_t reflex = 0;
  for (std::size_t l = 0; l < part.loops.size(); ++l) {
    const auto& edges = part.loops[l].edges;
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const Edge& edge = edges[e];
      arcs_seen += edge.is_arc();
      if (!(edge.is_arc() && edge.source == edge.target)) {
        Point in = oracle_tangent(edges[(e + edges.size() - 1) % edges.size()], edge.source);
        Point out = oracle_tangent(edge, edge.source);
        if (sgn(Rational(in.x * out.y - in.y * out.x)) < 0) {
          ++reflex;
        } else {
          BodyFeature f;
          f.ref = FeatureRef{part_index, l, e, FeatureRef::Kind::vertex};
          f.edge = &edge;
          want.push_back(f);
        }
      }
      BodyFeature f;
      f.ref = FeatureRef{part_index, l, e, edge.is_arc() ? FeatureRef::Kind::arc : FeatureRef::Kind::segment};
      f.edge = &edge;
      want.push_back(f);
    }
  }
  reflex_seen += static_cast<int>(reflex);
  for (bool labels : {false, true}) {
    std::size_t skipped = 0;
    const std::vector<BodyFeature> got = cspace::part_features(model, part_index, &skipped, labels);
    EXPECT_EQ(skipped, reflex) << name;
    ASSERT_EQ(got.size(), want.size()) << name;
    for (std::size_t i = 0; i < got.size(); ++i) {
      const std::string what = name + " feature " + std::to_string(i);
      EXPECT_EQ(got[i].ref.part, want[i].ref.part) << what;
      EXPECT_EQ(got[i].ref.loop, want[i].ref.loop) << what;
      EXPECT_EQ(got[i].ref.edge, want[i].ref.edge) << what;
      EXPECT_EQ(got[i].ref.kind, want[i].ref.kind) << what;
      EXPECT_EQ(got[i].edge, want[i].edge) << what;
      EXPECT_TRUE(got[i].point() == want[i].edge->source) << what;   // the vertex, or the edge's start
      if (!labels) {
        EXPECT_TRUE(got[i].label.empty()) << what;
      } else if (got[i].ref.kind == FeatureRef::Kind::vertex) {
        EXPECT_EQ(got[i].label, cspace::feature_label(model, got[i].ref)) << what;
      } else {
        EXPECT_FALSE(got[i].label.empty()) << what;
      }
    }
  }
}

// A point of the circle (c, r) at the rational half-angle tangent t.
Point on_circle(const Point& c, const Rational& r, const Rational& t) {
  Rational d = 1 + t * t;
  return Point{Rational(c.x + r * (1 - t * t) / d), Rational(c.y + r * 2 * t / d)};
}

TEST(CSpaceFrontEndFixedCosts, PartFeaturesEqualAnIndependentWalkOnExampleAndGeneratedParts) {
  int reflex = 0, arcs = 0, parts = 0;
  // every example model's parts (arcs, holes, full circles, reflex corners)
  int models = 0;
  for (const auto& entry : std::filesystem::directory_iterator(HIPAIR_EXAMPLES)) {
    if (entry.path().extension() != ".json") continue;
    Model model;
    try {
      model = read_model_file(entry.path());
    } catch (const ModelError&) {
      continue;   // (a template with unset parameters)
    }
    ++models;
    for (std::size_t p = 0; p < model.parts.size(); ++p, ++parts)
      expect_features_of(model, p, entry.path().filename().string() + " part " + std::to_string(p), reflex, arcs);
  }
  // generated loops: vertices on a circle at rational half-angle tangents, each edge a segment,
  // an arc along the circle (ccw) or an arc bulging inwards (cw, about the mirrored centre),
  // so that segment-segment, segment-arc and arc-arc corners are convex, straight or reflex;
  // a full circle as a second loop of some parts
  std::mt19937_64 random(2323);
  for (int round = 0; round < 40; ++round) {
    Model model;
    Part part;
    const Point centre{Rational(static_cast<long>(random() % 21) - 10, 3), Rational(static_cast<long>(random() % 21) - 10, 7)};
    const Rational radius(static_cast<long>(5 + random() % 20), static_cast<long>(1 + random() % 4));
    const int n = 3 + static_cast<int>(random() % 8);
    std::vector<Rational> ts;
    for (int i = 0; i < n; ++i) ts.emplace_back(static_cast<long>(-n + 2 * i), n + 1);   // increasing angles in (-pi/2, pi/2)
    std::vector<Point> vertices;
    for (const Rational& t : ts) vertices.push_back(on_circle(centre, radius, t));
    Loop loop;
    for (int i = 0; i < n; ++i) {
      Edge edge;
      edge.source = vertices[static_cast<std::size_t>(i)];
      edge.target = vertices[static_cast<std::size_t>((i + 1) % n)];
      const int kind = static_cast<int>(random() % 3);
      if (kind > 0 && i + 1 < n) {   // (the closing chord stays a segment)
        edge.kind = Edge::Kind::arc;
        edge.ccw = kind == 1;
        if (kind == 1) {
          edge.center = centre;
        } else {   // the centre mirrored in the chord: the same radius, the arc bulging inwards
          Rational mx = (edge.source.x + edge.target.x) / 2, my = (edge.source.y + edge.target.y) / 2;
          edge.center = Point{Rational(2 * mx - centre.x), Rational(2 * my - centre.y)};
        }
        edge.radius_squared = radius * radius;
      }
      loop.edges.push_back(edge);
    }
    part.loops.push_back(loop);
    if (round % 4 == 0) {
      Loop circle;
      Edge full;
      full.kind = Edge::Kind::arc;
      full.center = centre;
      full.source = full.target = on_circle(centre, Rational(1, 2), Rational(1, 3));
      full.radius_squared = Rational(1, 4);
      full.ccw = false;
      circle.edges.push_back(full);
      circle.is_hole = true;
      part.loops.push_back(circle);
    }
    part.name = "generated";
    model.parts.push_back(part);
    expect_features_of(model, 0, "generated " + std::to_string(round), reflex, arcs);
    ++parts;
  }
  EXPECT_GE(models, 25);
  EXPECT_GT(parts, 70);
  EXPECT_GT(reflex, 20);   // strictly reflex vertices occurred (skipped by both)
  EXPECT_GT(arcs, 40);
}

// Generated loops of random rational vertices (non-dyadic denominators, scaled by 10^-300 …
// 10^300), with vertices put exactly on the line of their neighbours (straight corners: cross
// zero, not strictly reflex) or where the loop turns back (antiparallel edges): part_features'
// integer tangents (scaled_tangent) against the independent walk's rational cross products.
TEST(CSpaceFrontEndFixedCosts, PartFeaturesOfRandomRationalLoopsAtExtremeScalesEqualAnIndependentWalk) {
  std::mt19937_64 random(3838);
  int reflex = 0, arcs = 0, straight = 0;
  const int exponents[] = {0, -300, 300, -30, 30, 0};
  for (int round = 0; round < 60; ++round) {
    const Rational scale = power_of_ten(exponents[round % 6]);
    const int n = 3 + static_cast<int>(random() % 9);
    std::vector<Point> vertices;
    for (int i = 0; i < n; ++i) {
      const int kind = static_cast<int>(random() % 5);
      if (i >= 2 && kind == 0) {   // on the line of the previous two, beyond or back
        const Point& a = vertices[vertices.size() - 2];
        const Point& b = vertices.back();
        Rational t = random_rational(random, 7, 9, Rational(1));
        if (t == 0) t = Rational(-2, 3);
        vertices.push_back(Point{Rational(b.x + t * (b.x - a.x)), Rational(b.y + t * (b.y - a.y))});
        ++straight;
      } else {
        vertices.push_back(Point{random_rational(random, 50, 11, scale), random_rational(random, 50, 13, scale)});
      }
    }
    Model model;
    Part part;
    Loop loop;
    for (int i = 0; i < n; ++i) {
      Edge edge;
      edge.source = vertices[static_cast<std::size_t>(i)];
      edge.target = vertices[static_cast<std::size_t>((i + 1) % n)];
      if (edge.source == edge.target) edge.target.x += scale;   // (no zero-length edge)
      loop.edges.push_back(edge);
    }
    for (std::size_t i = 0; i < loop.edges.size(); ++i)   // closed: each source the previous target
      loop.edges[(i + 1) % loop.edges.size()].source = loop.edges[i].target;
    part.loops.push_back(loop);
    part.name = "random";
    model.parts.push_back(part);
    expect_features_of(model, 0, "random " + std::to_string(round), reflex, arcs);
  }
  EXPECT_GT(reflex, 30);
  EXPECT_GT(straight, 15);
}

// scaled_tangent against edge_tangent: the signs of cross and dot products of random tangents
// of segments and arcs (both orientations), rational against integer, at 10^-300 … 10^300.
TEST(CSpaceFrontEndFixedCosts, ScaledTangentsHaveTheRationalTangentsSigns) {
  std::mt19937_64 random(3839);
  const int exponents[] = {0, -300, 300, 7, -7};
  int zero_cross = 0;
  kernels::Vector<mpz_class> a, b;
  for (int round = 0; round < 2000; ++round) {
    const Rational scale = power_of_ten(exponents[round % 5]);
    Edge edges[2];
    Point at[2];
    for (int k = 0; k < 2; ++k) {
      Edge& e = edges[k];
      e.source = Point{random_rational(random, 9, 7, scale), random_rational(random, 9, 5, scale)};
      if (k == 1 && round % 3 == 0) {   // parallel or antiparallel to the first
        Point d = cspace::edge_tangent(edges[0], at[0]);
        Rational t = random_rational(random, 5, 4, Rational(1));
        e.target = Point{Rational(e.source.x + t * d.x), Rational(e.source.y + t * d.y)};
      } else {
        e.target = Point{random_rational(random, 9, 3, scale), random_rational(random, 9, 11, scale)};
      }
      at[k] = e.source;
      if (random() % 3 == 0) {
        e.kind = Edge::Kind::arc;
        e.center = Point{random_rational(random, 9, 7, scale), random_rational(random, 9, 3, scale)};
        e.ccw = random() % 2 == 0;
      }
    }
    const Point ra = cspace::edge_tangent(edges[0], at[0]), rb = cspace::edge_tangent(edges[1], at[1]);
    cspace::scaled_tangent(edges[0], at[0], a);
    cspace::scaled_tangent(edges[1], at[1], b);
    const int cross = sgn(Rational(ra.x * rb.y - ra.y * rb.x)), dot = sgn(Rational(ra.x * rb.x + ra.y * rb.y));
    zero_cross += cross == 0;
    EXPECT_EQ(sgn(mpz_class(a.x * b.y - a.y * b.x)), cross) << round;
    EXPECT_EQ(sgn(mpz_class(a.x * b.x + a.y * b.y)), dot) << round;
    EXPECT_EQ(sgn(a.x), sgn(ra.x)) << round;
    EXPECT_EQ(sgn(a.y), sgn(ra.y)) << round;
  }
  EXPECT_GT(zero_cross, 100);
}

}  // namespace
}  // namespace hipair
