// cspace::PartialTerms (src/cspace/partial_terms.hpp), the premultiplied partial derivatives
// track_derivatives evaluates at every right-hand side of the simulator, against their oracle
// kernels::polynomial_partials: bit-for-bit equal (every bound of every partial) on generated
// polynomials (sparse and dense, degrees 0 ... 9 in each variable, coefficients up to 2^200,
// zeros) at generated points and boxes (points, narrow, wide, straddling 0, huge), in doubles and
// in double intervals; and track_derivatives with the terms on and off (switch
// cspace::partial_terms()) along walks on every edge of three example spaces: every field equal.
#include "cspace/partial_terms.hpp"
#include "cspace_test_support.hpp"
#include "kernels/implicit_curve.hpp"
#include "kernels/interval.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/edge_tracker.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

// kernels::Interval with the equality polynomial_partials needs (as track_derivatives' own)
struct Box : kernels::Interval {
  Box() = default;
  Box(int value) : kernels::Interval(value) {}                              // NOLINT(google-explicit-constructor)
  Box(const kernels::Interval& value) : kernels::Interval(value) {}         // NOLINT(google-explicit-constructor)
  friend bool operator==(const Box& a, const Box& b) { return a.lo == b.lo && a.hi == b.hi; }
};

// bit-for-bit (a NaN equals a NaN of the same bits; -0 differs from +0)
bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same(const Box& a, const Box& b) { return same(a.lo, b.lo) && same(a.hi, b.hi); }
std::string show(double a) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%a", a);
  return buffer;
}
std::string show(const Box& a) { return "[" + show(a.lo) + ", " + show(a.hi) + "]"; }

using Coefficients = std::vector<std::vector<mpz_class>>;

Coefficients generated_polynomial(std::mt19937_64& random) {
  Coefficients c(random() % 10);
  const int bits = static_cast<int>(random() % 4 == 0 ? 200 : 1 + random() % 40);
  const bool sparse = random() % 2 == 0;
  for (auto& row : c) {
    row.resize(random() % 10);
    for (mpz_class& a : row) {
      if (sparse && random() % 3 != 0) continue;   // zero
      a = 1;
      a <<= static_cast<unsigned long>(random() % static_cast<unsigned long>(bits));
      a -= mpz_class(static_cast<unsigned long>(random() >> 1));
      if (random() % 2 == 0) a = -a;
    }
  }
  return c;
}

double generated_double(std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(-1, 1);
  switch (random() % 5) {
    case 0: return 0.0;
    case 1: return unit(random);
    case 2: return unit(random) * std::pow(10.0, static_cast<double>(random() % 40) - 20);
    case 3: return std::ldexp(static_cast<double>(static_cast<int>(random() % 65) - 32), -3);   // exact small values
    default: return unit(random) * 1e3;
  }
}

Box generated_box(std::mt19937_64& random) {
  double a = generated_double(random);
  switch (random() % 4) {
    case 0: return Box(kernels::Interval::point(a));
    case 1: return Box(kernels::Interval(a, std::nextafter(a, INFINITY)));
    case 2: {
      double b = generated_double(random);
      return Box(kernels::Interval(std::min(a, b), std::max(a, b)));
    }
    default: {
      double w = std::abs(a) * 1e-9 + 1e-300;
      return Box(kernels::Interval(a - w, a + w));
    }
  }
}

