// The semantics of the model's distributions in the tolerance analysis (docs/tolerance.md
// "Distributions"), on 10 000 seeded draws per parameter: every draw inside the tolerance
// range (exact comparison), and the sample mean and variance equal to the truncated
// distribution's closed-form moments within bounds derived from the sample size.
#include "tolerance/sampling.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <numbers>

namespace hipair {
namespace {

using tolerance_detail::Distribution;

Parameter parameter(const char* name, Rational nominal, Rational lo, Rational hi, Parameter::Distribution kind,
                    std::optional<Rational> sigma = std::nullopt) {
  Parameter p;
  p.name = name;
  p.nominal = nominal;
  p.range = RationalInterval{nominal + lo, nominal + hi};
  p.distribution = kind;
  p.sigma = sigma;
  return p;
}

double phi(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2 * std::numbers::pi); }
double Phi(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

struct Moments {
  double mean, variance;
};
// A normal (mu, s) truncated to [a, b]: the closed forms.
Moments truncated(double mu, double s, double a, double b) {
  double al = (a - mu) / s, be = (b - mu) / s, z = Phi(be) - Phi(al);
  double r = (phi(al) - phi(be)) / z;
  return {mu + s * r, s * s * (1 + (al * phi(al) - be * phi(be)) / z - r * r)};
}

TEST(ToleranceDistribution, DrawsFollowTheStatedDistributions) {
  Model model;
  // default (no distribution): normal about the centre of [-0.01, 0.03], sigma = width / 6, truncated
  model.parameters.push_back(parameter("plain", Rational(5), Rational(-1, 100), Rational(3, 100), Parameter::Distribution::none));
  // uniform on an asymmetric range
  model.parameters.push_back(parameter("flat", Rational(2), Rational(-1, 50), Rational(0), Parameter::Distribution::uniform));
  // normal sigma 0.005 with an asymmetric tolerance [-0.02, 0.004]: about the nominal, truncated
  model.parameters.push_back(parameter("skew", Rational(10), Rational(-1, 50), Rational(1, 250), Parameter::Distribution::normal, Rational(1, 200)));
  // a range whose ends are not doubles (1/3): draws stay inside it exactly
  model.parameters.push_back(parameter("third", Rational(1), Rational(-1, 3), Rational(1, 3), Parameter::Distribution::uniform));
  model.parameters.push_back(parameter("fixed", Rational(7), Rational(0), Rational(0), Parameter::Distribution::none));
  std::vector<Distribution> ds = tolerance_detail::distributions(model);
  ASSERT_EQ(ds.size(), 5u);
  EXPECT_NEAR(ds[0].mean, 0.01, 1e-15);
  EXPECT_NEAR(ds[0].sigma, 0.04 / 6, 1e-15);
  EXPECT_NEAR(ds[1].mean, -0.01, 1e-15);
  EXPECT_NEAR(ds[1].sigma, 0.02 / std::sqrt(12.0), 1e-15);
  EXPECT_EQ(ds[2].mean, 0);
  EXPECT_NEAR(ds[2].sigma, 0.005, 1e-15);
  EXPECT_EQ(ds[4].kind, Distribution::Kind::fixed);
  EXPECT_EQ(ds[4].sigma, 0);

  const std::size_t N = 10000;
  std::vector<double> sum(5, 0), sum2(5, 0);
  std::vector<std::vector<double>> all(5);
  for (std::size_t k = 0; k < N; ++k) {
    std::vector<double> x = tolerance_detail::draw(ds, 42, k);
    for (std::size_t i = 0; i < 5; ++i) {
      const Parameter& p = model.parameters[i];
      Rational value = p.nominal + Rational(x[i]);
      ASSERT_GE(value, p.range.lo) << p.name << " draw " << k;   // never outside the box, exactly
      ASSERT_LE(value, p.range.hi) << p.name << " draw " << k;
      all[i].push_back(x[i]);
      sum[i] += x[i];
    }
  }
  std::vector<Moments> expected{truncated(0.01, 0.04 / 6, -0.01, 0.03),
                                {-0.01, 0.02 * 0.02 / 12},
                                truncated(0, 0.005, -0.02, 0.004),
                                {0, (2.0 / 3) * (2.0 / 3) / 12},
                                {0, 0}};
  for (std::size_t i = 0; i < 4; ++i) {
    double mean = sum[i] / N, var = 0;
    for (double v : all[i]) var += (v - mean) * (v - mean);
    var /= N - 1;
    double width = ds[i].hi - ds[i].lo, sd = std::sqrt(expected[i].variance);
    // The sample mean's standard error is sd / sqrt(N): 5 of them (two-sided p ~ 6e-7).
    EXPECT_NEAR(mean, expected[i].mean, 5 * sd / std::sqrt(double(N))) << model.parameters[i].name;
    // The sample variance's standard error is sqrt((mu4 - sd^4) / N) <= sqrt(mu4 / N), and
    // mu4 <= width^2 sd^2 for a distribution on a range of that width: 5 of them.
    EXPECT_NEAR(var, expected[i].variance, 5 * width * sd / std::sqrt(double(N))) << model.parameters[i].name;
  }
  // The asymmetric normal's truncation shifts its mean below the nominal (closed form ~ -0.0011).
  EXPECT_LT(sum[2] / N, -0.0008);
  for (double v : all[4]) EXPECT_EQ(v, 0);
  // Reproducible: the same seed and index give the same draw.
  EXPECT_EQ(tolerance_detail::draw(ds, 42, 17), tolerance_detail::draw(ds, 42, 17));
  EXPECT_NE(tolerance_detail::draw(ds, 43, 17), tolerance_detail::draw(ds, 42, 17));
}

TEST(ToleranceDistribution, FarTailTruncationStaysInside) {
  // sigma tiny against the range: the draws must still be inside and not collapse onto the mean.
  Model model;
  model.parameters.push_back(parameter("tail", Rational(0), Rational(0), Rational(1, 100), Parameter::Distribution::normal, Rational(1, 100000)));
  std::vector<Distribution> ds = tolerance_detail::distributions(model);
  double largest = 0;
  for (std::size_t k = 0; k < 2000; ++k) {
    double x = tolerance_detail::draw(ds, 1, k)[0];
    ASSERT_GE(x, 0);
    ASSERT_LE(x, 0.01);
    largest = std::max(largest, x);
  }
  // Half-normal with sigma 1e-5: the largest of 2000 is about 3.5 sigma.
  EXPECT_GT(largest, 2e-5);
  EXPECT_LT(largest, 6e-5);
}


// The certified bands' box (Distribution::box_lo/box_hi) contains the exact rational tolerance
// range, and the draws' range (sample_lo/sample_hi) lies inside it: exact comparisons on 2 000
// random ranges with denominators that are not powers of two (the ends' nearest doubles fall on
// either side of them), nominals far from 0 included.
TEST(ToleranceDistribution, BandBoxContainsTheExactRangeAndDrawsStayInside) {
  std::mt19937_64 random(12);
  std::uniform_int_distribution<long> numerator(1, 1000000), denominator(3, 99999), nominal(-100000, 100000);
  std::size_t below = 0, above = 0;   // how often the nearest double fell inside the range
  for (int trial = 0; trial < 2000; ++trial) {
    Rational lo(-numerator(random), denominator(random)), hi(numerator(random), denominator(random));
    lo.canonicalize();
    hi.canonicalize();
    Rational n(nominal(random), 7);
    n.canonicalize();
    Model model;
    model.parameters.push_back(parameter("p", n, lo, hi, Parameter::Distribution::uniform));
    Distribution d = tolerance_detail::distributions(model)[0];
    Rational exact_lo = model.parameters[0].range.lo - n, exact_hi = model.parameters[0].range.hi - n;
    ASSERT_LE(Rational(d.box_lo), exact_lo) << trial;
    ASSERT_GE(Rational(d.box_hi), exact_hi) << trial;
    ASSERT_GE(Rational(d.sample_lo), exact_lo) << trial;
    ASSERT_LE(Rational(d.sample_hi), exact_hi) << trial;
    // Outward by at most one ulp: nextafter towards the range lands inside it.
    ASSERT_GT(Rational(std::nextafter(d.box_lo, INFINITY)), exact_lo) << trial;
    ASSERT_LT(Rational(std::nextafter(d.box_hi, -INFINITY)), exact_hi) << trial;
    below += Rational(d.lo) > exact_lo;
    above += Rational(d.hi) < exact_hi;
  }
  // The hole this closes: the nearest doubles (d.lo, d.hi) leave part of the range out often.
  EXPECT_GT(below, 100u);
  EXPECT_GT(above, 100u);
}

}  // namespace
}  // namespace hipair
