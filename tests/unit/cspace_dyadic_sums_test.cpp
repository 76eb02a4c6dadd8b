// The crossing query's dyadic sums and its skip tests' product filter (src/cspace/dyadic.hpp;
// switches cspace::dyadic_sums() and cspace::offset_filter()):
//  - every sum, multiple sum and midpoint of generated rationals (dyadic of 1 ... 400 bits over
//    2^0 ... 2^600, zero, integers, sums that cancel or carry into an integer, and non-dyadic ones
//    that must go through GMP) is GMP's rational in GMP's canonical form, numerator and
//    denominator compared as integers;
//  - compare_product's sign is the exact sign of offset * r - s for generated dyadic and
//    non-dyadic offsets, rates of every magnitude and bounds at the exact product's double, a few
//    ulps around it, and far from it;
//  - first_crossing's answers with both switches on are those with both off, on the generated
//    motions of the path memo's test (the example spaces, the degenerate corpus' zero-clearance
//    pairs), over [0, 1], [0, a double] and [0, 2/3] (not dyadic: the GMP route);
//  - the simulator's runs (escapement, ratchet, cam follower) are bit for bit the runs with either
//    switch off.
#include "cspace/dyadic.hpp"
#include "cspace_motion_support.hpp"
#include "cspace_test_support.hpp"
#include "simulation_side_by_side.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

// a canonical rational: dyadic (most), an integer, zero, or over an odd or mixed denominator
Rational random_rational(std::mt19937_64& random) {
  const int kind = static_cast<int>(random() % 10);
  mpz_class num, den(1);
  const unsigned long bits = 1 + random() % (random() % 4 == 0 ? 400 : 60);
  // the numerator's bits from the generator, 64 at a time
  for (unsigned long done = 0; done < bits; done += 64) {
    num <<= 64;
    num += mpz_class(static_cast<unsigned long>(random()));
  }
  num >>= (64 - bits % 64) % 64;
  if (random() % 3 == 0) num <<= static_cast<unsigned long>(random() % 70);   // trailing zeros
  if (random() % 2 == 0) num = -num;
  if (kind == 0) return Rational(0);
  if (kind <= 6) {
    mpz_mul_2exp(den.get_mpz_t(), den.get_mpz_t(), random() % (random() % 4 == 0 ? 600 : 120));
  } else if (kind == 7) {
    den = 1;
  } else {
    den = mpz_class(static_cast<unsigned long>(3 + 2 * (random() % 1000)));
    if (kind == 9) den <<= static_cast<unsigned long>(random() % 80);
  }
  Rational r(num, den);
  r.canonicalize();
  return r;
}

bool same_form(const Rational& x, const Rational& y) {
  return mpz_cmp(mpq_numref(x.get_mpq_t()), mpq_numref(y.get_mpq_t())) == 0 &&
         mpz_cmp(mpq_denref(x.get_mpq_t()), mpq_denref(y.get_mpq_t())) == 0;
}

