// Exact signs of 2 atan(tau) + m pi - L (angle_sign.hpp).
#include "core/angle_sign.hpp"

#include "core/mp_values.hpp"

#include <algorithm>

namespace hipair {

long magnitude_bits(const Rational& x) {
  if (sgn(x) == 0) return 0;
  long bits = static_cast<long>(mpz_sizeinbase(x.get_num_mpz_t(), 2)) -
              static_cast<long>(mpz_sizeinbase(x.get_den_mpz_t(), 2)) + 1;
  return std::max(0L, bits);
}

long magnitude_bits(const mpz_class& x) {
  return sgn(x) == 0 ? 0 : static_cast<long>(mpz_sizeinbase(x.get_mpz_t(), 2));
}

void enclose_angle(mpfi_t out, const Rational& tau, const mpz_class& m, const Rational& L, mpfr_prec_t bits) {
  MpfiValue term(bits);
  mpfi_set_q(out, tau.get_mpq_t());
  mpfi_atan(out, out);
  mpfi_mul_2ui(out, out, 1);
  if (sgn(m) != 0) {
    mpfi_const_pi(term.v);
    mpfi_mul_z(term.v, term.v, m.get_mpz_t());
    mpfi_add(out, out, term.v);
  }
  if (sgn(L) != 0) {
    mpfi_set_q(term.v, L.get_mpq_t());
    mpfi_sub(out, out, term.v);
  }
}

mpfr_prec_t angle_bits(const mpz_class& m, const Rational& L) {
  return static_cast<mpfr_prec_t>(64 + std::max(magnitude_bits(L), magnitude_bits(m) + 2));
}

int angle_sign(const Rational& tau, const mpz_class& m, const Rational& L) {
  if (sgn(m) == 0 && sgn(L) == 0) return sgn(tau);   // 2 atan(tau) has the sign of tau
  // never 0 here (angle_sign.hpp): the refinement ends
  for (mpfr_prec_t bits = angle_bits(m, L);; bits *= 2) {
    MpfiValue difference(bits);
    enclose_angle(difference.v, tau, m, L, bits);
    if (mpfi_is_strictly_pos(difference.v) > 0) return 1;
    if (mpfi_is_strictly_neg(difference.v) > 0) return -1;
  }
}

}  // namespace hipair
