// Rounding to small coefficients (issue 14, item 3): every value that cannot be exact becomes
// the simplest rational within the model's rounding bound. Checked exactly (mpq comparisons):
// the chosen rational lies in the interval, and no rational with a smaller denominator does —
// by brute force on small intervals, and by the Stern–Brocot parents of the result (every
// rational strictly between a/b and c/d, the Farey parents of p/q, has denominator >= q) on
// generated and extreme values.
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/rational.hpp>

#include "model/exact_trig.hpp"
#include "model/expression.hpp"
#include "test_seed.hpp"
#include "random_rationals.hpp"

#include <gtest/gtest.h>

#include <mpfi.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <vector>

namespace {

using hipair::Rational;
using hipair::model_detail::simplest_rational_between;

using hipair::test_numbers::power_of_ten;

// |unit - (cos a, sin a)| <= bound for a = phase + multiple pi, certified with 256-bit MPFI.
bool within_of_angle(const hipair::Point& unit, const Rational& phase, const Rational& multiple, const Rational& bound) {
  mpfi_t angle, pi, c, s, dx, dy;
  for (mpfi_ptr v : {angle, pi, c, s, dx, dy}) mpfi_init2(v, 256);
  mpfi_const_pi(pi);
  mpfi_mul_q(angle, pi, multiple.get_mpq_t());
  mpfi_add_q(angle, angle, phase.get_mpq_t());
  mpfi_cos(c, angle);
  mpfi_sin(s, angle);
  mpfi_q_sub(dx, unit.x.get_mpq_t(), c);
  mpfi_q_sub(dy, unit.y.get_mpq_t(), s);
  mpfi_sqr(dx, dx);
  mpfi_sqr(dy, dy);
  mpfi_add(dx, dx, dy);
  mpfr_t upper;
  mpfr_init2(upper, 256);
  mpfi_get_right(upper, dx);
  const Rational bound2 = bound * bound;
  const bool within = mpfr_cmp_q(upper, bound2.get_mpq_t()) <= 0;
  mpfr_clear(upper);
  for (mpfi_ptr v : {angle, pi, c, s, dx, dy}) mpfi_clear(v);
  return within;
}

// The Farey parents of r = p/q (q > 0) in the Stern–Brocot tree: left < r < right, with
// every rational strictly between them having denominator >= q. For an integer r the parents
// are r - 1 and r + 1 (then "denominator < 1" is empty and the claim is about |numerator|).
std::pair<Rational, Rational> farey_parents(const Rational& r) {
  mpz_class p = r.get_num(), q = r.get_den();
  if (q == 1) return {Rational(p - 1), Rational(p + 1)};
  // Left parent a/b: p b - a q = 1, 0 < b < q (b = p^-1 mod q).
  mpz_class b;
  mpz_invert(b.get_mpz_t(), p.get_mpz_t(), q.get_mpz_t());
  mpz_class a = (p * b - 1) / q;
  Rational left(a, b), right(p - a, q - b);
  left.canonicalize();
  right.canonicalize();
  return {left, right};
}

// True when no rational with a denominator smaller than r's (or, among integers, a smaller
// magnitude) lies in [lo, hi], given lo <= r <= hi: the interval lies strictly inside the
// Farey parents' span, or contains 0 only when r = 0.
bool certified_simplest(const Rational& r, const Rational& lo, const Rational& hi) {
  if (r == 0) return true;
  if (lo <= 0 && hi >= 0) return false;  // 0 is simpler
  auto [left, right] = farey_parents(r);
  if (r.get_den() == 1) return r > 0 ? lo > left : hi < right;
  return lo > left && hi < right;
}

TEST(SimplestRational, BruteForceOnSmallIntervals) {
  std::mt19937 random(20261127);
  std::uniform_int_distribution<int> numerator(-400, 400), denominator(1, 60);
  int checked = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    Rational a(numerator(random), denominator(random)), b(numerator(random), denominator(random));
    a.canonicalize();
    b.canonicalize();
    if (trial % 7 == 0) b = a;  // degenerate intervals
    Rational lo = a < b ? a : b, hi = a < b ? b : a;
    Rational r = simplest_rational_between(lo, hi);
    ASSERT_TRUE(lo <= r && r <= hi) << lo << " " << hi << " -> " << r;
    ASSERT_GT(r.get_den(), 0);
    // No rational with a smaller denominator lies in [lo, hi]: ceil(lo q) > floor(hi q).
    for (long q = 1; q < r.get_den().get_si(); ++q) {
      Rational lq = lo * q, hq = hi * q;
      mpz_class ceil_lo, floor_hi;
      mpz_cdiv_q(ceil_lo.get_mpz_t(), lq.get_num_mpz_t(), lq.get_den_mpz_t());
      mpz_fdiv_q(floor_hi.get_mpz_t(), hq.get_num_mpz_t(), hq.get_den_mpz_t());
      ASSERT_GT(ceil_lo, floor_hi) << "[" << lo << ", " << hi << "] holds a rational with denominator " << q
                                   << " but the result is " << r;
    }
    // Among the rationals of that denominator in the interval, the smallest magnitude.
    mpz_class q = r.get_den();
    Rational lq = lo * Rational(q), hq = hi * Rational(q);
    mpz_class ceil_lo, floor_hi;
    mpz_cdiv_q(ceil_lo.get_mpz_t(), lq.get_num_mpz_t(), lq.get_den_mpz_t());
    mpz_fdiv_q(floor_hi.get_mpz_t(), hq.get_num_mpz_t(), hq.get_den_mpz_t());
    for (mpz_class p = ceil_lo; p <= floor_hi; ++p) {
      Rational candidate(p, q);
      candidate.canonicalize();
      if (candidate.get_den() == q) ASSERT_GE(abs(candidate), abs(r));
    }
    ASSERT_TRUE(certified_simplest(r, lo, hi)) << lo << " " << hi << " -> " << r;  // the certificate agrees
    ++checked;
  }
  EXPECT_EQ(checked, 4000);
}

