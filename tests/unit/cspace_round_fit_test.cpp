// A round pin in a round hole of exactly its radius (session 36): the pin (radius r, its
// centre c = R (cos θ, sin θ) turning about the origin) and a frame sliding along x whose hole
// is centred at h = (hx + s, hy). They fit where c = h: sin θ = hy / R (t = tan(θ/2) a root of
// hy t^2 - 2 R t + hy) and s = R cos θ - hx, both irrational unless R^2 - hy^2 is a rational
// square. Every other configuration near the fit overlaps, so the fit is an isolated touching
// vertex of the 2-D space, and the only vertex there: the arc–arc contact curve is an isolated
// point (a sum of squares).
//
// Two wrong claims of main, both found by this generator:
//  - a full circle written clockwise (`"dir": "cw"`, as a hole runs) was given the area of a
//    counter-clockwise one by the model reader, so the reader turned a hole written that way
//    into a solid disk (and an outer circle written so into a hole): the pin was blocked
//    everywhere in its hole, the exact fit reported blocked;
//  - a vertex with both coordinates irrational (or an ordinate known only by its curve) was
//    never checked: blocked all around, it was reported blocked without a warning (not even
//    counted in touching_undecided). Now the algebraic oracle poses it at its ordinate as a
//    rational function of its abscissa (curves/algebraic_overlap.hpp, RadicalOrdinate).
// The independent oracles: the closed form above (the vertex's t exactly a root of the
// quadratic, its s within 10^-9), and the rational oracle (classify_overlap) at rationals
// within 2^-100 of the vertex on every side: overlapping; at a rational fit: touching there.
// A frame with a tooth (a small square inside the hole, under the pin at the fit) overlaps at
// the fit: no touching vertex, nothing undecided. Scales 10^-300, 1, 10^300; both pair orders.
#include "algebra/exact_real.hpp"
#include "curves/contact_curves.hpp"
#include "overlapping_beside.hpp"
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
using test_loops::text;
using test_numbers::random_rational;

namespace {

using Random = std::mt19937_64;

struct RoundFit {
  Rational R, r, hx, hy;   // unscaled
  Rational scale = 1;
  bool clockwise = true;   // the hole written clockwise (else counter-clockwise, the reader turns it)
  bool tooth = false;
  bool pin_first = true;
  Rational s_lo, s_hi;     // limits of s, unscaled, around the fit with cos θ > 0

