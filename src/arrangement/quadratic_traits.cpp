// The filtered quadratic traits of the C-space builder (see quadratic_traits.hpp): CGAL's
// Arrangement_2 on arcs of curves of degree <= 2 in y, with our own exact univariate algebra.
#include "arrangement/quadratic_traits.hpp"

#include "arrangement/clip_common.hpp"
#include "algebra/proportional.hpp"

#include <hipair/error.hpp>

#include <CGAL/Arr_tags.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/enum.h>

#include <boost/variant.hpp>

#include <mpfi.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <limits>
#include <map>
#include <tuple>
#include <memory>
#include <unordered_map>

namespace hipair::cspace::raw {
namespace {

using algebra::Interval;
using algebra::Polynomial;
using algebra::Real;
using Clock = std::chrono::steady_clock;

/// Thrown where the input leaves the class the traits decides; the caller falls back.
struct NotApplicable {
  const char* why = "";
};

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// ------------------------------------------------------------------ univariate arithmetic

// (sums and products written into the result's coefficients: no temporary integer per term)
Polynomial add(const Polynomial& a, const Polynomial& b) {
  const Polynomial& longer = a.size() >= b.size() ? a : b;
  const Polynomial& shorter = a.size() >= b.size() ? b : a;
  Polynomial r(longer);
  for (std::size_t i = 0; i < shorter.size(); ++i) mpz_add(r[i].get_mpz_t(), r[i].get_mpz_t(), shorter[i].get_mpz_t());
  algebra::trim(r);
  return r;
}

Polynomial scale(const Polynomial& a, long k) {
  Polynomial r(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) r[i] = a[i] * k;
  algebra::trim(r);
  return r;
}

Polynomial sub(const Polynomial& a, const Polynomial& b) {
  Polynomial r(a);
  if (r.size() < b.size()) r.resize(b.size());
  for (std::size_t i = 0; i < b.size(); ++i) mpz_sub(r[i].get_mpz_t(), r[i].get_mpz_t(), b[i].get_mpz_t());
  algebra::trim(r);
  return r;
}

Polynomial mul(const Polynomial& a, const Polynomial& b) {
  if (a.empty() || b.empty()) return {};
  Polynomial r(a.size() + b.size() - 1);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j)
      mpz_addmul(r[i + j].get_mpz_t(), a[i].get_mpz_t(), b[j].get_mpz_t());
  algebra::trim(r);
  return r;
}

/// p / d when d divides p in Z[x]. \throws NotApplicable otherwise (never for a content).
Polynomial divide_exact(Polynomial p, const Polynomial& d) {
  const int n = algebra::degree(d);
  if (n < 0) throw NotApplicable{};
  if (algebra::degree(p) < n) {
    if (!p.empty()) throw NotApplicable{};
    return {};
  }
  Polynomial q(p.size() - static_cast<std::size_t>(n));
  for (int k = static_cast<int>(p.size()) - 1; k >= n; --k) {
    mpz_class& top = p[static_cast<std::size_t>(k)];
    if (sgn(top) == 0) continue;
    if (!mpz_divisible_p(top.get_mpz_t(), d.back().get_mpz_t())) throw NotApplicable{};
    mpz_class factor;
    mpz_divexact(factor.get_mpz_t(), top.get_mpz_t(), d.back().get_mpz_t());
    q[static_cast<std::size_t>(k - n)] = factor;
    for (int i = 0; i <= n; ++i) p[static_cast<std::size_t>(k - n + i)] -= factor * d[static_cast<std::size_t>(i)];
  }
  algebra::trim(p);
  if (!p.empty()) throw NotApplicable{};
  algebra::trim(q);
  return q;
}

/// Columns of f by powers of y: f = sum_j column[j](x) y^j, no trailing zero column.
std::vector<Polynomial> columns(const IntegerPolynomial2& f) {
  std::vector<Polynomial> out;
  for (std::size_t i = 0; i < f.coefficients.size(); ++i)
    for (std::size_t j = 0; j < f.coefficients[i].size(); ++j) {
      if (sgn(f.coefficients[i][j]) == 0) continue;
      if (out.size() <= j) out.resize(j + 1);
      if (out[j].size() <= i) out[j].resize(i + 1);
      out[j][i] = f.coefficients[i][j];
    }
  for (auto& c : out) algebra::trim(c);
  while (!out.empty() && out.back().empty()) out.pop_back();
  return out;
}

IntegerPolynomial2 from_columns(const std::vector<Polynomial>& cols) {
  IntegerPolynomial2 f;
  std::size_t rows = 0;
  for (const auto& c : cols) rows = std::max(rows, c.size());
  f.coefficients.assign(rows, std::vector<mpz_class>(cols.size()));
  for (std::size_t j = 0; j < cols.size(); ++j)
    for (std::size_t i = 0; i < cols[j].size(); ++i) f.coefficients[i][j] = cols[j][i];
  return f;
}

Polynomial column(const std::vector<Polynomial>& cols, std::size_t j) { return j < cols.size() ? cols[j] : Polynomial{}; }

/// Res_y(f, g) for f, g of degree <= 2 in y (exact degrees; closed forms of the Sylvester
/// determinants, up to sign). Both of degree 0 is not asked for.
Polynomial resultant_y(const std::vector<Polynomial>& f, const std::vector<Polynomial>& g) {
  if (f.size() < g.size()) return resultant_y(g, f);
  const std::size_t m = f.size() - 1, n = g.size() - 1;   // degrees, m >= n
  if (n == 0) {
    Polynomial r = g[0];
    for (std::size_t k = 1; k < m; ++k) r = mul(r, g[0]);
    return r;
  }
  if (m == 1) return sub(mul(f[1], g[0]), mul(f[0], g[1]));   // b f - c e
  const Polynomial &a = f[2], &b = f[1], &c = f[0];
  if (n == 1) {   // a f^2 - b e f + c e^2
    const Polynomial &e = g[1], &ff = g[0];
    return add(sub(mul(a, mul(ff, ff)), mul(b, mul(e, ff))), mul(c, mul(e, e)));
  }
  const Polynomial &d = g[2], &e = g[1], &ff = g[0];
  Polynomial af_cd = sub(mul(a, ff), mul(c, d));
  return sub(mul(af_cd, af_cd), mul(sub(mul(a, e), mul(b, d)), sub(mul(b, ff), mul(c, e))));
}

/// h mixed with an integer's size and lowest limb.
std::size_t mix_integer(std::size_t h, const mpz_class& c) {
  const mpz_srcptr z = c.get_mpz_t();
  h = (h ^ static_cast<std::size_t>(z->_mp_size)) * 0x100000001b3ULL;
  if (z->_mp_size != 0) h = (h ^ static_cast<std::size_t>(z->_mp_d[0])) * 0x100000001b3ULL;
  return h;
}

/// A hash of a column list (every coefficient's size and lowest limb).
std::size_t column_hash(const std::vector<Polynomial>& cols) {
  std::size_t h = cols.size();
  for (const Polynomial& column : cols) {
    h = h * 131u + column.size();
    for (const mpz_class& c : column) h = mix_integer(h, c);
  }
  return h;
}

// A bounded per-thread memo of a pure function of exact values (`Key`, compared exactly; `hash`
// only spreads them): a hit returns what the function would. Emptied when it holds `capacity`.
template <class Key, class Value, std::size_t capacity>
class ExactMemo {
 public:
  template <class Compute>
  Value get(std::size_t hash, Key key, Compute compute) {
    auto [first, last] = entries_.equal_range(hash);
    for (auto it = first; it != last; ++it)
      if (it->second.first == key) return it->second.second;
    Value value = compute();
    if (entries_.size() >= capacity) entries_.clear();
    entries_.emplace(hash, std::pair<Key, Value>{std::move(key), value});
    return value;
  }

