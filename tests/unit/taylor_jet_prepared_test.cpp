// Jets of Taylor models (src/tolerance/jet.hpp, session 34): the prepared forms of the jets'
// gradient operations (combine, scaled, sum: the factor's constancy and linear range computed
// once per operation, sums in place) give bit for bit what the plain forms give, on generated
// operands: gradients of every length up to 7 with exact zeros, constants, empty and short
// coefficient vectors, remainders, negative zeros, wide, tiny (1e-300) and huge (1e300) values
// and unbounded factors. Session 39: the products over the models' supports (taylor_model.hpp
// taylor_detail::Support) give bit for bit what the dense products give, on generated sparse
// models of up to 90 coefficients (past the listed capacity too) at scales 2^-300 ... 2^300.
// Session 40: sums and differences of jets that are temporaries, made in their own storage,
// give bit for bit what the forms on const operands give (sum_plain, the dense product by -1).
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

// Sparse models: coefficient vectors of 0 ... 90 entries (the support listed up to
// Support::capacity = 64 of them), each entry an exact zero with a random density (none, 5 %,
// 30 %, all); values at scales 2^-300 ... 2^300, point intervals (zero widths), negative zeros,
// subnormals; in some trials unbounded or NaN constants, coefficients and remainders.
class SparseGenerator {
 public:
  explicit SparseGenerator(unsigned seed) : random_(seed) {}
  TaylorModel1 model(bool unbounded) {
    TaylorModel1 t;
    int kind = pick(10);
    t.constant = kind == 0 ? Interval(0) : value(unbounded);
    static const std::size_t lengths[] = {0, 1, 3, 8, 17, 30, 63, 64, 65, 90};
    std::size_t length = lengths[pick(10)];
    static const double densities[] = {0.0, 0.05, 0.3, 1.0};
    double density = densities[pick(4)];
    t.coefficients.assign(length, Interval(0));
    for (Interval& c : t.coefficients)
      if (std::uniform_real_distribution<double>(0, 1)(random_) < density) c = value(unbounded);
    t.remainder = pick(3) == 0 ? Interval(0) : value(unbounded);
    if (kind == 1) t.remainder = Interval(0);   // a constant when no coefficient is listed
    return t;
  }
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(random_); }

 private:
  double number() {
    int e = std::uniform_int_distribution<int>(-300, 300)(random_);
    double m = std::uniform_real_distribution<double>(-2.0, 2.0)(random_);
    switch (pick(20)) {
      case 0: return -0.0;
      case 1: return std::numeric_limits<double>::denorm_min() * static_cast<double>(pick(5) + 1);
      default: return std::ldexp(m, e);
    }
  }
  Interval value(bool unbounded) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    if (unbounded) {
      switch (pick(12)) {
        case 0: return Interval(-inf, inf);
        case 1: return Interval(number(), inf);
        case 2: return Interval(std::numeric_limits<double>::quiet_NaN(), number());
        default: break;
      }
    }
    if (pick(4) == 0) return Interval::point(number());   // zero width
    double a = number(), b = number();
    return Interval(std::min(a, b), std::max(a, b));
  }
  std::mt19937_64 random_;
};

// The jets' x f before session 39: exact_zero() first, then the dense product
TaylorModel1 dense_times(const TaylorModel1& x, const tolerance_detail::taylor_detail::Factor& f, bool f_finite) {
  if (f_finite && x.exact_zero()) return TaylorModel1(0);
  return tolerance_detail::taylor_detail::multiply_dense(x, f);
}

