// The circle–segment CGAL stage of the C-space builder (see circle_segment_traits.hpp): the
// only translation unit that includes Arr_circle_segment_traits_2.
#include "arrangement/circle_segment_traits.hpp"
#include "core/exact_sqrt.hpp"

#include <hipair/error.hpp>

#include "algebra/exact_real.hpp"
#include "algebra/near_quotient.hpp"
#include "algebra/small_integers.hpp"

#include <CGAL/Arr_circle_segment_traits_2.h>
#include <CGAL/Arr_curve_data_traits_2.h>
#include <CGAL/Arr_extended_dcel.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>
#include <unordered_map>

namespace hipair::cspace::raw {
namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using BaseTraits = CGAL::Arr_circle_segment_traits_2<Kernel>;
// Every piece carries the index of its input curve (chart sides: no_curve); where pieces
// overlap, the smaller index is kept (a contact curve rather than a chart side). The export
// takes a line edge's support from that curve instead of converting CGAL's lazy line.
constexpr std::size_t no_curve = static_cast<std::size_t>(-1);
struct SmallerIndex {
  std::size_t operator()(std::size_t a, std::size_t b) const { return std::min(a, b); }
};
using NT = BaseTraits::NT;
using CoordNT = BaseTraits::CoordNT;
using ET = std::remove_cv_t<std::remove_reference_t<decltype(CGAL::exact(std::declval<NT>()))>>;
using Clock = std::chrono::steady_clock;
using algebra::Real;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// (templates, so that only the branch of the kernel's exact type is instantiated)
template <class E>
E exact_of(const Rational& q) {
  if constexpr (std::is_same_v<E, CGAL::Gmpq>)
    return E(q.get_mpq_t());
  else
    return E(q);
}

template <class E>
Rational rational_of(const E& e) {
  if constexpr (std::is_same_v<E, CGAL::Gmpq>)
    return Rational(e.mpq());
  else
    return Rational(e);
}

// A kernel number whose interval is given (it is CGAL's own: kernel_interval) with its exact
// value: CGAL's Lazy_exact_Ex_Cst, without its MPFR conversion of the exact value.
struct KnownIntervalConstant final : CGAL::Lazy_exact_nt_rep<ET> {
  KnownIntervalConstant(const CGAL::Interval_nt<false>& interval, ET&& exact)
      : CGAL::Lazy_exact_nt_rep<ET>(interval, std::move(exact)) {}
  void update_exact() const override {}
};

// Indices by key, in one array (open addressing, linear probing; entries may share a key):
// the segment stage's known points by handle and by value, without a node per point.
class IndexTable {
 public:
  void reserve(std::size_t entries) {
    std::size_t slots = 16;
    while (slots < 2 * entries) slots *= 2;
    if (slots > slots_.size()) rehash(slots);
  }
  void insert(std::size_t key, std::size_t value) {
    if (2 * (size_ + 1) > slots_.size()) rehash(std::max<std::size_t>(16, 2 * slots_.size()));
    place(key, value);
    ++size_;
  }
  // Calls visit(value) for the entries of `key` (in probe order) until it returns true; true
  // when it did.
  template <class Visit>
  bool find(std::size_t key, Visit visit) const {
    if (slots_.empty()) return false;
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = mix(key) & mask; slots_[i].value != none; i = (i + 1) & mask)
      if (slots_[i].key == key && visit(slots_[i].value)) return true;
    return false;
  }

 private:
  struct Slot {
    std::size_t key = 0;
    std::size_t value = none;   // none: empty
  };
  static std::size_t mix(std::size_t key) {
    key ^= key >> 33;
    key *= 0xff51afd7ed558ccdULL;
    return key ^ (key >> 33);
  }
  void place(std::size_t key, std::size_t value) {
    const std::size_t mask = slots_.size() - 1;
    std::size_t i = mix(key) & mask;
    while (slots_[i].value != none) i = (i + 1) & mask;
    slots_[i] = Slot{key, value};
  }
  void rehash(std::size_t slots) {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(slots, Slot{});
    for (const Slot& slot : old)
      if (slot.value != none) place(slot.key, slot.value);
  }
  std::vector<Slot> slots_;
  std::size_t size_ = 0;
};

// A kernel number whose interval is given (CGAL's own, as KnownIntervalConstant's) and whose
// exact value is made from a known point's rational (`points`[index], its x or y) only when the
// kernel asks for it (a filter failure, an intersection point's exact coordinates): most input
// points of a sweep never need it. The rational is read through the list (which may grow) and
// must stay there, unchanged, while the kernel can ask.
template <class Points>
struct DeferredKnownConstant final : CGAL::Lazy_exact_nt_rep<ET> {
  DeferredKnownConstant(const CGAL::Interval_nt<false>& interval, const Points* points, std::size_t index, bool y)
      : CGAL::Lazy_exact_nt_rep<ET>(interval), points_(points), index_(index), y_(y) {}
  void update_exact() const override {
    const auto& known = (*points_)[index_];
    auto* exact = new typename CGAL::Lazy_exact_nt_rep<ET>::Indirect(exact_of<ET>(y_ ? known.y : known.x));
    this->keep_at(exact);
    this->set_ptr(exact);
  }

 private:
  const Points* points_;
  std::size_t index_;
  bool y_;
};

NT to_nt(const Rational& q) {
  double lower, upper;   // CGAL's interval of q: the doubles around it (algebra/near_quotient.hpp)
  if (algebra::enclose_rational(q, lower, upper))
    return NT(new KnownIntervalConstant(CGAL::Interval_nt<false>(lower, upper), exact_of<ET>(q)));
  return NT(exact_of<ET>(q));
}
Rational to_rational(const NT& value) { return rational_of<ET>(CGAL::exact(value)); }

// The two flavours of the stage. Circles: the circle–segment traits on Epeck (one-root
// coordinates). Segments (every curve a line; see segments_apply): the segment traits on Epeck
// (rational points, the kernel's filtered predicates directly: no one-root numbers). Measured
// (docs/performance.md, session 12): CGAL's insertion 18 % -> 10 % of a 64/65-gon build;
// Filtered_kernel<Simple_cartesian<mpq_class>> instead of Epeck was 13 % (its filter converts
// every mpq through MPFR).
struct CircleFlavour {
  using K = Kernel;
  using BaseTraits = CGAL::Arr_circle_segment_traits_2<K>;
  static constexpr bool segments = false;
};
struct SegmentFlavour {
  using K = Kernel;
  using BaseTraits = CGAL::Arr_segment_traits_2<K>;
  static constexpr bool segments = true;
};

// A kernel number from a rational, and back (the segment kernel's numbers are rationals).
template <class FT>
FT ft_of(const Rational& q) {
  if constexpr (std::is_same_v<FT, Rational>)
    return q;
  else if constexpr (std::is_same_v<FT, NT>)
    return to_nt(q);
  else
    return FT(exact_of<ET>(q));
}
template <class FT>
Rational rational_from(const FT& value) {
  if constexpr (std::is_same_v<FT, Rational>)
    return value;
  else
    return rational_of<ET>(CGAL::exact(value));
}

const mpz_class& coefficient(const IntegerPolynomial2& f, std::size_t i, std::size_t j) {
  static const mpz_class zero = 0;
  if (i >= f.coefficients.size() || j >= f.coefficients[i].size()) return zero;
  return f.coefficients[i][j];
}

int total_degree(const IntegerPolynomial2& f) {
  int degree = -1;
  for (std::size_t i = 0; i < f.coefficients.size(); ++i)
    for (std::size_t j = 0; j < f.coefficients[i].size(); ++j)
      if (sgn(f.coefficients[i][j]) != 0) degree = std::max(degree, static_cast<int>(i + j));
  return degree;
}

// k0 + kx x + ky y + q (x^2 + y^2), exact: a validity atom (q = 0 but for the circles of
// arc–arc contacts, e.g. |D|^2 >= r1^2 + r2^2), or a line (q = 0).
struct Linear {
  Rational k0, kx, ky;
  Rational q = 0;
};

// A polynomial of total degree <= 1, or of the form q (x^2 + y^2) + linear.
bool atom_form(const IntegerPolynomial2& f) {
  int degree = total_degree(f);
  if (degree <= 1) return true;
  return degree == 2 && coefficient(f, 2, 0) == coefficient(f, 0, 2) && sgn(coefficient(f, 1, 1)) == 0;
}

Linear linear_of(const IntegerPolynomial2& f) {
  return Linear{Rational(coefficient(f, 0, 0)), Rational(coefficient(f, 1, 0)), Rational(coefficient(f, 0, 1)),
                Rational(coefficient(f, 2, 0))};
}

// The circle x^2 + y^2 + d x + e y + g = 0 (scaled): centre and squared radius.
struct Circle {
  Rational cx, cy, r2;
};

std::optional<Circle> circle_of(const IntegerPolynomial2& f) {
  if (total_degree(f) != 2) return std::nullopt;
  const mpz_class& a = coefficient(f, 2, 0);
  if (sgn(a) == 0 || coefficient(f, 0, 2) != a || sgn(coefficient(f, 1, 1)) != 0) return std::nullopt;
  Rational d(coefficient(f, 1, 0), a), e(coefficient(f, 0, 1), a), g(coefficient(f, 0, 0), a);
  d.canonicalize();
  e.canonicalize();
  g.canonicalize();
  Circle c{-d / 2, -e / 2, 0};
  c.r2 = c.cx * c.cx + c.cy * c.cy - g;
  return c;
}

// a0 + a1 sqrt(root), root >= 0, exactly.
struct OneRoot {
  Rational a0, a1, root;
  static OneRoot of(Rational a0, Rational a1, Rational root) {
    if (sgn(a1) == 0 || sgn(root) == 0) return OneRoot{std::move(a0), 0, 0};
    if (auto s = rational_sqrt(root)) return OneRoot{a0 + a1 * *s, 0, 0};
    return OneRoot{std::move(a0), std::move(a1), std::move(root)};
  }
  bool rational() const { return sgn(a1) == 0; }
  CoordNT coord() const {
    if (rational()) return CoordNT(to_nt(a0));
    return CoordNT(to_nt(a0), to_nt(a1), to_nt(root));
  }
};

