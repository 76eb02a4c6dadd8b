// Jets of Taylor models (src/tolerance/jet.hpp, session 34): the prepared forms of the jets'
// gradient operations (combine, scaled, sum: the factor's constancy and linear range computed
// once per operation, sums in place) give bit for bit what the plain forms give, on generated
// operands: gradients of every length up to 7 with exact zeros, constants, empty and short
// coefficient vectors, remainders, negative zeros, wide, tiny (1e-300) and huge (1e300) values
// and unbounded factors.
#include "tolerance/jet.hpp"
#include "tolerance/taylor_model.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using kernels::Interval;
using tolerance_detail::Jet;
using tolerance_detail::TaylorModel1;
namespace jd = tolerance_detail::jet_detail;

class Generator {
 public:
  explicit Generator(unsigned seed) : random_(seed) {}

  Interval interval() {
    switch (pick(12)) {
      case 0: return Interval(0);
      case 1: return Interval(-0.0, -0.0);
      case 2: return Interval(-0.0, 0.0);
      case 3: {
        double inf = std::numeric_limits<double>::infinity();
        return pick(2) ? Interval(-inf, inf) : Interval(number(), inf);
      }
      case 4: return Interval::point(number());
      default: {
        double a = number(), b = number();
        return Interval(std::min(a, b), std::max(a, b));
      }
    }
  }
  TaylorModel1 model(bool allow_infinite) {
    TaylorModel1 t;
    int kind = pick(8);
    if (kind == 0) return TaylorModel1(0);   // exact zero, no coefficients
    t.constant = finite_or(allow_infinite);
    if (kind == 1) return t;                  // a constant
    std::size_t length = pick(9);
    t.coefficients.resize(length);
    for (Interval& c : t.coefficients) c = pick(3) == 0 ? Interval(0) : finite_or(allow_infinite);
    t.remainder = pick(3) == 0 ? Interval(0) : finite_or(allow_infinite);
    if (kind == 2) {   // zeros everywhere but with a coefficient vector: exact zero all the same
      t.constant = Interval(0);
      for (Interval& c : t.coefficients) c = Interval(0);
      t.remainder = Interval(0);
    }
    return t;
  }
  Jet<TaylorModel1> jet(bool allow_infinite) {
    Jet<TaylorModel1> j(model(allow_infinite));
    j.gradient.resize(pick(8));
    for (TaylorModel1& g : j.gradient) g = model(allow_infinite);
    return j;
  }
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(random_); }

 private:
  double number() {
    static const double scales[] = {1.0, 1e-3, 1e3, 1e-300, 1e300, 0.5};
    double scale = scales[pick(6)];
    return std::uniform_real_distribution<double>(-2.0, 2.0)(random_) * scale;
  }
  Interval finite_or(bool allow_infinite) {
    Interval x = interval();
    if (!allow_infinite && !(std::isfinite(x.lo) && std::isfinite(x.hi))) return Interval(1);
    return x;
  }
  std::mt19937_64 random_;
};

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

// Bit for bit the same (both bounds' bit patterns, NaNs included), coefficient counts too.
::testing::AssertionResult same(const std::vector<TaylorModel1>& a, const std::vector<TaylorModel1>& b) {
  if (a.size() != b.size()) return ::testing::AssertionFailure() << "gradient lengths " << a.size() << ", " << b.size();
  auto interval_same = [](const Interval& x, const Interval& y) { return bits(x.lo) == bits(y.lo) && bits(x.hi) == bits(y.hi); };
  for (std::size_t i = 0; i < a.size(); ++i) {
    const TaylorModel1& x = a[i];
    const TaylorModel1& y = b[i];
    bool equal = interval_same(x.constant, y.constant) && interval_same(x.remainder, y.remainder) &&
                 x.coefficients.size() == y.coefficients.size();
    for (std::size_t c = 0; equal && c < x.coefficients.size(); ++c) equal = interval_same(x.coefficients[c], y.coefficients[c]);
    if (!equal)
      return ::testing::AssertionFailure() << "partial " << i << ": constant [" << x.constant.lo << ", " << x.constant.hi
                                           << "] vs [" << y.constant.lo << ", " << y.constant.hi << "], "
                                           << x.coefficients.size() << " vs " << y.coefficients.size() << " coefficients";
  }
  return ::testing::AssertionSuccess();
}

TEST(TaylorJetPrepared, CombineScaledAndSumEqualThePlainFormsBitForBit) {
  Generator gen(34);
  int combined = 0, unbounded = 0;
  for (int trial = 0; trial < 6000; ++trial) {
    bool allow_infinite = trial % 5 == 0;
    Jet<TaylorModel1> a = gen.jet(allow_infinite), b = gen.jet(allow_infinite);
    TaylorModel1 fa = gen.model(allow_infinite), fb = gen.model(allow_infinite);
    if (trial % 7 == 0) fb = fa;   // the same factor on both sides
    ASSERT_TRUE(same(jd::combine(a, fa, b, fb), jd::combine_plain(a, fa, b, fb))) << "combine, trial " << trial;
    ASSERT_TRUE(same(jd::scaled(a, fa), jd::scaled_plain(a, fa))) << "scaled, trial " << trial;
    ASSERT_TRUE(same(jd::sum(a, b), jd::sum_plain(a, b))) << "sum, trial " << trial;
    // the jet operations built on them
    Jet<TaylorModel1> product = a * b, difference = a - b;
    ASSERT_TRUE(same(product.gradient, jd::combine_plain(a, b.value, b, a.value))) << "product, trial " << trial;
    ASSERT_TRUE(same(difference.gradient, jd::sum_plain(a, Jet<TaylorModel1>(-b.value, jd::scaled_plain(b, TaylorModel1(-1))))))
        << "difference, trial " << trial;
    ++combined;
    if (!jd::finite(fa) || !jd::finite(fb)) ++unbounded;
  }
  EXPECT_EQ(combined, 6000);
  EXPECT_GT(unbounded, 100);   // the unbounded factors' branch was taken
}

}  // namespace
}  // namespace hipair
