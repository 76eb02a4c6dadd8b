// BlockedCells' cell sides tabulated (session 74, tile74): a 2-D grid with whole tables (a whole
// space's few grids) computes its cells' sides cell_x / cell_y once, to its finest depth (at
// most depth 9), and reads them from the table after; every other grid, and every depth or index
// outside the table, computes them as before. The sides decide every blocked test and every
// culling window, so the table must hold the computed values bit for bit. Generated chart boxes
// (seeded: rational ends of many magnitudes, spans from 10^-300 to 10^300, boxes that are one
// point) and grid depths: the sides of a grid with whole tables against the same grid without,
// at every index of every depth to two below the finest (and a few beyond), plus indices
// outside the box; 1-D grids (no table) too.
#include "curves/contact_curves.hpp"
#include "oracle/blocked_tester.hpp"
#include "random_rationals.hpp"
#include "test_paths.hpp"
#include "test_seed.hpp"

#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <random>
#include <string>

namespace hipair {
namespace {

// A random rational of magnitude about 10^e (either sign), e in [-e_max, e_max].
Rational random_end(std::mt19937_64& random, int e_max) {
  const long e = static_cast<long>(random() % static_cast<unsigned long>(2 * e_max + 1)) - e_max;
  Rational value = test_numbers::random_rational(random, Rational(-1), Rational(1), 1000003) *
                   test_numbers::power_of_ten(e);
  value.canonicalize();
  return value;
}

// The same double, bit for bit (so -0.0 differs from 0.0, as a computed side would).
bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

TEST(BlockedCellsSides, TabulatedSidesAreTheComputedOnesBitForBit) {
  const std::filesystem::path geneva = std::filesystem::path(HIPAIR_EXAMPLES) / "geneva.json";
  const Model model = read_model_file(geneva);
  const cspace::PairAxes axes = cspace::pair_axes(model, *model.find_part("driver"), *model.find_part("wheel"));
  auto tester = std::make_shared<const cspace::BlockedTester>(model, axes);
  ASSERT_TRUE(tester->usable());
  std::mt19937_64 random(test::test_seed(7401));
  std::size_t compared = 0, boxes = 0;
  for (int c = 0; c < 120; ++c) {
    // ends: a random box of random magnitude; every fourth box a narrow one around a large end
    // (the scaled path of the sides), every tenth one point
    const int e_max = c % 3 == 0 ? 300 : 6;
    Rational a = random_end(random, e_max), b = random_end(random, e_max);
    if (c % 4 == 1) b = a + random_end(random, 2) * test_numbers::power_of_ten(-300);
    if (c % 10 == 7) b = a;
    if (b < a) std::swap(a, b);
    Rational ya = random_end(random, 6), yb = random_end(random, 6);
    if (yb < ya) std::swap(ya, yb);
    const cspace::ChartAxis x{cspace::ChartAxis::Kind::rotation, (c & 1) != 0, a, b};
    const cspace::ChartAxis y{cspace::ChartAxis::Kind::rotation, (c & 2) != 0, ya, yb};
    const int depth = 1 + static_cast<int>(random() % 11);   // 1 ... 11 (the table stops at 9)
    for (int dimension : {2, 1}) {
      SCOPED_TRACE("box " + std::to_string(c) + " dimension " + std::to_string(dimension) + " depth " +
                   std::to_string(depth));
      const cspace::BlockedCells plain(tester, x, y, dimension, depth);
      const cspace::BlockedCells whole(tester, x, y, dimension, depth, nullptr, true);
      ASSERT_TRUE(whole.whole_tables());
      ++boxes;
      for (int d = 0; d <= std::min(depth + 2, 12); ++d) {
        const long count = 1L << d;
        for (long k = -2; k <= count + 1; ++k) {
          const cspace::algebra::Interval px = plain.cell_x(d, k), wx = whole.cell_x(d, k);
          const cspace::algebra::Interval py = plain.cell_y(d, k), wy = whole.cell_y(d, k);
          ASSERT_TRUE(same_bits(px.lo, wx.lo) && same_bits(px.hi, wx.hi)) << "x side (" << d << ", " << k << ")";
          ASSERT_TRUE(same_bits(py.lo, wy.lo) && same_bits(py.hi, wy.hi)) << "y side (" << d << ", " << k << ")";
          ++compared;
        }
      }
    }
  }
  EXPECT_EQ(boxes, 240u);
  EXPECT_GT(compared, 100000u);
}

}  // namespace
}  // namespace hipair
