// Session 49 (exact49): analyze's decisions on unwrapped coordinates made exact
// (kinematics/axis.hpp compare_unwrapped, compare_push_distances): a follower's exact position
// against its spring's rest (rad or mm, a rational), and the push out of blocked space towards
// the nearer end. Until session 49 both were doubles (`rest - here` with a dead zone of 1e-12,
// `down <= up`).
// Oracle: the unwrapped angle m pi + 2 atan(t) of a generated position (t a rational or the root
// sqrt(c) of x^2 - c, on a cyclic axis with whole turns) in MPFR at 2000 bits, far finer than the
// generated gaps (2^-55 ... 2^-300): a rest R = floor(A 2^k) / 2^k lies below A and
// ceil(A 2^k) / 2^k above it (A is irrational unless t = 0, m = 0). The pushes: three positions on
// a translation at rational ties (decided exactly as ties) and near-ties 2^-k off with an
// algebraic end, exact ties of irrational ends about a rational middle (sqrt c, 3, 6 - sqrt c) and
// near-ties 2^-1030 ... off them (past the enclosures' 2^-1024), and on a rotation near-ties, each
// sign from the oracle or the closed form.
#include "kinematics/axis.hpp"
#include "kinematics_axis_lines.hpp"

#include <gtest/gtest.h>
#include <mpfr.h>

#include <cmath>
#include <numbers>
#include <random>

