// Exact rational literals and their text forms (include/hipair/rational.hpp).
#include <hipair/error.hpp>
#include <hipair/rational.hpp>

#include <gtest/gtest.h>

#include <random>
#include <string>

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

// Session 29 (hunt29): values from 10^-400 to 10^400 are written with an exponent beyond
// [1e-21, 1e30) (statements and messages held 300 zeros for a 1e-300 mm offset), fixed inside it;
// either way the text reads back (parse_rational) within the digits asked for. Generated values.
TEST(Rational, DecimalTextsAtEveryScaleAreShortAndReadBack) {
  std::mt19937_64 random(29);
  for (int instance = 0; instance < 2000; ++instance) {
    const int digits = 5 + static_cast<int>(random() % 16);
    const long e = static_cast<long>(random() % 801) - 400;
    mpz_class p = mpz_class(static_cast<unsigned long>(random() % 999999999 + 1));
    mpz_class ten;
    mpz_ui_pow_ui(ten.get_mpz_t(), 10, static_cast<unsigned long>(e < 0 ? -e : e));
    Rational value = e < 0 ? Rational(p, ten * 1000) : Rational(p * ten, 1000);
    value.canonicalize();
    if (random() % 2) value = -value;
    const std::string text = hipair::to_decimal_string(value, digits);
    SCOPED_TRACE(value.get_str() + " at " + std::to_string(digits) + " digits: " + text);
    EXPECT_LE(text.size(), static_cast<std::size_t>(digits) + 34);
    const Rational magnitude = abs(value);
    const bool fixed = magnitude >= Rational(1, mpz_class("1" + std::string(21, '0'))) &&
                       magnitude < Rational(mpz_class("1" + std::string(30, '0')));
    EXPECT_EQ(text.find('e') == std::string::npos, fixed);
    Rational back = parse_rational(text);
    Rational error = abs(Rational(back - value)) / magnitude;
    mpz_class bound;
    mpz_ui_pow_ui(bound.get_mpz_t(), 10, static_cast<unsigned long>(digits - 1));
    EXPECT_LE(error, Rational(1, bound));
  }
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
