// Zero-clearance fits at irrational configurations (session 33): a point between blocked
// intervals (or a coincident-curve edge between blocked faces) where two or more contacts hold
// at an irrational half-angle tangent is decided exactly by the algebraic oracle
// (curves/algebraic_overlap.hpp): touching or overlapping, never left undecided, for parts
// bounded by segments.
//
// The generator: a lever turning about the origin (a thin quadrilateral from x = 5 to x = 10,
// half-width w) in a slot d/2 <= 3x + 4y <= d of a frame. Its far tip (10, 0) meets the upper
// wall and its near tip (5, 0) the lower wall when 10 (3 cos θ + 4 sin θ) = d, i.e. at the roots
// of m(t) = (30 + d) t^2 - 80 t + (d - 30) (t = tan θ/2), irrational for most d = 30 + δ: the
// upper wall's contact penetrates on one side of the root, the lower wall's on the other (their
// contact functions are -1/4 of each other), so the lever is blocked on both sides of the root
// t* ≈ δ/80 and only touches there (the closed form: every other lever vertex lies strictly
// between the walls). A notch of the frame reaching the lever's middle at θ ≈ 0 makes t* an
// overlapping configuration instead. The frame may slide along the slot (direction (4, -3):
// the walls' contact functions do not depend on the slide), making t = t* a vertical edge of a
// 2-D space.
#include "curves/algebraic_overlap.hpp"
#include "curves/contact_curves.hpp"
#include "polygon_loop_json.hpp"
#include "random_rationals.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using Random = std::mt19937_64;
using algebra_Real = cspace::algebra::Real;

using test_loops::text;
using test_numbers::random_rational;

struct XY {
  Rational x, y;
};

std::string loop(const std::vector<XY>& points, const Rational& scale) {
  test_loops::Points scaled;
  for (const XY& q : points) scaled.emplace_back(q.x * scale, q.y * scale);
  return test_loops::loop_json(scaled);
}

// The lever in the slot (see the file comment); `frame_motion` is the frame's motion JSON.
std::string lever_model(const Rational& delta, const Rational& w, const Rational& scale, bool notch,
                        const std::string& frame_motion = "\"fixed\"") {
  const Rational d = 30 + delta;
  std::vector<XY> lever{{Rational(5), Rational(0)}, {Rational(15, 2), -w}, {Rational(10), Rational(0)}, {Rational(15, 2), w}};
  // the slot d/2 <= 3x + 4y <= d inside the box [-40, 40]^2
  std::vector<XY> hole{{Rational(40), (d / 2 - 120) / 4}, {Rational(40), (d - 120) / 4}};
  if (notch) {
    hole.push_back({Rational(5), (d - 15) / 4});
    hole.push_back({Rational(15, 2), Rational(0)});
    hole.push_back({Rational(3), (d - 9) / 4});
  }
  hole.push_back({Rational(-40), (d + 120) / 4});
  hole.push_back({Rational(-40), (d / 2 + 120) / 4});
  std::vector<XY> outer{{Rational(-60), Rational(-60)}, {Rational(60), Rational(-60)}, {Rational(60), Rational(60)}, {Rational(-60), Rational(60)}};
  return R"({ "hipair": 1, "name": "lever-irrational-fit", "parts": [
      { "name": "lever", "motion": { "rotation": { "pivot": [0, 0] } }, "loops": [ )" + loop(lever, scale) + R"( ] },
      { "name": "frame", "motion": )" + frame_motion + R"(, "loops": [ )" + loop(outer, scale) + ", " + loop(hole, scale) + R"( ] } ],
    "pairs": [ { "parts": ["lever", "frame"] } ] })";
}

// The frame sliding along the slot (direction (4, -3), along both walls) by up to scale / 10.
std::string sliding(const Rational& scale) {
  return R"({ "translation": { "direction": [4, -3], "limits": [)" + text(-scale / 10) + ", " + text(scale / 10) + "] } }";
}

// m(t) = (30 + d) t^2 - 80 t + (d - 30) over integers, primitive, positive leading coefficient.
std::vector<mpz_class> fit_polynomial(const Rational& delta) {
  const Rational d = 30 + delta;
  std::vector<Rational> c{d - 30, Rational(-80), 30 + d};
  mpz_class l = 1;
  for (auto& v : c) mpz_lcm(l.get_mpz_t(), l.get_mpz_t(), v.get_den().get_mpz_t());
  std::vector<mpz_class> p;
  for (auto& v : c) p.push_back(mpz_class(v * l));
  mpz_class g = 0;
  for (auto& v : p) mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), v.get_mpz_t());
  for (auto& v : p) v /= g;
  return p;
}

bool is_square(const mpz_class& v) { return v >= 0 && mpz_perfect_square_p(v.get_mpz_t()) != 0; }

