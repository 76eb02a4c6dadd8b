// The blocked-space culler's core-pair test (curves/squared_distance.hpp, session 35): the
// relation of (ax - bx)^2 + (ay - by)^2 to a squared reach, as the plain interval expression
// decides it, and a difference's square bit for bit the interval product's. Generated operands:
// exact and signed zeros, points, straddling and one-signed intervals, unbounded ends, tiny
// (1e-300) and huge (1e300) values, products that overflow; reaches placed within a few units
// in the last place of the expression's ends (where the quick test and the full expression
// could disagree if either were wrong).
#include "curves/squared_distance.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace hipair {
namespace {

using kernels::Interval;

class Operands {
 public:
  explicit Operands(unsigned seed) : random_(seed) {}

  Interval interval() {
    const double inf = std::numeric_limits<double>::infinity();
    switch (pick(16)) {
      case 0: return Interval(0);
      case 1: return Interval(-0.0, -0.0);
      case 2: return Interval(-0.0, 0.0);
      case 3: return pick(2) ? Interval(-inf, inf) : Interval(number(), inf);
      case 4: return Interval(-inf, number());
      case 5: return Interval::point(number());
      case 6: return Interval(0.0, std::fabs(number()));
      case 7: return Interval(-std::fabs(number()), -0.0);
      default: {
        double a = number(), b = pick(3) == 0 ? a * (1 + 1e-15 * pick(5)) : number();
        return Interval(std::min(a, b), std::max(a, b));
      }
    }
  }
  double number() {
    static const double scales[] = {1.0, 1e-3, 1e3, 1e-300, 1e300, 0.5, 1e150, 1e-160};
    double scale = scales[pick(8)];
    return std::uniform_real_distribution<double>(-2.0, 2.0)(random_) * scale;
  }
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(random_); }

 private:
  std::mt19937_64 random_;
};

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }
bool same(const Interval& a, const Interval& b) { return bits(a.lo) == bits(b.lo) && bits(a.hi) == bits(b.hi); }

// The relation as the plain interval expression decides it (the culler's former code).
int plain_relation(const Interval& ax, const Interval& ay, const Interval& bx, const Interval& by, const Interval& r2) {
  Interval dx = ax - bx, dy = ay - by;
  Interval d = dx * dx + dy * dy;
  if (d.hi < r2.lo) return -1;
  return d.lo < r2.hi ? 0 : 1;
}

TEST(CullSquaredDistance, CorePairRelationIsThePlainExpressionsAtEveryScale) {
  namespace cd = cspace::cull_detail;
  Operands gen(3535);
  std::mt19937_64 random(7);
  int counts[3] = {0, 0, 0};
  for (int trial = 0; trial < 300000; ++trial) {
    // centres: at one scale, close together or apart, narrow or wide boxes
    static const double scales[] = {1.0, 1e-300, 1e300, 1e-3, 1e150, 1e-150, 40.0, 1e40};
    double scale = scales[gen.pick(8)];
    auto box = [&] {
      if (gen.pick(10) == 0) return gen.interval();   // zeros, unbounded ends, other scales
      double c = std::uniform_real_distribution<double>(-1.0, 1.0)(random) * scale;
      double w = gen.pick(4) == 0 ? 0.0 : std::uniform_real_distribution<double>(0.0, 0.3)(random) * scale;
      return Interval(c - w, c + w);
    };
    Interval ax = box(), ay = box(), bx = box(), by = box();
    // boxes touching on an axis: a difference's end exactly 0 (its outward rounding crosses 0)
    if (gen.pick(8) == 0) bx = Interval(std::min(bx.lo, ax.lo), ax.lo);
    if (gen.pick(8) == 0) by = Interval(ay.hi, std::max(by.hi, ay.hi));
    EXPECT_TRUE(same(cd::square_detail::squared_difference(ax, bx), (ax - bx) * (ax - bx))) << "trial " << trial;
    // a reach near one of the expression's ends (a few ulps either side), or anywhere
    Interval dx = ax - bx, dy = ay - by;
    Interval d = dx * dx + dy * dy;
    // the quick tests' own sums (curves/squared_distance.hpp): the sums of the rounded
    // differences' squares' ends, and the lower one's margin
    double xl = ax.lo - bx.hi, xh = ax.hi - bx.lo, yl = ay.lo - by.hi, yh = ay.hi - by.lo;
    double x_low, x_high, y_low, y_high;
    cd::square_detail::square_ends(xl, xh, x_low, x_high);
    cd::square_detail::square_ends(yl, yh, y_low, y_high);
    double anchors[] = {d.lo, d.hi, x_low + y_low, x_high + y_high,
                        x_low + y_low - ((std::fabs(x_low) + std::fabs(y_low)) * 0x1p-45 + 0x1p-1000)};
    double anchor = anchors[gen.pick(5)];
    if (!std::isfinite(anchor)) anchor = std::fabs(gen.number());
    for (int step = gen.pick(9) - 4; step != 0; step += step > 0 ? -1 : 1)
      anchor = step > 0 ? kernels::interval_detail::up(anchor) : kernels::interval_detail::down(anchor);
    Interval r2;
    switch (gen.pick(4)) {
      case 0: r2 = Interval::point(anchor); break;
      case 1: r2 = Interval(anchor, kernels::interval_detail::up(anchor)); break;
      case 2: r2 = Interval(kernels::interval_detail::down(anchor), anchor); break;
      default: {
        Interval reach = Interval::point(std::fabs(gen.number()));
        r2 = reach * reach;
      }
    }
    int fast = cd::squared_distance_relation(ax, ay, bx, by, r2), plain = plain_relation(ax, ay, bx, by, r2);
    ASSERT_EQ(fast, plain) << "trial " << trial << ": [" << ax.lo << ", " << ax.hi << "] [" << ay.lo << ", " << ay.hi
                           << "] [" << bx.lo << ", " << bx.hi << "] [" << by.lo << ", " << by.hi << "] against ["
                           << r2.lo << ", " << r2.hi << "]";
    ++counts[plain + 1];
  }
  // every answer met many times
  EXPECT_GT(counts[0], 10000);
  EXPECT_GT(counts[1], 10000);
  EXPECT_GT(counts[2], 10000);
}

}  // namespace
}  // namespace hipair