 private:
  std::unordered_multimap<std::size_t, std::pair<Key, Value>> entries_;
};

/// resultant_y, remembered per thread. A chart's curves do not depend on the tile's box, so
/// the tiles a curve crosses ask again for the same resultants (its horizontal tangents, its
/// validity atoms, each other curve of the tile it meets). The value is a pure function of the
/// two column lists (compared coefficient by coefficient), so a hit returns exactly what
/// resultant_y would. Bounded: emptied when it holds `capacity` resultants.
Polynomial remembered_resultant_y(const std::vector<Polynomial>& f, const std::vector<Polynomial>& g) {
  constexpr std::size_t capacity = 4096;
  struct Entry {
    std::vector<Polynomial> f, g;
    Polynomial resultant;
  };
  thread_local std::unordered_multimap<std::size_t, Entry> memo;
  const std::size_t key = column_hash(f) * 0x9e3779b97f4a7c15ULL + column_hash(g);
  auto [first, last] = memo.equal_range(key);
  for (auto it = first; it != last; ++it)
    if (it->second.f == f && it->second.g == g) return it->second.resultant;
  Polynomial r = resultant_y(f, g);
  if (memo.size() >= capacity) memo.clear();
  memo.emplace(key, Entry{f, g, r});
  return r;
}

/// Pseudo-remainder of g by f in y (deg_y f >= 1): degree < deg_y f, same common roots
/// where f's leading coefficient does not vanish.
std::vector<Polynomial> pseudo_remainder(std::vector<Polynomial> g, const std::vector<Polynomial>& f) {
  const std::size_t m = f.size() - 1;
  while (g.size() > m) {
    const std::size_t shift = g.size() - 1 - m;
    const Polynomial lead = g.back();
    for (auto& c : g) c = mul(c, f.back());
    for (std::size_t j = 0; j <= m; ++j) g[j + shift] = sub(g[j + shift], mul(lead, f[j]));
    while (!g.empty() && g.back().empty()) g.pop_back();
  }
  return g;
}

// ------------------------------------------------------------------ certified intervals

Interval ineg(Interval a) { return {-a.hi, -a.lo}; }

Interval idiv(Interval a, Interval b) {   // b must exclude 0
  const double inf = std::numeric_limits<double>::infinity();
  if (b.contains_zero() || !(b.lo == b.lo) || !(b.hi == b.hi)) return {-inf, inf};
  double q[4] = {a.lo / b.lo, a.lo / b.hi, a.hi / b.lo, a.hi / b.hi};
  double lo = q[0], hi = q[0];
  for (double v : q) {
    if (!(v == v)) return {-inf, inf};
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  return {algebra::interval_detail::down(lo), algebra::interval_detail::up(hi)};
}

Interval isqrt(Interval a) {   // of the non-negative part (the exact value is known >= 0)
  double lo = a.lo <= 0 ? 0 : algebra::interval_detail::down(std::sqrt(a.lo));
  double hi = a.hi <= 0 ? 0 : algebra::interval_detail::up(std::sqrt(a.hi));
  return {std::max(0.0, lo), hi};
}

std::vector<Interval> enclose(const Polynomial& p) {
  std::vector<Interval> out;
  for (const auto& c : p) out.push_back(algebra::enclose(c));
  return out;
}

Interval enclose(const Real& x) { return {x.lower_bound(), x.upper_bound()}; }

bool disjoint(Interval a, Interval b) { return a.hi < b.lo || b.hi < a.lo; }

/// Certified double enclosures of p / 2^shift (the same signs; the shift keeps resultants of
/// more than 1024 bits finite).
std::vector<Interval> enclose_scaled(const Polynomial& p) {
  std::size_t bits = 0;
  for (const auto& c : p) bits = std::max(bits, mpz_sizeinbase(c.get_mpz_t(), 2));
  const long shift = bits > 900 ? static_cast<long>(bits) - 900 : 0;
  std::vector<Interval> out;
  out.reserve(p.size());
  for (const auto& c : p) {
    if (sgn(c) == 0) {
      out.push_back({0, 0});
      continue;
    }
    long exponent = 0;
    const double d = mpz_get_d_2exp(&exponent, c.get_mpz_t());   // truncated: |c| in [|d|, |d| + 2^-53) 2^e
    const double far = std::nextafter(d, d > 0 ? 2.0 : -2.0);
    const long e = exponent - shift;
    double lo = std::ldexp(std::min(d, far), static_cast<int>(e)), hi = std::ldexp(std::max(d, far), static_cast<int>(e));
    if (e < -1000) {   // underflow: a coefficient below 2^-1000 (relative to the largest)
      lo = std::min(lo, -std::numeric_limits<double>::min());
      hi = std::max(hi, std::numeric_limits<double>::min());
    }
    out.push_back({lo, hi});
  }
  return out;
}

bool no_root_on(const std::vector<Interval>& c, double lo, double hi, int depth) {
  const Interval v = algebra::horner(c, Interval{lo, hi});
  if (v.lo > 0 || v.hi < 0) return true;   // (NaN fails both)
  if (depth == 0) return false;
  const double m = lo + (hi - lo) / 2;
  if (!(lo < m && m < hi)) return false;
  return no_root_on(c, lo, m, depth - 1) && no_root_on(c, m, hi, depth - 1);
}

/// Certified: p has no real root in [lo, hi] (interval evaluation on a subdivision), so that
/// the exact isolation (square-freeness test, Descartes bisection) is skipped for most polynomials of a
/// small chart. False means "may have one".
bool certainly_no_root(const Polynomial& p, const Rational& lo, const Rational& hi) {
  if (algebra::degree(p) < 1) return !p.empty();
  return no_root_on(enclose_scaled(p), algebra::lower_double(lo), algebra::upper_double(hi), 5);
}

/// algebra::descartes_real_roots(p, lo, hi) (Descartes' rule, dyadic bisection, modular
/// square-freeness test) behind certainly_no_root.
std::vector<Real> roots_in(const Polynomial& p, const Rational& lo, const Rational& hi) {
  if (certainly_no_root(p, lo, hi)) return {};
  return algebra::descartes_real_roots(p, lo, hi);
}

// ------------------------------------------------------------------ multiple-precision intervals

/// An MPFI interval (outward-rounded interval arithmetic at a chosen precision): the certified
/// filter between double intervals and exact arithmetic. Coefficients of 250-650 bits leave
/// double intervals about 2^-50 wide relative to the values, so two arcs closer than that (or
/// meeting) need more bits; evaluating at an x refined to 2^-k with k + 64 bits of precision
/// costs a few multiplications of (k + coefficient size)-bit numbers.
class Mp {
 public:
  explicit Mp(mpfr_prec_t bits) { mpfi_init2(v_, bits); }
  ~Mp() { mpfi_clear(v_); }
  Mp(const Mp&) = delete;
  Mp& operator=(const Mp&) = delete;
  mpfi_ptr get() { return v_; }
  mpfi_srcptr get() const { return v_; }

 private:
  mpfi_t v_;
};

/// Precision levels of the multiple-precision filter: x is refined to width 2^-bits and the
/// arithmetic runs at bits + 64 bits.
constexpr int mp_level_bits[] = {128, 320, 800, 2000};
constexpr int mp_levels = 4;

void mp_evaluate(mpfi_ptr out, const Polynomial& p, mpfi_srcptr x) {
  mpfi_set_ui(out, 0);
  for (auto it = p.rbegin(); it != p.rend(); ++it) {
    mpfi_mul(out, out, x);
    mpfi_add_z(out, out, it->get_mpz_t());
  }
}

/// -1 / +1 when the interval certifies the sign, 0 when it contains 0 (or is NaN).
int mp_sign(mpfi_srcptr v) {
  if (mpfi_nan_p(v)) return 0;
  if (mpfi_is_strictly_pos(v) > 0) return 1;
  if (mpfi_is_strictly_neg(v) > 0) return -1;
  return 0;
}

// ------------------------------------------------------------------ supports and points

/// One polynomial of the arrangement. `part` (= full without its factors in x alone) is
/// a y^2 + b y + c (degree 2) or b y + c (degree 1); degree 0: vertical lines only.
struct Support {
  IntegerPolynomial2 full;
  IntegerPolynomial2 part;
  std::vector<Polynomial> part_columns;
  int degree = 0;
  Polynomial a, b, disc, two_a, neg_b, neg_c, content;
  std::vector<Interval> i_a, i_b, i_disc, i_two_a, i_neg_b, i_neg_c;
  std::vector<Real> events;   ///< inside the box's open x-range, ascending
};

/// y = (P + s sqrt(D)) / Q of a support at a given x: kind 0 a root (-b + s sqrt(disc)) / 2a
/// (a != 0, disc > 0), kind 1 the double root -b / 2a (disc = 0), kind 2 the root -c / b of
/// a linear fibre (degree 1, or a = 0).
struct YExpr {
  int support = -1;
  int kind = 2;
  int s = 0;
  bool operator==(const YExpr& o) const { return support == o.support && kind == o.kind && s == o.s; }
  bool operator!=(const YExpr& o) const { return !(*this == o); }
};

/// An x-coordinate, shared by every point and root list with that x (one entry per number:
/// equal abscissae compare by address).
struct XEntry {
  Real x;
  Interval xi;
  /// x refined to 2^-mp_level_bits[k], computed when a filter at a coarser level fails
  mutable std::array<std::unique_ptr<Real>, mp_levels> refined;
};

struct PointRep {
  std::shared_ptr<const XEntry> entry;
  YExpr y;
  Interval yi;
  const Interval& xi() const { return entry->xi; }
};

struct Point {
  std::shared_ptr<const PointRep> rep;
  const Real& x() const { return rep->entry->x; }
};

struct XCurve {
  Point left, right;
  int support = -1;
  bool vertical = false;
  YExpr interior;   ///< non-vertical: the arc strictly between its ends
};

/// CGAL's insertion functions are also instantiated for general curves: a curve here is one
/// x-monotone arc (the builder does its own x-monotone split and inserts arcs only).
struct Curve {
  XCurve arc;
};

class QuadraticTraits;

}  // namespace
}  // namespace hipair::cspace::raw

namespace hipair::cspace::raw {
namespace {

class QuadraticTraits {
 public:
  using Point_2 = Point;
  using X_monotone_curve_2 = XCurve;
  using Multiplicity = unsigned int;
  using Curve_2 = Curve;
  using Has_left_category = CGAL::Tag_true;
  using Has_merge_category = CGAL::Tag_false;
  using Has_do_intersect_category = CGAL::Tag_false;
  using Left_side_category = CGAL::Arr_oblivious_side_tag;
  using Bottom_side_category = CGAL::Arr_oblivious_side_tag;
  using Top_side_category = CGAL::Arr_oblivious_side_tag;
  using Right_side_category = CGAL::Arr_oblivious_side_tag;

  QuadraticTraits(const Box& box) : st_(std::make_shared<State>()) { st_->box = box; }

  // ---------------------------------------------------------------- state

  /// A support without its events (everything that does not depend on the box), remembered
  /// per thread: a chart's curves do not depend on the tile's box, so every tile a curve
  /// crosses asks again for the same content, columns, discriminant and enclosures. The value is
  /// a pure function of `full` (compared coefficient by coefficient), so a hit is exactly what
  /// the computation gives. Bounded: emptied when it holds `capacity` supports.
  static Support box_free_support(const IntegerPolynomial2& full) {
    constexpr std::size_t capacity = 2048;
    thread_local std::unordered_multimap<std::size_t, Support> memo;
    const std::size_t key = column_hash(full.coefficients);
    auto [first, last] = memo.equal_range(key);
    for (auto it = first; it != last; ++it)
      if (it->second.full.coefficients == full.coefficients) return it->second;
    Support s;
    s.full = full;
    std::vector<Polynomial> cols = columns(full);
    if (cols.empty()) throw NotApplicable{"zero curve"};
    Polynomial content;
    for (const auto& c : cols) content = content.empty() ? algebra::primitive_part(c) : algebra::gcd(content, c);
    if (algebra::degree(content) >= 1)
      for (auto& c : cols) c = divide_exact(c, content);
    else
      content = {mpz_class(1)};
    s.content = content;
    s.degree = static_cast<int>(cols.size()) - 1;
    s.part_columns = cols;
    s.part = from_columns(cols);
    if (s.degree > 2) throw NotApplicable{"degree in y above 2"};
    if (s.degree == 2) {
      s.a = cols[2];
      s.b = cols[1];
      s.disc = sub(mul(cols[1], cols[1]), scale(mul(cols[2], cols[0]), 4));
      if (s.disc.empty()) throw NotApplicable{"zero discriminant"};
      s.two_a = scale(cols[2], 2);
      s.neg_b = scale(cols[1], -1);
      s.neg_c = scale(cols[0], -1);
    } else if (s.degree == 1) {
      s.b = cols[1];
      s.neg_c = scale(column(cols, 0), -1);
    }
    s.i_a = enclose(s.a);
    s.i_b = enclose(s.b);
    s.i_disc = enclose(s.disc);
    s.i_two_a = enclose(s.two_a);
    s.i_neg_b = enclose(s.neg_b);
    s.i_neg_c = enclose(s.neg_c);
    if (memo.size() >= capacity) memo.clear();
    memo.emplace(key, s);
    return s;
  }

  int add_support(const IntegerPolynomial2& full) {
    Support s = box_free_support(full);
    // events: x-only factors, leading coefficient and discriminant (the x where CGAL's curve
    // analysis has its status lines with events)
    std::vector<Real> events;
    auto add_roots = [&](const Polynomial& p) {
      if (algebra::degree(p) < 1) return;
      for (auto& r : roots_in(p, st_->box.x_lo, st_->box.x_hi))
        if (r.compare(st_->box.x_lo) > 0 && r.compare(st_->box.x_hi) < 0) events.push_back(std::move(r));
    };
    add_roots(s.content);
    if (s.degree == 2) {
      add_roots(s.a);
      add_roots(s.disc);
    } else if (s.degree == 1) {
      add_roots(s.b);
    }
    s.events = sorted_unique(std::move(events));
    st_->supports.push_back(std::move(s));
    return static_cast<int>(st_->supports.size()) - 1;
  }

  const Support& support(int i) const { return st_->supports[static_cast<std::size_t>(i)]; }

  /// Extends support k's hull (State::hulls) to hold [lo, hi] (the bounds of isolating intervals).
  void extend_hull(int k, const Real& lo, const Real& hi) {
    auto& hulls = st_->hulls;
    if (hulls.size() <= static_cast<std::size_t>(k)) hulls.resize(static_cast<std::size_t>(k) + 1);
    auto& hull = hulls[static_cast<std::size_t>(k)];
    if (!hull) {
      hull.emplace(lo.lower, hi.upper);
      return;
    }
    if (lo.lower < hull->first) hull->first = lo.lower;
    if (hull->second < hi.upper) hull->second = hi.upper;
  }

  /// From here on a support's resultant roots are isolated only over its hull (called once
  /// every piece and point is made, before the insertion). Roots memoised earlier (over the
  /// whole box) stay: a superset.
  void restrict_roots() { st_->restricted = true; }