// The descent on rationals, step by step (each end a canonical quotient), as it was before
// session 59 gave simplest_rational_between the ends as unreduced integer pairs: the reference
// the integer descent must equal bit for bit (the model's roundings, hence every output, depend
// on it).
Rational simplest_by_rationals(const Rational& lo_in, const Rational& hi_in) {
  Rational lo = lo_in, hi = hi_in;
  lo.canonicalize();
  hi.canonicalize();
  if (lo <= 0 && hi >= 0) return Rational(0);
  if (hi < 0) return Rational(-simplest_by_rationals(Rational(-hi), Rational(-lo)));
  Rational a = lo, b = hi;
  mpz_class p0 = 1, p1 = 0, q0 = 0, q1 = 1;
  for (;;) {
    mpz_class floor_a;
    mpz_fdiv_q(floor_a.get_mpz_t(), a.get_num_mpz_t(), a.get_den_mpz_t());
    std::optional<mpz_class> value;
    if (Rational(floor_a) == a)
      value = floor_a;
    else if (Rational(floor_a + 1) <= b)
      value = floor_a + 1;
    if (value) {
      Rational result(p0 * *value + p1, q0 * *value + q1);
      result.canonicalize();
      return result;
    }
    mpz_class np0 = p0 * floor_a + p1, nq0 = q0 * floor_a + q1;
    p1 = p0;
    q1 = q0;
    p0 = np0;
    q0 = nq0;
    Rational new_a = 1 / (b - floor_a), new_b = 1 / (a - floor_a);
    a = new_a;
    b = new_b;
  }
}

TEST(SimplestRational, IntegerDescentEqualsTheRationalDescent) {
  // Random ends from 2^-300 to 2^300 in magnitude, with 1 to 300-bit numerators and
  // denominators, not reduced (a common factor in half of them), both signs, windows from
  // equal ends to wide ones, and the half-angle tangent windows the model reader forms (256-bit
  // ends shrunk by 2^-240 around tan of a random angle's half, at bounds 1e-3 to 1e-30).
  std::mt19937_64 random(20261205);
  gmp_randclass bits(gmp_randinit_default);
  bits.seed(20261205);
  auto integer = [&](int max_bits) {
    mpz_class z = bits.get_z_bits(1 + static_cast<int>(random() % static_cast<unsigned>(max_bits)));
    return z == 0 ? mpz_class(1) : z;
  };
  int checked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int size = trial % 3 == 0 ? 16 : trial % 3 == 1 ? 64 : 300;
    mpz_class common = trial % 2 == 0 ? integer(40) : mpz_class(1);
    Rational a(integer(size) * common, integer(size) * common), width(integer(size), integer(size) * common);
    if (random() % 2) a = -a;
    if (trial % 5 == 0) width = 0;
    if (trial % 7 == 0) width = width * Rational(mpz_class(1), mpz_class(1) << 250);
    Rational a_reduced = a;   // a itself stays unreduced (callers pass mpq_class(n, d))
    a_reduced.canonicalize();
    width.canonicalize();
    Rational b = a_reduced + width;
    if (trial % 11 == 0) {   // b the integer just above a (both descents' integer test at its end)
      mpz_class floor_a;
      mpz_fdiv_q(floor_a.get_mpz_t(), a.get_num_mpz_t(), a.get_den_mpz_t());
      b = Rational(floor_a + 1);
    }
    ASSERT_EQ(simplest_rational_between(a, b), simplest_by_rationals(a, b)) << a << " " << b;
    ++checked;
  }
  std::uniform_real_distribution<double> angle(-1.5, 1.5);
  for (int trial = 0; trial < 200; ++trial) {
    const Rational t(std::tan(angle(random) / 2));
    const Rational bound = power_of_ten(-3 - trial % 28);
    const Rational shrink(mpz_class(1), mpz_class(1) << 240);
    const Rational lo = t - bound / 3 + shrink, hi = t + bound / 3 - shrink;
    ASSERT_EQ(simplest_rational_between(lo, hi), simplest_by_rationals(lo, hi)) << lo << " " << hi;
    ++checked;
  }
  EXPECT_EQ(checked, 3200);
}