// Sign of alpha + beta sqrt(s), s >= 0.
int sign_of(const Rational& alpha, const Rational& beta, const Rational& s) {
  int sa = sgn(alpha), sb = sgn(s) == 0 ? 0 : sgn(beta);
  if (sb == 0) return sa;
  if (sa == 0 || sa == sb) return sb;
  int c = cmp(alpha * alpha, beta * beta * s);
  return c > 0 ? sa : c < 0 ? sb : 0;
}

// The exact real a0 + a1 sqrt(root) as an algebra::Real (its minimal polynomial and an
// isolating interval about 2^-62 relatively wide).
Real to_real(const CoordNT& value) {
  Rational a0 = to_rational(value.a0());
  if (!value.is_extended()) return Real::from_rational(a0);
  Rational a1 = to_rational(value.a1()), root = to_rational(value.root());
  if (sgn(a1) == 0 || sgn(root) == 0) return Real::from_rational(a0);
  if (auto s = rational_sqrt(root)) return Real::from_rational(a0 + a1 * *s);
  if (sgn(root) < 0) throw NumericError("internal: a circle–segment coordinate with a negative radicand");
  // sqrt(root) = sqrt(num * den) / den, bracketed by floor(sqrt(num * den * 4^k)) / (den 2^k)
  mpz_class m = root.get_num() * root.get_den();
  long bits = static_cast<long>(mpz_sizeinbase(m.get_mpz_t(), 2));
  unsigned long k = bits >= 126 ? 1 : static_cast<unsigned long>((126 - bits) / 2 + 1);
  mpz_class scaled = m << (2 * k), s;
  mpz_sqrt(s.get_mpz_t(), scaled.get_mpz_t());
  mpz_class denominator = root.get_den() << k;
  Rational s_lo(s, denominator), s_hi(s + 1, denominator);
  s_lo.canonicalize();
  s_hi.canonicalize();
  Real r;
  r.polynomial = algebra::from_rationals({a0 * a0 - a1 * a1 * root, -2 * a0, Rational(1)});
  Rational u = a0 + a1 * s_lo, v = a0 + a1 * s_hi;
  r.lower = sgn(a1) > 0 ? u : v;
  r.upper = sgn(a1) > 0 ? v : u;
  r.exact = false;
  return r;
}

// exact_real(value) written into r (its rationals' and polynomial's storage reused); false
// (r untouched) when value is not canonical, which the caller then converts
bool assign_canonical_real(Real& r, const Rational& value) {
  const mpz_class& num = value.get_num();
  const mpz_class& den = value.get_den();
  bool canonical = sgn(den) > 0;
  if (canonical && mpz_cmp_ui(den.get_mpz_t(), 1) != 0) {
    thread_local mpz_class g;
    mpz_gcd(g.get_mpz_t(), num.get_mpz_t(), den.get_mpz_t());
    canonical = mpz_cmp_ui(g.get_mpz_t(), 1) == 0;
  }
  if (!canonical) return false;
  r.polynomial.resize(2);
  mpz_neg(r.polynomial[0].get_mpz_t(), num.get_mpz_t());
  r.polynomial[1] = den;
  r.upper = value;
  r.exact = true;
  return true;
}

// exact_real(value) written into r (its rationals' and polynomial's storage reused)
void assign_exact_real(Real& r, const Rational& value) {
  if (assign_canonical_real(r, value))
    r.lower = value;
  else
    r = Real::from_rational(value);
}

// The same, taking value's integers for r.lower (a rational read once: no copy of it)
void assign_exact_real(Real& r, Rational&& value) {
  if (assign_canonical_real(r, value))
    r.lower = std::move(value);   // gmpxx's move assignment swaps
  else
    r = Real::from_rational(value);
}

// The rest of a vertex's y from its number out.y: the minimal polynomial of y, in y alone, and
// y's index among its real roots.
void fill_y_from_number(Vertex& out) {
  out.y_exact = true;
  out.y_lower = out.y.lower;
  out.y_upper = out.y.upper;
  out.y_curve.coefficients.assign(1, out.y.polynomial);   // x^0 y^j
  out.y_branch = 0;
}

void fill_y(Real y, Vertex& out) {
  out.y = std::move(y);
  fill_y_from_number(out);
}

void fill_y(const CoordNT& value, Vertex& out) {
  fill_y(to_real(value), out);
  if (!out.y.exact && algebra::degree(out.y.polynomial) == 2)
    out.y_branch = sgn(to_rational(value.a1())) > 0 ? 1 : 0;   // a0 + |a1| sqrt(c) is the larger root
}

IntegerPolynomial2 integer_polynomial(const std::vector<std::vector<Rational>>& c) {
  mpz_class lcm = 1;
  for (const auto& row : c)
    for (const auto& q : row) mpz_lcm(lcm.get_mpz_t(), lcm.get_mpz_t(), q.get_den_mpz_t());
  IntegerPolynomial2 f;
  mpz_class g = 0;
  for (const auto& row : c) {
    f.coefficients.emplace_back();
    for (const auto& q : row) {
      mpz_class z = q.get_num() * (lcm / q.get_den());
      mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), z.get_mpz_t());
      f.coefficients.back().push_back(std::move(z));
    }
  }
  if (sgn(g) > 0)
    for (auto& row : f.coefficients)
      for (auto& z : row) z /= g;
  return f;
}

template <class Line>
IntegerPolynomial2 line_support(const Line& line) {
  return integer_polynomial(
      {{rational_from(line.c()), rational_from(line.b())}, {rational_from(line.a()), Rational(0)}});
}

template <bool Segments, class XCurve>
IntegerPolynomial2 support_of(const XCurve& arc) {
  if constexpr (Segments) {
    return line_support(arc.line());
  } else {
    if (arc.is_linear()) return line_support(arc.supporting_line());
  const auto& circle = arc.supporting_circle();
  Rational cx = to_rational(circle.center().x()), cy = to_rational(circle.center().y());
  Rational r2 = to_rational(circle.squared_radius());
  return integer_polynomial({{cx * cx + cy * cy - r2, -2 * cy, Rational(1)}, {-2 * cx, Rational(0)}, {Rational(1)}});
  }
}

// ---------------------------------------------------------------- sets of parameter values

struct Span {
  std::optional<Rational> lo, hi;   // closed; nullopt: infinite
};
using Set = std::vector<Span>;

Set everything() { return {Span{}}; }

// {t : p + q t >= 0}
Set half(const Rational& p, const Rational& q) {
  if (sgn(q) == 0) return sgn(p) >= 0 ? everything() : Set{};
  Rational t = -p / q;
  if (sgn(q) > 0) return {Span{t, std::nullopt}};
  return {Span{std::nullopt, t}};
}

// As lower bounds (nullopt: -infinity): a < b.
bool lo_before(const std::optional<Rational>& a, const std::optional<Rational>& b) {
  if (!a) return static_cast<bool>(b);
  if (!b) return false;
  return *a < *b;
}
// As upper bounds (nullopt: +infinity): a < b.
bool hi_before(const std::optional<Rational>& a, const std::optional<Rational>& b) {
  if (!a) return false;
  if (!b) return true;
  return *a < *b;
}

Set intersect(const Set& a, const Set& b) {
  Set out;
  for (const auto& x : a)
    for (const auto& y : b) {
      Span s;
      s.lo = lo_before(x.lo, y.lo) ? y.lo : x.lo;
      s.hi = hi_before(x.hi, y.hi) ? x.hi : y.hi;
      if (s.lo && s.hi && *s.hi < *s.lo) continue;
      out.push_back(std::move(s));
    }
  std::sort(out.begin(), out.end(), [](const Span& p, const Span& q) { return lo_before(p.lo, q.lo); });
  return out;
}

Set unite(Set a, const Set& b) {
  a.insert(a.end(), b.begin(), b.end());
  std::sort(a.begin(), a.end(), [](const Span& p, const Span& q) { return lo_before(p.lo, q.lo); });
  Set out;
  for (auto& s : a) {
    bool separate = out.empty() || (s.lo && out.back().hi && *s.lo > *out.back().hi);
    if (!separate) {
      if (hi_before(out.back().hi, s.hi)) out.back().hi = s.hi;
      continue;
    }
    out.push_back(std::move(s));
  }
  return out;
}

// ---------------------------------------------------------------- the builder

template <class Flavour>
class Builder {
  using K = typename Flavour::K;
  using FT = typename K::FT;
  using Traits = CGAL::Arr_curve_data_traits_2<typename Flavour::BaseTraits, std::size_t, SmallerIndex>;
  using Point = typename Traits::Point_2;
  using BaseCurve = typename Flavour::BaseTraits::Curve_2;
  using Curve = typename Traits::Curve_2;
  using XCurve = typename Traits::X_monotone_curve_2;
  // Each vertex, halfedge and face carries its index in the export (set by export_topology:
  // halfedges 2 edge + 1 when they run from the edge's smaller to its larger end), instead of
  // hash maps from CGAL's addresses.
  using Dcel = CGAL::Arr_extended_dcel<Traits, std::size_t, std::size_t, std::size_t>;
  using Arrangement_2 = CGAL::Arrangement_2<Traits, Dcel>;
  static constexpr bool segments = Flavour::segments;

 public:
  Builder(const Box& box, const Options& options) : box_(box), options_(options) {}

