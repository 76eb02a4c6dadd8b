// HIPAIR — the exact square root of a rational, where it is rational.
#pragma once

#include <hipair/rational.hpp>

#include <optional>

namespace hipair {

/// sqrt(value) when value >= 0 is the square of a rational (numerator and denominator perfect
/// squares), otherwise nothing.
inline std::optional<Rational> rational_sqrt(const Rational& value) {
  if (sgn(value) < 0) return std::nullopt;
  if (!mpz_perfect_square_p(value.get_num_mpz_t()) || !mpz_perfect_square_p(value.get_den_mpz_t()))
    return std::nullopt;
  mpz_class numerator, denominator;
  mpz_sqrt(numerator.get_mpz_t(), value.get_num_mpz_t());
  mpz_sqrt(denominator.get_mpz_t(), value.get_den_mpz_t());
  return Rational(numerator, denominator);   // canonical: roots of coprime squares are coprime
}

}  // namespace hipair