TEST(CSpaceDyadicSums, SumsAreGmpsCanonicalRationals) {
  std::mt19937_64 random(4701);
  const std::size_t before = cspace::dyadic_sum_count();
  std::size_t checked = 0;
  Rational out, mid;
  for (int i = 0; i < 60000; ++i) {
    Rational a = random_rational(random), b = random_rational(random);
    if (i % 7 == 0) b = -a + Rational(static_cast<long>(random() % 9) - 4);   // cancels to an integer
    if (i % 11 == 0) b = a;                                                      // doubles
    const int sign = random() % 2 == 0 ? 1 : -1;
    const long k = static_cast<long>(random() % 2000000) - 1000000;
    Rational sum_exact = sign > 0 ? Rational(a + b) : Rational(a - b);
    sum_exact.canonicalize();
    Rational multiple_exact = a + b * k;
    multiple_exact.canonicalize();
    Rational mid_exact = (a + b) / 2;
    mid_exact.canonicalize();
    cspace::sum_into(out, a, b, sign);
    ASSERT_TRUE(same_form(out, sum_exact)) << a << (sign > 0 ? " + " : " - ") << b << ": " << out << " against " << sum_exact;
    cspace::sum_multiple_into(out, a, b, k);
    ASSERT_TRUE(same_form(out, multiple_exact)) << a << " + " << b << " * " << k << ": " << out << " against " << multiple_exact;
    cspace::midpoint_into(mid, a, b);
    ASSERT_TRUE(same_form(mid, mid_exact)) << "(" << a << " + " << b << ") / 2: " << mid << " against " << mid_exact;
    checked += 3;
  }
  const std::size_t shifted = cspace::dyadic_sum_count() - before;
  std::printf("dyadic sums: %zu results equal to GMP's, %zu of them formed by shifts\n", checked, shifted);
  EXPECT_GT(shifted, checked / 3);
  EXPECT_LT(shifted, checked);   // the non-dyadic ones went through GMP
  // switched off: GMP for all, the same results
  test::FlagSwitch<cspace::dyadic_sums> off(false);
  const std::size_t off_before = cspace::dyadic_sum_count();
  cspace::sum_into(out, Rational(1, 4), Rational(3, 8), 1);
  EXPECT_TRUE(same_form(out, Rational(5, 8)));
  EXPECT_EQ(cspace::dyadic_sum_count(), off_before);
}

TEST(CSpaceDyadicSums, ProductSignIsTheExactSign) {
  std::mt19937_64 random(4702);
  std::uniform_real_distribution<double> unit(0, 1);
  const std::size_t before = cspace::offset_filter_count();
  std::size_t checked = 0, at_product = 0;
  Rational scratch;
  for (int i = 0; i < 40000; ++i) {
    Rational offset = random_rational(random);
    if (sgn(offset) < 0) offset = -offset;
    if (i % 5 == 0) offset = Rational(mpz_class(1 + random() % 100000), mpz_class(1) << 44);   // cells of a resolution
    const double r = i % 13 == 0 ? 0.0 : std::ldexp(unit(random) + 0.5, static_cast<int>(random() % 200) - 100);
    Rational product = offset * Rational(r);
    // bounds: the product's nearest double, a few ulps either side, far off either side
    double s = product.get_d();
    const int mode = static_cast<int>(random() % 4);
    if (mode == 1) {
      const int steps = static_cast<int>(random() % 9) - 4;
      for (int j = 0; j < std::abs(steps); ++j) s = std::nextafter(s, steps > 0 ? INFINITY : -INFINITY);
    } else if (mode == 2) {
      s *= 1 + (unit(random) - 0.5) * 1e-6;
    } else if (mode == 3) {
      s = std::ldexp(unit(random), static_cast<int>(random() % 300) - 150);
    }
    if (!std::isfinite(s)) continue;
    at_product += cmp(product, Rational(s)) == 0;
    const int exact = cmp(product, Rational(s));
    const int expected = (exact > 0) - (exact < 0);
    int with = 0, without = 0;
    {
      test::FlagSwitch<cspace::offset_filter> on(true);
      with = cspace::compare_product(offset, r, s, scratch);
    }
    {
      test::FlagSwitch<cspace::offset_filter> off(false);
      without = cspace::compare_product(offset, r, s, scratch);
    }
    ASSERT_EQ(with, expected) << offset << " * " << r << " against " << s;
    ASSERT_EQ(without, expected) << offset << " * " << r << " against " << s;
    ++checked;
  }
  const std::size_t filtered = cspace::offset_filter_count() - before;
  std::printf("product signs: %zu equal to the exact sign (%zu bounds equal to the product), %zu by the enclosure\n",
              checked, at_product, filtered);
  EXPECT_GT(checked, 35000u);
  EXPECT_GT(at_product, 500u);
  EXPECT_GT(filtered, checked / 2);
  EXPECT_LT(filtered, checked);
}