struct PairFrame {
  cspace::PairAxes axes;
  cspace::ChartLayout layout;
};

PairFrame pair_frame(const Model& model, const CSpace& space) {
  PairFrame f;
  f.axes = cspace::pair_axes(model, *model.find_part(space.first_part()), *model.find_part(space.second_part()));
  f.layout = cspace::chart_layout(model, f.axes);
  if (f.axes.dimension() == 1) f.layout.y_charts = {cspace::ChartAxis{cspace::ChartAxis::Kind::translation, false, Rational(0), Rational(0)}};
  return f;
}

cspace::Overlap rational_oracle(const Model& model, const PairFrame& f, std::size_t chart, const Rational& x, const Rational& y) {
  std::size_t n = f.layout.y_charts.size();
  return cspace::classify_overlap(model, f.axes, f.layout.x_charts[chart / n], f.layout.y_charts[chart % n], cspace::ChartPoint{x, y});
}

std::optional<cspace::Overlap> algebraic_oracle(const Model& model, const PairFrame& f, std::size_t chart, const algebra_Real& x,
                                                const algebra_Real& y) {
  std::size_t n = f.layout.y_charts.size();
  return cspace::algebraic_overlap(model, f.axes, f.layout.x_charts[chart / n], f.layout.y_charts[chart % n], x, y);
}

algebra_Real real_of(const AlgebraicNumber& a) {
  if (a.exact) return algebra_Real::from_rational(a.lower);
  algebra_Real r;
  r.polynomial = a.polynomial;
  r.lower = a.lower;
  r.upper = a.upper;
  return r;
}

// The scales of the generated sizes: 1, 10^-300, 10^300 and random powers of ten between.
Rational scale_of(int instance, Random& random) {
  int exponent = instance % 4 == 0 ? 0 : instance % 4 == 1 ? -300 : instance % 4 == 2 ? 300 : static_cast<int>(random() % 601) - 300;
  mpz_class p;
  mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(exponent < 0 ? -exponent : exponent));
  return exponent < 0 ? Rational(mpz_class(1), p) : Rational(p);
}

// The algebraic oracle agrees with the rational one at rational configurations: random angles,
// and the lever's exact fits at a rational root (d = 10 (cos θ0 + sin θ0), θ0 rational in t),
// where the parts touch at two points; 1-D (fixed frame) and 2-D (sliding frame).
TEST(AlgebraicOverlap, AgreesWithTheRationalOracleAtRationalConfigurations) {
  Random random(20261201);
  int touching = 0, overlapping = 0, apart = 0;
  for (int instance = 0; instance < 12; ++instance) {
    const Rational t0 = random_rational(random, Rational(-1, 20), Rational(1, 20));
    Rational delta = 10 * (3 * (1 - t0 * t0) + 8 * t0) / (1 + t0 * t0) - 30;
    delta.canonicalize();
    const Rational w = random_rational(random, Rational(1, 4), Rational(3, 2));
    const Rational scale = scale_of(instance, random);
    const bool slides = instance % 3 == 2;
    const std::string motion = slides ? sliding(scale) : "\"fixed\"";
    Model model = read_model(lever_model(delta, w, scale, instance % 2 == 1, motion));
    CSpace space = CSpace::build(model, "lever", "frame");
    PairFrame f = pair_frame(model, space);
    SCOPED_TRACE("instance " + std::to_string(instance) + " t0 " + t0.get_str());
    std::vector<Rational> ts{t0, Rational(0), Rational(1), Rational(-1)};
    for (int k = 0; k < 12; ++k) ts.push_back(random_rational(random, Rational(-1), Rational(1), 1000));
    for (std::size_t chart = 0; chart < f.layout.x_charts.size(); ++chart)
      for (const Rational& t : ts) {
        Rational y = slides ? random_rational(random, Rational(-1), Rational(1)) * scale : Rational(0);
        cspace::Overlap truth = rational_oracle(model, f, chart * f.layout.y_charts.size(), t, y);
        auto got = algebraic_oracle(model, f, chart * f.layout.y_charts.size(), algebra_Real::from_rational(t), algebra_Real::from_rational(y));
        ASSERT_TRUE(got.has_value());
        EXPECT_EQ(*got, truth) << "chart " << chart << " t " << t.get_str() << " y " << y.get_str();
        touching += truth == cspace::Overlap::touching;
        overlapping += truth == cspace::Overlap::overlapping;
        apart += truth == cspace::Overlap::apart;
      }
  }
  EXPECT_GE(touching, 6);   // the exact fits at t0 of the six frames without a notch
  EXPECT_GE(overlapping, 100);
}