TEST(SimplestRational, ExtremeMagnitudes) {
  // Around 1e-300 and 1e400, given as text, with widths from 1e-320 to 1e390.
  for (const char* centre_text : {"1e-300", "3.25e-300", "1e400", "-7.123456789e400", "1e-12", "0.999999999999"}) {
    Rational centre = hipair::parse_rational(centre_text);
    for (int width_exponent : {-320, -310, -301, -200, -12, 0, 390}) {
      Rational half_width = power_of_ten(width_exponent);
      Rational lo = centre - half_width, hi = centre + half_width;
      Rational r = simplest_rational_between(lo, hi);
      ASSERT_TRUE(lo <= r && r <= hi) << centre_text << " 1e" << width_exponent;
      ASSERT_TRUE(certified_simplest(r, lo, hi)) << centre_text << " 1e" << width_exponent << " -> " << r;
      // One-sided windows (the interval away from zero).
      Rational above = simplest_rational_between(abs(centre), abs(centre) + half_width);
      ASSERT_TRUE(abs(centre) <= above && above <= abs(centre) + half_width);
      ASSERT_TRUE(certified_simplest(above, abs(centre), abs(centre) + half_width));
    }
  }
  // Narrow window at 1e-300: the result is 1/q with q the smallest integer in
  // [1e300 / 1.000001, 1e300], exact.
  Rational tiny = hipair::parse_rational("1e-300");
  Rational r = simplest_rational_between(tiny, tiny * Rational(1000001, 1000000));
  Rational smallest_q = Rational(1) / (tiny * Rational(1000001, 1000000));
  mpz_class q;
  mpz_cdiv_q(q.get_mpz_t(), smallest_q.get_num_mpz_t(), smallest_q.get_den_mpz_t());
  EXPECT_EQ(r, Rational(mpz_class(1), q));
}

// The enclosure of sqrt(n) at 256 bits, as rationals.
struct Enclosure {
  Rational lower, upper;
};

// Exact check of |sqrt(n) - v| <= bound: (v - bound)^2 <= n <= (v + bound)^2 with v - bound >= 0.
bool within_sqrt(const Rational& v, long n, const Rational& bound) {
  Rational below = v - bound, above = v + bound;
  return below >= 0 && below * below <= n && above * above >= n;
}

TEST(ModelRounding, GeneratedSquareRootsAreTheSimplestWithinTheBound) {
  using namespace hipair::model_detail;
  int checked = 0;
  for (int exponent : {12, 9, 6, 4}) {
    Rational bound = power_of_ten(-exponent);
    RoundingBoundScope scope(bound);
    std::vector<std::size_t> sizes;
    for (long n = 2; n < 400; ++n) {
      if (n == static_cast<long>(std::sqrt(static_cast<double>(n))) * static_cast<long>(std::sqrt(static_cast<double>(n))))
        continue;
      std::string text = "sqrt(" + std::to_string(n) + ")";
      ExpressionContext context;
      context.pointer = "/test";
      Quantity q = evaluate_expression(text, context);
      ASSERT_FALSE(q.is_rational());
      std::vector<hipair::Rounding> roundings;
      Rational v = to_rational(q, "/test", text, roundings);
      ASSERT_EQ(roundings.size(), 1u);
      EXPECT_EQ(roundings[0].value, v);
      EXPECT_EQ(roundings[0].bound, bound);
      ASSERT_TRUE(within_sqrt(v, n, bound)) << text << " -> " << v;
      // No simpler rational within the bound of sqrt(n): both Farey parents lie outside
      // [sqrt(n) - bound, sqrt(n) + bound], decided exactly by squaring.
      auto [left, right] = farey_parents(v);
      Rational left_shift = left + bound, right_shift = right - bound;
      EXPECT_TRUE(left_shift < 0 || left_shift * left_shift < n) << text << " 1e-" << exponent;
      EXPECT_TRUE(right_shift > 0 && right_shift * right_shift > n) << text << " 1e-" << exponent;
      sizes.push_back(mpz_sizeinbase(v.get_den_mpz_t(), 2));
      ++checked;
    }
    // Typically the denominator is near 1/sqrt(bound) (the grid's is 1/bound): the median size
    // over the generated values (a guarantee holds only for the simplest property above).
    std::sort(sizes.begin(), sizes.end());
    EXPECT_LE(sizes[sizes.size() / 2], static_cast<std::size_t>(exponent * 3.33 / 2 + 4)) << "1e-" << exponent;
  }
  EXPECT_GT(checked, 1400);
}

