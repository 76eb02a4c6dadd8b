// The published figures of a sliced (3-DOF) pair correctly rounded (issue 13, session 64): every
// angle's `degrees` (SlicedAngle::degrees: representatives, witnesses; CriticalAngle::degrees) is
// the double nearest 360 atan(t) / pi, and a critical angle's `t.decimal` (nearest_double of its
// AlgebraicNumber) the double nearest t, against the MPFR-free oracle of rounding_oracle.hpp:
// tangents exactly 0, +-2^-k (k <= 1200, the subnormal degrees included), random tangents at
// 10^-300 ... 10^400, square roots isolated by intervals with an end at 0, and the JSON of
// `hipair cspace` (src/cli/cspace_sliced.cpp) read back for pegs in holes. Before session 64 the
// JSON's representatives' and witnesses' degrees were 2 atan(t) * 180 / pi in doubles and
// `t.decimal` AlgebraicNumber::approximate() (within an ulp or two).
#include <hipair/model.hpp>
#include <hipair/rational.hpp>
#include <hipair/sliced.hpp>

#include "cli/cspace_sliced.hpp"
#include "rounding_oracle.hpp"
#include "sliced_peg_in_hole.hpp"
#include "test_seed.hpp"
#include "random_rationals.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <optional>
#include <random>
#include <string>

