// Exact rational literals and their text forms (include/hipair/rational.hpp).
#include <hipair/error.hpp>
#include <hipair/rational.hpp>
#include "core/exact_literal.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <thread>
#include <vector>

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

// GMP's small blocks kept per thread for reuse (use_throwing_gmp_allocation): numbers of 1 to
// 12 limbs (pooled sizes and beyond) made, grown, shrunk and freed on four threads, many of
// them freed on another thread than the one that made them, give the values computed before
// the functions were installed (GMP's own allocation); every identity checked holds.
TEST(Rational, GmpBlocksReusedAcrossThreadsKeepEveryValue) {
  std::mt19937_64 random(20261201);
  auto number = [&](int limbs) {
    mpz_class value = 0;
    for (int k = 0; k < limbs; ++k) value = (value << 64) + mpz_class(std::to_string(random()));
    return random() % 3 == 0 ? mpz_class(-value) : value;
  };
  struct Case {
    mpz_class a, b;
    std::string product, sum, quotient, gcd;
  };
  std::vector<Case> cases;
  for (int k = 0; k < 3000; ++k) {
    Case c{number(1 + static_cast<int>(random() % 12)), number(1 + static_cast<int>(random() % 6)), {}, {}, {}, {}};
    if (c.b == 0) c.b = 7;
    // expected values with GMP's own allocation
    c.product = mpz_class(c.a * c.b).get_str();
    c.sum = mpz_class(c.a + c.b).get_str();
    c.quotient = mpz_class(c.a / c.b).get_str();
    c.gcd = mpz_class(gcd(c.a, c.b)).get_str();
    cases.push_back(c);
  }
  hipair::use_throwing_gmp_allocation();
  // each thread computes a quarter of the cases and hands its numbers to the next thread to
  // check and free
  constexpr int threads = 4;
  std::vector<std::vector<mpz_class>> handed(threads);
  std::vector<int> failures(threads, 0);
  auto compute = [&](int t) {
    std::vector<mpz_class>& out = handed[static_cast<std::size_t>(t)];
    for (std::size_t k = static_cast<std::size_t>(t); k < cases.size(); k += threads) {
      const Case& c = cases[k];
      mpz_class a = c.a, b = c.b;   // (copies made on this thread)
      mpz_class product = a * b, sum = a + b, quotient = a / b, divisor = gcd(a, b);
      mpz_class grown = product;
      grown *= product;   // grown past the pooled sizes, then back
      grown /= product;
      if (product.get_str() != c.product || sum.get_str() != c.sum || quotient.get_str() != c.quotient ||
          divisor.get_str() != c.gcd || grown != product || (product % a) != 0)
        ++failures[static_cast<std::size_t>(t)];
      out.push_back(product);
      out.push_back(sum);
      out.push_back(quotient);
    }
  };
  std::vector<std::thread> workers;
  for (int t = 0; t < threads; ++t) workers.emplace_back(compute, t);
  for (auto& worker : workers) worker.join();
  workers.clear();
  for (int t = 0; t < threads; ++t)
    workers.emplace_back([&, t] {
      std::vector<mpz_class> numbers = std::move(handed[static_cast<std::size_t>((t + 1) % threads)]);
      std::size_t m = 0;
      for (std::size_t k = static_cast<std::size_t>((t + 1) % threads); k < cases.size(); k += threads, m += 3) {
        const Case& c = cases[k];
        if (numbers[m].get_str() != c.product || numbers[m + 1].get_str() != c.sum ||
            numbers[m + 2].get_str() != c.quotient)
          ++failures[static_cast<std::size_t>(t)];
        // freed here, on another thread than the one that made them
        numbers[m] = 0;
        numbers[m + 1] = mpz_class(numbers[m + 2] * 3);
      }
    });
  for (auto& worker : workers) worker.join();
  for (int t = 0; t < threads; ++t) EXPECT_EQ(failures[static_cast<std::size_t>(t)], 0) << "thread " << t;
  // bursts longer than a size's list (8 192 blocks since session 53): 30 000 numbers of one and
  // of two limbs alive at once, freed together (the lists fill, the rest go to free), made again
  // (from the lists, then from malloc) and checked, on a fresh thread and on this one
  auto burst = [&] {
    int wrong = 0;
    for (int round = 0; round < 2; ++round) {
      std::vector<mpz_class> held;
      held.reserve(60000);
      for (int k = 0; k < 30000; ++k) {
        held.emplace_back(mpz_class(k) * 1000003 + round);                          // one limb
        held.emplace_back((mpz_class(k) << 64) + mpz_class(k) * 7 + round);         // two limbs
      }
      for (int k = 0; k < 30000; ++k)
        if (held[2 * static_cast<std::size_t>(k)] != mpz_class(k) * 1000003 + round ||
            held[2 * static_cast<std::size_t>(k) + 1] != (mpz_class(k) << 64) + mpz_class(k) * 7 + round)
          ++wrong;
    }
    return wrong;
  };
  int burst_wrong = 0;
  std::thread fresh([&] { burst_wrong = burst(); });
  fresh.join();
  EXPECT_EQ(burst_wrong, 0);
  EXPECT_EQ(burst(), 0);
}

}  // namespace

