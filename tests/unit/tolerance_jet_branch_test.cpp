// The library's interval jets across atan2's branch cut (session 51, exact51; the verifier's
// jets were fixed in session 50, certify_jet_branch_test.cpp). The tolerance solver encloses a
// contact function over a box in mean-value form, F(c) + sum_i F_i(B) (B_i - c_i), and tightens
// the partials F_i(B) with the second-order jets; a model's parametric formula atan2(y, x) jumps
// by 2 pi where y changes sign with x < 0, and until then both jets carried x / r^2, -y / r^2
// there: atan2(p, -1) over p in [-0.1, 0.1] was enclosed in [pi - 0.1, pi + 0.1].
// Generated boxes of (y, x) straddling the cut and beside it (both variables); oracle: MPFI's
// atan2 at exact points of the box (their values, and the certified difference quotients along
// each variable), against the first-order jet's mean-value enclosure and partials and the
// second-order jet's gradient (or its refusal, NumericError, after which the solver stays at
// first order).
#include "model/parametric/number_traits.hpp"
#include "tolerance/hessian_jet.hpp"
#include "tolerance/jet.hpp"

#include <hipair/error.hpp>

#include <gtest/gtest.h>
#include <mpfi.h>

#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using kernels::Interval;
using IntervalJet = tolerance_detail::Jet<Interval>;
using tolerance_detail::HessianJet;

// MPFI enclosure (256 bits) of an expression of exact doubles
struct Enclosure {
  mpfi_t v;
  Enclosure() { mpfi_init2(v, 256); }
  Enclosure(const Enclosure&) = delete;
  Enclosure& operator=(const Enclosure&) = delete;
  ~Enclosure() { mpfi_clear(v); }
};
bool meets(const Enclosure& e, const Interval& a) {
  // [a.lo, a.hi] meets the enclosure
  return !(mpfr_cmp_d(&e.v->left, a.hi) > 0) && !(mpfr_cmp_d(&e.v->right, a.lo) < 0);
}
void atan2_at(Enclosure& r, double y, double x) {
  Enclosure a, b;
  mpfi_set_d(a.v, y);
  mpfi_set_d(b.v, x);
  mpfi_atan2(r.v, a.v, b.v);
}
// (atan2(y1, x1) - atan2(y0, x0)) / step, certified
void quotient(Enclosure& r, double y0, double x0, double y1, double x1, double step) {
  Enclosure f0, f1;
  atan2_at(f0, y0, x0);
  atan2_at(f1, y1, x1);
  mpfi_sub(r.v, f1.v, f0.v);
  mpfi_div_d(r.v, r.v, step);
}

TEST(ToleranceJetBranch, Atan2JetsEncloseEveryValueAndDifferenceQuotient) {
  std::mt19937 random(51);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int straddling = 0, refused = 0;
  for (int trial = 0; trial < 40; ++trial) {
    // y over [-a, b] (the cut when x < 0) or a box of y > 0; x over [-c - w, -c] or [c, c + w]
    bool cut = trial % 2 == 0;
    double a = 0.01 + 0.2 * unit(random), b = 0.01 + 0.2 * unit(random);
    double c = 0.5 + 2 * unit(random), w = 0.05 * unit(random);
    Interval y = cut ? Interval(-a, b) : Interval(a, a + b);
    Interval x = trial % 4 < 2 ? Interval(-c - w, -c) : Interval(c, c + w);
    bool on_cut = y.lo < 0 && y.hi > 0 && x.hi < 0;
    straddling += on_cut;
    std::array<double, 2> center{y.middle(), x.middle()};
    SCOPED_TRACE("atan2 over y in [" + std::to_string(y.lo) + ", " + std::to_string(y.hi) + "], x in [" +
                 std::to_string(x.lo) + ", " + std::to_string(x.hi) + "]");
    using A1 = model_detail::Arithmetic<IntervalJet>;
    IntervalJet f = A1::atan2(IntervalJet::variable(y, 0, 2), IntervalJet::variable(x, 1, 2));
    Interval at_center =
        model_detail::Arithmetic<Interval>::atan2(Interval::point(center[0]), Interval::point(center[1]));
    // the mean-value enclosure over the box: F(c) + F_y(B) (y - c_y) + F_x(B) (x - c_x)
    Interval mean_value = at_center + f.partial(0) * (y - Interval::point(center[0])) +
                          f.partial(1) * (x - Interval::point(center[1]));
    std::vector<double> ys{y.lo, y.hi, y.lo + 0.3 * y.width(), y.lo + 0.7 * y.width()};
    std::vector<double> xs{x.lo, x.hi, x.lo + 0.5 * x.width()};
    for (double py : ys)
      for (double px : xs) {
        if (py == 0) continue;   // on the cut itself atan2(0, x < 0) = pi
        Enclosure v;
        atan2_at(v, py, px);
        EXPECT_TRUE(meets(v, f.value)) << "value at (" << py << ", " << px << ")";
        EXPECT_TRUE(meets(v, mean_value)) << "mean-value form at (" << py << ", " << px << ")";
      }
    bool second_refused = false;
    HessianJet g;
    try {
      using A2 = model_detail::Arithmetic<HessianJet>;
      g = A2::atan2(HessianJet::variable(y, 0, 2), HessianJet::variable(x, 1, 2));
    } catch (const NumericError&) {
      second_refused = true;
    }
    refused += second_refused;
    // difference quotients along y (x fixed) and along x (y fixed)
    for (double px : xs)
      for (std::size_t i = 0; i < ys.size(); ++i)
        for (std::size_t j = i + 1; j < ys.size(); ++j) {
          Enclosure q;
          quotient(q, ys[i], px, ys[j], px, ys[j] - ys[i]);
          EXPECT_TRUE(meets(q, f.partial(0))) << "d/dy between y = " << ys[i] << ", " << ys[j];
          if (!second_refused) EXPECT_TRUE(meets(q, g.partial(0))) << "second-order d/dy";
        }
    for (double py : ys)
      for (std::size_t i = 0; i < xs.size(); ++i)
        for (std::size_t j = i + 1; j < xs.size(); ++j) {
          if (xs[j] == xs[i]) continue;
          Enclosure q;
          quotient(q, py, xs[i], py, xs[j], xs[j] - xs[i]);
          EXPECT_TRUE(meets(q, f.partial(1))) << "d/dx between x = " << xs[i] << ", " << xs[j];
          if (!second_refused) EXPECT_TRUE(meets(q, g.partial(1))) << "second-order d/dx";
        }
    // beside the cut the jets stay finite (the fix costs nothing there)
    if (!cut || x.lo > 0) {
      EXPECT_FALSE(second_refused);
      EXPECT_TRUE(std::isfinite(f.partial(0).lo) && std::isfinite(f.partial(0).hi));
    }
  }
  EXPECT_EQ(straddling, 10);
  EXPECT_EQ(refused, 10);
}

}  // namespace
}  // namespace hipair
