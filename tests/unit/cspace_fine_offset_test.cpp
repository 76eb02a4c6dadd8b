// Plain rotating polygon pairs whose vertices are moved by 10^-k (hostile75 H1, session 75
// cliff75): two rotating parts of a triangle and a quadrilateral with small-integer vertices,
// a random subset of the coordinates moved by +-10^-k, k = 60 .. 110 (the offsets straddle
// 2^-256 = 10^-77). Such charts have degree <= 2 in y and coefficients far below the quadratic
// traits' 1024-bit limit, so every chart must be built on the quadratic traits (base75 sent a
// chart with two branches of a curve closer than doubles resolve, about 2^-52 of |y|, to CGAL's
// algebraic traits: > 120 s for four loops at k = 80); the cells match the unperturbed pair's
// count, and exact point location at random rational configurations agrees with the exact
// overlap oracle.
#include "cspace_oracle_sampling.hpp"
#include "random_rationals.hpp"
#include "test_seed.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <array>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace hipair {
namespace {

// a: the triangle (2, -1) (3, -5) (3, -3) about (-1, 2); b: the quadrilateral (-2, 6) (-1, 3)
// (4, 3) (3, 7) about (3, 1) (hostile75's rr-min pair)
constexpr std::array<std::array<int, 2>, 3> triangle{{{2, -1}, {3, -5}, {3, -3}}};
constexpr std::array<std::array<int, 2>, 4> quadrilateral{{{-2, 6}, {-1, 3}, {4, 3}, {3, 7}}};

std::string model_text(const std::vector<Rational>& c) {
  std::ostringstream out;
  auto loop = [&](std::size_t first, std::size_t n) {
    out << "[{\"start\": [\"" << c[first] << "\", \"" << c[first + 1] << "\"], \"edges\": [";
    for (std::size_t i = 1; i <= n; ++i) {
      const std::size_t k = first + 2 * (i % n);
      out << (i > 1 ? ", " : "") << "{\"line_to\": [\"" << c[k] << "\", \"" << c[k + 1] << "\"]}";
    }
    out << "]}]";
  };
  out << R"({"hipair": 1, "name": "fine-offset", "units": {"length": "mm", "angle": "rad"}, "parts": [)"
      << R"({"name": "a", "motion": {"rotation": {"pivot": ["-1", "2"]}}, "loops": )";
  loop(0, triangle.size());
  out << R"(}, {"name": "b", "motion": {"rotation": {"pivot": ["3", "1"]}}, "loops": )";
  loop(2 * triangle.size(), quadrilateral.size());
  out << R"(}], "pairs": [{"parts": ["a", "b"]}]})";
  return out.str();
}

std::vector<Rational> corners() {
  std::vector<Rational> c;
  for (const auto& p : triangle) c.insert(c.end(), {Rational(p[0]), Rational(p[1])});
  for (const auto& p : quadrilateral) c.insert(c.end(), {Rational(p[0]), Rational(p[1])});
  return c;
}

TEST(CSpaceFineOffset, PolygonPairsMovedBelowTwoToTheMinus256StayOnTheQuadraticTraits) {
  const std::vector<CSpace> base = CSpace::build_all(read_model(model_text(corners())));
  ASSERT_EQ(base.size(), 1u);
  const std::size_t base_cells = base[0].statistics().cells;
  std::mt19937_64 random(test::test_seed(75017));
  for (long k : {60L, 80L, 90L, 100L, 110L}) {
    std::vector<Rational> c = corners();
    const Rational offset = test_numbers::power_of_ten(-k);
    int moved = 0;
    for (Rational& v : c)
      if (random() % 2) {
        v += random() % 2 ? offset : Rational(-offset);
        ++moved;
      }
    if (moved == 0) c[0] -= offset;
    const std::string text = model_text(c);
    SCOPED_TRACE("k = " + std::to_string(k) + ", " + text);
    const Model model = read_model(text);
    const std::vector<CSpace> spaces = CSpace::build_all(model);
    ASSERT_EQ(spaces.size(), 1u);
    const CSpaceStatistics& s = spaces[0].statistics();
    EXPECT_EQ(s.quadratic_charts + s.circle_segment_charts, s.charts) << "a chart left to CGAL's algebraic traits";
    EXPECT_EQ(s.cells, base_cells);
    const test::OracleSampler sampler(model, spaces[0]);
    std::mt19937_64 points(random());
    for (int i = 0; i < 40; ++i) {
      const test::OracleSampler::Sample sample = sampler.next(points, {3, 32, 100003});
      sampler.expect_agrees(sample, sampler.where(sample));
    }
  }
}

}  // namespace
}  // namespace hipair
