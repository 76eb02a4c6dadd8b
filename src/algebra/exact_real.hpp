// Exact univariate algebra for the C-space adaptor: integer polynomials, Sturm sequences,
// real root isolation, real algebraic numbers, and bivariate substitutions. CGAL-free, so that
// point location and path queries never touch the arrangement code (and are thread-safe).
#pragma once

#include "algebra/polynomial.hpp"

#include <hipair/rational.hpp>

#include <gmpxx.h>

#include <string>
#include <vector>

namespace hipair::cspace::algebra {

/// Integer polynomial, ascending coefficients, no trailing zero; empty is the zero polynomial.
using Polynomial = std::vector<mpz_class>;

int degree(const Polynomial& p);
void trim(Polynomial& p);
Polynomial derivative(const Polynomial& p);
/// Sign of p at x, exact.
int sign_at(const Polynomial& p, const Rational& x);
/// Value of p at x, exact.
Rational value_at(const Polynomial& p, const Rational& x);
/// p divided by the gcd of its coefficients, with a positive leading coefficient.
Polynomial primitive_part(const Polynomial& p);
/// Primitive gcd over Q (positive leading coefficient); gcd(0, 0) is 0.
Polynomial gcd(const Polynomial& a, const Polynomial& b);
/// p / gcd(p, p'), primitive.
Polynomial square_free_part(const Polynomial& p);
/// The primitive integer polynomial proportional to the rational coefficients.
Polynomial from_rationals(const std::vector<Rational>& coefficients);
/// "3*x^2 - 2*x + 1".
std::string to_string(const Polynomial& p, const std::string& variable);

/// Certified double bounds of a rational: lower(r) <= r <= upper(r).
double lower_double(const Rational& r);
double upper_double(const Rational& r);

/// Sturm sequence of a square-free polynomial (counts distinct real roots).
class SturmSequence {
 public:
  explicit SturmSequence(const Polynomial& square_free);
  /// Distinct real roots in (a, b].
  int count(const Rational& a, const Rational& b) const;
  /// Distinct real roots in (-infinity, b].
  int count_up_to(const Rational& b) const;
  int total() const;

 private:
  int variations(const Rational& x) const;
  int variations_at_infinity(bool positive) const;
  std::vector<Polynomial> sequence_;
};

/// A real algebraic number: `value` when exact, else the unique root of `polynomial` in the
/// open interval (lower, upper), where the polynomial has opposite non-zero signs at the ends.
/// The polynomial is square-free. Methods never modify shared state: refining happens on
/// copies, so a const Real may be read from several threads.
struct Real {
  Polynomial polynomial;
  Rational lower;
  Rational upper;
  bool exact = false;