  Arrangement run(const std::vector<IntegerPolynomial2>& curves, const std::vector<std::vector<ValidityClause>>& validity,
                  const std::vector<std::vector<std::pair<Rational, Rational>>>& windows) {
    auto start = Clock::now();
    if constexpr (segments) {
      // room for the corners and two ends per curve (one piece each, the usual case), so that
      // the known points are not copied as the vector grows (a KnownPoint's rationals copy)
      known_points_.reserve(4 + 2 * curves.size());
      known_.reserve(4 + 2 * curves.size());
      by_value_.reserve(4 + 2 * curves.size());
      pieces_.reserve(4 + curves.size());
    }
    // the chart box
    typename K::Point_2 corners[4] = {point(box_.x_lo, box_.y_lo), point(box_.x_hi, box_.y_lo), point(box_.x_hi, box_.y_hi),
                                  point(box_.x_lo, box_.y_hi)};
    for (int i = 0; i < 4; ++i) pieces_.emplace_back(BaseCurve(corners[i], corners[(i + 1) % 4]), no_curve);
    static const std::vector<ValidityClause> no_clauses;
    static const std::vector<std::pair<Rational, Rational>> no_windows;
    for (std::size_t k = 0; k < curves.size(); ++k) {
      const auto& clauses = k < validity.size() ? validity[k] : no_clauses;
      const auto& curve_windows = k < windows.size() ? windows[k] : no_windows;
      int degree = total_degree(curves[k]);
      if (degree <= 0) continue;   // no points (or identically zero: bounds nothing)
      current_ = k;
      if (degree == 1) {
        line_supports_.resize(curves.size());
        line_supports_[k] = oriented_line(curves[k]);
        // (the segment flavour only: the circle flavour keeps clip_line, the reference the
        // tests compare it with)
        if (!segments || !clip_line_in_integers(curves[k], clauses, curve_windows))
          clip_line(linear_of(curves[k]), clauses, curve_windows);
      } else if constexpr (!segments) {
        if (auto circle = circle_of(curves[k]))
          clip_circle(*circle, clauses, curve_windows);
        else
          throw GeometryError("internal: a contact curve is neither a line nor a circle");
      } else
        throw GeometryError("internal: a contact curve is neither a line nor a circle");
    }
    result_.times.curves_seconds = seconds_since(start);
    result_.pieces_inserted = pieces_.size() - 4;
    if constexpr (segments) split_overlaps();

    start = Clock::now();
    Arrangement_2 arrangement;
    CGAL::insert(arrangement, pieces_.begin(), pieces_.end());
    for (const auto& p : isolated_) CGAL::insert_point(arrangement, p);
    result_.times.insertion_seconds = seconds_since(start);

    start = Clock::now();
    export_topology(arrangement);
    result_.times.export_seconds = seconds_since(start);
    return std::move(result_);
  }

 private:
  // A kernel point from rationals. The segment flavour remembers the rationals of every point
  // it makes (by the handle's identity; the handle is kept, so that its address is not reused):
  // an arrangement vertex at an input piece's end shares that handle, and the export takes its
  // coordinates from here instead of forcing the lazy point's exact value (only intersection
  // points are converted).
  // The segment flavour also makes each point once: pieces that share an end (consecutive
  // segments of a convolution, a chart corner) get the same handle, so that the kernel converts
  // the point and computes its exact value once (CGAL's sweep compares equal ends exactly).
  // The same coordinates, hence the same arrangement.
  // (X, Y: Rational, const or not: a new point's rationals are moved into its KnownPoint when
  // the caller passes temporaries — gmpxx's move construction allocates one limb for the
  // source's new denominator, a copy two, one per integer — and copied otherwise)
  template <class X, class Y>
  typename K::Point_2 point(X&& x, Y&& y) {
    static_assert(std::is_same_v<std::remove_cvref_t<X>, Rational> && std::is_same_v<std::remove_cvref_t<Y>, Rational>);
    if constexpr (segments) {
      const std::size_t h = point_hash(x, y);
      std::size_t found = none;
      if (by_value_.find(h, [&](std::size_t i) {
            const KnownPoint& k = known_points_[i];
            if (k.x != x || k.y != y) return false;
            found = i;
            return true;
          }))
        return known_points_[found].handle;
      // (its coordinates' exact values are made from the rationals kept here, when asked)
      const std::size_t index = known_points_.size();
      typename K::Point_2 p(known_ft(x, index, false), known_ft(y, index, true));
      known_points_.emplace_back(p, std::forward<X>(x), std::forward<Y>(y));   // (built in place)
      known_.insert(p.id(), index);
      by_value_.insert(h, index);
      return p;
    } else {
      return typename K::Point_2(ft_of<FT>(x), ft_of<FT>(y));
    }
  }

  // Segment flavour, before the sweep: where pieces of two or more input curves with one line
  // (the same oriented primitive polynomial, line_supports_) overlap, those pieces are replaced
  // by the pieces between their consecutive distinct ends that some of them cover, each carrying
  // the smallest index of the pieces covering it: what CGAL's sweep makes of the overlapping
  // pieces (it splits them at every end and merges an overlap's data with SmallerIndex), without
  // its overlap construction (_create_overlapping_curve, the lazy intersections). The ends are
  // the known points' handles (every segment end is one): no new point. Chart sides are left to
  // the sweep. The same arrangement: the same vertices, edges, data and faces, made by the sweep
  // in the same geometric order. (`pieces_inserted` counts the clipped pieces, as before.)
  void split_overlaps() {
    const std::size_t n = pieces_.size();
    if (n < 6 || line_supports_.empty()) return;
    // the line curves with pieces, by a hash of their oriented support
    auto support_hash = [](const IntegerPolynomial2& f) {
      std::size_t h = 0;
      for (const auto& row : f.coefficients)
        for (const mpz_class& z : row) {
          const std::size_t limb = static_cast<std::size_t>(mpz_getlimbn(z.get_mpz_t(), 0)) ^
                                   (static_cast<std::size_t>(mpz_size(z.get_mpz_t())) << 48);
          h ^= (sgn(z) < 0 ? ~limb : limb) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
        }
      return h;
    };
    thread_local std::vector<std::pair<std::size_t, std::size_t>> keyed;   // (hash, curve)
    keyed.clear();
    std::size_t previous = no_curve;
    for (std::size_t i = 4; i < n; ++i) {
      const std::size_t k = pieces_[i].data();
      if (k == previous || k >= line_supports_.size() || line_supports_[k].coefficients.empty()) continue;
      previous = k;   // (a curve's pieces are consecutive)
      keyed.emplace_back(support_hash(line_supports_[k]), k);
    }
    if (keyed.size() < 2) return;
    std::sort(keyed.begin(), keyed.end());
    bool shared = false;
    for (std::size_t j = 1; j < keyed.size() && !shared; ++j)
      shared = keyed[j].first == keyed[j - 1].first && keyed[j].second != keyed[j - 1].second;
    if (!shared) return;   // every line carries one curve: nothing can overlap
    // line group of each curve: the first curve of its run with an equal support
    std::vector<std::size_t> group(line_supports_.size(), no_curve);
    for (std::size_t j = 0; j < keyed.size();) {
      std::size_t end = j + 1;
      while (end < keyed.size() && keyed[end].first == keyed[j].first) ++end;
      for (std::size_t a = j; a < end; ++a) {
        const std::size_t ka = keyed[a].second;
        if (group[ka] != no_curve) continue;
        group[ka] = ka;
        for (std::size_t b = a + 1; b < end; ++b) {
          const std::size_t kb = keyed[b].second;
          if (group[kb] == no_curve && line_supports_[kb].coefficients == line_supports_[ka].coefficients) group[kb] = ka;
        }
      }
      j = end;
    }
    struct Span {
      std::size_t group;    // the line: its first curve
      std::size_t lo, hi;   // known points, lo before hi along the line
      std::size_t data;
      std::size_t piece;
    };
    thread_local std::vector<Span> spans;
    spans.clear();
    auto known_index = [&](const Point& p) {
      std::size_t found = none;
      known_.find(p.id(), [&](std::size_t i) {
        found = i;
        return true;
      });
      return found;
    };
    // along a line: x, or y for a vertical line (oriented_line: y coefficient 0)
    auto before = [&](std::size_t a, std::size_t b, bool vertical) {
      return vertical ? known_points_[a].y < known_points_[b].y : known_points_[a].x < known_points_[b].x;
    };
    auto vertical_line = [&](std::size_t k) { return sgn(coefficient(line_supports_[k], 0, 1)) == 0; };
    for (std::size_t i = 4; i < n; ++i) {
      const std::size_t k = pieces_[i].data();
      if (k >= group.size() || group[k] == no_curve) continue;
      std::size_t a = known_index(pieces_[i].source()), b = known_index(pieces_[i].target());
      if (a == none || b == none) return;   // (every end is a known point; else the sweep decides)
      if (before(b, a, vertical_line(k))) std::swap(a, b);
      spans.push_back(Span{group[k], a, b, k, i});
    }
    // by line, then along it (then by piece: a strict order)
    std::sort(spans.begin(), spans.end(), [&](const Span& u, const Span& w) {
      if (u.group != w.group) return u.group < w.group;
      if (u.lo != w.lo) return before(u.lo, w.lo, vertical_line(u.group));
      return u.piece < w.piece;
    });
    std::vector<char> replaced;
    std::vector<Curve> added;
    thread_local std::vector<std::size_t> ends;
    for (std::size_t first = 0; first < spans.size();) {
      std::size_t last = first + 1;
      while (last < spans.size() && spans[last].group == spans[first].group) ++last;
      const bool vertical = vertical_line(spans[first].group);
      // an overlap: a span starting before the furthest end so far
      bool overlap = false;
      std::size_t reach = spans[first].hi;
      for (std::size_t j = first + 1; j < last; ++j) {
        if (before(spans[j].lo, reach, vertical)) overlap = true;
        if (before(reach, spans[j].hi, vertical)) reach = spans[j].hi;
      }
      if (overlap) {
        ends.clear();
        for (std::size_t j = first; j < last; ++j) {
          ends.push_back(spans[j].lo);
          ends.push_back(spans[j].hi);
        }
        // (equal points are one known point: by_value_)
        std::sort(ends.begin(), ends.end(), [&](std::size_t a, std::size_t b) { return a != b && before(a, b, vertical); });
        ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
        // each span's ends as positions in `ends` (integers compared from here on)
        auto position = [&](std::size_t point) {
          return static_cast<std::size_t>(std::find(ends.begin(), ends.end(), point) - ends.begin());
        };
        for (std::size_t j = first; j < last; ++j) {
          spans[j].lo = position(spans[j].lo);
          spans[j].hi = position(spans[j].hi);
        }
        for (std::size_t e = 0; e + 1 < ends.size(); ++e) {
          std::size_t data = no_curve;
          for (std::size_t j = first; j < last; ++j)
            if (spans[j].lo <= e && spans[j].hi >= e + 1) data = std::min(data, spans[j].data);
          if (data != no_curve)
            added.emplace_back(BaseCurve(known_points_[ends[e]].handle, known_points_[ends[e + 1]].handle), data);
        }
        if (replaced.empty()) replaced.assign(n, 0);
        for (std::size_t j = first; j < last; ++j) replaced[spans[j].piece] = 1;
      }
      first = last;
    }
    if (added.empty()) return;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (!replaced[i]) {
        if (kept != i) pieces_[kept] = std::move(pieces_[i]);
        ++kept;
      }
    pieces_.resize(kept);
    for (Curve& c : added) pieces_.push_back(std::move(c));
  }

