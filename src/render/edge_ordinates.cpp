// Certified double enclosures of a C-space edge's ordinate (see edge_ordinates.hpp).
#include "render/edge_ordinates.hpp"

#include <hipair/error.hpp>

#include <gmp.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <utility>

namespace hipair::render {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr DoubleRange everything{-inf, inf};

// Every operation rounds to nearest and then steps one double outwards: the exact result of
// the operation on the exact ends lies inside (the rounding error is at most half a step).
double down(double v) { return std::nextafter(v, -inf); }
double up(double v) { return std::nextafter(v, inf); }
bool finite(const DoubleRange& r) { return std::isfinite(r.lo) && std::isfinite(r.hi); }

DoubleRange add(const DoubleRange& a, const DoubleRange& b) {
  if (!finite(a) || !finite(b)) return everything;
  return {down(a.lo + b.lo), up(a.hi + b.hi)};
}
DoubleRange negate(const DoubleRange& a) { return {-a.hi, -a.lo}; }
DoubleRange multiply(const DoubleRange& a, const DoubleRange& b) {
  if (!finite(a) || !finite(b)) return everything;
  const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return {down(*std::min_element(p, p + 4)), up(*std::max_element(p, p + 4))};
}
DoubleRange square(const DoubleRange& a) {
  if (!finite(a)) return everything;
  if (a.lo >= 0) return {std::max(0.0, down(a.lo * a.lo)), up(a.hi * a.hi)};
  if (a.hi <= 0) return {std::max(0.0, down(a.hi * a.hi)), up(a.lo * a.lo)};
  return {0, up(std::max(a.lo * a.lo, a.hi * a.hi))};
}
bool excludes_zero(const DoubleRange& a) { return finite(a) && (a.lo > 0 || a.hi < 0); }
// a / b, b excluding zero
DoubleRange divide(const DoubleRange& a, const DoubleRange& b) {
  if (!finite(a) || !excludes_zero(b)) return everything;
  const double q[4] = {a.lo / b.lo, a.lo / b.hi, a.hi / b.lo, a.hi / b.hi};
  return {down(*std::min_element(q, q + 4)), up(*std::max_element(q, q + 4))};
}
// sqrt of a non-negative range (correctly rounded sqrt, one step out)
DoubleRange root(const DoubleRange& a) {
  if (!finite(a) || a.lo < 0) return everything;
  return {std::max(0.0, down(std::sqrt(a.lo))), up(std::sqrt(a.hi))};
}
DoubleRange scale(const DoubleRange& a, double power_of_two) {   // exact unless it leaves the normal range
  if (!finite(a)) return everything;
  return {down(a.lo * power_of_two), up(a.hi * power_of_two)};
}

// z / 2^shift enclosed: mpz_get_d_2exp truncates towards zero, so the exact mantissa lies
// between the returned one and the next double away from zero; ldexp is exact in the normal
// range, and what would fall below it is enclosed by [0, DBL_MIN] of the right sign.
DoubleRange enclose_scaled(const mpz_class& z, long shift) {
  if (z == 0) return {0, 0};
  long exponent = 0;
  const double m = mpz_get_d_2exp(&exponent, z.get_mpz_t());
  const double beyond = std::nextafter(m, m > 0 ? 2.0 : -2.0);
  const long e = exponent - shift;
  if (e < -1000) return m > 0 ? DoubleRange{0, DBL_MIN} : DoubleRange{-DBL_MIN, 0};
  if (e > 1000) return everything;
  const double p = std::ldexp(m, static_cast<int>(e)), q = std::ldexp(beyond, static_cast<int>(e));
  return m > 0 ? DoubleRange{p, q} : DoubleRange{q, p};
}

DoubleRange horner(const std::vector<DoubleRange>& coefficients, const DoubleRange& x) {
  DoubleRange result{0, 0};
  for (auto c = coefficients.rbegin(); c != coefficients.rend(); ++c) result = add(multiply(result, x), *c);
  return result;
}

bool disjoint(const DoubleRange& a, const DoubleRange& b) { return a.hi < b.lo || b.hi < a.lo; }

}  // namespace