TEST(TaylorJetPrepared, ProductsOverTheSupportsEqualTheDenseProductsBitForBit) {
  namespace td = tolerance_detail::taylor_detail;
  SparseGenerator gen(39);
  int sparse = 0, dense = 0, constant = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    bool unbounded = trial % 6 == 0;
    TaylorModel1 a = gen.model(unbounded), b = gen.model(unbounded);
    if (trial % 11 == 0) b = a;   // a square
    const td::Factor fb = td::factor(b);
    td::Support sa;
    td::scan(a, sa);
    // what the scan answers is what the dense reads give
    ASSERT_EQ(sa.constant, a.is_constant()) << "trial " << trial;
    ASSERT_EQ(bits(sa.linear.lo), bits(a.linear_range().lo)) << "trial " << trial;
    ASSERT_EQ(bits(sa.linear.hi), bits(a.linear_range().hi)) << "trial " << trial;
    ASSERT_TRUE(same({td::multiply(a, fb)}, {td::multiply_dense(a, fb)})) << "multiply, trial " << trial;
    ASSERT_TRUE(same({a * b}, {td::multiply_dense(a, fb)})) << "operator*, trial " << trial;
    bool finite_b = jd::finite(b);
    ASSERT_TRUE(same({jd::times(a, fb, finite_b)}, {dense_times(a, fb, finite_b)})) << "jet times, trial " << trial;
    if (sa.constant || fb.constant) ++constant;
    else if (sa.listed && fb.support.listed && td::finite(a.constant) && td::finite(b.constant)) ++sparse;
    else ++dense;
  }
  // every branch taken often
  EXPECT_GT(sparse, 5000);
  EXPECT_GT(dense, 1000);
  EXPECT_GT(constant, 1000);
  // jets of sparse models: the prepared products against the dense ones
  for (int trial = 0; trial < 1500; ++trial) {
    bool unbounded = trial % 6 == 0;
    Jet<TaylorModel1> a(gen.model(unbounded)), b(gen.model(unbounded));
    a.gradient.resize(gen.pick(24));
    b.gradient.resize(gen.pick(24));
    for (TaylorModel1& g : a.gradient) g = gen.pick(3) == 0 ? TaylorModel1(0) : gen.model(unbounded);
    for (TaylorModel1& g : b.gradient) g = gen.pick(3) == 0 ? TaylorModel1(0) : gen.model(unbounded);
    const td::Factor fa = td::factor(b.value), fb = td::factor(a.value);   // a.gradient x b.value + b.gradient x a.value
    std::vector<TaylorModel1> reference(std::max(a.gradient.size(), b.gradient.size()), TaylorModel1(0));
    bool fa_finite = jd::finite(b.value), fb_finite = jd::finite(a.value);
    for (std::size_t i = 0; i < a.gradient.size(); ++i) reference[i] = dense_times(a.gradient[i], fa, fa_finite);
    for (std::size_t i = 0; i < b.gradient.size(); ++i) {
      TaylorModel1 t = dense_times(b.gradient[i], fb, fb_finite);
      if (reference[i].exact_zero()) reference[i] = t;
      else if (!t.exact_zero()) reference[i] = reference[i] + t;
    }
    Jet<TaylorModel1> product = a * b;
    ASSERT_TRUE(same(product.gradient, reference)) << "jet product, trial " << trial;
    ASSERT_TRUE(same({product.value}, {td::multiply_dense(a.value, td::factor(b.value))})) << "jet value, trial " << trial;
  }
}

// -x for one partial as the jets made it before session 40: scaled(x, -1) on the dense product
TaylorModel1 dense_negated(const TaylorModel1& x) {
  static const TaylorModel1 minus_one(-1);
  return dense_times(x, tolerance_detail::taylor_detail::factor(minus_one), true);
}
// a + b as the jets made it before session 40: the value by TaylorModel1's +, the partials by
// plus() (exact zeros give the other operand), the longer gradient's tail copied
Jet<TaylorModel1> reference_sum(const Jet<TaylorModel1>& a, const Jet<TaylorModel1>& b) {
  std::vector<TaylorModel1> g(std::max(a.gradient.size(), b.gradient.size()));
  for (std::size_t i = 0; i < g.size(); ++i) {
    if (i >= a.gradient.size()) g[i] = b.gradient[i];
    else if (i >= b.gradient.size()) g[i] = a.gradient[i];
    else if (a.gradient[i].exact_zero()) g[i] = b.gradient[i];
    else if (b.gradient[i].exact_zero()) g[i] = a.gradient[i];
    else g[i] = a.gradient[i] + b.gradient[i];
  }
  return Jet<TaylorModel1>(a.value + b.value, std::move(g));
}
Jet<TaylorModel1> reference_negated(const Jet<TaylorModel1>& a) {
  std::vector<TaylorModel1> g;
  for (const TaylorModel1& x : a.gradient) g.push_back(dense_negated(x));
  return Jet<TaylorModel1>(-a.value, std::move(g));
}
::testing::AssertionResult same_jet(const Jet<TaylorModel1>& a, const Jet<TaylorModel1>& b) {
  ::testing::AssertionResult value = same({a.value}, {b.value});
  if (!value) return value << " (value)";
  return same(a.gradient, b.gradient);
}