TEST(ModelRounding, HalfAngleTangentsTurnByAtMostTheBound) {
  using namespace hipair::model_detail;
  for (int exponent : {12, 9, 6}) {
    Rational bound = power_of_ten(-exponent);
    RoundingBoundScope scope(bound);
    for (int k = 1; k <= 58; ++k) {
      Rational angle(k, 37);  // rational angles in (0, pi/2) (58/37 < pi/2 < 59/37): irrational tangents
      angle.canonicalize();
      std::vector<hipair::Rounding> roundings;
      hipair::Point unit = exact_unit_vector(angle, "/test", "angle", roundings);
      ASSERT_EQ(roundings.size(), 1u);
      EXPECT_EQ(roundings[0].bound, bound);
      EXPECT_EQ(unit.x * unit.x + unit.y * unit.y, Rational(1));  // exactly on the unit circle
      // |2 atan(t) - angle| <= bound, certified with 256-bit interval arithmetic.
      mpfi_t t, turned;
      mpfi_init2(t, 256);
      mpfi_init2(turned, 256);
      mpfi_set_q(t, roundings[0].value.get_mpq_t());
      mpfi_atan(turned, t);
      mpfi_mul_ui(turned, turned, 2);
      mpfi_sub_q(turned, turned, angle.get_mpq_t());
      mpfr_t magnitude;
      mpfr_init2(magnitude, 256);
      mpfi_mag(magnitude, turned);
      EXPECT_LE(mpfr_cmp_q(magnitude, bound.get_mpq_t()), 0) << "angle " << angle << " 1e-" << exponent;
      mpfr_clear(magnitude);
      mpfi_clear(t);
      mpfi_clear(turned);
    }
  }
}

// An angle rounded first (a template's phase of 90 degrees becomes a rational near pi/2) and
// then turned into a direction: the half-angle tangent's window is the whole angle window
// [a' - b, a' + b], so the exact quarter turn stays reachable and is the simplest (t = +-1, 0).
TEST(ModelRounding, QuarterTurnsStayExactAfterTheAngleIsRounded) {
  using namespace hipair::model_detail;
  for (int exponent : {12, 9, 6}) {
    RoundingBoundScope scope(power_of_ten(-exponent));
    for (const char* text : {"pi/2", "-pi/2", "3*pi/2", "pi", "5*pi/2", "pi/2 + 0"}) {
      ExpressionContext context;
      context.pointer = "/test";
      std::vector<hipair::Rounding> roundings;
      Rational angle = to_rational(evaluate_expression(text, context), "/test", text, roundings);
      hipair::Point unit = exact_unit_vector(angle, "/test", text, roundings);
      EXPECT_EQ(abs(unit.x) + abs(unit.y), Rational(1)) << text << " 1e-" << exponent << ": " << unit.x << ", " << unit.y;
    }
  }
}

const char* model_with_rounding(const std::string& rounding_entry) {
  static std::string text;
  text = R"json({ "hipair": 1, "name": "r", )json" + rounding_entry + R"json(
    "parts": [
      { "name": "frame", "motion": "fixed", "loops": [ { "start": [0, 0], "edges": [
          { "line_to": [10, 0] }, { "line_to": [10, "sqrt(2)"] }, { "line_to": [0, 10] }, { "line_to": [0, 0] } ] } ] },
      { "name": "arm", "motion": { "rotation": { "pivot": [30, 0] } }, "loops": [ { "start": [20, 0], "edges": [
          { "line_to": [26, 0] }, { "line_to": [26, "sqrt(3)"] }, { "line_to": [20, 4] }, { "line_to": [20, 0] } ] } ] } ] })json";
  return text.c_str();
}

TEST(ModelRounding, BoundFromTheModelAndFromTheCommandLine) {
  hipair::Model plain = hipair::read_model(model_with_rounding(""));
  ASSERT_EQ(plain.roundings.size(), 2u);
  for (const hipair::Rounding& r : plain.roundings) EXPECT_EQ(r.bound, Rational(1, 1000000000000L));
  EXPECT_TRUE(within_sqrt(plain.roundings[0].value, 2, Rational(1, 1000000000000L)));

  hipair::Model coarse = hipair::read_model(model_with_rounding(R"("rounding": 1e-6,)"));
  ASSERT_EQ(coarse.roundings.size(), 2u);
  EXPECT_EQ(coarse.roundings[0].bound, Rational(1, 1000000));
  EXPECT_TRUE(within_sqrt(coarse.roundings[0].value, 2, Rational(1, 1000000)));
  EXPECT_EQ(coarse.roundings[0].value, Rational(1393, 985));  // a convergent of sqrt(2)
  EXPECT_TRUE(within_sqrt(coarse.roundings[1].value, 3, Rational(1, 1000000)));

  {
    // --rounding: overrides the model's key while it is in force
    hipair::model_detail::RoundingBoundScope command_line(Rational(1, 1000000000), true);
    hipair::Model overridden = hipair::read_model(model_with_rounding(R"("rounding": 1e-6,)"));
    EXPECT_EQ(overridden.roundings[0].bound, Rational(1, 1000000000));
    EXPECT_TRUE(within_sqrt(overridden.roundings[0].value, 2, Rational(1, 1000000000)));
    EXPECT_FALSE(within_sqrt(overridden.roundings[0].value, 2, Rational(mpz_class(1), mpz_class("10000000000"))));
  }
  {
    // an inner non-overriding scope (a library user's) does not change what a file asks for
    hipair::model_detail::RoundingBoundScope other(Rational(1, 1000));
    EXPECT_EQ(hipair::read_model(model_with_rounding("")).roundings[0].bound, Rational(1, 1000000000000L));
  }
  EXPECT_EQ(hipair::model_detail::rounding_bound(), hipair::model_detail::default_rounding_bound());
}

