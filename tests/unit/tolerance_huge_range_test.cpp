// Tolerance ranges beyond the doubles (session 50, hunt50): `hipair tolerance` on a model with a
// tolerance of 1e400 died of SIGFPE (round_to_double built a Rational of get_d()'s infinity, and
// GMP raises on that). On generated rationals of 10^280 ... 10^2000 (both signs, random
// mantissas): round_to_double's result is on the side asked (not below x when up, not above it
// when down; an infinity only beyond the doubles, the largest finite double towards zero), and
// distributions() refuses a parameter whose range overflows the doubles with a ModelError naming
// /parameters/NAME, accepting the same model with a range that fits.
#include "tolerance/sampling.hpp"
#include "random_rationals.hpp"

#include <hipair/error.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

namespace hipair {
namespace {

using tolerance_detail::distributions;
using tolerance_detail::round_to_double;

using test_numbers::power_of_ten;

// m / n x 10^k, m in [1, 10^6], n in [1, 1000], with a random sign
Rational huge(std::mt19937_64& rng, int k) {
  std::uniform_int_distribution<int> m(1, 1000000), n(1, 1000), sign(0, 1);
  Rational x = Rational(m(rng), n(rng)) * power_of_ten(k);
  x.canonicalize();
  return sign(rng) ? -x : x;
}

bool on_side(double d, const Rational& x, bool up) {
  if (std::isnan(d)) return false;
  if (std::isinf(d)) return up ? d > 0 : d < 0;
  return up ? Rational(d) >= x : Rational(d) <= x;
}

TEST(ToleranceHugeRange, RoundToDoubleKeepsItsSideBeyondTheDoubles) {
  std::mt19937_64 rng(50);
  constexpr double most = std::numeric_limits<double>::max();
  int checked = 0;
  for (int k : {280, 300, 305, 306, 307, 308, 309, 310, 320, 400, 1000, 2000})
    for (int round = 0; round < 8; ++round) {
      Rational x = huge(rng, k);
      bool beyond = abs(x) > Rational(most);
      for (bool up : {false, true}) {
        double d = round_to_double(x, up);
        EXPECT_TRUE(on_side(d, x, up)) << "x = " << x.get_str().substr(0, 40) << "... (10^" << k << "), up " << up;
        // finite whenever x is within the doubles; beyond them, the infinity only on x's side
        if (!beyond) EXPECT_TRUE(std::isfinite(d)) << "10^" << k;
        else EXPECT_EQ(std::isinf(d), up == (sgn(x) > 0)) << "10^" << k;
        ++checked;
      }
    }
  EXPECT_EQ(checked, 12 * 8 * 2);
}

Model model_with_tolerance(const Rational& tolerance) {
  Model m;
  m.name = "huge-tolerance";
  Parameter small;
  small.name = "small";
  small.nominal = Rational(8);
  small.range = RationalInterval{Rational(79, 10), Rational(81, 10)};
  m.parameters.push_back(small);
  Parameter wide;
  wide.name = "wide-one";
  wide.nominal = Rational(2);
  wide.range = RationalInterval{Rational(2) - tolerance, Rational(2) + tolerance};
  m.parameters.push_back(wide);
  return m;
}

TEST(ToleranceHugeRange, DistributionsRefuseRangesBeyondTheDoubles) {
  std::mt19937_64 rng(51);
  for (int k : {300, 305, 307, 308, 309, 310, 400, 1000}) {
    Rational t = abs(huge(rng, k));
    bool overflows = !std::isfinite(2 * t.get_d());
    try {
      auto ds = distributions(model_with_tolerance(t));
      EXPECT_FALSE(overflows) << "10^" << k << ": accepted";
      ASSERT_EQ(ds.size(), 2u);
      bool finite = std::isfinite(ds[1].box_lo) && std::isfinite(ds[1].box_hi);
      EXPECT_TRUE(finite) << "10^" << k;
      if (!finite) continue;   // (a Rational of an infinity raises SIGFPE)
      EXPECT_LE(Rational(ds[1].box_lo), -t);
      EXPECT_GE(Rational(ds[1].box_hi), t);
    } catch (const ModelError& e) {
      EXPECT_TRUE(overflows) << "10^" << k << ": refused: " << e.what();
      EXPECT_EQ(e.pointer(), "/parameters/wide-one") << e.what();
    }
  }
}

}  // namespace
}  // namespace hipair
