#include "algebra/liouville.hpp"

namespace hipair::cspace::algebra {

long liouville_bits(const std::vector<const Real*>& values, const std::vector<int>& partial_degrees, long length_bits) {
  // each value's polynomial: its degree d_i and ceil(log2 L(p_i)) (the bit size of the length)
  std::vector<long> degrees, bits;
  for (const Real* x : values) {
    Polynomial p = x->exact ? Polynomial{-x->lower.get_num(), x->lower.get_den()} : x->polynomial;
    mpz_class length = 0;
    for (const mpz_class& coefficient : p) length += abs(coefficient);
    degrees.push_back(degree(p));
    bits.push_back(static_cast<long>(mpz_sizeinbase(length.get_mpz_t(), 2)));
  }
  long product = 1;
  for (long d : degrees) product *= d;
  long total = product * length_bits;   // D - 1 < P
  for (std::size_t i = 0; i < values.size(); ++i) total += partial_degrees[i] * (product / degrees[i]) * bits[i];
  return total;
}

}  // namespace hipair::cspace::algebra
