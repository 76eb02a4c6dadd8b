// Vertices whose ordinate is a square root over Q(x) (session 37): a curve of degree 2 in y
// meeting a vertical contact line, or a vertical and a horizontal contact line of degree 2
// crossing (the escapement's 30 wheel–anchor vertices, before: `touching_undecided`, reported
// blocked unchecked). The ordinate is written y = (P(x) + √R(x)) / Q(x) and every sign of a
// polynomial there reduced to signs of univariate ones at x (algebra/ordinate.hpp).
//
//  - AlgebraRadicalOrdinate: the sign of random g(x, y) at (x0, y0), x0 a root of a random
//    integer quadratic, y0 a root of a random a(x) y^2 + b(x) y + c(x) at x0, against an
//    independent evaluation in 4096-bit floating point (GMP's mpf); exact zeros by construction
//    (g = f h + p k, p the minimal polynomial of x0), the sign of f_y (opposite at the two
//    roots), double roots (b^2 - 4ac = 0 at x0, the radicand given or not).
//  - CSpaceRadicalOrdinate: a round pin (radius r, centre at R from its pivot) and a part turning
//    about P with a D-shaped hole: an arc about P of radius H cut by a chord at distance d from P
//    (H, d and the half-chord a Pythagorean triple, the chord's normal a rational direction).
//    With a sagitta H - d of exactly 2r the pin fits only with its centre at distance H - r
//    from P, on the chord's normal: the arc contact is a vertical (or horizontal) line, the
//    chord's curve touches it there (a double root in the other angle: the radicand 0), both
//    coordinates irrational. The independent oracles: the closed form (the pin angle's
//    half-angle tangent a root of the quadratic of |c - P| = H - r) and the rational oracle
//    (classify_overlap) at rationals within 2^-100 of the vertex on all eight sides:
//    overlapping. Random rationals, both pair orders, hole written either way, scales 10^-300,
//    1, 10^300. Main: every fit `touching_undecided`, reported blocked.
//  - The escapement's wheel–anchor pair: no vertex left undecided, none touching (each of the
//    30 has two contact curves, each of one contact: were the parts only touching there, the
//    wedge on the free side of both would be free).
#include "algebra/exact_real.hpp"
#include "algebra/ordinate.hpp"
#include "curves/contact_curves.hpp"
#include "overlapping_beside.hpp"
#include "random_rationals.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace hipair {
using test_numbers::random_rational;