  std::vector<Real> sorted_unique(std::vector<Real> xs) const {
    for (auto& x : xs) refine(x);
    std::sort(xs.begin(), xs.end(), [&](const Real& p, const Real& q) { return compare_x(p, q) < 0; });
    std::vector<Real> out;
    for (auto& x : xs)
      if (out.empty() || compare_x(out.back(), x) != 0) out.push_back(std::move(x));
    return out;
  }

  static void refine(Real& x) {
    if (!x.exact) algebra::refine_dyadically(x, Rational(1, mpz_class(1) << 52));
  }

  // ---------------------------------------------------------------- numbers

  static int compare_x(const Real& a, const Real& b) {
    if (&a == &b) return 0;
    Interval ia = enclose(a), ib = enclose(b);
    if (ia.hi < ib.lo) return -1;
    if (ib.hi < ia.lo) return 1;
    return algebra::compare(a, b);
  }

  const Polynomial& P(const YExpr& e) const { return e.kind == 2 ? support(e.support).neg_c : support(e.support).neg_b; }
  const Polynomial& Q(const YExpr& e) const { return e.kind == 2 ? support(e.support).b : support(e.support).two_a; }

  Interval y_interval(const YExpr& e, Interval x) const {
    const Support& s = support(e.support);
    if (e.kind == 2) return idiv(algebra::horner(s.i_neg_c, x), algebra::horner(s.i_b, x));
    Interval p = algebra::horner(s.i_neg_b, x);
    if (e.kind == 0) {
      Interval r = isqrt(algebra::horner(s.i_disc, x));
      p = p + (e.s > 0 ? r : ineg(r));
    }
    return idiv(p, algebra::horner(s.i_two_a, x));
  }

  static int sign(const Polynomial& p, const Real& x) { return p.empty() ? 0 : algebra::sign_at(p, x); }

  // sign of A + B sqrt(D) at x (D(x) >= 0)
  static int sign2(const Real& x, const Polynomial& A, const Polynomial& B, const Polynomial& D) {
    int sa = sign(A, x);
    int sb = B.empty() ? 0 : sign(B, x);
    if (sb != 0 && sign(D, x) == 0) sb = 0;
    if (sb == 0) return sa;
    if (sa == 0 || sa == sb) return sb;
    return sa * sign(sub(mul(A, A), mul(mul(B, B), D)), x);
  }

  // sign of A + B sqrt(D1) + C sqrt(D2) at x
  static int sign3(const Real& x, const Polynomial& A, const Polynomial& B, const Polynomial& D1, const Polynomial& C,
                   const Polynomial& D2) {
    int sc = C.empty() ? 0 : sign(C, x);
    if (sc != 0 && sign(D2, x) == 0) sc = 0;
    int sx = sign2(x, A, B, D1);
    if (sc == 0) return sx;
    if (sx == 0 || sx == sc) return sc;
    Polynomial A2 = sub(add(mul(A, A), mul(mul(B, B), D1)), mul(mul(C, C), D2));
    return sx * sign2(x, A2, scale(mul(A, B), 2), D1);
  }

  /// sign(y1 - y2) at x, exact: filtered by the double intervals y1i, y2i, then decided
  /// equal or not at a root of the supports' resultant by their first subresultant, then by
  /// multiple-precision intervals at a finer x, then by exact_compare_y (squaring the square
  /// roots away); results after the double filter are cached per canonical x.
  int compare_y(const Real& x, const YExpr& e1, const YExpr& e2, Interval y1i, Interval y2i) const {
    if (e1 == e2) return 0;
    if (y1i.hi < y2i.lo) return -1;
    if (y2i.hi < y1i.lo) return 1;
    auto found = st_->entries.find(&x);
    const XEntry* entry = found == st_->entries.end() ? nullptr : found->second.get();
    auto key = std::make_tuple(static_cast<const void*>(entry), e1.support, e1.kind, e1.s, e2.support, e2.kind, e2.s);
    if (entry) {
      auto it = st_->exact_cache.find(key);
      if (it != st_->exact_cache.end()) return it->second;
    }
    int result = 0;
    std::optional<bool> equal = equal_by_subresultant(x, entry, e1, e2);
    if (equal && *equal) {
      ++st_->subresultant_equalities;
    } else {
      result = mp_compare_y(x, entry, e1, e2);
      if (result == 0) result = exact_compare_y(x, e1, e2);
    }
    if (entry) {
      st_->exact_cache.emplace(key, result);
      st_->exact_cache.emplace(std::make_tuple(static_cast<const void*>(entry), e2.support, e2.kind, e2.s, e1.support,
                                               e1.kind, e1.s),
                               -result);
    }
    return result;
  }

  // ---------------------------------------------------------------- multiple-precision filter

  /// x enclosed at a precision level (refined copies cached on x's entry).
  void mp_x(const Real& x, const XEntry* entry, int level, mpfi_ptr out) const {
    if (x.exact) {
      mpfi_set_q(out, x.lower.get_mpq_t());
      return;
    }
    const Rational width(1, mpz_class(1) << mp_level_bits[level]);
    Real local;
    const Real* refined = nullptr;
    if (entry && entry->refined[static_cast<std::size_t>(level)]) {
      refined = entry->refined[static_cast<std::size_t>(level)].get();
    } else {
      const Real* start = &x;   // refine from the finest level already known
      if (entry)
        for (int k = level - 1; k >= 0; --k)
          if (entry->refined[static_cast<std::size_t>(k)]) {
            start = entry->refined[static_cast<std::size_t>(k)].get();
            break;
          }
      auto fine = std::make_unique<Real>(*start);
      algebra::refine_dyadically(*fine, width);
      if (entry) {
        entry->refined[static_cast<std::size_t>(level)] = std::move(fine);
        refined = entry->refined[static_cast<std::size_t>(level)].get();
      } else {
        local = std::move(*fine);
        refined = &local;
      }
    }
    if (refined->exact)
      mpfi_set_q(out, refined->lower.get_mpq_t());
    else
      mpfi_interv_q(out, refined->lower.get_mpq_t(), refined->upper.get_mpq_t());
  }

  /// y of e over the interval x; false when the enclosure is useless (denominator not
  /// certified non-zero, discriminant certified negative).
  bool mp_y(const YExpr& e, mpfi_srcptr x, mpfr_prec_t prec, mpfi_ptr out) const {
    const Support& s = support(e.support);
    Mp num(prec), den(prec);
    if (e.kind == 2) {
      mp_evaluate(num.get(), s.neg_c, x);
      mp_evaluate(den.get(), s.b, x);
    } else {
      mp_evaluate(num.get(), s.neg_b, x);
      if (e.kind == 0) {
        Mp root(prec);
        mp_evaluate(root.get(), s.disc, x);
        if (mpfi_nan_p(root.get()) || mpfr_sgn(&root.get()->right) < 0) return false;
        if (mpfr_sgn(&root.get()->left) < 0) mpfr_set_zero(&root.get()->left, 1);   // the value is >= 0
        mpfi_sqrt(root.get(), root.get());
        if (e.s > 0)
          mpfi_add(num.get(), num.get(), root.get());
        else
          mpfi_sub(num.get(), num.get(), root.get());
      }
      mp_evaluate(den.get(), s.two_a, x);
    }
    if (mp_sign(den.get()) == 0) return false;
    mpfi_div(out, num.get(), den.get());
    return !mpfi_nan_p(out);
  }

  /// sign(y1 - y2) at x certified by multiple-precision intervals, 0 when undecided.
  int mp_compare_y(const Real& x, const XEntry* entry, const YExpr& e1, const YExpr& e2) const {
    for (int level = 0; level < mp_levels; ++level) {
      const mpfr_prec_t prec = mp_level_bits[level] + 64;
      Mp xi(prec), y1(prec), y2(prec);
      mp_x(x, entry, level, xi.get());
      if (!mp_y(e1, xi.get(), prec, y1.get()) || !mp_y(e2, xi.get(), prec, y2.get())) continue;
      mpfi_sub(y1.get(), y1.get(), y2.get());
      if (int c = mp_sign(y1.get())) {
        ++st_->mp_decided[level];
        return c;
      }
    }
    return 0;
  }

  /// sign of p at x certified by multiple-precision intervals (exact at a rational x), 0 when
  /// undecided (p may vanish at x).
  int mp_sign_at(const Polynomial& p, const Real& x, const XEntry* entry) const {
    if (p.empty()) return 0;
    if (x.exact) return algebra::sign_at(p, x.lower);
    for (int level = 0; level < mp_levels; ++level) {
      const mpfr_prec_t prec = mp_level_bits[level] + 64;
      Mp xi(prec), v(prec);
      mp_x(x, entry, level, xi.get());
      mp_evaluate(v.get(), p, xi.get());
      if (int c = mp_sign(v.get())) return c;
    }
    return 0;
  }

  // ---------------------------------------------------------------- equality without squaring

  /// The first subresultant N + M y of the parts of two distinct supports i < j (it vanishes
  /// at their common roots; where M(x) != 0 its root -N/M is the only one), and for each
  /// support the numerator T = b M - 2 a N of 2 a y* + b = T / M at that root.
  struct CommonRoot {
    Polynomial N, M, T_first, T_second;
  };

  const CommonRoot& common_root(int i, int j) const {
    auto key = std::make_pair(i, j);
    auto it = st_->common.find(key);
    if (it != st_->common.end()) return it->second;
    const auto &f = support(i).part_columns, &g = support(j).part_columns;
    CommonRoot r;
    if (f.size() == 2) {   // f = b y + c: its root
      r.N = column(f, 0);
      r.M = f[1];
    } else if (g.size() == 2) {
      r.N = column(g, 0);
      r.M = g[1];
    } else {   // f = a y^2 + b y + c, g = d y^2 + e y + h: S1 = (a e - b d) y + (a h - c d)
      r.M = sub(mul(f[2], g[1]), mul(f[1], g[2]));
      r.N = sub(mul(f[2], g[0]), mul(f[0], g[2]));
    }
    auto branch_numerator = [&](const Support& s) {
      return s.degree == 2 ? sub(mul(s.b, r.M), scale(mul(s.a, r.N), 2)) : Polynomial{};
    };
    r.T_first = branch_numerator(support(i));
    r.T_second = branch_numerator(support(j));
    return st_->common.emplace(key, std::move(r)).first->second;
  }

  /// Is y1 == y2 at x, for arcs of two distinct supports? Decided without squaring: a common
  /// point lies over a root of the resultant of the supports (root_entries: canonical, so
  /// membership is identity), and there, when one leading coefficient does not vanish and
  /// M(x) != 0, the common root is y* = -N(x)/M(x); an arc y = (-b + s sqrt(disc)) / 2a passes
  /// through it iff sign(2 a y* + b) = s, the other arc kinds (the only finite root of their
  /// fibre) always do. nullopt: not decided here (a rational or unregistered x, a vanishing
  /// M(x) or a sign the filter does not certify); the caller compares numerically then.
  std::optional<bool> equal_by_subresultant(const Real& x, const XEntry* entry, const YExpr& e1,
                                            const YExpr& e2) const {
    if (!entry || x.exact || e1.support == e2.support) return std::nullopt;
    bool root = false;
    for (const auto& r : root_entries(e1.support, e2.support)) root = root || r.get() == entry;
    if (!root) return false;
    // the resultant vanishes without a common root where both leading coefficients vanish:
    // arcs of kind 2 on a curve of degree 2 (a(x) = 0); kinds 0 and 1 have a(x) != 0, kind 2
    // on a curve of degree 1 has b(x) != 0 (their denominators)
    auto leading_may_vanish = [&](const YExpr& e) { return e.kind == 2 && support(e.support).degree == 2; };
    if (leading_may_vanish(e1) && leading_may_vanish(e2)) return std::nullopt;
    const bool first_is_1 = e1.support < e2.support;
    const CommonRoot& common = common_root(std::min(e1.support, e2.support), std::max(e1.support, e2.support));
    const int m = mp_sign_at(common.M, x, entry);
    if (m == 0) return std::nullopt;
    bool equal = true;
    for (const YExpr* e : {&e1, &e2}) {
      if (e->kind != 0) continue;
      const bool first = (e == &e1) == first_is_1;
      const int t = mp_sign_at(first ? common.T_first : common.T_second, x, entry);
      if (t == 0) return std::nullopt;
      if (t * m != e->s) equal = false;
    }
    return equal;
  }

