// Check 7 of a no_jam tolerance certificate (docs/certify.md "Tolerance", check 7): for every
// parameter vector p of the box, a free follower path crosses the whole driver range.
//
// The path is the certificate's own: over every region of its subdivision tree the follower
// follows the region's leaf witness y*(p, d) (affine in p and the driver d, exact rational
// coefficients), and at a driver value d0 where a region R ends and a region R' containing
// (p, d0) continues, the follower moves (driver held at d0) from R's witness to R''s:
// y = y_R + lambda (y_R' - y_R), lambda in [0, 1]. For a fixed p the regions whose closed boxes
// hold p cover the driver range, so such a chain exists for every p (finitely many regions, each
// step ends strictly further right). What is proved, over each region and each move (a box X of
// k + 1 dimensions: the varied parameters, then the driver or lambda):
//
//   the two parts are apart at X's centre, and no first-contact event happens anywhere in X.
//
// Why that suffices: if the closed parts met at some x of X, let t* be the first t at which they
// meet along the segment from the centre c to x (X is a box: the segment lies in it; the set of
// meeting t is closed and excludes 0). Their interiors are disjoint at t* (overlapping interiors
// persist under small motions, so they would overlap before t*), so they touch at a point q on
// an edge e of one part and an edge g of the other with: q an end of e on g (or of g on e), or q
// interior to both, where two edges crossing transversally would overlap the interiors, so they
// are tangent there: an arc tangent to a segment, or two tangent arcs (two collinear segments
// meeting in their interiors contain an end of one on the other). Each such event is excluded
// over X when its function has a certain sign there, or its point lies certainly outside an
// edge's extent:
//   vertex v on segment [s, t]: cross(t - s, v - s) != 0, or dot(v - s, t - s) < 0, or
//     dot(v - t, t - s) > 0;
//   vertex v on arc (c, r): |v - c|^2 - r^2 != 0, or v strictly beyond the arc's chord;
//   arc (c, r) tangent to segment [s, t] (d = t - s): cross(d, c - s)^2 - r^2 |d|^2 != 0, or the
//     foot point q = s + u d, u = dot(c - s, d) / |d|^2, beyond an end of the segment (u < 0 or
//     u > 1) or beyond the arc's chord (signs taken of |d|^2 (q - a.s), no division);
//   arcs (a.c, ra) and (b.c, rb) tangent, externally or internally (D = ra + rb or ra - rb):
//     |a.c - b.c|^2 - D^2 != 0, or the common point q = a.c + (b.c - a.c) ra / D beyond either
//     arc's chord (signs of D (q - s), no square root: nearly concentric lock arcs keep a
//     certain D where the unit direction between their centres would not exist).
// Full circles (pins) have no ends and no chord: only their function counts.
//
// Every sign is certain over X: first the plain MPFI enclosure, then the mean-value form about
// X's centre, then the second-order Taylor form (value and gradient at the centre, Hessian over
// X, narrowed after every operation: struct Taylor). An event none of them excludes splits X in
// two (the dimension that moves its function most), at most `budget` times over the whole check;
// past that the claim is not proved (the verdict is unproven, never valid).
#include "certify/tolerance_check.hpp"
#include "certify/tolerance_support.hpp"

#include <mpfr.h>

#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <tuple>
#include <optional>
#include <utility>