namespace {

using Random = std::mt19937_64;
using cspace::IntegerPolynomial2;
namespace algebra = cspace::algebra;

// ------------------------------------------------------------------ small bivariate arithmetic

// f g + h k through the kernels' rational polynomials: normalized_integer_polynomial keeps the
// zero set and the sign (it divides out the content and factors 1 + x^2, 1 + y^2 only)
cspace::RationalPolynomial2 rational(const IntegerPolynomial2& f) {
  cspace::RationalPolynomial2 r;
  for (std::size_t i = 0; i < f.coefficients.size(); ++i)
    for (std::size_t j = 0; j < f.coefficients[i].size(); ++j)
      if (sgn(f.coefficients[i][j]) != 0) r.set_coefficient(static_cast<int>(i), static_cast<int>(j), Rational(f.coefficients[i][j]));
  return r;
}

IntegerPolynomial2 times(const IntegerPolynomial2& f, const IntegerPolynomial2& g) {
  return cspace::normalized_integer_polynomial(rational(f) * rational(g));
}

IntegerPolynomial2 plus(const IntegerPolynomial2& f, const IntegerPolynomial2& g) {
  return cspace::normalized_integer_polynomial(rational(f) + rational(g));
}

IntegerPolynomial2 random_polynomial(Random& random, int dx, int dy) {
  std::uniform_int_distribution<int> c(-9, 9);
  IntegerPolynomial2 f;
  f.coefficients.assign(static_cast<std::size_t>(dx + 1), std::vector<mpz_class>(static_cast<std::size_t>(dy + 1)));
  for (auto& row : f.coefficients)
    for (auto& v : row) v = c(random);
  return f;
}

IntegerPolynomial2 in_x(const algebra::Polynomial& p) {   // p(x) as a bivariate polynomial
  IntegerPolynomial2 f;
  for (const auto& v : p) f.coefficients.push_back({v});
  return f;
}

// ------------------------------------------------------------------ the floating-point oracle

constexpr unsigned long precision = 4096;

mpf_class to_mpf(const Rational& r) {
  mpf_class n(r.get_num(), precision), d(r.get_den(), precision);
  return n / d;
}

mpf_class eval(const algebra::Polynomial& p, const mpf_class& x) {
  mpf_class v(0, precision);
  for (auto c = p.rbegin(); c != p.rend(); ++c) v = v * x + mpf_class(*c, precision);
  return v;
}

mpf_class eval(const IntegerPolynomial2& f, const mpf_class& x, const mpf_class& y) {
  mpf_class v(0, precision);
  for (auto row = f.coefficients.rbegin(); row != f.coefficients.rend(); ++row) {
    mpf_class r(0, precision);
    for (auto c = row->rbegin(); c != row->rend(); ++c) r = r * y + mpf_class(*c, precision);
    v = v * x + r;
  }
  return v;
}

// x0 to within 2^-3000
mpf_class approximate(const algebra::Real& x) {
  algebra::Real r = x;
  if (!r.exact) algebra::refine_dyadically(r, Rational(mpz_class(1), mpz_class(1) << 3000));
  return to_mpf((r.lower + r.upper) / 2);
}

int sign_of(const mpf_class& v) { return v > 0 ? 1 : v < 0 ? -1 : 0; }

// every mpf_class made in a test (members, temporaries) at 4096 bits; the default restored
struct Precision {
  mp_bitcnt_t saved = mpf_get_default_prec();
  Precision() { mpf_set_default_prec(precision); }
  ~Precision() { mpf_set_default_prec(saved); }
};

struct Point {
  algebra::Real x;
  IntegerPolynomial2 f;   // a y^2 + b y + c through (x, y)
  algebra::RadicalOrdinate y;
  int q = 0;              // sign of y.denominator at x
  int s = 0;              // y = (-b + s √D) / 2a
  mpf_class x_value, y_value;
};

// x0 a root of a random quadratic (rational every fourth time), f a random quadratic in y with
// a(x0) != 0 and D(x0) > 0, y0 its root number s
Point random_point(Random& random, int instance) {
  std::uniform_int_distribution<int> c(-20, 20);
  for (;;) {
    Point p;
    algebra::Polynomial m{c(random), c(random), instance % 4 == 3 ? mpz_class(0) : mpz_class(c(random))};
    algebra::trim(m);
    if (algebra::degree(m) < 1) continue;
    std::vector<algebra::Real> roots = algebra::real_roots(m);
    if (roots.empty()) continue;
    p.x = roots[static_cast<std::size_t>(random() % roots.size())];
    p.f = random_polynomial(random, 2, 2);
    const algebra::Polynomial a = algebra::y_coefficient(p.f, 2), b = algebra::y_coefficient(p.f, 1), cc = algebra::y_coefficient(p.f, 0);
    if (algebra::sign_at(a, p.x) == 0) continue;
    algebra::Polynomial D = algebra::product(b, b), ac4 = algebra::product(algebra::product(a, cc), {mpz_class(4)});
    if (D.size() < ac4.size()) D.resize(ac4.size());
    for (std::size_t i = 0; i < ac4.size(); ++i) D[i] -= ac4[i];
    algebra::trim(D);
    if (algebra::sign_at(D, p.x) <= 0) continue;
    p.s = random() % 2 == 0 ? 1 : -1;
    algebra::Polynomial two_a = algebra::product(a, {mpz_class(2 * p.s)}), minus_b = algebra::product(b, {mpz_class(-p.s)});
    p.y = algebra::RadicalOrdinate{minus_b, D, two_a, {}, {}};
    p.q = algebra::sign_at(two_a, p.x);
    p.x_value = approximate(p.x);
    mpf_class root = sqrt(eval(D, p.x_value));
    p.y_value = (eval(b, p.x_value) * -1 + root * p.s) / (eval(a, p.x_value) * 2);
    return p;
  }
}

TEST(AlgebraRadicalOrdinate, SignsAtARootOfAQuadraticOverQxAgreeWithAnIndependentEvaluation) {
  const Precision bits;
  Random random(3737);
  int compared = 0, zeros = 0, opposite = 0;
  for (int instance = 0; instance < 60; ++instance) {
    const Point p = random_point(random, instance);
    SCOPED_TRACE("instance " + std::to_string(instance) + " x " + p.x.description() + " f " + algebra::to_string(p.f, "x", "y") +
                 " s " + std::to_string(p.s));
    // the ordinate is a root of f: sign 0 (and f(x0, y0) ~ 0 in floating point)
    EXPECT_EQ(algebra::sign_at(p.f, p.x, p.y, p.q), 0);
    EXPECT_LT(abs(eval(p.f, p.x_value, p.y_value)), mpf_class(1e-300));
    // f_y = 2a y + b = s √D: sign s, times any h(x)
    IntegerPolynomial2 fy;
    fy.coefficients.resize(p.f.coefficients.size());
    for (std::size_t i = 0; i < p.f.coefficients.size(); ++i)
      for (std::size_t j = 1; j < p.f.coefficients[i].size(); ++j) fy.coefficients[i].push_back(p.f.coefficients[i][j] * static_cast<long>(j));
    const IntegerPolynomial2 h = random_polynomial(random, 2, 0);
    const algebra::Polynomial hx = algebra::y_coefficient(h, 0);
    if (algebra::sign_at(hx, p.x) != 0) {
      EXPECT_EQ(algebra::sign_at(times(fy, h), p.x, p.y, p.q), p.s * algebra::sign_at(hx, p.x));
      ++opposite;
    }
    // random polynomials: against the evaluation at 4096 bits
    for (int k = 0; k < 6; ++k) {
      const IntegerPolynomial2 g = random_polynomial(random, 1 + k % 3, 1 + k % 4);
      const mpf_class v = eval(g, p.x_value, p.y_value);
      if (abs(v) < mpf_class(1e-200)) continue;
      EXPECT_EQ(algebra::sign_at(g, p.x, p.y, p.q), sign_of(v)) << algebra::to_string(g, "x", "y");
      ++compared;
    }
    // exact zeros: g = f k + m l, m x0's polynomial
    if (!p.x.exact) {
      const IntegerPolynomial2 g = plus(times(p.f, random_polynomial(random, 1, 2)), times(in_x(p.x.polynomial), random_polynomial(random, 2, 3)));
      EXPECT_EQ(algebra::sign_at(g, p.x, p.y, p.q), 0) << algebra::to_string(g, "x", "y");
      ++zeros;
    }
  }
  EXPECT_GE(compared, 300);
  EXPECT_GE(zeros, 30);
  EXPECT_GE(opposite, 50);
}

TEST(AlgebraRadicalOrdinate, ADoubleRootIsPosedWithOrWithoutItsZeroRadicand) {
  // f = (d y - n)^2 + m(x) e(x, y): at a root x0 of m, f(x0, .) has the double root n / d
  const Precision bits;
  Random random(3738);
  std::uniform_int_distribution<int> c(-20, 20);
  int compared = 0;
  for (int instance = 0; instance < 40; ++instance) {
    algebra::Polynomial m{c(random), c(random), c(random)};
    algebra::trim(m);
    if (algebra::degree(m) < 2) continue;
    std::vector<algebra::Real> roots = algebra::real_roots(m);
    if (roots.empty()) continue;
    const algebra::Real x = roots.front();
    IntegerPolynomial2 line = random_polynomial(random, 1, 1);   // d(x) y - n(x)
    const algebra::Polynomial d = algebra::y_coefficient(line, 1);
    if (algebra::sign_at(d, x) == 0) continue;
    const IntegerPolynomial2 f = plus(times(line, line), times(in_x(m), random_polynomial(random, 1, 2)));
    if (f.degree_y() != 2) continue;
    const algebra::Polynomial a = algebra::y_coefficient(f, 2), b = algebra::y_coefficient(f, 1), cc = algebra::y_coefficient(f, 0);
    if (algebra::sign_at(a, x) == 0) continue;
    algebra::Polynomial D = algebra::product(b, b), ac4 = algebra::product(algebra::product(a, cc), {mpz_class(4)});
    if (D.size() < ac4.size()) D.resize(ac4.size());
    for (std::size_t i = 0; i < ac4.size(); ++i) D[i] -= ac4[i];
    algebra::trim(D);
    SCOPED_TRACE("instance " + std::to_string(instance) + " x " + x.description() + " f " + algebra::to_string(f, "x", "y"));
    ASSERT_EQ(algebra::sign_at(D, x), 0);
    const algebra::Polynomial two_a = algebra::product(a, {mpz_class(2)}), minus_b = algebra::product(b, {mpz_class(-1)});
    const int q = algebra::sign_at(two_a, x);
    const mpf_class xv = approximate(x);
    const mpf_class yv = eval(algebra::product(algebra::y_coefficient(line, 0), {mpz_class(-1)}), xv) / eval(d, xv);
    for (const algebra::Polynomial& radicand : {algebra::Polynomial{}, D}) {
      const algebra::RadicalOrdinate y{minus_b, radicand, two_a, {}, {}};
      EXPECT_EQ(algebra::sign_at(f, x, y, q), 0);
      EXPECT_EQ(algebra::sign_at(line, x, y, q), 0);
      for (int k = 0; k < 4; ++k) {
        const IntegerPolynomial2 g = random_polynomial(random, 1 + k % 2, 1 + k);
        const mpf_class v = eval(g, xv, yv);
        if (abs(v) < mpf_class(1e-200)) continue;
        EXPECT_EQ(algebra::sign_at(g, x, y, q), sign_of(v)) << algebra::to_string(g, "x", "y");
        ++compared;
      }
    }
  }
  EXPECT_GE(compared, 60);
}

// ------------------------------------------------------------------ the D-shaped hole

std::string text(const Rational& q) { return "\"" + q.get_str() + "\""; }

struct DFit {
  Rational R, px, py, k, m;   // unscaled; the chord's normal ((1 - k^2), 2k) / (1 + k^2)
  long p = 2, q = 1;          // H : d : w = p^2 + q^2 : p^2 - q^2 : 2pq (times m)
  Rational scale = 1;
  bool clockwise = true, pin_first = true;