TEST(ModelRounding, BadBoundsNameTheKey) {
  for (const char* entry : {R"("rounding": "1e-9",)", R"("rounding": 0,)", R"("rounding": -1e-9,)",
                            R"("rounding": 0.01,)", R"("rounding": 1e-31,)", R"("rounding": [1],)"}) {
    try {
      hipair::read_model(model_with_rounding(entry));
      ADD_FAILURE() << entry << " was accepted";
    } catch (const hipair::ModelError& error) {
      EXPECT_EQ(error.pointer(), "/rounding") << entry;
    }
  }
  hipair::model_detail::RoundingBoundScope command_line(Rational(1, 10), true);
  EXPECT_THROW(hipair::read_model(model_with_rounding("")), hipair::ModelError);
}

}  // namespace

// A template's direction phase + pi k / z (gear and ratchet teeth, Geneva slots, escapement
// teeth, the gear flank normal) is ONE rounding of the whole angle: exactly on the unit circle,
// within the bound of the exact angle (certified with 256-bit intervals: the chord to the
// exact direction is at most the angle error), one rounding recorded, and coordinates of one
// rounded tangent's size, where rotating a rounded u(pi k / z) by a rounded u(phase) made two
// roundings (2b) with the denominators multiplied.
TEST(ModelRounding, PhasePlusPiMultipleIsOneRoundingWithinTheBound) {
  using namespace hipair::model_detail;
  std::mt19937 random(20261128);
  for (int exponent : {12, 9, 6}) {
    Rational bound = power_of_ten(-exponent);
    RoundingBoundScope scope(bound);
    std::vector<std::size_t> one_bits, product_bits;
    for (int trial = 0; trial < 150; ++trial) {
      Rational phase(static_cast<long>(random() % 4001) - 2000, 577);  // (-3.5, 3.5) rad
      phase.canonicalize();
      long teeth = 3 + static_cast<long>(random() % 60);
      Rational multiple(static_cast<long>(random() % static_cast<unsigned>(2 * teeth)), teeth);
      multiple.canonicalize();
      std::vector<hipair::Rounding> roundings;
      hipair::Point unit = exact_unit_vector_sum(phase, multiple, "/test", "direction", roundings);
      EXPECT_EQ(unit.x * unit.x + unit.y * unit.y, Rational(1));
      if (phase == 0) continue;
      ASSERT_EQ(roundings.size(), 1u) << phase << " + pi " << multiple;
      EXPECT_EQ(roundings[0].bound, bound);
      EXPECT_TRUE(within_of_angle(unit, phase, multiple, bound)) << phase << " + pi " << multiple << " 1e-" << exponent;
      // the former two-rounding product, for the size comparison
      std::vector<hipair::Rounding> former;
      hipair::Point turn = exact_unit_vector_pi(multiple, "/test", "turn", former);
      hipair::Point base = exact_unit_vector(phase, "/test", "phase", former);
      Rational product_x = turn.x * base.x - turn.y * base.y;
      one_bits.push_back(mpz_sizeinbase(unit.x.get_den_mpz_t(), 2));
      product_bits.push_back(mpz_sizeinbase(product_x.get_den_mpz_t(), 2));
    }
    ASSERT_GT(one_bits.size(), 100u);
    std::sort(one_bits.begin(), one_bits.end());
    std::sort(product_bits.begin(), product_bits.end());
    // one rounded tangent p/q gives denominators q^2 + p^2, about log2(1/b) bits; the product
    // about twice that (when the turn is not exact)
    double expected = std::log2(std::pow(10.0, exponent));
    EXPECT_LE(static_cast<double>(one_bits[one_bits.size() / 2]), expected + 4) << "1e-" << exponent;
    EXPECT_GE(static_cast<double>(product_bits[product_bits.size() / 2]), 1.6 * expected) << "1e-" << exponent;
  }
}

