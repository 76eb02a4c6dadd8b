// Session 40 (scale40): the multi-precision interval filter of sign_at(Polynomial, Real).
#include "algebra/multiprecision_sign.hpp"

#include <mpfr.h>

#include <algorithm>
#include <cstddef>
#include <functional>
#include <memory>
#include <unordered_map>
#include <vector>
#include <utility>

namespace hipair::cspace::algebra {

namespace {

// An MPFR number owned for the scope.
struct Mp {
  mpfr_t v;
  explicit Mp(long bits) { mpfr_init2(v, static_cast<mpfr_prec_t>(bits)); }
  ~Mp() { mpfr_clear(v); }
  Mp(const Mp&) = delete;
  Mp& operator=(const Mp&) = delete;
  void widen(long bits) { mpfr_prec_round(v, static_cast<mpfr_prec_t>(bits), MPFR_RNDN); }  // exact when growing
};

// The working numbers of one evaluation, at one precision.
struct Scratch {
  Mp lo, hi, t1, t2, t3, t4;
  explicit Scratch(long bits) : lo(bits), hi(bits), t1(bits), t2(bits), t3(bits), t4(bits) {}
  void widen(long bits) {
    for (Mp* m : {&lo, &hi, &t1, &t2, &t3, &t4}) mpfr_set_prec(m->v, static_cast<mpfr_prec_t>(bits));
  }
};

// -1 / +1 when the enclosure [lo, hi] excludes zero, 0 when it does not.
int enclosure_sign(const Scratch& s) {
  if (mpfr_sgn(s.lo.v) > 0) return 1;
  if (mpfr_sgn(s.hi.v) < 0) return -1;
  return 0;
}

// An integer polynomial's coefficients as MPFR numbers, each exact (its own precision): the
// Horner steps below add them without converting an integer per step (mpfr_add rounds the exact
// sum as mpfr_add_z does).
class MpPolynomial {
 public:
  explicit MpPolynomial(const Polynomial& p) {
    c_.resize(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
      const auto bits = static_cast<mpfr_prec_t>(std::max<std::size_t>(mpz_sizeinbase(p[i].get_mpz_t(), 2), MPFR_PREC_MIN));
      mpfr_init2(&c_[i], bits);
      mpfr_set_z(&c_[i], p[i].get_mpz_t(), MPFR_RNDN);   // exact
    }
  }
  ~MpPolynomial() {
    for (__mpfr_struct& c : c_) mpfr_clear(&c);
  }
  MpPolynomial(const MpPolynomial&) = delete;
  MpPolynomial& operator=(const MpPolynomial&) = delete;
  std::size_t size() const { return c_.size(); }
  mpfr_srcptr operator[](std::size_t i) const { return &c_[i]; }