TEST(CSpacePartialTerms, EqualPolynomialPartialsBitForBit) {
  std::mt19937_64 random(2311);
  auto identity = [](const auto& v) { return v; };
  std::size_t polynomials = 0, evaluations = 0, terms = 0;
  for (int p = 0; p < 600; ++p) {
    Coefficients c = generated_polynomial(random);
    std::vector<std::vector<double>> nearest(c.size());
    std::vector<std::vector<Box>> enclosed(c.size());
    for (std::size_t i = 0; i < c.size(); ++i)
      for (const mpz_class& a : c[i]) {
        nearest[i].push_back(a.get_d());
        enclosed[i].push_back(Box(kernels::Interval::enclose(mpq_class(a))));
      }
    const cspace::PartialTerms<double> in_doubles(nearest, identity);
    const cspace::PartialTerms<Box> in_boxes(enclosed, identity);
    terms += in_boxes.size();
    ++polynomials;
    for (int k = 0; k < 20; ++k, ++evaluations) {
      const std::string where = "polynomial " + std::to_string(p) + ", point " + std::to_string(k);
      double x = generated_double(random), y = generated_double(random);
      kernels::Partials<double> d = kernels::polynomial_partials(nearest, x, y, identity);
      kernels::Partials<double> e = in_doubles.all(x, y);
      ASSERT_TRUE(same(d.fx, e.fx) && same(d.fy, e.fy) && same(d.fxx, e.fxx) && same(d.fxy, e.fxy) &&
                  same(d.fyy, e.fyy))
          << where << ": fx " << show(d.fx) << " / " << show(e.fx) << ", fy " << show(d.fy) << " / " << show(e.fy)
          << ", fxx " << show(d.fxx) << " / " << show(e.fxx) << ", fxy " << show(d.fxy) << " / " << show(e.fxy)
          << ", fyy " << show(d.fyy) << " / " << show(e.fyy);
      ASSERT_TRUE(same(d.fy, in_doubles.fy(x, y))) << where;

      Box X = generated_box(random), Y = generated_box(random);
      kernels::Partials<Box> b = kernels::polynomial_partials(enclosed, X, Y, identity);
      kernels::Partials<Box> f = in_boxes.all(X, Y);
      ASSERT_TRUE(same(b.fx, f.fx) && same(b.fy, f.fy) && same(b.fxx, f.fxx) && same(b.fxy, f.fxy) &&
                  same(b.fyy, f.fyy))
          << where << " on " << show(X) << " x " << show(Y) << ": fx " << show(b.fx) << " / " << show(f.fx) << ", fy "
          << show(b.fy) << " / " << show(f.fy) << ", fxx " << show(b.fxx) << " / " << show(f.fxx) << ", fxy "
          << show(b.fxy) << " / " << show(f.fxy) << ", fyy " << show(b.fyy) << " / " << show(f.fyy);
      std::pair<Box, Box> first = in_boxes.first(X, Y);
      ASSERT_TRUE(same(b.fx, first.first) && same(b.fy, first.second)) << where << " (first)";
    }
  }
  EXPECT_GT(terms, polynomials);   // not all empty
  std::printf("%zu polynomials, %zu terms, %zu points and boxes\n", polynomials, terms, evaluations);
}


bool same(const CertifiedRange& a, const CertifiedRange& b) { return same(a.lower, b.lower) && same(a.upper, b.upper); }

// track_derivatives with the terms on and off, each with its own tracker, along one walk (small
// steps as in a Runge-Kutta step, jumps, abscissae beyond the ends): every answer equal.
TEST(CSpacePartialTerms, TrackDerivativesEqualTheirAnswersWithoutTheTerms) {
  std::mt19937_64 random(2312);
  std::size_t compared = 0, answered = 0;
  for (const test::SlidingPair& c : test::sliding_pairs) {
    const char* file = c.file;
    Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / file);
    CSpace space = CSpace::build(model, c.first, c.second);
    for (std::size_t e = 0; e < space.edges().size(); ++e) {
      std::optional<std::pair<double, double>> range = test::edge_x_range(space, e);
      if (!range) continue;
      const auto [lo, hi] = *range;
      EdgeTracker with, without;
      std::uniform_real_distribution<double> anywhere(lo, hi);
      double x = anywhere(random);
      for (int i = 0; i < 60; ++i) {
        const double width = hi - lo;
        std::uniform_real_distribution<double> step(-width * 1e-3, width * 1e-3);
        x = i % 7 == 6 ? anywhere(random) : x + step(random);
        if (i % 17 == 16) x = random() % 2 ? hi + width * 1e-12 : lo - width * 1e-12;
        auto [a, b] = test::on_and_off<&cspace::partial_terms>(
            random, [&](bool on) { return track_derivatives(space, EdgeId(e), x, on ? with : without); });
        const std::string where = std::string(file) + " edge " + std::to_string(e) + " x " + show(x);
        ASSERT_EQ(a.has_value(), b.has_value()) << where;
        ++compared;
        if (!a) continue;
        ++answered;
        ASSERT_TRUE(same(a->y, b->y) && same(a->dy, b->dy) && same(a->d2y, b->d2y) &&
                    same(a->coordinate_dy, b->coordinate_dy) && same(a->coordinate_d2y, b->coordinate_d2y))
            << where << ": y " << show(a->y.lower) << " / " << show(b->y.lower) << ", d2y " << show(a->d2y.lower)
            << " / " << show(b->d2y.lower);
      }
    }
  }
  EXPECT_GT(answered, compared / 2) << answered << " of " << compared;
  std::printf("%zu calls compared, %zu answered by the filter\n", compared, answered);
}

}  // namespace
}  // namespace hipair