  int exact_compare_y(const Real& x, const YExpr& e1, const YExpr& e2) const {
    ++st_->exact_comparisons;
    const Polynomial &P1 = P(e1), &Q1 = Q(e1), &P2 = P(e2), &Q2 = Q(e2);
    const Polynomial& D1 = support(e1.support).disc;
    const Polynomial& D2 = support(e2.support).disc;
    int q1 = sign(Q1, x), q2 = sign(Q2, x);
    if (q1 == 0 || q2 == 0) throw NotApplicable{"zero denominator"};
    Polynomial A = sub(mul(P1, Q2), mul(P2, Q1));
    Polynomial B = e1.kind == 0 ? scale(Q2, e1.s) : Polynomial{};
    Polynomial C = e2.kind == 0 ? scale(Q1, -e2.s) : Polynomial{};
    if (e1.kind == 0 && e2.kind == 0 && e1.support == e2.support) {
      B = add(B, C);
      C.clear();
    }
    return q1 * q2 * sign3(x, A, B, D1, C, D2);
  }

  int compare_y(const Real& x, Interval xi, const YExpr& e1, const YExpr& e2) const {
    return compare_y(x, e1, e2, y_interval(e1, xi), y_interval(e2, xi));
  }

  /// The one entry of the number x.
  std::shared_ptr<const XEntry> canonical(const Real& x) const {
    auto known = st_->entries.find(&x);
    if (known != st_->entries.end()) return known->second;
    Real refined = x;
    refine(refined);
    Interval xi = enclose(refined);
    for (auto it = st_->by_lower.lower_bound(xi.lo - (1e-14 * (1 + std::fabs(xi.lo)))); it != st_->by_lower.end(); ++it) {
      if (it->first > xi.hi) break;
      if (!disjoint(it->second->xi, xi) && algebra::equal(it->second->x, refined)) return it->second;
    }
    auto entry = std::make_shared<XEntry>();
    entry->x = std::move(refined);
    entry->xi = xi;
    st_->entries.emplace(&entry->x, entry);
    st_->by_lower.emplace(xi.lo, entry);
    return entry;
  }

  Point make_point(const Real& x, const YExpr& y) const { return make_point(canonical(x), y); }

  /// The point of y over an x already made canonical (one entry shared by the cut's points).
  Point make_point(std::shared_ptr<const XEntry> entry, const YExpr& y) const {
    auto rep = std::make_shared<PointRep>();
    rep->entry = std::move(entry);
    rep->y = y;
    rep->yi = y_interval(y, rep->entry->xi);
    return Point{std::move(rep)};
  }

  int compare_x(const Point& p, const Point& q) const {
    if (p.rep == q.rep || p.rep->entry == q.rep->entry) return 0;
    if (p.rep->xi().hi < q.rep->xi().lo) return -1;
    if (q.rep->xi().hi < p.rep->xi().lo) return 1;
    return algebra::compare(p.x(), q.x());
  }

  int compare_y_same_x(const Point& p, const Point& q) const {
    if (p.rep == q.rep) return 0;
    return compare_y(p.x(), p.rep->y, q.rep->y, p.rep->yi, q.rep->yi);
  }

  int compare_xy(const Point& p, const Point& q) const {
    if (p.rep == q.rep) return 0;
    int c = compare_x(p, q);
    return c != 0 ? c : compare_y_same_x(p, q);
  }

  /// The point of the non-vertical curve c above x (x within c's closed x-range).
  Point point_on(const XCurve& c, const Real& x) const {
    if (compare_x(x, c.left.x()) == 0) return c.left;
    if (compare_x(x, c.right.x()) == 0) return c.right;
    return make_point(x, c.interior);
  }

  /// y of the non-vertical c vs the point p (p.x within c's x-range).
  int compare_point_curve(const Point& p, const XCurve& c) const {
    if (compare_x(p.x(), c.left.x()) == 0) return compare_y_same_x(p, c.left);
    if (compare_x(p.x(), c.right.x()) == 0) return compare_y_same_x(p, c.right);
    return compare_y(p.x(), p.rep->y, c.interior, p.rep->yi, y_interval(c.interior, p.rep->xi()));
  }

  /// Roots of Res_y of two distinct supports in the closed box x-range, ascending.
  const std::vector<std::shared_ptr<const XEntry>>& root_entries(int i, int j) const {
    auto key = std::make_pair(std::min(i, j), std::max(i, j));
    auto it = st_->roots.find(key);
    if (it != st_->roots.end()) return it->second;
    Polynomial r = remembered_resultant_y(support(i).part_columns, support(j).part_columns);
    if (r.empty()) throw NotApplicable{"common component"};   // a common component of two supports
    // the roots over the common part of the two supports' hulls (restrict_roots): every point
    // of the arrangement on both supports lies there, and every pair of arcs the insertion
    // compares or intersects overlaps in x there
    Rational lo = st_->box.x_lo, hi = st_->box.x_hi;
    for (int k : {i, j}) {
      if (!st_->restricted) break;
      const auto& hull = static_cast<std::size_t>(k) < st_->hulls.size() ? st_->hulls[static_cast<std::size_t>(k)]
                                                                          : std::optional<std::pair<Rational, Rational>>{};
      if (!hull) continue;
      if (lo < hull->first) lo = hull->first;
      if (hull->second < hi) hi = hull->second;
    }
    std::vector<Real> xs;
    if (algebra::degree(r) >= 1) {
      if (lo < hi)
        xs = roots_in(r, lo, hi);
      else if (lo == hi && algebra::sign_at(r, lo) == 0)
        xs.push_back(Real::from_rational(lo));
    }
    std::vector<std::shared_ptr<const XEntry>> out;
    for (const Real& x : sorted_unique(std::move(xs))) out.push_back(canonical(x));
    return st_->roots.emplace(key, std::move(out)).first->second;
  }

  /// A rational x strictly right (toward = +1) or left (-1) of p.x on both curves, before
  /// their next common point: the order of the curves there is their order next to p.
  int compare_beside(const XCurve& c1, const XCurve& c2, const Point& p, int toward) const {
    if (c1.vertical || c2.vertical) {
      if (c1.vertical && c2.vertical) return 0;
      // a vertical curve through p counts as above the other one to the right of p unless p
      // is its upper end, and below it to the left unless p is its lower end (as the slopes)
      const XCurve& v = c1.vertical ? c1 : c2;
      int above = toward > 0 ? (compare_xy(v.right, p) == 0 ? -1 : 1) : (compare_xy(v.left, p) == 0 ? 1 : -1);
      return c1.vertical ? above : -above;
    }
    if (c1.support == c2.support && c1.interior == c2.interior) return 0;
    const Point& e1 = toward > 0 ? c1.right : c1.left;
    const Point& e2 = toward > 0 ? c2.right : c2.left;
    const Point& end = (compare_x(e1, e2) <= 0) == (toward > 0) ? e1 : e2;
    const Real* bound = &end.x();
    if (c1.support != c2.support) {
      const auto& xs = root_entries(c1.support, c2.support);
      if (toward > 0) {
        for (const auto& r : xs)
          if (compare_x(r->x, p.x()) > 0) {
            if (compare_x(r->x, *bound) < 0) bound = &r->x;
            break;
          }
      } else {
        for (auto it = xs.rbegin(); it != xs.rend(); ++it)
          if (compare_x((*it)->x, p.x()) < 0) {
            if (compare_x((*it)->x, *bound) > 0) bound = &(*it)->x;
            break;
          }
      }
    }
    Rational m = toward > 0 ? algebra::rational_between(p.x(), *bound) : algebra::rational_between(*bound, p.x());
    Real x = Real::from_rational(m);
    return compare_y(x, enclose(x), c1.interior, c2.interior);
  }

  using Intersection = boost::variant<std::pair<Point, Multiplicity>, XCurve>;

  /// Certified: the non-vertical arcs c1, c2 of distinct supports have no common point over
  /// [lo.x, hi.x] (their common x-range). Over an x-interval X, y_interval of an arc's interior
  /// expression encloses the arc's y at every x of X in the arc's closed x-range (at an end
  /// where that expression is 0/0, a(x) = 0, the enclosure is infinite and the test fails);
  /// disjoint enclosures on every part of a subdivision of the range exclude a common point
  /// without the resultant of the supports (most pairs CGAL's zone computation tests are far
  /// apart).
  bool apart(const XCurve& c1, const XCurve& c2, const Point& lo, const Point& hi) const {
    return apart(c1, c2, lo.rep->xi().lo, hi.rep->xi().hi, 6);
  }

  bool apart(const XCurve& c1, const XCurve& c2, double left, double right, int depth) const {
    const Interval x{left, right};
    const Interval y1 = y_interval(c1.interior, x), y2 = y_interval(c2.interior, x);
    auto finite = [](Interval a) { return std::isfinite(a.lo) && std::isfinite(a.hi); };
    if (finite(y1) && finite(y2) && disjoint(y1, y2)) return true;
    if (depth == 0) return false;
    const double m = left + (right - left) / 2;
    if (!(left < m && m < right)) return false;
    return apart(c1, c2, left, m, depth - 1) && apart(c1, c2, m, right, depth - 1);
  }

  void intersect(const XCurve& c1, const XCurve& c2, std::vector<Intersection>& out) const {
    auto point = [&](const Point& p) { out.emplace_back(std::make_pair(p, Multiplicity(0))); };
    if (c1.vertical && c2.vertical) {
      if (compare_x(c1.left, c2.left) != 0) return;
      const Point& lo = compare_y_same_x(c1.left, c2.left) >= 0 ? c1.left : c2.left;
      const Point& hi = compare_y_same_x(c1.right, c2.right) <= 0 ? c1.right : c2.right;
      int c = compare_y_same_x(lo, hi);
      if (c < 0) out.emplace_back(XCurve{lo, hi, c1.support, true, {}});
      else if (c == 0) point(lo);
      return;
    }
    if (c1.vertical || c2.vertical) {
      const XCurve& v = c1.vertical ? c1 : c2;
      const XCurve& c = c1.vertical ? c2 : c1;
      if (compare_x(v.left, c.left) < 0 || compare_x(v.left, c.right) > 0) return;
      Point p = point_on(c, v.left.x());
      int below = compare_y_same_x(p, v.left);
      if (below < 0) return;
      if (below == 0) return point(v.left);
      int above = compare_y_same_x(p, v.right);
      if (above > 0) return;
      return point(above == 0 ? v.right : p);
    }
    const Point& lo = compare_x(c1.left, c2.left) >= 0 ? c1.left : c2.left;
    const Point& hi = compare_x(c1.right, c2.right) <= 0 ? c1.right : c2.right;
    int range = compare_x(lo, hi);
    if (range > 0) return;
    if (c1.support == c2.support) {
      if (range < 0 && c1.interior == c2.interior) {
        out.emplace_back(XCurve{lo, hi, c1.support, false, c1.interior});
        return;
      }
      // distinct branches of one support meet only at events: ends of both arcs
      for (const Point* e1 : {&c1.left, &c1.right})
        for (const Point* e2 : {&c2.left, &c2.right})
          if (compare_xy(*e1, *e2) == 0) point(*e1);
      return;
    }
    if (range < 0 && apart(c1, c2, lo, hi)) {
      ++st_->intersections_filtered;
      return;
    }
    for (const auto& entry : root_entries(c1.support, c2.support)) {
      const Real& x = entry->x;
      if (compare_x(x, lo.x()) < 0) continue;
      if (compare_x(x, hi.x()) > 0) break;
      Point p1 = point_on(c1, x), p2 = point_on(c2, x);
      if (compare_y_same_x(p1, p2) != 0) continue;
      bool p1_end = p1.rep == c1.left.rep || p1.rep == c1.right.rep;
      point(p1_end ? p1 : p2);
    }
  }