// The exact quarter turns survive the one rounding: a phase rounded near pi/2 plus a multiple
// of pi/2 is still an axis direction.
TEST(ModelRounding, PhasePlusPiMultipleKeepsQuarterTurnsExact) {
  using namespace hipair::model_detail;
  for (int exponent : {12, 9, 6}) {
    RoundingBoundScope scope(power_of_ten(-exponent));
    ExpressionContext context;
    context.pointer = "/test";
    std::vector<hipair::Rounding> roundings;
    Rational quarter = to_rational(evaluate_expression("pi/2", context), "/test", "pi/2", roundings);
    for (int twice = -4; twice <= 4; ++twice) {
      hipair::Point unit = exact_unit_vector_sum(quarter, Rational(twice, 2), "/test", "axis", roundings);
      EXPECT_EQ(abs(unit.x) + abs(unit.y), Rational(1)) << twice << " 1e-" << exponent;
    }
  }
}

// Values far from 1 mm (session 19; session 54). A value outside [2^-20, 2^40] (in its unit) is
// rounded at its decimal scale: in units U = 10^E, E the multiple of 10 that brings it within
// [1e-4, 1e6), the simplest rational within b of v / U, times U (bound b U). So a value written
// at 10^(10 j) times an ordinary one is exactly 10^(10 j) times the rational the ordinary one
// gets at 1 mm (a model scaled so reads as that model scaled), and a model drawn at 10^-300 mm
// keeps its shape and the small rationals it has at 1 mm. Oracle: the ordinary value's own
// rounding (the absolute bound b) and the exact value, decided by squaring.
TEST(ModelRounding, TinyValuesAreRoundedAtTheirDecimalScaleAsTheOrdinaryValueIs) {
  using namespace hipair::model_detail;
  const Rational bound = power_of_ten(-12);
  RoundingBoundScope scope(bound);
  auto rounded = [](const std::string& text, Rational& used_bound) {
    ExpressionContext context;
    context.pointer = "/test";
    Quantity q = evaluate_expression(text, context);
    std::vector<hipair::Rounding> roundings;
    Rational v = to_rational(q, "/test", text, roundings);
    EXPECT_EQ(roundings.size(), 1u) << text;
    used_bound = roundings.empty() ? Rational(0) : roundings[0].bound;
    return v;
  };
  int checked = 0;
  for (long n = 2; n < 160; ++n) {
    long root = static_cast<long>(std::sqrt(static_cast<double>(n)));
    if (root * root == n) continue;
    for (int shift : {0, 1, 3, 5}) {   // sqrt(n) 10^shift: ordinary values 1.4 .. 1.3e6
      Rational ordinary_bound;
      const std::string ordinary_text = "sqrt(" + std::to_string(n) + ")*1e" + std::to_string(shift);
      const Rational ordinary = rounded(ordinary_text, ordinary_bound);
      if (ordinary > 1000000) continue;   // beyond [1e-4, 1e6): another decimal unit
      ASSERT_EQ(ordinary_bound, bound) << ordinary_text;
      for (int k : {-300, -250, -120, -40, -30, -20}) {   // below 2^-20: at the decimal scale
        const std::string text = ordinary_text + "*1e" + std::to_string(k);
        Rational b;
        const Rational v = rounded(text, b);
        const Rational scale = power_of_ten(k), unit = power_of_ten(k + shift);
        EXPECT_EQ(b, Rational(bound * scale)) << text;
        // |v - sqrt(n) 10^(k + shift)| <= b, decided exactly by squaring in units of 10^(k + shift).
        ASSERT_TRUE(within_sqrt(Rational(v / unit), n, Rational(b / unit))) << text << " -> " << v;
        EXPECT_EQ(Rational(v / scale), ordinary) << text << ": not 10^" << k << " times the value at 1 mm";
        // Small: the digits' denominator is that of a rounding within 1e-12 at 1 mm.
        EXPECT_LE(mpz_sizeinbase(Rational(v / unit).get_den_mpz_t(), 2), static_cast<std::size_t>(64)) << text;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 2000);
}

// A large value (above 2^40 in its unit) is rounded at its decimal scale too (session 54; until
// then within the absolute bound b, which pi 10^100 needed 512 bits for and pi 10^400 2048): pi
// 10^k is 10^k times the rational pi gets at 1 mm, at the 256-bit precision.
TEST(ModelRounding, LargeValuesAreRoundedAtTheirDecimalScaleAsTheOrdinaryValueIs) {
  using namespace hipair::model_detail;
  const Rational bound = power_of_ten(-12);
  Rational pi_at_1mm;
  {
    RoundingBoundScope scope(bound);
    ExpressionContext context;
    context.pointer = "/test";
    std::vector<hipair::Rounding> roundings;
    pi_at_1mm = to_rational(evaluate_expression("pi", context), "/test", "pi", roundings);
    Quantity q = evaluate_expression("pi*1e100", context);
    roundings.clear();
    EXPECT_EQ(to_rational(q, "/test", "pi*1e100", roundings), Rational(pi_at_1mm * power_of_ten(100)));
    ASSERT_EQ(roundings.size(), 1u);
    EXPECT_EQ(roundings[0].bound, Rational(bound * power_of_ten(100)));
  }
  // A model with such values reads, and each lies within its bound (b 10^k) of the exact value,
  // checked against an 8192-bit enclosure, and is 10^k times pi's rational at 1 mm.
  for (int k : {30, 100, 250, 400}) {
    std::string radius = "pi*1e" + std::to_string(k);
    std::string text = R"({"hipair": 1, "name": "big", "units": {"length": "mm", "angle": "rad"},
      "parts": [{"name": "a", "motion": "fixed", "loops": [{"circle": {"center": [0, 0], "radius": ")" +
                       radius + R"("}}]}]})";
    hipair::Model model = hipair::read_model(text, "big");
    ASSERT_EQ(model.roundings.size(), 1u) << radius;
    const hipair::Rounding& rounding = model.roundings[0];
    EXPECT_EQ(rounding.bound, Rational(bound * power_of_ten(k))) << radius;
    EXPECT_EQ(rounding.value, Rational(pi_at_1mm * power_of_ten(k))) << radius;
    const Rational& used = rounding.bound;
    mpfi_t exact;
    mpfi_init2(exact, 8192);
    mpfi_const_pi(exact);
    mpfi_mul_q(exact, exact, power_of_ten(k).get_mpq_t());
    mpfr_t end;
    mpfr_init2(end, 8192);
    Rational lower, upper;
    mpfi_get_left(end, exact);
    mpfr_get_q(lower.get_mpq_t(), end);
    mpfi_get_right(end, exact);
    mpfr_get_q(upper.get_mpq_t(), end);
    mpfr_clear(end);
    mpfi_clear(exact);
    EXPECT_LE(Rational(rounding.value - used), lower) << radius;
    EXPECT_GE(Rational(rounding.value + used), upper) << radius;
    // The circle's radius is the rounded value.
    const hipair::Edge& edge = model.parts[0].loops[0].edges[0];
    EXPECT_EQ(edge.radius_squared, Rational(rounding.value * rounding.value)) << radius;
  }
}