namespace hipair::verify {

namespace {

// ----------------------------------------------------------------------------- Taylor form

// A quantity over a box X in second-order Taylor form: `over` its value, gradient and Hessian
// enclosed over X, `at` its value and gradient at X's centre. After every operation the value
// over X is narrowed to at + grad(at) (x - c) + (x - c)' H (x - c) / 2 and each partial
// derivative to its own mean-value form grad_a(at) + sum_b H_ab (x_b - c_b) (Taylor's theorem with
// the Lagrange remainder along the segment from c: X is a box). A non-smooth step leaves `over`.
struct Taylor {
  Jet2 over;
  Jet at;
  const std::vector<Interval>* offsets = nullptr;   ///< x - c per dimension of X
};

void narrow(Taylor& t) {
  if (!t.offsets || !t.over.smooth) return;
  const std::vector<Interval>& off = *t.offsets;
  Interval value = t.at.value;
  for (std::size_t i = 0; i < t.at.gradient.size() && i < off.size(); ++i) value = value + t.at.gradient[i] * off[i];
  Interval half(Rational(1, 2));
  std::size_t n = t.over.index.size();
  for (std::size_t a = 0; a < n; ++a) {
    const Interval& oa = off[t.over.index[a]];
    Interval square;
    mpfi_sqr(square.get(), oa.get());
    value = value + half * t.over.second(a, a) * square;
    for (std::size_t b = a + 1; b < n; ++b) value = value + t.over.second(a, b) * (oa * off[t.over.index[b]]);
  }
  t.over.value = meet(t.over.value, value);
  for (std::size_t a = 0; a < n; ++a) {
    Interval g = t.at.partial(t.over.index[a]);
    for (std::size_t b = 0; b < n; ++b) g = g + t.over.second(a, b) * off[t.over.index[b]];
    t.over.gradient[a] = meet(t.over.gradient[a], g);
  }
}

Taylor make(Jet2 over, Jet at, const std::vector<Interval>* offsets) {
  Taylor t{std::move(over), std::move(at), offsets};
  narrow(t);
  return t;
}
const std::vector<Interval>* either(const Taylor& a, const Taylor& b) { return a.offsets ? a.offsets : b.offsets; }
Taylor operator+(const Taylor& a, const Taylor& b) { return make(a.over + b.over, a.at + b.at, either(a, b)); }
Taylor operator-(const Taylor& a, const Taylor& b) { return make(a.over - b.over, a.at - b.at, either(a, b)); }
Taylor operator*(const Taylor& a, const Taylor& b) { return make(a.over * b.over, a.at * b.at, either(a, b)); }

// The certain sign of a mean-value pair over X (offsets: x - c per dimension).
int mean_value_sign(const MeanValue& x, const std::vector<Interval>& offsets) {
  Interval value = x.at;
  for (std::size_t i = 0; i < offsets.size(); ++i) value = value + x.over.partial(i) * offsets[i];
  return meet(value, x.over.value).sign();
}

// An upper bound of |x| as a double: only to choose which dimension to split (never a verdict).
double magnitude(const Interval& x) {
  mpfr_t m;
  mpfr_init2(m, 64);
  mpfi_mag(m, x.get());
  double d = mpfr_get_d(m, MPFR_RNDU);
  mpfr_clear(m);
  return d;
}

// ----------------------------------------------------------------------------- events

// Sub-boxes of the reduced tangency test per call.
constexpr std::size_t reduced_limit = 4096;

enum class EventKind { first_vertex_on_second, second_vertex_on_first, tangency, external, internal };

template <class N>
using Vec = kernels::Vector<N>;
template <class N>
Vec<N> difference(const Vec<N>& u, const Vec<N>& v) { return {u.x - v.x, u.y - v.y}; }
template <class N>
N cross_of(const Vec<N>& u, const Vec<N>& v) { return u.x * v.y - u.y * v.x; }
template <class N>
N dot_of(const Vec<N>& u, const Vec<N>& v) { return u.x * v.x + u.y * v.y; }

// +1: a (certain) sign that puts a point on the arc's side of its chord; a ccw arc lies to the
// right of its directed chord (cross < 0), a cw arc to its left.
template <class N>
int arc_side(const EdgeT<N>& e) { return e.ccw ? -1 : 1; }

// A posed edge with whether it is a full circle (no ends, no chord).
template <class N>
struct Feature {
  EdgeT<N> e;
  bool full = false;
};

// A point q of an arc's circle certainly not on the arc, told by the radial lines through the
// arc's ends rather than by its chord (docs/certify.md "Tolerance", check 7); `w` is a positive
// multiple of q - c times `ws` (+1 or -1; only its direction is read). Lemma: with o = +1 for a ccw arc, -1 for a cw
// one, u = s - c (the parametric model's radius is |s - c|: s lies on the circle) and
// ch = t - s, when o cross(u, ch) > 0 and dot(u, ch) < 0, every point x of the circle on the
// arc's side of the chord (cross(ch, x - s) of the sign arc_side or 0) has o cross(u, x - c) >= 0
// (in a frame with u = (r, 0): ch.y o > 0 and ch.x < 0; a circle point with o (x - c).y < 0 is
// strictly beyond the chord). So o cross(u, w) < 0 puts q beyond the end s. The chord meets the
// circle again at t' = s + lambda ch, lambda = -2 dot(u, ch) / |ch|^2 > 0 (t' = t when t lies on
// the circle); the lemma for the arc run backwards from t' (its two conditions follow from the
// two above) gives: o cross(E, w) > 0 puts q beyond t', with E = |ch|^2 u - 2 dot(u, ch) ch
// = |ch|^2 (t' - c). Near an end the chord's side is a thin quantity (the chord meets the circle
// at half the sweep: a point 0.05 mm beyond an end of the spur gear's 1.4 mm tip arc lies
// 0.0012 mm beyond its chord), the radial one is not (0.05 mm).
template <class N, class Sign>
bool beyond_arc_ends(const Vec<N>& w, int ws, const EdgeT<N>& arc, const Sign& sign) {
  int o = arc.ccw ? 1 : -1;
  Vec<N> u = difference(arc.s, arc.c);
  Vec<N> ch = difference(arc.t, arc.s);
  if (sign(cross_of(u, ch)) != o || sign(dot_of(u, ch)) >= 0) return false;
  if (sign(cross_of(u, w)) * ws == -o) return true;
  N L = dot_of(ch, ch);
  N h = dot_of(u, ch);
  N twice = h + h;
  Vec<N> end{L * u.x - twice * ch.x, L * u.y - twice * ch.y};
  return sign(cross_of(end, w)) * ws == o;
}

// True when the event is certainly excluded over X (see the file comment). `primary` receives
// the event's contact function (the one whose zero set is the touching), for the split choice.
template <class N, class Sign>
bool excluded(EventKind kind, const Feature<N>& first, const Feature<N>& second, const Sign& sign, N* primary) {
  auto vertex_off = [&](const Vec<N>& v, const Feature<N>& g) {
    if (!g.e.arc) {
      Vec<N> d = difference(g.e.t, g.e.s);
      N f = cross_of(d, difference(v, g.e.s));
      if (primary) *primary = f;
      if (sign(f) != 0) return true;
      return sign(dot_of(difference(v, g.e.s), d)) < 0 || sign(dot_of(difference(v, g.e.t), d)) > 0;
    }
    Vec<N> w = difference(v, g.e.c);
    N f = dot_of(w, w) - g.e.r2;
    if (primary) *primary = f;
    if (sign(f) != 0) return true;
    if (g.full) return false;
    int side = sign(cross_of(difference(g.e.t, g.e.s), difference(v, g.e.s)));
    if (side != 0 && side != arc_side(g.e)) return true;
    return beyond_arc_ends(w, 1, g.e, sign);   // on the event v lies on g's circle
  };
  switch (kind) {
    case EventKind::first_vertex_on_second: return vertex_off(first.e.s, second);
    case EventKind::second_vertex_on_first: return vertex_off(second.e.s, first);
    case EventKind::tangency: {
      const Feature<N>& arc = first.e.arc ? first : second;
      const Feature<N>& seg = first.e.arc ? second : first;
      Vec<N> d = difference(seg.e.t, seg.e.s);
      Vec<N> cs = difference(arc.e.c, seg.e.s);
      N k = cross_of(d, cs);
      N den = dot_of(d, d);
      N f = k * k - arc.e.r2 * den;
      if (primary) *primary = f;
      if (sign(f) != 0) return true;
      N num = dot_of(cs, d);
      if (sign(num) < 0 || sign(num - den) > 0) return true;   // the foot point beyond an end
      if (arc.full || sign(den) <= 0) return false;
      // den (q - arc.s) = den (seg.s - arc.s) + num d, with den > 0.
      Vec<N> ch = difference(arc.e.t, arc.e.s);
      int side = sign(den * cross_of(ch, difference(seg.e.s, arc.e.s)) + num * cross_of(ch, d));
      if (side != 0 && side != arc_side(arc.e)) return true;
      // On the event the foot point q lies on the circle: den (q - c) = num d - den (c - s).
      Vec<N> w{num * d.x - den * cs.x, num * d.y - den * cs.y};
      return beyond_arc_ends(w, 1, arc.e, sign);
    }
    case EventKind::external:
    case EventKind::internal: {
      const EdgeT<N>& a = first.e;
      const EdgeT<N>& b = second.e;
      N D = kind == EventKind::external ? a.r + b.r : a.r - b.r;
      Vec<N> cc = difference(b.c, a.c);
      N f = dot_of(cc, cc) - D * D;
      if (primary) *primary = f;
      if (sign(f) != 0) return true;
      int sd = sign(D);
      if (sd == 0) return false;
      // q = a.c + cc ra / D, so D (q - x.s) = D (a.c - x.s) + ra cc.
      for (const Feature<N>* x : {&first, &second}) {
        if (x->full) continue;
        Vec<N> ch = difference(x->e.t, x->e.s);
        Vec<N> w = difference(a.c, x->e.s);
        Vec<N> scaled{D * w.x + a.r * cc.x, D * w.y + a.r * cc.y};
        int side = sign(cross_of(ch, scaled)) * sd;
        if (side != 0 && side != arc_side(x->e)) return true;
      }
      // On the event q lies on both circles: q - a.c = cc ra / D and q - b.c = cc (ra - D) / D,
      // that is -cc rb / D (external) or cc rb / D (internal): positive multiples of sd cc, of
      // -sd cc (external) and of sd cc (internal).
      if (!first.full && beyond_arc_ends(cc, sd, a, sign)) return true;
      if (!second.full && beyond_arc_ends(cc, kind == EventKind::external ? -sd : sd, b, sign)) return true;
      return false;
    }
  }
  return false;
}

// The tangency of two arcs in reduced variables (docs/certify.md "Tolerance", check 7): on the
// event |cc| = |D| with D of the certain sign sd, so the common point is
// q = a.c + sd ra cc / |cc| and, for each arc x with an end (chord ch = x.t - x.s),
//   |cc| cross(ch, q - x.s) = |cc| k + sd (P cc.y - Q cc.x),
//   k = cross(ch, a.c - x.s), P = ra ch.x, Q = ra ch.y,
// whose sign is that of cross(ch, q - x.s) (|cc| = |D| > 0). These few quantities (cc, D, and k, P,
// Q per arc) are enclosed over X in Taylor form; every event of X has its values inside these
// enclosures and satisfies there |cc|^2 = D^2 and both arcs' chord conditions. The event is
// excluded when no point of the box of quantities satisfies them: the plane of cc is bisected
// (the other quantities range over their whole enclosures, so no relation between them is
// assumed) and each sub-box is dropped when |cc|^2 - D^2 has a certain sign there, or one arc's
// chord condition certainly fails (with |cc| enclosed by the root of the meet of |cc|^2 and D^2,
// its value on the event). At most `limit` sub-boxes.
bool tangency_excluded_reduced(EventKind kind, const Feature<Taylor>& first, const Feature<Taylor>& second,
                               std::size_t limit) {
  const EdgeT<Taylor>& a = first.e;
  const EdgeT<Taylor>& b = second.e;
  Taylor D = kind == EventKind::external ? a.r + b.r : a.r - b.r;
  int sd = D.over.value.sign();
  if (sd == 0) return false;
  Vec<Taylor> cc = difference(b.c, a.c);
  auto square = [](const Interval& x) {
    Interval r;
    mpfi_sqr(r.get(), x.get());
    return r;
  };
  Interval D2 = square(D.over.value);
  struct Chord {
    Interval k, P, Q;
    int side;
  };
  std::vector<Chord> chords;
  for (const Feature<Taylor>* x : {&first, &second}) {
    if (x->full) continue;
    Vec<Taylor> ch = difference(x->e.t, x->e.s);
    chords.push_back({cross_of(ch, difference(a.c, x->e.s)).over.value, (a.r * ch.x).over.value,
                      (a.r * ch.y).over.value, arc_side(x->e)});
  }
  if (chords.empty()) return false;
  const Interval sdi = enclose(Rational(sd));
  auto bounds = [](const Interval& x) { return RationalInterval{x.lower(), x.upper()}; };
  if (!cc.x.over.value.is_bounded() || !cc.y.over.value.is_bounded()) return false;
  std::vector<std::pair<RationalInterval, RationalInterval>> stack{{bounds(cc.x.over.value), bounds(cc.y.over.value)}};
  std::size_t boxes = 0;
  while (!stack.empty()) {
    auto [rx, ry] = stack.back();
    stack.pop_back();
    if (++boxes > limit) return false;
    Interval X = enclose(rx), Y = enclose(ry);
    Interval n2 = square(X) + square(Y);
    if ((n2 - D2).sign() != 0) continue;
    Interval n;
    mpfi_sqrt(n.get(), meet(n2, D2).get());
    bool out = false;
    for (const Chord& c : chords) {
      int side = (c.k * n + sdi * (c.P * Y - c.Q * X)).sign();
      if (side != 0 && side != c.side) out = true;
    }
    if (out) continue;
    bool along_x = rx.hi - rx.lo >= ry.hi - ry.lo;
    RationalInterval& cut = along_x ? rx : ry;
    Rational mid = middle(cut);
    RationalInterval low{cut.lo, mid}, high{mid, cut.hi};
    if (along_x) {
      stack.push_back({low, ry});
      stack.push_back({high, ry});
    } else {
      stack.push_back({rx, low});
      stack.push_back({rx, high});
    }
  }
  return true;
}

const char* event_text(EventKind kind) {
  switch (kind) {
    case EventKind::first_vertex_on_second: return "the start vertex of the first on the second";
    case EventKind::second_vertex_on_first: return "the start vertex of the second on the first";
    case EventKind::tangency: return "a tangency of the arc and the segment";
    case EventKind::external: return "an external tangency of the arcs";
    case EventKind::internal: return "an internal tangency of the arcs";
  }
  return "";
}

}  // namespace

// ----------------------------------------------------------------------------- the check

class ToleranceEvaluator::FreePath {
 public:
  FreePath(const ToleranceEvaluator& evaluator, std::size_t budget)
      : ev_(evaluator), claim_(evaluator.claim_), k_(evaluator.varied_.size()), budget_(budget) {
    const Model& m = ev_.model_->nominal();
    for (int side = 0; side < 2; ++side) {
      std::size_t part = side == 0 ? ev_.driver_ : ev_.follower_;
      const Part& p = m.parts[part];
      for (std::size_t l = 0; l < p.loops.size(); ++l)
        for (std::size_t e = 0; e < p.loops[l].edges.size(); ++e)
          (side == 0 ? driver_edges_ : follower_edges_)
              .push_back(EdgeRef{part, l, e, p.loops[l].edges[e].is_full_circle(),
                                 "'" + p.loops[l].edges[e].label + "' (" + p.name + " loop " + std::to_string(l) +
                                     " edge " + std::to_string(e) + ")"});
    }
  }

