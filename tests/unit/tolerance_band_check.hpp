// Shared pieces of the tolerance tests: the check of a tolerance analysis' certified band
// (tolerance_chain_test.cpp, parametric_ratchet_test.cpp): at every position in contact the band
// is bounded, holds the nominal value (the nominal vector is in the box) and every Monte Carlo
// value; none of the Monte Carlo evaluations left it (returns the number of positions in
// contact); `bounded` (a position with a finite certified band); `ScopedSwitch` (one of
// tolerance_detail's test switches set for a scope, restored after).
#pragma once

#include <hipair/kinematics.hpp>
#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

namespace hipair::test_band {

inline bool bounded(const VariationSample& s) {
  return s.contact && std::isfinite(s.certified.upper - s.certified.lower);
}

// The exact train `exact`'s position of part `output` at each bounded sample of `samples` (the
// analysis' samples; each one's driver must be a sample of `exact` too: a missing one is a test
// failure): visit(i, value, ulp) for samples[i], where ulp is the allowance of the exact engine's
// position, the exact root rounded to a double (within an ulp; 4 eps relative, absolute below 1).
template <class Visit>
void visit_exact_values(const KinematicsResult& exact, const std::string& output,
                        const std::vector<VariationSample>& samples, Visit&& visit) {
  const std::size_t index = static_cast<std::size_t>(
      std::find(exact.followers.begin(), exact.followers.end(), output) - exact.followers.begin());
  EXPECT_LT(index, exact.followers.size()) << output;
  if (index >= exact.followers.size()) return;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const VariationSample& sample = samples[i];
    if (!bounded(sample)) continue;
    auto at = std::find_if(exact.samples.begin(), exact.samples.end(),
                           [&](const KinematicSample& s) { return s.driver == sample.driver; });
    EXPECT_NE(at, exact.samples.end()) << "driver " << sample.driver;
    if (at == exact.samples.end()) continue;
    const double value = at->positions.at(index);
    EXPECT_TRUE(std::isfinite(value));
    visit(i, value, 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::fabs(value)));
  }
}

// Two analyses of one chain agree in their notes and in the certified sub-boxes they used, in all
// and per pair (the part of a bit-for-bit comparison the samples do not show).
inline void expect_same_notes_and_boxes(const ToleranceResult& a, const ToleranceResult& b) {
  EXPECT_EQ(a.notes, b.notes);
  EXPECT_EQ(a.certified_boxes, b.certified_boxes);
  EXPECT_EQ(a.chain.size(), b.chain.size());
  for (std::size_t s = 0; s < std::min(a.chain.size(), b.chain.size()); ++s)
    EXPECT_EQ(a.chain[s].certified_boxes, b.chain[s].certified_boxes) << "pair " << s;
}

// `ScopedSwitch on(tolerance_detail::chain_case_split(), 0);` sets the switch until `on` ends.
template <class T>
class ScopedSwitch {
 public:
  ScopedSwitch(T& slot, std::type_identity_t<T> value) : slot_(slot), saved_(slot) { slot_ = value; }
  ~ScopedSwitch() { slot_ = saved_; }
  ScopedSwitch(const ScopedSwitch&) = delete;
  ScopedSwitch& operator=(const ScopedSwitch&) = delete;

 private:
  T& slot_;
  T saved_;
};

inline std::size_t expect_certified_band_holds(const ToleranceResult& result) {
  std::size_t contact = 0;
  for (const VariationSample& s : result.samples) {
    if (!s.contact) continue;
    ++contact;
    EXPECT_TRUE(std::isfinite(s.certified.lower) && std::isfinite(s.certified.upper)) << s.driver;
    EXPECT_LE(s.certified.lower, s.nominal) << s.driver;
    EXPECT_GE(s.certified.upper, s.nominal) << s.driver;
    if (s.has_monte_carlo) {
      EXPECT_GE(s.monte_carlo_min, s.certified.lower) << s.driver;
      EXPECT_LE(s.monte_carlo_max, s.certified.upper) << s.driver;
    }
  }
  EXPECT_TRUE(result.monte_carlo.has_value());
  if (result.monte_carlo) EXPECT_EQ(result.monte_carlo->outside_certified, 0u);
  if (result.monte_carlo) EXPECT_EQ(result.monte_carlo->not_certified, 0u);
  return contact;
}

}  // namespace hipair::test_band