// Session 67 (issue 14): an angle r + p pi is reduced by its whole half turns n (p = n + f,
// f in (-1/2, 1/2]) before its one rounding, and its direction negated for odd n: two angles a
// half turn apart get exactly negated directions (a wheel's features k pi/2 + pi +- s/2 and
// (k + 2) pi/2 + pi +- s/2 keep the part's half-turn symmetry), each within the bounds of its
// roundings of the exact direction. (Before session 67 each whole angle was rounded on its own:
// the negation failed for most of these angles.)
TEST(ModelRounding, AnglesAHalfTurnApartGetExactlyNegatedDirections) {
  using namespace hipair::model_detail;
  std::mt19937 random(static_cast<std::mt19937::result_type>(hipair::test::test_seed(20261206)));
  for (int exponent : {12, 9}) {
    Rational bound = power_of_ten(-exponent);
    RoundingBoundScope scope(bound);
    for (int trial = 0; trial < 120; ++trial) {
      Rational r(static_cast<long>(random() % 4001) - 2000, 577);  // (-3.5, 3.5) rad
      r.canonicalize();
      const long q = std::vector<long>{1, 2, 3, 4, 6, 12}[random() % 6];
      Rational p(static_cast<long>(random() % static_cast<unsigned>(6 * q + 1)) - 3 * q, q);  // [-3, 3]
      p.canonicalize();
      if (r == 0) continue;
      hipair::Point units[2];
      for (int side = 0; side < 2; ++side) {
        Quantity angle = Quantity::of(r, true);
        angle.pi_multiple = side == 0 ? p : Rational(p + 1);
        angle.pi_multiple.canonicalize();
        std::vector<hipair::Rounding> roundings;
        const hipair::Point unit = unit_vector(angle, "/test", "angle", roundings);
        units[side] = unit;
        EXPECT_EQ(unit.x * unit.x + unit.y * unit.y, Rational(1));
        ASSERT_LE(roundings.size(), 2u);
        Rational total(0);
        for (const hipair::Rounding& rounding : roundings) total += rounding.bound;
        // |u - (cos a, sin a)| <= |a_used - a| <= the sum of the recorded bounds
        EXPECT_TRUE(within_of_angle(unit, r, angle.pi_multiple, total)) << r << " + pi " << angle.pi_multiple << " 1e-" << exponent;
      }
      EXPECT_EQ(units[1].x, Rational(-units[0].x)) << r << " + pi " << p << " and + pi " << Rational(p + 1);
      EXPECT_EQ(units[1].y, Rational(-units[0].y)) << r << " + pi " << p << " and + pi " << Rational(p + 1);
    }
  }
}

