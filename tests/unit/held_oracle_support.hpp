// Exact oracles shared by the held-force tests (simulation_held_force_sign_test.cpp,
// simulation_held_verdict_test.cpp): a deterministic generator, determinants by cofactor
// expansion and Cramer's rule in rationals; the slip oracle of one frictional contact (session 66,
// moved here in session 67 for the impact tests).
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

// The exact slip oracle of one contact (rationals): whether sliding in direction sigma (f = -sigma mu_k
// N) is consistent, held (lambda = -(J a0 + kappa) / (J M^-1 W^T) >= 0, W = J - sigma mu_k T, and
// sigma (T x + bias) >= 0 at x = a0 + M^-1 W^T lambda) or open (J a0 + kappa >= 0, sigma (T a0 + bias)
// >= 0). MJ, MT: M^-1 J^T and M^-1 T^T; Ja0, Ta0: J a0 + kappa and T a0 + bias.
inline bool slip_consistent(int sigma, const Rational& mu_k, const std::vector<Rational>& a0, const std::vector<Rational>& J,
                     const std::vector<Rational>& T, const std::vector<Rational>& MJ, const std::vector<Rational>& MT,
                     const Rational& bias, const Rational& Ja0, const Rational& Ta0) {
  const std::size_t n = a0.size();
  auto dot = [&](const std::vector<Rational>& u, const std::vector<Rational>& v) {
    Rational out = 0;
    for (std::size_t i = 0; i < n; ++i) out += u[i] * v[i];
    return out;
  };
  if (sgn(Ja0) >= 0 && sigma * Ta0 >= 0) return true;
  std::vector<Rational> MW(n);   // M^-1 W^T
  for (std::size_t i = 0; i < n; ++i) MW[i] = MJ[i] - sigma * mu_k * MT[i];
  const Rational JMW = dot(J, MW);
  if (sgn(JMW) == 0) return false;
  const Rational lambda = -Ja0 / JMW;
  if (sgn(lambda) < 0) return false;
  std::vector<Rational> x(a0);
  for (std::size_t i = 0; i < n; ++i) x[i] += MW[i] * lambda;
  return sigma * (dot(T, x) + bias) >= 0;
}

}  // namespace hipair::held_oracle