  // The path over one leaf's own box (the producer's test of a candidate leaf: a region is a
  // part of its leaf's box, so what holds here holds over the region).
  std::string leaf(std::size_t index) {
    const ToleranceLeaf& l = claim_.leaves[index];
    if (!l.witness) return "leaf " + std::to_string(index) + " has no witness path for the follower";
    std::vector<RationalInterval> box = l.parameters;
    box.push_back(l.driver);
    Path path{false, index, index, Rational(0), "over leaf " + std::to_string(index)};
    return prove(path, box);
  }

  std::string run() {
    std::vector<Region> regions = ev_.check_cover();
    for (const Region& r : regions)
      if (!claim_.leaves[r.leaf].witness)
        return "leaf " + std::to_string(r.leaf) + " has no witness path for the follower";
    if (std::string f = limits_failure(regions); !f.empty()) return f;
    // The work limit grows with the certificate: one more bisection per region (session 66: the
    // spur gears' whole-turn certificate, 85 leaves, needs 77; with 48 in all it stopped at 3.8 rad).
    budget_ += regions.size();
    for (const Region& r : regions) {
      Path path{false, r.leaf, r.leaf, Rational(0),
                "over leaf " + std::to_string(r.leaf) + "'s region (driver " + show(r.box[k_]) + ")"};
      if (std::string f = prove(path, r.box); !f.empty()) return f;
    }
    const Rational& end = claim_.range.hi;
    for (const Region& a : regions) {
      const Rational& d0 = a.box[k_].hi;
      if (!(d0 < end)) continue;
      for (const Region& b : regions) {
        if (&a == &b || !(b.box[k_].lo <= d0 && d0 < b.box[k_].hi)) continue;
        std::vector<RationalInterval> box;
        bool meets = true;
        for (std::size_t i = 0; i < k_ && meets; ++i) {
          RationalInterval common{std::max(a.box[i].lo, b.box[i].lo), std::min(a.box[i].hi, b.box[i].hi)};
          meets = common.lo <= common.hi;
          box.push_back(common);
        }
        if (!meets) continue;
        box.push_back({Rational(0), Rational(1)});
        Path path{true, a.leaf, b.leaf, d0,
                  "on the move from leaf " + std::to_string(a.leaf) + "'s witness to leaf " + std::to_string(b.leaf) +
                      "'s at driver " + to_exact_string(d0)};
        if (std::string f = prove(path, box); !f.empty()) return f;
      }
    }
    return "";
  }

