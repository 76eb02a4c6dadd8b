// The first contact along a straight motion in (x, y, w) (see motion.hpp).
#include "sliced/motion.hpp"

#include <hipair/error.hpp>
#include <hipair/overlap.hpp>

#include <algorithm>
#include <functional>
#include <optional>

namespace hipair::sliced {
namespace {

namespace algebra = cspace::algebra;
using algebra::Real;

// ---------------------------------------------------------------- polynomials in u
// Integer coefficients: the motion's inputs are scaled to integers first (lengths by a common
// denominator L, the tangent w by its own W), so no rational canonicalisation happens here.
using UPoly = std::vector<mpz_class>;   // ascending powers of u

UPoly constant(const mpz_class& r) { return UPoly{r}; }
UPoly operator+(const UPoly& a, const UPoly& b) {
  UPoly out(std::max(a.size(), b.size()), mpz_class(0));
  for (std::size_t i = 0; i < a.size(); ++i) out[i] += a[i];
  for (std::size_t i = 0; i < b.size(); ++i) out[i] += b[i];
  return out;
}
UPoly operator-(const UPoly& a) {
  UPoly out = a;
  for (auto& c : out) c = -c;
  return out;
}
UPoly operator-(const UPoly& a, const UPoly& b) { return a + (-b); }
UPoly operator*(const UPoly& a, const UPoly& b) {
  if (a.empty() || b.empty()) return {};
  UPoly out(a.size() + b.size() - 1, mpz_class(0));
  for (std::size_t i = 0; i < a.size(); ++i)
    if (sgn(a[i]) != 0)
      for (std::size_t j = 0; j < b.size(); ++j) out[i + j] += a[i] * b[j];
  return out;
}
UPoly operator*(const mpz_class& k, const UPoly& a) {
  UPoly out = a;
  for (auto& c : out) c *= k;
  return out;
}
bool is_zero(const UPoly& a) {
  return std::all_of(a.begin(), a.end(), [](const mpz_class& c) { return sgn(c) == 0; });
}
algebra::Polynomial integer(const UPoly& p) {
  algebra::Polynomial out = p;
  algebra::trim(out);
  return out;
}

struct HVec {
  UPoly x, y;
};
HVec operator-(const HVec& a, const HVec& b) { return {a.x - b.x, a.y - b.y}; }
HVec operator+(const HVec& a, const HVec& b) { return {a.x + b.x, a.y + b.y}; }
UPoly cross(const HVec& a, const HVec& b) { return a.x * b.y - a.y * b.x; }
UPoly dot(const HVec& a, const HVec& b) { return a.x * b.x + a.y * b.y; }

// Sign of a polynomial at an algebraic root.
int sign_of(const UPoly& p, const Real& u) {
  algebra::Polynomial q = integer(p);
  if (q.empty()) return 0;
  return algebra::sign_at(q, u);
}

// A direction `d` in an arc's closed ccw sector (from -> to), by signs.
bool in_closed_sector(int s1, int s2, bool reflex, bool full) {
  if (full) return true;
  return reflex ? (s1 >= 0 || s2 >= 0) : (s1 >= 0 && s2 >= 0);
}

// A contact candidate: its polynomial, the polynomials its validity depends on, its test.
struct Candidate {
  UPoly contact;
  std::vector<UPoly> conditions;
  std::function<bool(const Real&)> valid;
  MotionContact features;
};

Rational l1(const Point& p) { return abs(p.x) + abs(p.y); }

// Certainly no root in [0, 1]: the Bernstein coefficients on [0, 1] all have one strict sign
// (the polynomial is their convex combination there). b_k = sum_{i <= k} C(k, i)/C(n, i) p_i
// (n the degree), scaled by n!: B_k = sum_{i <= k} C(k, i) i! (n - i)! p_i. Exact.
bool no_root_in_unit_interval(const UPoly& p) {
  if (p.empty()) return false;
  const std::size_t n = p.size() - 1;
  std::vector<mpz_class> factorial(n + 1, mpz_class(1));
  for (std::size_t i = 1; i <= n; ++i) factorial[i] = factorial[i - 1] * static_cast<unsigned long>(i);
  int sign = 0;
  for (std::size_t k = 0; k <= n; ++k) {
    mpz_class b = 0, choose = 1;   // C(k, i)
    for (std::size_t i = 0; i <= k; ++i) {
      if (i > 0) choose = choose * static_cast<unsigned long>(k - i + 1) / static_cast<unsigned long>(i);
      if (sgn(p[i]) != 0) b += choose * factorial[i] * factorial[n - i] * p[i];
    }
    int s = sgn(b);
    if (s == 0 || (sign != 0 && s != sign)) return false;
    sign = s;
  }
  return true;
}

}  // namespace

std::pair<Rational, Rational> chart_rotation(const Rational& w, bool flip) {
  Rational d = 1 + w * w;
  Rational c = (1 - w * w) / d, s = 2 * w / d;
  if (flip) return {-c, -s};
  return {c, s};
}

bool parts_apart(const Part& fixed, const Part& free, const Rational& c, const Rational& s, const Rational& x,
                 const Rational& y) {
  auto relation = part_overlap(fixed, Placement{}, free, placement_about(free.motion.pivot, c, s, Point{x, y})).relation;
  return relation == PartRelation::apart;
}

MotionChecker::MotionChecker(const Model& model, std::size_t fixed, std::size_t free)
    : model_(&model), fixed_index_(fixed), free_index_(free) {
  pivot_ = model.parts[free].motion.pivot;
  auto collect = [&](const Part& part, std::size_t index, Features& out, const Point& origin, Rational& reach) {
    reach = 0;
    for (std::size_t l = 0; l < part.loops.size(); ++l)
      for (std::size_t k = 0; k < part.loops[l].edges.size(); ++k) {
        const Edge& e = part.loops[l].edges[k];
        Point source{Rational(e.source.x - origin.x), Rational(e.source.y - origin.y)};
        Point target{Rational(e.target.x - origin.x), Rational(e.target.y - origin.y)};
        if (!e.is_full_circle()) {
          out.vertices.push_back(Vertex{source, FeatureIdentity{index, l, k, FeatureKind::vertex}});
          reach = std::max(reach, l1(source));
        }
        if (!e.is_arc()) {
          out.segments.push_back(Segment{source, target, FeatureIdentity{index, l, k, FeatureKind::segment}});
          continue;
        }
        Arc arc;
        arc.center = Point{Rational(e.center.x - origin.x), Rational(e.center.y - origin.y)};
        Point a{Rational(source.x - arc.center.x), Rational(source.y - arc.center.y)};
        Point b{Rational(target.x - arc.center.x), Rational(target.y - arc.center.y)};
        arc.from = e.ccw ? a : b;
        arc.to = e.ccw ? b : a;
        arc.radius_squared = e.radius_squared;
        arc.full = e.is_full_circle();
        arc.reflex = !arc.full && sgn(arc.from.x * arc.to.y - arc.from.y * arc.to.x) < 0;
        arc.id = FeatureIdentity{index, l, k, FeatureKind::arc};
        out.arcs.push_back(arc);
        reach = std::max(reach, Rational(l1(arc.center) + (1 + e.radius_squared) / 2));   // r <= (1 + r^2)/2
      }
  };
  collect(model.parts[fixed], fixed, fixed_, Point{Rational(0), Rational(0)}, reach_fixed_);
  collect(model.parts[free], free, free_, pivot_, reach_free_);
  // the common denominator of every coordinate used (points, arc centres and sector vectors)
  lengths_denominator_ = 1;
  auto add = [&](const Point& p) {
    for (const Rational* r : {&p.x, &p.y}) mpz_lcm(lengths_denominator_.get_mpz_t(), lengths_denominator_.get_mpz_t(), r->get_den_mpz_t());
  };
  add(pivot_);
  for (const Features* f : {&fixed_, &free_}) {
    for (const auto& v : f->vertices) add(v.p);
    for (const auto& s : f->segments) {
      add(s.p0);
      add(s.p1);
    }
    for (const auto& a : f->arcs) {
      add(a.center);
      add(a.from);
      add(a.to);
    }
  }
}

MotionResult MotionChecker::first_contact(const StraightMotion& m) const {
  MotionResult result;
  const Part& fixed_part = model_->parts[fixed_index_];
  const Part& free_part = model_->parts[free_index_];
  {
    auto [c, s] = chart_rotation(m.w0, m.flip);
    result.starts_apart = parts_apart(fixed_part, free_part, c, s, m.x0, m.y0);
    if (!result.starts_apart) return result;
  }
  // Lengths scaled by L (every coordinate of the features, the pivot and the motion an integer),
  // the tangent w = (w_num(u)) / W; then den = W^2 + w_num^2 = W^2 (1 + w^2) and the rotation
  // scaled by den: cn = +-(W^2 - w_num^2), sn = +-2 W w_num. Every quantity below is an integer
  // polynomial in u, a positive multiple of the true one.
  mpz_class L = lengths_denominator_;
  for (const Rational* r : {&m.x0, &m.x1, &m.y0, &m.y1}) mpz_lcm(L.get_mpz_t(), L.get_mpz_t(), r->get_den_mpz_t());
  mpz_class W = 1;
  for (const Rational* r : {&m.w0, &m.w1}) mpz_lcm(W.get_mpz_t(), W.get_mpz_t(), r->get_den_mpz_t());
  auto scaled = [](const Rational& r, const mpz_class& k) {
    mpz_class out = r.get_num() * (k / r.get_den());
    return out;
  };
  auto Z = [&](const Rational& r) { return scaled(r, L); };
  const UPoly x{Z(m.x0), Z(Rational(m.x1 - m.x0))}, y{Z(m.y0), Z(Rational(m.y1 - m.y0))};
  const UPoly w{scaled(m.w0, W), scaled(Rational(m.w1 - m.w0), W)};
  const UPoly den = constant(W * W) + w * w;
  UPoly cn = constant(W * W) - w * w, sn = mpz_class(2 * W) * w;
  if (m.flip) {
    cn = -cn;
    sn = -sn;
  }
  const mpz_class L2 = L * L;
  auto r2 = [&](const Arc& a) { return scaled(a.radius_squared, L2); };   // L^2 r^2: an integer (|L s - L c|^2)
  // world points and vectors (times L), all scaled by den
  auto fixed_point = [&](const Point& p) { return HVec{Z(p.x) * den, Z(p.y) * den}; };
  auto free_vector = [&](const Point& v) { return HVec{Z(v.x) * cn - Z(v.y) * sn, Z(v.x) * sn + Z(v.y) * cn}; };
  auto free_point = [&](const Point& p) {
    HVec r = free_vector(p);
    return HVec{r.x + (constant(Z(pivot_.x)) + x) * den, r.y + (constant(Z(pivot_.y)) + y) * den};
  };
  const UPoly den2 = den * den;

  // Cull: every free feature stays within its L1 reach of pivot + shift(u); shift(u) lies in the
  // box of the motion's end shifts.
  const Rational sx_lo = std::min(m.x0, m.x1) + pivot_.x, sx_hi = std::max(m.x0, m.x1) + pivot_.x;
  const Rational sy_lo = std::min(m.y0, m.y1) + pivot_.y, sy_hi = std::max(m.y0, m.y1) + pivot_.y;
  auto may_meet = [&](const Rational& reach, const Rational& x_lo, const Rational& x_hi, const Rational& y_lo,
                      const Rational& y_hi) {
    return !(x_hi < sx_lo - reach || x_lo > sx_hi + reach || y_hi < sy_lo - reach || y_lo > sy_hi + reach);
  };
  auto point_box_meets = [&](const Rational& reach, const Point& p) { return may_meet(reach, p.x, p.x, p.y, p.y); };
  auto segment_box_meets = [&](const Rational& reach, const Point& a, const Point& b) {
    return may_meet(reach, std::min(a.x, b.x), std::max(a.x, b.x), std::min(a.y, b.y), std::max(a.y, b.y));
  };
  auto arc_box_meets = [&](const Rational& reach, const Point& c, const Rational& r2) {
    Rational r = (1 + r2) / 2;
    return may_meet(reach, c.x - r, c.x + r, c.y - r, c.y + r);
  };
  auto free_reach = [&](const Point& p) { return l1(p); };
  auto free_arc_reach = [&](const Arc& a) { return Rational(l1(a.center) + (1 + a.radius_squared) / 2); };

  std::vector<Candidate> candidates;
  auto vertex_segment = [&](const HVec& v, const HVec& p0, const HVec& p1, MotionContact features) {
    HVec d = p1 - p0, q = v - p0;
    Candidate c;
    c.contact = cross(q, d);
    UPoly along = dot(q, d), rest = dot(d, d) - dot(q, d);
    c.conditions = {along, rest};
    c.valid = [along, rest](const Real& u) { return sign_of(along, u) >= 0 && sign_of(rest, u) >= 0; };
    c.features = features;
    candidates.push_back(std::move(c));
  };
  auto vertex_arc = [&](const HVec& v, const HVec& centre, const HVec& from, const HVec& to, const Arc& arc,
                        MotionContact features) {
    HVec q = v - centre;
    Candidate c;
    c.contact = dot(q, q) - r2(arc) * den2;
    UPoly s1 = cross(from, q), s2 = cross(q, to);
    c.conditions = {s1, s2};
    bool reflex = arc.reflex, full = arc.full;
    c.valid = [s1, s2, reflex, full](const Real& u) {
      return full || in_closed_sector(sign_of(s1, u), sign_of(s2, u), reflex, false);
    };
    c.features = features;
    candidates.push_back(std::move(c));
  };
  auto segment_arc = [&](const HVec& p0, const HVec& p1, const HVec& centre, const HVec& from, const HVec& to,
                         const Arc& arc, MotionContact features) {
    HVec d = p1 - p0, q = centre - p0;
    UPoly k = cross(d, q);   // (centre - p0) . left normal of d, the normal n = (-d.y, d.x)
    Candidate c;
    c.contact = k * k - r2(arc) * den2 * dot(d, d);
    UPoly along = dot(q, d), rest = dot(d, d) - dot(q, d);
    // direction from the centre to the foot: -sign(k) n; its cross signs with from and to
    HVec n{-d.y, d.x};
    UPoly from_n = cross(from, n), n_to = cross(n, to);
    c.conditions = {along, rest, k, from_n, n_to};
    bool reflex = arc.reflex, full = arc.full;
    c.valid = [along, rest, k, from_n, n_to, reflex, full](const Real& u) {
      if (sign_of(along, u) < 0 || sign_of(rest, u) < 0) return false;
      if (full) return true;
      int sigma = sign_of(k, u);
      if (sigma == 0) return false;   // the centre on the line: not a tangency (r > 0)
      return in_closed_sector(-sigma * sign_of(from_n, u), -sigma * sign_of(n_to, u), reflex, false);
    };
    c.features = features;
    candidates.push_back(std::move(c));
  };
  auto arc_arc = [&](const HVec& c1, const HVec& from1, const HVec& to1, const Arc& a1, const HVec& c2, const HVec& from2,
                     const HVec& to2, const Arc& a2, MotionContact features) {
    HVec n = c2 - c1;
    UPoly distance = dot(n, n);
    UPoly e = distance - mpz_class(r2(a1) + r2(a2)) * den2;
    Candidate c;
    c.contact = e * e - mpz_class(4 * r2(a1) * r2(a2)) * den2 * den2;
    UPoly s1a = cross(from1, n), s2a = cross(n, to1), s1b = cross(from2, n), s2b = cross(n, to2);
    c.conditions = {distance, e, s1a, s2a, s1b, s2b};
    const int bigger = a1.radius_squared > a2.radius_squared ? 1 : a1.radius_squared < a2.radius_squared ? 2 : 0;
    Arc first = a1, second = a2;
    c.valid = [=](const Real& u) {
      if (sign_of(distance, u) == 0) return first.full && second.full;   // concentric equal circles
      int external = sign_of(e, u) > 0;
      // direction of the contact point from each centre: +n or -n
      int from_first = external || bigger == 1 ? 1 : -1;
      int from_second = external ? -1 : bigger == 1 ? 1 : -1;
      return in_closed_sector(from_first * sign_of(s1a, u), from_first * sign_of(s2a, u), first.reflex, first.full) &&
             in_closed_sector(from_second * sign_of(s1b, u), from_second * sign_of(s2b, u), second.reflex, second.full);
    };
    c.features = features;
    candidates.push_back(std::move(c));
  };

  // fixed vertices against free segments and arcs
  for (const auto& v : fixed_.vertices) {
    HVec hv = fixed_point(v.p);
    for (const auto& s : free_.segments)
      if (point_box_meets(std::max(free_reach(s.p0), free_reach(s.p1)), v.p))
        vertex_segment(hv, free_point(s.p0), free_point(s.p1), MotionContact{v.id, s.id});
    for (const auto& a : free_.arcs)
      if (point_box_meets(free_arc_reach(a), v.p))
        vertex_arc(hv, free_point(a.center), free_vector(a.from), free_vector(a.to), a, MotionContact{v.id, a.id});
  }
  // free vertices against fixed segments and arcs
  for (const auto& v : free_.vertices) {
    HVec hv = free_point(v.p);
    const Rational reach = free_reach(v.p);
    for (const auto& s : fixed_.segments)
      if (segment_box_meets(reach, s.p0, s.p1))
        vertex_segment(hv, fixed_point(s.p0), fixed_point(s.p1), MotionContact{s.id, v.id});
    for (const auto& a : fixed_.arcs)
      if (arc_box_meets(reach, a.center, a.radius_squared))
        vertex_arc(hv, fixed_point(a.center), fixed_point(a.from), fixed_point(a.to), a, MotionContact{a.id, v.id});
  }
  // tangencies
  for (const auto& a : fixed_.arcs) {
    for (const auto& s : free_.segments)
      if (arc_box_meets(std::max(free_reach(s.p0), free_reach(s.p1)), a.center, a.radius_squared))
        segment_arc(free_point(s.p0), free_point(s.p1), fixed_point(a.center), fixed_point(a.from), fixed_point(a.to), a,
                    MotionContact{a.id, s.id});
    for (const auto& b : free_.arcs)
      if (arc_box_meets(free_arc_reach(b), a.center, a.radius_squared))
        arc_arc(fixed_point(a.center), fixed_point(a.from), fixed_point(a.to), a, free_point(b.center), free_vector(b.from),
                free_vector(b.to), b, MotionContact{a.id, b.id});
  }
  for (const auto& b : free_.arcs) {
    const Rational reach = free_arc_reach(b);
    for (const auto& s : fixed_.segments)
      if (segment_box_meets(reach, s.p0, s.p1))
        segment_arc(fixed_point(s.p0), fixed_point(s.p1), free_point(b.center), free_vector(b.from), free_vector(b.to), b,
                    MotionContact{s.id, b.id});
  }

  // the least valid root of each candidate
  std::optional<Real> best;
  std::vector<std::pair<Real, MotionContact>> firsts;
  for (const auto& c : candidates) {
    bool skip = false;
    for (const MotionContact& i : m.ignored) skip = skip || (i.fixed == c.features.fixed && i.free == c.features.free);
    if (skip) continue;
    std::vector<Real> roots;
    if (is_zero(c.contact)) {
      // in contact position all along: the contact becomes valid where a condition changes sign
      for (const auto& p : c.conditions) {
        if (is_zero(p)) continue;
        algebra::Polynomial q = integer(p);
        if (algebra::degree(q) < 1) continue;
        for (auto& r : algebra::real_roots(algebra::square_free_part(q), Rational(0), Rational(1))) roots.push_back(r);
      }
      roots.push_back(Real::from_rational(Rational(0)));
      std::sort(roots.begin(), roots.end(), [](const Real& a, const Real& b) { return algebra::compare(a, b) < 0; });
    } else {
      if (no_root_in_unit_interval(c.contact)) continue;
      algebra::Polynomial q = integer(c.contact);
      if (algebra::degree(q) < 1) continue;
      roots = algebra::real_roots(algebra::square_free_part(q), Rational(0), Rational(1));
    }
    for (auto& r : roots) {
      if (best && algebra::compare(r, *best) > 0) break;
      if (!c.valid(r)) continue;
      if (!best || algebra::compare(r, *best) < 0) best = r;
      firsts.emplace_back(r, c.features);
      break;
    }
  }
  if (!best) return result;
  result.found = true;
  result.u = *best;
  for (const auto& [r, features] : firsts)
    if (algebra::compare(r, *best) == 0) result.contacts.push_back(features);
  return result;
}

}  // namespace hipair::sliced