  Rational H() const { return m * (p * p + q * q); }
  Rational d() const { return m * (p * p - q * q); }
  Rational w() const { return m * 2 * p * q; }
  Rational r() const { return (H() - d()) / 2; }
  std::string point(const Rational& x, const Rational& y) const { return "[" + text(x * scale) + ", " + text(y * scale) + "]"; }
  std::string json() const {
    const Rational n1 = (1 - k * k) / (1 + k * k), n2 = 2 * k / (1 + k * k);
    const Rational cx = px + d() * n1, cy = py + d() * n2;   // the chord's midpoint
    const Rational e1x = cx - w() * n2, e1y = cy + w() * n1, e2x = cx + w() * n2, e2y = cy - w() * n1;
    const Rational S = 2 * H();
    const std::string outer = R"({ "start": )" + point(px - S, py - S) + R"(, "edges": [ { "line_to": )" + point(px + S, py - S) +
                              R"( }, { "line_to": )" + point(px + S, py + S) + R"( }, { "line_to": )" + point(px - S, py + S) +
                              R"( }, { "line_to": )" + point(px - S, py - S) + " } ] }";
    // the arc runs from e2 to e1 counter-clockwise (through the normal's direction)
    const std::string hole =
        clockwise ? R"({ "start": )" + point(e1x, e1y) + R"(, "edges": [ { "arc_to": )" + point(e2x, e2y) + R"(, "center": )" +
                        point(px, py) + R"(, "dir": "cw" }, { "line_to": )" + point(e1x, e1y) + " } ] }"
                  : R"({ "start": )" + point(e2x, e2y) + R"(, "edges": [ { "arc_to": )" + point(e1x, e1y) + R"(, "center": )" +
                        point(px, py) + R"(, "dir": "ccw" }, { "line_to": )" + point(e2x, e2y) + " } ] }";
    const std::string pair = pin_first ? R"(["pin", "frame"])" : R"(["frame", "pin"])";
    return R"({ "hipair": 1, "name": "d-fit", "parts": [
      { "name": "pin", "motion": { "rotation": { "pivot": [0, 0], "limits": [0, 180] } },
        "loops": [ { "circle": { "center": )" + point(R, 0) + R"(, "radius": )" + text(r() * scale) + R"( } } ] },
      { "name": "frame", "motion": { "rotation": { "pivot": )" + point(px, py) + R"(, "limits": [-180, 180] } },
        "loops": [ )" + outer + ", " + hole + R"( ] } ],
      "pairs": [ { "parts": )" + pair + " } ] }";
  }
};