 private:
  struct EdgeRef {
    std::size_t part, loop, edge;
    bool full;
    std::string name;
  };
  // A region's path (move = false: the follower on leaf `first`'s witness, the last dimension is
  // the driver) or a move at driver `at` from leaf `first`'s witness to leaf `second`'s (the last
  // dimension is lambda).
  struct Path {
    bool move = false;
    std::size_t first = 0, second = 0;
    Rational at;
    std::string where;
  };

  // The leaf's witness y*(p, d) = w + sum a_i (p_i - c_i) + a_d (d - c_d) for a number type T.
  template <class T>
  T witness(std::size_t leaf, const std::vector<T>& p, const T& d) const {
    const ToleranceLeaf& l = claim_.leaves[leaf];
    T y(enclose(*l.witness));
    for (std::size_t i = 0; i <= k_; ++i) {
      const Rational& a = l.witness_slopes[i];
      if (a == 0) continue;
      const RationalInterval& r = i < k_ ? l.parameters[i] : l.driver;
      y = y + T(enclose(a)) * ((i < k_ ? p[i] : d) - T(enclose(middle(r))));
    }
    return y;
  }
  Rational witness_at(std::size_t leaf, const std::vector<Rational>& p, const Rational& d) const {
    const ToleranceLeaf& l = claim_.leaves[leaf];
    Rational y = *l.witness;
    for (std::size_t i = 0; i <= k_; ++i) {
      const RationalInterval& r = i < k_ ? l.parameters[i] : l.driver;
      y += l.witness_slopes[i] * ((i < k_ ? p[i] : d) - middle(r));
    }
    return y;
  }
  // The driver and follower coordinates of a path at the dimensions x (k parameters, then s).
  template <class T>
  std::pair<T, T> coordinates(const Path& path, const std::vector<T>& x) const {
    if (!path.move) return {x[k_], witness(path.first, x, x[k_])};
    T d(enclose(path.at));
    T y0 = witness(path.first, x, d), y1 = witness(path.second, x, d);
    return {d, y0 + x[k_] * (y1 - y0)};
  }

  // Every path stays within the follower's motion limits, and the range within the driver's
  // (exact: a witness is affine, so its extremes over a region are at the region's corners).
  std::string limits_failure(const std::vector<Region>& regions) const {
    const Model& m = ev_.model_->nominal();
    auto limits = [&](std::size_t part) -> std::optional<RationalInterval> {
      const Motion& motion = m.parts[part].motion;
      return motion.kind == Motion::Kind::rotation ? motion.angle_limits : motion.translation_limits;
    };
    if (auto l = limits(ev_.driver_); l && !(l->lo <= claim_.range.lo && claim_.range.hi <= l->hi))
      return "the driver range " + show(claim_.range) + " leaves the driver's limits " + show(*l);
    auto l = limits(ev_.follower_);
    if (!l) return "";
    for (const Region& r : regions) {
      const ToleranceLeaf& leaf = claim_.leaves[r.leaf];
      Rational lo = *leaf.witness, hi = *leaf.witness;
      for (std::size_t i = 0; i <= k_; ++i) {
        const RationalInterval& c = i < k_ ? leaf.parameters[i] : leaf.driver;
        Rational a = leaf.witness_slopes[i] * (r.box[i].lo - middle(c)), b = leaf.witness_slopes[i] * (r.box[i].hi - middle(c));
        lo += std::min(a, b);
        hi += std::max(a, b);
      }
      if (!(l->lo <= lo && hi <= l->hi))
        return "leaf " + std::to_string(r.leaf) + "'s witness path " + show(RationalInterval{lo, hi}) +
               " leaves the follower's limits " + show(*l);
    }
    return "";
  }

