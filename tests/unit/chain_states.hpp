// Field-for-field comparison of the engine's chain states for tests (analyze_fast_paths_test,
// kinematics_kernel_strips_test): exact numbers as numbers and isolating intervals, doubles
// bit for bit; exact numbers with the same isolating intervals, or (`same_intervals` false) only
// as the same numbers with the same exactness.
#pragma once

#include "algebra/exact_real.hpp"
#include "kinematics/engine.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>

namespace hipair::test_chain {

using cspace::algebra::Real;

inline void expect_same_real(const Real& a, const Real& b, const std::string& where, bool same_intervals = true) {
  EXPECT_EQ(a.exact, b.exact) << where;
  // (a default Real, of a bound that does not exist, has no polynomial: compared as it is)
  if (!same_intervals && (a.exact || !a.polynomial.empty()) && (b.exact || !b.polynomial.empty())) {
    EXPECT_EQ(cspace::algebra::compare(a, b), 0) << where;
    return;
  }
  EXPECT_EQ(a.lower, b.lower) << where;
  EXPECT_EQ(a.upper, b.upper) << where;
  EXPECT_TRUE(a.polynomial == b.polynomial) << where;
}

inline void expect_same_state(const kinematics_detail::ChainState& a, const kinematics_detail::ChainState& b,
                              const std::string& where, bool same_intervals = true) {
  using namespace kinematics_detail;
  auto bits = [](double x) {
    std::uint64_t u;
    std::memcpy(&u, &x, sizeof u);
    return u;
  };
  auto same_bound = [&](const Bound& x, const Bound& y, const std::string& what) {
    EXPECT_EQ(x.exists, y.exists) << what;
    EXPECT_EQ(x.limit, y.limit) << what;
    EXPECT_EQ(x.at.piece, y.at.piece) << what;
    expect_same_real(x.at.value, y.at.value, what, same_intervals);
    EXPECT_EQ(x.contacts, y.contacts) << what;
  };
  EXPECT_EQ(a.driver_piece, b.driver_piece) << where;
  EXPECT_EQ(a.driver_value, b.driver_value) << where;
  EXPECT_EQ(bits(a.driver_unwrapped), bits(b.driver_unwrapped)) << where;
  EXPECT_EQ(a.jammed, b.jammed) << where;
  EXPECT_EQ(a.coarse, b.coarse) << where;
  EXPECT_EQ(a.jam_part, b.jam_part) << where;
  EXPECT_EQ(a.jam_reason, b.jam_reason) << where;
  EXPECT_EQ(a.jam_contacts, b.jam_contacts) << where;
  ASSERT_EQ(a.known_rates.size(), b.known_rates.size()) << where;
  for (std::size_t k = 0; k < a.known_rates.size(); ++k) {
    EXPECT_EQ(bits(a.known_rates[k].ratio), bits(b.known_rates[k].ratio)) << where;
    EXPECT_EQ(bits(a.known_rates[k].acceleration), bits(b.known_rates[k].acceleration)) << where;
  }
  ASSERT_EQ(a.parts.size(), b.parts.size()) << where;
  for (std::size_t k = 0; k < a.parts.size(); ++k) {
    const PartState &x = a.parts[k], &y = b.parts[k];
    std::string part = where + " part " + std::to_string(k);
    EXPECT_EQ(x.position.piece, y.position.piece) << part;
    expect_same_real(x.position.value, y.position.value, part, same_intervals);
    EXPECT_EQ(bits(x.unwrapped), bits(y.unwrapped)) << part;
    EXPECT_EQ(x.side, y.side) << part;
    EXPECT_EQ(x.contacts, y.contacts) << part;
    same_bound(x.lower, y.lower, part + " lower");
    same_bound(x.upper, y.upper, part + " upper");
    EXPECT_EQ(x.kind, y.kind) << part;
    EXPECT_EQ(x.pushed, y.pushed) << part;
    EXPECT_EQ(bits(x.push_distance), bits(y.push_distance)) << part;
    EXPECT_EQ(x.blocked_by, y.blocked_by) << part;
    EXPECT_EQ(x.channel, y.channel) << part;
  }
}

}  // namespace hipair::test_chain
