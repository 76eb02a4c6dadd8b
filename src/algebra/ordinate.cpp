// Signs at a chart point whose ordinate is a square-root expression in its abscissa
// (algebra/ordinate.hpp).
#include "algebra/ordinate.hpp"

namespace hipair::cspace::algebra {

namespace {

Polynomial sum(Polynomial a, const Polynomial& b) {
  if (a.size() < b.size()) a.resize(b.size());
  for (std::size_t i = 0; i < b.size(); ++i) a[i] += b[i];
  trim(a);
  return a;
}

Polynomial difference(Polynomial a, const Polynomial& b) {
  if (a.size() < b.size()) a.resize(b.size());
  for (std::size_t i = 0; i < b.size(); ++i) a[i] -= b[i];
  trim(a);
  return a;
}

}  // namespace

std::pair<Polynomial, Polynomial> substitute_radical_ordinate(const IntegerPolynomial2& f, const RadicalOrdinate& y) {
  if (y.radicand.empty()) return {substitute_ordinate(f, y.numerator, y.denominator), {}};
  // Horner in y over Z[x][√R]: H = f_d, then H = H (P + √R) + f_j Q^(d - j) for j = d - 1 ... 0,
  // with (u + v √R)(P + √R) = (u P + v R) + (u + v P) √R
  const int d = f.degree_y();
  if (d < 0) return {};
  Polynomial u = y_coefficient(f, d), v, power{mpz_class(1)};
  for (int j = d - 1; j >= 0; --j) {
    power = product(power, y.denominator);
    Polynomial next_u = sum(product(u, y.numerator), product(v, y.radicand));
    v = sum(std::move(u), product(v, y.numerator));
    u = sum(std::move(next_u), product(y_coefficient(f, j), power));
  }
  return {std::move(u), std::move(v)};
}

int sign_with_root(const Polynomial& A, const Polynomial& B, const Polynomial& R, const Real& x) {
  const int a = sign_at(A, x);
  if (B.empty() || R.empty()) return a;
  const int b = sign_at(B, x);
  if (b == 0 || a == b) return a;
  if (sign_at(R, x) == 0) return a;
  if (a == 0) return b;
  // opposite signs: A + B √R has A's sign exactly when A^2 > B^2 R
  return a * sign_at(difference(product(A, A), product(product(B, B), R)), x);
}

int sign_at(const IntegerPolynomial2& f, const Real& x, const RadicalOrdinate& y, int denominator_sign) {
  auto [A, B] = substitute_radical_ordinate(f, y);
  const int s = sign_with_root(A, B, y.radicand, x);
  return f.degree_y() % 2 == 0 ? s : s * denominator_sign;
}

}  // namespace hipair::cspace::algebra