// Parts with arcs are decided too (session 34; cspace_irrational_arc_fit_test.cpp): here apart.
TEST(AlgebraicOverlap, ArcsAreDecided) {
  const std::string json = R"({ "hipair": 1, "name": "disk", "parts": [
      { "name": "disk", "motion": { "rotation": { "pivot": [0, 0] } }, "loops": [ { "circle": { "center": [5, 0], "radius": 1 } } ] },
      { "name": "frame", "motion": "fixed", "loops": [ { "start": [-10, 2], "edges": [ { "line_to": [10, 2] }, { "line_to": [10, 3] },
        { "line_to": [-10, 3] }, { "line_to": [-10, 2] } ] } ] } ],
    "pairs": [ { "parts": ["disk", "frame"] } ] })";
  Model model = read_model(json);
  CSpace space = CSpace::build(model, "disk", "frame");
  PairFrame f = pair_frame(model, space);
  auto got = algebraic_oracle(model, f, 0, algebra_Real::from_rational(Rational(0)), algebra_Real::from_rational(Rational(0)));
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(*got, cspace::Overlap::apart);
}

// The generated irrational fits, at scales 10^-300 ... 10^300: the builder decides both roots of
// m exactly (touching, or overlapping where the notch reaches the lever), leaves nothing
// undecided, and the rational oracle just either side of each root finds blocked space (so each
// root is a zero-clearance candidate); with the frame sliding along the slot the roots are
// vertical touching edges t = t* of the 2-D space.
TEST(IrrationalFit, LeverBetweenTwoWallsIsDecidedExactly) {
  Random random(33);
  int decided_touching = 0, decided_overlapping = 0, instances = 0;
  for (int instance = 0; instance < 32; ++instance) {
    Rational delta = random_rational(random, Rational(1, 100), Rational(1, 2), 997);
    const std::vector<mpz_class> m = fit_polynomial(delta);
    if (is_square(m[1] * m[1] - 4 * m[0] * m[2])) continue;   // a rational root: not this test's case
    ++instances;
    const Rational w = random_rational(random, Rational(1, 4), Rational(3, 2));
    const Rational scale = scale_of(instance, random);
    const bool notch = instance % 2 == 1, slides = instance % 4 >= 2;
    const std::string motion = slides ? sliding(scale) : "\"fixed\"";
    SCOPED_TRACE("instance " + std::to_string(instance) + " delta " + delta.get_str() + " w " + w.get_str() +
                 (notch ? " notched" : "") + (slides ? " sliding" : ""));
    Model model = read_model(lever_model(delta, w, scale, notch, motion));
    CSpace space = CSpace::build(model, "lever", "frame");
    PairFrame f = pair_frame(model, space);
    EXPECT_EQ(space.statistics().touching_undecided, 0u);
    // the two roots of m in chart 0 (t in [-1, 1] around θ = 0): the vertices carrying m (a
    // sliding frame: the vertical edges t = t* across the chart)
    int roots = 0;
    auto check = [&](std::size_t chart, const AlgebraicNumber& t, bool touching) {
      ++roots;
      const bool first_root = t.approximate() < 0.5;
      const bool truth = !(notch && first_root);   // the closed form (file comment)
      EXPECT_EQ(touching, truth) << t.to_string("t");
      // the neighbourhood is blocked on both sides (the rational oracle 2^-100 away)
      algebra_Real x = real_of(t);
      x.refine_to(Rational(mpz_class(1), mpz_class(1) << 100));
      for (const Rational& side : {x.lower, x.upper})
        EXPECT_EQ(rational_oracle(model, f, chart, side, Rational(0)), cspace::Overlap::overlapping);
      auto direct = algebraic_oracle(model, f, chart, real_of(t), algebra_Real::from_rational(Rational(0)));
      ASSERT_TRUE(direct.has_value());
      EXPECT_EQ(*direct, truth ? cspace::Overlap::touching : cspace::Overlap::overlapping);
      (truth ? decided_touching : decided_overlapping) += 1;
    };
    auto near_chart = [&](std::size_t chart) { return !f.layout.x_charts[chart / f.layout.y_charts.size()].half_turn; };
    // t* (by the double formula, to 1e-9; the vertex's polynomial may be a multiple of m)
    const double dd = delta.get_d(), t_star = (80 - std::sqrt(6400 - 4 * (60 + dd) * dd)) / (2 * (60 + dd));
    auto at_t_star = [&](const CSpaceVertex& v) {
      return !v.x.exact && near_chart(v.chart) && std::abs(v.x.approximate() - t_star) < 1e-9;
    };
    if (!slides) {
      for (const CSpaceVertex& vertex : space.vertices())
        if (at_t_star(vertex)) check(vertex.chart, vertex.x, vertex.touching);
    } else {
      // the vertical edges t = t* (their ends on the chart's sides and at the notch's curves)
      bool touching = false;
      const CSpaceVertex* first = nullptr;
      for (const CSpaceEdge& edge : space.edges()) {
        const CSpaceVertex& source = space.vertices()[edge.source];
        if (!edge.vertical || edge.role == EdgeRole::seam || !at_t_star(source)) continue;
        if (!first) first = &source;
        touching = touching || edge.role == EdgeRole::touching;
        if (edge.role == EdgeRole::touching) EXPECT_FALSE(notch) << source.x.to_string("t");
      }
      if (first) check(first->chart, first->x, touching);
    }
    // t* (t** = 80/(60 + δ) - t* lies in the half-turn chart) is a vertex without the notch; with
    // it the curves there may be culled (certainly blocked space): then no vertex, and the
    // algebraic oracle at t* itself says overlapping
    if (!notch) EXPECT_GE(roots, 1);
    if (roots == 0) {
      std::vector<algebra_Real> ts = cspace::algebra::real_roots(m, Rational(0), Rational(1, 2));
      ASSERT_EQ(ts.size(), 1u);
      auto direct = algebraic_oracle(model, f, 0, ts[0], algebra_Real::from_rational(Rational(0)));
      ASSERT_TRUE(direct.has_value());
      EXPECT_EQ(*direct, notch ? cspace::Overlap::overlapping : cspace::Overlap::touching);
      (notch ? decided_overlapping : decided_touching) += 1;
    }
  }
  EXPECT_GE(instances, 24);
  EXPECT_GE(decided_touching, 12);
  EXPECT_GE(decided_overlapping, 12);
}

