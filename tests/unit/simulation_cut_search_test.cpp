// The step's cut search (src/simulation/cut_search.hpp): the bracket of a held condition's change
// along the step, found with the violated condition's indicator proposing the probes instead of
// the former 50 halvings. On generated predicates (one change, several changes, a violation
// present from the start, indicators offset from the predicate, missing or noisy indicators) the
// bracket must have the bisection's property — lo is 0 or a probe the predicate holds at, hi a
// probe it fails at (or the given upper end), hi - lo <= width — and, for a single change, hold
// the change as the bisection's bracket (the oracle) does; with consistent indicators it takes
// far fewer probes than 50, and with misleading ones never more than 53.
#include "simulation/cut_search.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace hipair {
namespace {

using simulation::bracket_cut;
using simulation::CutBracket;
using simulation::CutProbe;

// A generated held condition along the step: violated on the union of `bad` intervals (closed at
// their left end); its indicator is `shape(u)` (0 at the first change, but for an offset).
struct Condition {
  std::vector<std::pair<double, double>> bad;
  std::function<double(double)> indicator;
  bool violated(double u) const {
    for (const auto& [a, b] : bad)
      if (u >= a && u < b) return true;
    return false;
  }
};

// The probe as simulation.cpp's: kind 1, indicator 1 of three (0 and 2: other conditions, held)
CutProbe probe_of(const Condition& c, double u, std::size_t& calls) {
  ++calls;
  CutProbe p;
  p.margins = {1.0 + u, c.indicator(u), 0.25};
  if (c.violated(u)) {
    p.kind = 1;
    p.which = 7;
    p.indicator = 1;
  }
  return p;
}

// the oracle: the former cut, 50 halvings of [0, hi]
std::pair<double, double> bisection(const Condition& c, double hi) {
  double lo = 0;
  for (int i = 0; i < 50; ++i) {
    double m = 0.5 * (lo + hi);
    if (c.violated(m)) hi = m;
    else lo = m;
  }
  return {lo, hi};
}

// the bracket's property; returns the bracket
CutBracket check_bracket(const Condition& c, double hi, const char* what, int index) {
  std::size_t calls = 0;
  CutProbe upper = probe_of(c, hi, calls);
  EXPECT_NE(upper.kind, 0) << what << " " << index;
  const double width = std::ldexp(hi, -50);
  CutBracket b = bracket_cut(hi, upper, width, [&](double u) { return probe_of(c, u, calls); });
  EXPECT_EQ(static_cast<std::size_t>(b.probes) + 1, calls) << what << " " << index;
  EXPECT_LE(0.0, b.lo) << what << " " << index;
  EXPECT_LT(b.lo, b.hi) << what << " " << index;
  EXPECT_LE(b.hi, hi) << what << " " << index;
  EXPECT_LE(b.hi - b.lo, width) << what << " " << index << " lo " << b.lo << " hi " << b.hi;
  EXPECT_TRUE(b.lo == 0 || !c.violated(b.lo)) << what << " " << index << " lo " << b.lo;
  EXPECT_TRUE(c.violated(b.hi)) << what << " " << index << " hi " << b.hi;
  EXPECT_EQ(b.at_hi.kind, 1) << what << " " << index;
  EXPECT_EQ(b.at_hi.which, 7u) << what << " " << index;
  return b;
}

TEST(SimulationCutSearch, OneChangeIsBracketedAsTheBisectionDoesWithFewProbes) {
  std::mt19937_64 random(20261130);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int total = 0, cases = 0, most = 0;
  for (int index = 0; index < 400; ++index) {
    const double hi = std::ldexp(0.5 + unit(random), -static_cast<int>(unit(random) * 30));
    const double root = hi * (index % 10 == 0 ? std::ldexp(unit(random), -40) : 0.001 + 0.998 * unit(random));
    // smooth indicators through the change: linear, curved, steep, with a scale of 1e-12..1e12
    const double scale = std::pow(10.0, -12 + 24 * unit(random));
    const double curve = 4 * unit(random) - 2;
    const int shape = index % 3;
    Condition c;
    c.bad = {{root, std::numeric_limits<double>::infinity()}};
    c.indicator = [=](double u) {
      double x = (root - u) / hi;
      if (shape == 0) return scale * x;
      if (shape == 1) return scale * x * (1 + curve * x * x) / (1 + std::abs(curve));
      return scale * std::expm1(3 * x);
    };
    CutBracket b = check_bracket(c, hi, "one change", index);
    int probes = b.probes;
    total += probes;
    most = std::max(most, probes);
    ++cases;
    // the oracle: the bisection's bracket holds the change, and so does this one (one change)
    auto [blo, bhi] = bisection(c, hi);
    ASSERT_TRUE(blo <= root && root <= bhi) << index;
    EXPECT_TRUE(b.lo <= root && root <= b.hi) << index << " root " << root << " [" << b.lo << ", " << b.hi << "]";
  }
  // the point of the search: about a fifth of the bisection's probes
  RecordProperty("mean_probes", std::to_string(double(total) / cases));
  RecordProperty("most_probes", std::to_string(most));
  EXPECT_LE(total, 12 * cases) << "mean probes " << double(total) / cases;
  EXPECT_LE(most, 20);
}

TEST(SimulationCutSearch, InconsistentMissingAndNoisyIndicatorsStillBracketTheChange) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int index = 0; index < 300; ++index) {
    const double hi = 0.25 + unit(random);
    const double root = hi * (0.001 + 0.998 * unit(random));
    const int kind = index % 4;
    const double offset = hi * std::ldexp(unit(random) - 0.5, -static_cast<int>(unit(random) * 45));
    Condition c;
    c.bad = {{root, INFINITY}};
    c.indicator = [=](double u) {
      if (kind == 0) return root + offset - u;                            // zero off the change
      if (kind == 1) return std::numeric_limits<double>::quiet_NaN();     // no indicator
      if (kind == 2) return u < root ? 1.0 : -1.0;                        // signs only
      return (root - u) + 1e-3 * std::sin(1e6 * u);                       // noisy
    };
    CutBracket b = check_bracket(c, hi, "inconsistent", index);
    EXPECT_TRUE(b.lo <= root && root <= b.hi) << index;
  }
}

