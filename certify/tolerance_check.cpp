// The verifier's check of tolerance certificates (tolerance_check.hpp, docs/certify.md
// "Tolerance"). No floating-point type: MPFI enclosures with exact rational ends, decided by
// certain signs and exact comparisons.
#include "certify/tolerance_check.hpp"

#include "certify/interval_geometry.hpp"
#include "certify/tolerance_support.hpp"

#include <hipair/error.hpp>

#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <set>

namespace hipair::verify {

// ----------------------------------------------------------------------------- jets

namespace {

Interval apply1(int (*f)(mpfi_ptr, mpfi_srcptr), const Interval& x) {
  Interval r;
  f(r.get(), x.get());
  return r;
}
Interval zero() { return Interval(Rational(0)); }
Interval one() { return Interval(Rational(1)); }

std::vector<Interval> scaled(const std::vector<Interval>& g, const Interval& f) {
  std::vector<Interval> out;
  out.reserve(g.size());
  for (const Interval& x : g) out.push_back(x * f);
  return out;
}
// a.gradient * fa + b.gradient * fb
std::vector<Interval> combine(const Jet& a, const Interval& fa, const Jet& b, const Interval& fb) {
  std::size_t n = std::max(a.gradient.size(), b.gradient.size());
  std::vector<Interval> g;
  g.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    bool ha = i < a.gradient.size(), hb = i < b.gradient.size();
    if (ha && hb) g.push_back(a.gradient[i] * fa + b.gradient[i] * fb);
    else if (ha) g.push_back(a.gradient[i] * fa);
    else g.push_back(b.gradient[i] * fb);
  }
  return g;
}
// The smaller (or larger) of two intervals, endpoint-wise.
Interval extremum(const Interval& a, const Interval& b, bool minimum) {
  mpfr_t x, y;
  mpfr_init2(x, model_detail::interval_bits);
  mpfr_init2(y, model_detail::interval_bits);
  Interval r;
  mpfi_get_left(x, a.get());
  mpfi_get_left(y, b.get());
  if (minimum) mpfr_min(x, x, y, MPFR_RNDD);
  else mpfr_max(x, x, y, MPFR_RNDD);
  mpfr_t z, w;
  mpfr_init2(z, model_detail::interval_bits);
  mpfr_init2(w, model_detail::interval_bits);
  mpfi_get_right(z, a.get());
  mpfi_get_right(w, b.get());
  if (minimum) mpfr_min(z, z, w, MPFR_RNDU);
  else mpfr_max(z, z, w, MPFR_RNDU);
  mpfi_interv_fr(r.get(), x, z);
  mpfr_clear(x);
  mpfr_clear(y);
  mpfr_clear(z);
  mpfr_clear(w);
  return r;
}

}  // namespace

Jet Jet::variable(const Interval& v, std::size_t index, std::size_t count) {
  std::vector<Interval> g(count, zero());
  g[index] = one();
  return Jet(v, std::move(g));
}

Jet operator+(const Jet& a, const Jet& b) { return Jet(a.value + b.value, combine(a, one(), b, one())); }
Jet operator-(const Jet& a, const Jet& b) { return Jet(a.value - b.value, combine(a, one(), b, -one())); }
Jet operator-(const Jet& a) { return Jet(-a.value, scaled(a.gradient, -one())); }
Jet operator*(const Jet& a, const Jet& b) { return Jet(a.value * b.value, combine(a, b.value, b, a.value)); }
Jet operator/(const Jet& a, const Jet& b) {
  Interval q = a.value / b.value;
  Interval inverse = one() / b.value;
  return Jet(q, combine(a, inverse, b, -(q * inverse)));
}

// ----------------------------------------------------------------------------- second-order jets

namespace {

// Row a of the upper triangle of an n x n matrix starts at a n - a (a - 1) / 2.
std::size_t triangle(std::size_t a, std::size_t b, std::size_t n) { return a * n - a * (a - 1) / 2 + (b - a); }

// x's gradient and Hessian spread over the dimensions u (a superset of x.index).
void spread(const Jet2& x, const std::vector<std::size_t>& u, std::vector<Interval>& g, std::vector<Interval>& h) {
  std::size_t n = u.size();
  if (x.index == u) {
    g = x.gradient;
    h = x.hessian;
    return;
  }
  g.assign(n, zero());
  h.assign(n * (n + 1) / 2, zero());
  std::vector<std::size_t> at;
  for (std::size_t d : x.index) at.push_back(static_cast<std::size_t>(std::lower_bound(u.begin(), u.end(), d) - u.begin()));
  std::size_t m = x.index.size();
  for (std::size_t a = 0; a < m; ++a) {
    g[at[a]] = x.gradient[a];
    for (std::size_t b = a; b < m; ++b) h[triangle(at[a], at[b], n)] = x.hessian[triangle(a, b, m)];
  }
}

// value; gradient fa ga + fb gb; Hessian fa Ha + fb Hb + faa ga ga' + fbb gb gb' + fab (ga gb' + gb ga')
// (a null multiplier of a first-order term is 1, of a second-order term 0).
Jet2 combine2(const Jet2& a, const Jet2& b, Interval value, const Interval* fa, const Interval* fb, const Interval* faa,
              const Interval* fbb, const Interval* fab) {
  Jet2 r(value);
  r.smooth = a.smooth && b.smooth;
  std::set_union(a.index.begin(), a.index.end(), b.index.begin(), b.index.end(), std::back_inserter(r.index));
  std::size_t n = r.index.size();
  if (n == 0) return r;
  std::vector<Interval> ga, ha, gb, hb;
  spread(a, r.index, ga, ha);
  spread(b, r.index, gb, hb);
  auto times = [](const Interval& x, const Interval* f) { return f ? x * *f : x; };
  r.gradient.reserve(n);
  for (std::size_t i = 0; i < n; ++i) r.gradient.push_back(times(ga[i], fa) + times(gb[i], fb));
  r.hessian.reserve(n * (n + 1) / 2);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {
      std::size_t t = triangle(i, j, n);
      Interval v = times(ha[t], fa) + times(hb[t], fb);
      if (faa) v = v + *faa * ga[i] * ga[j];
      if (fbb) v = v + *fbb * gb[i] * gb[j];
      if (fab) v = v + *fab * (ga[i] * gb[j] + gb[i] * ga[j]);
      r.hessian.push_back(std::move(v));
    }
  return r;
}

// f(x) with f' = f1, f'' = f2 at x (enclosed over x's value).
Jet2 chain2(const Jet2& x, Interval value, const Interval& f1, const Interval& f2) {
  Jet2 r(value);
  r.smooth = x.smooth;
  r.index = x.index;
  std::size_t n = x.index.size();
  r.gradient.reserve(n);
  for (const Interval& g : x.gradient) r.gradient.push_back(g * f1);
  r.hessian.reserve(x.hessian.size());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) r.hessian.push_back(x.hessian[triangle(i, j, n)] * f1 + f2 * x.gradient[i] * x.gradient[j]);
  return r;
}

// A non-differentiable point may lie in the range: the value stands, no derivative does.
Jet2 rough(const Jet2& a, const Jet2& b, Interval value) {
  Jet2 r = combine2(a, b, std::move(value), nullptr, nullptr, nullptr, nullptr, nullptr);
  r.smooth = false;
  return r;
}

}  // namespace

Jet2 Jet2::variable(const Interval& v, std::size_t dimension) {
  Jet2 r(v);
  r.index = {dimension};
  r.gradient = {one()};
  r.hessian = {zero()};
  return r;
}

const Interval& Jet2::second(std::size_t a, std::size_t b) const {
  return a <= b ? hessian[triangle(a, b, index.size())] : hessian[triangle(b, a, index.size())];
}

Jet2 operator+(const Jet2& a, const Jet2& b) {
  return combine2(a, b, a.value + b.value, nullptr, nullptr, nullptr, nullptr, nullptr);
}
Jet2 operator-(const Jet2& a, const Jet2& b) {
  Interval minus_one = -one();
  return combine2(a, b, a.value - b.value, nullptr, &minus_one, nullptr, nullptr, nullptr);
}
Jet2 operator-(const Jet2& a) { return chain2(a, -a.value, -one(), zero()); }
Jet2 operator*(const Jet2& a, const Jet2& b) {
  if (a.index.empty()) return chain2(b, a.value * b.value, a.value, zero()) ;
  if (b.index.empty()) return chain2(a, a.value * b.value, b.value, zero());
  Interval unit = one();
  return combine2(a, b, a.value * b.value, &b.value, &a.value, nullptr, nullptr, &unit);
}
Jet2 operator/(const Jet2& a, const Jet2& b) {
  Interval inverse = one() / b.value;
  if (b.index.empty()) return chain2(a, a.value * inverse, inverse, zero());
  // 1/x: -1/x^2, 2/x^3
  Interval square = inverse * inverse;
  Jet2 reciprocal = chain2(b, inverse, -square, Interval(Rational(2)) * square * inverse);
  return a * reciprocal;
}