// Session 41 (integrator): the exponent limit of an exact literal holds in both parts. A
// certificate's "1200/20e-4958" was read as a 16 473-bit number (the limit was checked only on
// the model's first exponent), and literal_cli_tests failed on such seeds. Generated literals
// m e±k, m/(d e±k) and (m e±j)/(d e±k) with k, j around the limit: accepted exactly when every
// exponent is within it, and then equal to the value built from integers.
TEST(Rational, ExactLiteralsExponentLimitInEitherPart) {
  std::mt19937_64 random(4141);
  const long limit = hipair::exact_literal_max_exponent;
  auto power = [](long k) {
    mpz_class p;
    mpz_ui_pow_ui(p.get_mpz_t(), 10, static_cast<unsigned long>(k < 0 ? -k : k));
    return k < 0 ? Rational(mpz_class(1), p) : Rational(p);
  };
  auto exponent = [&](void) -> long {
    long spread[] = {0, 1, 999, 1000, 1001, 1002, 4958, 9999, 10000, 33768};
    long k = spread[random() % 10] + static_cast<long>(random() % 3) - 1;
    return random() % 2 ? -k : k;
  };
  auto text_of = [&](long k) {
    std::string sign = k < 0 ? "-" : (random() % 2 ? "+" : "");
    std::string zeros(random() % 3, '0');  // leading zeros of the exponent do not hide it
    return std::string(random() % 2 ? "e" : "E") + sign + zeros + std::to_string(k < 0 ? -k : k);
  };
  int accepted = 0, refused = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    long m = 1 + static_cast<long>(random() % 99999), d = 1 + static_cast<long>(random() % 999);
    long j = exponent(), k = exponent();
    int shape = static_cast<int>(random() % 3);
    std::string text = std::to_string(m);
    Rational value(m);
    bool within = true;
    if (shape != 1) {
      text += text_of(j);
      value *= power(j);
      within = within && std::labs(j) <= limit;
    }
    if (shape != 0) {
      text += "/" + std::to_string(d) + text_of(k);
      value /= Rational(d) * power(k);
      within = within && std::labs(k) <= limit;
    }
    if (within) {
      ++accepted;
      EXPECT_EQ(hipair::parse_exact_literal(text), value) << text;
    } else {
      ++refused;
      try {
        hipair::parse_exact_literal(text);
        ADD_FAILURE() << text << " accepted beyond the exponent limit";
      } catch (const hipair::NumericError& error) {
        EXPECT_NE(std::string(error.what()).find("exponent"), std::string::npos) << error.what();
      }
    }
  }
  EXPECT_GT(accepted, 500);
  EXPECT_GT(refused, 500);
}