  static Real from_rational(const Rational& value);
  /// Halves the interval (or finds the value exactly).
  void refine();
  /// Refines until upper - lower <= width (or exact).
  void refine_to(const Rational& width);
  /// Certified double enclosure.
  double lower_bound() const { return lower_double(lower); }
  double upper_bound() const { return upper_double(upper); }
  double approximate() const;
  /// Makes the number exact exactly when it is rational (complete: narrow-interval refinement
  /// first for denominators below about 2^31, then algebra::rational_root, rational_root.hpp).
  void detect_rational();
  /// Exact comparison with a rational: -1, 0, +1.
  int compare(const Rational& r) const;
  /// Exact text: "p(x) = 0, x in [lo, hi]" or the rational.
  std::string description(const std::string& variable = "x") const;
};

/// Exact comparison of two real algebraic numbers: -1, 0, +1.
int compare(const Real& a, const Real& b);
/// compare(a, b) == 0, exactly, for callers that need only equality: overlapping enclosures
/// that the double filter cannot separate go straight to the gcd's roots in the common part
/// (compare first refines both copies by 2^-20 in case they are distinct; for equality that
/// refinement only adds work when they are equal).
bool equal(const Real& a, const Real& b);
/// A rational strictly between a < b, as simple as cheaply possible. \pre a < b.
Rational rational_between(const Real& a, const Real& b);
/// The simplest rational (smallest denominator) in the open interval (lo, hi). \pre lo < hi.
Rational simplest_between(const Rational& lo, const Rational& hi);
/// simplest_between's descent on GMP integers, whatever the ends' sizes (simplest_between takes
/// it when an end's numerator or denominator reaches 2^62; tests compare the two). \pre lo < hi.
Rational simplest_between_gmp(const Rational& lo, const Rational& hi);

/// All distinct real roots of p in the closed interval [lo, hi], ascending, isolated.
/// A zero polynomial has no isolated roots (the caller treats it).
std::vector<Real> real_roots(const Polynomial& p, const Rational& lo, const Rational& hi);
/// All distinct real roots of p, ascending.
std::vector<Real> real_roots(const Polynomial& p);
/// The same roots as real_roots(p, lo, hi) (closed interval, ascending, distinct), isolated by
/// Descartes' rule of signs with dyadic bisection of [lo, hi] (Vincent-Collins-Akritas: exact
/// integer Taylor shifts at the halves of the interval), after square_free_test: no Sturm
/// sequence. Every isolating interval is a dyadic part (lower, upper) of [lo, hi] holding
/// exactly one root of the square-free part, certified by one sign variation of its
/// Moebius-transformed coefficients, with non-zero opposite signs at its ends. The intervals
/// lie on the same bisection grid as real_roots' but may be narrower (one sign variation can
/// need more halvings than a Sturm count of one).
std::vector<Real> descartes_real_roots(const Polynomial& p, const Rational& lo, const Rational& hi);
/// Primitive square-free part of p with a positive leading coefficient, as square_free_part,
/// but p itself (made primitive) without an exact gcd when gcd(p, p') is trivial modulo one of
/// a few word-size primes not dividing the leading coefficient (which certifies that p is
/// square-free over Q: the reduction of the true gcd divides the modular one and keeps its
/// degree). `exact_needed`, when given, is set when the exact gcd was computed.
Polynomial square_free_test(const Polynomial& p, bool* exact_needed = nullptr);

/// The index-th (0-based, ascending) distinct real root of p. \throws NumericError if none.
Real nth_real_root(const Polynomial& p, int index);
/// The index-th (0-based, ascending, counted over the whole real line) distinct real root of
/// p, known to lie in the open interval (lo, hi). \throws NumericError if it does not.
Real nth_real_root_in(const Polynomial& p, int index, const Rational& lo, const Rational& hi);
/// Refines r's isolating interval to width <= `width` by bisection on dyadic rationals
/// (integer arithmetic, no rational canonicalisation): the same number, but not the same
/// interval as Real::refine_to (use it where the interval is private).
void refine_dyadically(Real& r, const Rational& width);
/// Bound B with every real root in (-B, B).
Rational root_bound(const Polynomial& p);

// ---------------------------------------------------------------- bivariate substitutions

/// f(x, y) at a rational x: a polynomial in y (scaled to integers, same roots).
Polynomial substitute_x(const IntegerPolynomial2& f, const Rational& x);
/// f(x, y) at a rational y: a polynomial in x.
Polynomial substitute_y(const IntegerPolynomial2& f, const Rational& y);
/// f(x0 + u dx, y0 + u dy): a polynomial in u (scaled to integers).
Polynomial substitute_line(const IntegerPolynomial2& f, const Rational& x0, const Rational& dx,
                           const Rational& y0, const Rational& dy);
/// Sign of f at a rational point.
int sign_at(const IntegerPolynomial2& f, const Rational& x, const Rational& y);
/// The univariate polynomial in x of a 1-D contact curve (coefficients c[i][0]).
Polynomial univariate_x(const IntegerPolynomial2& f);
/// Does f vanish at the point (x, y) where x is rational and y is algebraic?
bool vanishes_at(const IntegerPolynomial2& f, const Rational& x, const Real& y);
/// Does f vanish at the point (x, y) where y is rational and x is algebraic?
bool vanishes_at(const IntegerPolynomial2& f, const Real& x, const Rational& y);
/// Sign of p at the algebraic u, exact.
int sign_at(const Polynomial& p, const Real& u);
/// Sign of f at (x, y) with x rational and y algebraic, exact.
int sign_at(const IntegerPolynomial2& f, const Rational& x, const Real& y);
/// Sign of f at (x, y) with x algebraic and y rational, exact.
int sign_at(const IntegerPolynomial2& f, const Real& x, const Rational& y);
/// p(u) = 0 at the algebraic u? (gcd test)
bool vanishes_at(const Polynomial& p, const Real& u);
/// "3*x^2*y - y + 1".
std::string to_string(const IntegerPolynomial2& f, const std::string& x, const std::string& y);

// ---------------------------------------------------------------- certified double evaluation

/// Closed interval of doubles, rounded outwards.
struct Interval {
  double lo = 0;
  double hi = 0;
  bool contains_zero() const { return lo <= 0 && 0 <= hi; }
};
namespace interval_detail {
// Outward rounding without changing the rounding mode: a round-to-nearest result r of an exact
// x satisfies |x - r| <= 2^-53 |r| (plus the smallest subnormal when underflowing), so
// r -+ (2^-52 |r| + 2 denorm_min), itself rounded to nearest, still encloses x.
// An overflowed bound (an enclosed coefficient beyond the doubles' range is [DBL_MAX, inf]) stays
// a bound: +inf as a lower bound becomes DBL_MAX, -inf as an upper one -DBL_MAX (v - inf would be
// NaN, and a NaN bound silently drops out of the comparisons); NaN widens to the whole line.
inline double down(double v) {
  if (!(v < __builtin_inf())) return v == v ? 1.7976931348623157e308 : -__builtin_inf();
  return v - (__builtin_fabs(v) * 2.220446049250313e-16 + 2 * 4.9406564584124654e-324);
}
inline double up(double v) {
  if (!(v > -__builtin_inf())) return v == v ? -1.7976931348623157e308 : __builtin_inf();
  return v + (__builtin_fabs(v) * 2.220446049250313e-16 + 2 * 4.9406564584124654e-324);
}
// An end product 0 * inf (a bound of 0 times an unbounded end) is 0: the hull of the products
// of the real numbers in the two intervals, as in IEEE 1788.
inline double end_product(double a, double b) {
  double p = a * b;
  return p == p ? p : 0.0;
}
}  // namespace interval_detail

inline Interval operator+(Interval a, Interval b) {
  return {interval_detail::down(a.lo + b.lo), interval_detail::up(a.hi + b.hi)};
}
inline Interval operator*(Interval a, Interval b) {
  using interval_detail::end_product;
  double p1 = end_product(a.lo, b.lo), p2 = end_product(a.lo, b.hi), p3 = end_product(a.hi, b.lo),
         p4 = end_product(a.hi, b.hi);
  double lo = p1 < p2 ? p1 : p2, hi = p1 < p2 ? p2 : p1;
  lo = lo < p3 ? lo : p3;
  hi = hi < p3 ? p3 : hi;
  lo = lo < p4 ? lo : p4;
  hi = hi < p4 ? p4 : hi;
  return {interval_detail::down(lo), interval_detail::up(hi)};
}
namespace interval_detail {
// a * b when b's sign is known, with the same bounds as operator* in two products instead of
// four: rounding to nearest is monotone in each factor (and end_product's 0 * inf = 0 keeps
// that order), so of the four end products the least and the greatest are these two.
// times_nonnegative needs b.lo >= 0, times_nonpositive b.hi <= 0.
inline Interval times_nonnegative(Interval a, Interval b) {
  double lo, hi;
  if (a.lo >= 0) {
    lo = end_product(a.lo, b.lo);
    hi = end_product(a.hi, b.hi);
  } else if (a.hi <= 0) {
    lo = end_product(a.lo, b.hi);
    hi = end_product(a.hi, b.lo);
  } else {
    lo = end_product(a.lo, b.hi);
    hi = end_product(a.hi, b.hi);
  }
  return {down(lo), up(hi)};
}
inline Interval times_nonpositive(Interval a, Interval b) {
  double lo, hi;
  if (a.lo >= 0) {
    lo = end_product(a.hi, b.lo);
    hi = end_product(a.lo, b.hi);
  } else if (a.hi <= 0) {
    lo = end_product(a.hi, b.hi);
    hi = end_product(a.lo, b.lo);
  } else {
    lo = end_product(a.hi, b.lo);
    hi = end_product(a.lo, b.lo);
  }
  return {down(lo), up(hi)};
}
}  // namespace interval_detail

Interval enclose(const Rational& r);
Interval enclose(const mpz_class& z);

/// The polynomial sum c_i x^i (c: lowest degree first) over x, certified enclosure by interval
/// Horner: v = v * x + c_i from v = 0, each product operator*'s bounds (two end products when x
/// keeps one sign), each sum operator+'s. Empty c: {0, 0}.
Interval horner(const std::vector<Interval>& c, Interval x);
/// The same from v = the leading coefficient (one step fewer: the first product, 0 times x, is
/// not taken, so the bounds can be a rounding narrower than horner()'s). c not empty.
Interval horner_from_leading(const std::vector<Interval>& c, Interval x);

/// f over the box x in X, y in Y, certified enclosure.
class IntervalPolynomial2 {
 public:
  IntervalPolynomial2() = default;
  explicit IntervalPolynomial2(const IntegerPolynomial2& f);
  Interval evaluate(Interval x, Interval y) const;
  /// The rows of f at y (row i: the sum over j of c_ij y^j, enclosed), and f at x from them:
  /// evaluate_rows(x, rows) with `rows` from rows_at(y, rows) is evaluate(x, y) bound for bound
  /// (the same operations in the same order), so that boxes sharing their y share the rows.
  void rows_at(Interval y, std::vector<Interval>& rows) const;
  Interval evaluate_rows(Interval x, const std::vector<Interval>& rows) const;
  /// f at doubles with a certified bound on |value - exact f(x, y)|: returns value and bound.
  double evaluate(double x, double y, double* error_bound) const;
  bool empty() const { return rows_.empty(); }

 private:
  std::vector<std::vector<Interval>> rows_;   // rows_[i][j] encloses c[i][j]
  std::vector<std::vector<double>> nearest_;  // nearest doubles
  int total_degree_ = 0;
};

}  // namespace hipair::cspace::algebra