  // The parametric edges (unposed) and the parts' pivots over one box of the varied parameters,
  // for one number type (T = Jet: plain without gradient, or with it; T = Jet2: second order):
  // evaluated once per box and shared by every piece, region and move posed over that box (a
  // certificate's leaves mostly share the whole parameter box: all 85 of the spur gears'; until
  // session 67 every piece evaluated every edge's involute again, most of check 7's time).
  template <class T>
  struct Local {
    GeometryOf<T> g;
    std::map<std::tuple<std::size_t, std::size_t, std::size_t>, std::pair<model_detail::EdgeValue<T>, T>> edges;   ///< value, radius
  };
  struct BoxLess {
    bool operator()(const std::vector<RationalInterval>& a, const std::vector<RationalInterval>& b) const {
      for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
        if (a[i].lo != b[i].lo) return a[i].lo < b[i].lo;
        if (a[i].hi != b[i].hi) return a[i].hi < b[i].hi;
      }
      return a.size() < b.size();
    }
  };
  template <class T>
  using LocalCache = std::map<std::vector<RationalInterval>, std::shared_ptr<Local<T>>, BoxLess>;
  /// The caches' keys: the parameter box's intervals (at a centre, its point intervals).
  static constexpr std::size_t cache_limit = 64;

  // The parametric geometry over the dimensions x (their first k, the varied parameters, whose
  // ranges are `key`), from `cache`.
  template <class T>
  std::shared_ptr<Local<T>> geometry(LocalCache<T>& cache, std::vector<RationalInterval> key, const std::vector<T>& x) const {
    key.resize(k_);
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    auto local = std::make_shared<Local<T>>();
    std::vector<T> all(ev_.model_->parameter_count(), T(0));
    for (std::size_t i = 0; i < k_; ++i) all[ev_.varied_[i]] = x[i];
    local->g.parameters = ev_.model_->parameter_values(all);
    ev_.pose_pivots(local->g);
    if (cache.size() >= cache_limit) cache.clear();   // the pointers handed out stay alive
    cache.emplace(std::move(key), local);
    return local;
  }
  // The point intervals of a box's centre (a cache key).
  static std::vector<RationalInterval> centre_key(const std::vector<RationalInterval>& box) {
    std::vector<RationalInterval> key;
    for (const RationalInterval& r : box) key.push_back({middle(r), middle(r)});
    return key;
  }

  // Both parts placed over a piece: the geometry and each part's coordinate with its cosine and
  // sine (computed once per part, not per point).
  template <class T>
  struct Placement {
    std::shared_ptr<Local<T>> local;
    T coordinate[2], cos[2], sin[2];
  };
  template <class T>
  Placement<T> placement(std::shared_ptr<Local<T>> local, std::pair<T, T> coordinates) const {
    Placement<T> p;
    p.local = std::move(local);
    p.coordinate[0] = std::move(coordinates.first);
    p.coordinate[1] = std::move(coordinates.second);
    for (int i = 0; i < 2; ++i)
      if (i == 0 ? ev_.driver_rotates_ : ev_.follower_rotates_) {
        p.cos[i] = model_detail::Arithmetic<T>::cos(p.coordinate[i]);
        p.sin[i] = model_detail::Arithmetic<T>::sin(p.coordinate[i]);
      }
    return p;
  }

  template <class T>
  struct PosedEdge {
    kernels::Vector<T> s, t, c;
    T r2, r;
    bool arc = false, ccw = true;
  };
  template <class T>
  PosedEdge<T> pose(Placement<T>& placement, const EdgeRef& ref) const {
    Local<T>& local = *placement.local;
    auto key = std::make_tuple(ref.part, ref.loop, ref.edge);
    auto it = local.edges.find(key);
    if (it == local.edges.end()) {
      model_detail::EdgeValue<T> v = ev_.model_->edge_value(ref.part, ref.loop, ref.edge, local.g.parameters);
      T r = v.arc ? model_detail::Arithmetic<T>::sqrt(v.radius_squared) : T(0);
      it = local.edges.emplace(key, std::make_pair(std::move(v), std::move(r))).first;
    }
    const auto& [v, r] = it->second;
    bool is_driver = ref.part == ev_.driver_;
    int i = is_driver ? 0 : 1;
    bool rotates = is_driver ? ev_.driver_rotates_ : ev_.follower_rotates_;
    const GeometryOf<T>& g = local.g;
    const kernels::Vector<T>& pivot = is_driver ? g.driver_pivot : g.follower_pivot;
    const kernels::Vector<T>& direction = is_driver ? g.driver_direction : g.follower_direction;
    auto place = [&](const kernels::Vector<T>& q) {
      return placed(q, rotates, pivot, direction, placement.coordinate[i], placement.cos[i], placement.sin[i]);
    };
    PosedEdge<T> p;
    p.arc = v.arc;
    p.ccw = v.ccw;
    p.s = place(v.source);
    p.t = place(v.target);
    if (v.arc) {
      p.c = place(v.center);
      p.r2 = v.radius_squared;
      p.r = r;
    }
    return p;
  }

  // A feature of number type N from an edge posed over the piece (`over`) and at its centre
  // (`at`), each coordinate combined by `pair`.
  template <class N, class T, class Pair>
  static Feature<N> combined(const PosedEdge<T>& over, const PosedEdge<Jet>& at, bool full, const Pair& pair) {
    Feature<N> f;
    f.full = full;
    f.e.arc = over.arc;
    f.e.ccw = over.ccw;
    f.e.s = {pair(over.s.x, at.s.x), pair(over.s.y, at.s.y)};
    f.e.t = {pair(over.t.x, at.t.x), pair(over.t.y, at.t.y)};
    if (over.arc) {
      f.e.c = {pair(over.c.x, at.c.x), pair(over.c.y, at.c.y)};
      f.e.r2 = pair(over.r2, at.r2);
      f.e.r = pair(over.r, at.r);
    }
    return f;
  }