 private:
  std::vector<__mpfr_struct> c_;
};

// The enclosures computed on this thread (multiprecision_enclosures(), for tests).
thread_local long enclosures = 0;

// [s.lo, s.hi] encloses p(x) at the MPFR number x (Horner, each bound rounded outwards).
void enclose_at_point(const MpPolynomial& p, mpfr_srcptr x, Scratch& s) {
  ++enclosures;
  mpfr_set(s.lo.v, p[p.size() - 1], MPFR_RNDD);
  mpfr_set(s.hi.v, p[p.size() - 1], MPFR_RNDU);
  const bool negative = mpfr_sgn(x) < 0;
  for (std::size_t k = p.size() - 1; k-- > 0;) {
    // v in [lo, hi]: v x in [lo x, hi x] when x >= 0, [hi x, lo x] when x < 0
    mpfr_mul(s.t1.v, negative ? s.hi.v : s.lo.v, x, MPFR_RNDD);
    mpfr_mul(s.t2.v, negative ? s.lo.v : s.hi.v, x, MPFR_RNDU);
    mpfr_add(s.lo.v, s.t1.v, p[k], MPFR_RNDD);
    mpfr_add(s.hi.v, s.t2.v, p[k], MPFR_RNDU);
  }
}

using Operation = int (*)(mpfr_ptr, mpfr_srcptr, mpfr_srcptr, mpfr_rnd_t);

// out = the least (rounding down) or the greatest (rounding up) of the four end results of
// [lo, hi] op [a, b] (op: product, or quotient when [a, b] excludes zero), each rounded that
// way; t is scratch.
void extreme_product(mpfr_ptr out, mpfr_ptr t, mpfr_srcptr lo, mpfr_srcptr hi, mpfr_srcptr a, mpfr_srcptr b,
                     mpfr_rnd_t rounding, Operation op = mpfr_mul) {
  const bool least = rounding == MPFR_RNDD;
  op(out, lo, a, rounding);
  for (auto [x, y] : {std::pair{lo, b}, std::pair{hi, a}, std::pair{hi, b}}) {
    op(t, x, y, rounding);
    if (least ? mpfr_less_p(t, out) : mpfr_greater_p(t, out)) mpfr_swap(out, t);
  }
}

// [s.lo, s.hi] encloses p over [a, b] (a <= b; interval Horner, each bound rounded outwards).
void enclose_over(const MpPolynomial& p, mpfr_srcptr a, mpfr_srcptr b, Scratch& s) {
  ++enclosures;
  mpfr_set(s.lo.v, p[p.size() - 1], MPFR_RNDD);
  mpfr_set(s.hi.v, p[p.size() - 1], MPFR_RNDU);
  for (std::size_t k = p.size() - 1; k-- > 0;) {
    extreme_product(s.t1.v, s.t2.v, s.lo.v, s.hi.v, a, b, MPFR_RNDD);
    extreme_product(s.t3.v, s.t4.v, s.lo.v, s.hi.v, a, b, MPFR_RNDU);
    mpfr_add(s.lo.v, s.t1.v, p[k], MPFR_RNDD);
    mpfr_add(s.hi.v, s.t3.v, p[k], MPFR_RNDU);
  }
}

long coefficient_bits(const Polynomial& p) {
  std::size_t bits = 0;
  for (const mpz_class& c : p) bits = std::max(bits, mpz_sizeinbase(c.get_mpz_t(), 2));
  return static_cast<long>(bits);
}

Rational to_rational(mpfr_srcptr v) {
  if (mpfr_zero_p(v)) return Rational(0);   // (its exponent is not a number's)
  mpz_class mantissa;
  const mpfr_exp_t e = mpfr_get_z_2exp(mantissa.get_mpz_t(), v);
  Rational r(mantissa);
  if (e > 0) mpz_mul_2exp(r.get_num_mpz_t(), r.get_num_mpz_t(), static_cast<mp_bitcnt_t>(e));
  if (e < 0) mpz_mul_2exp(r.get_den_mpz_t(), r.get_den_mpz_t(), static_cast<mp_bitcnt_t>(-e));
  r.canonicalize();
  return r;
}

}  // namespace

long multiprecision_enclosures() { return enclosures; }

MultiprecisionEnclosure multiprecision_enclosure_over(const Polynomial& p, const Rational& a, const Rational& b, long bits) {
  Scratch s(bits);
  Mp lo(bits), hi(bits);
  mpfr_set_q(lo.v, a.get_mpq_t(), MPFR_RNDD);
  mpfr_set_q(hi.v, b.get_mpq_t(), MPFR_RNDU);
  enclose_over(MpPolynomial(p), lo.v, hi.v, s);
  return {a, to_rational(s.lo.v), to_rational(s.hi.v)};
}

MultiprecisionEnclosure multiprecision_enclosure_at_point(const Polynomial& p, const Rational& x, long bits) {
  Scratch s(bits);
  Mp point(bits);
  mpfr_set_q(point.v, x.get_mpq_t(), MPFR_RNDN);
  enclose_at_point(MpPolynomial(p), point.v, s);
  return {to_rational(point.v), to_rational(s.lo.v), to_rational(s.hi.v)};
}

namespace {

// rounding errors are relative to the terms: a start of 192 bits decides values down to about
// 10^-40 of their terms; the cap allows cancellation well beyond the coefficients' width
MultiprecisionBits bits_for_width(long bits) { return {bits, 192, std::max(4 * bits + 512, 1024L)}; }

}  // namespace

MultiprecisionBits multiprecision_sign_bits(const Polynomial& p, const Real& u) {
  return bits_for_width(std::max(coefficient_bits(p), coefficient_bits(u.polynomial)));
}

namespace {

// u's polynomial q and its derivative as MPFR numbers (shared by the brackets of one number).
struct BracketPolynomials {
  MpPolynomial q, dq;
  explicit BracketPolynomials(const Polynomial& p) : q(p), dq(derivative(p)) {}
};

// Session 46 (scale46): the narrowest bracket a number's Bracket reached, remembered per thread,
// so that the next order or sign of the same number (the same polynomial and isolating interval)
// starts from it instead of u's rational interval (a sweep compares one x-coordinate with many
// others; each comparison narrowed both brackets afresh). Any bracket kept holds u with the
// Bracket's invariants (an MPFR end lies strictly inside u's interval, on q's side of u it was
// certified on), so where a bracket starts changes how much work a decision takes, never the
// decision: every order and sign is still given only by disjoint or zero-free enclosures.
struct RememberedBracket {
  Polynomial polynomial;   // the number's key, with its interval
  Rational lower, upper;
  std::shared_ptr<const BracketPolynomials> polynomials;
  Mp lo{MPFR_PREC_MIN}, hi{MPFR_PREC_MIN};   // at their own precision
  bool narrowed = false, left_rational = true, right_rational = true;
  int low_sign = 0;   // q's sign at u.lower once known (0: not yet)
  explicit RememberedBracket(const Real& u)
      : polynomial(u.polynomial), lower(u.lower), upper(u.upper), polynomials(std::make_shared<const BracketPolynomials>(u.polynomial)) {}
};

std::size_t mix(std::size_t h, std::size_t v) { return h ^ (v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2)); }
std::size_t integer_hash(std::size_t h, mpz_srcptr z) {
  h = mix(h, static_cast<std::size_t>(z->_mp_size));
  return z->_mp_size == 0 ? h : mix(h, static_cast<std::size_t>(z->_mp_d[0]));
}

thread_local long memo_hits = 0;
thread_local bool memo_enabled = true;

class BracketMemo {
 public:
  std::shared_ptr<RememberedBracket> find(const Real& u) {
    std::size_t h = 0;
    for (const mpz_class& c : u.polynomial) h = integer_hash(h, c.get_mpz_t());
    for (const Rational* r : {&u.lower, &u.upper}) h = integer_hash(integer_hash(h, r->get_num_mpz_t()), r->get_den_mpz_t());
    auto it = entries_.find(h);
    if (it != entries_.end() && it->second->polynomial == u.polynomial && it->second->lower == u.lower && it->second->upper == u.upper) {
      ++memo_hits;
      return it->second;
    }
    if (it == entries_.end() && entries_.size() >= kCapacity) entries_.clear();   // bounded memory
    auto entry = std::make_shared<RememberedBracket>(u);
    entries_[h] = entry;   // (a colliding number's entry replaced; a live bracket keeps its own)
    return entry;
  }

