// Geneva pair under its 26 toleranced parameters: every Monte Carlo sample (each position a
// certified root) lies inside the certified band; the linearised band holds the envelope up to
// the linearisation error the analysis reports; the sampling is reproducible and does not
// depend on the number of threads.
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <filesystem>

#include "test_paths.hpp"

namespace hipair {
namespace {

std::filesystem::path geneva() { return std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json"; }

ToleranceOptions drive_phase(std::size_t samples, unsigned threads) {
  ToleranceOptions options;
  options.range = std::make_pair(Rational(12, 5), Rational(4));   // the pin in slot 1
  options.positions = 180;
  options.relative_accuracy = 0.5;
  options.monte_carlo = samples;
  options.seed = 20261124;
  options.threads = threads;
  return options;
}

TEST(ToleranceGeneva, CertifiedBandContainsEveryMonteCarloSample) {
  ToleranceResult result = analyze_tolerances(geneva(), drive_phase(400, 2));
  ASSERT_TRUE(result.monte_carlo);
  const MonteCarloSummary& mc = *result.monte_carlo;
  EXPECT_EQ(mc.outside_certified, 0u);
  EXPECT_EQ(mc.not_certified, 0u);
  std::size_t contact = 0;
  for (const VariationSample& s : result.samples) contact += s.contact;
  ASSERT_GE(contact, 30u);
  EXPECT_EQ(mc.evaluations, 400 * contact);
  for (const VariationSample& s : result.samples) {
    if (!s.contact) continue;
    ASSERT_TRUE(s.has_monte_carlo);
    EXPECT_LE(s.certified.lower, s.monte_carlo_min);
    EXPECT_GE(s.certified.upper, s.monte_carlo_max);
    EXPECT_LE(s.certified.lower, s.linear_lower);   // the linear band is inside (to its error)
    EXPECT_GE(s.certified.upper + mc.linearisation_error, s.linear_upper);
    EXPECT_GE(s.monte_carlo_min, s.linear_lower - mc.linearisation_error - 1e-12);
    EXPECT_LE(s.monte_carlo_max, s.linear_upper + mc.linearisation_error + 1e-12);
    EXPECT_LT(s.monte_carlo_min, s.monte_carlo_max);
  }
}

TEST(ToleranceGeneva, MonteCarloIsReproducibleAcrossThreadCounts) {
  ToleranceResult a = analyze_tolerances(geneva(), drive_phase(60, 1));
  ToleranceResult b = analyze_tolerances(geneva(), drive_phase(60, 2));
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (std::size_t k = 0; k < a.samples.size(); ++k) {
    EXPECT_EQ(a.samples[k].monte_carlo_min, b.samples[k].monte_carlo_min);
    EXPECT_EQ(a.samples[k].monte_carlo_max, b.samples[k].monte_carlo_max);
  }
  ToleranceOptions other = drive_phase(60, 2);
  other.seed = 7;
  ToleranceResult c = analyze_tolerances(geneva(), other);
  bool differs = false;
  for (std::size_t k = 0; k < a.samples.size(); ++k)
    differs = differs || a.samples[k].monte_carlo_max != c.samples[k].monte_carlo_max;
  EXPECT_TRUE(differs) << "another seed must give other samples";
}

}  // namespace
}  // namespace hipair