  // ---------------------------------------------------------------- CGAL functors

  class Compare_x_2 {
   public:
    explicit Compare_x_2(const QuadraticTraits* t) : t_(t) {}
    CGAL::Comparison_result operator()(const Point& p, const Point& q) const {
      return CGAL::Comparison_result(t_->compare_x(p, q));
    }
   private:
    const QuadraticTraits* t_;
  };
  Compare_x_2 compare_x_2_object() const { return Compare_x_2(this); }

  class Compare_xy_2 {
   public:
    explicit Compare_xy_2(const QuadraticTraits* t) : t_(t) {}
    CGAL::Comparison_result operator()(const Point& p, const Point& q) const {
      return CGAL::Comparison_result(t_->compare_xy(p, q));
    }
   private:
    const QuadraticTraits* t_;
  };
  Compare_xy_2 compare_xy_2_object() const { return Compare_xy_2(this); }

  class Construct_min_vertex_2 {
   public:
    const Point& operator()(const XCurve& c) const { return c.left; }
  };
  Construct_min_vertex_2 construct_min_vertex_2_object() const { return {}; }

  class Construct_max_vertex_2 {
   public:
    const Point& operator()(const XCurve& c) const { return c.right; }
  };
  Construct_max_vertex_2 construct_max_vertex_2_object() const { return {}; }

  class Is_vertical_2 {
   public:
    bool operator()(const XCurve& c) const { return c.vertical; }
  };
  Is_vertical_2 is_vertical_2_object() const { return {}; }

  class Compare_y_at_x_2 {
   public:
    explicit Compare_y_at_x_2(const QuadraticTraits* t) : t_(t) {}
    CGAL::Comparison_result operator()(const Point& p, const XCurve& c) const {
      if (c.vertical) {
        if (t_->compare_y_same_x(p, c.left) < 0) return CGAL::SMALLER;
        if (t_->compare_y_same_x(p, c.right) > 0) return CGAL::LARGER;
        return CGAL::EQUAL;
      }
      return CGAL::Comparison_result(t_->compare_point_curve(p, c));
    }
   private:
    const QuadraticTraits* t_;
  };
  Compare_y_at_x_2 compare_y_at_x_2_object() const { return Compare_y_at_x_2(this); }

  class Compare_y_at_x_right_2 {
   public:
    explicit Compare_y_at_x_right_2(const QuadraticTraits* t) : t_(t) {}
    CGAL::Comparison_result operator()(const XCurve& c1, const XCurve& c2, const Point& p) const {
      return CGAL::Comparison_result(t_->compare_beside(c1, c2, p, 1));
    }
   private:
    const QuadraticTraits* t_;
  };
  Compare_y_at_x_right_2 compare_y_at_x_right_2_object() const { return Compare_y_at_x_right_2(this); }

  class Compare_y_at_x_left_2 {
   public:
    explicit Compare_y_at_x_left_2(const QuadraticTraits* t) : t_(t) {}
    CGAL::Comparison_result operator()(const XCurve& c1, const XCurve& c2, const Point& p) const {
      return CGAL::Comparison_result(t_->compare_beside(c1, c2, p, -1));
    }
   private:
    const QuadraticTraits* t_;
  };
  Compare_y_at_x_left_2 compare_y_at_x_left_2_object() const { return Compare_y_at_x_left_2(this); }

  class Equal_2 {
   public:
    explicit Equal_2(const QuadraticTraits* t) : t_(t) {}
    bool operator()(const Point& p, const Point& q) const { return t_->compare_xy(p, q) == 0; }
    bool operator()(const XCurve& c1, const XCurve& c2) const {
      if (c1.vertical != c2.vertical) return false;
      if (!c1.vertical && (c1.support != c2.support || c1.interior != c2.interior)) return false;
      return t_->compare_xy(c1.left, c2.left) == 0 && t_->compare_xy(c1.right, c2.right) == 0;
    }
   private:
    const QuadraticTraits* t_;
  };
  Equal_2 equal_2_object() const { return Equal_2(this); }

  class Split_2 {
   public:
    void operator()(const XCurve& c, const Point& p, XCurve& c1, XCurve& c2) const {
      XCurve left = c, right = c;
      left.right = p;
      right.left = p;
      c1 = std::move(left);
      c2 = std::move(right);
    }
  };
  Split_2 split_2_object() const { return {}; }

  class Intersect_2 {
   public:
    explicit Intersect_2(const QuadraticTraits* t) : t_(t) {}
    template <typename OutputIterator>
    OutputIterator operator()(const XCurve& c1, const XCurve& c2, OutputIterator oi) const {
      std::vector<Intersection> out;
      t_->intersect(c1, c2, out);
      for (auto& item : out) *oi++ = std::move(item);
      return oi;
    }
   private:
    const QuadraticTraits* t_;
  };
  Intersect_2 intersect_2_object() const { return Intersect_2(this); }

  class Make_x_monotone_2 {
   public:
    template <typename OutputIterator>
    OutputIterator operator()(const Curve& c, OutputIterator oi) const {
      *oi++ = boost::variant<Point, XCurve>(c.arc);
      return oi;
    }
  };
  Make_x_monotone_2 make_x_monotone_2_object() const { return {}; }

  class Are_mergeable_2 {
   public:
    bool operator()(const XCurve&, const XCurve&) const { return false; }
  };
  Are_mergeable_2 are_mergeable_2_object() const { return {}; }

  class Merge_2 {
   public:
    void operator()(const XCurve&, const XCurve&, XCurve&) const {
      throw GeometryError("internal: the quadratic traits does not merge curves");
    }
  };
  Merge_2 merge_2_object() const { return {}; }

  std::size_t exact_comparisons() const { return st_->exact_comparisons; }
  std::size_t subresultant_equalities() const { return st_->subresultant_equalities; }
  std::size_t intersections_filtered() const { return st_->intersections_filtered; }
  std::size_t mp_decided(int level) const { return st_->mp_decided[static_cast<std::size_t>(level)]; }
  std::size_t x_entries() const { return st_->entries.size(); }

 private:
  // CGAL copies traits objects (adaptors): the supports and caches are shared by the copies.
  struct State {
    Box box;
    std::deque<Support> supports;   ///< (references stay valid while supports are added during clipping)
    std::map<std::pair<int, int>, std::vector<std::shared_ptr<const XEntry>>> roots;
    std::unordered_map<const Real*, std::shared_ptr<const XEntry>> entries;
    std::multimap<double, std::shared_ptr<const XEntry>> by_lower;
    std::map<std::tuple<const void*, int, int, int, int, int, int>, int> exact_cache;
    std::map<std::pair<int, int>, CommonRoot> common;
    /// per support: a closed rational x-range holding every piece and point inserted on it
    /// (unset: the whole box), set before the insertion (see restrict_roots)
    std::vector<std::optional<std::pair<Rational, Rational>>> hulls;
    bool restricted = false;
    std::size_t exact_comparisons = 0, subresultant_equalities = 0, intersections_filtered = 0;
    std::array<std::size_t, mp_levels> mp_decided{};
  };
  std::shared_ptr<State> st_;
};

}  // namespace
}  // namespace hipair::cspace::raw

namespace hipair::cspace::raw {
namespace {

using Arrangement_2 = CGAL::Arrangement_2<QuadraticTraits>;
using ClauseAlternatives = std::vector<const std::vector<ValidityClause>*>;
using Windows = std::vector<std::pair<Rational, Rational>>;

class QuadraticBuilder {
 public:
  QuadraticBuilder(const Box& box, const Options& options)
      : box_(box), options_(options), traits_(box), arrangement_(&traits_) {
    make_box();
  }

  Arrangement run(const std::vector<IntegerPolynomial2>& curves,
                  const std::vector<std::vector<ValidityClause>>& validity,
                  const std::vector<std::vector<std::pair<Rational, Rational>>>& windows) {
    auto start = Clock::now();
    std::vector<XCurve> pieces(sides_.begin(), sides_.end());
    std::vector<Point> isolated;
    static const std::vector<ValidityClause> no_clauses;
    const CurveGroups grouped = group_curves(curves);   // as the algebraic stage
    const auto& group_polynomials = grouped.polynomials;
    const auto& groups = grouped.members;
    for (std::size_t g = 0; g < groups.size(); ++g) {
      ClauseAlternatives alternatives;
      for (std::size_t member : groups[g])
        alternatives.push_back(member < validity.size() ? &validity[member] : &no_clauses);
      Windows group_windows;
      bool restricted = true;
      for (std::size_t member : groups[g]) {
        if (member >= windows.size() || windows[member].empty()) {
          restricted = false;
          break;
        }
        group_windows.insert(group_windows.end(), windows[member].begin(), windows[member].end());
      }
      // (the culling's surviving cells of the members, when every member has them)
      cells_ = group_cells(options_.cells, groups[g], group_cells_) ? &group_cells_ : nullptr;
      clip(group_polynomials[g], alternatives, restricted ? &group_windows : nullptr, pieces, isolated);
    }
    cells_ = nullptr;
    // every piece and isolated point is known: each support's resultant roots are needed only
    // over the x-range its pieces and points span (a support without any, such as a line
    // y = c ending vertical pieces, keeps the whole box)
    for (const auto& piece : pieces) traits_.extend_hull(piece.support, piece.left.x(), piece.right.x());
    for (const auto& point : isolated) traits_.extend_hull(point.rep->y.support, point.x(), point.x());
    traits_.restrict_roots();
    result_.times.curves_seconds = seconds_since(start);

    start = Clock::now();
    if (options_.aggregated_insertion) {
      CGAL::insert(arrangement_, pieces.begin(), pieces.end());
    } else {
      for (const auto& piece : pieces) CGAL::insert(arrangement_, piece);
    }
    for (const auto& point : isolated) CGAL::insert_point(arrangement_, point);
    result_.pieces_inserted = pieces.size();
    result_.times.insertion_seconds = seconds_since(start);
    static const bool debug = std::getenv("HIPAIR_CSPACE_DEBUG") != nullptr;
    if (debug)
      std::fprintf(stderr,
                   "  quadratic traits: %zu pieces, %zu arc pairs apart in interval enclosures, %zu equal by subresultant, decided at 2^-128/-320/-800/-2000: "
                   "%zu/%zu/%zu/%zu, %zu exact y comparisons, %zu x entries, insertion %.4f s\n",
                   pieces.size(), traits_.intersections_filtered(), traits_.subresultant_equalities(), traits_.mp_decided(0), traits_.mp_decided(1),
                   traits_.mp_decided(2), traits_.mp_decided(3), traits_.exact_comparisons(), traits_.x_entries(),
                   result_.times.insertion_seconds);

    start = Clock::now();
    export_topology();
    result_.times.export_seconds = seconds_since(start);
    return std::move(result_);
  }

