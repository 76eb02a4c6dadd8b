// The circle–segment stage's kernel numbers and range guard (docs/performance.md, session 29):
// kernel_interval (the interval a kernel number of the stage carries, computed without MPFR
// for numerators and denominators of at most 53 bits) against CGAL's own to_interval of the
// exact rational, double_bounds against lower_double and upper_double, and
// within_segment_filter_range (decided from bit sizes where they decide
// it) against the rounded comparison it replaces, on generated rationals. Session 41: the
// segment stage's carried line supports (oriented in place, the last edge of a line taking its
// support by move) and its applicability test on the lines' integer coefficients, against the
// circle–segment stage with CGAL's own supporting lines, on generated lines.
#include "algebra/exact_real.hpp"
#include "arrangement/arrangement.hpp"
#include "arrangement/circle_segment_traits.hpp"
#include "random_rationals.hpp"
#include "segment_stage_cases.hpp"

#include <hipair/rational.hpp>

#include <CGAL/mpq_class.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using test_numbers::canonical;
using test_numbers::random_integer;

// Rationals around the 53-bit boundary of the fast case, exact doubles, thirds, powers of two
// and their neighbours, huge and tiny values.
std::vector<Rational> generated_rationals(std::mt19937_64& random) {
  std::vector<Rational> values{Rational(0), Rational(1), Rational(-1), canonical(1, 3), canonical(-1, 7),
                               canonical(10, 1), canonical(23, 2), canonical(1, 1L << 52)};
  for (int i = 0; i < 6000; ++i) {
    const int num_bits = 1 + static_cast<int>(random() % 60), den_bits = 1 + static_cast<int>(random() % 60);
    values.push_back(canonical(random_integer(random, num_bits, true), random_integer(random, den_bits, false)));
  }
  for (int i = 0; i < 500; ++i) {   // exact doubles: 53-bit integers over powers of two
    mpz_class den = 1;
    den <<= static_cast<unsigned>(random() % 80);
    values.push_back(canonical(random_integer(random, 1 + static_cast<int>(random() % 53), true), den));
  }
  for (int i = 0; i < 300; ++i) {   // huge and tiny
    values.push_back(canonical(random_integer(random, 150 + static_cast<int>(random() % 300), true),
                               random_integer(random, 1 + static_cast<int>(random() % 40), false)));
    values.push_back(canonical(random_integer(random, 1 + static_cast<int>(random() % 40), true),
                               random_integer(random, 150 + static_cast<int>(random() % 300), false)));
  }
  return values;
}

TEST(CSpaceSegmentStage, KernelIntervalIsCgalsIntervalOnGeneratedRationals) {
  std::mt19937_64 random(29);
  const std::vector<Rational> values = generated_rationals(random);
  std::size_t fast_exact = 0, fast_inexact = 0, other = 0;
  for (const Rational& q : values) {
    const auto got = cspace::raw::kernel_interval(q);
    const auto want = CGAL::to_interval(q);
    ASSERT_EQ(got.first, want.first) << q.get_str();
    ASSERT_EQ(got.second, want.second) << q.get_str();
    const bool small = mpz_sizeinbase(q.get_num_mpz_t(), 2) <= 53 && mpz_sizeinbase(q.get_den_mpz_t(), 2) <= 53;
    if (!small)
      ++other;
    else if (want.first == want.second)
      ++fast_exact;
    else
      ++fast_inexact;
  }
  EXPECT_GE(fast_exact, 300u);
  EXPECT_GE(fast_inexact, 2000u);
  EXPECT_GE(other, 1000u);
}

TEST(CSpaceSegmentStage, DoubleBoundsAreLowerAndUpperDoubleOnGeneratedRationals) {
  std::mt19937_64 random(292);
  std::vector<Rational> values = generated_rationals(random);
  for (int i = 0; i < 200; ++i) {   // beyond the doubles' range: lower_double's clamping
    mpz_class huge = random_integer(random, 1100 + static_cast<int>(random() % 200), true);
    values.push_back(canonical(huge, 1));
    values.push_back(canonical(1, abs(huge)));
  }
  std::size_t apart = 0;
  for (const Rational& q : values) {
    const auto [lo, hi] = cspace::raw::double_bounds(q);
    ASSERT_EQ(lo, cspace::algebra::lower_double(q)) << q.get_str();
    ASSERT_EQ(hi, cspace::algebra::upper_double(q)) << q.get_str();
    if (lo != hi) ++apart;
  }
  EXPECT_GE(apart, 3000u);
}

TEST(CSpaceSegmentStage, RangeGuardIsTheRoundedComparisonOnGeneratedRationals) {
  std::mt19937_64 random(2929);
  std::vector<Rational> values = generated_rationals(random);
  std::size_t inside = 0, outside = 0, rounded_onto_the_limit = 0;
  for (int exponent : {-5, 0, 3, 52, 60, 200, 400}) {
    const Rational limit = exponent >= 0 ? canonical(mpz_class(1) << exponent, 1) : canonical(1, mpz_class(1) << -exponent);
    std::vector<Rational> cases = values;
    // around the limit: just below, just above (some round onto it), far and near
    for (int shift : {1, 10, 52, 53, 54, 60, 120}) {
      const Rational tiny = canonical(1, mpz_class(1) << shift);
      for (int sign : {1, -1}) {
        cases.push_back(Rational(sign * limit * (1 + tiny)));
        cases.push_back(Rational(sign * limit * (1 - tiny)));
        cases.push_back(Rational(sign * limit * (2 + tiny)));
        cases.push_back(Rational(sign * limit * (2 - tiny)));
        cases.push_back(Rational(sign * limit / 2 * (1 - tiny)));
      }
    }
    cases.push_back(limit);
    cases.push_back(Rational(-limit));
    for (int i = 0; i < 500; ++i) {   // numerators and denominators of sizes around the limit's
      const int den_bits = 1 + static_cast<int>(random() % 100);
      const int num_bits = std::max(1, den_bits + exponent - 3 + static_cast<int>(random() % 7));
      cases.push_back(canonical(random_integer(random, num_bits, true), random_integer(random, den_bits, false)));
    }
    for (const Rational& q : cases) {
      const bool want = std::abs(to_double(q)) <= std::ldexp(1.0, exponent);
      ASSERT_EQ(cspace::raw::within_segment_filter_range(q, exponent), want) << q.get_str() << " 2^" << exponent;
      (want ? inside : outside) += 1;
      if (want && abs(q) > limit) ++rounded_onto_the_limit;
    }
  }
  EXPECT_GE(inside, 5000u);
  EXPECT_GE(outside, 5000u);
  EXPECT_GE(rounded_onto_the_limit, 7u);
}

