// The first_crossing scanner's set-up (src/cspace/cspace_queries.cpp, MotionScanner): the
// derivative coefficients i c_i and i (i - 1) c_i enclosed by cspace::enclose_multiple
// (src/cspace/angle_filter.hpp) in doubles where c_i is a double, instead of the enclosure of the
// rational product. Oracle: kernels::Interval::enclose of the exact product, bit for bit.
#include "cspace/angle_filter.hpp"

#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace hipair {
namespace {

TEST(CSpaceCrossingScanner, MultiplesEncloseAsTheRationalProduct) {
  std::mt19937_64 random(3302);
  std::uniform_real_distribution<double> unit(0, 1), sym(-1, 1);
  std::size_t compared = 0, inexact = 0;
  auto check = [&](const Rational& c, long m) {
    Rational product = c * m;
    kernels::Interval expected = kernels::Interval::enclose(product);
    kernels::Interval got = cspace::enclose_multiple(c, m);
    ASSERT_EQ(std::bit_cast<std::uint64_t>(got.lo), std::bit_cast<std::uint64_t>(expected.lo)) << c << " * " << m;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(got.hi), std::bit_cast<std::uint64_t>(expected.hi)) << c << " * " << m;
    ++compared;
    if (!std::isfinite(product.get_d()) || Rational(product.get_d()) != product) ++inexact;
  };
  for (int i = 0; i < 200000; ++i) {
    double d = 0;
    switch (random() % 7) {
      case 0: d = sym(random); break;                                                    // the path's coefficients
      case 1: d = sym(random) * std::pow(10.0, -300 + 600 * unit(random)); break;        // 1e-300 ... 1e300
      case 2: d = std::bit_cast<double>(random() & ~(std::uint64_t(0x7ff) << 52) | (std::uint64_t(1 + random() % 2046) << 52)); break;
      case 3: d = static_cast<double>(static_cast<long>(random() % 2001) - 1000) / 8; break;   // small, exact products
      case 4: d = std::ldexp(static_cast<double>((random() >> 11) | 1), -static_cast<int>(random() % 1100)); break;   // subnormal region
      case 5: d = std::numeric_limits<double>::max() * unit(random); break;                 // near the top
      case 6: d = std::ldexp(1.0, static_cast<int>(random() % 1800) - 900) * (random() % 2 ? 1 : -1); break;   // the guard's edges
    }
    if (!std::isfinite(d)) continue;
    long m = random() % 4 == 0 ? static_cast<long>(1 + random() % (1L << 21)) : static_cast<long>(1 + random() % 30);
    check(Rational(d), m);
    if (HasFatalFailure()) return;
  }
  // rationals that are no doubles, and 0
  for (int i = 0; i < 20000; ++i) {
    Rational c(mpz_class(static_cast<long>(random() % 2000001) - 1000000), mpz_class(static_cast<long>(1 + random() % 999999)));
    c.canonicalize();
    check(c, static_cast<long>(1 + random() % 30));
    if (HasFatalFailure()) return;
  }
  std::printf("enclose_multiple: %zu products compared, %zu not a double\n", compared, inexact);
  EXPECT_GT(inexact, compared / 4);
}

}  // namespace
}  // namespace hipair
