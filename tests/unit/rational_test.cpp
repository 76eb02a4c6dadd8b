// Exact rational literals and their text forms (include/hipair/rational.hpp).
#include <hipair/error.hpp>
#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cstdlib>
#include <new>

namespace {

using hipair::parse_rational;
using hipair::Rational;

TEST(Rational, LiteralsAreExact) {
  EXPECT_EQ(parse_rational("9007199254740993"), Rational(mpz_class("9007199254740993")));
  EXPECT_EQ(parse_rational("0.1") * 10, Rational(1));
  EXPECT_EQ(parse_rational("46.683"), Rational(46683, 1000));
  EXPECT_EQ(parse_rational("1e-30") * Rational(mpz_class("1000000000000000000000000000000")), Rational(1));
  EXPECT_EQ(parse_rational("123456789012345678901234567890.5") * 2,
            Rational(mpz_class("246913578024691357802469135781")));
  EXPECT_EQ(parse_rational(" +2.50 "), Rational(5, 2));
  EXPECT_EQ(parse_rational("-0"), Rational(0));
  EXPECT_EQ(parse_rational(".5"), Rational(1, 2));
  EXPECT_EQ(parse_rational("5."), Rational(5));
  EXPECT_EQ(parse_rational("6/4"), Rational(3, 2));
  EXPECT_EQ(parse_rational("-1.5/0.5"), Rational(-3));
  EXPECT_EQ(parse_rational("2E3"), Rational(2000));
}

TEST(Rational, NonLiteralsAreNumericErrors) {
  for (const char* text : {"", " ", "+", "-", "1/", "/2", "1//2", "1e", "e5", "1.2.3", "1e+", "0x1p3", "one", "1 2",
                           "1e1000000"})
    EXPECT_THROW(parse_rational(text), hipair::NumericError) << "'" << text << "'";
}

TEST(Rational, TextForms) {
  EXPECT_EQ(hipair::to_exact_string(Rational(-6, 4)), "-3/2");
  EXPECT_EQ(hipair::to_exact_string(Rational(0)), "0");
  EXPECT_EQ(hipair::to_decimal_string(Rational(-1, 8), 12), "-0.125");
  EXPECT_EQ(hipair::to_decimal_string(Rational(1, 3), 5), "0.33333");
  EXPECT_EQ(hipair::to_decimal_string(Rational(1234), 12), "1234");
  EXPECT_EQ(hipair::to_decimal_string(Rational(0), 12), "0");
}

TEST(Rational, ToDoubleRoundsToNearestEven) {
  // 2^53 + 1 lies halfway between two doubles: round half to even gives 2^53.
  EXPECT_EQ(hipair::to_double(parse_rational("9007199254740993")), 9007199254740992.0);
  EXPECT_EQ(hipair::to_double(parse_rational("9007199254740995")), 9007199254740996.0);
  EXPECT_EQ(hipair::to_double(parse_rational("46.683")), 46.683);
  EXPECT_EQ(hipair::to_double(parse_rational("1e-30")), 1e-30);
}


// Out of memory inside GMP: with use_throwing_gmp_allocation() an allocation GMP cannot get
// throws std::bad_alloc (the CLI maps it to exit 4) instead of printing "GNU MP: Cannot
// allocate memory" and aborting (SIGABRT, exit 134). In a child process limited to 1 GB of
// address space, an 8 GB number cannot be allocated.
TEST(RationalDeathTest, GmpOutOfMemoryThrowsBadAlloc) {
  auto child = [] {
    rlimit limit{std::size_t{1} << 30, std::size_t{1} << 30};
    setrlimit(RLIMIT_AS, &limit);
    hipair::use_throwing_gmp_allocation();
    try {
      mpz_class huge;
      mpz_realloc2(huge.get_mpz_t(), mp_bitcnt_t{1} << 36);   // 8 GB
      std::exit(0);
    } catch (const std::bad_alloc&) {
      std::exit(4);
    }
  };
  EXPECT_EXIT(child(), ::testing::ExitedWithCode(4), "");
}

}  // namespace