 private:
  static IntegerPolynomial2 horizontal_line(const Rational& y) {   // den y - num
    return IntegerPolynomial2{{{mpz_class(-y.get_num()), mpz_class(y.get_den())}}};
  }
  static IntegerPolynomial2 vertical_line(const Rational& x) {   // den x - num
    return IntegerPolynomial2{{{mpz_class(-x.get_num())}, {mpz_class(x.get_den())}}};
  }

  void make_box() {
    bottom_ = YExpr{traits_.add_support(horizontal_line(box_.y_lo)), 2, 0};
    top_ = YExpr{traits_.add_support(horizontal_line(box_.y_hi)), 2, 0};
    int left = traits_.add_support(vertical_line(box_.x_lo));
    int right = traits_.add_support(vertical_line(box_.x_hi));
    Real x_lo = Real::from_rational(box_.x_lo), x_hi = Real::from_rational(box_.x_hi);
    Point corners[4] = {traits_.make_point(x_lo, bottom_), traits_.make_point(x_hi, bottom_),
                        traits_.make_point(x_hi, top_), traits_.make_point(x_lo, top_)};
    sides_.push_back(XCurve{corners[0], corners[1], bottom_.support, false, bottom_});   // bottom
    sides_.push_back(XCurve{corners[1], corners[2], right, true, {}});                    // right
    sides_.push_back(XCurve{corners[3], corners[2], top_.support, false, top_});          // top
    sides_.push_back(XCurve{corners[0], corners[3], left, true, {}});                     // left
  }

  bool strictly_between_sides(const Real& x, const YExpr& y) const {
    Interval xi = enclose(x);
    return traits_.compare_y(x, xi, y, bottom_) > 0 && traits_.compare_y(x, xi, y, top_) < 0;
  }

  static bool unrestricted(const ClauseAlternatives& alternatives) {
    for (const auto* clauses : alternatives)
      if (clauses->empty()) return true;
    return false;
  }

  // roots of p in the open box x-range
  void roots_inside(const Polynomial& p, std::vector<Real>& out) const {
    if (algebra::degree(p) < 1) return;
    for (auto& r : roots_in(p, box_.x_lo, box_.x_hi))
      if (r.compare(box_.x_lo) > 0 && r.compare(box_.x_hi) < 0) out.push_back(std::move(r));
  }

  // Cut abscissae: the roots of p strictly inside the box's x-range, and when the group has
  // windows only those in the (merged, closed) windows. A cut outside every window separates
  // two stretches outside every window, which bound nothing (clip_arc inserts no piece there,
  // and the windows' own bounds are cuts), so it changes no piece; isolating roots only in
  // the windows skips most of a curve's cuts in a finely culled chart.
  void cut_roots(const Polynomial& p, std::vector<Real>& out) const {
    if (!cut_windows_) {
      roots_inside(p, out);
      return;
    }
    if (algebra::degree(p) < 1) return;
    for (const auto& [lo, hi] : *cut_windows_) {
      const Rational& a = lo < box_.x_lo ? box_.x_lo : lo;
      const Rational& b = box_.x_hi < hi ? box_.x_hi : hi;
      if (!(a < b)) continue;
      for (auto& r : roots_in(p, a, b))
        if (r.compare(box_.x_lo) > 0 && r.compare(box_.x_hi) < 0) out.push_back(std::move(r));
    }
  }

  // Abscissae where an atom may change sign along the curve (a superset of the roots of the
  // resultant in y of the curve and the atom; none when they share a component, as in the
  // algebraic stage), in the windows (cut_roots).
  void validity_breaks(const Support& s, const ClauseAlternatives& alternatives, std::vector<Real>& out) const {
    for (const auto* clauses : alternatives)
      for (const auto& clause : *clauses)
        for (const auto& atom : clause.atoms) {
          std::vector<Polynomial> g = columns(atom);
          if (g.empty()) continue;
          if (g.size() > s.part_columns.size()) {
            g = pseudo_remainder(std::move(g), s.part_columns);
            if (g.empty()) continue;
            cut_roots(s.part_columns.back(), out);
          }
          Polynomial r = remembered_resultant_y(s.part_columns, g);
          if (r.empty()) continue;
          cut_roots(r, out);
        }
  }

  /// The signs of a support's a, disc and b at one bound of its event intervals, each exact
  /// and computed on first use (2: not yet). A bound is an event: a root of a, disc or the
  /// content, isolated with that polynomial's square-free part. When x's own polynomial is
  /// proportional to p, p vanishes at x (exactly: p = c P with P(x) = 0), without the sign
  /// computation's refinements and gcd.
  struct BoundSigns {
    int a = 2, disc = 2, b = 2;
    int of(int& slot, const Polynomial& p, const Real& x) {
      if (slot == 2) slot = !x.exact && algebra::proportional(p, x.polynomial) ? 0 : algebra::sign_at(p, x);
      return slot;
    }
  };

  enum class CutKind { soft = 0, hard = 1 };

  struct Cut {
    Real x;
    CutKind kind;
    /// x's canonical entry, made when a piece first ends at this cut (the branches of one
    /// event interval share it; cuts where no piece ends never make one)
    mutable std::shared_ptr<const XEntry> entry;
  };

  /// The exact order of two of one clip's cut abscissae (refined), each pair whose enclosures
  /// overlap decided once: the sort and the merge of equal cuts after it ask again. Such a
  /// pair is mostly one root of two polynomials (a resultant's factor shared with another's),
  /// which the gcd proves equal (algebra::equal) where compare() first bisects both in
  /// multiple precision, which cannot separate equal numbers; compare() orders the others.
  class CutOrder {
   public:
    explicit CutOrder(const std::vector<Real>& xs) : xs_(xs) {}
    int operator()(std::size_t i, std::size_t j) {
      if (i == j) return 0;
      const Real &a = xs_[i], &b = xs_[j];
      const Interval ia = enclose(a), ib = enclose(b);
      if (ia.hi < ib.lo) return -1;
      if (ib.hi < ia.lo) return 1;
      for (const auto& [p, q, c] : asked_) {
        if (p == i && q == j) return c;
        if (p == j && q == i) return -c;
      }
      const int c = algebra::equal(a, b) ? 0 : algebra::compare(a, b);
      asked_.emplace_back(i, j, c);
      return c;
    }

   private:
    const std::vector<Real>& xs_;
    std::vector<std::tuple<std::size_t, std::size_t, int>> asked_;
  };

  void clip(const IntegerPolynomial2& f, const ClauseAlternatives& alternatives, const Windows* windows,
            std::vector<XCurve>& pieces, std::vector<Point>& isolated) {
    const int id = traits_.add_support(f);
    const Support& s = traits_.support(id);
    // vertical lines (factors in x alone), strictly inside the box's x-range
    if (algebra::degree(s.content) >= 1) {
      std::vector<Real> lines;
      roots_inside(s.content, lines);
      for (const Real& r : lines) vertical_pieces(r, id, pieces);
    }
    if (s.degree == 0) return;
    // cuts strictly inside the box's x-range that are not events of the curve
    std::vector<Real> soft, hard;
    Windows merged_windows;
    if (windows) {
      merged_windows = *windows;
      std::sort(merged_windows.begin(), merged_windows.end());
      std::size_t n = 0;
      for (std::size_t w = 0; w < merged_windows.size(); ++w) {
        if (n > 0 && merged_windows[w].first <= merged_windows[n - 1].second) {
          if (merged_windows[n - 1].second < merged_windows[w].second) merged_windows[n - 1].second = merged_windows[w].second;
        } else {
          merged_windows[n++] = merged_windows[w];
        }
      }
      merged_windows.resize(n);
    }
    cut_windows_ = windows ? &merged_windows : nullptr;
    for (const Rational& y : {box_.y_lo, box_.y_hi}) cut_roots(algebra::substitute_y(f, y), soft);
    validity_breaks(s, alternatives, soft);
    if (windows)
      for (const auto& [lo, hi] : *windows)
        for (const Rational* bound : {&lo, &hi})
          if (box_.x_lo < *bound && *bound < box_.x_hi) soft.push_back(Real::from_rational(*bound));
    Polynomial tangents;   // resultant_y(f, f_x): its roots hold the horizontal tangents' abscissae
    {   // horizontal tangents of the whole polynomial (pieces stay y-monotone)
      std::vector<Polynomial> cols = columns(f), f_x;
      for (const auto& c : cols) f_x.push_back(algebra::derivative(c));
      while (!f_x.empty() && f_x.back().empty()) f_x.pop_back();
      if (!f_x.empty()) {
        tangents = remembered_resultant_y(cols, f_x);
        cut_roots(tangents, hard);
      }
    }
    cut_windows_ = nullptr;
    std::vector<Cut> cuts;
    {
      std::vector<Real> h = traits_.sorted_unique(std::move(hard)), all = std::move(h);
      std::size_t hard_count = all.size();
      for (auto& x : soft) all.push_back(std::move(x));
      std::vector<std::pair<std::size_t, Real*>> order;
      for (auto& x : all) QuadraticTraits::refine(x);
      for (std::size_t i = 0; i < all.size(); ++i) order.emplace_back(i, &all[i]);
      CutOrder cut_order(all);
      std::sort(order.begin(), order.end(), [&](const auto& p, const auto& q) {
        int c = cut_order(p.first, q.first);
        return c != 0 ? c < 0 : p.first < q.first;   // hard ones (lower index) first among equals
      });
      // (a cut equal to its predecessor in this order is equal to the first of their run)
      for (std::size_t k = 0; k < order.size(); ++k) {
        if (k > 0 && cut_order(order[k - 1].first, order[k].first) == 0) continue;
        cuts.push_back(Cut{*order[k].second, order[k].first < hard_count ? CutKind::hard : CutKind::soft, nullptr});
      }
    }
    // event intervals: [x_lo, e_1], ..., [e_k, x_hi]
    std::vector<Real> bounds;
    bounds.push_back(Real::from_rational(box_.x_lo));
    for (const Real& e : s.events) bounds.push_back(e);
    bounds.push_back(Real::from_rational(box_.x_hi));
    std::vector<int> branches(bounds.size() - 1, 0);
    std::vector<int> a_sign(bounds.size() - 1, 0);
    for (std::size_t i = 0; i + 1 < bounds.size(); ++i) {
      Rational m = algebra::rational_between(bounds[i], bounds[i + 1]);
      if (s.degree == 1) {
        branches[i] = 1;
        continue;
      }
      branches[i] = algebra::sign_at(s.disc, m) > 0 ? 2 : 0;
      a_sign[i] = algebra::sign_at(s.a, m);
    }
    // the signs at the bounds, each computed once (a bound ends up to four branch ends)
    std::vector<BoundSigns> bound_signs(bounds.size());
    std::size_t next_cut = 0;
    for (std::size_t i = 0; i + 1 < bounds.size(); ++i) {
      // cuts strictly inside (bounds[i], bounds[i + 1])
      std::vector<const Cut*> inside;
      while (next_cut < cuts.size() && QuadraticTraits::compare_x(cuts[next_cut].x, bounds[i]) <= 0) ++next_cut;
      for (std::size_t c = next_cut; c < cuts.size() && QuadraticTraits::compare_x(cuts[c].x, bounds[i + 1]) < 0; ++c)
        inside.push_back(&cuts[c]);
      for (int k = 0; k < branches[i]; ++k) {
        YExpr expr = s.degree == 1 ? YExpr{id, 2, 0} : YExpr{id, 0, k == 0 ? -a_sign[i] : a_sign[i]};
        std::optional<Point> first = end_point(s, id, expr, bounds[i], bound_signs[i]);
        std::optional<Point> last = end_point(s, id, expr, bounds[i + 1], bound_signs[i + 1]);
        clip_arc(s, id, expr, first, last, bounds[i], bounds[i + 1], inside, f, alternatives, windows, tangents, pieces);
      }
    }
    // isolated points: a double root with no branch on either side
    if (s.degree == 2)
      for (std::size_t e = 1; e + 1 < bounds.size(); ++e) {
        if (branches[e - 1] != 0 || branches[e] != 0) continue;
        const Real& x = bounds[e];
        if (bound_signs[e].of(bound_signs[e].a, s.a, x) == 0 || bound_signs[e].of(bound_signs[e].disc, s.disc, x) != 0 ||
            algebra::sign_at(s.content, x) == 0)
          continue;
        YExpr expr{id, 1, 0};
        if (!strictly_between_sides(x, expr)) continue;
        if (x.exact && !unrestricted(alternatives)) {
          algebra::Polynomial fiber = algebra::substitute_x(f, x.lower);
          if (algebra::degree(fiber) >= 1 && !clauses_hold(alternatives, x.lower, algebra::nth_real_root(fiber, 0)))
            continue;
        }
        isolated.push_back(traits_.make_point(x, expr));
      }
  }