  // One evaluation level of the geometry over a box: every edge posed lazily.
  template <class N>
  struct Level {
    std::function<Feature<N>(bool, std::size_t)> make;
    std::map<std::pair<bool, std::size_t>, Feature<N>> cache;
    const Feature<N>& get(bool driver, std::size_t index) {
      auto key = std::make_pair(driver, index);
      auto it = cache.find(key);
      if (it == cache.end()) it = cache.emplace(key, make(driver, index)).first;
      return it->second;
    }
  };

  struct Pending {
    std::size_t a, b;   // driver edge, follower edge
    EventKind kind;
  };

  // Proves the path free over `box`: apart at its centre, no event over it (bisected while
  // undecided). Returns "" or what was not proved.
  std::string prove(const Path& path, const std::vector<RationalInterval>& box) {
    if (std::string f = apart_at_centre(path, box); !f.empty()) return path.where + ": " + f;
    std::vector<std::vector<RationalInterval>> stack{box};
    while (!stack.empty()) {
      std::vector<RationalInterval> piece = std::move(stack.back());
      stack.pop_back();
      std::optional<std::size_t> split;
      std::string undecided;
      test_piece(path, piece, split, undecided);
      if (!split) continue;
      if (splits_ >= budget_) {
        last_split_ = *split;
        return path.where + ": " + undecided + " is undecided after " + std::to_string(splits_) +
               " bisections (the check's budget)";
      }
      ++splits_;
      Rational mid = middle(piece[*split]);
      std::vector<RationalInterval> low = piece, high = std::move(piece);
      low[*split].hi = mid;
      high[*split].lo = mid;
      stack.push_back(std::move(high));
      stack.push_back(std::move(low));
    }
    return "";
  }

  std::string apart_at_centre(const Path& path, const std::vector<RationalInterval>& box) {
    std::vector<Rational> c;
    for (const RationalInterval& r : box) c.push_back(middle(r));
    ToleranceLeaf point;
    for (std::size_t i = 0; i < k_; ++i) point.parameters.push_back({c[i], c[i]});
    Rational d = path.move ? path.at : c[k_];
    Rational y = witness_at(path.first, c, d);
    if (path.move) y += c[k_] * (witness_at(path.second, c, d) - y);
    point.driver = {d, d};
    point.follower = RationalInterval{y, y};
    std::vector<RationalInterval> key(point.parameters);
    auto it = centre_geometry_.find(key);
    if (it == centre_geometry_.end()) {
      if (centre_geometry_.size() >= cache_limit) centre_geometry_.clear();
      it = centre_geometry_.emplace(std::move(key), std::nullopt).first;
    }
    std::string f = ev_.apart_failure(point, &it->second);
    return f.empty() ? f : "the parts are not certainly apart at its centre: " + f;
  }

  // Tests the events over one piece; on failure `split` names the dimension to bisect and
  // `undecided` the event.
  void test_piece(const Path& path, const std::vector<RationalInterval>& box, std::optional<std::size_t>& split,
                  std::string& undecided) {
    std::size_t n = k_ + 1;
    // Plain enclosures.
    std::vector<Jet> plain_x;
    for (const RationalInterval& r : box) plain_x.push_back(Jet(enclose(r)));
    Placement<Jet> plain_p = placement(geometry(plain_cache_, box, plain_x), coordinates(path, plain_x));
    Level<Interval> plain;
    plain.make = [&](bool driver, std::size_t index) {
      const EdgeRef& ref = edge_ref(driver, index);
      PosedEdge<Jet> p = pose(plain_p, ref);
      Feature<Interval> f;
      f.full = ref.full;
      f.e.arc = p.arc;
      f.e.ccw = p.ccw;
      f.e.s = {p.s.x.value, p.s.y.value};
      f.e.t = {p.t.x.value, p.t.y.value};
      if (p.arc) {
        f.e.c = {p.c.x.value, p.c.y.value};
        f.e.r2 = p.r2.value;
        f.e.r = p.r.value;
      }
      return f;
    };
    auto plain_sign = [](const Interval& v) { return v.sign(); };
    // The broad phase: an edge pair whose boxes (every point of each edge over the piece) are
    // certainly disjoint shares no point over the piece, so it has no event (tolerance_support.hpp).
    std::vector<EdgeBox> driver_boxes, follower_boxes;
    for (std::size_t a = 0; a < driver_edges_.size(); ++a) driver_boxes.push_back(edge_box(plain.get(true, a).e, driver_edges_[a].full));
    for (std::size_t b = 0; b < follower_edges_.size(); ++b)
      follower_boxes.push_back(edge_box(plain.get(false, b).e, follower_edges_[b].full));
    std::vector<Pending> pending;
    for (std::size_t a = 0; a < driver_edges_.size(); ++a)
      for (std::size_t b = 0; b < follower_edges_.size(); ++b) {
        if (boxes_apart(driver_boxes[a], follower_boxes[b])) continue;
        const Feature<Interval>& fa = plain.get(true, a);
        const Feature<Interval>& fb = plain.get(false, b);
        if (separated(fa.e, fb.e, plain_sign)) continue;
        for (EventKind kind : events(fa, fb))
          if (!side_excluded(path, a, b, kind, fa.e, fb.e) && !excluded<Interval>(kind, fa, fb, plain_sign, nullptr))
            pending.push_back({a, b, kind});
      }
    if (pending.empty()) return;

    // Mean-value form about the piece's centre.
    std::vector<Interval> offsets;
    std::vector<Jet> over_x, at_x;
    for (std::size_t i = 0; i < n; ++i) {
      offsets.push_back(offset(box[i]));
      over_x.push_back(Jet::variable(enclose(box[i]), i, n));
      at_x.push_back(Jet::variable(enclose(middle(box[i])), i, n));
    }
    Placement<Jet> over_p = placement(geometry(over_cache_, box, over_x), coordinates(path, over_x));
    Placement<Jet> at_p = placement(geometry(at_cache_, centre_key(box), at_x), coordinates(path, at_x));
    std::map<std::pair<bool, std::size_t>, std::pair<PosedEdge<Jet>, PosedEdge<Jet>>> first_order;
    auto first = [&](bool driver, std::size_t index) -> const std::pair<PosedEdge<Jet>, PosedEdge<Jet>>& {
      auto key = std::make_pair(driver, index);
      auto it = first_order.find(key);
      if (it != first_order.end()) return it->second;
      const EdgeRef& ref = edge_ref(driver, index);
      return first_order
          .emplace(key, std::make_pair(pose(over_p, ref), pose(at_p, ref)))
          .first->second;
    };
    Level<MeanValue> mean;
    mean.make = [&](bool driver, std::size_t index) {
      const auto& [o, a] = first(driver, index);
      return combined<MeanValue>(o, a, edge_ref(driver, index).full,
                                 [](const Jet& over, const Jet& at) { return MeanValue{over, at.value}; });
    };
    auto mean_sign = [&](const MeanValue& v) { return mean_value_sign(v, offsets); };
    std::vector<Pending> still;
    for (const Pending& e : pending) {
      const Feature<MeanValue>& fa = mean.get(true, e.a);
      const Feature<MeanValue>& fb = mean.get(false, e.b);
      if (!excluded<MeanValue>(e.kind, fa, fb, mean_sign, nullptr)) still.push_back(e);
    }
    if (still.empty()) return;

    // Second-order Taylor form.
    std::vector<Jet2> second_x;
    for (std::size_t i = 0; i < n; ++i) second_x.push_back(Jet2::variable(enclose(box[i]), i));
    Placement<Jet2> second_p = placement(geometry(second_cache_, box, second_x), coordinates(path, second_x));
    Level<Taylor> taylor;
    taylor.make = [&](bool driver, std::size_t index) {
      const EdgeRef& ref = edge_ref(driver, index);
      PosedEdge<Jet2> o = pose(second_p, ref);
      return combined<Taylor>(o, first(driver, index).second, ref.full,
                              [&](const Jet2& over, const Jet& at) { return make(over, at, &offsets); });
    };
    auto taylor_sign = [](const Taylor& v) { return v.over.value.sign(); };
    for (const Pending& e : still) {
      const Feature<Taylor>& fa = taylor.get(true, e.a);
      const Feature<Taylor>& fb = taylor.get(false, e.b);
      Taylor primary;
      if (excluded<Taylor>(e.kind, fa, fb, taylor_sign, &primary)) continue;
      if ((e.kind == EventKind::internal || e.kind == EventKind::external) &&
          tangency_excluded_reduced(e.kind, fa, fb, reduced_limit))
        continue;
      if (monotone_excluded(path, box, e, primary)) continue;
      undecided = std::string(event_text(e.kind)) + " of " + driver_edges_[e.a].name + " and " + follower_edges_[e.b].name;
      last_event_ = side_of(e);
      split = split_dimension(box, primary);
      return;
    }
  }