  // The kernel number of coordinate x or y (`y`) of the known point `index` (q): its exact value
  // deferred (DeferredKnownConstant), or made now when q has no interval from
  // enclose_rational (to_nt's fallback).
  FT known_ft(const Rational& q, std::size_t index, bool y) const {
    double lower, upper;
    if (algebra::enclose_rational(q, lower, upper))
      return FT(new DeferredKnownConstant<std::vector<KnownPoint>>(CGAL::Interval_nt<false>(lower, upper), &known_points_,
                                                                   index, y));
    return ft_of<FT>(q);
  }

  // A hash of two canonical rationals (their lowest limbs and signed sizes).
  static std::size_t point_hash(const Rational& x, const Rational& y) {
    std::size_t h = 0;
    for (const mpz_srcptr z : {x.get_num_mpz_t(), x.get_den_mpz_t(), y.get_num_mpz_t(), y.get_den_mpz_t()}) {
      const std::size_t limb = static_cast<std::size_t>(mpz_getlimbn(z, 0)) ^ (static_cast<std::size_t>(mpz_size(z)) << 48);
      h ^= (mpz_sgn(z) < 0 ? ~limb : limb) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    }
    return h;
  }

  // Clauses hold at a point where each atom's value is given by `value` (a sign).
  template <class SignOf>
  static bool clauses_hold(const std::vector<ValidityClause>& clauses, SignOf sign_of_atom) {
    for (const auto& clause : clauses) {
      bool holds = false;
      for (const auto& atom : clause.atoms)
        if (sign_of_atom(linear_of(atom)) >= 0) {
          holds = true;
          break;
        }
      if (!holds) return false;
    }
    return true;
  }

  static bool in_windows(const Rational& x, const std::vector<std::pair<Rational, Rational>>& windows) {
    if (windows.empty()) return true;
    for (const auto& [lo, hi] : windows)
      if (lo <= x && x <= hi) return true;
    return false;
  }

  // clip_line's one-interval case for a non-vertical line without windows whose every clause
  // is one linear atom (every contact segment of a polygon pair), in integers: each constraint
  // (a box side m x - n >= 0 for x_lo = n / m, ..., or an atom g0 + gx x + gy y >= 0) along the
  // line y = -(k0 + kx x) / ky, times ky, is P + Q x with P = g0 ky - gy k0, Q = gx ky - gy kx;
  // it holds where sgn(ky) (P + Q x) >= 0, a lower bound -P / Q of x when sgn(ky) Q > 0, an
  // upper one when < 0. The bounds are compared as unreduced fractions (cross products) and
  // only the two kept are canonicalised: the same ends, hence the same piece, as clip_line.
  // A vertical line (ky = 0, kx != 0) is the same with x and y exchanged: the parameter is y,
  // x = -k0 / kx throughout (clip_line's vertical case: x0 outside [x_lo, x_hi] makes the x
  // sides' constraints, constant along the line, fail; the y bounds are its parameter's).
  // False (nothing done) when the line is not of that kind (or a vertical line has windows).
  bool clip_line_in_integers(const IntegerPolynomial2& f, const std::vector<ValidityClause>& clauses,
                             const std::vector<std::pair<Rational, Rational>>& windows) {
    const bool vertical = sgn(coefficient(f, 0, 1)) == 0;
    // the line in the exchanged coordinates when vertical: kx the parameter's coefficient, ky
    // the solved variable's
    const mpz_class &k0 = coefficient(f, 0, 0), &kx = coefficient(f, vertical ? 0 : 1, vertical ? 1 : 0),
                    &ky = coefficient(f, vertical ? 1 : 0, vertical ? 0 : 1);
    if (sgn(ky) == 0 || !windows.empty()) return false;
    for (const auto& clause : clauses)
      if (clause.atoms.size() != 1 || total_degree(clause.atoms[0]) > 1) return false;
    const int sy = sgn(ky);
    // the bounds so far as fractions num / den, den > 0
    bool has_lo = false, has_hi = false, empty = false;
    // per-thread integers that keep their storage from call to call (each is written before it
    // is read in a call; the function does not re-enter itself)
    struct Scratch {
      mpz_class lo_num, lo_den, hi_num, hi_den, P, Q, t1, t2, minus_x_lo_num, minus_y_lo_num, minus_x_hi_den,
          minus_y_hi_den;
    };
    thread_local Scratch scratch;
    auto& [lo_num, lo_den, hi_num, hi_den, P, Q, t1, t2, minus_x_lo_num, minus_y_lo_num, minus_x_hi_den,
           minus_y_hi_den] = scratch;
    auto bound_exchanged = [&](const mpz_class& g0, const mpz_class& gx, const mpz_class& gy) {
      mpz_mul(P.get_mpz_t(), g0.get_mpz_t(), ky.get_mpz_t());
      mpz_submul(P.get_mpz_t(), gy.get_mpz_t(), k0.get_mpz_t());   // g0 ky - gy k0
      mpz_mul(Q.get_mpz_t(), gx.get_mpz_t(), ky.get_mpz_t());
      mpz_submul(Q.get_mpz_t(), gy.get_mpz_t(), kx.get_mpz_t());   // gx ky - gy kx
      if (sy < 0) {
        mpz_neg(P.get_mpz_t(), P.get_mpz_t());
        mpz_neg(Q.get_mpz_t(), Q.get_mpz_t());
      }
      // P + Q x >= 0
      const int sq = sgn(Q);
      if (sq == 0) {
        if (sgn(P) < 0) empty = true;
        return;
      }
      // x = -P / Q as num / den with den > 0
      if (sq > 0) {
        mpz_neg(P.get_mpz_t(), P.get_mpz_t());
      } else {
        mpz_neg(Q.get_mpz_t(), Q.get_mpz_t());
      }
      if (sq > 0) {   // x >= P / Q
        if (has_lo) {
          mpz_mul(t1.get_mpz_t(), P.get_mpz_t(), lo_den.get_mpz_t());
          mpz_mul(t2.get_mpz_t(), lo_num.get_mpz_t(), Q.get_mpz_t());
          if (!(t2 < t1)) return;
        }
        has_lo = true;
        mpz_swap(lo_num.get_mpz_t(), P.get_mpz_t());
        mpz_swap(lo_den.get_mpz_t(), Q.get_mpz_t());
      } else {        // x <= P / Q
        if (has_hi) {
          mpz_mul(t1.get_mpz_t(), P.get_mpz_t(), hi_den.get_mpz_t());
          mpz_mul(t2.get_mpz_t(), hi_num.get_mpz_t(), Q.get_mpz_t());
          if (!(t1 < t2)) return;
        }
        has_hi = true;
        mpz_swap(hi_num.get_mpz_t(), P.get_mpz_t());
        mpz_swap(hi_den.get_mpz_t(), Q.get_mpz_t());
      }
    };
    // g0 + gx x + gy y >= 0 in the chart's coordinates
    auto bound = [&](const mpz_class& g0, const mpz_class& gx, const mpz_class& gy) {
      if (vertical)
        bound_exchanged(g0, gy, gx);
      else
        bound_exchanged(g0, gx, gy);
    };
    // The same bounds in machine integers (algebra/small_integers.hpp): the same integer
    // expressions, exact in __int128 with every operation checked for overflow; false (nothing
    // written) when an integer read is not below 2^62 or an expression overflows, and the
    // bounds are then computed in GMP's integers below.
    auto small_bounds = [&]() -> bool {
      namespace si = algebra::small_integers;
      si::Wide s_k0, s_kx, s_ky;
      if (!si::read(k0.get_mpz_t(), s_k0) || !si::read(kx.get_mpz_t(), s_kx) || !si::read(ky.get_mpz_t(), s_ky))
        return false;
      bool s_has_lo = false, s_has_hi = false, s_empty = false, fits = true;
      si::Wide s_lo_num = 0, s_lo_den = 1, s_hi_num = 0, s_hi_den = 1;
      auto exchanged = [&](si::Wide g0, si::Wide gx, si::Wide gy) {   // bound_exchanged's steps
        si::Wide p, q, t1, t2;
        if (!fits) return;
        if (!si::cross(g0, s_ky, gy, s_k0, p) || !si::cross(gx, s_ky, gy, s_kx, q) ||
            (sy < 0 && (!si::sub(0, p, p) || !si::sub(0, q, q)))) {
          fits = false;
          return;
        }
        const int sq = si::sign(q);
        if (sq == 0) {
          if (p < 0) s_empty = true;
          return;
        }
        if (!(sq > 0 ? si::sub(0, p, p) : si::sub(0, q, q))) {
          fits = false;
          return;
        }
        if (sq > 0) {   // x >= p / q
          if (s_has_lo) {
            if (!si::mul(p, s_lo_den, t1) || !si::mul(s_lo_num, q, t2)) {
              fits = false;
              return;
            }
            if (!(t2 < t1)) return;
          }
          s_has_lo = true;
          s_lo_num = p;
          s_lo_den = q;
        } else {        // x <= p / q
          if (s_has_hi) {
            if (!si::mul(p, s_hi_den, t1) || !si::mul(s_hi_num, q, t2)) {
              fits = false;
              return;
            }
            if (!(t1 < t2)) return;
          }
          s_has_hi = true;
          s_hi_num = p;
          s_hi_den = q;
        }
      };
      auto small_bound = [&](si::Wide g0, si::Wide gx, si::Wide gy) {
        if (vertical)
          exchanged(g0, gy, gx);
        else
          exchanged(g0, gx, gy);
      };
      si::Wide x_lo_num, x_lo_den, x_hi_num, x_hi_den, y_lo_num, y_lo_den, y_hi_num, y_hi_den;
      if (!si::read(box_.x_lo.get_num_mpz_t(), x_lo_num) || !si::read(box_.x_lo.get_den_mpz_t(), x_lo_den) ||
          !si::read(box_.x_hi.get_num_mpz_t(), x_hi_num) || !si::read(box_.x_hi.get_den_mpz_t(), x_hi_den) ||
          !si::read(box_.y_lo.get_num_mpz_t(), y_lo_num) || !si::read(box_.y_lo.get_den_mpz_t(), y_lo_den) ||
          !si::read(box_.y_hi.get_num_mpz_t(), y_hi_num) || !si::read(box_.y_hi.get_den_mpz_t(), y_hi_den))
        return false;
      small_bound(-x_lo_num, x_lo_den, 0);   // (below 2^62 in magnitude: negated exactly)
      small_bound(x_hi_num, -x_hi_den, 0);
      small_bound(-y_lo_num, 0, y_lo_den);
      small_bound(y_hi_num, 0, -y_hi_den);
      for (const auto& clause : clauses) {
        const IntegerPolynomial2& g = clause.atoms[0];
        si::Wide g0, gx, gy;
        if (!si::read(coefficient(g, 0, 0).get_mpz_t(), g0) || !si::read(coefficient(g, 1, 0).get_mpz_t(), gx) ||
            !si::read(coefficient(g, 0, 1).get_mpz_t(), gy))
          return false;
        small_bound(g0, gx, gy);
      }
      if (!fits) return false;
      has_lo = s_has_lo;
      has_hi = s_has_hi;
      empty = s_empty;
      if (has_lo) {
        si::write(lo_num.get_mpz_t(), s_lo_num);
        si::write(lo_den.get_mpz_t(), s_lo_den);
      }
      if (has_hi) {
        si::write(hi_num.get_mpz_t(), s_hi_num);
        si::write(hi_den.get_mpz_t(), s_hi_den);
      }
      return true;
    };
    if (!small_bounds()) {
      static const mpz_class zero(0);
      mpz_neg(minus_x_lo_num.get_mpz_t(), box_.x_lo.get_num_mpz_t());
      mpz_neg(minus_y_lo_num.get_mpz_t(), box_.y_lo.get_num_mpz_t());
      mpz_neg(minus_x_hi_den.get_mpz_t(), box_.x_hi.get_den_mpz_t());
      mpz_neg(minus_y_hi_den.get_mpz_t(), box_.y_hi.get_den_mpz_t());
      bound(minus_x_lo_num, box_.x_lo.get_den(), zero);   // x_lo.den x - x_lo.num >= 0
      bound(box_.x_hi.get_num(), minus_x_hi_den, zero);   // x_hi.num - x_hi.den x >= 0
      bound(minus_y_lo_num, zero, box_.y_lo.get_den());
      bound(box_.y_hi.get_num(), zero, minus_y_hi_den);
      for (const auto& clause : clauses) {
        const IntegerPolynomial2& g = clause.atoms[0];
        bound(coefficient(g, 0, 0), coefficient(g, 1, 0), coefficient(g, 0, 1));
      }
    }
    if (empty || !has_lo || !has_hi) {
      if (!empty && (!has_lo || !has_hi)) throw GeometryError("internal: a clipped contact segment is unbounded");
      return true;
    }
    mpz_mul(t1.get_mpz_t(), lo_num.get_mpz_t(), hi_den.get_mpz_t());
    mpz_mul(t2.get_mpz_t(), hi_num.get_mpz_t(), lo_den.get_mpz_t());
    if (!(t1 < t2)) return true;   // empty, or a single valid point: no segment (as clip_line)
    // (the scratch integers swapped in: one allocation per rational, its new denominator's
    // limb, which the scratch keeps; copying them in would make two)
    Rational lo, hi;
    mpz_swap(mpq_numref(lo.get_mpq_t()), lo_num.get_mpz_t());
    mpz_swap(mpq_denref(lo.get_mpq_t()), lo_den.get_mpz_t());
    mpz_swap(mpq_numref(hi.get_mpq_t()), hi_num.get_mpz_t());
    mpz_swap(mpq_denref(hi.get_mpq_t()), hi_den.get_mpz_t());
    lo.canonicalize();
    hi.canonicalize();
    auto y_at = [&](const Rational& x) {   // -(k0 + kx x) / ky, its integers written in place
      Rational y;
      const mpz_ptr num = mpq_numref(y.get_mpq_t()), den = mpq_denref(y.get_mpq_t());
      mpz_mul(num, kx.get_mpz_t(), x.get_num_mpz_t());
      mpz_addmul(num, k0.get_mpz_t(), x.get_den_mpz_t());
      mpz_neg(num, num);
      mpz_mul(den, ky.get_mpz_t(), x.get_den_mpz_t());
      y.canonicalize();
      return y;
    };
    Rational y_lo = y_at(lo), y_hi = y_at(hi);
    // (the four rationals are read here last: moved into the points' KnownPoint when new)
    if (vertical) {   // (x = y_lo = y_hi, the parameter's ends lo < hi in y)
      typename K::Point_2 first = point(std::move(y_lo), std::move(lo));
      pieces_.emplace_back(BaseCurve(first, point(std::move(y_hi), std::move(hi))), current_);
    } else {
      typename K::Point_2 first = point(std::move(lo), std::move(y_lo));
      pieces_.emplace_back(BaseCurve(first, point(std::move(hi), std::move(y_hi))), current_);
    }
    return true;
  }

