// The fast paths of the kinematic analysis against their exact or uncached forms, on generated
// cases: compare() of real algebraic numbers (certified double bisection filter, equality of
// two roots of one polynomial by two signs) against the unfiltered exact comparison, and the
// engine's kept rates and coordinates against recomputing them.
#include "algebra/exact_real.hpp"
#include "kinematics/engine.hpp"
#include "chain_states.hpp"
#include "random_integers.hpp"
#include "test_paths.hpp"

#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <random>
#include <string>

namespace hipair {
namespace {

using cspace::algebra::Polynomial;
using cspace::algebra::Real;
namespace algebra = cspace::algebra;
using test_chain::expect_same_state;

Polynomial multiply(const Polynomial& a, const Polynomial& b) {
  Polynomial product(a.size() + b.size() - 1);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) product[i + j] += a[i] * b[j];
  return product;
}

// compare() as it was before the filters: separated intervals, else refinement of copies by
// exact canonical bisection, the gcd's Sturm count on the common part, and refinement until
// the intervals separate.
void bisect(Real& r) {
  Rational middle = (r.lower + r.upper) / 2;
  int s = algebra::sign_at(r.polynomial, middle);
  if (s == 0) {
    r.lower = r.upper = middle;
    r.exact = true;
  } else if (s == algebra::sign_at(r.polynomial, r.lower)) {
    r.lower = middle;
  } else {
    r.upper = middle;
  }
}

int reference_compare(const Real& a, const Real& b) {
  if (a.exact && b.exact) return cmp(a.lower, b.lower) < 0 ? -1 : cmp(a.lower, b.lower) > 0 ? 1 : 0;
  if (a.exact) return -b.compare(a.lower);
  if (b.exact) return a.compare(b.lower);
  if (a.upper <= b.lower) return -1;
  if (b.upper <= a.lower) return 1;
  Polynomial g = algebra::gcd(a.polynomial, b.polynomial);
  Rational lo = std::max(a.lower, b.lower), hi = std::min(a.upper, b.upper);
  if (algebra::degree(g) >= 1) {
    algebra::SturmSequence sturm(g);
    if (sturm.count(lo, hi) - (algebra::sign_at(g, hi) == 0 ? 1 : 0) > 0) return 0;
  }
  Real x = a, y = b;
  for (;;) {
    bisect(x);
    bisect(y);
    if (x.exact || y.exact) return reference_compare(x, y);
    if (x.upper <= y.lower) return -1;
    if (y.upper <= x.lower) return 1;
  }
}

// Roots of (b x^2 - a) and of (b x^2 - a - d) with d from 1 down to 2^-120 of a (closer than
// doubles resolve), of products sharing a factor (equal numbers from different polynomials),
// and the same root with overlapping isolating intervals of one polynomial (equal) next to an
// interval of a neighbouring root overlapping it (distinct): every pair compared both ways.
TEST(AnalyzeFastPaths, CompareFilterAgreesWithExactComparison) {
  gmp_randclass random(gmp_randinit_default);
  random.seed(20261128);
  std::size_t pairs = 0, equal = 0, beyond_doubles = 0;
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<Real> numbers;
    mpz_class a = random.get_z_bits(trial % 2 ? 64 : 12) + 2, b = random.get_z_bits(trial % 3 ? 20 : 8) + 1;
    int gap_bits = (trial * 7) % 121;   // relative gap 2^-gap_bits
    mpz_class scale = mpz_class(1) << gap_bits;
    // b x^2 - a and (b scale) x^2 - (a scale + a): roots sqrt(a/b) and sqrt(a/b (1 + 2^-gap))
    Polynomial p{-a, 0, b};
    Polynomial q = algebra::primitive_part(Polynomial{-(a * scale + a), 0, b * scale});
    Polynomial shared = multiply(p, Polynomial{mpz_class(trial + 3), mpz_class(-2)});   // (3 + t - 2 x) p
    Rational top = Rational(a + 1, b) + 2 + trial;
    for (const Polynomial& poly : {p, q, algebra::square_free_part(shared)})
      for (Real& root : algebra::real_roots(poly, Rational(-top), top)) numbers.push_back(root);
    // one polynomial, overlapping isolating intervals: the same positive root, and the
    // negative root with an interval reaching up past zero towards the positive one
    std::vector<Real> roots = algebra::real_roots(p, Rational(-top), top);
    ASSERT_EQ(roots.size(), 2u);
    Real negative = roots[0], positive = roots[1];
    if (!positive.exact) {
      Real narrow = positive;
      narrow.refine_to((positive.upper - positive.lower) / 1024);
      Real shifted = narrow;   // (lower of narrow, upper of positive): the same root
      shifted.upper = positive.upper;
      numbers.push_back(narrow);
      numbers.push_back(shifted);
      Real reaching = negative;   // (lower, midpoint of 0 and the positive root's lower end)
      if (!negative.exact && narrow.lower > 0) {
        reaching.upper = narrow.lower / 2;
        if (algebra::sign_at(p, reaching.upper) != 0) numbers.push_back(reaching);
      }
    }
    numbers.push_back(Real::from_rational(Rational(trial + 3, 2)));   // the rational root of `shared`
    for (const Real& x : numbers)
      for (const Real& y : numbers) {
        int expected = reference_compare(x, y);
        ASSERT_EQ(algebra::compare(x, y), expected) << x.description() << " vs " << y.description();
        ASSERT_EQ(algebra::compare(y, x), -expected);
        ++pairs;
        equal += expected == 0;
        beyond_doubles += expected != 0 && gap_bits > 60 && x.upper > y.lower && y.upper > x.lower;
      }
  }
  EXPECT_GT(pairs, 2000u);
  EXPECT_GT(equal, 400u);
  EXPECT_GT(beyond_doubles, 10u);
}