// Adversarial bounds for compare_product's filter: the offset's double truncation moves the
// product by up to m_r ulps of the product (r's mantissa m_r in [1, 2), when the product stays in
// the binade of a * r), more than the one-ulp outward widening of the rounded product. Offsets
// a + ulp(a) f (f in (0, 1): non-dyadic 1 - 1/q, dyadic 1 - 2^-k, or p/q with q odd), so that
// get_d() gives a, rates with mantissa in [1.6, 2), a's mantissa below 2 / m_r; bounds: the
// doubles within 4 ulps of the rounded product get_d() * r. The gap — a bound beyond that rounded
// product's one-ulp widening on the side of the exact product, with the exact product beyond the
// bound — is where a filter that enclosed the offset by the point get_d() gives the wrong sign;
// the test counts the gap bounds it met (independently of the code under test) and requires many.
TEST(CSpaceDyadicSums, ProductSignAcrossTheTruncationGap) {
  std::mt19937_64 random(4747);
  std::uniform_real_distribution<double> unit(0, 1);
  const std::size_t before = cspace::offset_filter_count();
  std::size_t checked = 0, in_gap = 0, non_dyadic = 0, wrong_with = 0, wrong_without = 0;
  Rational scratch;
  for (int i = 0; i < 20000; ++i) {
    double mr = 1.6 + 0.4 * unit(random);
    if (mr >= 2) mr = std::nextafter(2.0, 0.0);
    const double ma = 1 + (2 / mr - 1) * unit(random);
    const double a = std::ldexp(ma, static_cast<int>(random() % 200) - 100);
    double r = std::ldexp(mr, static_cast<int>(random() % 200) - 100);
    const Rational ulp_a = Rational(std::nextafter(a, INFINITY)) - Rational(a);
    Rational fraction;
    const int mode = static_cast<int>(random() % 3);
    if (mode == 0) {
      fraction = 1 - Rational(mpz_class(1), mpz_class(static_cast<unsigned long>(3 + 2 * (random() % 500000))));
    } else if (mode == 1) {
      fraction = 1 - Rational(mpz_class(1), mpz_class(1) << static_cast<unsigned long>(1 + random() % 40));
    } else {
      const unsigned long q = 3 + 2 * (random() % 500000);
      fraction = Rational(mpz_class(1 + random() % (q - 1)), mpz_class(q));
    }
    fraction.canonicalize();
    Rational offset = Rational(a) + ulp_a * fraction;
    offset.canonicalize();
    const bool negative_offset = random() % 2, negative_rate = random() % 2;
    if (negative_offset) offset = -offset;
    if (negative_rate) r = -r;
    non_dyadic += mpz_popcount(offset.get_den_mpz_t()) != 1;
    // the construction: get_d() truncates the offset to +-a
    ASSERT_EQ(offset.get_d(), negative_offset ? -a : a) << offset;
    const Rational product = offset * Rational(r);
    const double rounded = offset.get_d() * r;   // the product of the truncated offset, rounded
    const double low = std::nextafter(rounded, -INFINITY), high = std::nextafter(rounded, INFINITY);
    double s = rounded;
    for (int j = 0; j < 4; ++j) s = std::nextafter(s, -INFINITY);
    for (int j = -4; j <= 4; ++j, s = std::nextafter(s, INFINITY)) {
      const int exact = cmp(product, Rational(s));
      const int expected = (exact > 0) - (exact < 0);
      in_gap += (s > high && expected > 0) || (s < low && expected < 0);
      int with = 0, without = 0;
      {
        test::FlagSwitch<cspace::offset_filter> on(true);
        with = cspace::compare_product(offset, r, s, scratch);
      }
      {
        test::FlagSwitch<cspace::offset_filter> off(false);
        without = cspace::compare_product(offset, r, s, scratch);
      }
      // every wrong sign counted (the first few shown): a mutant's count is the test's measure
      if (with != expected && wrong_with++ < 5)
        ADD_FAILURE() << "filtered sign " << with << ", exact " << expected << ": " << offset << " * " << r << " against "
                      << s << " (" << j << " ulps from " << rounded << ")";
      if (without != expected && wrong_without++ < 5)
        ADD_FAILURE() << "unfiltered sign " << without << ", exact " << expected << ": " << offset << " * " << r << " against " << s;
      ++checked;
    }
  }
  const std::size_t filtered = cspace::offset_filter_count() - before;
  std::printf("truncation gap: %zu bounds checked against the exact sign, %zu of them in the gap, %zu non-dyadic offsets, %zu by the enclosure\n",
              checked, in_gap, non_dyadic, filtered);
  EXPECT_EQ(wrong_with, 0u) << "wrong filtered signs";
  EXPECT_EQ(wrong_without, 0u) << "wrong unfiltered signs";
  EXPECT_GT(in_gap, 1000u);
  EXPECT_GT(non_dyadic, 10000u);
  EXPECT_GT(filtered, checked / 4);
  EXPECT_LT(filtered, checked);
}