// Indicators with the right signs but misleading values (the interpolation would crawl toward one
// end): never more probes than the bisection's 50 halvings and 3 (u = 0, ITP's spare, rounding).
TEST(SimulationCutSearch, MisleadingIndicatorsCostNoMoreThanTheBisection) {
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int index = 0; index < 200; ++index) {
    const double hi = 0.5 + unit(random);
    const double root = hi * (0.001 + 0.998 * unit(random));
    const bool high = index % 2 == 0;
    Condition c;
    c.bad = {{root, INFINITY}};
    c.indicator = [=](double u) {
      if (high) return u < root ? 1e300 : -(u - root) * 1e-300;
      return u < root ? (root - u) * 1e-300 : -1e300;
    };
    CutBracket b = check_bracket(c, hi, "misleading", index);
    EXPECT_LE(b.probes, 53) << index;
    EXPECT_TRUE(b.lo <= root && root <= b.hi) << index;
  }
}

TEST(SimulationCutSearch, SeveralChangesGiveABracketOfOneOfThem) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int index = 0; index < 300; ++index) {
    const double hi = 1;
    std::vector<double> ends;
    for (int k = 0; k < 2 + index % 5; ++k) ends.push_back(unit(random));
    std::sort(ends.begin(), ends.end());
    Condition c;
    for (std::size_t k = 0; k + 1 < ends.size(); k += 2) c.bad.push_back({ends[k], ends[k + 1]});
    c.bad.push_back({0.999999, INFINITY});   // violated at the upper end
    c.indicator = [ends](double u) {
      double v = 1;
      for (double e : ends) v *= (e - u) * 4;
      return v;
    };
    check_bracket(c, hi, "several", index);
  }
}

TEST(SimulationCutSearch, AViolationFromTheStartGivesTheBisectionsBracket) {
  for (int index = 0; index < 50; ++index) {
    const double hi = std::ldexp(1.0 + index / 50.0, -index % 20);
    Condition c;
    c.bad = {{0, INFINITY}};
    c.indicator = [](double u) { return -38767.3 - u; };
    CutBracket b = check_bracket(c, hi, "from the start", index);
    EXPECT_LE(b.probes, 2) << index;
    auto [blo, bhi] = bisection(c, hi);
    EXPECT_EQ(b.lo, blo) << index;
    EXPECT_EQ(b.hi, bhi) << index;
  }
}

}  // namespace
}  // namespace hipair
