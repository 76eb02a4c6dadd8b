// HIPAIR — exact order of slice points (exact_order.hpp).
#include "tolerance/exact_order.hpp"

#include <hipair/error.hpp>

#include <utility>

namespace hipair::tolerance_detail {
namespace {

int sign_of(const Rational& x) { return sgn(x); }

// An isolating interval being refined: the root is `value` when `exact`, else in (lo, hi)
// with the polynomial of sign `sign_lo` at lo and -sign_lo at hi.
struct Enclosure {
  const std::vector<mpz_class>* polynomial = nullptr;
  Rational lo, hi;
  int sign_lo = 0;
  bool exact = false;

  explicit Enclosure(const AlgebraicNumber& a) : polynomial(&a.polynomial), lo(a.lower), hi(a.upper), exact(a.exact) {
    if (exact) {
      hi = lo;
      return;
    }
    sign_lo = sign_at(a.polynomial, lo);
    int sign_hi = sign_at(a.polynomial, hi);
    // An end may be another root of the polynomial: the sign just inside it is then the
    // opposite of the other end's (one simple root in between).
    if (sign_lo == 0) sign_lo = -sign_hi;
    else if (sign_hi == 0) sign_hi = -sign_lo;
    if (sign_lo == 0 || sign_lo == sign_hi || !(lo < hi))
      throw GeometryError("exact order: an algebraic number's isolating interval " + a.to_string() +
                          " does not bracket a sign change");
  }
  void bisect() {
    if (exact) return;
    Rational m = (lo + hi) / 2;
    int s = sign_at(*polynomial, m);
    if (s == 0) {
      lo = hi = m;
      exact = true;
    } else if (s == sign_lo) {
      lo = m;
    } else {
      hi = m;
    }
  }
};

using QPoly = std::vector<Rational>;   // ascending powers, no trailing zeros

void trim(QPoly& p) {
  while (!p.empty() && p.back() == 0) p.pop_back();
}

QPoly remainder(QPoly a, const QPoly& b) {
  while (a.size() >= b.size() && !a.empty()) {
    Rational factor = a.back() / b.back();
    std::size_t shift = a.size() - b.size();
    for (std::size_t i = 0; i < b.size(); ++i) a[shift + i] -= factor * b[i];
    a.pop_back();   // the leading term cancels exactly
    trim(a);
  }
  return a;
}

QPoly gcd(const std::vector<mpz_class>& p, const std::vector<mpz_class>& q) {
  QPoly a(p.begin(), p.end()), b(q.begin(), q.end());
  trim(a);
  trim(b);
  while (!b.empty()) {
    QPoly r = remainder(a, b);
    a = std::move(b);
    b = std::move(r);
  }
  return a;
}

int sign_at_q(const QPoly& p, const Rational& x) {
  Rational value = 0;
  for (std::size_t i = p.size(); i-- > 0;) value = value * x + p[i];
  return sign_of(value);
}

}  // namespace

int sign_at(const std::vector<mpz_class>& polynomial, const Rational& x) {
  Rational value = 0;
  for (std::size_t i = polynomial.size(); i-- > 0;) value = value * x + polynomial[i];
  return sign_of(value);
}

int compare(const AlgebraicNumber& a, const Rational& x) {
  if (a.exact) return sign_of(a.lower - x);
  if (x <= a.lower) return 1;
  if (x >= a.upper) return -1;
  int s = sign_at(a.polynomial, x);
  if (s == 0) return 0;
  // One simple root in (lower, upper): x is below it iff the sign at x is the sign at lower
  // (or, should lower be another root of the polynomial, not the sign at upper).
  int s_lo = sign_at(a.polynomial, a.lower);
  if (s_lo != 0) return s == s_lo ? 1 : -1;
  int s_hi = sign_at(a.polynomial, a.upper);
  if (s_hi == 0)
    throw GeometryError("exact order: an algebraic number's isolating interval " + a.to_string() +
                        " does not bracket a sign change");
  return s == s_hi ? -1 : 1;
}

int compare(const AlgebraicNumber& a, const AlgebraicNumber& b) {
  if (a.exact) return -compare(b, a.lower);
  if (b.exact) return compare(a, b.lower);
  Enclosure ea(a), eb(b);
  QPoly g = gcd(a.polynomial, b.polynomial);
  bool may_be_equal = g.size() >= 2;
  // Each isolating interval holds one root of its polynomial, so g has at most one root in the
  // intersection of the two, and it is a = b when it does.
  for (int step = 0; step < 100000; ++step) {
    if (ea.exact) return -compare(b, ea.lo);
    if (eb.exact) return compare(a, eb.lo);
    if (ea.hi <= eb.lo) return -1;
    if (eb.hi <= ea.lo) return 1;
    if (may_be_equal) {
      const Rational& l = ea.lo > eb.lo ? ea.lo : eb.lo;
      const Rational& u = ea.hi < eb.hi ? ea.hi : eb.hi;
      int gl = sign_at_q(g, l), gu = sign_at_q(g, u);
      if (gl * gu < 0) return 0;   // g changes sign inside: the common root, a = b
      // Same nonzero signs: no root of g in (l, u), a != b; zero at an end: refine and retry.
    }
    ea.bisect();
    eb.bisect();
  }
  throw GeometryError("exact order: two algebraic numbers could not be separated");
}

AlgebraicNumber exact_algebraic(const Rational& x) {
  Rational q = x;
  q.canonicalize();
  AlgebraicNumber a;
  a.polynomial = {-q.get_num(), q.get_den()};
  a.lower = a.upper = q;
  a.exact = true;
  return a;
}

std::optional<AlgebraicNumber> other_half_turn(const AlgebraicNumber& a) {
  if (compare(a, Rational(0)) == 0) return std::nullopt;
  Enclosure e(a);
  for (int step = 0; step < 100000 && !e.exact && !(e.hi < 0 || e.lo > 0); ++step) e.bisect();
  if (e.exact) return exact_algebraic(Rational(-1) / e.lo);
  if (!(e.hi < 0 || e.lo > 0)) throw GeometryError("exact order: " + a.to_string() + " could not be separated from 0");
  AlgebraicNumber r;
  const std::size_t d = a.polynomial.size() - 1;
  r.polynomial.resize(d + 1);
  // p(-1/t) t^d = sum_i a_i (-1)^i t^(d - i)
  for (std::size_t j = 0; j <= d; ++j) r.polynomial[j] = (d - j) % 2 == 0 ? a.polynomial[d - j] : mpz_class(-a.polynomial[d - j]);
  r.lower = Rational(-1) / e.lo;
  r.upper = Rational(-1) / e.hi;
  r.lower.canonicalize();
  r.upper.canonicalize();
  return r;
}

PointMatch match_point(const std::vector<Slice::Point>& points, const Rational& t, bool in_contact) {
  PointMatch match;
  for (std::size_t k = 0; k < points.size(); ++k) {
    int c = compare(points[k].at, t);
    if (c == 0) match.at = k;
    else if (c < 0) match.below = k + 1;
  }
  if (match.at || !in_contact) return match;
  bool has_lower = match.below > 0, has_upper = match.below < points.size();
  if (has_lower != has_upper) {
    match.at = has_lower ? match.below - 1 : match.below;
    return match;
  }
  if (!has_lower) return match;
  // Distances t - a and b - t, enclosed exactly and refined until they separate.
  Enclosure a(points[match.below - 1].at), b(points[match.below].at);
  for (int step = 0; step < 256; ++step) {
    Rational da_lo = t - a.hi, da_hi = t - a.lo, db_lo = b.lo - t, db_hi = b.hi - t;
    if (da_hi < db_lo) {
      match.at = match.below - 1;
      return match;
    }
    if (db_hi < da_lo) {
      match.at = match.below;
      return match;
    }
    if (a.exact && b.exact) break;   // equal distances
    a.bisect();
    b.bisect();
  }
  match.ambiguous = true;
  return match;
}

std::vector<std::size_t> free_intervals_meeting(const Slice& slice, const AlgebraicNumber* lower,
                                                const AlgebraicNumber* upper) {
  std::vector<std::size_t> meeting;
  for (std::size_t j = 0; j < slice.intervals.size(); ++j) {
    if (slice.intervals[j].kind != CellKind::free) continue;
    bool below_upper = j == 0 || !upper || compare(slice.points[j - 1].at, *upper) < 0;            // a < upper
    bool above_lower = j == slice.points.size() || !lower || compare(slice.points[j].at, *lower) > 0;   // b > lower
    if (below_upper && above_lower) meeting.push_back(j);
  }
  return meeting;
}

std::size_t free_intervals_in_channel(const Slice& slice, const AlgebraicNumber& lower, const AlgebraicNumber& upper) {
  return free_intervals_meeting(slice, &lower, &upper).size();
}

}  // namespace hipair::tolerance_detail