  // A vertical line x = r of the group being clipped: the whole box height when the group is not
  // restricted; otherwise only its stretches inside the culling's surviving cells (the line
  // bounds nothing outside them, as a branch piece meeting none of them): the y-ranges of the
  // cells whose closed x-range meets r's certified enclosure, merged where they overlap or
  // touch, clipped to the box, each a piece between points at those rational y.
  void vertical_pieces(Real r, int id, std::vector<XCurve>& pieces) {
    if (!cells_) {
      pieces.push_back(XCurve{traits_.make_point(r, bottom_), traits_.make_point(r, top_), id, true, {}});
      return;
    }
    QuadraticTraits::refine(r);   // (an isolating interval may span many columns)
    const double lo = r.lower_bound(), hi = r.upper_bound();
    std::vector<std::pair<double, double>> ys;
    for (const auto& cell : *cells_) {
      if (cell[0] > hi) break;   // sorted by x_lo
      if (cell[1] < lo) continue;
      ys.emplace_back(cell[2], cell[3]);
    }
    std::sort(ys.begin(), ys.end());
    std::vector<std::pair<double, double>> merged;
    for (const auto& y : ys) {
      if (!merged.empty() && !(y.first > merged.back().second))
        merged.back().second = std::max(merged.back().second, y.second);
      else
        merged.push_back(y);
    }
    for (const auto& [y0, y1] : merged) {
      // (a side beyond the doubles' range or the box's: the box side)
      const bool from_bottom = !std::isfinite(y0) || Rational(y0) <= box_.y_lo;
      const bool to_top = !std::isfinite(y1) || Rational(y1) >= box_.y_hi;
      if (!from_bottom && Rational(y0) >= box_.y_hi) continue;
      if (!to_top && Rational(y1) <= box_.y_lo) continue;
      if (!from_bottom && !to_top && !(Rational(y0) < Rational(y1))) continue;
      const YExpr low = from_bottom ? bottom_ : horizontal(Rational(y0));
      const YExpr high = to_top ? top_ : horizontal(Rational(y1));
      pieces.push_back(XCurve{traits_.make_point(r, low), traits_.make_point(r, high), id, true, {}});
    }
  }

  // The line y = c as a y expression (one support per value).
  YExpr horizontal(const Rational& c) {
    auto it = horizontals_.find(c);
    if (it == horizontals_.end()) it = horizontals_.emplace(c, YExpr{traits_.add_support(horizontal_line(c)), 2, 0}).first;
    return it->second;
  }

  // The end of a branch at a bound of its event interval; nullopt when the branch goes to
  // infinity there (a vertical asymptote).
  std::optional<Point> end_point(const Support& s, int id, const YExpr& expr, const Real& x, BoundSigns& signs) const {
    if (s.degree == 1) {
      if (signs.of(signs.b, s.b, x) == 0) return std::nullopt;
      return traits_.make_point(x, expr);
    }
    int a = signs.of(signs.a, s.a, x);
    if (a != 0) {
      if (signs.of(signs.disc, s.disc, x) == 0) return traits_.make_point(x, YExpr{id, 1, 0});
      return traits_.make_point(x, expr);
    }
    int b = signs.of(signs.b, s.b, x);
    if (b == 0 || b != expr.s) return std::nullopt;
    return traits_.make_point(x, YExpr{id, 2, 0});
  }

  // Arc number of a branch at a rational x inside its event interval (index among the
  // distinct real roots of the support's fibre).
  int arcno(const Support& s, const YExpr& expr, const Real& x) const {
    if (expr.kind != 0) return 0;
    return algebra::sign_at(s.a, x) * expr.s < 0 ? 0 : 1;
  }

  void clip_arc(const Support& s, int id, const YExpr& expr, const std::optional<Point>& first_end,
                const std::optional<Point>& last_end, const Real& x_first, const Real& x_last,
                const std::vector<const Cut*>& inside, const IntegerPolynomial2& f,
                const ClauseAlternatives& alternatives, const Windows* windows, const Polynomial& tangents,
                std::vector<XCurve>& pieces) {
    // the cut abscissae along the arc, its ends included (an infinite end keeps its x)
    // (a cut's point is made only where a piece ends at it: most cuts bound culled or
    // invalid stretches, and each point costs a canonical x)
    std::vector<const Real*> xs;
    std::vector<std::optional<Point>> points;
    std::vector<char> is_hard;
    xs.push_back(&x_first);
    points.push_back(first_end);
    is_hard.push_back(0);
    for (const Cut* cut : inside) {
      xs.push_back(&cut->x);
      points.emplace_back();
      is_hard.push_back(cut->kind == CutKind::hard);
    }
    xs.push_back(&x_last);
    points.push_back(last_end);
    is_hard.push_back(0);
    const std::size_t count = xs.size() - 1;
    auto has_point = [&](std::size_t k) { return points[k].has_value() || (k > 0 && k < count); };
    auto point_at = [&](std::size_t k) -> Point {
      if (!points[k]) {
        const Cut* cut = inside[k - 1];
        if (!cut->entry) cut->entry = traits_.canonical(cut->x);
        points[k] = traits_.make_point(cut->entry, expr);
      }
      return *points[k];
    };
    std::vector<char> in_box(count, 0), valid(count, 0);
    const bool any_clauses = !unrestricted(alternatives);
    for (std::size_t i = 0; i < count; ++i) {
      Rational m = algebra::rational_between(*xs[i], *xs[i + 1]);
      Real mx = Real::from_rational(m);
      in_box[i] = strictly_between_sides(mx, expr);
      if (!in_box[i] || !in_windows(m, windows)) continue;
      // a piece whose certified y enclosure meets none of the culling's surviving cells bounds nothing
      if (cells_ && !branch_meets_cells(*cells_, xs[i]->lower_bound(), xs[i + 1]->upper_bound(),
                                        [&](Interval x) { return traits_.y_interval(expr, x); }))
        continue;
      // an asymptote inside the box, where a piece may be inserted (a stretch outside the windows
      // or the cells is never inserted: its missing end is never a piece's end; a cut outside
      // the windows no longer separates such a stretch from the part of the branch in the box)
      if (!has_point(i) || !has_point(i + 1)) throw NotApplicable{"asymptote inside the box"};
      if (!any_clauses) {
        valid[i] = 1;
        continue;
      }
      // certified double filter first (the branch's y enclosure at m), exact fallback
      const Interval mi = enclose(mx);
      const int filtered = clauses_hold_filter(alternatives, mi, traits_.y_interval(expr, mi));
      if (filtered >= 0) {
        valid[i] = static_cast<char>(filtered);
        continue;
      }
      algebra::Polynomial fiber = algebra::substitute_x(f, m);
      valid[i] = clauses_hold(alternatives, m, algebra::nth_real_root(fiber, arcno(s, expr, mx)));
    }
    auto near = [&](std::size_t from, std::size_t to) {
      // a point of the arc strictly between xs[from] and xs[to], near xs[to] (a short
      // spurious stretch: 8 halvings toward the bound of xs[to]'s interval on this side)
      Rational m = algebra::rational_between(*xs[std::min(from, to)], *xs[std::max(from, to)]);
      // The stretch joins the piece, whose box is the box of its ends: it must hold no
      // horizontal tangent. Inside the windows every tangent is a hard cut; outside them none
      // was isolated (cut_roots), so there the closed x-range from the point to xs[to]'s
      // interval is checked exactly, and where a tangent may lie in it the piece ends at the
      // cut itself (session 69: the film advance's cam:follower slice at tan(psi/2) = -7/2048
      // had a piece over a tangent outside its window, and its box missed the arc's top).
      const bool outside_windows = windows && !in_windows(m, windows);
      const Rational& bound = from < to ? xs[to]->lower : xs[to]->upper;
      if (from < to ? m < bound || xs[to]->exact : bound < m || xs[to]->exact)
        for (int k = 0; k < 8; ++k) m = (m + bound) / 2;
      if (outside_windows && algebra::degree(tangents) >= 1) {
        const Rational& lo = from < to ? std::min(m, xs[to]->lower) : xs[to]->lower;
        const Rational& hi = from < to ? xs[to]->upper : std::max(m, xs[to]->upper);
        if (!roots_in(tangents, lo, hi).empty()) return point_at(to);
      }
      return traits_.make_point(Real::from_rational(m), expr);
    };
    for (std::size_t i = 0; i < count;) {
      if (!valid[i]) {
        ++i;
        continue;
      }
      std::size_t start = i, end = i + 1;
      while (end < count && valid[end] && !is_hard[end]) ++end;
      // a piece never reaches across a hard cut (a horizontal tangent): its edge box is the box
      // of its ends, so it must stay y-monotone (a circle's lower branch stretched past its
      // bottom point lost the bottom from its box, and evaluating the edge there failed)
      Point first = start > 0 && in_box[start - 1] && !valid[start - 1] && !is_hard[start] ? near(start - 1, start)
                                                                                          : point_at(start);
      Point last = end < count && in_box[end] && !valid[end] && !is_hard[end] ? near(end + 1, end) : point_at(end);
      pieces.push_back(XCurve{first, last, id, false, expr});
      i = end;
    }
  }

  // ---------------------------------------------------------------- export

  /// Finest x width (2^-bits) tried by y_bounds before the chart is left to CGAL's traits.
  static constexpr int y_bounds_max_bits = 16384;

  // Certified y bounds isolating the point's y among the roots of its curve's fibre: double
  // intervals while x's refinement still narrows its double enclosure, then multiple
  // precision (hostile75 H1: two branches 1e-80 apart are never disjoint in doubles, whose
  // width is about 2^-52 of |y|; the chart then fell to CGAL's algebraic traits, 100x slower).
  void y_bounds(const Point& p, int branches, Rational& lower, Rational& upper, int bits) const {
    const PointRep& r = *p.rep;
    Interval previous{1, 0};
    for (; bits <= 1600; bits *= 2) {
      Real x = r.entry->x;
      algebra::refine_dyadically(x, Rational(1, mpz_class(1) << bits));
      Interval xi = enclose(x);
      // the double enclosure of y depends on x only through xi: once refining x leaves xi
      // unchanged, every finer level fails as this one did
      if (xi.lo == previous.lo && xi.hi == previous.hi) break;
      previous = xi;
      Interval yi = traits_.y_interval(r.y, xi);
      if (!std::isfinite(yi.lo) || !std::isfinite(yi.hi)) continue;
      if (branches == 2) {
        Interval other = traits_.y_interval(YExpr{r.y.support, 0, -r.y.s}, xi);
        if (!disjoint(yi, other)) continue;
      }
      lower = Rational(yi.lo);
      upper = Rational(yi.hi);
      return;
    }
    mp_y_bounds(r, branches, lower, upper, bits);
  }