namespace hipair::kinematics_detail {
namespace {

namespace algebra = cspace::algebra;
using algebra::Polynomial;

constexpr double pi_d = std::numbers::pi;

AxisLine translation_line() {
  AxisLine line;
  line.rotation = false;
  line.pieces = {ChartAxis{ChartAxis::Kind::translation, false, Rational(-100), Rational(100)}};
  line.half_turns = {0};
  line.offsets = {0.0};
  return line;
}

// sqrt(c) (0 < c < 1 rational, not a square) as the root of den x^2 - num in (0, 1)
Real square_root(const Rational& c) {
  Polynomial p{-c.get_num(), 0, c.get_den()};
  std::vector<Real> roots = algebra::real_roots(p, Rational(0), Rational(1));
  return roots.at(0);
}

struct Oracle {
  mpfr_t v;
  Oracle() { mpfr_init2(v, 2000); }
  ~Oracle() { mpfr_clear(v); }
};

// A = m pi + 2 atan(t), t = sign sqrt(c) or the rational r (c == 0)
void oracle_angle(Oracle& out, long m, const Rational& c, int sign, const Rational& r) {
  mpfr_t x, p;
  mpfr_inits2(2000, x, p, static_cast<mpfr_ptr>(nullptr));
  if (sgn(c) != 0) {
    mpfr_set_q(x, c.get_mpq_t(), MPFR_RNDN);
    mpfr_sqrt(x, x, MPFR_RNDN);
    if (sign < 0) mpfr_neg(x, x, MPFR_RNDN);
  } else {
    mpfr_set_q(x, r.get_mpq_t(), MPFR_RNDN);
  }
  mpfr_atan(x, x, MPFR_RNDN);
  mpfr_mul_2ui(x, x, 1, MPFR_RNDN);
  mpfr_const_pi(p, MPFR_RNDN);
  mpfr_mul_si(p, p, m, MPFR_RNDN);
  mpfr_add(out.v, x, p, MPFR_RNDN);
  mpfr_clears(x, p, static_cast<mpfr_ptr>(nullptr));
}

// floor (down) or ceil of A 2^k, over 2^k
Rational grid_neighbour(const Oracle& a, int k, bool down) {
  mpfr_t s;
  mpfr_init2(s, 2000);
  mpfr_mul_2ui(s, a.v, static_cast<unsigned long>(k), MPFR_RNDN);
  if (down) mpfr_floor(s, s);
  else mpfr_ceil(s, s);
  mpz_class z;
  mpfr_get_z(z.get_mpz_t(), s, MPFR_RNDN);
  mpfr_clear(s);
  Rational r(z, mpz_class(1) << k);
  r.canonicalize();
  return r;
}

struct Position {
  AxisPosition at;
  double unwrapped = 0;
  long m = 0;   // half turns
  Rational c, r;
  int sign = 1;
};

// A generated position on the cyclic axis: piece, whole turns, t irrational or rational.
Position generated_position(std::mt19937_64& random, const AxisLine& line) {
  Position p;
  std::size_t piece = random() % 2;
  long turns = static_cast<long>(random() % 7) - 3;
  p.m = 2 * turns + static_cast<long>(piece);
  Real t;
  if (random() % 4 != 0) {
    p.c = Rational(static_cast<long>(random() % 997) + 1, 1009);   // never a square
    p.sign = random() % 2 ? 1 : -1;
    t = square_root(p.c);
    if (p.sign < 0) {
      Polynomial q = t.polynomial;
      for (std::size_t i = 1; i < q.size(); i += 2) q[i] = -q[i];
      Real negated{q, -t.upper, -t.lower, false};
      t = negated;
    }
  } else {
    p.r = Rational(static_cast<long>(random() % 1999) - 999, 1000);
    t = Real::from_rational(p.r);
  }
  p.at = AxisPosition{piece, t};   // |t| < 1: canonical
  p.unwrapped = 2 * pi_d * turns + coordinate(line, p.at);
  return p;
}

TEST(KinematicsExactRest, RotatingRestAgainstCertifiedAngle) {
  std::mt19937_64 random(49);
  AxisLine line = test_axes::full_turn();
  int cases = 0;
  for (int i = 0; i < 120; ++i) {
    Position p = generated_position(random, line);
    Oracle a;
    oracle_angle(a, p.m, p.c, p.sign, p.r);
    if (sgn(p.c) == 0 && sgn(p.r) == 0 && p.m == 0) continue;   // the rational case below
    int k = 55 + static_cast<int>(random() % 246);
    Rational below = grid_neighbour(a, k, true), above = grid_neighbour(a, k, false);
    EXPECT_EQ(compare_unwrapped(line, p.at, p.unwrapped, below), 1) << "k " << k << " m " << p.m;
    EXPECT_EQ(compare_unwrapped(line, p.at, p.unwrapped, above), -1) << "k " << k << " m " << p.m;
    ++cases;
  }
  EXPECT_GT(cases, 100);
  // rest 0 at t = 0: equal, exactly; and a rest 2^-200 either side
  AxisPosition zero{0, Real::from_rational(Rational(0))};
  Rational tiny(mpz_class(1), mpz_class(1) << 200);
  EXPECT_EQ(compare_unwrapped(line, zero, 0.0, Rational(0)), 0);
  EXPECT_EQ(compare_unwrapped(line, zero, 0.0, tiny), -1);
  EXPECT_EQ(compare_unwrapped(line, zero, 0.0, Rational(-tiny)), 1);
  // the same point a whole turn on
  EXPECT_EQ(compare_unwrapped(line, zero, 2 * pi_d, Rational(6)), 1);
  EXPECT_EQ(compare_unwrapped(line, zero, 2 * pi_d, Rational(7)), -1);
}

TEST(KinematicsExactRest, TranslatingRestExact) {
  std::mt19937_64 random(4949);
  AxisLine line = translation_line();
  for (int i = 0; i < 60; ++i) {
    Rational c(static_cast<long>(random() % 997) + 1, 1009);
    Real t = square_root(c);
    int k = 55 + static_cast<int>(random() % 246);
    Oracle a;
    mpfr_set_q(a.v, c.get_mpq_t(), MPFR_RNDN);
    mpfr_sqrt(a.v, a.v, MPFR_RNDN);
    AxisPosition at{0, t};
    EXPECT_EQ(compare_unwrapped(line, at, t.approximate(), grid_neighbour(a, k, true)), 1);
    EXPECT_EQ(compare_unwrapped(line, at, t.approximate(), grid_neighbour(a, k, false)), -1);
    // a rational position equal to the rest
    Rational r = grid_neighbour(a, k, true);
    EXPECT_EQ(compare_unwrapped(line, AxisPosition{0, Real::from_rational(r)}, r.get_d(), r), 0);
  }
}

TEST(KinematicsExactRest, PushTowardsTheNearerEnd) {
  std::mt19937_64 random(494949);
  AxisLine straight = translation_line();
  for (int i = 0; i < 40; ++i) {
    // rational tie: b the midpoint of a and c, decided as a tie (down)
    Rational a(static_cast<long>(random() % 1000) - 500, 7), c = a + Rational(static_cast<long>(random() % 1000) + 1, 13);
    Rational b = (a + c) / 2;
    bool decided = false;
    auto at = [](const Rational& v) { return AxisPosition{0, Real::from_rational(v)}; };
    EXPECT_EQ(compare_push_distances(straight, at(a), a.get_d(), at(b), b.get_d(), at(c), c.get_d(), decided), 0);
    EXPECT_TRUE(decided);
    // c = 2 b - a + 2^-k: up is longer; - 2^-k: shorter (a algebraic: sqrt, k up to 300)
    Rational root_c(static_cast<long>(random() % 997) + 1, 1009);
    Real alg = square_root(root_c);
    Oracle s;
    mpfr_set_q(s.v, root_c.get_mpq_t(), MPFR_RNDN);
    mpfr_sqrt(s.v, s.v, MPFR_RNDN);
    int k = 55 + static_cast<int>(random() % 246);
    Rational b2(3);
    Rational far_down = grid_neighbour(s, k, true);   // < sqrt(c): 2 b2 - sqrt - far_down < 2 b2 - 2 far_down
    // a = sqrt(c), b = 3, c_end = 6 - floor(sqrt 2^k)/2^k > 6 - sqrt: (b - a) < (c_end - b)
    Rational c_end = 2 * b2 - far_down;
    EXPECT_EQ(compare_push_distances(straight, AxisPosition{0, alg}, alg.approximate(), at(b2), 3.0, at(c_end),
                                     c_end.get_d(), decided),
              -1)
        << "k " << k;
    EXPECT_TRUE(decided);
    Rational c_near = 2 * b2 - grid_neighbour(s, k, false);
    EXPECT_EQ(compare_push_distances(straight, AxisPosition{0, alg}, alg.approximate(), at(b2), 3.0, at(c_near),
                                     c_near.get_d(), decided),
              1)
        << "k " << k;
    EXPECT_TRUE(decided);
  }
  // an exact tie of irrational ends about a rational middle: a = sqrt c, b = 3, c_end = 6 - sqrt c
  // (the lower root of (x - 6)^2 - c), decided as a tie; and 6 - sqrt c' for c' = c + 2^-k: not one
  for (int i = 0; i < 10; ++i) {
    Rational root_c(static_cast<long>(random() % 997) + 1, 1009);
    Real alg = square_root(root_c);
    auto lower_root_about_six = [](const Rational& c) {
      Rational c0 = 36 - c;   // (x - 6)^2 - c = x^2 - 12 x + 36 - c, times the denominator
      Polynomial p{c0.get_num(), mpz_class(-12) * c0.get_den(), c0.get_den()};
      return algebra::real_roots(p, Rational(0), Rational(6)).at(0);
    };
    Real mirror = lower_root_about_six(root_c);
    bool decided = false;
    EXPECT_EQ(compare_push_distances(straight, AxisPosition{0, alg}, alg.approximate(), AxisPosition{0, Real::from_rational(Rational(3))},
                                     3.0, AxisPosition{0, mirror}, mirror.approximate(), decided),
              0);
    EXPECT_TRUE(decided);
    int k = 1030 + static_cast<int>(random() % 200);   // beyond the 2^-1024 enclosures
    Real off = lower_root_about_six(root_c + Rational(mpz_class(1), mpz_class(1) << k));   // 6 - sqrt(c + 2^-k) < 6 - sqrt c
    // the way up 6 - sqrt(c') - 3 is shorter than the way down 3 - sqrt c: 2 b - a - c_end > 0
    EXPECT_EQ(compare_push_distances(straight, AxisPosition{0, alg}, alg.approximate(), AxisPosition{0, Real::from_rational(Rational(3))},
                                     3.0, AxisPosition{0, off}, off.approximate(), decided),
              1);
    EXPECT_TRUE(decided);
  }
  // a rotation: b at 0, c at 2 atan(sqrt c), a at -2 atan(t_a) with the rational t_a 2^-k from
  // sqrt c on either side: the way down longer or shorter by about 2^-k
  AxisLine line = test_axes::full_turn();
  for (int i = 0; i < 40; ++i) {
    Rational root_c(static_cast<long>(random() % 997) + 1, 1009);
    Real alg = square_root(root_c);   // t_c = sqrt(c): angle 2 atan(sqrt c) in (0, pi/2)
    int k = 55 + static_cast<int>(random() % 200);
    Oracle half;
    mpfr_set_q(half.v, root_c.get_mpq_t(), MPFR_RNDN);
    mpfr_sqrt(half.v, half.v, MPFR_RNDN);
    for (bool longer : {true, false}) {
      Rational ta = -grid_neighbour(half, k, !longer);   // longer: |t_a| > sqrt c, the way down longer
      AxisPosition a{0, Real::from_rational(ta)}, b{0, Real::from_rational(Rational(0))}, c{0, alg};
      bool decided = false;
      int sign = compare_push_distances(line, a, coordinate(line, a), b, 0.0, c, coordinate(line, c), decided);
      EXPECT_TRUE(decided);
      EXPECT_EQ(sign, longer ? 1 : -1) << "k " << k;
    }
  }
}

// Session 50 (exact50): ties of irrational middles, decided by Liouville's bound past the 2^-1024
// enclosures (base50 counted them undecided and returned 0). A translation: a = r rational,
// b = sqrt q, c = 2 sqrt q - r (the root of (x + r)^2 - 4 q) a tie, c -+ 2^-k (k 1030 ... 1229)
// not one. A rotation: t_a = r, t_b = sqrt q, t_c = x + y sqrt q with atan t_c = 2 atan t_b -
// atan t_a (tan's addition formula), so 2 theta_b = theta_a + theta_c, the three on piece 0 of
// the cyclic axis and the same whole turns; t_a = r +- 2^-k near ties (the way down shorter when
// t_a is above r).
// The root of den^2 ((x - s)^2 - w) (s, w rational) nearest `near`.
Real shifted_root(const Rational& s, const Rational& w, double near) {
  Rational c0 = s * s - w, c1 = -2 * s;
  mpz_class den = lcm(c0.get_den(), c1.get_den());
  Polynomial p{c0.get_num() * (den / c0.get_den()), c1.get_num() * (den / c1.get_den()), den};
  for (const Real& root : algebra::real_roots(p))
    if (std::abs(root.approximate() - near) < 1e-6) return root;
  ADD_FAILURE() << "no root near " << near;
  return Real::from_rational(Rational(0));
}

TEST(KinematicsExactRest, PushTiesOfIrrationalMiddles) {
  std::mt19937_64 random(505050);
  AxisLine straight = translation_line();
  auto rational_at = [](const Rational& v) { return AxisPosition{0, Real::from_rational(v)}; };
  for (int i = 0; i < 10; ++i) {
    Rational q(static_cast<long>(random() % 997) + 1, 1009), r(static_cast<long>(random() % 2001) - 1000, 1013);
    Real b = square_root(q);
    const double sqrt_q = std::sqrt(q.get_d());
    Real tie = shifted_root(-r, 4 * q, 2 * sqrt_q - r.get_d());
    bool decided = false;
    EXPECT_EQ(compare_push_distances(straight, rational_at(r), r.get_d(), AxisPosition{0, b}, sqrt_q, AxisPosition{0, tie},
                                     tie.approximate(), decided),
              0);
    EXPECT_TRUE(decided);
    int k = 1030 + static_cast<int>(random() % 200);
    Rational tiny(mpz_class(1), mpz_class(1) << k);
    for (int side : {1, -1}) {
      // c = 2 sqrt q - r + side 2^-k: the way up longer (side > 0), 2 b - a - c = -side 2^-k
      Real off = shifted_root(-r + side * tiny, 4 * q, 2 * sqrt_q - r.get_d());
      EXPECT_EQ(compare_push_distances(straight, rational_at(r), r.get_d(), AxisPosition{0, b}, sqrt_q,
                                       AxisPosition{0, off}, off.approximate(), decided),
                -side)
          << "k " << k;
      EXPECT_TRUE(decided);
    }
  }
  AxisLine line = test_axes::full_turn();
  for (int i = 0; i < 10; ++i) {
    Rational q(static_cast<long>(random() % 97) + 3, 1009);   // sqrt q < 0.32, not a square
    const double sqrt_q = std::sqrt(q.get_d());
    Rational r(static_cast<long>(std::floor(sqrt_q * 900 * static_cast<double>(random() % 1000) / 1000)), 1000);   // 0 <= r < sqrt q
    // t_c = (2 sqrt q - r (1 - q)) / ((1 - q) + 2 r sqrt q) = x + y sqrt q
    Rational norm = (1 - q) * (1 - q) - 4 * r * r * q;
    Rational x = (-r * (1 - q) * (1 - q) - 4 * r * q) / norm, y = 2 * (1 - q) * (1 + r * r) / norm;
    const double tc_d = x.get_d() + y.get_d() * sqrt_q;
    Real tc = shifted_root(x, y * y * q, tc_d);
    long turns = static_cast<long>(random() % 5) - 2;
    auto unwrapped = [&](double t) { return 2 * pi_d * static_cast<double>(turns) + 2 * std::atan(t); };
    AxisPosition b{0, square_root(q)}, c{0, tc};
    bool decided = false;
    EXPECT_EQ(compare_push_distances(line, rational_at(r), unwrapped(r.get_d()), b, unwrapped(sqrt_q), c, unwrapped(tc_d),
                                     decided),
              0)
        << "q " << q << " r " << r;
    EXPECT_TRUE(decided);
    int k = 1030 + static_cast<int>(random() % 200);
    for (int side : {1, -1}) {
      Rational ta = r + side * Rational(mpz_class(1), mpz_class(1) << k);
      EXPECT_EQ(compare_push_distances(line, rational_at(ta), unwrapped(r.get_d()), b, unwrapped(sqrt_q), c,
                                       unwrapped(tc_d), decided),
                -side)
          << "k " << k;
      EXPECT_TRUE(decided);
    }
  }
}

}  // namespace
}  // namespace hipair::kinematics_detail
