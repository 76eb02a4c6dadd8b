// Small pieces the tolerance checks share (tolerance_check.cpp: checks 1-6 and no_interference;
// free_path_check.cpp: check 7): enclosure helpers, the separation test of two posed edges and
// the mean-value pair. Verifier-internal: no floating-point type, MPFI enclosures with exact
// rational ends.
#pragma once

#include "certify/tolerance_check.hpp"

#include <string>
#include <utility>

namespace hipair::verify {

/// An enclosure printed with 8 significant digits per end (for messages only).
std::string show(const Interval& x);
/// Exact ends as fractions, each rounded to 25 significant digits (marked) when its fraction
/// is longer than 60 characters (a forged 1e100000 would otherwise fill a 100 KB line).
std::string show(const RationalInterval& r);
/// `value` as its exact fraction when that has at most 60 characters, else 25 significant
/// digits marked " (rounded)" (check.cpp; the fixed-axis messages' last resort too).
std::string fraction_or_rounded(const Rational& value);
/// Two different values as two different texts: exactly when both have a short exact form, else
/// rounded to as many significant digits as it takes to tell them apart (check.cpp; every
/// "a, less than b" message uses it so that it never shows two different numbers as equal).
std::pair<std::string, std::string> show_apart(const Rational& a, const Rational& b);
/// x intersected with y (both enclose the same number).
Interval meet(const Interval& x, const Interval& y);
/// The hull of two enclosures.
Interval hull2(const Interval& a, const Interval& b);

inline bool contains(const RationalInterval& outer, const RationalInterval& inner) {
  return outer.lo <= inner.lo && inner.hi <= outer.hi;
}

inline Rational middle(const RationalInterval& r) { return (r.lo + r.hi) / 2; }

inline Interval offset(const RationalInterval& r) { return enclose(RationalInterval{r.lo - middle(r), r.hi - middle(r)}); }

// The separation tests on two posed edges, for a number type N (plain enclosures, or the
// mean-value pairs below) with `sign` its certain sign (+1, -1; 0 undecided).
template <class N>
struct EdgeT {
  bool arc = false, ccw = false;
  kernels::Vector<N> s, t, c;
  N r2, r;
};

template <class N, class Sign>
bool separated(const EdgeT<N>& a, const EdgeT<N>& b, const Sign& sign) {
  using V = kernels::Vector<N>;
  auto minus = [](const V& u, const V& v) { return V{u.x - v.x, u.y - v.y}; };
  auto cross = [](const V& u, const V& v) { return u.x * v.y - u.y * v.x; };
  auto dot = [](const V& u, const V& v) { return u.x * v.x + u.y * v.y; };
  auto chord = [&](const EdgeT<N>& e, const V& q) {   // +1 on the arc's side of its chord, -1 the other
    int side = sign(cross(minus(e.t, e.s), minus(q, e.s)));
    return side == 0 ? 0 : (side == (e.ccw ? -1 : 1) ? 1 : -1);
  };
  auto same_side_of_line = [&](const EdgeT<N>& line, const EdgeT<N>& e) {   // e's ends strictly on one side
    V d = minus(line.t, line.s);
    int s0 = sign(cross(d, minus(e.s, line.s))), s1 = sign(cross(d, minus(e.t, line.s)));
    return s0 != 0 && s0 == s1;
  };
  if (!a.arc && !b.arc) return same_side_of_line(a, b) || same_side_of_line(b, a);
  if (a.arc && b.arc) {
    V cc = minus(a.c, b.c);
    N d2 = dot(cc, cc);
    N outer = a.r + b.r, inner = a.r - b.r;
    if (sign(d2 - outer * outer) > 0) return true;   // circles apart
    if (sign(inner * inner - d2) > 0) return true;   // one circle strictly inside the other
    return false;
  }
  const EdgeT<N>& arc = a.arc ? a : b;
  const EdgeT<N>& seg = a.arc ? b : a;
  V d = minus(seg.t, seg.s);
  N k = cross(d, minus(arc.c, seg.s));
  if (sign(k * k - arc.r2 * dot(d, d)) > 0) return true;   // the segment's line misses the circle
  V cs = minus(arc.c, seg.s), ct = minus(arc.c, seg.t);
  int in_s = sign(arc.r2 - dot(cs, cs)), in_t = sign(arc.r2 - dot(ct, ct));
  if (in_s > 0 && in_t > 0) return true;   // the segment strictly inside the disc
  // Both ends strictly outside the disc, and the point of the line nearest the centre beyond
  // one end: the segment's point nearest the centre is an end, outside.
  if (in_s < 0 && in_t < 0 && (sign(dot(cs, d)) < 0 || sign(dot(ct, d)) > 0)) return true;
  if (chord(arc, seg.s) < 0 && chord(arc, seg.t) < 0) return true;   // beyond the arc's chord
  return false;
}

// A part's point placed at its coordinate: turned about `pivot` by the angle whose cosine and
// sine are c and s (a rotating part), or moved by coordinate times `direction` (a sliding one;
// c and s unused). ToleranceEvaluator::posed and check 7's posing (which computes c and s once
// per part and piece) share it, so that both give the same enclosures.
template <class T>
kernels::Vector<T> placed(const kernels::Vector<T>& point, bool rotates, const kernels::Vector<T>& pivot,
                          const kernels::Vector<T>& direction, const T& coordinate, const T& c, const T& s) {
  if (!rotates) return {point.x + coordinate * direction.x, point.y + coordinate * direction.y};
  T dx = point.x - pivot.x, dy = point.y - pivot.y;
  return {pivot.x + (c * dx - s * dy), pivot.y + (s * dx + c * dy)};
}

// The broad phase of the edge-pair tests (check 7, free_path_check.cpp; no_interference's
// apart()): an axis-aligned box enclosing every point of a closed edge for every point of the
// box of parameters it was posed over. A segment: the hull of its ends' enclosures (its points
// are convex combinations of the ends). An arc: that hull and each of its circle's four
// axis-extreme points c +- r e_k unless certainly beyond the arc's chord (the chord's line cuts
// the circle into the arc, on its side, and the rest): the extreme coordinates of an arc are
// those of its ends or of the axis-extreme points it contains. A full circle: c +- r on both
// axes. Every component is an MPFI enclosure, so the box holds the edge at every parameter
// vector the enclosures were taken over.
struct EdgeBox {
  Interval x, y;
};

template <class E>
EdgeBox edge_box(const E& e, bool full) {
  using V = kernels::Vector<Interval>;
  EdgeBox b;
  if (full) {
    b.x = e.c.x;
    b.y = e.c.y;
  } else {
    b.x = hull2(e.s.x, e.t.x);
    b.y = hull2(e.s.y, e.t.y);
    if (!e.arc) return b;
  }
  V ch{e.t.x - e.s.x, e.t.y - e.s.y};
  int arc_side = e.ccw ? -1 : 1;   // a ccw arc lies to the right of its directed chord
  for (int k = 0; k < 4; ++k) {
    V p = e.c;
    if (k == 0) p.x = e.c.x + e.r;
    if (k == 1) p.x = e.c.x - e.r;
    if (k == 2) p.y = e.c.y + e.r;
    if (k == 3) p.y = e.c.y - e.r;
    if (!full) {
      int side = (ch.x * (p.y - e.s.y) - ch.y * (p.x - e.s.x)).sign();
      if (side != 0 && side != arc_side) continue;   // certainly beyond the chord: not on the arc
    }
    b.x = hull2(b.x, p.x);
    b.y = hull2(b.y, p.y);
  }
  return b;
}

/// The two boxes certainly disjoint: an upper end of one strictly below the lower end of the
/// other on an axis, compared exactly (MPFR numbers are exact binary fractions; a NaN or an
/// unbounded end never compares less). Then the two edges share no point over the box they
/// were posed over: no contact and no first-contact event between them.
inline bool boxes_apart(const EdgeBox& a, const EdgeBox& b) {
  auto below = [](const Interval& u, const Interval& v) { return mpfr_less_p(&u.get()->right, &v.get()->left) != 0; };
  return below(a.x, b.x) || below(b.x, a.x) || below(a.y, b.y) || below(b.y, a.y);
}

// A quantity over a leaf in mean-value form: `over` its jet over the whole leaf (gradient with
// respect to the varied parameters, the driver and the follower), `at` its value at the
// leaf's centre. Its certain sign is that of at + sum over_i' (X_i - c_i), met with over.
struct MeanValue {
  Jet over;
  Interval at;
};
inline MeanValue operator+(const MeanValue& a, const MeanValue& b) { return {a.over + b.over, a.at + b.at}; }
inline MeanValue operator-(const MeanValue& a, const MeanValue& b) { return {a.over - b.over, a.at - b.at}; }
inline MeanValue operator*(const MeanValue& a, const MeanValue& b) { return {a.over * b.over, a.at * b.at}; }

}  // namespace hipair::verify