  // y_bounds in multiple precision: x refined to 2^-bits, arithmetic at bits + 64 bits,
  // doubling until the branch's enclosure is disjoint from the other branch's (the gap
  // sqrt(disc(x)) / |a(x)| > 0 is met at a finite level); NotApplicable past the limit.
  void mp_y_bounds(const PointRep& r, int branches, Rational& lower, Rational& upper, int bits) const {
    for (; bits <= y_bounds_max_bits; bits *= 2) {
      const mpfr_prec_t prec = bits + 64;
      Real x = r.entry->x;
      algebra::refine_dyadically(x, Rational(1, mpz_class(1) << bits));
      Mp xi(prec), yi(prec);
      if (x.exact)
        mpfi_set_q(xi.get(), x.lower.get_mpq_t());
      else
        mpfi_interv_q(xi.get(), x.lower.get_mpq_t(), x.upper.get_mpq_t());
      if (!traits_.mp_y(r.y, xi.get(), prec, yi.get())) continue;
      if (branches == 2) {
        Mp other(prec);
        if (!traits_.mp_y(YExpr{r.y.support, 0, -r.y.s}, xi.get(), prec, other.get())) continue;
        if (mpfr_cmp(&yi.get()->right, &other.get()->left) >= 0 && mpfr_cmp(&other.get()->right, &yi.get()->left) >= 0)
          continue;
      }
      mpfr_get_q(lower.get_mpq_t(), &yi.get()->left);
      mpfr_get_q(upper.get_mpq_t(), &yi.get()->right);
      return;
    }
    throw NotApplicable{"y bounds"};
  }

  void fill_vertex(const Point& p, Vertex& out) const {
    const PointRep& r = *p.rep;
    const Support& s = traits_.support(r.y.support);
    out.x = r.entry->x;
    out.y_curve = s.part;
    out.y_branch = arcno(s, r.y, r.entry->x);
    if (r.entry->x.exact) {
      algebra::Polynomial fiber = algebra::substitute_x(out.y_curve, r.entry->x.lower);
      if (algebra::degree(fiber) < 1) throw NotApplicable{"vanishing fibre"};
      // Remembered per thread (session 63): a vertex on a side shared by two tiles of an
      // operating region is the same root of the same fibre in both (a pure function of the
      // fibre and the branch, compared exactly).
      thread_local ExactMemo<std::pair<algebra::Polynomial, int>, Real, 2048> memo;
      std::size_t h = fiber.size() * 131u + static_cast<std::size_t>(out.y_branch);
      for (const mpz_class& c : fiber) h = mix_integer(h, c);
      out.y = memo.get(h, std::pair<algebra::Polynomial, int>{fiber, out.y_branch}, [&] {
        Real y = algebra::nth_real_root(fiber, out.y_branch);
        algebra::refine_dyadically(y, Rational(1, mpz_class(1) << 64));
        return y;
      });
      out.y_exact = true;
      out.y_lower = out.y.lower;
      out.y_upper = out.y.upper;
      return;
    }
    y_bounds(p, r.y.kind == 0 ? 2 : 1, out.y_lower, out.y_upper, 52);
  }

  void separate_in_y(const Point& low, const Point& high, std::size_t low_id, std::size_t high_id) const {
    Vertex& a = result_.vertices[low_id];
    Vertex& b = result_.vertices[high_id];
    for (int bits = 104; !(a.y_upper < b.y_lower); bits *= 2) {
      if (bits > y_bounds_max_bits) throw NotApplicable{"y bounds"};
      for (auto [point, vertex] : {std::pair{&low, &a}, std::pair{&high, &b}}) {
        Rational lower, upper;
        if (vertex->y_exact) {
          algebra::refine_dyadically(vertex->y, Rational(1, mpz_class(1) << bits));
          lower = vertex->y.lower;
          upper = vertex->y.upper;
        } else {
          y_bounds(*point, point->rep->y.kind == 0 ? 2 : 1, lower, upper, bits);
        }
        if (lower > vertex->y_lower) vertex->y_lower = std::move(lower);
        if (upper < vertex->y_upper) vertex->y_upper = std::move(upper);
      }
    }
  }

  int side_of(const XCurve& c) const {
    if (c.vertical) {
      if (c.left.x().compare(box_.x_lo) == 0) return 3;
      if (c.left.x().compare(box_.x_hi) == 0) return 1;
      return -1;
    }
    Real m = Real::from_rational(algebra::rational_between(c.left.x(), c.right.x()));
    Interval mi = enclose(m);
    if (traits_.compare_y(m, mi, c.interior, bottom_) == 0) return 0;
    if (traits_.compare_y(m, mi, c.interior, top_) == 0) return 2;
    return -1;
  }

  void fill_arc_numbers(const XCurve& c, ArcNumbers& out) const {
    const Support& s = traits_.support(c.support);
    for (const Real& e : s.events)
      if (traits_.compare_x(e, c.left.x()) > 0 && traits_.compare_x(e, c.right.x()) < 0)
        throw NotApplicable{"event inside an edge"};   // never: arcs end at their curve's events
    Real m = Real::from_rational(algebra::rational_between(c.left.x(), c.right.x()));
    out.between.push_back(arcno(s, c.interior, m));
  }

  std::size_t wedge_containing(const std::vector<Arrangement_2::Halfedge_const_handle>& around,
                               const std::vector<Incidence>& incidences, const Point& p, bool below) const {
    return wedge_around(incidences, below, [&](std::size_t a, std::size_t b, Direction side) {
      if (side == Direction::right) return traits_.compare_beside(around[a]->curve(), around[b]->curve(), p, 1) > 0;
      return traits_.compare_beside(around[a]->curve(), around[b]->curve(), p, -1) < 0;
    });
  }

  void export_topology() {
    const Arrangement_2& arr = arrangement_;
    std::unordered_map<const void*, std::size_t> vertex_id, face_id, edge_id;
    std::unordered_map<const void*, bool> forward;
    for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v) {
      vertex_id[&*v] = result_.vertices.size();
      Vertex out;
      fill_vertex(v->point(), out);
      out.isolated = v->is_isolated();
      result_.vertices.push_back(std::move(out));
    }
    for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
      face_id[&*f] = result_.faces.size();
      Face out;
      out.unbounded = f->is_unbounded();
      if (out.unbounded && result_.unbounded_face == none) result_.unbounded_face = result_.faces.size();
      result_.faces.push_back(std::move(out));
    }
    for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
      auto h = e->direction() == CGAL::ARR_LEFT_TO_RIGHT ? e : e->twin();
      edge_id[&*h] = edge_id[&*h->twin()] = result_.edges.size();
      forward[&*h] = true;
      forward[&*h->twin()] = false;
      Edge out;
      const XCurve& arc = h->curve();
      out.min_vertex = vertex_id.at(&*h->source());
      out.max_vertex = vertex_id.at(&*h->target());
      out.vertical = arc.vertical;
      if (out.vertical) separate_in_y(h->source()->point(), h->target()->point(), out.min_vertex, out.max_vertex);
      out.support = traits_.support(arc.support).full;
      out.left_face = face_id.at(&*h->face());
      out.right_face = face_id.at(&*h->twin()->face());
      fill_edge_box(result_.vertices, out);
      out.box_side = side_of(arc);
      if (!out.vertical) fill_arc_numbers(arc, out.arc_numbers);
      result_.edges.push_back(std::move(out));
    }
    for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v) {
      Vertex& out = result_.vertices[vertex_id.at(&*v)];
      if (v->is_isolated()) {
        out.face_below = out.face_above = face_id.at(&*v->face());
        result_.faces[out.face_below].isolated_vertices.push_back(vertex_id.at(&*v));
        continue;
      }
      std::vector<Arrangement_2::Halfedge_const_handle> around;
      auto circulator = v->incident_halfedges();
      auto first = circulator;
      do {
        around.push_back(circulator);
      } while (++circulator != first);
      for (const auto& h : around) {
        Incidence incidence;
        incidence.edge = edge_id.at(&*h);
        incidence.direction = leaving_direction(h->curve().vertical, h->direction() == CGAL::ARR_LEFT_TO_RIGHT);
        incidence.wedge_face = face_id.at(&*h->face());
        out.around.push_back(incidence);
      }
      out.face_below = wedge_containing(around, out.around, v->point(), true);
      out.face_above = wedge_containing(around, out.around, v->point(), false);
    }
    for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f)
      export_face_boundary(*f, result_.faces[face_id.at(&*f)], [&](const auto& c) { return edge_id.at(&*c); },
                           [&](const auto& c) { return forward.at(&*c); });
  }

  Box box_;
  Options options_;
  QuadraticTraits traits_;
  Arrangement_2 arrangement_;
  YExpr bottom_, top_;
  std::vector<XCurve> sides_;
  mutable Arrangement result_;
  CellBoxes group_cells_;              // the group being clipped: its members' surviving cells
  const CellBoxes* cells_ = nullptr;   // null: not restricted
  std::map<Rational, YExpr> horizontals_;   // supports of the lines y = c ending vertical pieces
  const Windows* cut_windows_ = nullptr;     // the group's merged windows while its cuts are found
};

}  // namespace

bool quadratic_applies(const std::vector<IntegerPolynomial2>& curves, std::size_t max_bits) {
  for (const auto& c : curves) {
    if (c.degree_y() > 2) return false;
    for (const auto& row : c.coefficients)
      for (const auto& z : row)
        if (mpz_sizeinbase(z.get_mpz_t(), 2) > max_bits) return false;
  }
  return true;
}

std::optional<Arrangement> build_quadratic_arrangement(
    const Box& box, const std::vector<IntegerPolynomial2>& curves,
    const std::vector<std::vector<ValidityClause>>& validity,
    const std::vector<std::vector<std::pair<Rational, Rational>>>& windows, const Options& options) {
  static const bool debug = std::getenv("HIPAIR_CSPACE_DEBUG") != nullptr;
  if (debug) {
    int max_x = 0, max_y = 0;
    for (const auto& c : curves) {
      max_x = std::max(max_x, c.degree_x());
      max_y = std::max(max_y, c.degree_y());
    }
    std::fprintf(stderr, "  quadratic traits: %zu curves, degrees up to %d in x, %d in y\n", curves.size(), max_x, max_y);
  }
  if (options.keep_cgal || !quadratic_applies(curves, options.quadratic_max_coefficient_bits)) return std::nullopt;
  try {
    QuadraticBuilder builder(box, options);
    Arrangement result = builder.run(curves, validity, windows);
    return result;
  } catch (const NotApplicable& e) {
    if (debug) std::fprintf(stderr, "  quadratic traits not applicable: %s\n", e.why);
    return std::nullopt;
  } catch (const CGAL::Failure_exception& e) {
    throw GeometryError(std::string("CGAL rejected a contact curve arrangement (quadratic traits): ") + e.what());
  }
}

}  // namespace hipair::cspace::raw
