// Interval jets (src/tolerance/jet.hpp) keep exact-zero partial derivatives exact. Generated
// tests: (1) every component of a + b, a - b, a * b, a / b is contained in the component of the
// previous form (zero-filled gradient, every product and sum widened by one ulp): equal or
// tighter, never looser; (2) on point jets, every component contains the exact rational value
// (GMP), so the tighter enclosures are still certified.
#include "tolerance/jet.hpp"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <limits>
#include <random>

namespace {

using hipair::kernels::Interval;
using IntervalJet = hipair::tolerance_detail::Jet<Interval>;

// The previous forms (before exact zeros were kept).
std::vector<Interval> old_combine(const IntervalJet& a, const Interval& fa, const IntervalJet& b, const Interval& fb) {
  std::size_t n = std::max(a.gradient.size(), b.gradient.size());
  std::vector<Interval> g(n, Interval(0));
  for (std::size_t i = 0; i < a.gradient.size(); ++i) g[i] = g[i] + a.gradient[i] * fa;
  for (std::size_t i = 0; i < b.gradient.size(); ++i) g[i] = g[i] + b.gradient[i] * fb;
  return g;
}
IntervalJet old_negation(const IntervalJet& a) {
  std::vector<Interval> g(a.gradient.size());
  for (std::size_t i = 0; i < g.size(); ++i) g[i] = a.gradient[i] * Interval(-1);
  return IntervalJet(-a.value, std::move(g));
}
IntervalJet old_sum(const IntervalJet& a, const IntervalJet& b) {
  std::size_t n = std::max(a.gradient.size(), b.gradient.size());
  std::vector<Interval> g(n, Interval(0));
  for (std::size_t i = 0; i < a.gradient.size(); ++i) g[i] = a.gradient[i];
  for (std::size_t i = 0; i < b.gradient.size(); ++i) g[i] = g[i] + b.gradient[i];
  return IntervalJet(a.value + b.value, std::move(g));
}
IntervalJet old_product(const IntervalJet& a, const IntervalJet& b) {
  return IntervalJet(a.value * b.value, old_combine(a, b.value, b, a.value));
}
IntervalJet old_quotient(const IntervalJet& a, const IntervalJet& b) {
  Interval q = a.value / b.value;
  Interval inverse = Interval(1) / b.value;
  return IntervalJet(q, old_combine(a, inverse, b, Interval(-(q * inverse))));
}

double random_double(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 5);
  std::uniform_real_distribution<double> u(-3, 3);
  switch (kind(rng)) {
    case 0: return 0.0;
    case 1: return -0.0;
    default: return u(rng);
  }
}
Interval random_interval(std::mt19937_64& rng, bool points) {
  std::uniform_int_distribution<int> kind(0, 9);
  double inf = std::numeric_limits<double>::infinity();
  int k = kind(rng);
  if (points || k >= 4) {
    double x = random_double(rng);
    if (points || k >= 7) return Interval::point(x);
    double y = random_double(rng);
    return Interval(std::min(x, y), std::max(x, y));
  }
  if (k == 0) return Interval(0);
  if (k == 1) return Interval(-inf, inf);
  if (k == 2) return Interval(random_double(rng), inf);
  return Interval(-0.0, 0.0);
}
IntervalJet random_jet(std::mt19937_64& rng, bool points) {
  std::uniform_int_distribution<int> length(0, 6);
  IntervalJet j(random_interval(rng, points));
  int n = length(rng);
  for (int i = 0; i < n; ++i) j.gradient.push_back(random_interval(rng, points));
  return j;
}

// x within y (NaN bounds of the old form count as "anything")
bool within(const Interval& x, const Interval& y) {
  bool lo = std::isnan(y.lo) || (!std::isnan(x.lo) && x.lo >= y.lo);
  bool hi = std::isnan(y.hi) || (!std::isnan(x.hi) && x.hi <= y.hi);
  return lo && hi;
}
void expect_within(const IntervalJet& x, const IntervalJet& y) {
  EXPECT_TRUE(within(x.value, y.value));
  ASSERT_EQ(x.gradient.size(), y.gradient.size());
  for (std::size_t i = 0; i < x.gradient.size(); ++i)
    EXPECT_TRUE(within(x.gradient[i], y.gradient[i]))
        << i << ": [" << x.gradient[i].lo << ", " << x.gradient[i].hi << "] vs [" << y.gradient[i].lo << ", "
        << y.gradient[i].hi << "]";
}

TEST(ToleranceJet, ExactZerosGiveEqualOrTighterEnclosuresThanThePreviousForm) {
  std::mt19937_64 rng(20261128);
  for (int trial = 0; trial < 50000; ++trial) {
    IntervalJet a = random_jet(rng, false), b = random_jet(rng, false);
    expect_within(a + b, old_sum(a, b));
    expect_within(a - b, old_sum(a, old_negation(b)));
    expect_within(a * b, old_product(a, b));
    expect_within(a / b, old_quotient(a, b));
  }
}

mpq_class exact(double x) { return mpq_class(x); }
bool contains(const Interval& x, const mpq_class& q) { return x.contains(q); }

TEST(ToleranceJet, PointJetsContainTheExactRationalDerivatives) {
  std::mt19937_64 rng(1128);
  for (int trial = 0; trial < 50000; ++trial) {
    IntervalJet a = random_jet(rng, true), b = random_jet(rng, true);
    IntervalJet sum = a + b, difference = a - b, product = a * b;
    std::size_t n = std::max(a.gradient.size(), b.gradient.size());
    auto ga = [&](std::size_t i) { return i < a.gradient.size() ? exact(a.gradient[i].lo) : mpq_class(0); };
    auto gb = [&](std::size_t i) { return i < b.gradient.size() ? exact(b.gradient[i].lo) : mpq_class(0); };
    mpq_class av = exact(a.value.lo), bv = exact(b.value.lo);
    for (std::size_t i = 0; i < n; ++i) {
      EXPECT_TRUE(contains(sum.gradient[i], ga(i) + gb(i)));
      EXPECT_TRUE(contains(difference.gradient[i], ga(i) - gb(i)));
      EXPECT_TRUE(contains(product.gradient[i], ga(i) * bv + gb(i) * av));
    }
    if (bv != 0) {
      IntervalJet quotient = a / b;
      for (std::size_t i = 0; i < n; ++i)
        EXPECT_TRUE(contains(quotient.gradient[i], (ga(i) * bv - gb(i) * av) / (bv * bv)));
    }
  }
}

}  // namespace