// Session 41 (trans41): build_circle_segment_arrangement with carried line supports (the
// segment flavour where segments_apply, now decided on the lines' integer coefficients: bit
// sizes, and -k0 / k against the top and left sides by cross products; each line's oriented
// support written in place and moved into the last of its edges) equals the same build without
// them (the circle–segment flavour, every support from CGAL's supporting line), field by field:
// vertices, edges, supports, box sides, faces. Generated lines through random points of a
// random non-dyadic box, lines along all four sides (the top and left ones make the segment
// flavour decline), repeated and overlapping lines (zero clearance: one line cut into many
// edges), at scales 2^-300 … 2^198 (coefficients across the segment filter's 2^400 limit).
TEST(CSpaceSegmentStage, CarriedSupportsEqualCgalLinesOnGeneratedLinesAndScales) {
  std::mt19937_64 random(4141);
  using cspace::IntegerPolynomial2;
  auto grid = [&](long range) { return test_segment_stage::grid_value(random, range); };
  // k0 + kx x + ky y = 0 through p and q, as a primitive-free integer polynomial times a
  // random non-zero integer (any sign: the stage must orient it)
  auto line_through = [&](const Rational& px, const Rational& py, const Rational& qx, const Rational& qy) {
    Rational kx = py - qy, ky = qx - px;
    Rational k0 = -(kx * px + ky * py);
    long factor = 1 + static_cast<long>(random() % 3);
    if (random() % 2) factor = -factor;
    return test_segment_stage::integer_line(k0, kx, ky, factor);
  };
  int built = 0, declined_sides = 0, shared_lines = 0;
  for (int instance = 0; instance < 60; ++instance) {
    SCOPED_TRACE("instance " + std::to_string(instance));
    const Rational scale = test_segment_stage::instance_scale(instance);
    const auto [x_lo, x_hi, y_lo, y_hi] = test_segment_stage::random_grid_box(random);
    cspace::raw::Box box{Rational(x_lo * scale), Rational(x_hi * scale), Rational(y_lo * scale), Rational(y_hi * scale)};
    std::vector<IntegerPolynomial2> curves;
    auto point_x = [&] { return Rational((x_lo + (x_hi - x_lo) * grid(1)) * scale); };
    auto point_y = [&] { return Rational((y_lo + (y_hi - y_lo) * grid(1)) * scale); };
    const int lines = 2 + static_cast<int>(random() % 6);
    for (int k = 0; k < lines; ++k) {
      Rational px = point_x(), py = point_y(), qx = point_x(), qy = point_y();
      if (px == qx && py == qy) qx += scale;
      curves.push_back(line_through(px, py, qx, qy));
      if (random() % 4 == 0) curves.push_back(curves.back());   // the same line twice
    }
    // lines along the sides: bottom and right keep the segment flavour, top and left decline it
    const int side = static_cast<int>(random() % 6);
    if (side < 4) {
      const Rational& ax = side == 1 ? box.x_hi : box.x_lo;
      const Rational& ay = side == 2 ? box.y_hi : box.y_lo;
      const bool vertical = side == 1 || side == 3;
      curves.push_back(line_through(ax, ay, vertical ? ax : Rational(ax + scale), vertical ? Rational(ay + scale) : ay));
      declined_sides += side >= 2;
    }
    // a line crossing all the others (many edges on one carried support)
    curves.push_back(line_through(box.x_lo, point_y(), box.x_hi, point_y()));
    std::vector<std::vector<cspace::ValidityClause>> validity(curves.size());
    std::vector<std::vector<std::pair<Rational, Rational>>> windows;
    cspace::raw::Options carried, cgal_lines;
    cgal_lines.carry_line_supports = false;
    const cspace::raw::Arrangement p = cspace::raw::build_circle_segment_arrangement(box, curves, validity, windows, carried);
    const cspace::raw::Arrangement q = cspace::raw::build_circle_segment_arrangement(box, curves, validity, windows, cgal_lines);
    test_segment_stage::expect_same_arrangement(p, q);
    if (HasFatalFailure()) return;
    std::vector<int> edges_of(curves.size(), 0);
    for (std::size_t e = 0; e < p.edges.size(); ++e) {
      const cspace::raw::Edge& a = p.edges[e];
      if (a.support_curve != cspace::raw::none) ++edges_of.at(a.support_curve);
    }
    for (int n : edges_of) shared_lines += n >= 2;
    ++built;
  }
  EXPECT_EQ(built, 60);
  EXPECT_GE(declined_sides, 8);
  EXPECT_GE(shared_lines, 60);   // lines cut into two or more edges (moved into the last)
}

}  // namespace
}  // namespace hipair
