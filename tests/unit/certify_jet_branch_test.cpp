// The tolerance verifier's first-order jets across atan2's branch cut (session 50, exact50b).
// The mean-value and monotonicity tests of tolerance_check.cpp take a jet's gradient as an
// enclosure of every difference quotient over the leaf. atan2(y, x) jumps by 2 pi where y
// changes sign with x < 0: there no finite gradient does, and until then the jet carried
// x / r^2, -y / r^2 anyway (atan2(p, -1) over p in [-0.1, 0.1] enclosed in [pi - 0.1, pi]).
// Generated boxes straddling the cut and boxes beside it; oracle: the certified difference
// quotient of the function's values at the box's ends and at points inside it.
#include "certify/tolerance_check.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>

namespace {

using namespace hipair;
using hipair::verify::Interval;
using hipair::verify::Jet;
using A = hipair::model_detail::Arithmetic<Jet>;

Interval at(const Rational& q) { return Interval(q); }
Interval atan2_at(const Rational& y, const Rational& x) {
  Interval r;
  mpfi_atan2(r.get(), at(y).get(), at(x).get());
  return r;
}
// Two enclosures have a common point.
bool meet(const Interval& a, const Interval& b) {
  Interval both;
  mpfi_intersect(both.get(), a.get(), b.get());
  return !mpfi_is_empty(both.get());
}

TEST(CertifyJetBranch, Atan2GradientEnclosesEveryDifferenceQuotient) {
  std::mt19937 random(50);
  auto fraction = [&](long scale) -> Rational { return Rational(1 + long(random() % 997), 997) * scale; };
  int straddling = 0;
  for (int trial = 0; trial < 40; ++trial) {
    // y over [lo, hi]; x = -a (left of the origin: the cut) or +a (beside it, the smooth side)
    bool cut = trial % 2 == 0;
    Rational lo = cut ? Rational(-fraction(1)) : fraction(1), hi = cut ? fraction(1) : Rational(lo + fraction(1));
    Rational x = cut ? Rational(-fraction(3)) : fraction(3);
    Interval box(lo);
    mpfi_put_q(box.get(), const_cast<mpq_ptr>(hi.get_mpq_t()));
    Jet f = A::atan2(Jet::variable(box, 0, 1), Jet(at(x)));
    straddling += cut && sgn(hi) > 0;
    SCOPED_TRACE("atan2(y, " + to_exact_string(x) + ") over y in [" + to_exact_string(lo) + ", " + to_exact_string(hi) + "]");
    std::vector<Rational> points{lo, hi, lo + (hi - lo) / 3, lo + 2 * (hi - lo) / 3};
    for (std::size_t i = 0; i < points.size(); ++i)
      for (std::size_t j = i + 1; j < points.size(); ++j) {
        if (sgn(points[i]) == 0 || sgn(points[j]) == 0) continue;   // on the cut itself: atan2(0, x < 0) = pi
        Interval quotient = (atan2_at(points[j], x) - atan2_at(points[i], x)) / at(points[j] - points[i]);
        EXPECT_TRUE(meet(quotient, f.partial(0))) << "points " << i << ", " << j;
        // and the values lie in the jet's value
        EXPECT_TRUE(meet(atan2_at(points[i], x), f.value));
      }
  }
  EXPECT_EQ(straddling, 20);
}

}  // namespace