TEST(CSpaceDyadicSums, EnclosuresAreKernelsEnclosures) {
  std::mt19937_64 random(4703);
  std::uniform_real_distribution<double> unit(0, 1);
  const std::size_t before = cspace::dyadic_enclosure_count();
  std::size_t checked = 0;
  auto check = [&](const Rational& r) {
    const kernels::Interval fast = cspace::enclose_exact(r), exact = kernels::Interval::enclose(r);
    ASSERT_TRUE(std::memcmp(&fast.lo, &exact.lo, sizeof(double)) == 0 && std::memcmp(&fast.hi, &exact.hi, sizeof(double)) == 0)
        << r << ": [" << fast.lo << ", " << fast.hi << "] against [" << exact.lo << ", " << exact.hi << "]";
    ++checked;
  };
  for (int i = 0; i < 100000; ++i) {
    check(random_rational(random));
    // doubles (the simulator's coefficients, the filtered bounds), at every scale, and around the
    // ends of the normal range (2^-1022, 2^1024) where the shortcut stops
    const double d = std::ldexp(unit(random) + 0.5, static_cast<int>(random() % 2112) - 1090) * (random() % 2 ? 1 : -1);
    check(Rational(d));
    Rational near(mpz_class(1 + random() % 1000000) * (random() % 2 ? 1 : -1),
                  mpz_class(1) << static_cast<unsigned long>(1000 + random() % 80));
    near.canonicalize();
    check(near);
    Rational big(mpz_class(1) << static_cast<unsigned long>(1000 + random() % 40));
    big *= Rational(mpz_class(static_cast<unsigned long>(random() | 1)), mpz_class(1) << 40);
    big.canonicalize();
    check(big);
    if (HasFatalFailure()) return;
  }
  const std::size_t shortcut = cspace::dyadic_enclosure_count() - before;
  std::printf("enclosures: %zu equal to kernels::Interval::enclose, %zu of them by the shortcut\n", checked, shortcut);
  EXPECT_GT(shortcut, checked / 2);
  EXPECT_LT(shortcut, checked);
}

struct Counts {
  int motions = 0, crossing = 0, none = 0, other = 0;
  std::size_t sums = 0, products = 0;
};

