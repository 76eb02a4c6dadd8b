// Whole turns of an unlimited rotating coordinate, removed exactly: see whole_turns.hpp.
#include "simulation/whole_turns.hpp"

#include <mpfr.h>

#include <algorithm>
#include <cmath>

namespace hipair::simulation {
namespace {

// bits above the binary point of |x| (0 for |x| < 1)
long magnitude_bits(const Rational& x) {
  if (sgn(x) == 0) return 0;
  long num = static_cast<long>(mpz_sizeinbase(x.get_num_mpz_t(), 2));
  long den = static_cast<long>(mpz_sizeinbase(x.get_den_mpz_t(), 2));
  return std::max(0L, num - den + 1);
}

// 128 bits below the unit: the residue's rounding to a double is then decided by the value
// except within 2^-128 rad of a midpoint between two doubles
constexpr long guard_bits = 128;

struct Mpfr {
  mpfr_t v;
  explicit Mpfr(long bits) { mpfr_init2(v, static_cast<mpfr_prec_t>(bits)); }
  ~Mpfr() { mpfr_clear(v); }
  Mpfr(const Mpfr&) = delete;
  Mpfr& operator=(const Mpfr&) = delete;
};

// x - 2 pi n at `bits` bits, rounded to the nearest double
double residue(const Mpfr& x, const mpz_t n, long bits) {
  Mpfr two_pi(bits), product(bits), r(bits);
  mpfr_const_pi(two_pi.v, MPFR_RNDN);
  mpfr_mul_2ui(two_pi.v, two_pi.v, 1, MPFR_RNDN);
  mpfr_mul_z(product.v, two_pi.v, n, MPFR_RNDN);
  mpfr_sub(r.v, x.v, product.v, MPFR_RNDN);
  return mpfr_get_d(r.v, MPFR_RNDN);
}

}  // namespace

ReducedAngle reduce_turns(const Rational& x) {
  const long bits = magnitude_bits(x) + guard_bits;
  Mpfr value(bits), quotient(bits), two_pi(bits);
  mpfr_set_q(value.v, x.get_mpq_t(), MPFR_RNDN);
  mpfr_const_pi(two_pi.v, MPFR_RNDN);
  mpfr_mul_2ui(two_pi.v, two_pi.v, 1, MPFR_RNDN);
  mpfr_div(quotient.v, value.v, two_pi.v, MPFR_RNDN);
  mpfr_rint(quotient.v, quotient.v, MPFR_RNDN);
  ReducedAngle out;
  mpz_class n;
  mpfr_get_z(n.get_mpz_t(), quotient.v, MPFR_RNDN);
  out.angle = residue(value, n.get_mpz_t(), bits);
  out.turns = Rational(n);
  return out;
}

double minus_turns(const Rational& x, const Rational& turns) {
  const long bits = std::max(magnitude_bits(x), magnitude_bits(turns) + 3) + guard_bits;
  Mpfr value(bits);
  mpfr_set_q(value.v, x.get_mpq_t(), MPFR_RNDN);
  return residue(value, turns.get_num_mpz_t(), bits);
}

double add_turns(double r, const Rational& turns) {
  // (a non-finite r is its own sum: its rational would abort in GMP, and a published state that
  // is not finite is reported by the step)
  if (sgn(turns) == 0 || !std::isfinite(r)) return r;
  const long bits = std::max(magnitude_bits(Rational(r)), magnitude_bits(turns) + 3) + guard_bits;
  Mpfr value(bits);
  mpfr_set_d(value.v, r, MPFR_RNDN);
  mpz_class minus = -turns.get_num();
  return residue(value, minus.get_mpz_t(), bits);
}

}  // namespace hipair::simulation
