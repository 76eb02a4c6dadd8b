// Shared pieces of the tolerance tests: the check of a tolerance analysis' certified band
// (tolerance_chain_test.cpp, parametric_ratchet_test.cpp): at every position in contact the band
// is bounded, holds the nominal value (the nominal vector is in the box) and every Monte Carlo
// value; none of the Monte Carlo evaluations left it (returns the number of positions in
// contact); `bounded` (a position with a finite certified band); `ScopedSwitch` (one of
// tolerance_detail's test switches set for a scope, restored after).
#pragma once

#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <type_traits>

namespace hipair::test_band {

inline bool bounded(const VariationSample& s) {
  return s.contact && std::isfinite(s.certified.upper - s.certified.lower);
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
