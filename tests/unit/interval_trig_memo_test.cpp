// The remembered interval sine and cosine (number_traits.hpp, session 30) give the bounds of
// MPFI itself (through_mpfi) on every argument: generated intervals, each asked several times, in
// an order that shares one end between different arguments, more distinct ones than the memo holds (16 384),
// and from two threads at once.
#include "model/parametric/number_traits.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>
#include <thread>
#include <vector>

namespace hipair {
namespace {

using kernels::Interval;

kernels::Interval direct_sin(const Interval& x) {
  return model_detail::number_detail::through_mpfi(x, [](mpfi_ptr r, mpfi_srcptr a) { mpfi_sin(r, a); });
}
kernels::Interval direct_cos(const Interval& x) {
  return model_detail::number_detail::through_mpfi(x, [](mpfi_ptr r, mpfi_srcptr a) { mpfi_cos(r, a); });
}

bool same_bits(const Interval& a, const Interval& b) {
  return std::bit_cast<std::uint64_t>(a.lo) == std::bit_cast<std::uint64_t>(b.lo) &&
         std::bit_cast<std::uint64_t>(a.hi) == std::bit_cast<std::uint64_t>(b.hi);
}

// Arguments: lows in [-8, 8] (and 0, -0), widths from 0 through a few ulps to several radians;
// each low used with several highs and each high with several lows.
std::vector<Interval> generated_arguments(unsigned seed, std::size_t count) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> low(-8.0, 8.0);
  std::uniform_int_distribution<int> kind(0, 5);
  std::vector<Interval> result;
  while (result.size() < count) {
    double lo = result.size() % 97 == 0 ? (result.size() % 2 ? 0.0 : -0.0) : low(random);
    for (int k = 0; k < 3; ++k) {
      double hi = lo;
      switch (kind(random)) {
        case 0: break;
        case 1: hi = std::nextafter(lo, 100.0); break;
        case 2: hi = lo + 1e-12 * (1 + k); break;
        case 3: hi = lo + 1e-3 * (1 + k); break;
        case 4: hi = lo + 0.7 * (1 + k); break;
        default: hi = lo + 4.0 + k; break;
      }
      result.push_back(Interval(lo, hi));
      // the same high with another low
      result.push_back(Interval(lo - 1e-6 * (1 + k), hi));
    }
  }
  return result;
}

// Every argument asked twice, in two passes, and the pool larger than the memo's capacity
// (16 384), so that hits, misses and the clearing are all taken.
int mismatches(unsigned seed) {
  std::vector<Interval> arguments = generated_arguments(seed, 20000);
  int wrong = 0;
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t i = 0; i < arguments.size(); ++i) {
      const Interval& x = arguments[pass == 0 ? i : (i * 7919) % arguments.size()];
      if (!same_bits(model_detail::number_detail::interval_sin(x), direct_sin(x))) ++wrong;
      if (!same_bits(model_detail::number_detail::interval_cos(x), direct_cos(x))) ++wrong;
      // a recent argument again (a hit)
      const Interval& y = arguments[i / 2];
      if (!same_bits(model_detail::number_detail::interval_sin(y), direct_sin(y))) ++wrong;
      if (!same_bits(model_detail::number_detail::interval_cos(y), direct_cos(y))) ++wrong;
    }
  return wrong;
}

TEST(IntervalTrigMemo, RememberedSinAndCosEqualMpfiOnGeneratedArguments) { EXPECT_EQ(mismatches(30), 0); }

TEST(IntervalTrigMemo, TwoThreadsEachGetMpfisBounds) {
  int wrong[2] = {0, 0};
  std::thread first([&] { wrong[0] = mismatches(31); });
  std::thread second([&] { wrong[1] = mismatches(32); });
  first.join();
  second.join();
  EXPECT_EQ(wrong[0], 0);
  EXPECT_EQ(wrong[1], 0);
}

}  // namespace
}  // namespace hipair