Interval enclose(const Rational& value) { return Interval(value); }
Interval enclose(const RationalInterval& range) {
  Interval r;
  mpfi_interv_q(r.get(), range.lo.get_mpq_t(), range.hi.get_mpq_t());
  return r;
}

Interval hull2(const Interval& a, const Interval& b) {
  Interval r;
  mpfi_union(r.get(), a.get(), b.get());
  return r;
}

// An enclosure printed with 8 significant digits per end (for messages only).
std::string show(const Interval& x) {
  if (!x.is_bounded()) return "unbounded";
  mpfr_t end;
  mpfr_init2(end, model_detail::interval_bits);
  char* lo = nullptr;
  char* hi = nullptr;
  mpfi_get_left(end, x.get());
  mpfr_asprintf(&lo, "%.8RDg", end);
  mpfi_get_right(end, x.get());
  mpfr_asprintf(&hi, "%.8RUg", end);
  std::string out = std::string("[") + lo + ", " + hi + "]";
  mpfr_free_str(lo);
  mpfr_free_str(hi);
  mpfr_clear(end);
  return out;
}

std::string show(const RationalInterval& r) { return "[" + fraction_or_rounded(r.lo) + ", " + fraction_or_rounded(r.hi) + "]"; }

// x intersected with y (both enclose the same number).
Interval meet(const Interval& x, const Interval& y) {
  Interval r;
  mpfi_intersect(r.get(), x.get(), y.get());
  if (mpfi_is_empty(r.get())) return x;   // cannot happen for two enclosures of one number
  return r;
}

}  // namespace hipair::verify

namespace hipair::model_detail {

// The verifier's own arithmetic for the parametric formulas: MPFI, outward rounded.
using J1 = verify::Jet;
J1 Arithmetic<J1>::constant(const Rational& q) { return J1(Interval(q)); }
J1 Arithmetic<J1>::pi() { return J1(Interval::pi()); }
J1 Arithmetic<J1>::sqrt(const J1& x) {
  Interval r = verify::apply1(mpfi_sqrt, x.value);
  return J1(r, verify::scaled(x.gradient, Interval(Rational(1)) / (Interval(Rational(2)) * r)));
}
J1 Arithmetic<J1>::sin(const J1& x) {
  return J1(verify::sin_of(x.value), verify::scaled(x.gradient, verify::cos_of(x.value)));
}
J1 Arithmetic<J1>::cos(const J1& x) {
  return J1(verify::cos_of(x.value), verify::scaled(x.gradient, -verify::sin_of(x.value)));
}
J1 Arithmetic<J1>::tan(const J1& x) { return sin(x) / cos(x); }
J1 Arithmetic<J1>::atan2(const J1& y, const J1& x) {
  Interval r;
  mpfi_atan2(r.get(), y.value.get(), x.value.get());
  // The branch cut (y = 0, x <= 0) inside the range: atan2 jumps by 2 pi there and no gradient
  // bounds its difference quotients, so every partial is the whole line (the mean-value and
  // monotonicity tests then fall back to the value). Until session 50 (exact50b) the gradient
  // x / r^2, -y / r^2 was used across the jump: atan2(p, -1) over p in [-0.1, 0.1] was
  // enclosed in [pi - 0.1, pi] by the mean-value form, its values near -pi left out.
  if (y.value.sign() == 0 && x.value.sign() <= 0) {
    Interval whole;
    mpfr_set_inf(&whole.get()->left, -1);
    mpfr_set_inf(&whole.get()->right, 1);
    std::vector<Interval> g(std::max(x.gradient.size(), y.gradient.size()), whole);
    return J1(r, std::move(g));
  }
  Interval r2 = x.value * x.value + y.value * y.value;
  return J1(r, verify::combine(y, x.value / r2, x, -(y.value / r2)));
}
J1 Arithmetic<J1>::abs(const J1& x) {
  int s = x.value.sign();
  if (s > 0) return x;
  if (s < 0) return -x;
  // Not differentiable at 0: the generalised gradient lies in [-1, 1] times the gradient.
  Interval unit;
  mpfi_interv_si(unit.get(), -1, 1);
  return J1(verify::apply1(mpfi_abs, x.value), verify::scaled(x.gradient, unit));
}
J1 Arithmetic<J1>::extremum(const J1& a, const J1& b, bool minimum) {
  int s = (a.value - b.value).sign();
  if (s < 0) return minimum ? a : b;
  if (s > 0) return minimum ? b : a;
  std::size_t n = std::max(a.gradient.size(), b.gradient.size());
  std::vector<Interval> g;
  for (std::size_t i = 0; i < n; ++i) g.push_back(verify::hull2(a.partial(i), b.partial(i)));
  return J1(verify::extremum(a.value, b.value, minimum), std::move(g));
}


// The same formulas with second-order jets (tolerance_check.hpp; the witness test's Taylor
// form): each operation carries f' and f'' enclosed over its argument's range.
using J2 = verify::Jet2;
J2 Arithmetic<J2>::constant(const Rational& q) { return J2(Interval(q)); }
J2 Arithmetic<J2>::pi() { return J2(Interval::pi()); }
J2 Arithmetic<J2>::sqrt(const J2& x) {
  using I = Interval;
  I r = verify::apply1(mpfi_sqrt, x.value);
  I f1 = I(Rational(1)) / (I(Rational(2)) * r);   // 1 / (2 r)
  return verify::chain2(x, r, f1, -(f1 / (I(Rational(2)) * x.value)));   // -1 / (4 r^3)
}
J2 Arithmetic<J2>::sin(const J2& x) {
  Interval s = verify::sin_of(x.value);
  return verify::chain2(x, s, verify::cos_of(x.value), -s);
}
J2 Arithmetic<J2>::cos(const J2& x) {
  Interval c = verify::cos_of(x.value);
  return verify::chain2(x, c, -verify::sin_of(x.value), -c);
}
J2 Arithmetic<J2>::tan(const J2& x) { return sin(x) / cos(x); }
J2 Arithmetic<J2>::atan2(const J2& y, const J2& x) {
  using I = Interval;
  I r;
  mpfi_atan2(r.get(), y.value.get(), x.value.get());
  // The branch cut (y = 0, x <= 0) inside the range: atan2 jumps there, no Taylor form holds.
  if (y.value.sign() == 0 && x.value.sign() <= 0) return verify::rough(y, x, r);
  I r2 = x.value * x.value + y.value * y.value;
  I r4 = r2 * r2;
  I ty = x.value / r2, tx = -(y.value / r2);
  I two_xy = I(Rational(2)) * x.value * y.value / r4;
  I tyy = -two_xy, txy = (y.value * y.value - x.value * x.value) / r4;
  return verify::combine2(y, x, r, &ty, &tx, &tyy, &two_xy, &txy);
}
J2 Arithmetic<J2>::abs(const J2& x) {
  int s = x.value.sign();
  if (s > 0) return x;
  if (s < 0) return -x;
  return verify::rough(x, J2(0), verify::apply1(mpfi_abs, x.value));
}
J2 Arithmetic<J2>::extremum(const J2& a, const J2& b, bool minimum) {
  int s = (a.value - b.value).sign();
  if (s < 0) return minimum ? a : b;
  if (s > 0) return minimum ? b : a;
  return verify::rough(a, b, verify::extremum(a.value, b.value, minimum));
}

}  // namespace hipair::model_detail