  // A line k0 + kx x + ky y = 0: the parameter set (x, or y for a vertical line) where it is
  // inside the box, valid and inside its windows, as segments with rational ends.
  void clip_line(const Linear& line, const std::vector<ValidityClause>& clauses,
                 const std::vector<std::pair<Rational, Rational>>& windows) {
    const bool vertical = sgn(line.ky) == 0;
    Rational x0;     // vertical: the constant x
    Rational u, v;   // else y = u + v x
    // a linear function g0 + gx x + gy y along the line: p + q t
    auto along = [&](const Linear& g) -> std::pair<Rational, Rational> {
      if (vertical) return {g.k0 + g.kx * x0, g.ky};
      return {g.k0 + g.ky * u, g.kx + g.ky * v};
    };
    if (vertical) {
      x0 = -line.k0 / line.kx;
      if (x0 < box_.x_lo || x0 > box_.x_hi || !in_windows(x0, windows)) return;
    } else {
      u = -line.k0 / line.ky;
      v = -line.kx / line.ky;
    }
    auto at = [&](const Rational& t) {
      if (vertical) return point(x0, t);
      return point(t, Rational(-(line.k0 + line.kx * t) / line.ky));
    };
    // One-atom clauses and no windows (every contact segment of a polygon pair): the set is
    // one closed interval, kept as its two ends (the same ends as the set arithmetic below).
    const bool single = (vertical || windows.empty()) &&
                        std::all_of(clauses.begin(), clauses.end(), [](const ValidityClause& c) { return c.atoms.size() == 1; });
    if (single) {
      std::optional<Rational> lo, hi;
      bool empty = false;
      auto bound_pq = [&](const Rational& p, const Rational& q) {   // p + q t >= 0
        if (sgn(q) == 0) {
          if (sgn(p) < 0) empty = true;
          return;
        }
        Rational t = -p / q;
        if (sgn(q) > 0) {
          if (!lo || *lo < t) lo = std::move(t);
        } else if (!hi || t < *hi) {
          hi = std::move(t);
        }
      };
      auto bound = [&](const Linear& g) {
        auto [p, q] = along(g);
        bound_pq(p, q);
      };
      // the box sides x >= x_lo, x <= x_hi, y >= y_lo, y <= y_hi: along() of each written out
      // (the same p and q without the products by 0 and 1)
      static const Rational one(1), minus_one(-1);
      if (vertical) {
        bound_pq(Rational(x0 - box_.x_lo), Rational(0));
        bound_pq(Rational(box_.x_hi - x0), Rational(0));
        bound_pq(Rational(-box_.y_lo), one);
        bound_pq(box_.y_hi, minus_one);
      } else {
        bound_pq(Rational(-box_.x_lo), one);
        bound_pq(box_.x_hi, minus_one);
        bound_pq(Rational(u - box_.y_lo), v);
        bound_pq(Rational(box_.y_hi - u), Rational(-v));
      }
      for (const auto& clause : clauses) bound(linear_of(clause.atoms[0]));
      if (empty || (lo && hi && *hi < *lo)) return;
      if (!lo || !hi) throw GeometryError("internal: a clipped contact segment is unbounded");
      if (!(*lo < *hi)) return;   // a single valid point: no segment (as the algebraic stage)
      pieces_.emplace_back(BaseCurve(at(*lo), at(*hi)), current_);
      return;
    }
    Set set = everything();
    auto require = [&](const Linear& g) {
      auto [p, q] = along(g);
      set = intersect(set, half(p, q));
    };
    require(Linear{-box_.x_lo, 1, 0});
    require(Linear{box_.x_hi, -1, 0});
    require(Linear{-box_.y_lo, 0, 1});
    require(Linear{box_.y_hi, 0, -1});
    for (const auto& clause : clauses) {
      Set either;
      for (const auto& atom : clause.atoms) {
        auto [p, q] = along(linear_of(atom));
        either = unite(std::move(either), half(p, q));
      }
      set = intersect(set, either);
      if (set.empty()) return;
    }
    if (!vertical && !windows.empty()) {
      Set allowed;
      for (const auto& [lo, hi] : windows) allowed = unite(std::move(allowed), Set{Span{lo, hi}});
      set = intersect(set, allowed);
    }
    for (const auto& span : set) {
      if (!span.lo || !span.hi) throw GeometryError("internal: a clipped contact segment is unbounded");
      if (!(*span.lo < *span.hi)) continue;   // a single valid point: no segment (as the algebraic stage)
      pieces_.emplace_back(BaseCurve(at(*span.lo), at(*span.hi)), current_);
    }
  }

  struct Break {
    OneRoot x, y;
  };