EdgeOrdinates::EdgeOrdinates(const CSpace& space, std::size_t edge_index, const std::vector<double>& xs, bool by_extent) {
  if (space.dimension() != 2 || edge_index >= space.edges().size() || xs.empty()) return;
  const double first = xs.front(), last = xs.back();
  if (!(first <= last) || !std::isfinite(first) || !std::isfinite(last)) return;
  const CSpaceEdge& edge = space.edges()[edge_index];
  if (edge.vertical) return;
  // the abscissas lie strictly inside the edge's exact extent (the drawing computes them from
  // approximations of the vertices: a very short edge is left to the exact evaluation)
  const AlgebraicNumber& source = space.vertices().at(edge.source).x;
  const AlgebraicNumber& target = space.vertices().at(edge.target).x;
  if (!(Rational(first) > (source.exact ? source.lower : source.upper)) ||
      !(Rational(last) < target.lower))
    return;
  const std::vector<std::vector<mpz_class>>& c = space.edge_polynomial_coefficients(edge_index);
  int degree = -1;
  std::size_t bits = 0;
  for (const auto& row : c)
    for (std::size_t j = 0; j < row.size(); ++j)
      if (row[j] != 0) {
        degree = std::max(degree, static_cast<int>(j));
        bits = std::max(bits, mpz_sizeinbase(row[j].get_mpz_t(), 2));
      }
  if (degree != 1 && degree != 2) return;
  const long shift = bits > 800 ? static_cast<long>(bits) - 800 : 0;
  for (const auto& row : c) {
    a_.push_back(row.size() > 2 ? enclose_scaled(row[2], shift) : DoubleRange{0, 0});
    b_.push_back(row.size() > 1 ? enclose_scaled(row[1], shift) : DoubleRange{0, 0});
    c_.push_back(!row.empty() ? enclose_scaled(row[0], shift) : DoubleRange{0, 0});
  }
  if (degree == 1) {
    degree_ = 1;   // one root wherever b(x) != 0 (checked at each abscissa)
    return;
  }
  // a(x) != 0 and b^2 - 4ac > 0 on boxes covering [first, last], bisected up to 2^7 boxes
  std::vector<std::pair<DoubleRange, int>> boxes{{DoubleRange{first, last}, 0}};
  while (!boxes.empty()) {
    auto [box, depth] = boxes.back();
    boxes.pop_back();
    DoubleRange a = horner(a_, box), b = horner(b_, box), c0 = horner(c_, box);
    DoubleRange discriminant = add(square(b), negate(scale(multiply(a, c0), 4)));
    if (excludes_zero(a) && finite(discriminant) && discriminant.lo > 0) continue;
    if (depth == 7) return;   // not certified: every sample evaluated exactly
    double middle = box.lo + (box.hi - box.lo) / 2;
    if (!(middle > box.lo && middle < box.hi)) return;
    boxes.push_back({DoubleRange{box.lo, middle}, depth + 1});
    boxes.push_back({DoubleRange{middle, box.hi}, depth + 1});
  }
  // which root: at the middle abscissa, the root whose enclosure alone meets the edge's
  // certified y extent, or else the exact ordinate's certified enclosure
  const double x = xs[xs.size() / 2];
  std::optional<std::pair<DoubleRange, DoubleRange>> both = roots(x);
  if (!both) return;
  const DoubleRange extent{edge.y_chart.lower, edge.y_chart.upper};
  bool meets_lower = !disjoint(both->first, extent), meets_upper = !disjoint(both->second, extent);
  if (by_extent && meets_lower != meets_upper) {
    branch_ = meets_lower ? 0 : 1;
  } else {
    CertifiedValue exact;
    try {
      exact = space.evaluate(edge_index, x);
    } catch (const Error&) {
      return;
    }
    reference_ = exact;
    const DoubleRange y{down(exact.value - exact.error), up(exact.value + exact.error)};
    meets_lower = !disjoint(both->first, y);
    meets_upper = !disjoint(both->second, y);
    if (meets_lower == meets_upper) return;
    branch_ = meets_lower ? 0 : 1;
  }
  degree_ = 2;
}

std::optional<std::pair<DoubleRange, DoubleRange>> EdgeOrdinates::roots(double x) const {
  const DoubleRange at{x, x};
  const DoubleRange a = horner(a_, at), b = horner(b_, at), c = horner(c_, at);
  const DoubleRange discriminant = add(square(b), negate(scale(multiply(a, c), 4)));
  if (!excludes_zero(a) || !finite(discriminant) || !(discriminant.lo > 0)) return std::nullopt;
  const DoubleRange s = root(discriminant);
  DoubleRange r1, r2;
  if (excludes_zero(b)) {
    // q = -(b + sign(b) sqrt) / 2, roots q / a and c / q (no cancellation)
    const DoubleRange q = scale(negate(b.lo > 0 ? add(b, s) : add(b, negate(s))), 0.5);
    r1 = divide(q, a);
    r2 = divide(c, q);
  } else {
    const DoubleRange twice_a = scale(a, 2);
    r1 = divide(add(negate(b), s), twice_a);
    r2 = divide(add(negate(b), negate(s)), twice_a);
  }
  if (!finite(r1) || !finite(r2) || !disjoint(r1, r2)) return std::nullopt;
  if (r2.hi < r1.lo) std::swap(r1, r2);
  return std::make_pair(r1, r2);
}

std::optional<DoubleRange> EdgeOrdinates::enclose(double x) const {
  if (degree_ == 1) {
    const DoubleRange at{x, x};
    const DoubleRange b = horner(b_, at), c = horner(c_, at);
    if (!excludes_zero(b)) return std::nullopt;
    DoubleRange y = divide(negate(c), b);
    if (!finite(y)) return std::nullopt;
    return y;
  }
  if (degree_ != 2) return std::nullopt;
  std::optional<std::pair<DoubleRange, DoubleRange>> both = roots(x);
  if (!both) return std::nullopt;
  return branch_ == 0 ? both->first : both->second;
}

}  // namespace hipair::render