DFit generate(Random& random, int instance) {
  static const std::vector<Rational> scales = {Rational(1), Rational(mpz_class(1), mpz_class("1" + std::string(300, '0'))),
                                               Rational(mpz_class("1" + std::string(300, '0')))};
  static const std::vector<std::pair<long, long>> triples = {{2, 1}, {3, 2}, {4, 1}, {4, 3}, {5, 2}};
  DFit fit;
  fit.scale = scales[static_cast<std::size_t>(instance) % 3];
  std::tie(fit.p, fit.q) = triples[static_cast<std::size_t>(instance) % triples.size()];
  fit.m = random_rational(random, Rational(1, 2), Rational(3, 2)) / (fit.p * fit.p + fit.q * fit.q);   // H in (1/2, 3/2)
  fit.k = random_rational(random, Rational(-2), Rational(2));
  // the pin's circle (radius R about the origin) crosses |c - P| = H - r away from tangency,
  // with the pin above the x axis (limits 0 .. 180 degrees): P above, |P| - R small
  fit.R = random_rational(random, Rational(4), Rational(8));
  const Rational rho = fit.H() - fit.r();
  fit.px = random_rational(random, Rational(-1), Rational(1));
  fit.py = fit.R + random_rational(random, -rho / 2, rho / 2);
  for (Rational* v : {&fit.R, &fit.px, &fit.py, &fit.k, &fit.m}) v->canonicalize();
  fit.clockwise = instance % 2 == 0;
  fit.pin_first = instance % 4 < 2;
  return fit;
}

