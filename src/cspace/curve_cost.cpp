#include "cspace/curve_cost.hpp"

#include "algebra/content.hpp"

#include <algorithm>

namespace hipair::cspace {

std::size_t primitive_coefficient_bits(const IntegerPolynomial2& f) {
  auto for_each = [&f](auto visit) {
    for (const auto& row : f.coefficients)
      for (const mpz_class& c : row) visit(c.get_mpz_t());
  };
  const mpz_class content = algebra::smallest_first_content(for_each);
  if (sgn(content) == 0) return 0;
  std::size_t largest = 0;
  for_each([&](mpz_srcptr v) {
    if (mpz_sgn(v) != 0) largest = std::max(largest, mpz_sizeinbase(v, 2));
  });
  if (mpz_cmp_ui(content.get_mpz_t(), 1) == 0) return largest;
  mpz_class quotient;
  for (const auto& row : f.coefficients)
    for (const mpz_class& c : row)
      if (mpz_sizeinbase(c.get_mpz_t(), 2) == largest) {
        mpz_divexact(quotient.get_mpz_t(), c.get_mpz_t(), content.get_mpz_t());
        return mpz_sizeinbase(quotient.get_mpz_t(), 2);
      }
  return largest;
}

}  // namespace hipair::cspace
