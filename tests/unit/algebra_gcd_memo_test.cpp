// algebra::gcd is remembered per thread (a memo keyed by both arguments, in order): generated
// pairs that share one argument and differ in the other, asked in turn and again, must each give
// the exact primitive gcd, known by construction (products of primitive linear factors d x - n
// with small roots, times contents of either sign: the gcd is the product of the common factors
// at their smaller multiplicity, leading coefficient positive).
#include "algebra/exact_real.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace hipair::cspace::algebra {
namespace {

// the linear factors d x - n (d > 0, gcd(d, n) = 1): primitive, so their products are
using GcdMemoFactor = std::pair<long, long>;   // (n, d)
constexpr std::array<GcdMemoFactor, 9> gcd_memo_factors{
    {{0, 1}, {1, 1}, {-1, 1}, {2, 1}, {-3, 1}, {1, 2}, {-2, 3}, {5, 3}, {7, 1}}};

Polynomial gcd_memo_product(const std::map<int, int>& multiplicities, long content) {
  Polynomial p{mpz_class(content)};
  for (const auto& [k, m] : multiplicities)
    for (int r = 0; r < m; ++r) {
      const auto& [n, d] = gcd_memo_factors[static_cast<std::size_t>(k)];
      Polynomial q(p.size() + 1);
      for (std::size_t i = 0; i < p.size(); ++i) {
        q[i] -= p[i] * n;
        q[i + 1] += p[i] * d;
      }
      p = std::move(q);
    }
  trim(p);
  return p;
}

std::map<int, int> gcd_memo_factor_set(std::mt19937_64& random) {
  std::map<int, int> set;
  const int count = 1 + static_cast<int>(random() % 5);
  for (int k = 0; k < count; ++k) ++set[static_cast<int>(random() % gcd_memo_factors.size())];
  return set;
}

TEST(AlgebraGcdMemo, PairsSharingAnArgumentGiveTheirOwnGcd) {
  std::mt19937_64 random(20261203);
  auto content = [&] {
    const long c = 1 + static_cast<long>(random() % 40);
    return random() % 2 ? c : -c;
  };
  int checked = 0, repeated = 0;
  for (int trial = 0; trial < 150; ++trial) {
    const std::map<int, int> a_set = gcd_memo_factor_set(random);
    const Polynomial a = gcd_memo_product(a_set, content());
    // several second arguments with the same first (and each asked twice, both ways round)
    std::vector<std::pair<Polynomial, Polynomial>> cases;   // (b, expected gcd)
    for (int k = 0; k < 4; ++k) {
      const std::map<int, int> b_set = gcd_memo_factor_set(random);
      std::map<int, int> common;
      for (const auto& [f, m] : a_set)
        if (auto it = b_set.find(f); it != b_set.end()) common[f] = std::min(m, it->second);
      cases.emplace_back(gcd_memo_product(b_set, content()), gcd_memo_product(common, 1));
    }
    for (int round = 0; round < 2; ++round)
      for (const auto& [b, expected] : cases) {
        ASSERT_EQ(gcd(a, b), expected) << "trial " << trial << ": gcd(" << to_string(a, "x") << ", " << to_string(b, "x")
                                       << ") is not " << to_string(expected, "x");
        ASSERT_EQ(gcd(b, a), expected) << "trial " << trial << ": gcd(" << to_string(b, "x") << ", " << to_string(a, "x")
                                       << ") is not " << to_string(expected, "x");
        ++checked;
        repeated += round;
      }
    // a zero argument: the other's primitive part
    ASSERT_EQ(gcd(Polynomial{}, a), primitive_part(a));
    ASSERT_EQ(gcd(a, Polynomial{}), primitive_part(a));
  }
  EXPECT_EQ(checked, 1200);
  EXPECT_EQ(repeated, 600);
}

}  // namespace
}  // namespace hipair::cspace::algebra