 private:
  static constexpr std::size_t kCapacity = 4096;
  std::unordered_map<std::size_t, std::shared_ptr<RememberedBracket>> entries_;
};

BracketMemo& bracket_memo() {
  thread_local BracketMemo memo;
  return memo;
}

// The bracket of a non-exact u narrowed in MPFR: [lo, hi] encloses an open interval (left, right)
// holding u, where an end is u's rational end (enclosed outwards) until a midpoint replaces it
// (then the MPFR number itself). A midpoint m = (lo + hi) / 2 (rounded to nearest) is kept only
// when it lies strictly inside (left, right) (compared exactly with the rational end or the MPFR
// one) and the sign of u's polynomial q at m is certified non-zero by a point enclosure; m then
// replaces the end whose sign it shares (q changes sign once in u's interval, at u). With
// `remember`, the bracket starts where the thread's last bracket of the same number ended (see
// RememberedBracket) and leaves its own there when narrower.
class Bracket {
 public:
  Bracket(const Real& u, long bits, bool remember = true)
      : u_(u), memo_(remember && memo_enabled ? bracket_memo().find(u) : nullptr),
        polynomials_(memo_ ? memo_->polynomials : std::make_shared<const BracketPolynomials>(u.polynomial)),
        q_(polynomials_->q), dq_(polynomials_->dq), a_(bits), b_(bits), m_(bits), d_lo_(bits), d_hi_(bits), n_(bits) {
    mpfr_set_q(a_.v, u.lower.get_mpq_t(), MPFR_RNDD);
    mpfr_set_q(b_.v, u.upper.get_mpq_t(), MPFR_RNDU);
    if (memo_) recall(*memo_);
  }
  ~Bracket() {
    if (memo_) remember(*memo_);
  }
  Bracket(const Bracket&) = delete;
  Bracket& operator=(const Bracket&) = delete;
  mpfr_srcptr lo() const { return a_.v; }
  mpfr_srcptr hi() const { return b_.v; }
  /// Up to `count` halvings at the current precision; the number done (fewer: this precision's
  /// floor, a midpoint not strictly inside or too near u for a point sign).
  int halve(int count, Scratch& s) {
    if (low_sign_ == 0) {
      // non-zero, the opposite of q's sign at u.upper: the sign of q over the enclosure of
      // u.lower when it excludes zero, exactly otherwise
      // (a remembered MPFR end is no longer u.lower's enclosure)
      mpfr_set_q(m_.v, u_.lower.get_mpq_t(), MPFR_RNDU);
      if (left_rational_) {
        enclose_over(q_, a_.v, m_.v, s);
      } else {
        Mp lower(mpfr_get_prec(a_.v));
        mpfr_set_q(lower.v, u_.lower.get_mpq_t(), MPFR_RNDD);
        enclose_over(q_, lower.v, m_.v, s);
      }
      low_sign_ = enclosure_sign(s);
      if (low_sign_ == 0) low_sign_ = sign_at(u_.polynomial, u_.lower);
    }
    int done = 0;
    for (; done < count; ++done) {
      mpfr_add(m_.v, a_.v, b_.v, MPFR_RNDN);
      mpfr_div_2ui(m_.v, m_.v, 1, MPFR_RNDN);
      const bool inside = (left_rational_ ? mpfr_cmp_q(m_.v, u_.lower.get_mpq_t()) > 0 : mpfr_cmp(m_.v, a_.v) > 0) &&
                          (right_rational_ ? mpfr_cmp_q(m_.v, u_.upper.get_mpq_t()) < 0 : mpfr_cmp(m_.v, b_.v) < 0);
      if (!inside) break;
      enclose_at_point(q_, m_.v, s);
      const int sign = enclosure_sign(s);
      if (sign == 0) break;   // m at (or too near) u: a point sign this precision cannot give
      if (sign == low_sign_) {
        mpfr_set(a_.v, m_.v, MPFR_RNDN);   // exact: same precision
        left_rational_ = false;
      } else {
        mpfr_set(b_.v, m_.v, MPFR_RNDN);
        right_rational_ = false;
      }
    }
    return done;
  }
  /// The precision raised to `bits`: a rational end enclosed afresh (u's interval may be far
  /// narrower than the old precision's ulp), a midpoint kept exactly.
  void widen(long bits) {
    a_.widen(bits);
    b_.widen(bits);
    if (left_rational_) mpfr_set_q(a_.v, u_.lower.get_mpq_t(), MPFR_RNDD);
    if (right_rational_) mpfr_set_q(b_.v, u_.upper.get_mpq_t(), MPFR_RNDU);
    for (Mp* m : {&m_, &d_lo_, &d_hi_, &n_}) mpfr_set_prec(m->v, static_cast<mpfr_prec_t>(bits));
  }
  /// One interval Newton step: u = m - q(m) / q'(xi) for the midpoint m and some xi in the
  /// bracket (the mean value theorem), so u lies in m - Q(m) / Q'([lo, hi]) for enclosures Q, Q'
  /// (every bound rounded outwards); an end of that interval strictly inside the bracket's
  /// (left, right) replaces it (u may then be that end: the bracket is closed from here on).
  /// Nothing when Q' contains zero. Quadratic convergence near a simple root, at this precision.
  void newton(Scratch& s) {
    enclose_over(dq_, a_.v, b_.v, s);
    if (mpfr_sgn(s.lo.v) <= 0 && mpfr_sgn(s.hi.v) >= 0) return;
    mpfr_swap(d_lo_.v, s.lo.v);   // (the same precision)
    mpfr_swap(d_hi_.v, s.hi.v);
    mpfr_add(m_.v, a_.v, b_.v, MPFR_RNDN);
    mpfr_div_2ui(m_.v, m_.v, 1, MPFR_RNDN);
    enclose_at_point(q_, m_.v, s);
    // the new lower end: m - (the greatest quotient, rounded up), rounded down
    extreme_product(s.t1.v, s.t2.v, s.lo.v, s.hi.v, d_lo_.v, d_hi_.v, MPFR_RNDU, mpfr_div);
    mpfr_sub(n_.v, m_.v, s.t1.v, MPFR_RNDD);
    if (left_rational_ ? mpfr_cmp_q(n_.v, u_.lower.get_mpq_t()) > 0 : mpfr_greater_p(n_.v, a_.v)) {
      mpfr_swap(a_.v, n_.v);
      left_rational_ = false;
    }
    extreme_product(s.t1.v, s.t2.v, s.lo.v, s.hi.v, d_lo_.v, d_hi_.v, MPFR_RNDD, mpfr_div);
    mpfr_sub(n_.v, m_.v, s.t1.v, MPFR_RNDU);
    if (right_rational_ ? mpfr_cmp_q(n_.v, u_.upper.get_mpq_t()) < 0 : mpfr_less_p(n_.v, b_.v)) {
      mpfr_swap(b_.v, n_.v);
      right_rational_ = false;
    }
  }