namespace hipair {
namespace {

using nlohmann::json;
using test::rounding::expected_degrees;
using test::rounding::oracle_round;
using test::rounding::power_of_two;
using test::rounding::same_double;

using test_numbers::power_of_ten;

SlicedAngle angle_of(const Rational& t) {
  SlicedAngle a;
  a.t = t;
  return a;
}

TEST(SlicedFigures, AngleDegreesAtEveryScale) {
  EXPECT_TRUE(same_double(angle_of(Rational(0)).degrees(), 0.0));
  SlicedAngle half;
  half.half_turn = true;
  EXPECT_TRUE(same_double(half.degrees(), 180.0));
  EXPECT_TRUE(same_double(angle_of(Rational(1)).degrees(), 90.0));
  EXPECT_TRUE(same_double(angle_of(Rational(-1)).degrees(), -90.0));
  std::mt19937_64 random(test::test_seed(64));
  int checked = 0, subnormal = 0;
  // +-2^-k: the degrees 360 2^-k / pi reach the subnormal range near k = 1017
  for (long k = 1; k <= 1200; k += 1 + static_cast<long>(random() % 5))
    for (int s : {1, -1}) {
      const Rational t = power_of_two(-k) * s;
      const auto expected = expected_degrees(t, t);
      ASSERT_TRUE(expected.has_value()) << "2^-" << k;
      const double degrees = angle_of(t).degrees();
      EXPECT_TRUE(same_double(degrees, *expected)) << "2^-" << k << " sign " << s << ": " << degrees << " for " << *expected;
      if (std::fabs(*expected) < std::numeric_limits<double>::min()) ++subnormal;
      ++checked;
    }
  // random tangents m / n 10^e, e in [-300, 400], both signs, and near the right angles
  for (int i = 0; i < 1500; ++i) {
    const long e = static_cast<long>(random() % 701) - 300;
    Rational t(mpz_class(static_cast<unsigned long>((random() >> 2) | 1)), mpz_class(static_cast<unsigned long>(random() | (1ul << 63))));
    t.canonicalize();
    t *= power_of_ten(e);
    if (i % 7 == 0) t = 1 + power_of_ten(-static_cast<long>(random() % 300)) * ((i % 2) ? 1 : -1);
    if (i % 2) t = -t;
    const auto expected = expected_degrees(t, t);
    if (!expected) continue;
    EXPECT_TRUE(same_double(angle_of(t).degrees(), *expected)) << to_exact_string(t) << ": " << angle_of(t).degrees() << " for " << *expected;
    ++checked;
  }
  EXPECT_GT(checked, 1900);
  EXPECT_GT(subnormal, 20);
}

AlgebraicNumber algebraic(std::vector<mpz_class> polynomial, const Rational& lower, const Rational& upper) {
  AlgebraicNumber a;
  a.polynomial = std::move(polynomial);
  a.lower = lower;
  a.upper = upper;
  return a;
}

TEST(SlicedFigures, NearestDoubleOfAlgebraicNumbers) {
  // 0 isolated by (-1, 1): +0
  EXPECT_TRUE(same_double(nearest_double(algebraic({0, -3, 1}, Rational(-1), Rational(1))), 0.0));
  std::mt19937_64 random(test::test_seed(64));
  int checked = 0;
  for (int i = 0; i < 600; ++i) {
    // +-sqrt(c), c = m / n 10^(2e), a root of n x^2 - m 10^(2e), isolated by (0, c + 1) or (-(c + 1), 0)
    const long e = static_cast<long>(random() % 701) - 300;
    const mpz_class m(static_cast<unsigned long>((random() >> 1) | 1)), n(static_cast<unsigned long>((random() >> 1) | 1));
    Rational c(m, n);
    c.canonicalize();
    c *= power_of_ten(2 * e);
    const int s = i % 2 ? -1 : 1;
    const Rational end = c + 1;
    const AlgebraicNumber root = algebraic({-c.get_num(), 0, c.get_den()}, s > 0 ? Rational(0) : Rational(-end),
                                           s > 0 ? end : Rational(0));
    // the oracle: sqrt(num den 4^b) / (den 2^b) between consecutive integers over den 2^b
    const long b = 600 + 4 * (e < 0 ? -e : 0);
    mpz_class radicand = c.get_num() * c.get_den(), floor_root;
    radicand <<= static_cast<mp_bitcnt_t>(2 * b);
    mpz_sqrt(floor_root.get_mpz_t(), radicand.get_mpz_t());
    const Rational scale = power_of_two(-b) / Rational(c.get_den());
    const double lo = oracle_round(Rational(floor_root) * scale), hi = oracle_round(Rational(floor_root + 1) * scale);
    if (!same_double(lo, hi)) continue;
    ++checked;
    EXPECT_TRUE(same_double(nearest_double(root), s * lo)) << root.to_string() << ": " << nearest_double(root) << " for " << s * lo;
  }
  EXPECT_GT(checked, 590);
  // +-2^-k, roots of (2^k x -+ 1)(x - 5) isolated by (-1, 1): an interval straddling 0
  for (long k = 1; k <= 1200; k += 7)
    for (int s : {1, -1}) {
      const mpz_class two_k = mpz_class(1) << static_cast<mp_bitcnt_t>(k);
      const AlgebraicNumber root = algebraic({mpz_class(5 * s), -(5 * two_k + s), two_k}, Rational(-1), Rational(1));
      EXPECT_TRUE(same_double(nearest_double(root), oracle_round(power_of_two(-k) * s))) << "2^-" << k;
    }
}

using test::peg_in_hole;

// An angle object of the JSON ({"half_turn", "t", "degrees"}): its degrees the oracle's.
void expect_angle_rounded(const json& angle, int* checked) {
  const double degrees = angle.at("degrees").get<double>();
  if (angle.at("half_turn").get<bool>()) {
    EXPECT_TRUE(same_double(degrees, 180.0));
    return;
  }
  const Rational t = parse_rational(angle.at("t").get<std::string>());
  const auto expected = expected_degrees(t, t);
  if (!expected) return;
  ++*checked;
  EXPECT_TRUE(same_double(degrees, *expected)) << angle.dump() << ": " << *expected;
}

// Every figure of the JSON of `space`: angles' degrees, critical angles' degrees and t.decimal
// (the oracle on the isolating interval narrowed until it decides), the slices' labels.
void expect_json_rounded(const SlicedSpace& space) {
  const json doc = json::parse(cli::sliced_json(space, false));
  int angles = 0, criticals = 0;
  for (const json& slice : doc.at("slices")) {
    expect_angle_rounded(slice.at("representative"), &angles);
    // the label's "slice at theta = D" is the representative's degrees, "%.2f"
    char text[64];
    std::snprintf(text, sizeof text, "%.2f\u00b0", slice.at("representative").at("degrees").get<double>());
    EXPECT_NE(slice.at("label").get<std::string>().find(std::string("slice at \u03b8 = ") + text), std::string::npos)
        << slice.at("label");
  }
  for (const json& crossing : doc.at("crossings"))
    for (const json& w : crossing.at("witnesses")) {
      expect_angle_rounded(w.at("left"), &angles);
      expect_angle_rounded(w.at("right"), &angles);
    }
  for (std::size_t i = 0; i < space.critical_angles().size(); ++i) {
    const CriticalAngle& c = space.critical_angles()[i];
    const json& j = doc.at("critical_angles").at(i);
    if (c.half_turn) {
      EXPECT_TRUE(same_double(j.at("degrees").get<double>(), 180.0));
      continue;
    }
    // the oracle on the exact t: a rational, or the interval narrowed by bisection on the
    // polynomial's sign (the root is simple in its isolating interval)
    Rational lo = c.t.lower, hi = c.t.upper;
    auto value = [&](const Rational& x) {
      Rational v = 0;
      for (std::size_t k = c.t.polynomial.size(); k-- > 0;) v = v * x + Rational(c.t.polynomial[k]);
      return sgn(v);
    };
    std::optional<double> degrees, decimal;
    if (c.t.exact) {
      degrees = expected_degrees(lo, lo);
      decimal = oracle_round(lo);
    }
    const int at_lo = c.t.exact ? 0 : value(lo);
    for (int round = 0; round < 3000 && !c.t.exact && !(degrees && decimal); ++round) {
      const Rational mid = (lo + hi) / 2;
      const int v = value(mid);
      if (v == 0) {
        lo = hi = mid;
      } else if (v == at_lo) {
        lo = mid;
      } else {
        hi = mid;
      }
      if (!degrees) degrees = expected_degrees(lo, hi);
      if (!decimal && same_double(oracle_round(lo), oracle_round(hi))) decimal = oracle_round(lo);
    }
    ASSERT_TRUE(degrees && decimal) << c.t.to_string("t");
    ++criticals;
    EXPECT_TRUE(same_double(j.at("degrees").get<double>(), *degrees)) << j.dump() << ": " << *degrees;
    EXPECT_TRUE(same_double(c.degrees, *degrees));
    EXPECT_TRUE(same_double(j.at("t").at("decimal").get<double>(), *decimal)) << j.dump() << ": " << *decimal;
  }
  EXPECT_GT(angles, 10);
  EXPECT_GE(criticals, 3);
}

TEST(SlicedFigures, JsonOfPegsInHolesCorrectlyRounded) {
  // a 10 mm peg in a 12 mm hole (examples/models/peg-in-hole.json), one in a 14.15 mm hole, and
  // a 1/3 mm peg in a 2/5 mm hole (tangents with long expansions)
  for (auto [s, h] : {std::pair{"5", "6"}, std::pair{"5", "7.075"}, std::pair{"1/6", "1/5"}}) {
    SCOPED_TRACE(std::string("peg ") + s + ", hole " + h);
    expect_json_rounded(SlicedSpace::build(peg_in_hole(s, h), "plate", "peg"));
  }
}

}  // namespace
}  // namespace hipair