  // Points of the circle on the line k0 + kx x + ky y = 0.
  static void circle_line(const Circle& c, const Linear& atom, std::vector<Break>& out) {
    Linear g = atom;
    if (sgn(atom.q) != 0) {
      // a circle: its points on c lie on the radical line (atom / q) - (c's monic polynomial)
      g = Linear{atom.k0 / atom.q - (c.cx * c.cx + c.cy * c.cy - c.r2), atom.kx / atom.q + 2 * c.cx,
                 atom.ky / atom.q + 2 * c.cy};
      if (sgn(g.kx) == 0 && sgn(g.ky) == 0) return;   // concentric: no common point (or the same circle)
    }
    if (sgn(g.ky) == 0) {
      if (sgn(g.kx) == 0) return;
      Rational x0 = -g.k0 / g.kx;
      Rational s = c.r2 - (x0 - c.cx) * (x0 - c.cx);
      if (sgn(s) < 0) return;
      out.push_back({OneRoot::of(x0, 0, 0), OneRoot::of(c.cy, 1, s)});
      if (sgn(s) > 0) out.push_back({OneRoot::of(x0, 0, 0), OneRoot::of(c.cy, -1, s)});
      return;
    }
    Rational u = -g.k0 / g.ky, v = -g.kx / g.ky;   // y = u + v x
    Rational w = u - c.cy;
    Rational a = 1 + v * v, b = 2 * (v * w - c.cx), d = c.cx * c.cx + w * w - c.r2;
    Rational disc = b * b - 4 * a * d;
    if (sgn(disc) < 0) return;
    Rational x_mid = -b / (2 * a), x_half = 1 / (2 * a);
    for (int sign : {1, -1}) {
      Rational a1 = sign * x_half;
      out.push_back({OneRoot::of(x_mid, a1, disc), OneRoot::of(u + v * x_mid, v * a1, disc)});
      if (sgn(disc) == 0) break;
    }
  }

