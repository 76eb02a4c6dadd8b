// The Taylor models' interval product (src/tolerance/taylor_model.hpp taylor_detail::times,
// session 71): for finite operands the two end products kept are chosen by the ends' signs
// (times_finite) instead of taking the least and greatest of all four; the result must be bit for
// bit kernels::Interval's product (and the exact zero of an exact-zero operand times a finite one).
// Generated operands (seed test_seed(71)): every sign class of both ends (negative, zero, positive,
// negative zeros, intervals straddling 0, points), magnitudes 2^-1074 ... 2^1023 (subnormal
// products, products that overflow to infinity), and unbounded or NaN ends, which take the general
// product. Oracle: kernels::operator* with the zero rule, compared on the bounds' bit patterns.
// Mutants that swap two end products of one sign class (e.g. low = a.lo * b.lo for a <= 0 <= b)
// fail it. It cannot fail on the base: there times() is that oracle.
#include "tolerance/taylor_model.hpp"

#include "test_seed.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace hipair {
namespace {

using kernels::Interval;

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

class Operands {
 public:
  explicit Operands(std::uint64_t seed) : random_(seed) {}
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(random_); }
  double number(bool with_special) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    switch (pick(with_special ? 24 : 20)) {
      case 0: return 0.0;
      case 1: return -0.0;
      case 2: return std::numeric_limits<double>::denorm_min() * static_cast<double>(pick(9) + 1) * (pick(2) ? 1 : -1);
      case 3: return std::numeric_limits<double>::max() * (pick(2) ? 1 : -1) / static_cast<double>(pick(3) + 1);
      case 20: return inf;
      case 21: return -inf;
      case 22: return std::numeric_limits<double>::quiet_NaN();
      case 23: return std::ldexp(1.0, 1023) * (pick(2) ? 1 : -1);
      default: {
        // a few exponents only, so that equal magnitudes and ties between end products occur
        static const int exponents[] = {-1074, -1060, -600, -300, -52, -1, 0, 1, 52, 300, 600, 1000, 1023};
        const int e = exponents[pick(13)];
        const double m = pick(4) == 0 ? static_cast<double>(pick(5)) : std::uniform_real_distribution<double>(0.0, 2.0)(random_);
        return std::ldexp(m, e) * (pick(2) ? 1 : -1);
      }
    }
  }
  Interval interval(bool with_special) {
    const double a = number(with_special);
    switch (pick(6)) {
      case 0: return Interval::point(a);
      case 1: return Interval(-std::fabs(a), std::fabs(a));   // straddling 0, symmetric
      default: {
        const double b = number(with_special);
        if (a != a || b != b) return Interval(a, b);   // a NaN end, as it comes
        return Interval(std::min(a, b), std::max(a, b));
      }
    }
  }

 private:
  std::mt19937_64 random_;
};

// The product before session 71: the exact zero rule, then kernels::Interval's product.
Interval reference(const Interval& a, const Interval& b) {
  namespace td = tolerance_detail::taylor_detail;
  const bool a_finite = std::isfinite(a.lo) && std::isfinite(a.hi), b_finite = std::isfinite(b.lo) && std::isfinite(b.hi);
  if ((td::zero(a) && b_finite) || (td::zero(b) && a_finite)) return Interval(0);
  return a * b;
}

TEST(ToleranceTaylorTimes, SignCaseProductsAreTheIntervalProductBitForBit) {
  namespace td = tolerance_detail::taylor_detail;
  Operands gen(test::test_seed(71));
  // sign classes of (a, b): negative, straddling, positive (by lo >= 0, hi <= 0)
  auto sign_class = [](const Interval& x) { return x.lo >= 0.0 ? 2 : (x.hi <= 0.0 ? 0 : 1); };
  std::size_t classes[3][3] = {};
  std::size_t finite = 0, special = 0, overflowed = 0, subnormal = 0;
  for (int trial = 0; trial < 400000; ++trial) {
    const bool with_special = trial % 8 == 0;
    const Interval a = gen.interval(with_special), b = gen.interval(with_special);
    const Interval want = reference(a, b);
    const Interval got = td::times(a, b);
    ASSERT_EQ(bits(got.lo), bits(want.lo)) << "trial " << trial << ": [" << a.lo << ", " << a.hi << "] x [" << b.lo << ", "
                                           << b.hi << "]: low " << got.lo << " vs " << want.lo;
    ASSERT_EQ(bits(got.hi), bits(want.hi)) << "trial " << trial << ": [" << a.lo << ", " << a.hi << "] x [" << b.lo << ", "
                                           << b.hi << "]: high " << got.hi << " vs " << want.hi;
    const bool both_finite = std::isfinite(a.lo) && std::isfinite(a.hi) && std::isfinite(b.lo) && std::isfinite(b.hi);
    if (both_finite) {
      ++finite;
      ++classes[sign_class(a)][sign_class(b)];
      if (std::isinf(want.lo) || std::isinf(want.hi)) ++overflowed;
      if (want.lo != 0.0 && std::fabs(want.lo) < std::numeric_limits<double>::min()) ++subnormal;
      ASSERT_EQ(bits(td::times_finite(a, b).lo), bits((a * b).lo)) << "trial " << trial;
      ASSERT_EQ(bits(td::times_finite(a, b).hi), bits((a * b).hi)) << "trial " << trial;
    } else {
      ++special;
    }
  }
  // every sign class of both operands met often, and the edges of the range
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_GT(classes[i][j], 5000u) << "sign classes " << i << ", " << j;
  EXPECT_GT(special, 10000u);
  EXPECT_GT(overflowed, 1000u);
  EXPECT_GT(subnormal, 1000u);
  EXPECT_GT(finite, 300000u);
}

}  // namespace
}  // namespace hipair