cspace::Overlap oracle(const Model& model, const CSpace& space, std::size_t chart, const Rational& x, const Rational& y) {
  const std::size_t first = *model.find_part(space.first_part()), second = *model.find_part(space.second_part());
  const cspace::PairAxes axes = cspace::pair_axes(model, first, second);
  return test::chart_overlap(model, axes, cspace::chart_layout(model, axes), chart, x, y);
}

TEST(CSpaceRadicalOrdinate, APinInADShapedHoleOfExactlyItsSagittaTouchesAtTheClosedForm) {
  int touching = 0, beside = 0;   // fits found; fits checked by the rational oracle beside them
  Random random(3739);
  for (int instance = 0; instance < 12; ++instance) {
    const DFit fit = generate(random, instance);
    SCOPED_TRACE("instance " + std::to_string(instance) + " R " + fit.R.get_str() + " P " + fit.px.get_str() + ", " +
                 fit.py.get_str() + " k " + fit.k.get_str() + " m " + fit.m.get_str() + " triple " + std::to_string(fit.p) + "," +
                 std::to_string(fit.q) + (fit.clockwise ? " cw" : " ccw") + (fit.pin_first ? "" : " frame first") + " scale 10^" +
                 std::to_string(fit.scale > 1 ? 300 : fit.scale < 1 ? -300 : 0));
    const Model model = read_model(fit.json());
    const CSpace space = fit.pin_first ? CSpace::build(model, "pin", "frame") : CSpace::build(model, "frame", "pin");
    ASSERT_EQ(space.dimension(), 2);
    EXPECT_EQ(space.statistics().touching_undecided, 0u);
    // two fits: the pin's circle meets |c - P| = H - r twice, both within the pin's limits
    EXPECT_EQ(space.statistics().touching_vertices, 2u);
    const bool t_is_x = space.x_part() == "pin";
    // |c - P|^2 = (H - r)^2 with c = R ((1 - t^2), 2t) / (1 + t^2):
    // (R^2 + |P|^2 - (H - r)^2)(1 + t^2) - 2R (px (1 - t^2) + 2 py t) = 0
    // (a chart about theta = pi: c = -R ((1 - t^2), 2t) / (1 + t^2), P's signs turned instead)
    const Rational rho = fit.H() - fit.r(), e = fit.R * fit.R + fit.px * fit.px + fit.py * fit.py - rho * rho;
    const std::size_t first = *model.find_part(space.first_part()), second = *model.find_part(space.second_part());
    const cspace::ChartLayout layout = cspace::chart_layout(model, cspace::pair_axes(model, first, second));
    for (const CSpaceVertex& vertex : space.vertices()) {
      if (!vertex.touching) continue;
      ++touching;
      const std::size_t n = layout.y_charts.size();
      const int turn = (t_is_x ? layout.x_charts[vertex.chart / n] : layout.y_charts[vertex.chart % n]).half_turn ? -1 : 1;
      const std::vector<Rational> coefficients{e - 2 * turn * fit.R * fit.px, -4 * turn * fit.R * fit.py, e + 2 * turn * fit.R * fit.px};
      const algebra::Polynomial quadratic = algebra::from_rationals(coefficients);
      const bool exact = vertex.x.exact && vertex.y_exact && vertex.y.exact;
      EXPECT_FALSE(exact);
      // the pin's angle: a root of the quadratic (isolated by its interval)
      if (t_is_x) {
        if (vertex.x.exact) {
          EXPECT_EQ(algebra::sign_at(quadratic, vertex.x.lower), 0);
        } else {
          EXPECT_LT(algebra::sign_at(quadratic, vertex.x.lower) * algebra::sign_at(quadratic, vertex.x.upper), 0) << vertex.x.to_string();
        }
      } else {
        EXPECT_LT(algebra::sign_at(quadratic, vertex.y_lower) * algebra::sign_at(quadratic, vertex.y_upper), 0);
      }
      // the rational oracle within 2^-100 on every side (scaled for a frame translation: none
      // here, both coordinates are half-angle tangents): overlapping
      const Rational x_width = vertex.x.upper - vertex.x.lower, y_width = vertex.y_upper - vertex.y_lower;
      if (x_width.get_d() > 1e-12 || y_width.get_d() > 1e-12) continue;
      const Rational x0 = (vertex.x.lower + vertex.x.upper) / 2, y0 = (vertex.y_lower + vertex.y_upper) / 2;
      const Rational epsilon(mpz_class(1), mpz_class(1) << 100);
      ++beside;
      test::expect_overlapping_beside([&](const Rational& x, const Rational& y) { return oracle(model, space, vertex.chart, x, y); },
                                      x0, y0, epsilon, epsilon);
    }
  }
  EXPECT_EQ(touching, 24);
  EXPECT_GE(beside, 12);
}

TEST(CSpaceRadicalOrdinate, TheEscapementWheelAndAnchorLeaveNoVertexUndecided) {
  const Model model = read_model_file(std::string(HIPAIR_SOURCE_DIR) + "/examples/models/escapement.json");
  const CSpace space = CSpace::build(model, "escape-wheel", "anchor");
  EXPECT_EQ(space.statistics().touching_undecided, 0u);   // main: 30
  EXPECT_EQ(space.statistics().touching_vertices, 0u);
  EXPECT_EQ(space.statistics().touching_edges, 0u);
}

}  // namespace
}  // namespace hipair