// generated motions (those of cspace_crossing_path_memo_test.cpp) over [0, 1], [0, a double] or
// [0, 2/3], each asked with both switches on and both off, in a random order
void compare_motions(const CSpace& space, int count, std::uint64_t seed, Counts& counts) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  const std::vector<std::size_t> edges = test::real_edges(space);
  for (int i = 0; i < count; ++i) {
    std::optional<test::GeneratedMotion> motion = test::generated_motion(space, edges, random);
    if (!motion) continue;
    MotionPath& path = motion->path;
    const double speed = motion->speed, x0 = motion->x0, y0 = motion->y0;
    const std::size_t chart_index = motion->chart;
    const int range = static_cast<int>(random() % 3);
    if (range == 1) path.u_end = Rational(0.25 + unit(random));
    else if (range == 2) path.u_end = Rational(2, 3);
    std::string with, without;
    auto run = [&](bool on) {
      test::FlagSwitch<cspace::dyadic_sums> sums(on);
      test::FlagSwitch<cspace::offset_filter> products(on);
      const std::size_t s0 = cspace::dyadic_sum_count(), p0 = cspace::offset_filter_count();
      std::string answer = test::crossing_answer(space, path);
      if (on) {
        counts.sums += cspace::dyadic_sum_count() - s0;
        counts.products += cspace::offset_filter_count() - p0;
      } else {
        EXPECT_EQ(cspace::dyadic_sum_count(), s0) << "the switch must turn the sums off";
        EXPECT_EQ(cspace::offset_filter_count(), p0) << "the switch must turn the filter off";
      }
      return answer;
    };
    if (random() % 2 == 0) {
      with = run(true);
      without = run(false);
    } else {
      without = run(false);
      with = run(true);
    }
    ASSERT_EQ(with, without) << space.first_part() << ":" << space.second_part() << " motion " << i << " speed "
                             << speed << " from (" << x0 << ", " << y0 << ") in chart " << chart_index << " to u "
                             << path.u_end;
    ++counts.motions;
    if (with.rfind("status 1 ", 0) == 0) ++counts.crossing;
    else if (with.rfind("status 0 ", 0) == 0) ++counts.none;
    else ++counts.other;
  }
}

TEST(CSpaceDyadicSums, CrossingAnswersAreThoseWithoutThem) {
  Counts counts;
  std::uint64_t seed = 4710;
  for (const std::unique_ptr<CSpace>& space : test::example_spaces()) {
    compare_motions(*space, 120, ++seed, counts);
    ASSERT_FALSE(HasFatalFailure());
  }
  Model model = read_model_file(std::filesystem::path(HIPAIR_TEST_DATA) / "degenerate/zero-clearance.json");
  for (const PairBuild& pair : CSpace::build_pairs(model)) {
    if (pair.status != PairBuild::Status::built) continue;
    compare_motions(*pair.space, 80, ++seed, counts);
    ASSERT_FALSE(HasFatalFailure());
  }
  std::printf("motions %d: crossing %d, none %d, other %d; %zu dyadic sums, %zu product signs by the enclosure\n",
              counts.motions, counts.crossing, counts.none, counts.other, counts.sums, counts.products);
  EXPECT_GE(counts.motions, 600);
  EXPECT_GE(counts.crossing, 40);
  EXPECT_GE(counts.none, 150);
  EXPECT_GT(counts.sums, 3000u);
  EXPECT_GT(counts.products, 50u);
}

TEST(CSpaceDyadicSums, SimulationRunsEqualTheRunsWithoutThem) {
  struct Case {
    const char* model;
    double t_end, accuracy;
  };
  const Case cases[] = {{"escapement.json", 0.5, 1e-3}, {"ratchet.json", 0.2, 1e-6}, {"cam-follower.json", 0.3, 1e-6}};
  std::size_t steps = 0, events = 0;
  for (const Case& c : cases) {
    Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / c.model);
    SimulationOptions options;
    options.accuracy = c.accuracy;
    const std::string where = std::string(c.model) + " at " + std::to_string(c.accuracy);
    test::SideBySide sums = test::run_side_by_side<cspace::dyadic_sums>(model, options, c.t_end, where + " (sums)", 100000);
    ASSERT_EQ(sums.mismatch, "");
    ASSERT_EQ(sums.error, "") << where;
    test::SideBySide products =
        test::run_side_by_side<cspace::offset_filter>(model, options, c.t_end, where + " (products)", 100000);
    ASSERT_EQ(products.mismatch, "");
    ASSERT_EQ(products.error, "") << where;
    steps += sums.steps + products.steps;
    events += sums.events + products.events;
  }
  std::printf("dyadic sums: %zu steps, %zu events equal with each switch off\n", steps, events);
  EXPECT_GT(events, 50u);
}

}  // namespace
}  // namespace hipair
