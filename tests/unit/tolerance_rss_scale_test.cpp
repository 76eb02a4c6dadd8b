// Session 64 (tol64, issue 12): the statistical band mean +- 3 sigma of the linearised variation
// (tolerance_detail::linear_bands) at every scale. Generated sensitivities s_i and sigmas
// sigma_i (seeded), the pairs multiplied by 10^k and 10^-k (k from -300 to 300: a model whose
// parameters are lengths of 1e-300 or 1e300 mm has sensitivities of 1e300 or 1e-300 per mm and
// sigmas of 1e-302 or 1e298 mm), so that each product s_i sigma_i is an ordinary number. Oracle:
// sqrt(sum (s_i sigma_i)^2) from the same doubles in MPFR at 256 bits; the band's half width
// within 8 n ulps of 3 times it. Until session 64 s_i^2 sigma_i^2 was a product of squares,
// which overflowed (band +-inf) or underflowed (+-0: the raw spur gear pair at 1e-300 mm).
#include "tolerance/sampling.hpp"
#include "tolerance/stage.hpp"

#include <gtest/gtest.h>
#include "test_seed.hpp"

#include <mpfr.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using tolerance_detail::Distribution;

double exact_deviation(const std::vector<double>& s, const std::vector<Distribution>& d) {
  mpfr_t sum, term;
  mpfr_init2(sum, 256);
  mpfr_init2(term, 256);
  mpfr_set_zero(sum, 1);
  for (std::size_t i = 0; i < s.size(); ++i) {
    mpfr_set_d(term, s[i], MPFR_RNDN);
    mpfr_mul_d(term, term, d[i].sigma, MPFR_RNDN);
    mpfr_sqr(term, term, MPFR_RNDN);
    mpfr_add(sum, sum, term, MPFR_RNDN);
  }
  mpfr_sqrt(sum, sum, MPFR_RNDN);
  const double result = mpfr_get_d(sum, MPFR_RNDN);
  mpfr_clear(sum);
  mpfr_clear(term);
  return result;
}

TEST(ToleranceRssScale, StatisticalBandIsTheSameAtEveryScale) {
  const std::uint64_t seed = test::test_seed(64);
  SCOPED_TRACE("HIPAIR_TEST_SEED=" + std::to_string(seed));
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.1, 10);
  int checked = 0;
  for (int round = 0; round < 200; ++round) {
    const std::size_t n = 1 + round % 26;
    std::vector<double> s0(n), sigma0(n);
    for (std::size_t i = 0; i < n; ++i) {
      s0[i] = (random() % 2 ? 1 : -1) * unit(random) * (random() % 5 == 0 ? 0 : 1);
      sigma0[i] = 0.01 * unit(random) * (random() % 7 == 0 ? 0 : 1);
    }
    for (int k : {0, 40, 150, 200, 290, 300, -40, -150, -200, -290, -300}) {
      std::vector<double> s(n);
      std::vector<Distribution> d(n);
      for (std::size_t i = 0; i < n; ++i) {
        s[i] = s0[i] * std::pow(10.0, k);
        d[i].sigma = sigma0[i] * std::pow(10.0, -k);
        d[i].kind = d[i].sigma > 0 ? Distribution::Kind::normal : Distribution::Kind::fixed;
        d[i].lo = -3 * d[i].sigma;
        d[i].hi = 3 * d[i].sigma;
      }
      VariationSample sample;
      sample.nominal = 1;
      tolerance_detail::linear_bands(sample, s, d);
      const double expected = 3 * exact_deviation(s, d);
      const double bound = 8.0 * static_cast<double>(n + 2) * std::numeric_limits<double>::epsilon() * (expected + 1);
      SCOPED_TRACE("round " + std::to_string(round) + ", n " + std::to_string(n) + ", scale 1e" + std::to_string(k));
      ASSERT_TRUE(std::isfinite(sample.rss_upper) && std::isfinite(sample.rss_lower));
      EXPECT_NEAR(sample.rss_upper - 1, expected, bound);
      EXPECT_NEAR(1 - sample.rss_lower, expected, bound);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 2200);
}

}  // namespace
}  // namespace hipair