 private:
  // The remembered bracket loaded at this precision: an MPFR end rounded outwards when it has
  // more bits; an inexactly rounded end at or beyond u's rational end is that end again (q may
  // have other roots outside u's interval, so an MPFR end must lie strictly inside it).
  void recall(const RememberedBracket& r) {
    low_sign_ = r.low_sign;
    if (!r.narrowed) return;
    if (!r.left_rational) {
      const int inexact = mpfr_set(a_.v, r.lo.v, MPFR_RNDD);
      left_rational_ = inexact != 0 && mpfr_cmp_q(a_.v, u_.lower.get_mpq_t()) <= 0;
      if (left_rational_) mpfr_set_q(a_.v, u_.lower.get_mpq_t(), MPFR_RNDD);
    }
    if (!r.right_rational) {
      const int inexact = mpfr_set(b_.v, r.hi.v, MPFR_RNDU);
      right_rational_ = inexact != 0 && mpfr_cmp_q(b_.v, u_.upper.get_mpq_t()) >= 0;
      if (right_rational_) mpfr_set_q(b_.v, u_.upper.get_mpq_t(), MPFR_RNDU);
    }
  }
  // This bracket kept when the remembered one is wider (widths rounded up: a heuristic choice,
  // either bracket holds u).
  void remember(RememberedBracket& r) const {
    if (low_sign_ != 0) r.low_sign = low_sign_;
    if (left_rational_ && right_rational_) return;
    if (r.narrowed) {
      const mpfr_prec_t bits = std::max(mpfr_get_prec(a_.v), mpfr_get_prec(r.lo.v));
      Mp mine(bits), theirs(bits);
      mpfr_sub(mine.v, b_.v, a_.v, MPFR_RNDU);
      mpfr_sub(theirs.v, r.hi.v, r.lo.v, MPFR_RNDU);
      if (!mpfr_less_p(mine.v, theirs.v)) return;
    }
    mpfr_set_prec(r.lo.v, mpfr_get_prec(a_.v));
    mpfr_set_prec(r.hi.v, mpfr_get_prec(b_.v));
    mpfr_set(r.lo.v, a_.v, MPFR_RNDN);   // exact: the same precision
    mpfr_set(r.hi.v, b_.v, MPFR_RNDN);
    r.left_rational = left_rational_;
    r.right_rational = right_rational_;
    r.narrowed = true;
  }