// step() keeps the rates it computed: the same as rates() recomputes for that state; and the
// cached coordinate of a position is the double of its value's approximate().
TEST(AnalyzeFastPaths, KeptRatesAndCoordinatesAreTheRecomputedOnes) {
  Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/ratchet.json");
  std::size_t driver = *model.find_part("wheel");
  using namespace kinematics_detail;
  Chain chain = build_chain(model, driver, {}, SliceMethod::kernels, {});
  std::vector<Interference> interference;
  const AxisLine& line = chain.parts[0].line;
  ChainState state = initial_state(chain, 0, Rational(0), 0.0, interference);
  ASSERT_FALSE(state.jammed);
  std::size_t kept = 0;
  for (int i = 1; i <= 120; ++i) {
    // t = tan(theta / 2) on the driver's first chart, theta up to 60 degrees in 0.5 degree steps
    double theta = i * std::numbers::pi / 360;
    Rational t(mpz_class(static_cast<long>(std::llround(std::tan(theta / 2) * 1048576.0))), mpz_class(1048576));
    t.canonicalize();
    ChainState next = step(chain, state, 0, t, theta);
    if (next.jammed) break;
    ASSERT_EQ(next.known_rates.size(), chain.parts.size());
    ChainState fresh = next;
    fresh.known_rates.clear();
    std::vector<Rates> recomputed = rates(chain, fresh);
    for (std::size_t k = 0; k < chain.parts.size(); ++k) {
      // bitwise the same doubles (NaN for an undefined ratio)
      EXPECT_EQ(std::isnan(recomputed[k].ratio), std::isnan(next.known_rates[k].ratio));
      if (!std::isnan(recomputed[k].ratio)) EXPECT_EQ(recomputed[k].ratio, next.known_rates[k].ratio);
      if (!std::isnan(recomputed[k].acceleration)) EXPECT_EQ(recomputed[k].acceleration, next.known_rates[k].acceleration);
      const AxisPosition& position = next.parts[k].position;
      const AxisLine& part_line = chain.parts[k].line;
      double first = coordinate(part_line, position), again = coordinate(part_line, position);
      EXPECT_EQ(first, part_line.coordinate(position.piece, position.value.approximate()));
      EXPECT_EQ(again, first);
    }
    ++kept;
    state = std::move(next);
  }
  EXPECT_GT(kept, 100u);
  (void)line;
}

