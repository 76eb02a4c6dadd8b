// Exact oracles shared by the held-force tests (simulation_held_force_sign_test.cpp,
// simulation_held_verdict_test.cpp): a deterministic generator, determinants by cofactor
// expansion and Cramer's rule in rationals.
#pragma once

#include <hipair/rational.hpp>

#include <cstdint>
#include <vector>

namespace hipair::held_oracle {

using RMatrix = std::vector<std::vector<Rational>>;

struct Rng {
  std::uint64_t s;
  double uniform(double a, double b) {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return a + (b - a) * static_cast<double>(s >> 11) / 9007199254740992.0;
  }
  int below(int n) { return static_cast<int>(uniform(0, n)) % n; }
};

// det by cofactor expansion along the first row (small n)
inline Rational det(const RMatrix& a) {
  const std::size_t n = a.size();
  if (n == 0) return 1;
  if (n == 1) return a[0][0];
  Rational out = 0;
  for (std::size_t c = 0; c < n; ++c) {
    if (sgn(a[0][c]) == 0) continue;
    RMatrix minor;
    for (std::size_t r = 1; r < n; ++r) {
      std::vector<Rational> row;
      for (std::size_t j = 0; j < n; ++j)
        if (j != c) row.push_back(a[r][j]);
      minor.push_back(row);
    }
    const Rational term = a[0][c] * det(minor);
    out += c % 2 == 0 ? term : Rational(-term);
  }
  return out;
}

// Cramer's rule: x_i = det(A with column i replaced by -b) / det A (A regular): A x = -b
inline std::vector<Rational> cramer(const RMatrix& A, const std::vector<Rational>& b) {
  const Rational d = det(A);
  std::vector<Rational> out;
  for (std::size_t i = 0; i < A.size(); ++i) {
    RMatrix Ai = A;
    for (std::size_t r = 0; r < A.size(); ++r) Ai[r][i] = -b[r];
    out.push_back(det(Ai) / d);
  }
  return out;
}

}  // namespace hipair::held_oracle
