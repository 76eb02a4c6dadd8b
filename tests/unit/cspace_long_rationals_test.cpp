// Point queries and first crossings of C-spaces whose model numbers are long rationals (session
// 55, esc55; src/algebra/interval_shift.hpp). The escapement's anchor/banking pair with the banking
// pins moved by generated rationals of 50 ... 2000 digits (numerator and denominator): its curves'
// integer coefficients reach thousands of bits, beyond the doubles' range from about 290 digits
// on. Before the fix their double enclosures were [DBL_MAX, inf], every curve "possibly vanished"
// at every configuration, and CSpace::first_crossing answered "starts in contact (grazing)"
// everywhere (the simulator's jammed escapement). Every answer here is checked against the exact
// overlap predicate (part_overlap) at the exact configuration: a point path is free (status none)
// exactly where the parts are apart; a motion's crossing bracket [u_lower, u_upper] has the parts
// apart before u_lower and not apart at u_upper.
#include "algebra/interval_shift.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>

#include <gtest/gtest.h>
#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstddef>
#include <filesystem>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace hipair {
namespace {

// A random integer of exactly `digits` decimal digits.
mpz_class random_digits(std::mt19937_64& random, int digits) {
  std::string text(static_cast<std::size_t>(digits), '0');
  text[0] = static_cast<char>('1' + random() % 9);
  for (std::size_t i = 1; i < text.size(); ++i) text[i] = static_cast<char>('0' + random() % 10);
  return mpz_class(text);
}

// Every point of part `part`'s loops moved by (dx, 0).
void shift_part(Part& part, const Rational& dx) {
  for (Loop& loop : part.loops)
    for (Edge& edge : loop.edges)
      for (Point* p : {&edge.source, &edge.target, &edge.center}) p->x += dx;
}

struct Tally {
  std::size_t points = 0, free = 0, contact = 0, motions = 0, crossings = 0, huge_spaces = 0;
};

// The anchor turned to half-angle tangent t against the fixed banking pins: apart?
PartRelation relation_at(const Model& model, const Rational& t) {
  const Part& anchor = model.parts[*model.find_part("anchor")];
  const Part& banking = model.parts[*model.find_part("banking")];
  const Rational d = 1 + t * t;
  Placement turned = placement_about(anchor.motion.pivot, (1 - t * t) / d, 2 * t / d, Point{Rational(0), Rational(0)});
  return part_overlap(anchor, turned, banking, Placement{}).relation;
}

// tan(theta / 2) for a double theta, enclosed by rationals 2^-200 apart (MPFR, directed rounding)
std::pair<Rational, Rational> half_tangent_of(double theta) {
  mpfr_t half, t;
  mpfr_inits2(220, half, t, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_d(half, theta, MPFR_RNDN);   // exact
  mpfr_div_2ui(half, half, 1, MPFR_RNDN);
  Rational lo, hi;
  mpfr_tan(t, half, MPFR_RNDD);
  mpfr_get_q(lo.get_mpq_t(), t);
  mpfr_tan(t, half, MPFR_RNDU);
  mpfr_get_q(hi.get_mpq_t(), t);
  mpfr_clears(half, t, static_cast<mpfr_ptr>(nullptr));
  return {lo, hi};
}

MotionPath angle_path(double theta0, double theta1) {
  MotionPath path;
  path.x.kind = AxisPath::Kind::angle;
  path.x.coefficients = {Rational(theta0), Rational(theta1) - Rational(theta0)};
  return path;
}

MotionPath half_tangent_path(const Rational& t0, const Rational& t1) {
  MotionPath path;
  path.x.kind = AxisPath::Kind::half_tangent;
  path.x.coefficients = {t0, t1 - t0};
  return path;
}

void check_space(const Model& model, std::mt19937_64& random, int points, int motions, const std::string& what, Tally& tally) {
  CSpace space = CSpace::build(model, "anchor", "banking");
  ASSERT_EQ(space.dimension(), 1) << what;
  // the curves' coefficients: beyond the doubles' range (2^1024) for the long cases
  std::size_t bits = 0;
  for (std::size_t c = 0; c < space.charts().size(); ++c)
    for (std::size_t f = 0; f < space.feature_pairs().size(); ++f)
      for (const auto& row : space.curve_polynomial(c, FeatureId(f)))
        for (const mpz_class& z : row) bits = std::max(bits, mpz_sizeinbase(z.get_mpz_t(), 2));
  if (bits > 1024) ++tally.huge_spaces;
  // the anchor's swing between the pins: theta in [-0.3, 0.3], t = tan(theta / 2)
  std::uniform_real_distribution<double> swing(-0.15, 0.15), unit(0, 1);
  std::vector<Rational> boundary;   // the free range's ends, within 2^-40 (from the oracle below)
  for (int i = 0; i < points; ++i) {
    const Rational t(swing(random));
    MotionPath at = half_tangent_path(t, t);
    at.u_end = at.u_begin;
    const MotionCrossing c = space.first_crossing(at);
    const PartRelation oracle = relation_at(model, t);
    ++tally.points;
    if (oracle == PartRelation::apart) {
      ++tally.free;
      EXPECT_EQ(c.status, CrossingStatus::none) << what << " t = " << t << ": apart, yet " << static_cast<int>(c.status)
                                                << (c.grazing ? " (grazing)" : "");
      EXPECT_EQ(space.locate(PartCoordinate{PartCoordinate::Kind::half_angle_tangent, t}).kind, Location::Kind::free)
          << what << " t = " << t;
    } else {
      ++tally.contact;
      EXPECT_EQ(c.status, CrossingStatus::starts_in_contact) << what << " t = " << t << ": not apart";
    }
  }
  // the same at angles (the simulator's paths: the start's 160-bit pieces, the filtered start),
  // where both ends of the configuration's enclosure agree (not within 2^-200 of a contact)
  std::uniform_real_distribution<double> angle(-0.3, 0.3);
  for (int i = 0; i < points; ++i) {
    const double theta = angle(random);
    MotionPath at = angle_path(theta, theta);
    at.u_end = at.u_begin;
    const MotionCrossing c = space.first_crossing(at);
    const auto [lo, hi] = half_tangent_of(theta);
    const PartRelation a = relation_at(model, lo), b = relation_at(model, hi);
    ++tally.points;
    if (a == PartRelation::apart && b == PartRelation::apart) {
      ++tally.free;
      EXPECT_EQ(c.status, CrossingStatus::none) << what << " theta = " << theta << ": apart, yet "
                                                << static_cast<int>(c.status) << (c.grazing ? " (grazing)" : "");
    } else if (a != PartRelation::apart && b != PartRelation::apart) {
      ++tally.contact;
      EXPECT_EQ(c.status, CrossingStatus::starts_in_contact) << what << " theta = " << theta << ": not apart";
    }
  }
  for (int i = 0; i < motions; ++i) {
    const double theta1 = (random() % 2 == 0 ? 1 : -1) * (0.2 + 0.1 * unit(random));
    const MotionCrossing c = space.first_crossing(angle_path(0, theta1));
    ++tally.motions;
    const auto [lo, hi] = half_tangent_of(theta1);
    if (relation_at(model, lo) == PartRelation::apart && relation_at(model, hi) == PartRelation::apart) {
      EXPECT_EQ(c.status, CrossingStatus::none) << what << " to " << theta1;
      continue;
    }
    ++tally.crossings;
    ASSERT_EQ(c.status, CrossingStatus::crossing) << what << " to " << theta1 << (c.grazing ? " (grazing)" : "");
    // apart just before u_lower (both ends of the enclosure), not apart at u_upper (the enclosure's
    // end beyond it: the contact lies between 0 and theta(u_upper))
    const Rational before = c.u_lower * (1 - Rational(1, 1 << 20));
    const auto [b_lo, b_hi] = half_tangent_of(Rational(Rational(theta1) * before).get_d());
    EXPECT_EQ(relation_at(model, b_lo), PartRelation::apart) << what << " u = " << before;
    EXPECT_EQ(relation_at(model, b_hi), PartRelation::apart) << what << " u = " << before;
    // (the double nearest theta1 u_upper, moved outward by a few ulps: beyond theta(u_upper))
    double past = Rational(Rational(theta1) * c.u_upper).get_d();
    for (int k = 0; k < 4; ++k) past = std::nextafter(past, theta1 > 0 ? 1.0 : -1.0);
    const auto [p_lo, p_hi] = half_tangent_of(past);
    EXPECT_NE(relation_at(model, theta1 > 0 ? p_lo : p_hi), PartRelation::apart) << what << " u_upper = " << c.u_upper;
    EXPECT_LT(Rational(c.u_upper - c.u_lower), Rational(1, 1 << 30)) << what;
  }
  // motions from a free start (t = 0: the anchor centred between the pins) outward past a pin
  for (int i = 0; i < motions; ++i) {
    const Rational t1((random() % 2 == 0 ? 1 : -1) * (0.1 + 0.05 * unit(random)));
    const MotionPath path = half_tangent_path(Rational(0), t1);
    ASSERT_EQ(relation_at(model, Rational(0)), PartRelation::apart) << what;
    const MotionCrossing c = space.first_crossing(path);
    ++tally.motions;
    const Rational t_at_end = t1;
    if (relation_at(model, t_at_end) == PartRelation::apart) {
      EXPECT_EQ(c.status, CrossingStatus::none) << what << " to " << t1;
      continue;
    }
    ++tally.crossings;
    ASSERT_EQ(c.status, CrossingStatus::crossing) << what << " to " << t1 << (c.grazing ? " (grazing)" : "");
    EXPECT_LE(c.u_lower, c.u_upper);
    const Rational before = c.u_lower * (1 - Rational(1, 1 << 20));   // inside [0, u_lower)
    EXPECT_EQ(relation_at(model, t1 * before), PartRelation::apart) << what << " u = " << before;
    EXPECT_NE(relation_at(model, t1 * c.u_upper), PartRelation::apart) << what << " u_upper = " << c.u_upper;
    EXPECT_LT(Rational(c.u_upper - c.u_lower), Rational(1, 1 << 30)) << what;
  }
}

TEST(CSpaceLongRationals, PointQueriesAndCrossingsFollowTheOverlapOracle) {
  const Model base = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "escapement.json");
  std::mt19937_64 random(55055);
  Tally tally;
  // the digits of the moves' numerators and denominators: generated between 50 and 2000, with
  // the lengths around the old threshold (289 digits) and the model reader's largest (4096 bits)
  std::vector<int> lengths = {50, 287, 289, 300, 1233, 2000};
  std::uniform_int_distribution<int> digits(50, 2000);
  for (int i = 0; i < 4; ++i) lengths.push_back(digits(random));
  for (int length : lengths) {
    Model model = base;
    // a move of the pins below 10^-3 mm: numerator and denominator of `length` digits
    const mpz_class numerator = random_digits(random, length);
    mpz_class denominator = random_digits(random, length) * 1000;
    Rational move(numerator, denominator);
    move.canonicalize();
    if (random() % 2 == 0) move = -move;
    Part& banking = model.parts[*model.find_part("banking")];
    shift_part(banking, move);
    check_space(model, random, 60, 6, "digits " + std::to_string(length), tally);
  }
  std::printf("[ tally    ] %zu spaces with coefficients beyond 2^1024; %zu points (%zu free, %zu in contact); "
              "%zu motions (%zu crossings)\n",
              tally.huge_spaces, tally.points, tally.free, tally.contact, tally.motions, tally.crossings);
  EXPECT_GE(tally.huge_spaces, 6u);
  EXPECT_GE(tally.free, 300u);
  EXPECT_GE(tally.contact, 50u);
  EXPECT_GE(tally.crossings, 20u);
}

// interval_shift's enclosures: z / 2^s for generated z of 1 ... 20 000 bits and shifts, against
// the exact rational (inside, and one double wide at most where the quotient is a normal double).
TEST(CSpaceLongRationals, ShiftedEnclosuresHoldTheExactQuotient) {
  namespace algebra = cspace::algebra;
  std::mt19937_64 random(5505);
  gmp_randclass bits_source(gmp_randinit_mt);
  bits_source.seed(5505);
  int normal = 0, tiny = 0;
  for (int i = 0; i < 4000; ++i) {
    const int bits = 1 + static_cast<int>(random() % 20000);
    mpz_class z = bits_source.get_z_bits(static_cast<mp_bitcnt_t>(bits));
    if (random() % 2 == 0) z = -z;
    const long size = static_cast<long>(mpz_sizeinbase(z.get_mpz_t(), 2));
    // shifts that put z / 2^s anywhere from beyond DBL_MAX to below the least subnormal
    const long shift = std::max(0L, size - 1100 + static_cast<long>(random() % 2300));
    const algebra::Interval v = algebra::enclose_shifted(z, shift);
    Rational exact(z);
    mpq_div_2exp(exact.get_mpq_t(), exact.get_mpq_t(), static_cast<mp_bitcnt_t>(shift));
    ASSERT_TRUE(v.lo <= v.hi) << i;
    if (std::isfinite(v.lo)) EXPECT_LE(Rational(v.lo), exact) << i;
    if (std::isfinite(v.hi)) EXPECT_GE(Rational(v.hi), exact) << i;
    const double nearest = algebra::nearest_shifted(z, shift);
    if (sgn(z) != 0 && std::isfinite(v.lo) && std::isfinite(v.hi) && std::fabs(v.lo) >= 2.2250738585072014e-308 &&
        std::fabs(v.hi) >= 2.2250738585072014e-308 && std::fabs(v.hi) <= 1.7976931348623157e308 &&
        std::fabs(v.lo) <= 1.7976931348623157e308) {
      ++normal;
      EXPECT_LE(v.hi, std::nextafter(v.lo, v.hi + 1)) << i;   // at most one double wide
      EXPECT_TRUE(nearest == v.lo || nearest == v.hi) << i;
    } else if (sgn(z) != 0 && (v.lo == 0.0 || v.hi == 0.0)) {
      ++tiny;   // below the least normal double: [0, DBL_MIN] or [-DBL_MIN, 0]
      EXPECT_EQ(std::max(std::fabs(v.lo), std::fabs(v.hi)), 2.2250738585072014e-308) << i;
      EXPECT_TRUE(std::isnan(nearest)) << i;
    }
    // the same scaled by a power of two: scale_by_power_of_two(v, -k) holds exact / 2^k
    const long k = static_cast<long>(random() % 2200) - 1100;
    const algebra::Interval w = algebra::scale_by_power_of_two(v, k);
    Rational scaled = exact;
    if (k >= 0) mpq_mul_2exp(scaled.get_mpq_t(), scaled.get_mpq_t(), static_cast<mp_bitcnt_t>(k));
    else mpq_div_2exp(scaled.get_mpq_t(), scaled.get_mpq_t(), static_cast<mp_bitcnt_t>(-k));
    ASSERT_TRUE(w.lo <= w.hi) << i;
    if (std::isfinite(w.lo)) EXPECT_LE(Rational(w.lo), scaled) << i << " k " << k;
    if (std::isfinite(w.hi)) EXPECT_GE(Rational(w.hi), scaled) << i << " k " << k;
  }
  EXPECT_GE(normal, 1000);
  EXPECT_GE(tiny, 100);
}

// interval_shift: 0 for polynomials of ordinary size (enclosed as before), and under
// ScaledEnclosures the enclosures of a huge polynomial's values hold the exact value / 2^shift
// (outside it the enclosure is unbounded, as before, beyond 2^1024).
TEST(CSpaceLongRationals, HugePolynomialsEncloseTheirScaledValues) {
  namespace algebra = cspace::algebra;
  std::mt19937_64 random(550);
  int decided = 0;
  for (int i = 0; i < 300; ++i) {
    const int bits = 100 + static_cast<int>(random() % 6000);
    cspace::IntegerPolynomial2 f;
    const std::size_t dx = 1 + random() % 4, dy = 1 + random() % 3;
    f.coefficients.assign(dx + 1, std::vector<mpz_class>(dy + 1));
    for (auto& row : f.coefficients)
      for (mpz_class& c : row) {
        c = random_digits(random, 1 + static_cast<int>((bits - static_cast<int>(random() % 40)) * 0.30103));
        if (random() % 2 == 0) c = -c;
      }
    const long shift = algebra::interval_shift(f);
    std::size_t largest = 0;
    for (const auto& row : f.coefficients)
      for (const mpz_class& c : row) largest = std::max(largest, mpz_sizeinbase(c.get_mpz_t(), 2));
    EXPECT_EQ(shift, largest > 900 ? static_cast<long>(largest) - 900 : 0) << i;
    const algebra::IntervalPolynomial2 plain(f);   // (outside the scope: unscaled, as before)
    if (largest > 1024) {
      const algebra::Interval v = plain.evaluate(algebra::Interval{0.5, 0.5}, algebra::Interval{0.5, 0.5});
      EXPECT_FALSE(std::isfinite(v.lo) && std::isfinite(v.hi)) << i;
    }
    const algebra::IntervalPolynomial2 p = [&] {
      algebra::ScaledEnclosures scope;
      return algebra::IntervalPolynomial2(f);
    }();
    std::uniform_real_distribution<double> sym(-1, 1);
    for (int k = 0; k < 5; ++k) {
      const double x = sym(random), y = sym(random);
      const algebra::Interval v = p.evaluate(algebra::Interval{x, x}, algebra::Interval{y, y});
      Rational exact = 0;
      for (std::size_t a = f.coefficients.size(); a-- > 0;) {
        Rational row = 0;
        for (std::size_t b = f.coefficients[a].size(); b-- > 0;) row = row * Rational(y) + Rational(f.coefficients[a][b]);
        exact = exact * Rational(x) + row;
      }
      mpq_div_2exp(exact.get_mpq_t(), exact.get_mpq_t(), static_cast<mp_bitcnt_t>(shift));
      ASSERT_TRUE(std::isfinite(v.lo) && std::isfinite(v.hi)) << i << " bits " << largest;
      EXPECT_LE(Rational(v.lo), exact) << i;
      EXPECT_GE(Rational(v.hi), exact) << i;
      if (!v.contains_zero()) ++decided;
      double error = 0;
      const double value = p.evaluate(x, y, &error);
      ASSERT_TRUE(std::isfinite(value) && std::isfinite(error)) << i;
      EXPECT_LE(Rational(value) - Rational(error), exact) << i;
      EXPECT_GE(Rational(value) + Rational(error), exact) << i;
    }
  }
  EXPECT_GE(decided, 1000);
}

}  // namespace
}  // namespace hipair