  // The two features of an event in Taylor form over `box` (offsets: x - c per dimension, kept
  // alive by the caller).
  std::pair<Feature<Taylor>, Feature<Taylor>> taylor_features(const Path& path, const std::vector<RationalInterval>& box,
                                                              const Pending& e, std::vector<Interval>& offsets) const {
    std::size_t n = k_ + 1;
    offsets.clear();
    std::vector<Jet> at_x;
    std::vector<Jet2> over_x;
    for (std::size_t i = 0; i < n; ++i) {
      offsets.push_back(offset(box[i]));
      at_x.push_back(Jet::variable(enclose(middle(box[i])), i, n));
      over_x.push_back(Jet2::variable(enclose(box[i]), i));
    }
    Placement<Jet> at_p = placement(geometry(at_cache_, centre_key(box), at_x), coordinates(path, at_x));
    Placement<Jet2> over_p = placement(geometry(second_cache_, box, over_x), coordinates(path, over_x));
    auto feature = [&](bool driver, std::size_t index) {
      const EdgeRef& ref = edge_ref(driver, index);
      PosedEdge<Jet2> o = pose(over_p, ref);
      PosedEdge<Jet> a = pose(at_p, ref);
      return combined<Taylor>(o, a, ref.full, [&](const Jet2& over, const Jet& at) { return make(over, at, &offsets); });
    };
    return {feature(true, e.a), feature(false, e.b)};
  }

  // The monotone form of an event's contact function f (docs/certify.md "Tolerance", check 7):
  // to show that f keeps over the piece X the sign `want` it has at X's centre, every dimension
  // whose partial derivative has a certain sign over the current face is fixed at the end of its
  // interval where f is nearest to 0 (for every x of the face, moving that coordinate to that end
  // moves f towards 0 and stays in the face, a box), and f is enclosed again in Taylor form over
  // the smaller face (up to four rounds). f of the certain sign `want` over the final face has
  // that sign over X: f has no zero there, so the event does not happen. Only f counts here, never
  // an extent test on a face (those hold on the face only).
  bool monotone_excluded(const Path& path, const std::vector<RationalInterval>& box, const Pending& e,
                         const Taylor& primary) const {
    int want = primary.at.value.sign();
    if (want == 0 || !primary.over.smooth) return false;
    std::vector<RationalInterval> face = box;
    Taylor f = primary;
    for (int round = 0; round < 4; ++round) {
      bool fixed = false;
      for (std::size_t a = 0; a < f.over.index.size(); ++a) {
        std::size_t i = f.over.index[a];
        if (!(face[i].lo < face[i].hi)) continue;
        int s = f.over.gradient[a].sign();
        if (s == 0) continue;
        Rational end = s == want ? face[i].lo : face[i].hi;
        face[i] = {end, end};
        fixed = true;
      }
      if (!fixed) return false;
      std::vector<Interval> offsets;
      auto [fa, fb] = taylor_features(path, face, e, offsets);
      Taylor g;
      excluded<Taylor>(e.kind, fa, fb, [](const Taylor& v) { return v.over.value.sign(); }, &g);
      if (g.over.value.sign() == want) return true;
      if (!g.over.smooth) return false;
      f = std::move(g);
      f.offsets = nullptr;   // the face's offsets end with this round; only over is read below
    }
    return false;
  }