// rate_of's fraction-free slopes (integer numerators and denominators, one canonicalisation per
// result) against the rational chain rule canonical at every operation, bitwise, on generated
// polynomials and points: bidegrees up to (4, 4), coefficients up to 2^120, points from
// integers to 200-bit rationals, dyadic 60-bit ones as rational_near gives, points where P_v
// vanishes, and the ratchet's own contact polynomials.
TEST(AnalyzeFastPaths, FractionFreeSlopesAreTheRationalOnes) {
  using namespace kinematics_detail;
  std::mt19937_64 random(20261130);
  auto integer = [&](int bits) {
    return test_random::random_sign(random, test_random::below_power_of_two(random, bits));
  };
  auto rational = [&]() {
    switch (random() % 5) {
      case 0: return Rational(integer(static_cast<int>(random() % 4)));   // small integers, zero
      case 1: {   // dyadic, as rational_near(., 60) gives
        Rational r(integer(61), mpz_class(1) << 60);
        r.canonicalize();
        return r;
      }
      default: {
        mpz_class den = integer(1 + static_cast<int>(random() % 200));
        if (den == 0) den = 7;
        Rational r(integer(1 + static_cast<int>(random() % 200)), den);
        r.canonicalize();
        return r;
      }
    }
  };
  auto same = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  auto check = [&](const IntegerPolynomial2& p, const Rational& u, const Rational& v, bool other_rotates, bool part_rotates,
                   std::size_t& singular) {
    CurveSlopes fast = contact_slopes(p, u, v, other_rotates, part_rotates);
    CurveSlopes exact = contact_slopes_rational(p, u, v, other_rotates, part_rotates);
    ASSERT_EQ(fast.singular, exact.singular) << "u=" << u << " v=" << v;
    if (exact.singular) {
      ++singular;
      return;
    }
    EXPECT_TRUE(same(fast.first, exact.first)) << fast.first << " vs " << exact.first << " u=" << u << " v=" << v;
    EXPECT_TRUE(same(fast.second, exact.second)) << fast.second << " vs " << exact.second << " u=" << u << " v=" << v;
    // without the second derivative: the same first one, the second left 0
    CurveSlopes first_only = contact_slopes(p, u, v, other_rotates, part_rotates, false);
    EXPECT_FALSE(first_only.singular);
    EXPECT_TRUE(same(first_only.first, exact.first)) << first_only.first << " vs " << exact.first;
    EXPECT_EQ(first_only.second, 0.0);
  };
  std::size_t cases = 0, singular = 0;
  for (int n = 0; n < 600; ++n) {
    IntegerPolynomial2 p;
    std::size_t rows = 1 + random() % 5, columns = 1 + random() % 5;
    int bits = 1 + static_cast<int>(random() % 120);
    p.coefficients.assign(rows, std::vector<mpz_class>(columns));
    for (auto& row : p.coefficients)
      for (mpz_class& c : row)
        if (random() % 4) c = integer(bits);
    for (int k = 0; k < 6; ++k) {
      check(p, rational(), rational(), random() % 2, random() % 2, singular);
      ++cases;
    }
  }
  // P_v = 0 at the point: (v - v0)^2 q(u) + r(u) has P_v(u, v0) = 0
  for (int n = 0; n < 60; ++n) {
    Rational v0 = rational();
    mpz_class vn = v0.get_num(), vd = v0.get_den();
    IntegerPolynomial2 p;
    p.coefficients.assign(3, std::vector<mpz_class>(3));
    for (std::size_t i = 0; i < 3; ++i) {
      mpz_class qi = integer(40), ri = integer(40);
      // (vd v - vn)^2 qi u^i + ri u^i
      p.coefficients[i][2] = vd * vd * qi;
      p.coefficients[i][1] = -2 * vd * vn * qi;
      p.coefficients[i][0] = vn * vn * qi + ri;
    }
    check(p, rational(), v0, random() % 2, random() % 2, singular);
    ++cases;
  }
  // the ratchet's contact polynomials at points of their chart pairs
  Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/ratchet.json");
  Chain chain = build_chain(model, *model.find_part("wheel"), {}, SliceMethod::kernels, {});
  const PairSlicer& slicer = *chain.slicers.at(0);
  slicer.slice(0, Rational(0), 0);   // generates the chart pair's first strip
  std::size_t real = 0;
  for (std::size_t o = 0; o < std::max<std::size_t>(1, slicer.other_charts().size()); ++o)
    for (std::size_t f = 0; f < slicer.follower_charts().size(); ++f)
      for (std::size_t feature = 0; feature < slicer.features().size(); ++feature) {
        const IntegerPolynomial2* p = slicer.polynomial(o, f, feature);
        if (!p) continue;
        for (int k = 0; k < 4; ++k) {
          Rational u(integer(61), mpz_class(1) << 60), v(integer(61), mpz_class(1) << 60);
          u.canonicalize();
          v.canonicalize();
          check(*p, u, v, true, true, singular);
          ++real;
        }
      }
  EXPECT_GT(singular, 60u);
  EXPECT_GT(real, 20u);
  EXPECT_GT(cases, 3600u);
}