// Directions asked again (session 70, growth70: exact_trig.cpp keeps the directions a thread has
// made, since a model repeats its angles). A pool of angles — rational angles (exact_unit_vector),
// rational multiples of pi (exact_unit_vector_pi) and phase + multiple (exact_unit_vector_sum),
// some given as non-canonical rationals — asked many times in a random order under random
// rounding bounds (RoundingBoundScope, nested as a command line's --rounding over a model's):
// every answer is a direction of ITS bound (exactly on the unit circle, within the bound of the
// exact angle, certified with 256-bit MPFI), its one Rounding record names THIS call's pointer and
// text, holds the half-angle tangent t of the direction (unit = +-((1 - t^2), 2t) / (1 + t^2)) and
// the bound in force, and the same angle under the same bound always gives the same direction and
// tangent. A memo keyed without the bound, or replaying the first caller's record, fails it. (It
// cannot fail on the base: there every call computes afresh.)
TEST(ModelRounding, RepeatedAnglesGetTheDirectionOfTheirOwnBoundAndRecord) {
  using namespace hipair::model_detail;
  std::mt19937_64 random(hipair::test::test_seed(20261206));
  struct Angle {
    int kind;   // 0: rational angle, 1: multiple of pi, 2: phase + multiple of pi
    Rational phase, multiple;
  };
  std::vector<Angle> pool;
  for (int i = 0; i < 48; ++i) {
    const int kind = i % 3;
    Rational phase, multiple;
    if (kind != 1) {
      // away from 0 and +-pi/2 (a phase with an exact direction takes the two-rounding path)
      phase = hipair::test_numbers::random_rational(random, Rational(1, 50), Rational(7, 5));
      if (random() % 2) phase = -phase;
      if (kind == 0 && random() % 2) phase += 2;   // beyond pi/2: reduced by a half turn
    }
    if (kind != 0) {
      const long teeth = 3 + static_cast<long>(random() % 60);
      multiple = Rational(static_cast<long>(random() % static_cast<unsigned long>(2 * teeth)) - teeth, teeth);
      multiple.canonicalize();
    }
    pool.push_back({kind, phase, multiple});
  }
  const std::vector<Rational> bounds{power_of_ten(-12), power_of_ten(-9), power_of_ten(-6), power_of_ten(-3)};
  std::map<std::tuple<std::size_t, std::size_t>, std::pair<hipair::Point, std::optional<Rational>>> first_answer;
  std::size_t repeats = 0;
  for (int call = 0; call < 600; ++call) {
    const std::size_t a = random() % pool.size(), b = random() % bounds.size();
    const Angle& angle = pool[a];
    std::optional<RoundingBoundScope> outer;
    if (random() % 3 == 0) outer.emplace(bounds[(b + 1) % bounds.size()]);   // overridden by the inner scope
    RoundingBoundScope scope(bounds[b], outer.has_value());
    // the same number written as a non-canonical quotient half the time
    auto written = [&](const Rational& q) {
      if (random() % 2) return q;
      return Rational(q.get_num() * 6, q.get_den() * 6);
    };
    const std::string pointer = "/call/" + std::to_string(call), text = "angle " + std::to_string(call);
    std::vector<hipair::Rounding> roundings;
    hipair::Point unit;
    if (angle.kind == 0) unit = exact_unit_vector(written(angle.phase), pointer, text, roundings);
    else if (angle.kind == 1) unit = exact_unit_vector_pi(written(angle.multiple), pointer, text, roundings);
    else unit = exact_unit_vector_sum(written(angle.phase), written(angle.multiple), pointer, text, roundings);
    const std::string where = "call " + std::to_string(call) + " kind " + std::to_string(angle.kind) + " phase " +
                              angle.phase.get_str() + " multiple " + angle.multiple.get_str() + " bound " +
                              bounds[b].get_str();
    EXPECT_EQ(unit.x * unit.x + unit.y * unit.y, Rational(1)) << where;
    EXPECT_TRUE(within_of_angle(unit, angle.phase, angle.multiple, bounds[b])) << where;
    const Rational twice = 2 * angle.multiple;
    const bool exact = angle.kind == 1 && twice.get_den() == 1;   // a multiple of pi/2
    std::optional<Rational> tangent;
    if (exact) {
      EXPECT_TRUE(roundings.empty()) << where;
      EXPECT_EQ(abs(unit.x) + abs(unit.y), Rational(1)) << where;
    } else {
      ASSERT_EQ(roundings.size(), 1u) << where;
      EXPECT_EQ(roundings[0].pointer, pointer) << where;
      EXPECT_NE(roundings[0].expression.find(text), std::string::npos) << where << ": " << roundings[0].expression;
      EXPECT_EQ(roundings[0].bound, bounds[b]) << where;
      tangent = roundings[0].value;
      const hipair::Point from_tangent = unit_from_half_tangent(*tangent);
      EXPECT_TRUE((from_tangent.x == unit.x && from_tangent.y == unit.y) ||
                  (from_tangent.x == -unit.x && from_tangent.y == -unit.y))
          << where << ": t " << *tangent;
    }
    auto [found, inserted] = first_answer.try_emplace({a, b}, unit, tangent);
    if (!inserted) {
      ++repeats;
      EXPECT_TRUE(found->second.first.x == unit.x && found->second.first.y == unit.y) << where;
      EXPECT_EQ(found->second.second, tangent) << where;
    }
  }
  EXPECT_GT(repeats, 300u);   // most calls ask again
}
