// Session 56 (kin56): the kinematic sweep's driver plan made exact (kinematics/engine.hpp
// plan_driver, locate_coordinate, half_turns_at_most). Until then the start's turn came from
// std::lround of start.get_d(), the end from start.get_d() + travel and the segments were counted
// until the doubles' travel was reached within 1e-6: beyond 2^53 rad the turns and the end were
// wrong, and a cam with limits near 10^17 deg ran for minutes.
// Oracles, on generated cases at magnitudes 10^-300 .. 10^1000 (rad) and 10^-300 .. 10^400 (mm):
// - the chart about m pi holding an angle theta, m = floor(theta / pi + 1 / 2), by rational
//   arithmetic with rational bounds pi_lo < pi < pi_hi (MPFR's pi rounded down and up at a
//   precision beyond the magnitude), and the segment count |m(b) - m(a)| + 1 from it;
// - each located end's exact coordinate (half turns pi + 2 atan(t)) within 2^-57 rad of the
//   angle asked (t is rounded to 2^-60), in MPFR at a precision beyond the magnitude;
// - whole turns: the end is the start's exact position, 2 k half turns on;
// - translations: the exact clamp of the range to the line;
// - half_turns_at_most: MPFR at 2000 bits away from ties, and the exact ties (+-1, n pi);
// - the whole analysis: the cam follower with its cam's limits (and a cyclic cam's range) moved
//   out by whole turns (rationals within 2^-200 of the shift) has the same pieces, events and
//   contacts as at the origin, its driver coordinates shifted by the turns; beyond 2^63 half
//   turns a limited rotation is refused with one clear message.
#include "core/angle_sign.hpp"
#include "kinematics/engine.hpp"
#include "kinematics_axis_lines.hpp"
#include "test_paths.hpp"
#include "random_rationals.hpp"