  void clip_circle(const Circle& c, const std::vector<ValidityClause>& clauses,
                   const std::vector<std::pair<Rational, Rational>>& windows) {
    if (sgn(c.r2) < 0) return;
    if (sgn(c.r2) == 0) {
      // a single point (equal arcs, concentric): kept when inside the box and valid
      if (c.cx < box_.x_lo || c.cx > box_.x_hi || c.cy < box_.y_lo || c.cy > box_.y_hi || !in_windows(c.cx, windows)) return;
      bool valid = clauses_hold(clauses, [&](const Linear& g) {
        return sgn(g.k0 + g.kx * c.cx + g.ky * c.cy + g.q * (c.cx * c.cx + c.cy * c.cy));
      });
      if (valid) isolated_.emplace_back(CoordNT(to_nt(c.cx)), CoordNT(to_nt(c.cy)));
      return;
    }
    // cheap rejection: the circle's bounding box misses the chart box
    {
      auto outside = [&](const Rational& centre, const Rational& lo, const Rational& hi) {
        Rational below = lo - centre, above = centre - hi;   // > r means outside
        return (sgn(below) > 0 && below * below > c.r2) || (sgn(above) > 0 && above * above > c.r2);
      };
      if (outside(c.cx, box_.x_lo, box_.x_hi) || outside(c.cy, box_.y_lo, box_.y_hi)) return;
    }
    std::vector<Break> breaks;
    circle_line(c, Linear{-box_.x_lo, 1, 0}, breaks);
    circle_line(c, Linear{-box_.x_hi, 1, 0}, breaks);
    circle_line(c, Linear{-box_.y_lo, 0, 1}, breaks);
    circle_line(c, Linear{-box_.y_hi, 0, 1}, breaks);
    for (const auto& clause : clauses)
      for (const auto& atom : clause.atoms) circle_line(c, linear_of(atom), breaks);
    for (const auto& [lo, hi] : windows) {
      circle_line(c, Linear{-lo, 1, 0}, breaks);
      circle_line(c, Linear{-hi, 1, 0}, breaks);
    }
    const Kernel::Circle_2 circle(point(c.cx, c.cy), to_nt(c.r2));   // counter-clockwise
    const Break right{OneRoot::of(c.cx, 1, c.r2), OneRoot::of(c.cy, 0, 0)};
    const Break top{OneRoot::of(c.cx, 0, 0), OneRoot::of(c.cy, 1, c.r2)};
    const Break left{OneRoot::of(c.cx, -1, c.r2), OneRoot::of(c.cy, 0, 0)};
    const Break bottom{OneRoot::of(c.cx, 0, 0), OneRoot::of(c.cy, -1, c.r2)};
    struct Quarter {
      Break first, last;   // ascending x
      bool upper;
      int sx, sy;
    };
    const Quarter quarters[4] = {{top, right, true, 1, 1}, {left, top, true, -1, 1}, {left, bottom, false, -1, -1},
                                 {bottom, right, false, 1, -1}};
    const CoordNT cx(to_nt(c.cx)), cy(to_nt(c.cy));
    struct Located {
      CoordNT x;
      Break at;
    };
    std::vector<Located> located[4];
    for (const auto& b : breaks) {
      CoordNT bx = b.x.coord(), by = b.y.coord();
      int sx = static_cast<int>(CGAL::compare(bx, cx)), sy = static_cast<int>(CGAL::compare(by, cy));
      if (sx == 0 || sy == 0) continue;   // an extreme point: a quarter's end anyway
      for (int q = 0; q < 4; ++q)
        if (quarters[q].sx == sx && quarters[q].sy == sy) located[q].push_back({bx, b});
    }
    for (int q = 0; q < 4; ++q) {
      const Quarter& quarter = quarters[q];
      auto& list = located[q];
      std::sort(list.begin(), list.end(), [](const Located& a, const Located& b) { return CGAL::compare(a.x, b.x) == CGAL::SMALLER; });
      list.erase(std::unique(list.begin(), list.end(),
                             [](const Located& a, const Located& b) { return CGAL::compare(a.x, b.x) == CGAL::EQUAL; }),
                 list.end());
      std::vector<Break> chain{quarter.first};
      for (const auto& l : list) chain.push_back(l.at);
      chain.push_back(quarter.last);
      const int ysign = quarter.upper ? 1 : -1;
      std::size_t run_start = 0;
      bool in_run = false;
      auto emit = [&](std::size_t from, std::size_t to) {
        Point a(chain[from].x.coord(), chain[from].y.coord()), b(chain[to].x.coord(), chain[to].y.coord());
        // counter-clockwise: the upper half runs right to left, the lower half left to right
        if (quarter.upper)
          pieces_.emplace_back(BaseCurve(circle, b, a), current_);
        else
          pieces_.emplace_back(BaseCurve(circle, a, b), current_);
      };
      for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
        // a rational abscissa strictly inside the sub-arc, and its exact ordinate cy +- sqrt(s)
        Real xa = to_real(chain[i].x.coord()), xb = to_real(chain[i + 1].x.coord());
        Rational x = algebra::rational_between(xa, xb);
        Rational s = c.r2 - (x - c.cx) * (x - c.cx);
        auto sign_at = [&](const Linear& g) {   // g at (x, cy + ysign sqrt(s)): alpha + beta sqrt(s)
          return sign_of(g.k0 + g.kx * x + g.ky * c.cy + g.q * (x * x + c.cy * c.cy + s), (g.ky + 2 * g.q * c.cy) * ysign, s);
        };
        bool keep = box_.x_lo < x && x < box_.x_hi && sign_at(Linear{-box_.y_lo, 0, 1}) > 0 &&
                    sign_at(Linear{box_.y_hi, 0, -1}) > 0 && in_windows(x, windows) && clauses_hold(clauses, sign_at);
        if (keep && !in_run) {
          in_run = true;
          run_start = i;
        } else if (!keep && in_run) {
          in_run = false;
          emit(run_start, i);
        }
      }
      if (in_run) emit(run_start, chain.size() - 1);
    }
  }

  // ---------------------------------------------------------------- export

  void export_topology(Arrangement_2& arr) {
    auto edge_id = [](const auto& h) { return h->data() / 2; };
    auto forward = [](const auto& h) { return h->data() % 2 == 1; };   // goes min -> max
    result_.vertices.reserve(arr.number_of_vertices());
    result_.faces.reserve(arr.number_of_faces());
    result_.edges.reserve(arr.number_of_edges());
    for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v) {
      v->set_data(result_.vertices.size());
      // built where it stays (reserved above): moving a Vertex would leave six fresh rationals
      // behind, and its numbers are written into the ones it has
      Vertex& out = result_.vertices.emplace_back();
      if constexpr (segments) {
        std::size_t known = none;
        if (known_.find(v->point().id(), [&](std::size_t i) {
              known = i;
              return true;
            })) {
          // (copied, not moved: the kernel may still make a point's exact value from them,
          // DeferredKnownConstant — an intersection point's below, a wedge's predicate)
          const KnownPoint& k = known_points_[known];
          assign_exact_real(out.x, k.x);
          assign_exact_real(out.y, k.y);
        } else {
          assign_exact_real(out.x, rational_from(v->point().x()));
          assign_exact_real(out.y, rational_from(v->point().y()));
        }
        fill_y_from_number(out);
      } else {
        out.x = to_real(v->point().x());
        fill_y(v->point().y(), out);
      }
      out.isolated = v->is_isolated();
    }
    // each vertex's certified double bounds, once (the edges' boxes below)
    struct Bounds {
      double x_lo, y_lo, x_hi, y_hi;
    };
    std::vector<Bounds> bounds;
    bounds.reserve(result_.vertices.size());
    for (const Vertex& v : result_.vertices)
      bounds.push_back({double_bounds(v.x.lower).first, double_bounds(v.y_lower).first, double_bounds(v.x.upper).second,
                        double_bounds(v.y_upper).second});
    for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
      f->set_data(result_.faces.size());
      Face out;
      out.unbounded = f->is_unbounded();
      if (out.unbounded && result_.unbounded_face == none) result_.unbounded_face = result_.faces.size();
      result_.faces.push_back(std::move(out));
    }
    // segments: how many edges take each input line's carried support, so that the last of
    // them takes it by move (support_for's copy for the others: the same polynomial)
    std::vector<std::size_t> support_uses;
    if constexpr (segments) {
      support_uses.assign(line_supports_.size(), 0);
      for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e)
        if (carries_support(e->curve())) ++support_uses[e->curve().data()];
    }
    for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
      auto h = e->direction() == CGAL::ARR_LEFT_TO_RIGHT ? e : e->twin();
      h->set_data(2 * result_.edges.size() + 1);
      h->twin()->set_data(2 * result_.edges.size());
      Edge out;
      const XCurve& arc = h->curve();
      out.min_vertex = h->source()->data();
      out.max_vertex = h->target()->data();
      const Vertex& a = result_.vertices[out.min_vertex];
      const Vertex& b = result_.vertices[out.max_vertex];
      out.vertical = is_vertical(arc, a, b);
      const int side = chart_side_of(arc, a, b);
      if constexpr (segments) {
        if (side < 0 && carries_support(arc) && --support_uses[arc.data()] == 0)
          out.support = std::move(line_supports_[arc.data()]);   // (its last edge: no copy)
        else
          out.support = side >= 0 ? chart_side_support(side) : support_for(arc);
      } else {
        out.support = side >= 0 ? chart_side_support(side) : support_for(arc);
      }
      if (carries_support(arc)) out.support_curve = arc.data();
      out.left_face = h->face()->data();
      out.right_face = h->twin()->face()->data();
      const Bounds& ba = bounds[out.min_vertex];
      const Bounds& bb = bounds[out.max_vertex];
      // certified box of the ends (every edge is monotone in x and in y), strictly around it
      constexpr double inf = std::numeric_limits<double>::infinity();
      out.box[0] = std::nextafter(std::min(ba.x_lo, bb.x_lo), -inf);
      out.box[1] = std::nextafter(std::min(ba.y_lo, bb.y_lo), -inf);
      out.box[2] = std::nextafter(std::max(ba.x_hi, bb.x_hi), inf);
      out.box[3] = std::nextafter(std::max(ba.y_hi, bb.y_hi), inf);
      if (is_linear(arc)) {
        auto on = [](const Real& u, const Real& w, const Rational& q) { return u.compare(q) == 0 && w.compare(q) == 0; };
        if (out.vertical)
          out.box_side = on(a.x, b.x, box_.x_lo) ? 3 : on(a.x, b.x, box_.x_hi) ? 1 : -1;
        else
          out.box_side = on(a.y, b.y, box_.y_lo) ? 0 : on(a.y, b.y, box_.y_hi) ? 2 : -1;
      }
      if (!out.vertical) {
        int arcno = 0;
        if constexpr (!segments) {
          if (arc.is_circular()) {
            const CoordNT cy(arc.supporting_circle().center().y());
            arcno = CGAL::compare(arc.left().y(), cy) == CGAL::LARGER || CGAL::compare(arc.right().y(), cy) == CGAL::LARGER;
          }
        }
        out.arc_numbers.between.push_back(arcno);
      }
      result_.edges.push_back(std::move(out));
    }
    // (one list of a vertex's halfedges for all vertices, and each vertex's incidences
    // reserved to its degree: no regrowth of either per vertex)
    std::vector<typename Arrangement_2::Halfedge_const_handle> around;
    for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v) {
      Vertex& out = result_.vertices[v->data()];
      if (v->is_isolated()) {
        out.face_below = out.face_above = v->face()->data();
        result_.faces[out.face_below].isolated_vertices.push_back(v->data());
        continue;
      }
      around.clear();
      auto circulator = v->incident_halfedges();
      auto first = circulator;
      do {
        around.push_back(circulator);
      } while (++circulator != first);
      out.around.reserve(around.size());
      for (const auto& h : around) {
        Incidence incidence;
        incidence.edge = edge_id(h);
        // (the exported edge's vertical: is_vertical without CGAL's line)
        incidence.direction =
            leaving_direction(result_.edges[incidence.edge].vertical, h->direction() == CGAL::ARR_LEFT_TO_RIGHT);
        incidence.wedge_face = h->face()->data();
        out.around.push_back(incidence);
      }
      out.face_below = wedge_containing(around, out.around, v->point(), true);
      out.face_above = wedge_containing(around, out.around, v->point(), false);
    }
    for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
      Face& out = result_.faces[f->data()];
      auto add_ccb = [&](typename Arrangement_2::Ccb_halfedge_const_circulator c) {
        out.component_starts.push_back(out.boundary.size());
        auto first = c;
        do {
          out.boundary.emplace_back(edge_id(c), forward(c));
        } while (++c != first);
      };
      // (the boundary reserved to its length first: no regrowth)
      std::size_t length = 0, components = 0;
      auto count = [&](typename Arrangement_2::Ccb_halfedge_const_circulator c) {
        ++components;
        auto first = c;
        do ++length;
        while (++c != first);
      };
      if (f->has_outer_ccb()) count(f->outer_ccb());
      for (auto inner = f->inner_ccbs_begin(); inner != f->inner_ccbs_end(); ++inner) count(*inner);
      out.boundary.reserve(length);
      out.component_starts.reserve(components);
      if (f->has_outer_ccb()) add_ccb(f->outer_ccb());
      for (auto inner = f->inner_ccbs_begin(); inner != f->inner_ccbs_end(); ++inner) add_ccb(*inner);
    }
  }

  // Which wedge around the vertex contains the straight-down (below) or straight-up direction?
  // (arrangement.hpp, wedge_around: angles clockwise from the reference direction.)
  std::size_t wedge_containing(const std::vector<typename Arrangement_2::Halfedge_const_handle>& around,
                               const std::vector<Incidence>& incidences, const Point& p, bool below) const {
    auto compare_right = traits_.compare_y_at_x_right_2_object();
    auto compare_left = traits_.compare_y_at_x_left_2_object();
    return wedge_around(incidences, below, [&](std::size_t a, std::size_t b, Direction side) {
      if (side == Direction::right) return compare_right(around[a]->curve(), around[b]->curve(), p) == CGAL::LARGER;
      return compare_left(around[a]->curve(), around[b]->curve(), p) == CGAL::SMALLER;
    });
  }

  // The support of an edge: for a piece of an input line, that line's primitive polynomial
  // with the sign CGAL's supporting line has (the same polynomial support_of computes from the
  // lazy line, without its exact conversion); else support_of.
  static bool is_linear(const XCurve& arc) {
    if constexpr (segments)
      return true;
    else
      return arc.is_linear();
  }

  // Whether the edge `arc` from a to b is vertical: CGAL's is_vertical, but for a segment with
  // rational ends their abscissae compared exactly (a segment is vertical exactly when its ends
  // have one abscissa). CGAL's segment computes its supporting line for is_vertical when no
  // predicate of the sweep has (a lazy construction per edge, whose interval filter throws and
  // falls back to exact numbers when the ends' ordinates are not points, e.g. 1/7).
  static bool is_vertical(const XCurve& arc, const Vertex& a, const Vertex& b) {
    if constexpr (segments)
      if (a.x.exact && b.x.exact) return mpq_equal(a.x.lower.get_mpq_t(), b.x.lower.get_mpq_t()) != 0;
    return arc.is_vertical();
  }

  // Whether support_for gives `arc` an input line's carried support (line_supports_).
  bool carries_support(const XCurve& arc) const {
    return options_.carry_line_supports && is_linear(arc) && arc.data() < line_supports_.size();
  }

  IntegerPolynomial2 support_for(const XCurve& arc) const {
    if (!carries_support(arc)) return support_of<segments>(arc);
    // segments: every piece of a contact line runs from its smaller to its larger end, and no
    // contact line lies on a chart side that runs the other way (segments_apply), so CGAL's
    // line of such an edge is oriented as oriented_line
    if constexpr (segments) return line_supports_[arc.data()];
    IntegerPolynomial2 support = line_supports_[arc.data()];
    // oriented_line has y coefficient > 0, or x coefficient < 0 for a vertical line; CGAL's
    // line (a, b, c) has its own orientation: compare the signs of b (or a)
    const bool vertical = sgn(coefficient(support, 0, 1)) == 0;
    const int ours = vertical ? sgn(coefficient(support, 1, 0)) : sgn(coefficient(support, 0, 1));
    const auto line = [&] {
      if constexpr (segments)
        return arc.line();
      else
        return arc.supporting_line();
    }();
    const int theirs = static_cast<int>(CGAL::sign(vertical ? line.a() : line.b()));
    if (theirs == 0) return support_of<segments>(arc);   // (cannot happen: a line has a or b non-zero)
    if (ours != theirs)
      for (auto& row : support.coefficients)
        for (auto& z : row) z = -z;
    return support;
  }

  // A piece of a chart side only (no input curve overlaps it: an overlapping curve's smaller
  // index would be its data), with carried supports in the segment flavour: the side, 0 bottom,
  // 1 right, 2 top, 3 left, from its ends; -1 for every other edge. The box was inserted as the
  // segments corner i -> corner i + 1 (run), and a piece of a segment keeps that segment's
  // orientation (CGAL splits a segment by moving its ends, and a line through two of its points
  // in the same order is the same line up to a positive factor).
  int chart_side_of(const XCurve& arc, const Vertex& a, const Vertex& b) const {
    if constexpr (!segments) return -1;
    if (!options_.carry_line_supports || arc.data() != no_curve) return -1;
    auto on = [](const Real& u, const Real& w, const Rational& q) { return u.compare(q) == 0 && w.compare(q) == 0; };
    if (on(a.y, b.y, box_.y_lo)) return 0;
    if (on(a.x, b.x, box_.x_hi)) return 1;
    if (on(a.y, b.y, box_.y_hi)) return 2;
    if (on(a.x, b.x, box_.x_lo)) return 3;
    throw GeometryError("internal: a chart side piece off the chart's sides");
  }

  // The support of chart side `side` as support_of computes it from CGAL's line of the side's
  // segment corner i -> corner i + 1 (a, b, c) = (y_i - y_i+1, x_i+1 - x_i, x_i y_i+1 - y_i x_i+1),
  // made primitive with its sign kept: bottom (x_lo, y_lo) -> (x_hi, y_lo): (x_hi - x_lo)(y - y_lo);
  // right (x_hi, y_lo) -> (x_hi, y_hi): (y_hi - y_lo)(x_hi - x); top (x_hi, y_hi) -> (x_lo, y_hi):
  // (x_hi - x_lo)(y_hi - y); left (x_lo, y_hi) -> (x_lo, y_lo): (y_hi - y_lo)(x - x_lo). Without
  // the lazy line's exact coefficients.
  IntegerPolynomial2 chart_side_support(int side) const {
    const Rational& q = side == 0 ? box_.y_lo : side == 1 ? box_.x_hi : side == 2 ? box_.y_hi : box_.x_lo;
    const int s = side == 0 || side == 3 ? 1 : -1;   // the sign of the variable's coefficient
    // (the coefficients written where they stay: no initializer list copied into the rows)
    IntegerPolynomial2 out;
    out.coefficients.resize(2);
    for (auto& row : out.coefficients) row.resize(2);
    mpz_class& num = out.coefficients[0][0];
    mpz_class& den = side == 0 || side == 2 ? out.coefficients[0][1] : out.coefficients[1][0];
    num = q.get_num();
    den = q.get_den();
    thread_local mpz_class g;
    mpz_gcd(g.get_mpz_t(), num.get_mpz_t(), den.get_mpz_t());
    if (g != 1) {
      mpz_divexact(num.get_mpz_t(), num.get_mpz_t(), g.get_mpz_t());
      mpz_divexact(den.get_mpz_t(), den.get_mpz_t(), g.get_mpz_t());
    }
    if (s < 0) mpz_neg(den.get_mpz_t(), den.get_mpz_t());
    else mpz_neg(num.get_mpz_t(), num.get_mpz_t());
    return out;
  }

  // The primitive integer polynomial of a line (total degree 1) oriented as CGAL orients a
  // segment from its smaller to its larger end: y coefficient > 0, or, for a vertical line,
  // x coefficient < 0.
  static IntegerPolynomial2 oriented_line(const IntegerPolynomial2& f) {
    const mpz_class& kx = coefficient(f, 1, 0);
    const mpz_class& ky = coefficient(f, 0, 1);
    const mpz_class& k0 = coefficient(f, 0, 0);
    thread_local mpz_class g;
    g = 0;
    for (const mpz_class* z : {&k0, &kx, &ky}) mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), z->get_mpz_t());
    const bool flip = sgn(ky) != 0 ? sgn(ky) < 0 : sgn(kx) > 0;
    if (flip) mpz_neg(g.get_mpz_t(), g.get_mpz_t());
    // {{k0, ky}, {kx, 0}} / g (g divides each: exact), written where they stay (no
    // initializer list copied into the rows)
    IntegerPolynomial2 out;
    out.coefficients.resize(2);
    for (auto& row : out.coefficients) row.resize(2);
    mpz_divexact(out.coefficients[0][0].get_mpz_t(), k0.get_mpz_t(), g.get_mpz_t());
    mpz_divexact(out.coefficients[0][1].get_mpz_t(), ky.get_mpz_t(), g.get_mpz_t());
    mpz_divexact(out.coefficients[1][0].get_mpz_t(), kx.get_mpz_t(), g.get_mpz_t());
    return out;
  }

  const Box& box_;   // (the caller's, which outlives the builder: build_circle_segment_arrangement)
  Options options_;
  Traits traits_;
  std::size_t current_ = no_curve;                  // the input curve being clipped
  std::vector<IntegerPolynomial2> line_supports_;   // per input line curve (empty for others)
  std::vector<Curve> pieces_;
  std::vector<Point> isolated_;
  struct KnownPoint {
    Point handle;
    Rational x, y;
  };
  IndexTable known_;      // handle id -> index in known_points_ (each handle once)
  IndexTable by_value_;   // point_hash -> index in known_points_
  std::vector<KnownPoint> known_points_;
  Arrangement result_;
};