TEST(TaylorJetPrepared, SumsAndDifferencesOfTemporariesEqualTheConstFormsBitForBit) {
  Generator small(40);
  SparseGenerator sparse(40);
  int in_place = 0, constant_partials = 0, zero_partials = 0, longer_right = 0, unbounded = 0;
  for (int trial = 0; trial < 6000; ++trial) {
    bool allow_infinite = trial % 6 == 0;
    Jet<TaylorModel1> a, b;
    if (trial % 2 == 0) {   // short gradients of short models
      a = small.jet(allow_infinite);
      b = small.jet(allow_infinite);
    } else {                // up to 24 partials of sparse models of up to 90 coefficients
      a = Jet<TaylorModel1>(sparse.model(allow_infinite));
      b = Jet<TaylorModel1>(sparse.model(allow_infinite));
      a.gradient.resize(sparse.pick(24));
      b.gradient.resize(sparse.pick(24));
      for (TaylorModel1& g : a.gradient) g = sparse.pick(3) == 0 ? TaylorModel1(0) : sparse.model(allow_infinite);
      for (TaylorModel1& g : b.gradient) g = sparse.pick(3) == 0 ? TaylorModel1(0) : sparse.model(allow_infinite);
    }
    if (trial % 13 == 0) b = a;
    Jet<TaylorModel1> sum = reference_sum(a, b);
    Jet<TaylorModel1> negated_b = reference_negated(b);
    Jet<TaylorModel1> difference = reference_sum(a, negated_b);
    // the const forms (the templates) are the reference forms
    ASSERT_TRUE(same_jet(a + b, sum)) << "const +, trial " << trial;
    ASSERT_TRUE(same_jet(-b, negated_b)) << "const unary -, trial " << trial;
    ASSERT_TRUE(same_jet(a - b, difference)) << "const -, trial " << trial;
    // the in-place forms on temporaries
    auto copy = [](const Jet<TaylorModel1>& x) { return Jet<TaylorModel1>(x); };
    ASSERT_TRUE(same_jet(copy(a) + b, sum)) << "rvalue + const, trial " << trial;
    ASSERT_TRUE(same_jet(copy(a) + copy(b), sum)) << "rvalue + rvalue, trial " << trial;
    ASSERT_TRUE(same_jet(-copy(b), negated_b)) << "unary - rvalue, trial " << trial;
    ASSERT_TRUE(same_jet(copy(a) - b, difference)) << "rvalue - const, trial " << trial;
    ASSERT_TRUE(same_jet(copy(a) - copy(b), difference)) << "rvalue - rvalue, trial " << trial;
    ASSERT_TRUE(same_jet(a - copy(b), difference)) << "const - rvalue, trial " << trial;
    // longer chains, as the kernels write them: a * b - b * a + a
    Jet<TaylorModel1> chain = reference_sum(reference_sum(a * b, reference_negated(b * a)), a);
    ASSERT_TRUE(same_jet(a * b - b * a + a, chain)) << "chain, trial " << trial;
    for (const TaylorModel1& x : b.gradient) {
      if (x.exact_zero()) ++zero_partials;
      else if (x.is_constant()) ++constant_partials;
      else ++in_place;
    }
    if (b.gradient.size() > a.gradient.size()) ++longer_right;
    if (!jd::finite(a.value) || !jd::finite(b.value)) ++unbounded;
  }
  // every branch of the in-place forms taken often
  EXPECT_GT(in_place, 10000);
  EXPECT_GT(constant_partials, 1000);
  EXPECT_GT(zero_partials, 5000);
  EXPECT_GT(longer_right, 1000);
  EXPECT_GT(unbounded, 200);
}

}  // namespace
}  // namespace hipair