  const Real& u_;
  std::shared_ptr<RememberedBracket> memo_;
  std::shared_ptr<const BracketPolynomials> polynomials_;
  const MpPolynomial &q_, &dq_;   // u's polynomial, its derivative
  Mp a_, b_, m_, d_lo_, d_hi_, n_;
  bool left_rational_ = true, right_rational_ = true;
  int low_sign_ = 0;   // q's sign at u.lower, when the first halving needs it
};

}  // namespace

std::optional<int> multiprecision_sign(const Polynomial& p, const Real& u, long start_bits, long max_bits) {
  if (p.empty() || u.exact || u.polynomial.size() < 2) return std::nullopt;
  if (p.size() == 1) return sgn(p[0]);
  long bits = start_bits;
  Scratch s(bits);
  Bracket bracket(u, bits);
  const MpPolynomial mp(p);
  for (;;) {
    for (;;) {
      enclose_over(mp, bracket.lo(), bracket.hi(), s);
      if (const int sign = enclosure_sign(s)) return sign;
      // halve the bracket twice and take an interval Newton step (as multiprecision_order
      // does), then enclose p again; at this precision's floor: enclose once more, then widen
      const int done = bracket.halve(2, s);
      bracket.newton(s);
      if (done < 2) break;
    }
    enclose_over(mp, bracket.lo(), bracket.hi(), s);
    if (const int sign = enclosure_sign(s)) return sign;
    if (2 * bits > max_bits) return std::nullopt;
    bits *= 2;
    bracket.widen(bits);
    s.widen(bits);
  }
}