// The segment flavour: every curve a line (or without points), line supports carried
// (Options::carry_line_supports), and no line on the chart's top or left side (those sides are
// inserted right to left and top to bottom: an edge where a contact line overlaps them would
// take its orientation from whichever piece CGAL keeps, which the two traits choose
// differently). Such charts give the same arrangement as the circle–segment flavour.
// CGAL's Arr_segment_traits_2 on Epeck takes its interval filter's doubles from products of up
// to four coordinates; far outside the doubles' range the filter overflows (infinite and NaN
// bounds) and the sweep crashed (SIGSEGV) on translating polygon pairs at 10^150 mm. The
// circle–segment traits builds the same arrangement there (checked at 10^200 and 10^300), so
// the segment traits is taken only while the chart box and every line's coefficients are well
// inside the range: |box| <= 2^200 and |coefficient| <= 2^400 (a line's constant term is a
// product of two coordinates). Tiny scales need no guard (underflow only widens the filter).
// within_segment_filter_range(Rational(z), exponent) for an integer z, deciding from its bit
// size alone where that decides (the rational form only between 2^exponent and 2^(exponent+1))
bool integer_within_segment_filter_range(const mpz_class& z, int exponent) {
  if (sgn(z) == 0) return true;
  const long nb = static_cast<long>(mpz_sizeinbase(z.get_mpz_t(), 2));
  if (nb + 1 <= exponent) return true;
  if (nb - 1 >= exponent + 1) return false;
  return within_segment_filter_range(Rational(z), exponent);
}

// -k0 / k == q exactly, k != 0: -k0 den(q) == num(q) k (q canonical, den(q) > 0)
bool quotient_equals(const mpz_class& k0, const mpz_class& k, const Rational& q) {
  thread_local mpz_class left, right;
  mpz_mul(left.get_mpz_t(), k0.get_mpz_t(), q.get_den_mpz_t());
  mpz_neg(left.get_mpz_t(), left.get_mpz_t());
  mpz_mul(right.get_mpz_t(), q.get_num_mpz_t(), k.get_mpz_t());
  return mpz_cmp(left.get_mpz_t(), right.get_mpz_t()) == 0;
}

bool segments_apply(const Box& box, const std::vector<IntegerPolynomial2>& curves, const Options& options) {
  if (!options.carry_line_supports) return false;
  const int box_limit = 200, coefficient_limit = 400;
  for (const Rational* v : {&box.x_lo, &box.x_hi, &box.y_lo, &box.y_hi})
    if (!within_segment_filter_range(*v, box_limit)) return false;
  for (const auto& f : curves) {
    int degree = total_degree(f);
    if (degree >= 2) return false;
    if (degree < 1) continue;
    // (on the line's integer coefficients: no rational copies of them, no quotient)
    const mpz_class& k0 = coefficient(f, 0, 0);
    const mpz_class& kx = coefficient(f, 1, 0);
    const mpz_class& ky = coefficient(f, 0, 1);
    if (!integer_within_segment_filter_range(k0, coefficient_limit) ||
        !integer_within_segment_filter_range(kx, coefficient_limit) ||
        !integer_within_segment_filter_range(ky, coefficient_limit))
      return false;
    // -k0 / ky == y_hi (a horizontal line on the top side), -k0 / kx == x_lo (a vertical line
    // on the left side), compared as -k0 den == num k (k != 0: the line has degree 1)
    if (sgn(kx) == 0 && quotient_equals(k0, ky, box.y_hi)) return false;
    if (sgn(ky) == 0 && quotient_equals(k0, kx, box.x_lo)) return false;
  }
  return true;
}

}  // namespace

std::pair<double, double> kernel_interval(const Rational& value) {
  double lower, upper;
  if (algebra::enclose_rational(value, lower, upper)) return {lower, upper};
  return CGAL::to_interval(exact_of<ET>(value));
}

std::pair<double, double> double_bounds(const Rational& value) {
  double lower, upper;
  if (algebra::enclose_rational(value, lower, upper)) return {lower, upper};
  return {algebra::lower_double(value), algebra::upper_double(value)};
}

bool within_segment_filter_range(const Rational& value, int exponent) {
  // |num| in [2^(nb-1), 2^nb), den in [2^(db-1), 2^db): 2^(nb-db-1) < |value| < 2^(nb-db+1).
  // Below 2^exponent the rounded value is at most 2^exponent; above 2^(exponent+1) it is more.
  if (sgn(value) == 0) return true;
  if (sgn(value.get_den()) > 0) {
    const long nb = static_cast<long>(mpz_sizeinbase(value.get_num_mpz_t(), 2));
    const long db = static_cast<long>(mpz_sizeinbase(value.get_den_mpz_t(), 2));
    if (nb - db + 1 <= exponent) return true;
    if (nb - db - 1 >= exponent + 1) return false;
  }
  return std::abs(to_double(value)) <= std::ldexp(1.0, exponent);
}

algebra::Real exact_real(const Rational& value) {
  Real r;
  assign_exact_real(r, value);
  return r;
}

void exact_real_into(algebra::Real& r, Rational&& value) { assign_exact_real(r, std::move(value)); }

bool circle_segment_applies(const std::vector<IntegerPolynomial2>& curves,
                            const std::vector<std::vector<ValidityClause>>& validity) {
  for (std::size_t k = 0; k < curves.size(); ++k) {
    int degree = total_degree(curves[k]);
    bool circle = degree >= 2;
    if (circle && !circle_of(curves[k])) return false;
    if (k >= validity.size()) continue;
    // atoms: linear on every curve; on a circle also q (x^2 + y^2) + linear
    for (const auto& clause : validity[k])
      for (const auto& atom : clause.atoms)
        if (circle ? !atom_form(atom) : total_degree(atom) > 1) return false;
  }
  return true;
}

Arrangement build_circle_segment_arrangement(const Box& box, const std::vector<IntegerPolynomial2>& curves,
                                             const std::vector<std::vector<ValidityClause>>& validity,
                                             const std::vector<std::vector<std::pair<Rational, Rational>>>& windows,
                                             const Options& options) {
  if (!circle_segment_applies(curves, validity))
    throw GeometryError("internal: the circle–segment arrangement needs lines and circles with linear validity");
  try {
    if (segments_apply(box, curves, options)) {
      Builder<SegmentFlavour> builder(box, options);
      return builder.run(curves, validity, windows);
    }
    Builder<CircleFlavour> builder(box, options);
    return builder.run(curves, validity, windows);
  } catch (const hipair::Error&) {
    throw;
  } catch (const CGAL::Failure_exception& e) {
    throw GeometryError(std::string("CGAL rejected a circle–segment contact arrangement: ") + e.what());
  }
}

}  // namespace hipair::cspace::raw