  // An event that a side of the region's leaf excludes (session 20): checks 4 or 6 have proved,
  // in this evaluator and for this very leaf (witness_proved), that the side's contact
  // function F(side, d, y*(p, d)) has one certain sign over the whole leaf box, which holds the
  // region and every piece of it. F is zero wherever the side's two features touch: a vertex on
  // the other edge's line or circle, two circles tangent externally (both arcs ccw: |c1 - c2| =
  // r1 + r2) or internally (|c1 - c2| = |r1 - r2|), a circle tangent to a segment's line. The
  // matching event (the same edges, the same vertex, the same tangency) has its point on that
  // line or circle, so it is a zero of F: it cannot happen on the region's path. Not on a move
  // (the follower between two witnesses is not on the leaf's witness path).
  template <class E>
  bool side_excluded(const Path& path, std::size_t a, std::size_t b, EventKind kind, const E& ea, const E& eb) const {
    if (path.move) return false;
    const ToleranceLeaf& leaf = claim_.leaves[path.first];
    if (!leaf.witness || !ev_.witness_proved(path.first, leaf)) return false;
    const EdgeRef& da = driver_edges_[a];
    const EdgeRef& fb = follower_edges_[b];
    for (const LeafSide* side : {&leaf.lower, &leaf.upper}) {
      if (side->pair >= claim_.sides.size()) continue;
      const ContactSidePair& pair = claim_.sides[side->pair];
      if (pair.driver.edge.loop != da.loop || pair.driver.edge.edge != da.edge) continue;
      if (pair.follower.edge.loop != fb.loop || pair.follower.edge.edge != fb.edge) continue;
      EventKind matching;
      if (pair.driver.vertex && pair.follower.vertex) continue;
      if (pair.driver.vertex)
        matching = EventKind::first_vertex_on_second;
      else if (pair.follower.vertex)
        matching = EventKind::second_vertex_on_first;
      else {
        // The arcs' kinds and orientations as the contact function reads them (the parametric
        // edge values: ToleranceEvaluator::contact_of).
        bool a_arc = ea.arc, b_arc = eb.arc;
        if (a_arc && b_arc)
          matching = ea.ccw && eb.ccw ? EventKind::external : EventKind::internal;
        else if (a_arc != b_arc)
          matching = EventKind::tangency;
        else
          continue;
      }
      if (matching == kind) return true;
    }
    return false;
  }

  // An undecided vertex event as the contact side of its two features (nullopt for tangencies).
  std::optional<ContactSidePair> side_of(const Pending& e) const {
    if (e.kind != EventKind::first_vertex_on_second && e.kind != EventKind::second_vertex_on_first) return std::nullopt;
    const Model& m = ev_.model_->nominal();
    auto reference = [&](const EdgeRef& r, bool vertex) {
      FeatureReference f;
      f.edge = EdgeReference{m.parts[r.part].name, r.loop, r.edge, m.parts[r.part].loops[r.loop].edges[r.edge].label};
      f.vertex = vertex;
      return f;
    };
    bool driver_vertex = e.kind == EventKind::first_vertex_on_second;
    return ContactSidePair{reference(driver_edges_[e.a], driver_vertex), reference(follower_edges_[e.b], !driver_vertex)};
  }

  // The events a pair of edges can have (first: the driver's edge).
  template <class N>
  static std::vector<EventKind> events(const Feature<N>& a, const Feature<N>& b) {
    std::vector<EventKind> out;
    if (!a.full) out.push_back(EventKind::first_vertex_on_second);
    if (!b.full) out.push_back(EventKind::second_vertex_on_first);
    if (a.e.arc != b.e.arc) out.push_back(EventKind::tangency);
    if (a.e.arc && b.e.arc) {
      out.push_back(EventKind::external);
      out.push_back(EventKind::internal);
    }
    return out;
  }

  const EdgeRef& edge_ref(bool driver, std::size_t index) const {
    return driver ? driver_edges_[index] : follower_edges_[index];
  }

  // The dimension along which the undecided function varies most over the piece: the width
  // times (|gradient at the centre| + half the Hessian's row weighted by the widths); a
  // heuristic choice of work, never a verdict (any split keeps the proof sound).
  std::size_t split_dimension(const std::vector<RationalInterval>& box, const Taylor& f) const {
    std::size_t n = box.size();
    std::vector<double> width(n);
    for (std::size_t i = 0; i < n; ++i) width[i] = magnitude(enclose(box[i].hi - box[i].lo));
    std::vector<double> weight(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) weight[i] = magnitude(f.at.partial(i));
    if (f.over.smooth)
      for (std::size_t a = 0; a < f.over.index.size(); ++a)
        for (std::size_t b = 0; b < f.over.index.size(); ++b)
          weight[f.over.index[a]] += 0.5 * magnitude(f.over.second(a, b)) * width[f.over.index[b]];
    std::size_t best = n;
    double best_score = -1;
    for (std::size_t i = 0; i < n; ++i) {
      if (!(box[i].lo < box[i].hi)) continue;
      double score = width[i] * weight[i];
      if (score > best_score) {
        best_score = score;
        best = i;
      }
    }
    if (best == n || best_score <= 0) {   // nothing measurable: the widest dimension
      for (std::size_t i = 0; i < n; ++i)
        if (box[i].lo < box[i].hi && (best == n || width[i] > width[best])) best = i;
    }
    return best == n ? 0 : best;
  }

  const ToleranceEvaluator& ev_;
  const ToleranceClaim& claim_;
  std::size_t k_;
  mutable LocalCache<Jet> plain_cache_, over_cache_, at_cache_;
  mutable LocalCache<Jet2> second_cache_;
  /// The geometry at a centre's parameters for apart_failure (its parametric edges kept).
  std::map<std::vector<RationalInterval>, std::optional<ToleranceGeometry>, BoxLess> centre_geometry_;
  std::size_t budget_;
  std::size_t splits_ = 0;

 public:
  /// The dimension the undecided piece would have been split along when the budget ran out.
  std::optional<std::size_t> last_split_;
  /// The last undecided event as a contact side, when it is a vertex on an edge.
  std::optional<ContactSidePair> last_event_;
  std::vector<EdgeRef> driver_edges_, follower_edges_;
};

std::string ToleranceEvaluator::free_leaf_failure(std::size_t leaf, std::size_t piece_budget,
                                                  std::optional<std::size_t>* split,
                                                  std::optional<ContactSidePair>* event) const {
  FreePath check(*this, piece_budget);
  std::string failure = check.leaf(leaf);
  if (split) *split = check.last_split_;
  if (event) *event = check.last_event_;
  return failure;
}

std::string ToleranceEvaluator::free_path_failure(std::size_t piece_budget) const {
  if (claim_.property != "no_jam") return "";
  FreePath check(*this, piece_budget);
  return check.run();
}

}  // namespace hipair::verify