namespace hipair::verify {
namespace {

[[noreturn]] void reject(const std::string& reason) { throw Rejection{reason}; }




std::string feature_text(const FeatureReference& f) {
  return std::string(f.vertex ? "vertex at the start of " : "") + "'" + f.edge.label + "' (" + f.edge.part + " loop " +
         std::to_string(f.edge.loop) + " edge " + std::to_string(f.edge.edge) + ")";
}

}  // namespace

// ----------------------------------------------------------------------------- evaluator

ToleranceEvaluator::ToleranceEvaluator(std::shared_ptr<const model_detail::ParametricModel> model,
                                       const ToleranceClaim& claim)
    : model_(std::move(model)), claim_(claim) {
  const Model& m = model_->nominal();
  if (claim.property != "no_jam" && claim.property != "no_interference")
    reject("unknown tolerance property '" + claim.property + "' (expected no_jam or no_interference)");
  if (claim.property == "no_interference") {
    if (!claim.follower_range) reject("a no_interference claim needs its follower_range");
    if (!(claim.follower_range->lo <= claim.follower_range->hi))
      reject("the follower range " + show(*claim.follower_range) + " is empty");
    if (!claim.sides.empty()) reject("a no_interference claim has no contact sides");
  } else if (claim.follower_range) {
    reject("a follower_range belongs to no_interference claims only");
  }
  auto part_index = [&](const std::string& name, const char* role) {
    std::optional<std::size_t> k = m.find_part(name);
    if (!k) reject(std::string("the model has no ") + role + " part '" + name + "'");
    auto kind = m.parts[*k].motion.kind;
    if (kind != Motion::Kind::rotation && kind != Motion::Kind::translation)
      reject(std::string("the ") + role + " '" + name + "' neither rotates nor translates");
    return *k;
  };
  driver_ = part_index(claim.driver, "driver");
  follower_ = part_index(claim.follower, "follower");
  if (driver_ == follower_) reject("the driver and the follower are the same part");
  driver_rotates_ = m.parts[driver_].motion.kind == Motion::Kind::rotation;
  follower_rotates_ = m.parts[follower_].motion.kind == Motion::Kind::rotation;
  if (!model_->generic())
    reject("the model uses feature template '" + model_->exact_only_feature() + "', which has no parametric form");
  if (!(claim.range.lo < claim.range.hi)) reject("the driver range " + show(claim.range) + " is empty");
  if (!(claim.scale > 0)) reject("the scale " + to_exact_string(claim.scale) + " is not positive");
  if (claim.varied.empty()) reject("no varied parameter");
  if (claim.box.size() != claim.varied.size())
    reject("the box has " + std::to_string(claim.box.size()) + " intervals for " + std::to_string(claim.varied.size()) +
           " varied parameters");
  std::set<std::string> seen;
  for (std::size_t i = 0; i < claim.varied.size(); ++i) {
    const std::string& name = claim.varied[i];
    if (!seen.insert(name).second) reject("parameter '" + name + "' is varied twice");
    if (name == "driver") reject("a parameter named 'driver' cannot be varied (the name is the driver's dimension)");
    const Parameter* p = m.find_parameter(name);
    if (!p) reject("the model has no parameter '" + name + "'");
    RationalInterval expected{claim.scale * (p->range.lo - p->nominal), claim.scale * (p->range.hi - p->nominal)};
    if (!(expected.lo < expected.hi)) reject("parameter '" + name + "' has no tolerance to vary");
    if (claim.box[i].lo != expected.lo || claim.box[i].hi != expected.hi)
      reject("wrong parameter box: '" + name + "' varies over " + show(claim.box[i]) + ", but " +
             to_exact_string(claim.scale) + " x its tolerance range is " + show(expected));
    varied_.push_back(static_cast<std::size_t>(p - m.parameters.data()));
  }
  {
    // A template's generic form follows its nominal shape: a box that may change it is refused
    // (the box's ends rounded outwards to doubles).
    std::vector<double> lo(m.parameters.size(), 0.0), hi(m.parameters.size(), 0.0);
    bool in_doubles = true;
    for (std::size_t i = 0; i < varied_.size(); ++i) {
      lo[varied_[i]] = std::nextafter(claim.box[i].lo.get_d(), -HUGE_VAL);
      hi[varied_[i]] = std::nextafter(claim.box[i].hi.get_d(), HUGE_VAL);
      in_doubles = in_doubles && std::fabs(lo[varied_[i]]) <= 1e300 && std::fabs(hi[varied_[i]]) <= 1e300;
    }
    try {
      if (in_doubles) {
        model_->check_choices(lo, hi);
      } else {
        // deviations beyond the doubles (a raw parameter of 2e400 mm, session 67): the exact box
        std::vector<Rational> exact_lo(m.parameters.size(), Rational(0)), exact_hi(m.parameters.size(), Rational(0));
        for (std::size_t i = 0; i < varied_.size(); ++i) {
          exact_lo[varied_[i]] = claim.box[i].lo;
          exact_hi[varied_[i]] = claim.box[i].hi;
        }
        model_->check_choices(exact_lo, exact_hi);
      }
    } catch (const ModelError& error) {
      reject(error.what());
    }
  }
  if (claim.sides.empty() && claim.property == "no_jam") reject("no contact sides");
  for (std::size_t s = 0; s < claim.sides.size(); ++s) {
    const ContactSidePair& pair = claim.sides[s];
    for (int k = 0; k < 2; ++k) {
      const FeatureReference& f = k == 0 ? pair.driver : pair.follower;
      std::size_t part = k == 0 ? driver_ : follower_;
      const Part& p = m.parts[part];
      if (f.edge.part != p.name)
        reject("side " + std::to_string(s) + ": feature " + feature_text(f) + " is not a feature of '" + p.name + "'");
      if (f.edge.loop >= p.loops.size() || f.edge.edge >= p.loops[f.edge.loop].edges.size())
        reject("side " + std::to_string(s) + ": '" + p.name + "' has no loop " + std::to_string(f.edge.loop) +
               " edge " + std::to_string(f.edge.edge));
      const Edge& e = p.loops[f.edge.loop].edges[f.edge.edge];
      if (e.label != f.edge.label)
        reject("side " + std::to_string(s) + ": edge " + std::to_string(f.edge.edge) + " of loop " +
               std::to_string(f.edge.loop) + " of '" + p.name + "' is labelled '" + e.label + "', not '" +
               f.edge.label + "'");
    }
    const Edge& a = m.parts[driver_].loops[pair.driver.edge.loop].edges[pair.driver.edge.edge];
    const Edge& b = m.parts[follower_].loops[pair.follower.edge.loop].edges[pair.follower.edge.edge];
    bool a_arc = !pair.driver.vertex && a.kind == Edge::Kind::arc;
    bool b_arc = !pair.follower.vertex && b.kind == Edge::Kind::arc;
    bool a_segment = !pair.driver.vertex && !a_arc, b_segment = !pair.follower.vertex && !b_arc;
    bool ok = (pair.driver.vertex && !pair.follower.vertex) || (!pair.driver.vertex && pair.follower.vertex) ||
              (a_arc && b_arc && (a.ccw || b.ccw)) || (a_arc && b_segment && a.ccw) || (a_segment && b_arc && b.ccw);
    if (!ok)
      reject("side " + std::to_string(s) + ": " + feature_text(pair.driver) + " and " + feature_text(pair.follower) +
             " have no contact of their own");
  }
}

ToleranceGeometry ToleranceEvaluator::geometry(const std::vector<Interval>& deviations, bool gradient) const {
  std::size_t n = model_->parameter_count();
  std::vector<Jet> all(n, Jet(0));
  for (std::size_t i = 0; i < varied_.size(); ++i)
    all[varied_[i]] = gradient ? Jet::variable(deviations.at(i), i, variables()) : Jet(deviations.at(i));
  ToleranceGeometry g;
  g.parameters = model_->parameter_values(all);
  pose_pivots(g);
  return g;
}

template <class T>
void ToleranceEvaluator::pose_pivots(GeometryOf<T>& g) const {
  model_->motion_value(driver_, g.parameters, g.driver_pivot, g.driver_direction);
  model_->motion_value(follower_, g.parameters, g.follower_pivot, g.follower_direction);
}

template <class T>
const model_detail::EdgeValue<T>& ToleranceEvaluator::edge(GeometryOf<T>& g, std::size_t part,
                                                            const FeatureReference& f) const {
  auto key = std::make_tuple(part, f.edge.loop, f.edge.edge);
  auto it = g.edges.find(key);
  if (it == g.edges.end())
    it = g.edges.emplace(key, model_->edge_value(part, f.edge.loop, f.edge.edge, g.parameters)).first;
  return it->second;
}

template <class T>
kernels::Vector<T> ToleranceEvaluator::posed(const GeometryOf<T>& g, bool driver_part, const kernels::Vector<T>& point,
                                             const T& coordinate) const {
  bool rotates = driver_part ? driver_rotates_ : follower_rotates_;
  const kernels::Vector<T>& pivot = driver_part ? g.driver_pivot : g.follower_pivot;
  const kernels::Vector<T>& direction = driver_part ? g.driver_direction : g.follower_direction;
  if (!rotates) return placed(point, false, pivot, direction, coordinate, coordinate, coordinate);
  using A = model_detail::Arithmetic<T>;
  return placed(point, true, pivot, direction, coordinate, A::cos(coordinate), A::sin(coordinate));
}

// free_path_check.cpp poses parts with first- and second-order jets.
template void ToleranceEvaluator::pose_pivots<Jet>(GeometryOf<Jet>&) const;
template void ToleranceEvaluator::pose_pivots<Jet2>(GeometryOf<Jet2>&) const;
template kernels::Vector<Jet> ToleranceEvaluator::posed<Jet>(const GeometryOf<Jet>&, bool, const kernels::Vector<Jet>&,
                                                            const Jet&) const;
template kernels::Vector<Jet2> ToleranceEvaluator::posed<Jet2>(const GeometryOf<Jet2>&, bool,
                                                              const kernels::Vector<Jet2>&, const Jet2&) const;

Jet ToleranceEvaluator::contact(ToleranceGeometry& g, std::size_t pair, const Jet& driver, const Jet& follower) const {
  return contact_of(g, pair, driver, follower);
}

template <class T>
T ToleranceEvaluator::contact_of(GeometryOf<T>& g, std::size_t pair, const T& driver, const T& follower) const {
  const ContactSidePair& side = claim_.sides.at(pair);
  const model_detail::EdgeValue<T>& ea = edge(g, driver_, side.driver);
  const model_detail::EdgeValue<T>& eb = edge(g, follower_, side.follower);
  using V = kernels::Vector<T>;
  auto cross = [](const V& u, const V& v) { return u.x * v.y - u.y * v.x; };
  auto dot = [](const V& u, const V& v) { return u.x * v.x + u.y * v.y; };
  auto minus = [](const V& u, const V& v) { return V{u.x - v.x, u.y - v.y}; };
  auto pa = [&](const V& p) { return posed(g, true, p, driver); };
  auto pb = [&](const V& p) { return posed(g, false, p, follower); };
  // vertex against a segment: the vertex on the segment's line.
  auto vertex_segment = [&](const V& v, const V& s, const V& t) { return cross(minus(t, s), minus(v, s)); };
  // vertex against an arc: the vertex on the arc's circle.
  auto vertex_arc = [&](const V& v, const V& c, const T& r2) {
    V d = minus(v, c);
    return dot(d, d) - r2;
  };
  // arc (convex) against a segment: the circle tangent to the segment's line (either side).
  auto arc_segment = [&](const V& c, const T& r2, const V& s, const V& t) {
    V d = minus(t, s);
    T k = cross(d, minus(c, s));
    return k * k - r2 * dot(d, d);
  };
  bool a_vertex = side.driver.vertex, b_vertex = side.follower.vertex;
  if (a_vertex && !eb.arc) return vertex_segment(pa(ea.source), pb(eb.source), pb(eb.target));
  if (a_vertex) return vertex_arc(pa(ea.source), pb(eb.center), eb.radius_squared);
  if (b_vertex && !ea.arc) return vertex_segment(pb(eb.source), pa(ea.source), pa(ea.target));
  if (b_vertex) return vertex_arc(pb(eb.source), pa(ea.center), ea.radius_squared);
  if (ea.arc && eb.arc) {
    using A = model_detail::Arithmetic<T>;
    T ra = A::sqrt(ea.radius_squared), rb = A::sqrt(eb.radius_squared);
    T r = ea.ccw && eb.ccw ? ra + rb : ra - rb;   // external, or internal tangency
    V d = minus(pa(ea.center), pb(eb.center));
    return dot(d, d) - r * r;
  }
  if (ea.arc) return arc_segment(pa(ea.center), ea.radius_squared, pb(eb.source), pb(eb.target));
  return arc_segment(pb(eb.center), eb.radius_squared, pa(ea.source), pa(ea.target));
}

SideEnclosure ToleranceEvaluator::check_side(const ToleranceLeaf& leaf, const LeafSide& side, ToleranceGeometry& over,
                                             ToleranceGeometry& centre, const std::string& where,
                                             bool monotone_in_bracket) const {
  if (side.pair >= claim_.sides.size()) reject(where + ": side " + std::to_string(side.pair) + " does not exist");
  if (!contains(side.bracket, side.centre))
    reject(where + ": the centre interval " + show(side.centre) + " is not inside the bracket " + show(side.bracket));
  std::size_t k = varied_.size();
  std::size_t m = variables();
  Jet driver = Jet::variable(enclose(leaf.driver), driver_variable(), m);
  Jet driver_centre(enclose(middle(leaf.driver)));
  auto sign_at = [&](const Rational& y) { return sign_over_leaf(leaf, side.pair, y, over, centre); };
  int s0 = sign_at(side.bracket.lo), s1 = sign_at(side.bracket.hi);
  if (s0 == 0 || s1 == 0 || s0 == s1)
    reject(where + ": the contact function of side " + std::to_string(side.pair) +
           " does not certainly change sign across the bracket " + show(side.bracket));
  SideEnclosure result;
  result.bracket = enclose(side.bracket);
  int c0 = contact(centre, side.pair, driver_centre, Jet(enclose(side.centre.lo))).value.sign();
  int c1 = contact(centre, side.pair, driver_centre, Jet(enclose(side.centre.hi))).value.sign();
  if (c0 == 0 || c1 == 0 || c0 == c1)
    reject(where + ": at the leaf's centre the contact function of side " + std::to_string(side.pair) +
           " does not certainly change sign across " + show(side.centre));
  result.centre = enclose(side.centre);
  // With a witness the side is the root nearest the channel in the bracket; the witness check
  // proves there is none between it and the witness (check_witness). Without one the play is
  // enclosed from the root's slopes, which needs the one root of a monotone function.
  if (!monotone_in_bracket) return result;
  Jet follower = Jet::variable(enclose(side.bracket), follower_variable(), m);
  Jet f = contact(over, side.pair, driver, follower);
  Interval fy = f.partial(follower_variable());
  if (fy.sign() == 0)
    reject(where + ": the contact function of side " + std::to_string(side.pair) +
           " may be stationary in the follower over the bracket (derivative " + show(fy) + ")");
  for (std::size_t i = 0; i <= k; ++i) result.slope.push_back(-(f.partial(i) / fy));
  // Contraction: the side's root L(p, d) lies in root = centre + sum slope_i (P_i - c_i) (mean
  // value theorem along the segment from the leaf's centre; slope encloses -F_p / F_y along it)
  // and in the bracket; the slopes evaluated over that narrower follower range still enclose
  // the gradient along the segment (its points are roots of the leaf), so iterate.
  std::vector<Interval> offsets;
  for (const RationalInterval& p : leaf.parameters) offsets.push_back(offset(p));
  offsets.push_back(offset(leaf.driver));
  for (int iteration = 0; iteration < 3; ++iteration) {
    Interval root = result.centre;
    for (std::size_t i = 0; i <= k; ++i) root = root + result.slope[i] * offsets[i];
    root = meet(root, result.bracket);
    if (!root.is_bounded()) break;
    Jet g = contact(over, side.pair, driver, Jet::variable(root, follower_variable(), m));
    Interval gy = g.partial(follower_variable());
    if (gy.sign() == 0) break;
    std::vector<Interval> slope;
    for (std::size_t i = 0; i <= k; ++i) slope.push_back(meet(-(g.partial(i) / gy), result.slope[i]));
    result.slope = std::move(slope);
    result.bracket = root;
  }
  return result;
}

template <class Evaluate>
int ToleranceEvaluator::monotone_sign(const ToleranceLeaf& leaf, const Jet& over_leaf, int want,
                                      const Evaluate& evaluate) const {
  // For fixed values of the other dimensions the function is monotone in each dimension whose
  // partial derivative has a certain sign over the current face (a box, so moving one
  // coordinate at a time stays inside it): its smallest (want = +1) or largest (want = -1)
  // value over the face is on the sub-face with those dimensions at the chosen ends. On the
  // final face, the mean value theorem about its centre with the gradient enclosed over that
  // face bounds the rest.
  std::size_t k = varied_.size();
  ToleranceLeaf face;
  face.parameters = leaf.parameters;
  face.driver = leaf.driver;
  auto dimension = [&](std::size_t i) -> RationalInterval& { return i < k ? face.parameters[i] : face.driver; };
  Jet gradient = over_leaf;
  for (int round = 0; round < 4; ++round) {
    bool fixed = false;
    for (std::size_t i = 0; i <= k; ++i) {
      RationalInterval& r = dimension(i);
      if (r.lo == r.hi) continue;
      int s = gradient.partial(i).sign();
      if (s == 0) continue;
      Rational end = s == want ? r.lo : r.hi;
      r = {end, end};
      fixed = true;
    }
    if (!fixed) return 0;   // nothing new: the previous round's bound stands
    std::vector<Interval> box, centre;
    ToleranceLeaf middle_point;
    for (std::size_t i = 0; i < k; ++i) {
      box.push_back(enclose(face.parameters[i]));
      Rational c = middle(face.parameters[i]);
      centre.push_back(enclose(c));
      middle_point.parameters.push_back({c, c});
    }
    Rational dc = middle(face.driver);
    middle_point.driver = {dc, dc};
    ToleranceGeometry at = geometry(centre, false);
    Interval bound = evaluate(middle_point, at).value;
    ToleranceGeometry over = geometry(box, true);
    gradient = evaluate(face, over);
    for (std::size_t i = 0; i <= k; ++i) {
      const RationalInterval& r = dimension(i);
      if (r.lo != r.hi) bound = bound + gradient.partial(i) * offset(r);
    }
    bound = meet(bound, gradient.value);
    if (bound.sign() == want) return want;
  }
  return 0;
}

int ToleranceEvaluator::sign_over_leaf(const ToleranceLeaf& leaf, std::size_t pair, const Rational& y,
                                       ToleranceGeometry& over, ToleranceGeometry& centre) const {
  // Mean-value form about the leaf's centre in the parameters and the driver (the follower
  // held at y), intersected with the plain enclosure; when that is undecided, the monotone
  // form with the sign the function has at the centre.
  std::size_t k = varied_.size();
  Jet driver = Jet::variable(enclose(leaf.driver), driver_variable(), variables());
  Jet f = contact(over, pair, driver, Jet(enclose(y)));
  Interval at_centre = contact(centre, pair, Jet(enclose(middle(leaf.driver))), Jet(enclose(y))).value;
  Interval value = at_centre;
  for (std::size_t i = 0; i < k; ++i) value = value + f.partial(i) * offset(leaf.parameters[i]);
  value = value + f.partial(k) * offset(leaf.driver);
  int sign = meet(value, f.value).sign();
  if (sign != 0) return sign;
  int want = at_centre.sign();
  if (want == 0) return 0;
  return monotone_sign(leaf, f, want, [&](const ToleranceLeaf& face, ToleranceGeometry& g) {
    return contact(g, pair, Jet::variable(enclose(face.driver), driver_variable(), variables()), Jet(enclose(y)));
  });
}

void ToleranceEvaluator::check_witness(const ToleranceLeaf& leaf, ToleranceGeometry& over, ToleranceGeometry& at,
                                       const std::string& where) const {
  std::size_t k = varied_.size();
  if (leaf.witness_slopes.size() != k + 1)
    reject(where + ": the witness has " + std::to_string(leaf.witness_slopes.size()) + " slopes for " +
           std::to_string(k + 1) + " variables");
  // y* as a jet over the leaf: its value encloses y* over the leaf, its gradient is the slopes.
  std::vector<Interval> slopes;
  Interval value = enclose(*leaf.witness);
  for (std::size_t i = 0; i <= k; ++i) {
    slopes.push_back(enclose(leaf.witness_slopes[i]));
    value = value + slopes.back() * (i < k ? offset(leaf.parameters[i]) : offset(leaf.driver));
  }
  slopes.push_back(zero());
  Jet witness(value, slopes);
  Jet driver = Jet::variable(enclose(leaf.driver), driver_variable(), variables());
  Jet driver_centre(enclose(middle(leaf.driver)));
  for (int s = 0; s < 2; ++s) {
    const LeafSide& side = s == 0 ? leaf.lower : leaf.upper;
    const char* name = s == 0 ? "lower" : "upper";
    // y* within the side's bracket, where the side's function is monotone with its one root.
    Interval below = value - enclose(side.bracket.lo), above = enclose(side.bracket.hi) - value;
    if (below.sign() <= 0 || above.sign() <= 0)
      reject(where + ": the witness " + show(value) + " is not certainly inside the " + name + " side's bracket " +
             show(side.bracket));
    int inside = sign_over_leaf(leaf, side.pair, s == 0 ? side.bracket.hi : side.bracket.lo, over, at);
    if (!leaf.witness_margins.empty()) {
      // Check 6: the second-order Taylor form keeps the sign of the channel-side end with at
      // least the recorded margin (the verifier's own enclosure; the margin is only a claim).
      if (leaf.witness_margins.size() != 2) reject(where + ": the witness needs two second-order margins");
      const Rational& margin = leaf.witness_margins[static_cast<std::size_t>(s)];
      if (!(margin > 0)) reject(where + ": the " + name + " side's second-order margin " + to_exact_string(margin) + " is not positive");
      if (inside == 0)
        reject(where + ": the sign of the " + name + " side's contact function at its bracket's channel-side end is not certain");
      Interval e = second_order(leaf, s == 1);
      Interval beyond = inside > 0 ? e - enclose(margin) : enclose(-margin) - e;
      if (!beyond.is_bounded() || beyond.lower() < 0)
        reject(where + ": the witness is not certainly " + (s == 0 ? "above the lower" : "below the upper") +
               " side with margin " + to_exact_string(margin) + " (second-order form of its contact function: " +
               show(e) + ")");
    } else {
      // The side's function at y*(p, d): mean-value form about the leaf's centre (chain rule
      // through the jet), with the sign it has at the bracket's end on the channel's side.
      Jet h = contact(over, side.pair, driver, witness);
      Interval centred = contact(at, side.pair, driver_centre, Jet(enclose(*leaf.witness))).value;
      for (std::size_t i = 0; i < k; ++i) centred = centred + h.partial(i) * offset(leaf.parameters[i]);
      centred = centred + h.partial(k) * offset(leaf.driver);
      int sign = meet(centred, h.value).sign();
      if (sign == 0 && inside != 0)
        sign = monotone_sign(leaf, h, inside, [&](const ToleranceLeaf& face, ToleranceGeometry& g) {
          // y* over the face: exact at its centre plus the slopes times the face's offsets.
          Interval y = enclose(*leaf.witness);
          for (std::size_t i = 0; i < k; ++i)
            y = y + slopes[i] * enclose(RationalInterval{face.parameters[i].lo - middle(leaf.parameters[i]),
                                                         face.parameters[i].hi - middle(leaf.parameters[i])});
          y = y + slopes[k] * enclose(RationalInterval{face.driver.lo - middle(leaf.driver), face.driver.hi - middle(leaf.driver)});
          return contact(g, side.pair, Jet::variable(enclose(face.driver), driver_variable(), variables()), Jet(y, slopes));
        });
      if (sign == 0 || sign != inside)
        reject(where + ": the witness is not certainly " + (s == 0 ? "above the lower" : "below the upper") +
               " side (its contact function there encloses to " + show(meet(centred, h.value)) + ")");
    }
    // No root between y* and the bracket's end on the channel's side: the function is monotone
    // there (its follower derivative of one certain sign over the leaf, y* taking every value
    // of its enclosure) and has the same sign at both ends. So the side, the root nearest the
    // channel in the bracket, lies strictly beyond y*.
    Interval between = s == 0 ? hull2(value, enclose(side.bracket.hi)) : hull2(enclose(side.bracket.lo), value);
    Interval fy = contact(over, side.pair, driver, Jet::variable(between, follower_variable(), variables()))
                      .partial(follower_variable());
    if (fy.sign() == 0)
      reject(where + ": the " + name + " side's contact function may be stationary in the follower between the witness and " +
             "the bracket's end " + show(between) + " (derivative " + show(fy) + "): another root may lie beyond the witness");
  }
}

Interval ToleranceEvaluator::second_order(const ToleranceLeaf& leaf, bool upper) const {
  // h(x) = F(side, d, y*(x)) over the leaf's dimensions x = (p, d): Taylor's theorem with the
  // Lagrange remainder about the centre c, h(x) in h(c) + grad h(c) (x - c) + (x - c)' H (x - c) / 2
  // with H the Hessian enclosed over the whole leaf (the segment from c to x lies in it). The
  // value and gradient at c are narrow (no width enters them); only H carries the dependency
  // problem, and it is multiplied by the squared half-widths.
  std::size_t k = varied_.size();
  const LeafSide& side = upper ? leaf.upper : leaf.lower;
  if (side.pair >= claim_.sides.size() || leaf.witness_slopes.size() != k + 1 || !leaf.witness)
    reject("a second-order witness test needs the side and k + 1 witness slopes");
  std::vector<RationalInterval> dims = leaf.parameters;
  dims.push_back(leaf.driver);
  auto evaluate = [&](bool at_centre) {
    std::vector<Jet2> variable;
    for (std::size_t i = 0; i <= k; ++i)
      variable.push_back(Jet2::variable(at_centre ? enclose(middle(dims[i])) : enclose(dims[i]), i));
    std::vector<Jet2> all(model_->parameter_count(), Jet2(0));
    for (std::size_t i = 0; i < k; ++i) all[varied_[i]] = variable[i];
    GeometryOf<Jet2> g;
    g.parameters = model_->parameter_values(all);
    pose_pivots(g);
    Jet2 y(enclose(*leaf.witness));
    for (std::size_t i = 0; i <= k; ++i)
      if (leaf.witness_slopes[i] != 0)
        y = y + Jet2(enclose(leaf.witness_slopes[i])) * (variable[i] - Jet2(enclose(middle(dims[i]))));
    return contact_of(g, side.pair, variable[k], y);
  };
  Jet2 over = evaluate(false);
  if (!over.smooth) return over.value;
  Jet2 at = evaluate(true);
  if (!at.smooth) return over.value;
  std::vector<Interval> offsets;
  for (const RationalInterval& r : dims) offsets.push_back(offset(r));
  Interval bound = at.value;
  for (std::size_t a = 0; a < at.index.size(); ++a) bound = bound + at.gradient[a] * offsets[at.index[a]];
  Interval half(Rational(1, 2));
  for (std::size_t a = 0; a < over.index.size(); ++a) {
    const Interval& oa = offsets[over.index[a]];
    Interval square;
    mpfi_sqr(square.get(), oa.get());
    bound = bound + half * over.second(a, a) * square;
    for (std::size_t b = a + 1; b < over.index.size(); ++b) bound = bound + over.second(a, b) * (oa * offsets[over.index[b]]);
  }
  return meet(bound, over.value);
}

Interval ToleranceEvaluator::play(const ToleranceLeaf& leaf, const SideEnclosure& lower, const SideEnclosure& upper) const {
  std::size_t k = varied_.size();
  Interval value = upper.centre - lower.centre;
  for (std::size_t i = 0; i < k; ++i) value = value + (upper.slope[i] - lower.slope[i]) * offset(leaf.parameters[i]);
  value = value + (upper.slope[k] - lower.slope[k]) * offset(leaf.driver);
  return meet(value, upper.bracket - lower.bracket);
}

void ToleranceEvaluator::check_leaf(const ToleranceLeaf& leaf, std::size_t index) const {
  std::string where = "leaf " + std::to_string(index);
  std::size_t k = varied_.size();
  if (leaf.parameters.size() != k)
    reject(where + ": " + std::to_string(leaf.parameters.size()) + " parameter intervals for " + std::to_string(k) +
           " varied parameters");
  std::vector<Interval> box, centre;
  for (const RationalInterval& p : leaf.parameters) {
    box.push_back(enclose(p));
    centre.push_back(enclose(middle(p)));
  }
  ToleranceGeometry over = geometry(box, true);
  ToleranceGeometry at = geometry(centre, false);
  check_leaf(leaf, index, over, at);
}

void ToleranceEvaluator::check_leaf(const ToleranceLeaf& leaf, std::size_t index, ToleranceGeometry& over,
                                    ToleranceGeometry& at) const {
  std::string where = "leaf " + std::to_string(index);
  if (leaf.parameters.size() != varied_.size()) reject(where + ": wrong number of parameter intervals");
  bool monotone = !leaf.witness;
  SideEnclosure lower = check_side(leaf, leaf.lower, over, at, where + " (lower side)", monotone);
  SideEnclosure upper = check_side(leaf, leaf.upper, over, at, where + " (upper side)", monotone);
  if (leaf.witness) {
    check_witness(leaf, over, at, where);
    if (witness_proved_.size() <= index) witness_proved_.resize(index + 1);
    witness_proved_[index] = leaf;
    return;
  }
  Interval gap = play(leaf, lower, upper);
  if (gap.sign() <= 0)
    reject(where + ": the channel is not certainly open: the play between the sides encloses to " + show(gap) +
           " over driver " + show(leaf.driver));
}

bool ToleranceEvaluator::witness_proved(std::size_t index, const ToleranceLeaf& leaf) const {
  if (index >= witness_proved_.size() || !witness_proved_[index]) return false;
  const ToleranceLeaf& p = *witness_proved_[index];
  auto same = [](const RationalInterval& a, const RationalInterval& b) { return a.lo == b.lo && a.hi == b.hi; };
  auto same_side = [&](const LeafSide& a, const LeafSide& b) {
    return a.pair == b.pair && same(a.bracket, b.bracket) && same(a.centre, b.centre);
  };
  if (p.parameters.size() != leaf.parameters.size() || !same(p.driver, leaf.driver) || bool(p.follower) != bool(leaf.follower) ||
      !same_side(p.lower, leaf.lower) || !same_side(p.upper, leaf.upper) || p.witness != leaf.witness ||
      p.witness_slopes != leaf.witness_slopes || p.witness_margins != leaf.witness_margins)
    return false;
  for (std::size_t i = 0; i < p.parameters.size(); ++i)
    if (!same(p.parameters[i], leaf.parameters[i])) return false;
  return true;
}

std::vector<ToleranceEvaluator::Region> ToleranceEvaluator::check_cover() const {
  std::size_t k = varied_.size();
  bool interference = interference_claim();
  std::vector<RationalInterval> region = claim_.box;
  region.push_back(claim_.range);
  if (interference) region.push_back(*claim_.follower_range);
  std::size_t last = interference ? k + 1 : k;   // the last dimension
  std::vector<char> used(claim_.leaves.size(), 0);
  std::size_t next = 0;
  auto dimension = [&](const std::string& name) -> std::size_t {
    if (name == "driver") return k;
    if (name == "follower" && interference) return k + 1;
    for (std::size_t i = 0; i < k; ++i)
      if (claim_.varied[i] == name) return i;
    reject("tree node " + std::to_string(next) + ": '" + name + "' is neither a varied parameter nor the driver" +
           (interference ? " nor the follower" : ""));
  };
  auto name_of = [&](std::size_t d) {
    return d == k ? std::string("driver") : d == k + 1 ? std::string("follower") : claim_.varied[d];
  };
  // Iterative preorder walk (the tree can be deep).
  std::vector<Region> regions;
  std::vector<std::vector<RationalInterval>> stack{region};
  while (!stack.empty()) {
    std::vector<RationalInterval> r = std::move(stack.back());
    stack.pop_back();
    if (next >= claim_.tree.size()) reject("the subdivision tree ends early: part of the box is not covered");
    const ToleranceTreeNode& node = claim_.tree[next];
    if (node.leaf) {
      if (node.index >= claim_.leaves.size()) reject("tree node " + std::to_string(next) + ": no leaf " + std::to_string(node.index));
      if (used[node.index]) reject("leaf " + std::to_string(node.index) + " is used twice in the tree");
      used[node.index] = 1;
      const ToleranceLeaf& leaf = claim_.leaves[node.index];
      if (leaf.parameters.size() != k) reject("leaf " + std::to_string(node.index) + ": wrong number of parameter intervals");
      if (bool(leaf.follower) != interference)
        reject("leaf " + std::to_string(node.index) + (interference ? " has no follower interval (a no_interference leaf needs one)"
                                                                    : " has a follower interval, but the claim is no_jam"));
      for (std::size_t d = 0; d <= last; ++d) {
        const RationalInterval& have = d == k + 1 ? *leaf.follower : d == k ? leaf.driver : leaf.parameters[d];
        if (!contains(have, r[d]))
          reject("coverage gap: leaf " + std::to_string(node.index) + " covers " + name_of(d) + " " + show(have) +
                 " but its region of the box needs " + show(r[d]));
      }
      regions.push_back(Region{node.index, std::move(r)});
      ++next;
      continue;
    }
    std::size_t d = dimension(node.dimension);
    if (!(r[d].lo < node.value && node.value < r[d].hi))
      reject("tree node " + std::to_string(next) + ": the split of " + name_of(d) + " at " + to_exact_string(node.value) +
             " is not inside " + show(r[d]));
    ++next;
    std::vector<RationalInterval> low = r, high = std::move(r);
    low[d].hi = node.value;
    high[d].lo = node.value;
    stack.push_back(std::move(high));   // the lower part comes first in preorder
    stack.push_back(std::move(low));
  }
  if (next != claim_.tree.size()) reject("the subdivision tree has " + std::to_string(claim_.tree.size() - next) + " extra nodes");
  for (std::size_t i = 0; i < used.size(); ++i)
    if (!used[i]) reject("leaf " + std::to_string(i) + " is not in the subdivision tree");
  return regions;
}

// ----------------------------------------------------------------------------- no_interference

namespace {

using IV = kernels::Vector<Interval>;

Interval sq(const Interval& x) { return x * x; }
Interval cross_iv(const IV& u, const IV& v) { return u.x * v.y - u.y * v.x; }
IV minus_iv(const IV& u, const IV& v) { return {u.x - v.x, u.y - v.y}; }

// A posed edge over a leaf (every coordinate an enclosure).
struct Posed {
  std::string name;   // for messages: "'label' (loop l edge e)"
  std::size_t loop = 0, edge = 0;
  bool arc = false, ccw = false;
  IV s, t, c;
  Interval r2, r;
  EdgeBox box;   // enclosure of the edge's points (bounding box)
};

// The side of the arc's chord on which the arc lies (strictly, except its ends): a
// counter-clockwise arc from s to t lies to the right of the directed chord s -> t, a clockwise
// one to its left.
int arc_side(const Posed& e) { return e.ccw ? -1 : 1; }
// +1/-1: p certainly on the arc's side of the chord / on the other side; 0: undecided.
int chord_side(const Posed& e, const IV& p) {
  int side = cross_iv(minus_iv(e.t, e.s), minus_iv(p, e.s)).sign();
  return side == 0 ? 0 : (side == arc_side(e) ? 1 : -1);
}

void bound(Posed& e) { e.box = edge_box(e, false); }   // a full circle (s = t) keeps all four extreme points



// The points where the supports of an arc and another edge meet (two circles, or a circle and a
// line), each certainly outside one of the two edges' extents (beyond an arc's chord, or past a
// segment's end): then the closed edges have no common point although their supports meet
// (separated() only sees supports apart or nested; Geneva's lock arcs have intersecting circles
// and disjoint arcs). A tangency of the supports, or a point not certainly outside: false.
bool meets_outside(const Posed& a, const Posed& b) {
  if (!a.arc && !b.arc) return false;   // separated() decides two segments
  auto dot = [](const IV& u, const IV& v) { return u.x * v.x + u.y * v.y; };
  auto outside = [&](const Posed& e, const IV& q) {   // q, on e's support, certainly not on e
    if (e.arc) return chord_side(e, q) < 0;
    IV d = minus_iv(e.t, e.s);
    Interval along = dot(minus_iv(q, e.s), d);
    return along.sign() < 0 || (along - dot(d, d)).sign() > 0;
  };
  // The meeting points foot +- h w, with h^2 = h2 (w: perp(cc) for two circles, d for a line).
  IV foot, w;
  Interval h2;
  if (a.arc && b.arc) {
    IV cc = minus_iv(b.c, a.c);
    Interval d2 = dot(cc, cc);
    if (d2.sign() <= 0) return false;
    Interval m = (a.r2 - b.r2 + d2) / (Interval(Rational(2)) * d2);   // |q - a.c| = ra, |q - b.c| = rb
    foot = {a.c.x + m * cc.x, a.c.y + m * cc.y};
    w = {-cc.y, cc.x};
    h2 = a.r2 / d2 - m * m;
  } else {
    const Posed& arc = a.arc ? a : b;
    const Posed& seg = a.arc ? b : a;
    IV d = minus_iv(seg.t, seg.s);
    Interval dd = dot(d, d);
    if (dd.sign() <= 0) return false;
    Interval m = dot(minus_iv(arc.c, seg.s), d) / dd;   // the foot of the centre on the line
    foot = {seg.s.x + m * d.x, seg.s.y + m * d.y};
    IV fc = minus_iv(foot, arc.c);
    w = d;
    h2 = (arc.r2 - dot(fc, fc)) / dd;
  }
  int s = h2.sign();
  if (s < 0) return true;   // the supports do not meet
  if (s == 0) return false;
  Interval h = model_detail::Arithmetic<Jet>::sqrt(Jet(h2)).value;
  for (int k = 0; k < 2; ++k) {
    Interval f = k == 0 ? h : -h;
    IV q{foot.x + f * w.x, foot.y + f * w.y};
    if (!outside(a, q) && !outside(b, q)) return false;
  }
  return true;
}

// Certainly no common point of the two closed edges (plain enclosures).
bool apart(const Posed& a, const Posed& b) {
  if (boxes_apart(a.box, b.box)) return true;   // boxes (exact comparisons of their ends, as b - a > 0 was)
  auto edge = [](const Posed& p) {
    EdgeT<Interval> e;
    e.arc = p.arc;
    e.ccw = p.ccw;
    e.s = p.s;
    e.t = p.t;
    e.c = p.c;
    e.r2 = p.r2;
    e.r = p.r;
    return e;
  };
  return separated(edge(a), edge(b), [](const Interval& x) { return x.sign(); }) || meets_outside(a, b);
}


}  // namespace

namespace {


// The point p (rotated so that the ray is +x from the origin) against the edges: the number of
// crossings of the ray, or -1 when a crossing cannot be decided.
int crossings(const IV& p, const std::vector<Posed>& edges, int direction) {
  auto turn = [&](const IV& q) -> IV {
    IV v = minus_iv(q, p);
    switch (direction) {
      case 0: return v;
      case 1: return {-v.x, -v.y};
      case 2: return {v.y, -v.x};
      default: return {-v.y, v.x};
    }
  };
  int count = 0;
  for (const Posed& e0 : edges) {
    Posed e = e0;   // rotations keep the arcs' orientation
    e.s = turn(e0.s);
    e.t = turn(e0.t);
    e.c = turn(e0.c);
    if (!e.arc) {
      int ys = e.s.y.sign(), yt = e.t.y.sign();
      if (ys == 0 || yt == 0) return -1;
      if (ys == yt) continue;
      Interval x = e.s.x - e.s.y * (e.t.x - e.s.x) / (e.t.y - e.s.y);
      int sx = x.sign();
      if (sx == 0) return -1;
      count += sx > 0;
      continue;
    }
    Interval h2 = e.r2 - sq(e.c.y);
    int sh = h2.sign();
    if (sh < 0) continue;
    if (sh == 0) return -1;
    Interval h = model_detail::Arithmetic<Jet>::sqrt(Jet(h2)).value;
    for (int k = 0; k < 2; ++k) {
      IV q{k == 0 ? e.c.x + h : e.c.x - h, zero()};
      int sx = q.x.sign();
      if (sx == 0) return -1;
      if (sx < 0) continue;
      int on = chord_side(e, q);
      if (on == 0) return -1;
      count += on > 0;
    }
  }
  return count;
}

}  // namespace

std::string ToleranceEvaluator::apart_failure(const ToleranceLeaf& leaf) const { return apart_failure(leaf, nullptr); }

std::string ToleranceEvaluator::apart_failure(const ToleranceLeaf& leaf, std::optional<ToleranceGeometry>* at_point) const {
  std::size_t k = varied_.size();
  if (leaf.parameters.size() != k) return "wrong number of parameter intervals";
  if (!leaf.follower) return "no follower interval";
  auto is_point = [](const RationalInterval& r) { return r.lo == r.hi; };
  bool point = is_point(leaf.driver) && is_point(*leaf.follower) &&
               std::all_of(leaf.parameters.begin(), leaf.parameters.end(), is_point);
  if (!point) at_point = nullptr;
  const Model& m = model_->nominal();
  auto pose_part = [&](ToleranceGeometry& g, std::size_t part, const Jet& coordinate) {
    std::vector<std::vector<Posed>> loops;
    bool is_driver = part == driver_;
    bool rotates = is_driver ? driver_rotates_ : follower_rotates_;
    Jet c = rotates ? model_detail::Arithmetic<Jet>::cos(coordinate) : coordinate;
    Jet s = rotates ? model_detail::Arithmetic<Jet>::sin(coordinate) : coordinate;
    const kernels::Vector<Jet>& pivot = is_driver ? g.driver_pivot : g.follower_pivot;
    const kernels::Vector<Jet>& direction = is_driver ? g.driver_direction : g.follower_direction;
    const Part& p = m.parts[part];
    for (std::size_t l = 0; l < p.loops.size(); ++l) {
      std::vector<Posed> loop;
      for (std::size_t e = 0; e < p.loops[l].edges.size(); ++e) {
        auto key = std::make_tuple(part, l, e);
        auto it = g.edges.find(key);
        if (it == g.edges.end()) it = g.edges.emplace(key, model_->edge_value(part, l, e, g.parameters)).first;
        const model_detail::EdgeValue<Jet>& v = it->second;
        Posed q;
        q.name = "'" + p.loops[l].edges[e].label + "' (loop " + std::to_string(l) + " edge " + std::to_string(e) + ")";
        q.loop = l;
        q.edge = e;
        q.arc = v.arc;
        q.ccw = v.ccw;
        auto pose = [&](const kernels::Vector<Jet>& at) {
          kernels::Vector<Jet> w = placed(at, rotates, pivot, direction, coordinate, c, s);   // as posed()
          return IV{w.x.value, w.y.value};
        };
        q.s = pose(v.source);
        q.t = pose(v.target);
        if (q.arc) {
          q.c = pose(v.center);
          q.r2 = v.radius_squared.value;
          q.r = model_detail::Arithmetic<Jet>::sqrt(Jet(q.r2)).value;
        }
        bound(q);
        loop.push_back(std::move(q));
      }
      loops.push_back(std::move(loop));
    }
    return loops;
  };
  auto flat = [](const std::vector<std::vector<Posed>>& loops) {
    std::vector<Posed> all;
    for (const auto& l : loops) all.insert(all.end(), l.begin(), l.end());
    return all;
  };
  std::pair<std::vector<std::vector<Posed>>, std::vector<std::vector<Posed>>> point_loops;
  // 1. Over the whole leaf: no edge of one part meets an edge of the other. The boundaries are
  //    then apart for every point of the (connected) leaf, so each loop of a part stays on one
  //    side of the other part throughout.
  {
    std::vector<Interval> box, centre;
    for (const RationalInterval& p : leaf.parameters) {
      box.push_back(enclose(p));
      centre.push_back(enclose(middle(p)));
    }
    std::optional<ToleranceGeometry> own;
    std::optional<ToleranceGeometry>& kept = at_point ? *at_point : own;
    if (!kept) kept = geometry(box, false);
    ToleranceGeometry& g = *kept;
    point_loops.first = pose_part(g, driver_, Jet(enclose(leaf.driver)));
    point_loops.second = pose_part(g, follower_, Jet(enclose(*leaf.follower)));
    std::vector<Posed> a = flat(point_loops.first);
    std::vector<Posed> b = flat(point_loops.second);
    // Pairs the plain enclosures do not separate are tried again in mean-value form (the
    // geometry with its gradient over the leaf, evaluated once and only when needed).
    std::optional<ToleranceGeometry> over, at;
    std::vector<Interval> offsets;
    std::map<std::tuple<bool, std::size_t, std::size_t>, EdgeT<MeanValue>> cache;
    std::size_t m = variables();
    Jet driver_over = Jet::variable(enclose(leaf.driver), driver_variable(), m);
    Jet follower_over = Jet::variable(enclose(*leaf.follower), follower_variable(), m);
    Jet driver_at(enclose(middle(leaf.driver))), follower_at(enclose(middle(*leaf.follower)));
    auto mean_value_edge = [&](bool is_driver, const Posed& p) -> const EdgeT<MeanValue>& {
      auto key = std::make_tuple(is_driver, p.loop, p.edge);
      auto it = cache.find(key);
      if (it != cache.end()) return it->second;
      if (!over) {
        over = geometry(box, true);
        at = geometry(centre, false);
        for (const RationalInterval& r : leaf.parameters) offsets.push_back(offset(r));
        offsets.push_back(offset(leaf.driver));
        offsets.push_back(offset(*leaf.follower));
      }
      std::size_t part = is_driver ? driver_ : follower_;
      model_detail::EdgeValue<Jet> vo = model_->edge_value(part, p.loop, p.edge, over->parameters);
      model_detail::EdgeValue<Jet> va = model_->edge_value(part, p.loop, p.edge, at->parameters);
      const Jet& co = is_driver ? driver_over : follower_over;
      const Jet& ca = is_driver ? driver_at : follower_at;
      auto pose = [&](const kernels::Vector<Jet>& qo, const kernels::Vector<Jet>& qa) {
        kernels::Vector<Jet> wo = posed(*over, is_driver, qo, co), wa = posed(*at, is_driver, qa, ca);
        return kernels::Vector<MeanValue>{MeanValue{wo.x, wa.x.value}, MeanValue{wo.y, wa.y.value}};
      };
      EdgeT<MeanValue> e;
      e.arc = vo.arc;
      e.ccw = vo.ccw;
      e.s = pose(vo.source, va.source);
      e.t = pose(vo.target, va.target);
      if (e.arc) {
        e.c = pose(vo.center, va.center);
        e.r2 = MeanValue{vo.radius_squared, va.radius_squared.value};
        e.r = MeanValue{model_detail::Arithmetic<Jet>::sqrt(vo.radius_squared),
                        model_detail::Arithmetic<Jet>::sqrt(va.radius_squared).value};
      }
      return cache.emplace(key, std::move(e)).first->second;
    };
    auto mean_value_sign = [&](const MeanValue& x) {
      Interval value = x.at;
      for (std::size_t i = 0; i < offsets.size(); ++i) value = value + x.over.partial(i) * offsets[i];
      return meet(value, x.over.value).sign();
    };
    for (std::size_t i = 0; i < a.size(); ++i)
      for (std::size_t j = 0; j < b.size(); ++j)
        if (!apart(a[i], b[j]) && !separated(mean_value_edge(true, a[i]), mean_value_edge(false, b[j]), mean_value_sign))
          return a[i].name + " of '" + claim_.driver + "' and " + b[j].name + " of '" + claim_.follower +
                 "' are not certainly apart over driver " + show(leaf.driver) + ", follower " +
                 show(*leaf.follower);
  }
  // 2. At the leaf's centre: one vertex of every loop of each part certainly outside the other
  //    part (ray crossings of certain parity). With 1., the parts' boundaries never meet and no
  //    boundary point lies in the other part, so the closed parts are disjoint over the leaf.
  //    A point leaf is its own centre: the parts as posed in 1. (the same enclosures).
  if (!point) {
    std::vector<Interval> centre;
    for (const RationalInterval& p : leaf.parameters) centre.push_back(enclose(middle(p)));
    ToleranceGeometry g = geometry(centre, false);
    point_loops.first = pose_part(g, driver_, Jet(enclose(middle(leaf.driver))));
    point_loops.second = pose_part(g, follower_, Jet(enclose(middle(*leaf.follower))));
  }
  const auto& la = point_loops.first;
  const auto& lb = point_loops.second;
  for (int side = 0; side < 2; ++side) {
    const auto& loops = side == 0 ? la : lb;
    std::vector<Posed> other = flat(side == 0 ? lb : la);
    for (std::size_t l = 0; l < loops.size(); ++l) {
      if (loops[l].empty()) continue;
      int count = -1;
      for (int direction = 0; direction < 4 && count < 0; ++direction) count = crossings(loops[l][0].s, other, direction);
      const std::string& name = side == 0 ? claim_.driver : claim_.follower;
      const std::string& other_name = side == 0 ? claim_.follower : claim_.driver;
      if (count < 0)
        return "at the leaf's centre, whether loop " + std::to_string(l) + " of '" + name + "' lies inside '" +
               other_name + "' is undecided";
      if (count % 2 == 1)
        return "at the leaf's centre, loop " + std::to_string(l) + " of '" + name + "' lies inside '" + other_name +
               "': the parts interfere";
    }
  }
  return "";
}

void ToleranceEvaluator::check_apart(const ToleranceLeaf& leaf, std::size_t index) const {
  std::string failure = apart_failure(leaf);
  if (!failure.empty()) reject("leaf " + std::to_string(index) + ": the parts may interfere: " + failure);
}

std::string check_tolerance(const Certificate& c, const Model& model, std::string_view model_text,
                            std::string& not_proved) {
  not_proved.clear();
  if (!c.tolerance) reject("a tolerance certificate needs its 'tolerance' section");
  const ToleranceClaim& claim = *c.tolerance;
  for (const ParameterValue& value : c.parameters)
    if (value.overridden) reject("a tolerance certificate varies parameters about their nominal values: '" + value.name + "' is overridden");
  bool pair_ok = (claim.driver == c.first && claim.follower == c.second) || (claim.driver == c.second && claim.follower == c.first);
  if (!pair_ok) reject("the driver and follower are not the certificate's pair");
  auto parametric = std::make_shared<const model_detail::ParametricModel>(
      model_detail::ParametricModel::read(model_text, model.source));
  ToleranceEvaluator evaluator(parametric, claim);
  evaluator.check_cover();
  std::string unit = model.parts[*model.find_part(claim.driver)].motion.kind == Motion::Kind::rotation ? " rad" : " mm";
  if (evaluator.interference_claim()) {
    for (std::size_t i = 0; i < claim.leaves.size(); ++i) evaluator.check_apart(claim.leaves[i], i);
    std::string follower_unit =
        model.parts[*model.find_part(claim.follower)].motion.kind == Motion::Kind::rotation ? " rad" : " mm";
    return "for every parameter vector within " + to_exact_string(claim.scale) + " x the tolerances of " +
           std::to_string(claim.varied.size()) + " parameters, with '" + claim.driver + "' over " + show(claim.range) +
           unit + " and '" + claim.follower + "' over " + show(*claim.follower_range) + follower_unit +
           ", the two parts are apart: they never interfere (" + std::to_string(claim.leaves.size()) + " leaves)";
  }
  for (std::size_t i = 0; i < claim.leaves.size(); ++i) evaluator.check_leaf(claim.leaves[i], i);
  // Check 7: checks 1-6 prove the named sides apart, not that they bound the channel; the free
  // path proves the claim itself.
  not_proved = evaluator.free_path_failure();
  return "for every parameter vector within " + to_exact_string(claim.scale) + " x the tolerances of " +
         std::to_string(claim.varied.size()) + " parameters, driving '" + claim.driver + "' over " + show(claim.range) + unit +
         ", the named contact sides of '" + claim.driver + "' and '" + claim.follower +
         "' stay apart over every leaf of the box x range (" + std::to_string(claim.leaves.size()) + " leaves)";
}

// The claim holds the model's toleranced parameters that it does not vary at their nominal
// values; the verdict names them (session 43: a certificate with a toleranced parameter dropped
// from `varied`, its box and leaves verified "within 1 x the tolerances of 25 parameters ...
// they never interfere" on a model of 26, and did not say which one was held fixed).
std::string held_at_nominal(const Certificate& certificate, const Model& model) {
  if (!certificate.tolerance) return {};
  const std::vector<std::string>& varied = certificate.tolerance->varied;
  std::string held;
  std::size_t held_count = 0;
  for (const Parameter& p : model.parameters) {
    if (!(p.range.lo < p.range.hi)) continue;
    if (std::find(varied.begin(), varied.end(), p.name) != varied.end()) continue;
    if (++held_count <= 3) held += (held.empty() ? "'" : ", '") + p.name + "'";
  }
  if (held_count == 0) return {};
  if (held_count > 3) held += " and " + std::to_string(held_count - 3) + " more";
  return "; the model's other toleranced parameters (" + std::to_string(held_count) + ": " + held +
         ") are held at their nominal values";
}

}  // namespace hipair::verify