MultiprecisionBits multiprecision_order_bits(const Real& a, const Real& b) {
  MultiprecisionBits bits = bits_for_width(std::max(coefficient_bits(a.polynomial), coefficient_bits(b.polynomial)));
  // distinct numbers that the double filter could not separate differ far below a double's
  // precision (mixed scales: the lengths' ratio squared and more); twice the coefficients' width
  // separates most of them at once (the two rotating squares of 10^-30 / 10^30 mm: 29 % fewer
  // instructions in compare than from 192 bits, where every pair went on to the gcd and more)
  bits.start = std::max(bits.start, 2 * bits.width);
  return bits;
}

std::vector<std::pair<Rational, Rational>> multiprecision_brackets(const Real& u, long bits, int rounds) {
  std::vector<std::pair<Rational, Rational>> brackets;
  if (u.exact || u.polynomial.size() < 2) return brackets;
  Scratch s(bits);
  Bracket x(u, bits, false);
  for (int round = 0; round < rounds; ++round) {
    x.halve(2, s);
    x.newton(s);
    brackets.emplace_back(to_rational(x.lo()), to_rational(x.hi()));
  }
  return brackets;
}

std::optional<int> multiprecision_order(const Real& a, const Real& b, long start_bits, long max_bits,
                                        const std::function<bool()>& equal) {
  if (a.exact || b.exact || a.polynomial.size() < 2 || b.polynomial.size() < 2) return std::nullopt;
  long bits = start_bits;
  Scratch s(bits);
  Bracket x(a, bits), y(b, bits);
  // a bracket at this precision's floor (fewer than two halvings) is left alone until the other
  // reaches its floor too (session 46: a remembered bracket starts near its floor, and the
  // other one must still be narrowed at this precision)
  bool floor_x = false, floor_y = false;
  for (;;) {
    // a < right end of a's bracket <= x.hi, and likewise for the others
    if (mpfr_less_p(x.hi(), y.lo())) return -1;
    if (mpfr_less_p(y.hi(), x.lo())) return 1;
    // each halved twice (as far as this precision allows) and narrowed by a Newton step; when
    // both are at their floors, the next precision
    if (!floor_x) floor_x = x.halve(2, s) < 2;
    if (!floor_y) floor_y = y.halve(2, s) < 2;
    x.newton(s);
    y.newton(s);
    if (!floor_x || !floor_y) continue;
    if (mpfr_less_p(x.hi(), y.lo())) return -1;
    if (mpfr_less_p(y.hi(), x.lo())) return 1;
    if (bits == start_bits && equal && equal()) return 0;
    if (2 * bits > max_bits) return std::nullopt;
    bits *= 2;
    x.widen(bits);
    y.widen(bits);
    s.widen(bits);
    floor_x = floor_y = false;
  }
}

long multiprecision_bracket_memo_hits() { return memo_hits; }

bool set_multiprecision_bracket_memo(bool enabled) {
  const bool was = memo_enabled;
  memo_enabled = enabled;
  return was;
}

std::optional<std::pair<Rational, Rational>> remembered_bracket(const Real& u) {
  if (u.exact || u.polynomial.size() < 2 || !memo_enabled) return std::nullopt;
  const std::shared_ptr<RememberedBracket> r = bracket_memo().find(u);
  --memo_hits;   // (a look, not a use)
  if (!r->narrowed) return std::nullopt;
  return std::pair{r->left_rational ? u.lower : to_rational(r->lo.v), r->right_rational ? u.upper : to_rational(r->hi.v)};
}

}  // namespace hipair::cspace::algebra