// The state right of an event: non_strict_step reuses the bisection's strict step from the same
// state only when it was not stopped as coarse, and is then the non-strict step itself, field
// for field. Generated steps along the first chart of three examples' drivers: from states of a
// walk, and from those states with the followers moved by up to 0.05 rad, to driver values from
// 10^-6 to 0.6 rad ahead (strict steps that are and are not coarse).
TEST(AnalyzeFastPaths, NonStrictStepReusesOnlyAStrictStepThatWasNotCoarse) {
  using namespace kinematics_detail;
  std::mt19937_64 random(25);
  std::size_t coarse = 0, fine = 0;
  for (const char* name : {"ratchet.json", "geneva.json", "escapement.json"}) {
    Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/" + name);
    std::size_t driver = model.pairs.front().first;
    for (std::size_t candidate : {model.pairs.front().first, model.pairs.front().second})
      if (model.parts[candidate].motion.kind == Motion::Kind::rotation) {
        driver = candidate;
        break;
      }
    Chain chain = build_chain(model, driver, {}, SliceMethod::kernels, {});
    ASSERT_TRUE(chain.parts[0].line.rotation) << name;
    auto chart_value = [](double theta) {
      Rational t(mpz_class(static_cast<long>(std::llround(std::tan(theta / 2) * 1048576.0))), mpz_class(1048576));
      t.canonicalize();
      return t;
    };
    std::vector<Interference> interference;
    ChainState state = initial_state(chain, 0, Rational(0), 0.0, interference);
    double theta = 0;
    for (int i = 0; i < 40 && !state.jammed; ++i) {
      for (int k = 0; k < 4; ++k) {
        // from the walk's state, or from it with the followers moved by up to 0.05 rad (into
        // blocked space, some: a short strict step must then push them further than it allows)
        ChainState from = state;
        if (k % 2 == 1)
          for (std::size_t part = 1; part < from.parts.size(); ++part) {
            double shift = (static_cast<double>(random() % 1000) / 1000.0 - 0.5) * 0.1;
            double to_coordinate = from.parts[part].unwrapped + shift;
            if (!chain.parts[part].line.rotation) continue;
            from.parts[part].position = position_of_coordinate(chain.parts[part].line, Rational(to_coordinate));
            from.parts[part].unwrapped = to_coordinate;
            from.known_rates.clear();
          }
        double ahead = std::pow(10.0, -6.0 + (k % 2 ? 4.0 : 5.8) * static_cast<double>(random() % 1000) / 1000.0);
        double to = std::min(theta + ahead, 1.5);
        Rational t = chart_value(to);
        std::string where = std::string(name) + " from " + std::to_string(theta) + " to " + std::to_string(to);
        ChainState expected = step(chain, from, 0, t, to, false);
        ChainState strict = step(chain, from, 0, t, to, true);
        (strict.coarse ? coarse : fine) += 1;
        ChainState reused = non_strict_step(chain, from, 0, t, to, &strict);
        expect_same_state(reused, expected, where);
        ChainState taken = non_strict_step(chain, from, 0, t, to, nullptr);
        expect_same_state(taken, expected, where + " (no strict step)");
        if (HasFailure()) return;
      }
      theta += 0.03;
      state = step(chain, state, 0, chart_value(theta), theta, false);
    }
  }
  EXPECT_GT(coarse, 5u);
  EXPECT_GT(fine, 100u);
}

}  // namespace
}  // namespace hipair