#include <hipair/error.hpp>
#include <hipair/kinematics.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>
#include <mpfr.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair::kinematics_detail {
namespace {

using test_numbers::power_of_ten;

// A random rational of magnitude about 10^e: a 40-bit numerator over a 20-bit denominator.
Rational random_rational(std::mt19937_64& random, long e) {
  Rational r(mpz_class(static_cast<unsigned long>(random() % (1ULL << 40)) + 1),
             mpz_class(static_cast<unsigned long>(random() % (1ULL << 20)) + (1UL << 20)));
  r.canonicalize();
  r *= power_of_ten(e);
  return random() % 2 ? r : Rational(-r);
}

mpfr_prec_t precision_for(const Rational& x) { return 300 + std::max(magnitude_bits(x), 0L); }

// Rational bounds of pi at `bits`.
std::pair<Rational, Rational> pi_bounds(mpfr_prec_t bits) {
  mpfr_t p;
  mpfr_init2(p, bits);
  mpq_t q;
  mpq_init(q);
  mpfr_const_pi(p, MPFR_RNDD);
  mpfr_get_q(q, p);
  Rational lo(q);
  mpfr_const_pi(p, MPFR_RNDU);
  mpfr_get_q(q, p);
  Rational hi(q);
  mpq_clear(q);
  mpfr_clear(p);
  return {lo, hi};
}

mpz_class floor_of(const Rational& x) {
  mpz_class f;
  mpz_fdiv_q(f.get_mpz_t(), x.get_num_mpz_t(), x.get_den_mpz_t());
  return f;
}

// m = floor(theta / pi + 1 / 2) by rationals; nullopt when theta lies within 2^-40 rad of a
// seam (m pi + pi / 2) or the bounds of pi do not decide it.
std::optional<mpz_class> chart_oracle(const Rational& theta) {
  auto [lo, hi] = pi_bounds(precision_for(theta) + 100);
  const Rational margin(mpz_class(1), mpz_class(1) << 40);
  std::optional<mpz_class> m;
  for (const Rational& x : {Rational(theta - margin), Rational(theta + margin)})
    for (const Rational* p : {&lo, &hi}) {
      mpz_class candidate = floor_of(Rational(x / *p + Rational(1, 2)));
      if (m && *m != candidate) return std::nullopt;
      m = candidate;
    }
  return m;
}

// |half_turns pi + 2 atan(t) - theta| <= 2^-57, in MPFR well beyond the magnitude.
bool coordinate_near(const mpz_class& half_turns, const Rational& t, const Rational& theta) {
  const mpfr_prec_t bits = precision_for(theta) + static_cast<mpfr_prec_t>(mpz_sizeinbase(half_turns.get_mpz_t(), 2));
  mpfr_t x, p, q;
  mpfr_inits2(bits, x, p, q, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_q(x, t.get_mpq_t(), MPFR_RNDN);
  mpfr_atan(x, x, MPFR_RNDN);
  mpfr_mul_2ui(x, x, 1, MPFR_RNDN);
  mpfr_const_pi(p, MPFR_RNDN);
  mpfr_mul_z(p, p, half_turns.get_mpz_t(), MPFR_RNDN);
  mpfr_add(x, x, p, MPFR_RNDN);
  mpfr_set_q(q, theta.get_mpq_t(), MPFR_RNDN);
  mpfr_sub(x, x, q, MPFR_RNDN);
  const bool near = mpfr_cmp_ui_2exp(x, 1, -57) <= 0 && mpfr_cmp_si_2exp(x, -1, -57) >= 0;
  mpfr_clears(x, p, q, static_cast<mpfr_ptr>(nullptr));
  return near;
}

// A rational within 2^-(precision) of half_turns pi + shift (shift rational), rounded.
Rational rational_near(const mpz_class& half_turns, const Rational& shift, mpfr_prec_t precision) {
  mpfr_t x, p;
  mpfr_inits2(precision + static_cast<mpfr_prec_t>(mpz_sizeinbase(half_turns.get_mpz_t(), 2)), x, p,
              static_cast<mpfr_ptr>(nullptr));
  mpfr_const_pi(p, MPFR_RNDN);
  mpfr_mul_z(p, p, half_turns.get_mpz_t(), MPFR_RNDN);
  mpfr_set_q(x, shift.get_mpq_t(), MPFR_RNDN);
  mpfr_add(x, x, p, MPFR_RNDN);
  mpq_t q;
  mpq_init(q);
  mpfr_get_q(q, x);
  Rational r(q);
  mpq_clear(q);
  mpfr_clears(x, p, static_cast<mpfr_ptr>(nullptr));
  return r;
}

// The segments are consecutive charts of the full turn from the plan's start to its end: each
// nonempty, the next chart one half turn on in the direction, interior segments whole charts.
void expect_consecutive(const DriverPlan& plan, int direction, const std::string& where) {
  const auto& segments = plan.segments;
  ASSERT_FALSE(segments.empty()) << where;
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const DriverSegment& segment = segments[s];
    EXPECT_NE(segment.from, segment.to) << where << " segment " << s;
    EXPECT_EQ((segment.to - segment.from) * direction > 0, true) << where << " segment " << s;
    const mpz_class half_turns = plan.reference + segment.base_pi;
    EXPECT_EQ(segment.piece, mpz_odd_p(half_turns.get_mpz_t()) ? 1u : 0u) << where << " segment " << s;
    if (s > 0) {
      EXPECT_EQ(segment.base_pi, segments[s - 1].base_pi + direction) << where << " segment " << s;
      EXPECT_EQ(segment.from, Rational(-direction)) << where << " segment " << s;
    }
    if (s + 1 < segments.size()) EXPECT_EQ(segment.to, Rational(direction)) << where << " segment " << s;
  }
  EXPECT_EQ(plan.reference + segments.front().base_pi, plan.start_half_turns + ((segments.front().from != plan.start.value.lower) ? direction : 0))
      << where;
  EXPECT_EQ(segments.back().to, plan.end.value.lower) << where;
  EXPECT_EQ(plan.reference + segments.back().base_pi, plan.end_half_turns) << where;
}

// The expected count from the plan's located ends (the ends themselves checked against the
// angles asked): |m_e - m_s| + 1 charts, less an empty first (a start on the chart's end it
// leaves from) or last (an end on the chart's start).
std::size_t count_from_ends(const DriverPlan& plan, int direction) {
  mpz_class span = (plan.end_half_turns - plan.start_half_turns) * direction;
  if (span < 0) return 0;
  if (span == 0) return plan.start.value.lower != plan.end.value.lower ? 1 : 0;
  std::size_t count = span.get_ui() + 1;
  if (plan.start.value.lower == Rational(direction)) --count;
  if (plan.end.value.lower == Rational(-direction)) --count;
  return count;
}

TEST(KinematicsDriverPlan, FullTurnRangesAtEveryMagnitudeAgainstRationalCharts) {
  std::mt19937_64 random(5601);
  const AxisLine line = test_axes::full_turn();
  int counted = 0;
  for (int i = 0; i < 240; ++i) {
    const long e = i % 6 == 0 ? 1000 : static_cast<long>(random() % 701) - 300;   // the reader's limit, and 10^-300 .. 10^400
    const Rational a = random_rational(random, e);
    // widths from 10^-15 rad to 190 pi
    Rational width = Rational(mpz_class(static_cast<unsigned long>(random() % 600000) + 1), mpz_class(1000));
    if (i % 4 == 1) width /= power_of_ten(static_cast<long>(random() % 15));
    const Rational b = random() % 2 ? Rational(a + width) : Rational(a - width);
    const int direction = b > a ? 1 : -1;
    std::vector<std::string> warnings;
    const DriverPlan plan = plan_driver(line, a, direction, DriverEnd{DriverEnd::Kind::coordinate, b}, warnings);
    const std::string where = "a = " + a.get_str().substr(0, 60) + " width " + width.get_str() + " dir " + std::to_string(direction);
    EXPECT_TRUE(warnings.empty()) << where;
    EXPECT_TRUE(coordinate_near(plan.start_half_turns, plan.start.value.lower, a)) << where;
    EXPECT_TRUE(coordinate_near(plan.end_half_turns, plan.end.value.lower, b)) << where;
    const std::optional<mpz_class> ma = chart_oracle(a), mb = chart_oracle(b);
    if (ma) EXPECT_EQ(plan.start_half_turns, *ma) << where;
    if (mb) EXPECT_EQ(plan.end_half_turns, *mb) << where;
    if (ma && mb) {
      mpz_class expected = abs(mpz_class(*mb - *ma)) + 1;
      EXPECT_EQ(mpz_class(plan.segments.size()), expected) << where;
      ++counted;
    }
    if (plan.segments.empty()) {
      EXPECT_EQ(count_from_ends(plan, direction), 0u) << where;
      continue;
    }
    expect_consecutive(plan, direction, where);
    EXPECT_EQ(plan.segments.size(), count_from_ends(plan, direction)) << where;
    // the frame: whole turns taken out only far out, and its doubles small
    EXPECT_EQ(mpz_even_p(plan.reference.get_mpz_t()) != 0, true) << where;
    EXPECT_LE(std::labs(plan.segments.front().base_pi), 1L << 20) << where;
  }
  EXPECT_GT(counted, 200);
}

TEST(KinematicsDriverPlan, StartsOnSeamsAndAtHalfTurnMultiples) {
  std::mt19937_64 random(5602);
  const AxisLine line = test_axes::full_turn();
  for (int i = 0; i < 120; ++i) {
    const long e = static_cast<long>(random() % 400);
    // a start within 2^-100 rad of k pi + pi / 2 (a seam: its half-angle tangent rounds to +-1)
    // or of k pi (a chart's centre: tangent 0), k about 10^e
    mpz_class k = floor_of(random_rational(random, e));
    const bool seam = i % 2 == 0;
    const Rational offset = Rational(mpz_class(static_cast<long>(random() % 3) - 1), mpz_class(1) << 100);
    const Rational a = seam ? rational_near(2 * k + 1, offset, 400) * Rational(1, 2)
                            : rational_near(k, offset, 400);
    // half the seam: (2k + 1) pi / 2 = rational_near(2k + 1) / 2 up to 2^-401
    const Rational width = Rational(mpz_class(static_cast<unsigned long>(random() % 40000) + 1), mpz_class(100));
    const int direction = random() % 2 ? 1 : -1;
    const Rational b = a + direction * width;
    std::vector<std::string> warnings;
    const DriverPlan plan = plan_driver(line, a, direction, DriverEnd{DriverEnd::Kind::coordinate, b}, warnings);
    const std::string where = std::string(seam ? "seam" : "centre") + " k = " + k.get_str().substr(0, 40) + " dir " +
                              std::to_string(direction);
    EXPECT_TRUE(coordinate_near(plan.start_half_turns, plan.start.value.lower, a)) << where;
    EXPECT_TRUE(coordinate_near(plan.end_half_turns, plan.end.value.lower, b)) << where;
    if (seam) {
      // on the seam: the start of the upper chart (canonical), t = -1
      EXPECT_EQ(plan.start.value.lower, Rational(-1)) << where;
      EXPECT_EQ(plan.start_half_turns, k + 1) << where;
    } else {
      EXPECT_EQ(plan.start.value.lower, Rational(0)) << where;
      EXPECT_EQ(plan.start_half_turns, k) << where;
    }
    if (const std::optional<mpz_class> mb = chart_oracle(b)) EXPECT_EQ(plan.end_half_turns, *mb) << where;
    expect_consecutive(plan, direction, where);
    EXPECT_EQ(plan.segments.size(), count_from_ends(plan, direction)) << where;
  }
}

TEST(KinematicsDriverPlan, WholeTurnsEndExactlyWhereTheyStart) {
  std::mt19937_64 random(5603);
  const AxisLine line = test_axes::full_turn();
  for (int i = 0; i < 100; ++i) {
    const long e = static_cast<long>(random() % 1301) - 300;
    const Rational a = random_rational(random, e);
    const int direction = random() % 2 ? 1 : -1;
    const long turns = static_cast<long>(random() % 100) + 1;
    std::vector<std::string> warnings;
    const DriverPlan plan = plan_driver(line, a, direction, DriverEnd{DriverEnd::Kind::cycles, Rational(turns)}, warnings);
    const std::string where = "a ~ 1e" + std::to_string(e) + " turns " + std::to_string(turns);
    EXPECT_EQ(plan.end.piece, plan.start.piece) << where;
    EXPECT_EQ(plan.end.value.lower, plan.start.value.lower) << where;
    EXPECT_EQ(plan.end_half_turns - plan.start_half_turns, mpz_class(2 * turns * direction)) << where;
    expect_consecutive(plan, direction, where);
    EXPECT_EQ(plan.segments.size(), static_cast<std::size_t>(2 * turns + 1) - (plan.start.value.lower == Rational(direction) ? 2 : 0))
        << where;
    // part turns: the end within 2^-57 rad of a + 2 pi c (c = turns - 1/3)
    const Rational cycles = Rational(turns) - Rational(1, 3);
    const DriverPlan part = plan_driver(line, a, direction, DriverEnd{DriverEnd::Kind::cycles, cycles}, warnings);
    const mpfr_prec_t bits = precision_for(a) + 100;
    mpfr_t x, p;
    mpfr_inits2(bits, x, p, static_cast<mpfr_ptr>(nullptr));
    mpfr_const_pi(p, MPFR_RNDN);
    mpfr_mul_q(p, p, cycles.get_mpq_t(), MPFR_RNDN);
    mpfr_mul_si(p, p, 2 * direction, MPFR_RNDN);
    mpfr_set_q(x, a.get_mpq_t(), MPFR_RNDN);
    mpfr_add(x, x, p, MPFR_RNDN);
    mpq_t q;
    mpq_init(q);
    mpfr_get_q(q, x);
    const Rational end(q);
    mpq_clear(q);
    mpfr_clears(x, p, static_cast<mpfr_ptr>(nullptr));
    EXPECT_TRUE(coordinate_near(part.end_half_turns, part.end.value.lower, end)) << where;
    expect_consecutive(part, direction, where);
    EXPECT_TRUE(warnings.empty()) << where;
  }
}

TEST(KinematicsDriverPlan, TranslationsAtEveryScaleClampExactly) {
  std::mt19937_64 random(5604);
  for (int i = 0; i < 300; ++i) {
    const long e = static_cast<long>(random() % 701) - 300;
    Rational lo = random_rational(random, e), hi = random_rational(random, e);
    if (lo == hi) continue;
    if (hi < lo) std::swap(lo, hi);
    AxisLine line;
    line.rotation = false;
    line.pieces = {ChartAxis{ChartAxis::Kind::translation, false, lo, hi}};
    line.half_turns = {0};
    line.offsets = {0.0};
    line.limited = true;
    const Rational width = hi - lo;
    // ends inside, on and beyond the limits
    auto pick = [&]() -> Rational {
      switch (random() % 4) {
        case 0: return lo;
        case 1: return hi;
        case 2: return lo + width * Rational(static_cast<long>(random() % 1000), 1000);
        default: return random() % 2 ? Rational(lo - width * Rational(static_cast<long>(random() % 1000) + 1, 1000))
                                     : Rational(hi + width * Rational(static_cast<long>(random() % 1000) + 1, 1000));
      }
    };
    const Rational a = pick(), b = pick();
    if (a == b) continue;
    const int direction = b > a ? 1 : -1;
    std::vector<std::string> warnings;
    const DriverPlan plan = plan_driver(line, a, direction, DriverEnd{DriverEnd::Kind::coordinate, b}, warnings);
    const std::string where = "[" + lo.get_str() + ", " + hi.get_str() + "] a = " + a.get_str() + " b = " + b.get_str();
    const Rational from = std::clamp(a, lo, hi), to = std::clamp(b, lo, hi);
    const bool beyond = direction > 0 ? b > hi : b < lo;
    EXPECT_EQ(plan.beyond, beyond) << where;
    EXPECT_EQ(warnings.size(), beyond ? 1u : 0u) << where;
    ASSERT_EQ(plan.segments.size(), from != to ? 1u : 0u) << where;
    if (from != to) {
      EXPECT_EQ(plan.segments[0].from, from) << where;
      EXPECT_EQ(plan.segments[0].to, to) << where;
    }
  }
}

TEST(KinematicsDriverPlan, LimitedRotationsFarOutWalkTheirChartsToTheLimit) {
  std::mt19937_64 random(5605);
  for (int i = 0; i < 80; ++i) {
    const int n = static_cast<int>(random() % 6) + 1;
    mpz_class m0 = mpz_class(static_cast<long>(random() % (1ULL << 62))) * (random() % 2 ? 1 : -1);
    if (i % 3 == 0) m0 = static_cast<long>(random() % 20) - 10;
    AxisLine line;
    line.rotation = true;
    line.limited = true;
    for (int j = 0; j < n; ++j) {
      const mpz_class m = m0 + j;
      line.pieces.push_back(ChartAxis{ChartAxis::Kind::rotation, mpz_odd_p(m.get_mpz_t()) != 0, Rational(-1), Rational(1)});
      line.half_turns.push_back(m.get_si());
      line.offsets.push_back(m.get_d() * std::numbers::pi);
    }
    line.pieces.front().lo = Rational(-static_cast<long>(random() % 900), 1000);
    line.pieces.back().hi = Rational(static_cast<long>(random() % 900), 1000);
    // a start inside chart j, t = u in (-0.9, 0.9) within the chart's range
    const int j = static_cast<int>(random() % n);
    Rational u(static_cast<long>(random() % 1799) - 899, 1000);
    u = std::clamp(u, line.pieces[j].lo, line.pieces[j].hi);
    mpfr_t x;
    mpfr_init2(x, 400);
    mpfr_set_q(x, u.get_mpq_t(), MPFR_RNDN);
    mpfr_atan(x, x, MPFR_RNDN);
    mpfr_mul_2ui(x, x, 1, MPFR_RNDN);
    mpq_t q;
    mpq_init(q);
    mpfr_get_q(q, x);
    const Rational start = rational_near(m0 + j, Rational(q), 400);
    mpq_clear(q);
    mpfr_clear(x);
    const int direction = random() % 2 ? 1 : -1;
    std::vector<std::string> warnings;
    const DriverPlan plan = plan_driver(line, start, direction, DriverEnd{DriverEnd::Kind::limit, Rational(0)}, warnings);
    const std::string where = "m0 = " + m0.get_str() + " n " + std::to_string(n) + " j " + std::to_string(j);
    EXPECT_EQ(plan.start_half_turns, m0 + j) << where;
    EXPECT_EQ(plan.start.piece, static_cast<std::size_t>(j)) << where;
    EXPECT_TRUE(coordinate_near(plan.start_half_turns, plan.start.value.lower, start)) << where;
    const std::size_t last = direction > 0 ? n - 1 : 0;
    EXPECT_EQ(plan.end.piece, last) << where;
    EXPECT_EQ(plan.end_half_turns, m0 + static_cast<long>(last)) << where;
    EXPECT_TRUE(warnings.empty()) << where;
    std::size_t expected = direction > 0 ? n - j : j + 1;
    if (plan.start.value.lower == (direction > 0 ? line.pieces[j].hi : line.pieces[j].lo)) --expected;
    ASSERT_EQ(plan.segments.size(), expected) << where;
    for (std::size_t s = 0; s < plan.segments.size(); ++s)
      EXPECT_EQ(plan.reference + plan.segments[s].base_pi, mpz_class(line.half_turns[plan.segments[s].piece])) << where;
    if (plan.segments.empty()) continue;   // a start on the limit
    EXPECT_EQ(plan.segments.back().to, direction > 0 ? line.pieces.back().hi : line.pieces.front().lo) << where;
    // an end beyond the limit: the limit, with the warning
    const Rational beyond = rational_near(m0 + (direction > 0 ? n + 2 : -3), Rational(0), 400);
    warnings.clear();
    const DriverPlan past = plan_driver(line, start, direction, DriverEnd{DriverEnd::Kind::coordinate, beyond}, warnings);
    EXPECT_TRUE(past.beyond) << where;
    EXPECT_EQ(warnings.size(), 1u) << where;
    EXPECT_EQ(past.segments.size(), plan.segments.size()) << where;
  }
}

TEST(KinematicsDriverPlan, TravelAgainstWholeTurnsDecidedByRationals) {
  std::mt19937_64 random(5606);
  // exact ties: (n - 1) pi + 2 (atan 1 - atan -1) = n pi; (n + 1) pi + 2 (atan -1 - atan 1) = n pi
  for (long n : {-3L, 0L, 5L, 200L}) {
    EXPECT_TRUE(half_turns_at_most(mpz_class(n - 1), Rational(-1), Rational(1), n));
    EXPECT_TRUE(half_turns_at_most(mpz_class(n + 1), Rational(1), Rational(-1), n));
    EXPECT_TRUE(half_turns_at_most(mpz_class(n), Rational(1, 3), Rational(1, 3), n));
    EXPECT_FALSE(half_turns_at_most(mpz_class(n - 1), Rational(-1), Rational(1) + Rational(mpz_class(1), mpz_class(1) << 200), n));
    EXPECT_FALSE(half_turns_at_most(mpz_class(n), Rational(1, 3), Rational(1, 3) + Rational(mpz_class(1), mpz_class(1) << 300), n));
  }
  int decided = 0;
  for (int i = 0; i < 2000; ++i) {
    const Rational from(static_cast<long>(random() % 8001) - 4000, static_cast<long>(random() % 999) + 1);
    const Rational to(static_cast<long>(random() % 8001) - 4000, static_cast<long>(random() % 999) + 1);
    const long n = static_cast<long>(random() % 11) - 5;
    const mpz_class m = n + static_cast<long>(random() % 7) - 3;
    // m + 2 (atan to - atan from) / pi - n at 2000 bits
    mpfr_t x, y, p;
    mpfr_inits2(2000, x, y, p, static_cast<mpfr_ptr>(nullptr));
    mpfr_set_q(x, to.get_mpq_t(), MPFR_RNDN);
    mpfr_atan(x, x, MPFR_RNDN);
    mpfr_set_q(y, from.get_mpq_t(), MPFR_RNDN);
    mpfr_atan(y, y, MPFR_RNDN);
    mpfr_sub(x, x, y, MPFR_RNDN);
    mpfr_mul_2ui(x, x, 1, MPFR_RNDN);
    mpfr_const_pi(p, MPFR_RNDN);
    mpfr_div(x, x, p, MPFR_RNDN);
    mpfr_add_z(x, x, mpz_class(m - n).get_mpz_t(), MPFR_RNDN);
    const bool tie = mpfr_cmpabs_ui(x, 0) == 0 || mpfr_get_exp(x) < -1900;
    const bool expected = mpfr_sgn(x) <= 0;
    mpfr_clears(x, y, p, static_cast<mpfr_ptr>(nullptr));
    if (tie) continue;
    EXPECT_EQ(half_turns_at_most(m, from, to, n), expected) << "m " << m << " from " << from << " to " << to << " n " << n;
    ++decided;
  }
  EXPECT_GT(decided, 1900);
}

// The cam follower with its cam moved, without the follower's spring: limits [lo, hi] rad
// (limited) or none (full turn, range [lo, hi]); initial angle `initial`.
KinematicsResult cam_follower(const Rational& lo, const Rational& hi, const Rational& initial, bool limited) {
  Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/cam-follower.json");
  Part& cam = model.parts[*model.find_part("cam")];
  cam.initial.angle = initial;
  KinematicsOptions options;
  options.driver = "cam";
  options.steps_per_cycle = 64;
  options.reversal = false;
  options.model_loads = false;   // no spring: the follower is left behind where the cam falls away (events)
  if (limited) cam.motion.angle_limits = RationalInterval{lo, hi};
  else options.range = std::make_pair(lo, hi);
  return analyze_kinematics(model, options);
}

void expect_same_structure(const KinematicsResult& near, const KinematicsResult& far, double shift, const std::string& where) {
  ASSERT_EQ(near.pieces.size(), far.pieces.size()) << where;
  for (std::size_t p = 0; p < near.pieces.size(); ++p) {
    EXPECT_EQ(near.pieces[p].mode, far.pieces[p].mode) << where;
    EXPECT_EQ(near.pieces[p].moving, far.pieces[p].moving) << where;
    EXPECT_EQ(near.pieces[p].contacts, far.pieces[p].contacts) << where;
    EXPECT_EQ(near.pieces[p].start.chart, far.pieces[p].start.chart) << where;
    // the driver's coordinates shifted by the whole turns, to the doubles' precision far out
    const double tolerance = 4e-15 * std::abs(shift) + 1e-6;
    EXPECT_NEAR(far.pieces[p].start.value(), near.pieces[p].start.value() + shift, tolerance) << where;
    EXPECT_NEAR(far.pieces[p].end.value(), near.pieces[p].end.value() + shift, tolerance) << where;
    EXPECT_LE(far.pieces[p].start.coordinate.lower, far.pieces[p].start.coordinate.upper) << where;
  }
  ASSERT_EQ(near.events.size(), far.events.size()) << where;
  for (std::size_t e = 0; e < near.events.size(); ++e) {
    EXPECT_EQ(near.events[e].kind, far.events[e].kind) << where;
    EXPECT_EQ(near.events[e].before, far.events[e].before) << where;
    EXPECT_EQ(near.events[e].after, far.events[e].after) << where;
  }
  EXPECT_EQ(near.jam.has_value(), far.jam.has_value()) << where;
  EXPECT_EQ(near.samples.size(), far.samples.size()) << where;
  EXPECT_EQ(near.warnings, far.warnings) << where;
}

TEST(KinematicsDriverPlan, CamMovedOutByWholeTurnsHasTheSameMotion) {
  std::mt19937_64 random(5607);
  // 10^17 deg (the session-55 case: minutes), up to 2^62 half turns (limited), 10^400 rad (full turn)
  for (int i = 0; i < 6; ++i) {
    const Rational lo(static_cast<long>(random() % 2000) - 1000, 1000);
    const Rational width(static_cast<long>(random() % 5500) + 500, 1000);   // 0.5 .. 6 rad
    const Rational initial = lo + width * Rational(static_cast<long>(random() % 900) + 50, 1000);
    const KinematicsResult near = cam_follower(lo, lo + width, initial, true);
    for (long e : {17L, 18L}) {
      // whole turns K near 10^e deg
      const mpz_class turns = floor_of(Rational(power_of_ten(e) / 360)) + static_cast<long>(random() % 1000);
      auto moved = [&](const Rational& x) { return rational_near(2 * turns, x, 400); };
      const KinematicsResult far = cam_follower(moved(lo), moved(lo + width), moved(initial), true);
      const double shift = mpz_class(2 * turns).get_d() * std::numbers::pi;
      expect_same_structure(near, far, shift, "limited, K = " + turns.get_str());
    }
    for (long e : {30L, 300L}) {
      const mpz_class turns = floor_of(power_of_ten(e));
      auto moved = [&](const Rational& x) { return rational_near(2 * turns, x, 400); };
      const KinematicsResult full_near = cam_follower(lo, lo + width, lo, false);
      const KinematicsResult full_far = cam_follower(moved(lo), moved(lo + width), moved(lo), false);
      const double shift = mpz_class(2 * turns).get_d() * std::numbers::pi;
      expect_same_structure(full_near, full_far, shift, "full turn, K = 1e" + std::to_string(e));
    }
    // 10^400 rad: planned and swept, but the report's angles (doubles) would be infinite: refused
    try {
      const mpz_class turns = floor_of(power_of_ten(400));
      cam_follower(rational_near(2 * turns, lo, 400), rational_near(2 * turns, lo + width, 400), Rational(0), false);
      ADD_FAILURE() << "a driver at 10^400 rad was taken";
    } catch (const NumericError& error) {
      EXPECT_NE(std::string(error.what()).find("beyond the range of doubles"), std::string::npos) << error.what();
    }
  }
  // limits beyond 2^63 half turns: one clear refusal
  const mpz_class turns = mpz_class(1) << 63;
  auto moved = [&](const Rational& x) { return rational_near(2 * turns, x, 400); };
  try {
    cam_follower(moved(Rational(0)), moved(Rational(1)), moved(Rational(1, 2)), true);
    ADD_FAILURE() << "limits beyond 2^63 half turns were taken";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("beyond about 10^19 rad"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace hipair::kinematics_detail