// The sliding frame as the pair's first part: its offset is the chart's x, the lever's t its y,
// so t = t* is a horizontal edge whose points have a rational abscissa and the irrational
// ordinate t* (the algebraic oracle with y algebraic): touching without the notch, overlapping
// (or culled) with it; nothing undecided.
TEST(IrrationalFit, FrameFirstGivesHorizontalFitEdges) {
  Random random(3333);
  int edges_checked = 0;
  for (int instance = 0; instance < 12; ++instance) {
    Rational delta = random_rational(random, Rational(1, 100), Rational(1, 2), 997);
    const std::vector<mpz_class> m = fit_polynomial(delta);
    if (is_square(m[1] * m[1] - 4 * m[0] * m[2])) continue;
    const Rational w = random_rational(random, Rational(1, 4), Rational(3, 2));
    const Rational scale = scale_of(instance, random);
    const bool notch = instance % 2 == 1;
    SCOPED_TRACE("instance " + std::to_string(instance) + " delta " + delta.get_str() + (notch ? " notched" : ""));
    Model model = read_model(lever_model(delta, w, scale, notch, sliding(scale)));
    CSpace space = CSpace::build(model, "frame", "lever");
    ASSERT_EQ(space.dimension(), 2);
    PairFrame f = pair_frame(model, space);
    EXPECT_EQ(space.statistics().touching_undecided, 0u);
    std::vector<algebra_Real> ts = cspace::algebra::real_roots(m, Rational(0), Rational(1, 2));
    ASSERT_EQ(ts.size(), 1u);
    const double t_star = ts[0].approximate();
    const std::size_t n = f.layout.y_charts.size();
    std::size_t chart = 0;
    while (chart < f.layout.x_charts.size() * n && f.layout.y_charts[chart % n].half_turn) ++chart;
    auto near_t_star = [&](const CSpaceVertex& v) {
      return !f.layout.y_charts[v.chart % n].half_turn && std::abs(Rational(v.y_lower + v.y_upper).get_d() / 2 - t_star) < 1e-9;
    };
    for (const CSpaceEdge& edge : space.edges()) {
      if (edge.vertical || edge.role == EdgeRole::seam || !near_t_star(space.vertices()[edge.source]) ||
          !near_t_star(space.vertices()[edge.target]))
        continue;
      ++edges_checked;
      EXPECT_EQ(edge.role == EdgeRole::touching, !notch);
    }
    auto direct = algebraic_oracle(model, f, chart, algebra_Real::from_rational(Rational(0)), ts[0]);
    ASSERT_TRUE(direct.has_value());
    EXPECT_EQ(*direct, notch ? cspace::Overlap::overlapping : cspace::Overlap::touching);
    algebra_Real t = ts[0];
    t.refine_to(Rational(mpz_class(1), mpz_class(1) << 100));
    for (const Rational& side : {t.lower, t.upper})
      EXPECT_EQ(rational_oracle(model, f, chart, Rational(0), side), cspace::Overlap::overlapping);
  }
  EXPECT_GE(edges_checked, 4);
}

}  // namespace
}  // namespace hipair