  double fit_s() const {
    const double R_ = R.get_d(), hy_ = hy.get_d();
    return std::sqrt(R_ * R_ - hy_ * hy_) - hx.get_d();
  }
  std::string point(const Rational& x, const Rational& y) const { return "[" + text(x * scale) + ", " + text(y * scale) + "]"; }
  std::string json() const {
    const Rational side = 3 * r;
    std::string hole = R"({ "start": )" + point(hx + r, hy) + R"(, "edges": [ { "arc_to": )" + point(hx + r, hy) +
                       R"(, "center": )" + point(hx, hy) + R"(, "dir": ")" + (clockwise ? "cw" : "ccw") + R"(" } ] })";
    auto square = [&](const Rational& cx, const Rational& cy, const Rational& a) {
      return R"({ "start": )" + point(cx - a, cy - a) + R"(, "edges": [ { "line_to": )" + point(cx + a, cy - a) +
             R"( }, { "line_to": )" + point(cx + a, cy + a) + R"( }, { "line_to": )" + point(cx - a, cy + a) +
             R"( }, { "line_to": )" + point(cx - a, cy - a) + " } ] }";
    };
    std::string loops = square(hx, hy, side) + ", " + hole;
    if (tooth) loops += ", " + square(hx + r / 2, hy, r / 10);
    const std::string pair = pin_first ? R"(["pin", "frame"])" : R"(["frame", "pin"])";
    return R"({ "hipair": 1, "name": "round-fit", "parts": [
      { "name": "pin", "motion": { "rotation": { "pivot": [0, 0] } },
        "loops": [ { "circle": { "center": )" + point(R, 0) + R"(, "radius": )" + text(r * scale) + R"( } } ] },
      { "name": "frame", "motion": { "translation": { "direction": [1, 0], "limits": [)" + text(s_lo * scale) + ", " +
           text(s_hi * scale) + R"(] } }, "loops": [ )" + loops + R"( ] } ],
      "pairs": [ { "parts": )" + pair + " } ] }";
  }
};

RoundFit generate(Random& random, int instance) {
  static const std::vector<Rational> scales = {Rational(1), Rational(mpz_class(1), mpz_class("1" + std::string(300, '0'))),
                                               Rational(mpz_class("1" + std::string(300, '0')))};
  RoundFit fit;
  fit.scale = scales[static_cast<std::size_t>(instance) % 3];
  if (instance % 5 == 4) {   // a Pythagorean fit: sin θ = 3/5, cos θ = 4/5 (both coordinates rational)
    const Rational m = random_rational(random, Rational(1), Rational(3));
    fit.R = 5 * m;
    fit.hy = 3 * m;
  } else {
    fit.R = random_rational(random, Rational(5), Rational(15));
    fit.hy = random_rational(random, -fit.R * Rational(4, 5), fit.R * Rational(4, 5));
  }
  fit.r = random_rational(random, Rational(1, 2), Rational(2));
  fit.hx = random_rational(random, Rational(-3), Rational(3));
  for (Rational* q : {&fit.R, &fit.hy, &fit.r, &fit.hx}) q->canonicalize();
  fit.clockwise = instance % 2 == 0;
  fit.tooth = instance % 4 == 3;
  fit.pin_first = instance % 3 != 1;
  // limits: the fit with cos θ > 0 within (s_lo, s_hi), the other (cos θ < 0) far outside
  const double s = fit.fit_s();
  fit.s_lo = Rational(std::floor(s * 8) / 8 - 1);
  fit.s_hi = Rational(std::floor(s * 8) / 8 + 1);
  return fit;
}

struct Pair {
  cspace::PairAxes axes;
  cspace::ChartLayout layout;
};

Pair pair_of(const Model& model, const CSpace& space) {
  std::size_t first = *model.find_part(space.first_part()), second = *model.find_part(space.second_part());
  Pair p{cspace::pair_axes(model, first, second), {}};
  p.layout = cspace::chart_layout(model, p.axes);
  return p;
}

cspace::Overlap oracle(const Model& model, const Pair& p, std::size_t chart, const Rational& x, const Rational& y) {
  return test::chart_overlap(model, p.axes, p.layout, chart, x, y);
}

TEST(CSpaceRoundFit, APinInAHoleOfExactlyItsRadiusIsAnIsolatedTouchingVertexAtTheClosedForm) {
  Random random(3636);
  int irrational = 0, touching = 0, exact_contacts = 0;
  for (int instance = 0; instance < 24; ++instance) {
    const RoundFit fit = generate(random, instance);
    SCOPED_TRACE("instance " + std::to_string(instance) + " R " + fit.R.get_str() + " r " + fit.r.get_str() + " hx " +
                 fit.hx.get_str() + " hy " + fit.hy.get_str() + (fit.clockwise ? " cw" : " ccw") +
                 (fit.tooth ? " tooth" : "") + (fit.pin_first ? "" : " frame first") + " scale 10^" +
                 std::to_string(fit.scale > 1 ? 300 : fit.scale < 1 ? -300 : 0));
    const Model model = read_model(fit.json());
    // the reader: the hole is a hole whichever way it was written, the pin a disk
    const Part& frame = model.parts.at(*model.find_part("frame"));
    ASSERT_EQ(frame.loops.size(), fit.tooth ? 3u : 2u);
    EXPECT_TRUE(frame.loops[1].is_hole);
    EXPECT_FALSE(frame.loops[1].edges[0].ccw);
    EXPECT_TRUE(model.parts.at(*model.find_part("pin")).loops[0].edges[0].ccw);

    const CSpace space = fit.pin_first ? CSpace::build(model, "pin", "frame") : CSpace::build(model, "frame", "pin");
    ASSERT_EQ(space.dimension(), 2);
    const bool t_is_x = space.x_part() == "pin";
    EXPECT_EQ(space.statistics().touching_undecided, 0u);
    EXPECT_EQ(space.statistics().touching_vertices, fit.tooth ? 0u : 1u);
    const Pair p = pair_of(model, space);
    // hy t^2 - 2 R t + hy over one denominator (the closed form of sin θ = hy / R)
    Rational a = fit.hy, b = -2 * fit.R;
    const mpz_class den = a.get_den() * b.get_den();
    Rational an = a * den, bn = b * den;
    an.canonicalize();
    bn.canonicalize();
    const std::vector<mpz_class> quadratic{an.get_num(), bn.get_num(), an.get_num()};
    for (const CSpaceVertex& vertex : space.vertices()) {
      if (!vertex.touching) continue;
      ++touching;
      ASSERT_FALSE(fit.tooth);
      // the closed form: t exactly a root of the quadratic; s within 10^-9 of R cos θ - hx
      const AlgebraicNumber& t = t_is_x ? vertex.x : vertex.y;
      if (!t_is_x && !vertex.y_exact) {
        // t known by its isolating bounds on the vertex's curve: the quadratic changes sign there
        EXPECT_LT(cspace::algebra::sign_at(quadratic, vertex.y_lower) * cspace::algebra::sign_at(quadratic, vertex.y_upper), 0);
      } else if (t.exact) {
        EXPECT_EQ(cspace::algebra::sign_at(quadratic, t.lower), 0) << t.to_string();
      } else {
        // the quadratic changes sign across t's isolating interval and shares t's polynomial's
        // roots (t's is square-free with one root there)
        EXPECT_LT(cspace::algebra::sign_at(quadratic, t.lower) * cspace::algebra::sign_at(quadratic, t.upper), 0) << t.to_string();
        EXPECT_EQ(cspace::algebra::degree(cspace::algebra::gcd(quadratic, t.polynomial)), 2) << t.to_string();
      }
      const Rational s_lo = (t_is_x ? vertex.y_lower : vertex.x.lower) / fit.scale, s_hi = (t_is_x ? vertex.y_upper : vertex.x.upper) / fit.scale;
      // (an abscissa's isolating interval is not refined: only narrow ones are compared)
      const Rational x_width = (vertex.x.upper - vertex.x.lower) / (t_is_x ? Rational(1) : fit.scale);
      const Rational y_width = (vertex.y_upper - vertex.y_lower) / (t_is_x ? fit.scale : Rational(1));
      if (x_width.get_d() > 1e-12 || y_width.get_d() > 1e-12) continue;
      EXPECT_NEAR((s_lo.get_d() + s_hi.get_d()) / 2, fit.fit_s(), 1e-9);
      // the rational oracle: at a rational fit touching there; within 2^-100 on every side overlapping
      const bool exact = vertex.x.exact && vertex.y_exact && vertex.y.exact;
      if (exact) {
        EXPECT_EQ(oracle(model, p, vertex.chart, vertex.x.lower, vertex.y.lower), cspace::Overlap::touching);
        // the contacts there: the pin and the hole are concentric circles of one radius, touching
        // along the whole circle, so their pair has no contact point or normal and is not listed
        // (the exact frame divided by the centres' squared distance, 0 there: GMP's division by
        // zero, a crash, until session 73); every other feature pair is apart at the fit
        ++exact_contacts;
        const std::vector<Contact> contacts = space.contact_at(ChartPoint{vertex.chart, vertex.x.lower, vertex.y.lower});
        EXPECT_TRUE(contacts.empty()) << contacts.size();
      } else {
        ++irrational;
      }
      const Rational x0 = exact ? vertex.x.lower : (vertex.x.lower + vertex.x.upper) / 2;
      const Rational y0 = exact ? vertex.y.lower : (vertex.y_lower + vertex.y_upper) / 2;
      const Rational ex = Rational(mpz_class(1), mpz_class(1) << 100), ey = ex * (t_is_x ? fit.scale : Rational(1));
      const Rational exs = ex * (t_is_x ? Rational(1) : fit.scale);
      test::expect_overlapping_beside([&](const Rational& x, const Rational& y) { return oracle(model, p, vertex.chart, x, y); },
                                      x0, y0, exs, ey);
    }
  }
  // both kinds were generated and decided
  EXPECT_GE(irrational, 4);
  EXPECT_GE(touching, 12);
  EXPECT_GE(exact_contacts, 2);   // the Pythagorean fits of this seed with narrow intervals
}

}  // namespace
}  // namespace hipair
