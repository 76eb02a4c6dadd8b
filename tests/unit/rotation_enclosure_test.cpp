// Session 60 (perf60): cspace::rotation_enclosure (src/curves/contact_curves.cpp), the certified
// (cos, sin) of a part angle 2 atan(t) (+ pi on half-turn charts) over a chart interval t, computes
// each end's square, cosine and sine once, and a point t's once for both ends. The bounds must be
// those of the former form (four end squares, two cosines and two sines, kept below as the
// oracle) bit for bit, on generated points and intervals (both signs, across 0, the ends +-1,
// subnormal and signed-zero ends, beyond [-1, 1]), both chart kinds; and they must enclose the
// exact rational cos and sin at exact points of t (the ends, the middle and random interior points).
#include "curves/contact_curves.hpp"
#include "kernels/interval.hpp"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <vector>

namespace hipair {
namespace {

using kernels::Interval;

// The form before session 60 (every end's square and cosine computed twice), the oracle.
std::pair<Interval, Interval> former_rotation_enclosure(bool half_turn, const Interval& t) {
  Interval c, s;
  auto cosine = [](double u) { return (Interval(1) - Interval(u, u)) / (Interval(1) + Interval(u, u)); };
  auto sine = [](double v) { return (Interval(2) * Interval(v, v)) / (Interval(1) + Interval(v, v) * Interval(v, v)); };
  if (t.lo >= -1 && t.hi <= 1) {
    double u_lo = (t.lo <= 0 && t.hi >= 0) ? 0.0 : std::min((Interval(t.lo, t.lo) * Interval(t.lo, t.lo)).lo,
                                                          (Interval(t.hi, t.hi) * Interval(t.hi, t.hi)).lo);
    double u_hi = std::max((Interval(t.lo, t.lo) * Interval(t.lo, t.lo)).hi,
                           (Interval(t.hi, t.hi) * Interval(t.hi, t.hi)).hi);
    c = Interval(cosine(u_hi).lo, cosine(u_lo).hi);
    s = Interval(sine(t.lo).lo, sine(t.hi).hi);
  } else {
    Interval t2 = t * t;
    c = (Interval(1) - t2) / (Interval(1) + t2);
    s = (Interval(2) * t) / (Interval(1) + t2);
  }
  if (half_turn) {
    c = -c;
    s = -s;
  }
  return {c, s};
}

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

// `value` in [i.lo, i.hi], an infinite end bounding nothing (the general branch's enclosure of an
// interval across 0 beyond [-1, 1] is the whole line: its t * t is not a square's enclosure)
bool encloses(const Interval& i, const mpq_class& value) {
  if (std::isnan(i.lo) || std::isnan(i.hi)) return false;
  const bool above_lo = std::isinf(i.lo) ? i.lo < 0 : mpq_class(i.lo) <= value;
  const bool below_hi = std::isinf(i.hi) ? i.hi > 0 : value <= mpq_class(i.hi);
  return above_lo && below_hi;
}

// Generated chart intervals: points and intervals of every kind named above.
std::vector<Interval> generated_intervals() {
  std::mt19937_64 rng(60);
  std::vector<double> ends = {0.0, -0.0, 1.0, -1.0, 0.5, -0.5, std::nextafter(1.0, 0.0), std::nextafter(-1.0, 0.0),
                              std::nextafter(1.0, 2.0), 4.9406564584124654e-324, -4.9406564584124654e-324,
                              2.2250738585072014e-308, 1e-160, -1e-160, 1e-8, 3.0, -7.5, 1e150};
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-60, 0);
  for (int k = 0; k < 400; ++k) ends.push_back(unit(rng));
  for (int k = 0; k < 200; ++k) ends.push_back(std::ldexp(unit(rng), exponent(rng)));
  std::vector<Interval> out;
  for (double e : ends) out.emplace_back(e, e);   // points
  std::uniform_int_distribution<std::size_t> pick(0, ends.size() - 1);
  for (int k = 0; k < 3000; ++k) {
    double a = ends[pick(rng)], b = ends[pick(rng)];
    if (b < a) std::swap(a, b);
    out.emplace_back(a, b);
  }
  // narrow intervals (a cell of a deep grid): the ends one to a few doubles apart
  for (int k = 0; k < 500; ++k) {
    const double a = unit(rng);
    double b = a;
    for (int step = k % 4; step >= 0; --step) b = std::nextafter(b, 2.0);
    out.emplace_back(a, b);
  }
  return out;
}

TEST(RotationEnclosure, SameBoundsAsTheFormerFourProductForm) {
  int compared = 0;
  for (const Interval& t : generated_intervals())
    for (bool half_turn : {false, true}) {
      const auto [c, s] = cspace::rotation_enclosure(half_turn, t);
      const auto [c0, s0] = former_rotation_enclosure(half_turn, t);
      ASSERT_EQ(bits(c.lo), bits(c0.lo)) << "t = [" << t.lo << ", " << t.hi << "] half turn " << half_turn;
      ASSERT_EQ(bits(c.hi), bits(c0.hi)) << "t = [" << t.lo << ", " << t.hi << "] half turn " << half_turn;
      ASSERT_EQ(bits(s.lo), bits(s0.lo)) << "t = [" << t.lo << ", " << t.hi << "] half turn " << half_turn;
      ASSERT_EQ(bits(s.hi), bits(s0.hi)) << "t = [" << t.lo << ", " << t.hi << "] half turn " << half_turn;
      ++compared;
    }
  EXPECT_GT(compared, 8000);
}

TEST(RotationEnclosure, EnclosesTheExactCosineAndSine) {
  std::mt19937_64 rng(61);
  std::uniform_real_distribution<double> fraction(0.0, 1.0);
  int checked = 0, bounded = 0;   // bounded: both enclosures finite
  for (const Interval& t : generated_intervals()) {
    if (std::fabs(t.lo) > 1e100 || std::fabs(t.hi) > 1e100) continue;   // exact squares stay small
    std::vector<mpq_class> points = {mpq_class(t.lo), mpq_class(t.hi), (mpq_class(t.lo) + mpq_class(t.hi)) / 2};
    for (int k = 0; k < 3; ++k) {
      // an exact interior point: lo + f (hi - lo), f a double in [0, 1]
      points.push_back(mpq_class(t.lo) + mpq_class(fraction(rng)) * (mpq_class(t.hi) - mpq_class(t.lo)));
    }
    for (bool half_turn : {false, true}) {
      const auto [c, s] = cspace::rotation_enclosure(half_turn, t);
      const bool finite = std::isfinite(c.lo) && std::isfinite(c.hi) && std::isfinite(s.lo) && std::isfinite(s.hi);
      for (const mpq_class& x : points) {
        const mpq_class square = x * x;
        mpq_class exact_c = (1 - square) / (1 + square), exact_s = 2 * x / (1 + square);
        if (half_turn) {
          exact_c = -exact_c;
          exact_s = -exact_s;
        }
        ASSERT_TRUE(encloses(c, exact_c)) << "cos at t = " << x.get_d() << " of [" << t.lo << ", " << t.hi << "]";
        ASSERT_TRUE(encloses(s, exact_s)) << "sin at t = " << x.get_d() << " of [" << t.lo << ", " << t.hi << "]";
        ++checked;
        bounded += finite;
      }
    }
  }
  EXPECT_GT(checked, 40000);
  EXPECT_GT(bounded, 35000);
}

}  // namespace
}  // namespace hipair
