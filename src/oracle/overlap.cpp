// Exact overlap predicate: apart / touching / overlapping for two parts bounded by segments
// and circular arcs, posed by exact rational rigid maps. See overlap.hpp and
// docs/contact-kernels.md ("The overlap predicate") for the argument.
//
// Method (in the second part's body frame, where only the first part is moved):
//  1. double bounding boxes from certified interval enclosures reject far edge pairs (only
//     while every enclosure is finite and below 2^200 in magnitude, so that no interval
//     operation overflows: a part beyond that range, e.g. with coordinates of 1e400 mm, is
//     analysed without boxes and without the interval filter, exactly);
//  2. each remaining edge pair is intersected exactly: a transversal crossing interior to
//     both edges means overlap; a common piece (collinear segments, cocircular arcs) with
//     material on the same side means overlap, on opposite sides touching; every other
//     common point (a vertex on the other boundary, a tangency) is a rational touch point;
//  3. at each touch point the boundary germs of both parts are sorted by tangent direction
//     and curvature; overlap iff some sector between consecutive germs is material of both;
//  4. a loop with no common point with the other boundary lies entirely inside or outside
//     the other part's interior: one exact point-in-region test per such loop decides.
#include "oracle/overlap.hpp"
#include "oracle/filter_counts.hpp"
#include "oracle/box_grid.hpp"
#include "curves/algebraic_overlap.hpp"

#include "algebra/near_quotient.hpp"
#include "kernels/interval.hpp"

#include <mpfr.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <optional>

namespace hipair::cspace {

namespace {

// ============================================================================ exact helpers

int sign_of(const Rational& value) { return sgn(value); }

// Sign of u + v sqrt(w), w >= 0.
int sign_with_root(const Rational& u, const Rational& v, const Rational& w) {
  int su = sgn(u);
  int sv = sgn(v);
  if (sv == 0 || sgn(w) == 0) return su;
  if (su == 0) return sv;
  if (su == sv) return su;
  int c = cmp(Rational(u * u), Rational(v * v * w));
  if (c > 0) return su;
  if (c < 0) return sv;
  return 0;
}

Point minus(const Point& a, const Point& b) { return difference(a, b); }

// (x - y) as numerator n over positive denominator d, without a gcd (one product of
// denominators, none when they are equal: a part's posed vertices often share one).
void fraction_free_difference(const Rational& x, const Rational& y, mpz_class& n, mpz_class& d) {
  mpz_srcptr xn = mpq_numref(x.get_mpq_t()), xd = mpq_denref(x.get_mpq_t());
  mpz_srcptr yn = mpq_numref(y.get_mpq_t()), yd = mpq_denref(y.get_mpq_t());
  if (mpz_cmp(xd, yd) == 0) {
    mpz_sub(n.get_mpz_t(), xn, yn);
    mpz_set(d.get_mpz_t(), xd);
    return;
  }
  mpz_mul(n.get_mpz_t(), xn, yd);
  mpz_submul(n.get_mpz_t(), yn, xd);
  mpz_mul(d.get_mpz_t(), xd, yd);
}

// Sign of cross(b - a, p - a), exactly, by integer products over the rationals' own
// (positive) denominators: the rational expression's canonical forms (a gcd per operation,
// which dominated the oracle when coordinates mix 10^-300 and millimetres) are never formed.
// The same sign as sgn(cross(minus(b, a), minus(p, a))).
int orientation_sign(const Point& a, const Point& b, const Point& p) {
  thread_local mpz_class ux, uxd, uy, uyd, vx, vxd, vy, vyd, left, right;
  fraction_free_difference(b.x, a.x, ux, uxd);
  fraction_free_difference(b.y, a.y, uy, uyd);
  fraction_free_difference(p.x, a.x, vx, vxd);
  fraction_free_difference(p.y, a.y, vy, vyd);
  // cross = ux vy / (uxd vyd) - uy vx / (uyd vxd); the denominators are positive
  const int sl = sgn(ux) * sgn(vy), sr = sgn(uy) * sgn(vx);
  // one product zero, or the two of opposite signs: the difference's sign is known without
  // forming them
  if (sl == 0) return -sr;
  if (sr == 0 || sl != sr) return sl;
  mpz_mul(left.get_mpz_t(), ux.get_mpz_t(), vy.get_mpz_t());
  mpz_mul(left.get_mpz_t(), left.get_mpz_t(), uyd.get_mpz_t());
  mpz_mul(left.get_mpz_t(), left.get_mpz_t(), vxd.get_mpz_t());
  mpz_mul(right.get_mpz_t(), uy.get_mpz_t(), vx.get_mpz_t());
  mpz_mul(right.get_mpz_t(), right.get_mpz_t(), uxd.get_mpz_t());
  mpz_mul(right.get_mpz_t(), right.get_mpz_t(), vyd.get_mpz_t());
  const int c = mpz_cmp(left.get_mpz_t(), right.get_mpz_t());
  return (c > 0) - (c < 0);
}

// Witness construction works at this precision: sites and directions are rational
// approximations with relative error about 2^-witness_bits.
constexpr mpfr_prec_t witness_bits = 640;

Rational to_rational(const mpfr_t value) {
  Rational result;
  mpfr_get_q(result.get_mpq_t(), value);
  return result;
}

// Rational approximation of sqrt(value), value >= 0.
Rational approximate_sqrt(const Rational& value) {
  mpfr_t root;
  mpfr_init2(root, witness_bits);
  mpfr_set_q(root, value.get_mpq_t(), MPFR_RNDN);
  mpfr_sqrt(root, root, MPFR_RNDN);
  Rational result = to_rational(root);
  mpfr_clear(root);
  return result;
}

// Rational approximation of v / |v|.
Point approximate_unit(const Point& v) {
  Rational length2 = dot(v, v);
  if (sgn(length2) == 0) return v;
  Rational length = approximate_sqrt(length2);
  return Point{Rational(v.x / length), Rational(v.y / length)};
}
Point left_perpendicular(const Point& v) { return Point{Rational(-v.y), v.x}; }

// ============================================================================ placed edges

// A point's coordinate for the box screens: rounded toward zero (so that for a box with double
// ends, `lo <= x <= hi` holds for the rounded value whenever it holds for the exact one), and
// +-DBL_MAX beyond double range (GMP's own conversion is system dependent there).
double toward_zero(const Rational& value) {
  double lower, upper;   // numerator and denominator within 53 bits: the same double without MPFR
  if (algebra::enclose_rational(value, lower, upper)) return lower > 0 ? lower : upper;
  mpfr_t rounded;
  mpfr_init2(rounded, 53);
  mpfr_set_q(rounded, value.get_mpq_t(), MPFR_RNDZ);
  double result = mpfr_get_d(rounded, MPFR_RNDZ);
  mpfr_clear(rounded);
  return result;
}

struct Box {
  double xlo = 0, xhi = 0, ylo = 0, yhi = 0;
  static Box everything() {
    double inf = std::numeric_limits<double>::infinity();
    return Box{-inf, inf, -inf, inf};
  }
  bool meets(const Box& other) const {
    return xlo <= other.xhi && other.xlo <= xhi && ylo <= other.yhi && other.ylo <= yhi;
  }
  bool contains(double x, double y) const { return xlo <= x && x <= xhi && ylo <= y && y <= yhi; }
  void add(double x, double y) {
    xlo = std::min(xlo, x);
    xhi = std::max(xhi, x);
    ylo = std::min(ylo, y);
    yhi = std::max(yhi, y);
  }
};

BoxGrid::Bounds bounds(const Box& box) { return BoxGrid::Bounds{box.xlo, box.xhi, box.ylo, box.yhi}; }

// A grid of boxes (BoxGrid) filed in index order.
BoxGrid grid_of(const std::vector<Box>& boxes) {
  std::vector<BoxGrid::Bounds> filed;
  filed.reserve(boxes.size());
  for (const Box& box : boxes) filed.push_back(bounds(box));
  return BoxGrid(filed);
}

// An arc's exact geometry beyond its ends (a segment has none: a segment's PlacedEdge makes no
// rational beyond its two ends).
struct PlacedArc {
  Point center;
  Rational radius_squared;
  kernels::ArcSector<Rational> sector;
};

struct PlacedEdge {
  bool arc = false;
  bool full = false;
  bool ccw = true;
  Point source;
  Point target;
  std::optional<PlacedArc> circle;   ///< set exactly when `arc`
  std::size_t loop = 0;
  std::size_t index = 0;
  const Point& center() const { return circle->center; }
  const Rational& radius_squared() const { return circle->radius_squared; }
  const kernels::ArcSector<Rational>& sector() const { return circle->sector; }
};

bool in_sector(const PlacedEdge& edge, const Point& v) { return sector_contains(edge.sector(), v); }

// Closed membership of a rational point.
bool on_edge(const PlacedEdge& edge, const Point& p) {
  if (!edge.arc) {
    if (orientation_sign(edge.source, edge.target, p) != 0) return false;
    Point d = minus(edge.target, edge.source);
    Point f = minus(p, edge.source);
    Rational along = dot(f, d);
    return sgn(along) >= 0 && along <= dot(d, d);
  }
  Point v = minus(p, edge.center());
  if (dot(v, v) != edge.radius_squared()) return false;
  return in_sector(edge, v);
}

bool is_endpoint(const PlacedEdge& edge, const Point& p) {
  return p == edge.source || p == edge.target;
}

using kernels::Interval;

// Session 47's lazy placement and block skips (set_lazy_placement: off is the route before).
bool lazy_placement_enabled = true;

// The double intervals are used only while they are finite and at most 2^200 in magnitude:
// then no operation of the filter (degree 4 in coordinates at most) overflows, and no
// infinity or NaN can enter a bound. Beyond (or for NaN) the exact path alone decides.
constexpr double tame_limit = 0x1p200;
bool tame(const Interval& value) { return value.lo >= -tame_limit && value.hi <= tame_limit; }

// Certified enclosure of a rigid map p -> (c x - s y + ox, s x + c y + oy).
struct IntervalMap {
  Interval c{1};
  Interval s{0};
  Interval ox{0};
  Interval oy{0};
  void apply(const Interval& x, const Interval& y, Interval& u, Interval& v) const {
    u = c * x - s * y + ox;
    v = s * x + c * y + oy;
  }
  static IntervalMap enclose(const RigidMap& map) {
    return IntervalMap{algebra::enclose_kernel(map.c), algebra::enclose_kernel(map.s),
                       algebra::enclose_kernel(map.offset.x), algebra::enclose_kernel(map.offset.y)};
  }
  bool tame() const { return hipair::cspace::tame(c) && hipair::cspace::tame(s) && hipair::cspace::tame(ox) && hipair::cspace::tame(oy); }
};

// An edge's posed geometry as certified intervals (the filter stage).
struct IntervalEdge {
  bool arc = false;
  bool full = false;
  bool ccw = true;
  int large = 0;  // arc sector wider than a half turn: 0 no, 1 yes, 2 unknown
  Interval sx, sy, tx, ty, cx, cy, radius_squared;
  Interval start_x, start_y, end_x, end_y;  // sector: counter-clockwise from start to end
  bool tame() const {
    for (const Interval* v : {&sx, &sy, &tx, &ty, &cx, &cy, &radius_squared, &start_x, &start_y, &end_x, &end_y})
      if (!hipair::cspace::tame(*v)) return false;
    return true;
  }
};

// A part's pose-independent data: its edges in boundary order and certified enclosures of their
// body coordinates (Interval::enclose of each rational: mpq_get_d is most of the cost of a
// placement, and the enclosures do not depend on the pose). Immutable once built.
struct PartEnclosure {
  struct Body {
    Interval sx, sy, tx, ty, cx, cy, radius_squared;
  };
  // A body-frame disk (centre, radius: doubles) holding edges [k * kBlock, (k + 1) * kBlock)
  // of the boundary order (session 47): posed by a rigid map, the disk's mapped centre widened
  // by the radius is a certified box of those edges (a rotation keeps distances), from one
  // interval product per block instead of every edge's placement. Empty: not prepared (or a
  // part beyond the tame range), and every placement is eager.
  struct Block {
    double cx = 0, cy = 0, r = 0;
  };
  static constexpr std::size_t kBlock = 8;
  // Every body coordinate within 2^64 in magnitude and every arc's squared radius within 2^128
  // (session 70): then an edge posed by a map whose cos/sin are within 2 and offsets within
  // 2^64 (bounded_map) has every value of its interval geometry within 2^69, far inside the
  // tame range (2^200): posed_edge cannot fail there.
  static constexpr double kBodyBound = 0x1p64;
  const Part* part = nullptr;
  std::vector<std::pair<std::size_t, std::size_t>> refs;
  std::vector<std::size_t> loop_begin;
  std::vector<Body> body;
  std::vector<Block> blocks;
  // each edge's own disk (session 74; made with the blocks, empty when they are): posed, a
  // certified box of the edge from one interval product, where posing the edge costs ~25
  std::vector<Block> edge_disks;
  bool bounded = true;

  explicit PartEnclosure(const Part& source) : part(&source) {
    for (std::size_t l = 0; l < source.loops.size(); ++l) {
      loop_begin.push_back(refs.size());
      for (std::size_t e = 0; e < source.loops[l].edges.size(); ++e) refs.push_back({l, e});
    }
    loop_begin.push_back(refs.size());
    body.reserve(refs.size());
    for (const auto& [l, e] : refs) {
      const Edge& edge = source.loops[l].edges[e];
      Body b;
      b.sx = algebra::enclose_kernel(edge.source.x);
      b.sy = algebra::enclose_kernel(edge.source.y);
      if (!edge.is_full_circle()) {
        b.tx = algebra::enclose_kernel(edge.target.x);
        b.ty = algebra::enclose_kernel(edge.target.y);
      }
      if (edge.is_arc()) {
        b.cx = algebra::enclose_kernel(edge.center.x);
        b.cy = algebra::enclose_kernel(edge.center.y);
        b.radius_squared = algebra::enclose_kernel(edge.radius_squared);
      }
      auto within = [](const Interval& v, double bound) { return v.lo >= -bound && v.hi <= bound; };
      bounded = bounded && within(b.sx, kBodyBound) && within(b.sy, kBodyBound) && within(b.tx, kBodyBound) &&
                within(b.ty, kBodyBound) && within(b.cx, kBodyBound) && within(b.cy, kBodyBound) &&
                within(b.radius_squared, kBodyBound * kBodyBound);
      body.push_back(b);
    }
  }
};

// A map under which every edge of a bounded PartEnclosure poses tame (PartEnclosure::bounded).
bool bounded_map(const IntervalMap& map) {
  auto within = [](const Interval& v, double bound) { return v.lo >= -bound && v.hi <= bound; };
  return within(map.c, 2) && within(map.s, 2) && within(map.ox, PartEnclosure::kBodyBound) &&
         within(map.oy, PartEnclosure::kBodyBound);
}

// The interval geometry of a placed part: every edge's posed enclosure and box, each loop's box
// and the whole part's.
struct Placement {
  std::vector<IntervalEdge> intervals;
  std::vector<Box> boxes;
  std::vector<Box> loop_boxes;
  // the union of the boxes of edges [k * kBlock, (k + 1) * kBlock) (eager placements only): a
  // box that misses it misses each of them
  std::vector<Box> block_boxes;
  Box total;
  bool filtered = true;
};

// A part placed in the common frame by a rigid map: certified interval geometry and boxes
// for every edge, exact geometry computed lazily (the exact map itself is computed only
// when first needed). A part at the identity (the second part, in whose body frame the
// analysis works) can borrow a placement and its exact edges computed once (`IdentityPart`):
// they do not depend on the pose.
class PlacedPart {
 public:
  PlacedPart(const Part& part, const IntervalMap& map, std::function<RigidMap()> exact_map,
             bool identity)
      : PlacedPart(std::make_shared<const PartEnclosure>(part), map, std::move(exact_map), identity) {}

  // `lazy` (and the enclosure's blocks prepared, the map tame): the edges' interval geometry
  // made on first use, the part's and loops' boxes from the blocks' posed disks (session 47).
  PlacedPart(std::shared_ptr<const PartEnclosure> enclosure, const IntervalMap& map,
             std::function<RigidMap()> exact_map, bool identity, bool lazy = false)
      : enclosure_(std::move(enclosure)), exact_source_(std::move(exact_map)), identity_(identity) {
    if (!(lazy && !enclosure_->blocks.empty() && map.tame() && place_lazily(map))) place(*enclosure_, map, own_);
    placement_ = &own_;
    exact_.resize(enclosure_->refs.size());
  }

  // At the identity, borrowing `placement` (placed at IntervalMap{}) and `exact` (every edge's
  // exact geometry at the identity), both of `enclosure`'s part and alive while this is.
  PlacedPart(std::shared_ptr<const PartEnclosure> enclosure, const Placement& placement,
             const std::vector<PlacedEdge>& exact)
      : enclosure_(std::move(enclosure)), identity_(true), placement_(&placement), borrowed_exact_(&exact) {}

  PlacedPart(const PlacedPart&) = delete;
  PlacedPart& operator=(const PlacedPart&) = delete;

  /// The interval enclosures (and the boxes from them) are usable: every one is tame. When
  /// false, every box is the whole plane and only exact tests decide.
  bool filtered() const { return placement_->filtered && !untamed_; }

  std::size_t size() const { return enclosure_->refs.size(); }
  std::size_t loops() const { return enclosure_->part->loops.size(); }
  std::size_t loop_begin(std::size_t loop) const { return enclosure_->loop_begin[loop]; }
  std::size_t loop_end(std::size_t loop) const { return enclosure_->loop_begin[loop + 1]; }
  /// A certified box of edge i that may be wider than box(i) (its block's, when lazy): an edge
  /// whose coarse box misses a region cannot meet it; only then is box(i) asked.
  const Box& coarse(std::size_t i) const {
    return lazy_ ? coarse_[i / PartEnclosure::kBlock] : placement_->boxes[i];
  }
  const Box& box(std::size_t i) const {
    if (lazy_ && !placed_[i]) ensure(i);
    return placement_->boxes[i];
  }
  const IntervalEdge& interval(std::size_t i) const {
    if (lazy_ && !placed_[i]) ensure(i);
    return placement_->intervals[i];
  }
  /// Lazy placements with edge disks (PartEnclosure::edge_disks): edge i's posed disk's box, a
  /// certified box of the edge from one interval product (session 74); false otherwise (or
  /// beyond the tame range), `out` unset.
  bool disk_box(std::size_t i, Box& out) const {
    return lazy_ && !enclosure_->edge_disks.empty() && posed_block(enclosure_->edge_disks[i], map_, out);
  }
  /// Eager placements: the blocks' boxes (Placement::block_boxes); nullptr when lazy.
  const std::vector<Box>* block_boxes() const { return lazy_ ? nullptr : &placement_->block_boxes; }
  /// Lazy placement met an edge whose enclosure is beyond the tame range: the analysis's answer
  /// is not used, the caller repeats it eagerly (where every box is the whole plane).
  bool untamed() const { return untamed_; }
  bool lazy() const { return lazy_; }
  /// The edges whose interval geometry was made (all when not lazy).
  std::size_t placed_edges() const {
    return lazy_ ? static_cast<std::size_t>(std::count(placed_.begin(), placed_.end(), 1)) : size();
  }
  const Box& total() const { return placement_->total; }
  const Box& loop_box(std::size_t loop) const { return placement_->loop_boxes[loop]; }
  const Edge& original(std::size_t i) const {
    const auto& ref = enclosure_->refs[i];
    return enclosure_->part->loops[ref.first].edges[ref.second];
  }

  const PlacedEdge& edge(std::size_t i) {
    if (borrowed_exact_) return (*borrowed_exact_)[i];
    if (!exact_[i]) {
      if (!identity_ && !exact_map_) exact_map_ = exact_source_();
      exact_[i] = place_exact(i, identity_ ? nullptr : &*exact_map_);
    }
    return *exact_[i];
  }

  // The interval placement of `enclosure`'s part by `map`.
  static void place(const PartEnclosure& enclosure, const IntervalMap& map, Placement& out) {
    const std::size_t n = enclosure.refs.size();
    const Part& part = *enclosure.part;
    out.intervals.resize(n);
    out.boxes.resize(n);
    out.total = Box{1e300, -1e300, 1e300, -1e300};
    out.loop_boxes.assign(part.loops.size(), Box{1e300, -1e300, 1e300, -1e300});
    out.filtered = map.tame();
    for (std::size_t i = 0; i < n; ++i) {
      const auto& ref = enclosure.refs[i];
      out.intervals[i] = interval_edge(part.loops[ref.first].edges[ref.second], enclosure.body[i], map);
      out.filtered = out.filtered && out.intervals[i].tame();
    }
    for (std::size_t i = 0; i < n; ++i) {
      out.boxes[i] = out.filtered ? box_of(out.intervals[i]) : Box::everything();
      out.total.add(out.boxes[i].xlo, out.boxes[i].ylo);
      out.total.add(out.boxes[i].xhi, out.boxes[i].yhi);
      out.loop_boxes[enclosure.refs[i].first].add(out.boxes[i].xlo, out.boxes[i].ylo);
      out.loop_boxes[enclosure.refs[i].first].add(out.boxes[i].xhi, out.boxes[i].yhi);
    }
    out.block_boxes.assign((n + PartEnclosure::kBlock - 1) / PartEnclosure::kBlock, Box{1e300, -1e300, 1e300, -1e300});
    for (std::size_t i = 0; i < n; ++i) {
      Box& block = out.block_boxes[i / PartEnclosure::kBlock];
      block.add(out.boxes[i].xlo, out.boxes[i].ylo);
      block.add(out.boxes[i].xhi, out.boxes[i].yhi);
    }
  }

  // The blocks' posed disks as boxes, the part's and loops' boxes from them; the edges' own
  // geometry left for ensure(). False (nothing kept) when a box is beyond the tame range.
  bool place_lazily(const IntervalMap& map) {
    const PartEnclosure& enclosure = *enclosure_;
    const std::size_t n = enclosure.refs.size();
    coarse_.resize(enclosure.blocks.size());
    for (std::size_t k = 0; k < enclosure.blocks.size(); ++k)
      if (!posed_block(enclosure.blocks[k], map, coarse_[k])) return false;
    own_.intervals.resize(n);
    own_.boxes.resize(n);
    own_.filtered = true;
    own_.total = Box{1e300, -1e300, 1e300, -1e300};
    own_.loop_boxes.assign(enclosure.part->loops.size(), Box{1e300, -1e300, 1e300, -1e300});
    for (const Box& box : coarse_) {
      own_.total.add(box.xlo, box.ylo);
      own_.total.add(box.xhi, box.yhi);
    }
    for (std::size_t l = 0; l + 1 < enclosure.loop_begin.size(); ++l) {
      const std::size_t begin = enclosure.loop_begin[l], end = enclosure.loop_begin[l + 1];
      if (begin == end) continue;
      for (std::size_t k = begin / PartEnclosure::kBlock; k <= (end - 1) / PartEnclosure::kBlock; ++k) {
        own_.loop_boxes[l].add(coarse_[k].xlo, coarse_[k].ylo);
        own_.loop_boxes[l].add(coarse_[k].xhi, coarse_[k].yhi);
      }
    }
    placed_.assign(n, 0);
    map_ = map;
    lazy_ = true;
    return true;
  }

  // Edge i's interval geometry and box, made on its first use when lazy (as place() makes it).
  [[gnu::noinline]] void ensure(std::size_t i) const {
    if (!posed_edge(*enclosure_, i, map_, own_.intervals[i], own_.boxes[i])) {
      untamed_ = true;
      own_.boxes[i] = Box::everything();
    }
    placed_[i] = 1;
  }

  // The box of a block's disk (PartEnclosure::Block) posed by `map`: a certified box of the
  // block's edges at every pose of the map; false when beyond the tame range.
  static bool posed_block(const PartEnclosure::Block& block, const IntervalMap& map, Box& out) {
    Interval u, v;
    map.apply(Interval::point(block.cx), Interval::point(block.cy), u, v);
    const Interval r = Interval::point(block.r);
    const Interval xlo = u - r, xhi = u + r, ylo = v - r, yhi = v + r;
    if (!tame(xlo) || !tame(xhi) || !tame(ylo) || !tame(yhi)) return false;
    out = Box{xlo.lo, xhi.hi, ylo.lo, yhi.hi};
    return true;
  }

  // Edge i of `enclosure`'s part posed by `map`: its interval geometry (as place() makes it)
  // and, when tame, its box; false (the box not set) when beyond the tame range.
  static bool posed_edge(const PartEnclosure& enclosure, std::size_t i, const IntervalMap& map, IntervalEdge& e,
                         Box& box) {
    const auto& ref = enclosure.refs[i];
    e = interval_edge(enclosure.part->loops[ref.first].edges[ref.second], enclosure.body[i], map);
    if (!e.tame()) return false;
    box = box_of(e);
    return true;
  }

  // Edge i's exact geometry placed by `map` (nullptr: the identity).
  PlacedEdge place_exact(std::size_t i, const RigidMap* map) const { return place_exact(*enclosure_, i, map); }

  // Edge i of `enclosure`'s part placed by `map` (nullptr: the identity): the ends made where
  // they stay (no default rationals assigned over), an arc's centre, radius and sector only for
  // an arc.
  static PlacedEdge place_exact(const PartEnclosure& enclosure, std::size_t i, const RigidMap* map) {
    const auto& [loop, index] = enclosure.refs[i];
    const Edge& source = enclosure.part->loops[loop].edges[index];
    PlacedEdge placed{source.is_arc(),
                      source.is_full_circle(),
                      source.ccw,
                      map ? map->apply(source.source) : source.source,
                      map ? map->apply(source.target) : source.target,
                      std::nullopt,
                      loop,
                      index};
    if (placed.arc) {
      PlacedArc& arc = placed.circle.emplace();
      arc.center = !map ? source.center : map->apply(source.center);
      arc.radius_squared = source.radius_squared;
      Edge moved;
      moved.kind = Edge::Kind::arc;
      moved.source = placed.source;
      moved.target = placed.target;
      moved.center = arc.center;
      moved.ccw = placed.ccw;
      arc.sector = arc_sector(moved);
    }
    return placed;
  }

 private:
  static IntervalEdge interval_edge(const Edge& edge, const PartEnclosure::Body& body, const IntervalMap& map) {
    IntervalEdge e;
    e.arc = edge.is_arc();
    e.full = edge.is_full_circle();
    e.ccw = edge.ccw;
    map.apply(body.sx, body.sy, e.sx, e.sy);
    if (e.full) {
      e.tx = e.sx;
      e.ty = e.sy;
    } else {
      map.apply(body.tx, body.ty, e.tx, e.ty);
    }
    if (!e.arc) return e;
    map.apply(body.cx, body.cy, e.cx, e.cy);
    e.radius_squared = body.radius_squared;
    Interval ax = e.sx - e.cx, ay = e.sy - e.cy, bx = e.tx - e.cx, by = e.ty - e.cy;
    if (!e.ccw) {
      std::swap(ax, bx);
      std::swap(ay, by);
    }
    e.start_x = ax;
    e.start_y = ay;
    e.end_x = bx;
    e.end_y = by;
    if (!e.full) {
      int turn = (ax * by - ay * bx).sign();
      if (turn == 2) {
        // decide exactly from the body geometry (rotation does not change it)
        Point start = difference(edge.ccw ? edge.source : edge.target, edge.center);
        Point end = difference(edge.ccw ? edge.target : edge.source, edge.center);
        turn = sgn(cross(start, end));
      }
      e.large = turn < 0 ? 1 : 0;
    }
    return e;
  }

  // Possibly-in-sector test for the direction u (exact unit axis vector).
  static bool possibly_in_sector(const IntervalEdge& e, double ux, double uy) {
    if (e.full) return true;
    Interval after = e.start_x * Interval(uy, uy) - e.start_y * Interval(ux, ux);
    Interval before = Interval(ux, ux) * e.end_y - Interval(uy, uy) * e.end_x;
    bool a = after.hi >= 0;
    bool b = before.hi >= 0;
    return e.large ? (a || b) : (a && b);
  }

  static Box box_of(const IntervalEdge& e) {
    Box box{std::min(e.sx.lo, e.tx.lo), std::max(e.sx.hi, e.tx.hi), std::min(e.sy.lo, e.ty.lo),
            std::max(e.sy.hi, e.ty.hi)};
    if (!e.arc) return box;
    Interval r = kernels::sqrt(e.radius_squared);
    if (possibly_in_sector(e, 1, 0)) box.xhi = std::max(box.xhi, (e.cx + r).hi);
    if (possibly_in_sector(e, -1, 0)) box.xlo = std::min(box.xlo, (e.cx - r).lo);
    if (possibly_in_sector(e, 0, 1)) box.yhi = std::max(box.yhi, (e.cy + r).hi);
    if (possibly_in_sector(e, 0, -1)) box.ylo = std::min(box.ylo, (e.cy - r).lo);
    return box;
  }

  std::shared_ptr<const PartEnclosure> enclosure_;
  std::function<RigidMap()> exact_source_;
  std::optional<RigidMap> exact_map_;
  bool identity_;
  // (mutable: a lazy placement's edges are made by the const accessors)
  mutable Placement own_;
  const Placement* placement_ = nullptr;
  bool lazy_ = false;
  mutable bool untamed_ = false;
  IntervalMap map_;
  mutable std::vector<char> placed_;
  std::vector<Box> coarse_;
  std::vector<std::optional<PlacedEdge>> exact_;
  const std::vector<PlacedEdge>* borrowed_exact_ = nullptr;
};

// A part at the identity, placed once: the interval placement and every edge's exact geometry,
// shared (read only) by the analyses that borrow them.
struct IdentityPart {
  std::shared_ptr<const PartEnclosure> enclosure;
  Placement placement;
  std::vector<PlacedEdge> exact;

  explicit IdentityPart(const Part& part) : enclosure(std::make_shared<const PartEnclosure>(part)) {
    PlacedPart::place(*enclosure, IntervalMap{}, placement);
    const std::size_t n = enclosure->refs.size();
    exact.reserve(n);
    for (std::size_t i = 0; i < n; ++i) exact.push_back(PlacedPart::place_exact(*enclosure, i, nullptr));
  }
};

// The blocks of `enclosure` (PartEnclosure::Block): each block's edges' boxes at the identity
// (certified), their union's middle as the disk's centre, the distance to the farthest corner
// rounded up as its radius. Left empty for a part beyond the tame range.
// (Session 74: each edge's own disk too, PartEnclosure::edge_disks, made the same way from its
// box alone.)
bool disk_of(const Box& box, PartEnclosure::Block& block);

void prepare_blocks(PartEnclosure& enclosure) {
  Placement body;
  PlacedPart::place(enclosure, IntervalMap{}, body);
  if (!body.filtered) return;
  const std::size_t n = enclosure.refs.size();
  std::vector<PartEnclosure::Block> blocks, edge_disks(n);
  for (std::size_t first = 0; first < n; first += PartEnclosure::kBlock) {
    Box box{1e300, -1e300, 1e300, -1e300};
    for (std::size_t i = first; i < std::min(n, first + PartEnclosure::kBlock); ++i) {
      box.add(body.boxes[i].xlo, body.boxes[i].ylo);
      box.add(body.boxes[i].xhi, body.boxes[i].yhi);
      if (!disk_of(body.boxes[i], edge_disks[i])) return;
    }
    PartEnclosure::Block block;
    if (!disk_of(box, block)) return;
    blocks.push_back(block);
  }
  enclosure.blocks = std::move(blocks);
  enclosure.edge_disks = std::move(edge_disks);
}

// A disk (PartEnclosure::Block) holding `box`: its middle as the centre, the distance to the
// farthest corner rounded up as the radius; false beyond the tame range.
bool disk_of(const Box& box, PartEnclosure::Block& block) {
  block.cx = 0.5 * box.xlo + 0.5 * box.xhi;
  block.cy = 0.5 * box.ylo + 0.5 * box.yhi;
  // |p - c| <= r for every p of the box: the half-extents from c to the farther side, upward
  const double hx = std::max((Interval::point(block.cx) - Interval::point(box.xlo)).hi,
                             (Interval::point(box.xhi) - Interval::point(block.cx)).hi);
  const double hy = std::max((Interval::point(block.cy) - Interval::point(box.ylo)).hi,
                             (Interval::point(box.yhi) - Interval::point(block.cy)).hi);
  const Interval hx2 = Interval::point(hx) * Interval::point(hx), hy2 = Interval::point(hy) * Interval::point(hy);
  block.r = kernels::sqrt(hx2 + hy2).hi;
  return std::isfinite(block.r) && tame(Interval::point(block.cx)) && tame(Interval::point(block.cy)) &&
         tame(Interval::point(block.r));
}

// ============================================================================ interval filter

// Certified decisions on an edge pair from interval geometry.
enum class Filter { disjoint, overlapping, unknown };

Interval icross(const Interval& ax, const Interval& ay, const Interval& bx, const Interval& by) {
  return ax * by - ay * bx;
}
Interval idot(const Interval& ax, const Interval& ay, const Interval& bx, const Interval& by) {
  return ax * bx + ay * by;
}

// Sign of a value known to be of interest: -1, 0 (impossible here: treated as unknown), +1,
// or 2 when unknown.
int strict_sign(const Interval& value) {
  int s = value.sign();
  return s == 0 ? 2 : s;
}

Filter filter_segment_segment(const IntervalEdge& a, const IntervalEdge& b) {
  Interval dax = a.tx - a.sx, day = a.ty - a.sy, dbx = b.tx - b.sx, dby = b.ty - b.sy;
  int o1 = strict_sign(icross(dbx, dby, a.sx - b.sx, a.sy - b.sy));
  int o2 = strict_sign(icross(dbx, dby, a.tx - b.sx, a.ty - b.sy));
  int o3 = strict_sign(icross(dax, day, b.sx - a.sx, b.sy - a.sy));
  int o4 = strict_sign(icross(dax, day, b.tx - a.sx, b.ty - a.sy));
  if ((o1 != 2 && o1 == o2) || (o3 != 2 && o3 == o4)) return Filter::disjoint;
  if (o1 != 2 && o2 != 2 && o3 != 2 && o4 != 2 && o1 != o2 && o3 != o4)
    return Filter::overlapping;  // proper crossing, interior to both
  return Filter::unknown;
}

// Whether the point (vx, vy) relative to an arc's centre is certainly strictly inside its
// sector (1), certainly outside its closed sector (0), or unknown (2).
int in_sector_certainly(const IntervalEdge& arc, const Interval& vx, const Interval& vy) {
  if (arc.full) return 1;
  if (arc.large == 2) return 2;
  int after = strict_sign(icross(arc.start_x, arc.start_y, vx, vy));
  int before = strict_sign(icross(vx, vy, arc.end_x, arc.end_y));
  if (after == 2 || before == 2) return 2;
  bool a = after > 0, b = before > 0;
  return (arc.large ? (a || b) : (a && b)) ? 1 : 0;
}

Filter filter_segment_arc(const IntervalEdge& segment, const IntervalEdge& arc) {
  Interval dx = segment.tx - segment.sx, dy = segment.ty - segment.sy;
  Interval fx = segment.sx - arc.cx, fy = segment.sy - arc.cy;
  Interval a = idot(dx, dy, dx, dy);
  Interval b = idot(dx, dy, fx, fy);
  Interval c = idot(fx, fy, fx, fy) - arc.radius_squared;
  Interval disc = b * b - a * c;
  int sd = strict_sign(disc);
  if (sd < 0) return Filter::disjoint;
  if (sd == 2 || a.lo <= 0) return Filter::unknown;
  Interval root = kernels::sqrt(disc);
  bool all_disjoint = true;
  for (int k = 0; k < 2; ++k) {
    Interval lambda = (-b + (k == 0 ? root : -root)) / a;
    int in_segment;
    if (lambda.lo > 0 && lambda.hi < 1) {
      in_segment = 1;
    } else if (lambda.hi < 0 || lambda.lo > 1) {
      in_segment = 0;
    } else {
      in_segment = 2;
    }
    if (in_segment == 0) continue;
    int in_arc = in_sector_certainly(arc, fx + lambda * dx, fy + lambda * dy);
    if (in_arc == 0) continue;
    if (in_segment == 1 && in_arc == 1) return Filter::overlapping;
    all_disjoint = false;
  }
  return all_disjoint ? Filter::disjoint : Filter::unknown;
}

Filter filter_arc_arc(const IntervalEdge& ea, const IntervalEdge& eb) {
  Interval dx = eb.cx - ea.cx, dy = eb.cy - ea.cy;
  Interval distance2 = idot(dx, dy, dx, dy);
  if (distance2.lo <= 0) return Filter::unknown;  // possibly concentric: exact
  Interval m = distance2 + ea.radius_squared - eb.radius_squared;
  Interval h = Interval(4) * distance2 * ea.radius_squared - m * m;
  int sh = strict_sign(h);
  if (sh < 0) return Filter::disjoint;
  if (sh == 2) return Filter::unknown;
  Interval root = kernels::sqrt(h);
  Interval scale = Interval(2) * distance2;
  bool all_disjoint = true;
  for (int k = 0; k < 2; ++k) {
    Interval beta = k == 0 ? root : -root;
    // scale * (x - ka) = m d + beta perp(d); scale * (x - kb) = (m - scale) d + beta perp(d)
    Interval ax = m * dx - beta * dy, ay = m * dy + beta * dx;
    Interval bx = (m - scale) * dx - beta * dy, by = (m - scale) * dy + beta * dx;
    int in_a = in_sector_certainly(ea, ax, ay);
    if (in_a == 0) continue;
    int in_b = in_sector_certainly(eb, bx, by);
    if (in_b == 0) continue;
    if (in_a == 1 && in_b == 1) return Filter::overlapping;
    all_disjoint = false;
  }
  return all_disjoint ? Filter::disjoint : Filter::unknown;
}

Filter filter_pair(const IntervalEdge& a, const IntervalEdge& b) {
  if (!a.arc && !b.arc) return filter_segment_segment(a, b);
  if (!a.arc) return filter_segment_arc(a, b);
  if (!b.arc) return filter_segment_arc(b, a);
  return filter_arc_arc(a, b);
}

// Ray-casting location of an interval point; nullopt when some decision is uncertain.
std::optional<bool> inside_by_intervals(const PlacedPart& part, const Interval& px,
                                        const Interval& py) {
  if (!part.filtered() || !tame(px) || !tame(py)) return std::nullopt;
  bool inside = false;
  for (std::size_t i = 0; i < part.size(); ++i) {
    const Box& coarse = part.coarse(i);
    if (coarse.xhi < px.lo || coarse.yhi < py.lo || coarse.ylo > py.hi) continue;  // misses the ray
    const Box& box = part.box(i);
    if (box.xhi < px.lo || box.yhi < py.lo || box.ylo > py.hi) continue;  // misses the ray
    const IntervalEdge& e = part.interval(i);
    auto crosses_chord = [&](bool& result) {
      int a_above = strict_sign(e.sy - py);
      int b_above = strict_sign(e.ty - py);
      if (a_above == 2 || b_above == 2) return false;
      if (a_above == b_above) {
        result = false;
        return true;
      }
      int o = strict_sign(icross(e.tx - e.sx, e.ty - e.sy, px - e.sx, py - e.sy));
      if (o == 2) return false;
      result = b_above > 0 ? o > 0 : o < 0;
      return true;
    };
    if (!e.arc || !e.full) {
      bool crossing = false;
      if (!crosses_chord(crossing)) return std::nullopt;
      if (crossing) inside = !inside;
      if (!e.arc) continue;
    }
    Interval vx = px - e.cx, vy = py - e.cy;
    int in_disk = strict_sign(e.radius_squared - idot(vx, vy, vx, vy));
    if (in_disk == 2) return std::nullopt;
    if (in_disk < 0) continue;
    if (e.full) {
      inside = !inside;
      continue;
    }
    int side = strict_sign(icross(e.tx - e.sx, e.ty - e.sy, px - e.sx, py - e.sy));
    if (side == 2) return std::nullopt;
    if (e.ccw ? side < 0 : side > 0) inside = !inside;
  }
  return inside;
}

// ============================================================================ the analysis

struct Site {
  Point point;          // rational approximation of where overlap was found
  bool known = false;
};

// Session 75 (growth75): the last few edge pairs (first part's edge, second part's edge) that
// certified a crossing of one pair's parts on one thread, most recent first:
// PairOverlap::certainly_overlapping tries them before its broad phase (consecutive questions
// about one region of a pair's configuration space find the same teeth overlapping). Only ever
// a guess to test first: the answer does not depend on it (the argument where it is read).
struct PairMemo {
  const void* owner = nullptr;
  std::array<std::pair<std::uint32_t, std::uint32_t>, 4> pairs{};
  std::size_t count = 0;
  void reset_for(const void* who) {
    if (owner != who) owner = who, count = 0;
  }
  void remember(const void* who, std::size_t i, std::size_t j) {
    reset_for(who);
    const std::pair<std::uint32_t, std::uint32_t> pair{static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)};
    std::size_t at = 0;
    while (at < count && pairs[at] != pair) ++at;
    if (at == count && count < pairs.size()) ++count;
    for (std::size_t k = std::min(at, count - 1); k > 0; --k) pairs[k] = pairs[k - 1];
    pairs[0] = pair;
  }
};

class OverlapAnalysis {
 public:
  OverlapAnalysis(PlacedPart& first, PlacedPart& second) : parts_{&first, &second} {
    touched_[0].assign(first.loops(), false);
    touched_[1].assign(second.loops(), false);
  }

  Overlap run() {
    if (!parts_[0]->total().meets(parts_[1]->total())) return Overlap::apart;
    PlacedPart& a = *parts_[0];
    PlacedPart& b = *parts_[1];
    const std::vector<Box>* b_blocks = lazy_placement_enabled ? b.block_boxes() : nullptr;
    if (b_grid_) {
      if (grid_pairs()) return Overlap::overlapping;
    } else {
      for (std::size_t i = 0; i < a.size(); ++i) {
        if (!a.coarse(i).meets(b.total())) continue;
        const Box& box = a.box(i);
        if (!box.meets(b.total())) continue;
        for (std::size_t j = 0; j < b.size(); ++j) {
          // a block of b's edges whose boxes' union misses edge i's box: none of them meets it
          if (b_blocks && j % PartEnclosure::kBlock == 0 && !box.meets((*b_blocks)[j / PartEnclosure::kBlock])) {
            j += PartEnclosure::kBlock - 1;
            continue;
          }
          if (!box.meets(b.box(j))) continue;
          if (pair_overlaps(i, j)) return Overlap::overlapping;
        }
      }
    }
    for (const Point& p : touch_points_)
      if (locally_overlapping(p)) return Overlap::overlapping;
    for (int side = 0; side < 2; ++side)
      if (loop_inside_other(side)) return Overlap::overlapping;
    return touch_points_.empty() && !shared_ ? Overlap::apart : Overlap::touching;
  }

  // Edge i of the first part against edge j of the second (their boxes meet): true on overlap.
  bool pair_overlaps(std::size_t i, std::size_t j) {
    PlacedPart& a = *parts_[0];
    PlacedPart& b = *parts_[1];
    Filter filter = exact_only_ || !a.filtered() || !b.filtered() ? Filter::unknown
                                                                   : filter_pair(a.interval(i), b.interval(j));
    if (filter == Filter::disjoint) return false;
    if (filter == Filter::overlapping && !need_site_) return true;
    return intersect(i, j);
  }

  // run()'s edge pairs through the grid of the second part's edge boxes (session 74): a run of
  // the first part's edges that share a coarse box (a lazy placement's block: its posed disk) is
  // asked of the grid once, with the union of their coarse boxes; the second part's edges whose
  // boxes meet it are the only partners any of them can have (an edge lies in its coarse box),
  // and a run without one is skipped without posing its edges, as is an edge whose own posed
  // disk (PlacedPart::disk_box) meets none of them (before, every edge of the first
  // part in the second part's whole box was posed: O(n) a call on an n-tooth gear pair). Each
  // edge then meets the listed partners whose boxes meet its own box, ascending, as the scan
  // does; a pair left out has certified disjoint enclosures (the edge's coarse box and the
  // partner's box), where the exact test finds nothing either. True on overlap.
  bool grid_pairs() {
    PlacedPart& a = *parts_[0];
    PlacedPart& b = *parts_[1];
    thread_local std::vector<std::size_t> listed, partners;
    const std::size_t run = a.lazy() ? PartEnclosure::kBlock : 1;
    for (std::size_t first = 0; first < a.size(); first += run) {
      const std::size_t last = std::min(a.size(), first + run);
      Box window{1e300, -1e300, 1e300, -1e300};
      bool any = false;
      for (std::size_t i = first; i < last; ++i)
        if (a.coarse(i).meets(b.total())) {
          window.add(a.coarse(i).xlo, a.coarse(i).ylo);
          window.add(a.coarse(i).xhi, a.coarse(i).yhi);
          any = true;
        }
      if (!any) continue;
      b_grid_->query(bounds(window), listed);
      partners.clear();
      for (std::size_t j : listed)
        if (window.meets(b.box(j))) partners.push_back(j);
      if (partners.empty()) continue;
      for (std::size_t i = first; i < last; ++i) {
        if (!a.coarse(i).meets(b.total())) continue;
        // an edge whose own posed disk meets no partner's box has no partner (not posed)
        Box disk;
        if (a.disk_box(i, disk) &&
            std::none_of(partners.begin(), partners.end(), [&](std::size_t j) { return disk.meets(b.box(j)); }))
          continue;
        const Box& box = a.box(i);
        if (!box.meets(b.total())) continue;
        for (std::size_t j : partners)
          if (box.meets(b.box(j)) && pair_overlaps(i, j)) return true;
      }
    }
    return false;
  }

  /// Exact overlap sites are needed (for a witness): no shortcut on certified crossings.
  void need_site() { need_site_ = true; }
  /// A grid of the second part's edge boxes (box(j) of every j, as placed), to find the edges
  /// near an edge of the first part without scanning the second.
  void use_grid(const BoxGrid* grid) { b_grid_ = grid; }
  void exact_only() { exact_only_ = true; }

  const std::vector<Point>& touch_points() const { return touch_points_; }
  const Site& site() const { return site_; }

  // Edges of part `side` through p (exact), with endpoint flags.
  std::vector<TouchEdge> edges_through(int side, const Point& p) {
    std::vector<TouchEdge> result;
    PlacedPart& part = *parts_[side];
    double px = toward_zero(p.x);
    double py = toward_zero(p.y);
    for (std::size_t i = 0; i < part.size(); ++i) {
      if (!part.coarse(i).contains(px, py) || !part.box(i).contains(px, py)) continue;
      const PlacedEdge& e = part.edge(i);
      if (!on_edge(e, p)) continue;
      result.push_back(TouchEdge{e.loop, e.index, p == e.source, p == e.target});
    }
    return result;
  }

 private:
  // ---------------------------------------------------------------- edge pairs

  // Returns true on overlap.
  bool intersect(std::size_t i, std::size_t j) {
    const PlacedEdge& ea = parts_[0]->edge(i);
    const PlacedEdge& eb = parts_[1]->edge(j);
    if (!ea.arc && !eb.arc) return segment_segment(ea, eb);
    if (!ea.arc) return segment_arc(ea, eb, true);
    if (!eb.arc) return segment_arc(eb, ea, false);
    return arc_arc(ea, eb);
  }

  void touch(const Point& p, const PlacedEdge& ea, const PlacedEdge& eb) {
    touched_[0][ea.loop] = true;
    touched_[1][eb.loop] = true;
    for (const Point& q : touch_points_)
      if (q == p) return;
    touch_points_.push_back(p);
  }

  bool overlap_at(const Point& p) {
    site_ = Site{p, true};
    return true;
  }

  // Inward normal (exact, not unit) of an edge's material near point p.
  static Point inward_normal(const PlacedEdge& e, const Point& p) {
    if (!e.arc) return left_perpendicular(minus(e.target, e.source));
    Point to_centre = minus(e.center(), p);
    return e.ccw ? to_centre : Point{Rational(-to_centre.x), Rational(-to_centre.y)};
  }

  // Overlap found at a transversal crossing of ea and eb near p: the sum of the inward
  // normals points into both materials.
  bool crossing_at(const Point& p, const PlacedEdge& ea, const PlacedEdge& eb) {
    site_ = Site{p, true};
    crossing_edges_ = {&ea, &eb};
    return true;
  }

  // A rational common point of ea and eb, known to lie on both underlying curves.
  // `transversal`: the curves cross there (not tangent).
  bool common_point(const Point& p, const PlacedEdge& ea, const PlacedEdge& eb, bool transversal) {
    if (!on_edge(ea, p) || !on_edge(eb, p)) return false;
    if (transversal && !is_endpoint(ea, p) && !is_endpoint(eb, p)) return crossing_at(p, ea, eb);
    touch(p, ea, eb);
    return false;
  }

  void endpoints_on(const PlacedEdge& ea, const PlacedEdge& eb) {
    for (const Point* p : {&ea.source, &ea.target})
      if (on_edge(eb, *p)) touch(*p, ea, eb);
    for (const Point* p : {&eb.source, &eb.target})
      if (on_edge(ea, *p)) touch(*p, ea, eb);
  }

  bool segment_segment(const PlacedEdge& ea, const PlacedEdge& eb) {
    Point da = minus(ea.target, ea.source);
    Point db = minus(eb.target, eb.source);
    int o1 = sign_of(cross(db, minus(ea.source, eb.source)));
    int o2 = sign_of(cross(db, minus(ea.target, eb.source)));
    int o3 = sign_of(cross(da, minus(eb.source, ea.source)));
    int o4 = sign_of(cross(da, minus(eb.target, ea.source)));
    if (o1 * o2 < 0 && o3 * o4 < 0) {
      // proper crossing; the point is rational
      Rational t = cross(db, minus(eb.source, ea.source)) / cross(db, da);
      return crossing_at(Point{Rational(ea.source.x + t * da.x), Rational(ea.source.y + t * da.y)},
                         ea, eb);
    }
    if (o1 == 0 && o2 == 0) {
      // collinear: common piece of positive length?
      Rational length = dot(da, da);
      Rational u0 = dot(minus(eb.source, ea.source), da);
      Rational u1 = dot(minus(eb.target, ea.source), da);
      Rational low = std::max(Rational(0), std::min(u0, u1));
      Rational high = std::min(length, std::max(u0, u1));
      if (low < high) {
        if (sgn(dot(da, db)) > 0) {
          Rational middle = (low + high) / (2 * length);
          Point p{Rational(ea.source.x + middle * da.x), Rational(ea.source.y + middle * da.y)};
          hints_.push_back(inward_normal(ea, p));
          return overlap_at(p);
        }
        shared_ = true;
        touched_[0][ea.loop] = true;
        touched_[1][eb.loop] = true;
      }
    }
    endpoints_on(ea, eb);
    return false;
  }

  bool segment_arc(const PlacedEdge& segment, const PlacedEdge& arc, bool segment_first) {
    // ea / eb: the same edges as (first part, second part), for touch bookkeeping.
    const PlacedEdge& ea = segment_first ? segment : arc;
    const PlacedEdge& eb = segment_first ? arc : segment;
    Point d = minus(segment.target, segment.source);
    Point f = minus(segment.source, arc.center());
    Rational a = dot(d, d);
    Rational b = dot(d, f);
    Rational c = dot(f, f) - arc.radius_squared();
    Rational disc = b * b - a * c;
    int sd = sgn(disc);
    if (sd >= 0) {
      std::optional<Rational> root = exact_square_root(disc);
      if (root) {
        for (int k = 0; k < (sd == 0 ? 1 : 2); ++k) {
          Rational lambda = (-b + (k == 0 ? *root : Rational(-*root))) / a;
          Point p{Rational(segment.source.x + lambda * d.x),
                  Rational(segment.source.y + lambda * d.y)};
          if (common_point(p, ea, eb, sd > 0)) return true;
        }
      } else {
        // Irrational crossing points: never endpoints; overlap iff one lies strictly inside
        // both edges.
        for (int k = 0; k < 2; ++k) {
          Rational sign = k == 0 ? 1 : -1;
          // lambda = (-b + sign sqrt(disc)) / a ; 0 < lambda < 1
          if (sign_with_root(Rational(-b), sign, disc) <= 0) continue;
          if (sign_with_root(Rational(-b - a), sign, disc) >= 0) continue;
          if (!arc.sector().full) {
            Point start{arc.sector().start.x, arc.sector().start.y};
            Point end{arc.sector().end.x, arc.sector().end.y};
            // a * cross(start, f + lambda d) = [a cross(start,f) - b cross(start,d)] + sign cross(start,d) sqrt
            Rational sd_start = cross(start, d);
            int after = sign_with_root(Rational(a * cross(start, f) - b * sd_start),
                                       Rational(sign * sd_start), disc);
            Rational sd_end = cross(d, end);
            int before = sign_with_root(Rational(a * cross(f, end) - b * sd_end),
                                        Rational(sign * sd_end), disc);
            bool inside = arc.sector().large ? (after > 0 || before > 0) : (after > 0 && before > 0);
            if (!inside) continue;
          }
          Rational lambda = (-b + sign * approximate_sqrt(disc)) / a;
          return crossing_at(Point{Rational(segment.source.x + lambda * d.x),
                                   Rational(segment.source.y + lambda * d.y)},
                             ea, eb);
        }
      }
    }
    endpoints_on(ea, eb);
    return false;
  }

  bool arc_arc(const PlacedEdge& ea, const PlacedEdge& eb) {
    Point d = minus(eb.center(), ea.center());
    Rational distance2 = dot(d, d);
    if (sgn(distance2) == 0) {
      if (ea.radius_squared() == eb.radius_squared() && arcs_share_piece(ea, eb)) {
        if (ea.ccw == eb.ccw) {
          // same side of a common arc: overlap near any common point
          const Point& p = in_sector(eb, minus(ea.source, eb.center())) ? ea.source : eb.source;
          hints_.push_back(inward_normal(ea, p));
          return overlap_at(p);
        }
        shared_ = true;
        touched_[0][ea.loop] = true;
        touched_[1][eb.loop] = true;
      }
      endpoints_on(ea, eb);
      return false;
    }
    Rational m = distance2 + ea.radius_squared() - eb.radius_squared();
    Rational h = 4 * distance2 * ea.radius_squared() - m * m;
    int sh = sgn(h);
    if (sh >= 0) {
      Point perpendicular = left_perpendicular(d);
      std::optional<Rational> root = exact_square_root(h);
      Rational scale = 2 * distance2;
      if (root) {
        for (int k = 0; k < (sh == 0 ? 1 : 2); ++k) {
          Rational beta = k == 0 ? *root : Rational(-*root);
          Point p{Rational(ea.center().x + (m * d.x + beta * perpendicular.x) / scale),
                  Rational(ea.center().y + (m * d.y + beta * perpendicular.y) / scale)};
          if (common_point(p, ea, eb, sh > 0)) return true;
        }
      } else {
        for (int k = 0; k < 2; ++k) {
          Rational sign = k == 0 ? 1 : -1;
          // 2 D2 (x - ka) = m d + sign sqrt(h) perp ; 2 D2 (x - kb) = (m - 2 D2) d + sign sqrt(h) perp
          if (!strictly_in_arc(ea, d, perpendicular, m, sign, h)) continue;
          if (!strictly_in_arc(eb, d, perpendicular, Rational(m - scale), sign, h)) continue;
          Rational beta = sign * approximate_sqrt(h) / scale;
          Rational alpha = m / scale;
          return crossing_at(Point{Rational(ea.center().x + alpha * d.x + beta * perpendicular.x),
                                   Rational(ea.center().y + alpha * d.y + beta * perpendicular.y)},
                             ea, eb);
        }
      }
    }
    endpoints_on(ea, eb);
    return false;
  }

  // Whether the irrational point with (x - centre) = (alpha d + sign sqrt(h) perp) / positive
  // lies in the arc's sector (never on its boundary rays: those carry rational points).
  static bool strictly_in_arc(const PlacedEdge& arc, const Point& d, const Point& perpendicular,
                              const Rational& alpha, const Rational& sign, const Rational& h) {
    if (arc.sector().full) return true;
    Point start{arc.sector().start.x, arc.sector().start.y};
    Point end{arc.sector().end.x, arc.sector().end.y};
    int after = sign_with_root(Rational(alpha * cross(start, d)),
                               Rational(sign * cross(start, perpendicular)), h);
    int before = sign_with_root(Rational(alpha * cross(d, end)),
                                Rational(sign * cross(perpendicular, end)), h);
    return arc.sector().large ? (after > 0 || before > 0) : (after > 0 && before > 0);
  }

  // Cocircular arcs: do they share a piece of positive length?
  static bool arcs_share_piece(const PlacedEdge& ea, const PlacedEdge& eb) {
    if (ea.sector().full || eb.sector().full) return true;
    auto starts_inside = [](const PlacedEdge& x, const PlacedEdge& y) {
      // start of y in [start of x, end of x)
      Point start{y.sector().start.x, y.sector().start.y};
      Point end{x.sector().end.x, x.sector().end.y};
      if (!sector_contains(x.sector(), start)) return false;
      return !(sgn(cross(start, end)) == 0 && sgn(dot(start, end)) > 0);
    };
    return starts_inside(ea, eb) || starts_inside(eb, ea);
  }

 private:
  // ---------------------------------------------------------------- local analysis

  struct Germ {
    Point direction;
    int curvature_sign = 0;
    Rational radius_squared;
    bool forward = true;
    int owner = 0;
  };

  static int half(const Point& d) { return (sgn(d.y) > 0 || (sgn(d.y) == 0 && sgn(d.x) > 0)) ? 0 : 1; }

  // -1, 0, +1: order of germs counter-clockwise from direction (1, 0).
  static int compare(const Germ& g, const Germ& h) {
    int hg = half(g.direction);
    int hh = half(h.direction);
    if (hg != hh) return hg < hh ? -1 : 1;
    int c = sgn(cross(g.direction, h.direction));
    if (c > 0) return -1;
    if (c < 0) return 1;
    // same tangent: the germ curving more to the left comes later
    if (g.curvature_sign != h.curvature_sign) return g.curvature_sign < h.curvature_sign ? -1 : 1;
    if (g.curvature_sign == 0) return 0;
    int r = cmp(g.radius_squared, h.radius_squared);  // larger radius: smaller |curvature|
    if (r == 0) return 0;
    return (g.curvature_sign > 0) == (r > 0) ? -1 : 1;
  }

  void add_germs(int owner, const PlacedEdge& e, const Point& p, std::vector<Germ>& germs) {
    bool at_source = p == e.source;
    bool at_target = p == e.target;
    bool interior = !at_source && !at_target;
    bool forward_present = at_source || interior;
    bool backward_present = at_target || interior;
    Point tangent;
    int curvature = 0;
    if (e.arc) {
      Point left = left_perpendicular(minus(p, e.center()));
      tangent = e.ccw ? left : Point{Rational(-left.x), Rational(-left.y)};
      curvature = e.ccw ? 1 : -1;
    } else {
      tangent = minus(e.target, e.source);
    }
    // (a segment's germ has no radius: read only for curved germs, compare)
    if (forward_present)
      germs.push_back(Germ{tangent, curvature, e.arc ? e.radius_squared() : Rational(), true, owner});
    if (backward_present)
      germs.push_back(Germ{Point{Rational(-tangent.x), Rational(-tangent.y)}, -curvature,
                           e.arc ? e.radius_squared() : Rational(), false, owner});
  }

  bool locally_overlapping(const Point& p) {
    std::vector<Germ> germs;
    double px = toward_zero(p.x);
    double py = toward_zero(p.y);
    for (int side = 0; side < 2; ++side) {
      PlacedPart& part = *parts_[side];
      for (std::size_t i = 0; i < part.size(); ++i) {
        if (!part.coarse(i).contains(px, py) || !part.box(i).contains(px, py)) continue;
        const PlacedEdge& e = part.edge(i);
        if (on_edge(e, p)) add_germs(side, e, p, germs);
      }
    }
    std::sort(germs.begin(), germs.end(),
              [](const Germ& g, const Germ& h) { return compare(g, h) < 0; });
    // Groups of identical germs; material state of each part after each group.
    std::vector<std::size_t> group_start;
    for (std::size_t i = 0; i < germs.size(); ++i)
      if (i == 0 || compare(germs[i - 1], germs[i]) != 0) group_start.push_back(i);
    std::size_t groups = group_start.size();
    if (groups == 0) return false;
    std::vector<std::array<int, 2>> after(groups, {-1, -1});  // -1: part has no germ here
    for (std::size_t g = 0; g < groups; ++g) {
      std::size_t end = g + 1 < groups ? group_start[g + 1] : germs.size();
      for (std::size_t i = group_start[g]; i < end; ++i) {
        int& state = after[g][static_cast<std::size_t>(germs[i].owner)];
        if (germs[i].forward) {
          state = 1;
        } else if (state != 1) {
          state = 0;
        }
      }
    }
    std::array<int, 2> state{-1, -1};
    for (int side = 0; side < 2; ++side)
      for (std::size_t g = 0; g < groups; ++g)
        if (after[g][static_cast<std::size_t>(side)] >= 0)
          state[static_cast<std::size_t>(side)] = after[g][static_cast<std::size_t>(side)];
    for (std::size_t g = 0; g < groups; ++g) {
      for (int side = 0; side < 2; ++side)
        if (after[g][static_cast<std::size_t>(side)] >= 0)
          state[static_cast<std::size_t>(side)] = after[g][static_cast<std::size_t>(side)];
      if (state[0] == 1 && state[1] == 1) {
        // the sector between group g and the next one is material of both
        const Germ& from = germs[group_start[g]];
        const Germ& to = germs[group_start[(g + 1) % groups]];
        site_ = Site{p, true};
        hints_.push_back(bisector(from.direction, to.direction, groups == 1));
        return true;
      }
    }
    return false;
  }

  // A direction between `from` and `to` (a hint for the witness search, not a decision; the
  // directions are normalised first so that any magnitude converts to double).
  static Point bisector(const Point& from_direction, const Point& to_direction, bool whole_turn) {
    Point from = approximate_unit(from_direction), to = approximate_unit(to_direction);
    double fx = from.x.get_d(), fy = from.y.get_d(), tx = to.x.get_d(), ty = to.y.get_d();
    double a = std::atan2(fy, fx);
    double b = std::atan2(ty, tx);
    double span = b - a;
    while (span <= 0) span += 2 * M_PI;
    if (whole_turn) span = 2 * M_PI;
    double m = a + span / 2;
    return Point{Rational(std::cos(m)), Rational(std::sin(m))};
  }

  // ---------------------------------------------------------------- containment

  bool loop_inside_other(int side) {
    PlacedPart& part = *parts_[side];
    PlacedPart& other = *parts_[1 - side];
    for (std::size_t l = 0; l < part.loops(); ++l) {
      if (touched_[side][l]) continue;
      if (!part.loop_box(l).meets(other.total())) continue;
      std::size_t first = part.loop_begin(l);
      if (first == part.loop_end(l)) continue;
      // The probe (a vertex of the loop) is not on the other boundary: the loop is untouched.
      const IntervalEdge& probe_interval = part.interval(first);
      std::optional<bool> quick;
      if (!exact_only_ && part.filtered())
        quick = inside_by_intervals(other, probe_interval.sx, probe_interval.sy);
      if (quick && !*quick) continue;
      if (quick && *quick && !need_site_) return true;
      const Point& probe = part.edge(first).source;
      if (locate(other, probe, !exact_only_) == PointLocation::inside) {
        site_ = Site{probe, true};
        material_hints(side, probe);
        return true;
      }
    }
    return false;
  }

 public:
  /// A rational point strictly inside both parts near the overlap site, or nullopt.
  /// Candidates site + delta * u are tried for hint directions u (into both materials) at
  /// scales delta = size * 2^-k down to the precision of the site, and for 16 fixed
  /// directions at coarse scales; each candidate is verified exactly.
  std::optional<Point> find_witness() {
    if (!site_.known) return std::nullopt;
    std::vector<Point> hints;
    if (crossing_edges_[0]) {
      // Sum of the unit inward normals of two crossing edges points into both materials.
      Point na = approximate_unit(inward_normal(*crossing_edges_[0], site_.point));
      Point nb = approximate_unit(inward_normal(*crossing_edges_[1], site_.point));
      hints.push_back(Point{Rational(na.x + nb.x), Rational(na.y + nb.y)});
    }
    for (const Point& h : hints_) hints.push_back(approximate_unit(h));
    std::vector<Point> directions;
    for (int k = 0; k < 16; ++k)
      directions.push_back(Point{Rational(std::cos(k * M_PI / 8 + 0.1)),
                                 Rational(std::sin(k * M_PI / 8 + 0.1))});
    // The overlap lies within the smaller part: start at its size (a part of 1e400 mm around a
    // puck of 1 mm would otherwise need 1300 halvings).
    Rational step = std::min(exact_size(*parts_[0]), exact_size(*parts_[1])) / 4;
    auto inside_both = [&](const Point& direction) {
      Point candidate{Rational(site_.point.x + step * direction.x),
                      Rational(site_.point.y + step * direction.y)};
      if (locate(*parts_[0], candidate, !exact_only_) == PointLocation::inside &&
          locate(*parts_[1], candidate, !exact_only_) == PointLocation::inside)
        return std::optional<Point>(candidate);
      return std::optional<Point>();
    };
    // A part whose smallest edge lies far below its size (a 10^-300 x 2 mm peg) overlaps in a
    // region of that edge's scale: after the coarse levels (directions), the hints continue
    // from a quarter of the smallest edge instead of halving down to it (1000 halvings from
    // 2 mm to 10^-300 mm, beyond the levels: no witness, at a cost of thousands of exact
    // locations). Parts whose edges are all above 2^-38 of the size never jump.
    const Rational fine = std::min(smallest_edge(*parts_[0]), smallest_edge(*parts_[1])) / 4;
    for (int level = 2; level < static_cast<int>(witness_bits) - 40; ++level) {
      for (const Point& h : hints)
        if (auto found = inside_both(h)) return found;
      if (level < 40)
        for (const Point& d : directions)
          if (auto found = inside_both(d)) return found;
      step /= 2;
      if (level == 39 && step > fine && sgn(fine) > 0) step = fine;
    }
    return std::nullopt;
  }

 private:
  // The smallest extent of an edge of a part (in its own frame: no exact posing; a rotation
  // changes it by at most sqrt 2): the larger side of a segment's or a partial arc's chord box,
  // a full circle's approximate radius (positive for a valid model; 0 if none).
  static Rational smallest_edge(const PlacedPart& part) {
    std::optional<Rational> least;
    for (std::size_t i = 0; i < part.size(); ++i) {
      const Edge& e = part.original(i);
      Rational extent;
      if (e.is_full_circle()) {
        extent = approximate_sqrt(e.radius_squared);
      } else {
        Rational dx = abs(e.target.x - e.source.x), dy = abs(e.target.y - e.source.y);
        extent = std::max(dx, dy);
      }
      if (sgn(extent) > 0 && (!least || extent < *least)) least = extent;
    }
    return least ? *least : Rational(0);
  }

  // The larger side of the bounding box of a part's vertices and arc circles (approximate
  // radii), exactly in rationals: the witness search's first scale, at any magnitude.
  static Rational exact_size(PlacedPart& part) {
    std::optional<Rational> xlo, xhi, ylo, yhi;
    auto add = [&](const Rational& x, const Rational& y) {
      if (!xlo || x < *xlo) xlo = x;
      if (!xhi || x > *xhi) xhi = x;
      if (!ylo || y < *ylo) ylo = y;
      if (!yhi || y > *yhi) yhi = y;
    };
    for (std::size_t i = 0; i < part.size(); ++i) {
      const PlacedEdge& e = part.edge(i);
      add(e.source.x, e.source.y);
      add(e.target.x, e.target.y);
      if (e.arc) {
        Rational r = approximate_sqrt(e.radius_squared());
        add(Rational(e.center().x - r), Rational(e.center().y - r));
        add(Rational(e.center().x + r), Rational(e.center().y + r));
      }
    }
    if (!xlo) return Rational(1);
    Rational size = std::max(Rational(*xhi - *xlo), Rational(*yhi - *ylo));
    return sgn(size) > 0 ? size : Rational(1);
  }

  // Directions into part `side`'s material at boundary point p.
  void material_hints(int side, const Point& p) {
    PlacedPart& part = *parts_[side];
    std::vector<Germ> germs;
    for (std::size_t i = 0; i < part.size(); ++i) {
      const PlacedEdge& e = part.edge(i);
      if (on_edge(e, p)) add_germs(side, e, p, germs);
    }
    std::sort(germs.begin(), germs.end(),
              [](const Germ& g, const Germ& h) { return compare(g, h) < 0; });
    for (std::size_t i = 0; i < germs.size(); ++i)
      if (germs[i].forward)
        hints_.push_back(bisector(germs[i].direction, germs[(i + 1) % germs.size()].direction,
                                  germs.size() == 1));
  }

 public:
  // Exact location of p relative to a placed part (see locate_point).
  // `filter`: the certified interval ray cast first (a certain answer implies p is on no edge:
  // an edge through p gives an orientation or circle test whose interval contains 0), the
  // exact ray cast only when some interval decision is uncertain.
  static PointLocation locate(PlacedPart& part, const Point& p, bool filter = false) {
    double px = toward_zero(p.x);
    double py = toward_zero(p.y);
    const Box& total = part.total();
    if (!total.contains(px, py)) return PointLocation::outside;
    if (filter && part.filtered()) {
      std::optional<bool> quick = inside_by_intervals(part, algebra::enclose_kernel(p.x), algebra::enclose_kernel(p.y));
      if (quick) return *quick ? PointLocation::inside : PointLocation::outside;
    }
    for (std::size_t i = 0; i < part.size(); ++i)
      if (part.coarse(i).contains(px, py) && part.box(i).contains(px, py) && on_edge(part.edge(i), p))
        return PointLocation::boundary;
    // Parity of crossings of the ray from p' = p + (eps^2, eps) towards +x.
    bool inside = false;
    for (std::size_t i = 0; i < part.size(); ++i) {
      const Box& coarse = part.coarse(i);
      if (coarse.xhi < px || coarse.yhi < py || coarse.ylo > py) continue;  // cannot meet the ray
      const Box& box = part.box(i);
      if (box.xhi < px || box.yhi < py || box.ylo > py) continue;  // cannot meet the ray
      const PlacedEdge& e = part.edge(i);
      if (!e.arc) {
        if (ray_crosses_chord(e.source, e.target, p)) inside = !inside;
        continue;
      }
      if (!e.full && ray_crosses_chord(e.source, e.target, p)) inside = !inside;
      if (in_lens(e, p)) inside = !inside;
    }
    return inside ? PointLocation::inside : PointLocation::outside;
  }

 private:
  // Sign of orient(a, b, p + (eps^2, eps)), lexicographic in eps.
  static int perturbed_orientation(const Point& a, const Point& b, const Point& p) {
    int s = orientation_sign(a, b, p);
    if (s != 0) return s;
    s = sgn(b.x - a.x);
    if (s != 0) return s;
    return -sgn(b.y - a.y);
  }

  static bool ray_crosses_chord(const Point& a, const Point& b, const Point& p) {
    bool a_above = a.y > p.y;  // a.y > p.y + eps  <=>  a.y > p.y
    bool b_above = b.y > p.y;
    if (a_above == b_above) return false;
    int o = perturbed_orientation(a, b, p);
    return b_above ? o > 0 : o < 0;  // upward: crossing to the right iff p' left of a->b
  }

  // p' strictly inside the region bounded by the arc and its chord (the whole disk for a
  // full circle).
  static bool in_lens(const PlacedEdge& e, const Point& p) {
    Point v = minus(p, e.center());
    int s = sgn(dot(v, v) - e.radius_squared());
    if (s == 0) s = sgn(v.y);
    if (s == 0) s = sgn(2 * v.x + 1);
    if (s == 0) s = 1;
    if (s >= 0) return false;
    if (e.full) return true;
    int side = perturbed_orientation(e.source, e.target, p);
    return e.ccw ? side < 0 : side > 0;
  }

  std::array<PlacedPart*, 2> parts_;
  std::array<std::vector<bool>, 2> touched_;
  std::vector<Point> touch_points_;
  bool shared_ = false;
  bool need_site_ = false;
  bool exact_only_ = false;
  const BoxGrid* b_grid_ = nullptr;
  Site site_;
  std::vector<Point> hints_;
  std::array<const PlacedEdge*, 2> crossing_edges_{nullptr, nullptr};
};

RigidMap inverse(const RigidMap& map) {
  RigidMap result;
  result.c = map.c;
  result.s = -map.s;
  result.offset = Point{Rational(-(map.c * map.offset.x + map.s * map.offset.y)),
                        Rational(-(-map.s * map.offset.x + map.c * map.offset.y))};
  return result;
}

// (outer o inner)(p) = outer(inner(p))
RigidMap compose(const RigidMap& outer, const RigidMap& inner) {
  RigidMap result;
  result.c = outer.c * inner.c - outer.s * inner.s;
  result.s = outer.s * inner.c + outer.c * inner.s;
  Point moved = outer.rotate(inner.offset);
  result.offset = Point{Rational(moved.x + outer.offset.x), Rational(moved.y + outer.offset.y)};
  return result;
}

}  // namespace

namespace {

// The analysis in the second part's body frame: the first part placed by `relative`
// (interval enclosure now, exact map on demand); `second_world` maps results to the world.
OverlapReport analyse_placed(PlacedPart& a, PlacedPart& b, const std::function<RigidMap()>& second_world,
                             const OverlapOptions& options, const BoxGrid* b_grid = nullptr) {
  OverlapAnalysis analysis(a, b);
  analysis.use_grid(b_grid);
  if (options.want_witness) analysis.need_site();
  if (options.exact_only) analysis.exact_only();
  OverlapReport report;
  report.relation = analysis.run();
  if (options.want_touches && report.relation == Overlap::touching) {
    RigidMap world = second_world();
    for (const Point& p : analysis.touch_points()) {
      TouchPoint touch;
      touch.point = world.apply(p);
      touch.first_edges = analysis.edges_through(0, p);
      touch.second_edges = analysis.edges_through(1, p);
      report.touches.push_back(std::move(touch));
    }
  }
  if (options.want_witness && report.relation == Overlap::overlapping) {
    std::optional<Point> witness = analysis.find_witness();
    if (witness) report.witness = second_world().apply(*witness);
  }
  return report;
}

OverlapReport analyse(const Part& first, const Part& second, const IntervalMap& relative,
                      std::function<RigidMap()> exact_relative,
                      const std::function<RigidMap()>& second_world,
                      const OverlapOptions& options) {
  PlacedPart a(first, relative, std::move(exact_relative), false);
  PlacedPart b(second, IntervalMap{}, {}, true);
  return analyse_placed(a, b, second_world, options);
}

// Certified interval enclosure of a part's world map at every chart value in v (a moving part).
IntervalMap interval_world_map(const Part& part, const ChartAxis& axis, const Interval& v) {
  IntervalMap map;
  if (part.motion.kind == Motion::Kind::rotation) {
    Interval t2 = v * v;
    Interval w = Interval(1) + t2;
    map.c = (Interval(1) - t2) / w;
    map.s = (Interval(2) * v) / w;
    if (axis.half_turn) {
      map.c = -map.c;
      map.s = -map.s;
    }
    Interval px = algebra::enclose_kernel(part.motion.pivot.x);
    Interval py = algebra::enclose_kernel(part.motion.pivot.y);
    map.ox = px - (map.c * px - map.s * py);
    map.oy = py - (map.s * px + map.c * py);
    return map;
  }
  map.ox = v * algebra::enclose_kernel(part.motion.direction.x);
  map.oy = v * algebra::enclose_kernel(part.motion.direction.y);
  return map;
}

// Certified interval enclosure of a part's world map at a chart value.
IntervalMap interval_world_map(const Part& part, bool moves, const ChartAxis& axis,
                               const Rational& value) {
  return moves ? interval_world_map(part, axis, algebra::enclose_kernel(value)) : IntervalMap{};
}

// second^-1 o first, in intervals.
IntervalMap interval_relative(const IntervalMap& a, const IntervalMap& b) {
  IntervalMap r;
  r.c = b.c * a.c + b.s * a.s;
  r.s = b.c * a.s - b.s * a.c;
  Interval dx = a.ox - b.ox;
  Interval dy = a.oy - b.oy;
  r.ox = b.c * dx + b.s * dy;
  r.oy = -(b.s * dx) + b.c * dy;
  return r;
}

}  // namespace

OverlapReport analyse_overlap(const Part& first, const RigidMap& first_map, const Part& second,
                              const RigidMap& second_map, const OverlapOptions& options) {
  RigidMap relative = compose(inverse(second_map), first_map);
  return analyse(first, second, IntervalMap::enclose(relative), [relative] { return relative; },
                 [&second_map] { return second_map; }, options);
}

namespace {

// The model's pair at chart point q: `with(first, second, relative, exact_relative,
// second_world)` with the relative map in intervals and the exact maps on demand.
template <class With>
auto at_chart_point(const Model& model, const PairAxes& axes, const ChartAxis& x, const ChartAxis& y,
                    const ChartPoint& q, With&& with) {
  const Part& first = model.parts.at(axes.first);
  const Part& second = model.parts.at(axes.second);
  const ChartAxis& second_axis = axes.first_moves ? y : x;
  const Rational& second_value = axes.first_moves ? q.y : q.x;
  IntervalMap relative =
      interval_relative(interval_world_map(first, axes.first_moves, x, q.x),
                        interval_world_map(second, axes.second_moves, second_axis, second_value));
  auto exact_relative = [&] {
    return compose(inverse(world_map(second, axes.second_moves, second_axis, second_value)),
                   world_map(first, axes.first_moves, x, q.x));
  };
  auto second_world = [&] { return world_map(second, axes.second_moves, second_axis, second_value); };
  return with(first, second, relative, exact_relative, second_world);
}

}  // namespace

OverlapReport analyse_overlap(const Model& model, const PairAxes& axes, const ChartAxis& x,
                              const ChartAxis& y, const ChartPoint& q,
                              const OverlapOptions& options) {
  return at_chart_point(model, axes, x, y, q,
                        [&](const Part& first, const Part& second, const IntervalMap& relative,
                            const auto& exact_relative, const auto& second_world) {
                          return analyse(first, second, relative, exact_relative, second_world, options);
                        });
}

Overlap classify_overlap(const Model& model, const PairAxes& axes, const ChartAxis& x,
                         const ChartAxis& y, const ChartPoint& q) {
  return analyse_overlap(model, axes, x, y, q).relation;
}

// A pair's pose-independent oracle data: the first part's enclosures, the second part placed
// at the identity (the analysis works in its body frame).
struct PairOverlap::Data {
  std::shared_ptr<const PartEnclosure> first;
  IdentityPart second;
  // Session 74 (growth74): grids of the second part's edge boxes and block boxes at the identity
  // (its placement's), made once: classify and certainly_overlapping find the second part's
  // edges and blocks near a posed edge or block of the first from them, not by a scan
  // and a grid of the first part's blocks' disks in its body frame (certified boxes of them),
  // asked with the second part's box brought into that frame
  BoxGrid second_edges, second_blocks, first_blocks;
  Data(const Part& a, const Part& b)
      : first(blocked_enclosure(a)), second(b), second_edges(grid_of(second.placement.boxes)),
        second_blocks(grid_of(second.placement.block_boxes)), first_blocks(disk_grid(*first)) {}
  static BoxGrid disk_grid(const PartEnclosure& enclosure) {
    std::vector<BoxGrid::Bounds> disks;
    disks.reserve(enclosure.blocks.size());
    for (const PartEnclosure::Block& block : enclosure.blocks) {
      const Interval x = Interval::point(block.cx), y = Interval::point(block.cy), r = Interval::point(block.r);
      disks.push_back(BoxGrid::Bounds{(x - r).lo, (x + r).hi, (y - r).lo, (y + r).hi});
    }
    return BoxGrid(disks);
  }
  // the first part's enclosure with its blocks (its placements are lazy)
  static std::shared_ptr<const PartEnclosure> blocked_enclosure(const Part& part) {
    auto enclosure = std::make_shared<PartEnclosure>(part);
    prepare_blocks(*enclosure);
    return enclosure;
  }
};

PairOverlap::PairOverlap(const Model& model, const PairAxes& axes)
    : model_(model), axes_(axes),
      data_(std::make_unique<const Data>(model.parts.at(axes.first), model.parts.at(axes.second))) {}

PairOverlap::~PairOverlap() = default;

namespace {
std::atomic<std::uint64_t> lazy_asked{0}, lazy_edges{0}, lazy_placed{0};
}  // namespace

Overlap PairOverlap::classify(const ChartAxis& x, const ChartAxis& y, const ChartPoint& q) const {
  // as analyse_overlap (the model's pair at chart point q), on the prepared parts
  // The first part placed lazily (session 47): only the edges whose block's posed disk meets
  // the region a test asks about get their interval geometry; the others cannot meet the
  // second part (nor a probe's ray), and the answer is the oracle's exact relation either way.
  return at_chart_point(model_, axes_, x, y, q,
                        [&](const Part&, const Part&, const IntervalMap& relative, const auto& exact_relative,
                            const auto& second_world) {
                          Overlap relation;
                          {
                            PlacedPart a(data_->first, relative, exact_relative, false, lazy_placement_enabled);
                            PlacedPart b(data_->second.enclosure, data_->second.placement, data_->second.exact);
                            relation = analyse_placed(a, b, second_world, OverlapOptions{},
                                                      lazy_placement_enabled ? &data_->second_edges : nullptr)
                                           .relation;
                            if (a.lazy()) {
                              lazy_asked.fetch_add(1, std::memory_order_relaxed);
                              lazy_edges.fetch_add(a.size(), std::memory_order_relaxed);
                              lazy_placed.fetch_add(a.placed_edges(), std::memory_order_relaxed);
                            }
                            if (!a.untamed()) return relation;
                          }
                          // an edge beyond the tame range: as before, every box the whole plane
                          PlacedPart a(data_->first, relative, exact_relative, false);
                          PlacedPart b(data_->second.enclosure, data_->second.placement, data_->second.exact);
                          return analyse_placed(a, b, second_world, OverlapOptions{}).relation;
                        });
}

std::array<std::uint64_t, 3> lazy_placement_counts() {
  return {lazy_asked.load(std::memory_order_relaxed), lazy_edges.load(std::memory_order_relaxed),
          lazy_placed.load(std::memory_order_relaxed)};
}

void set_lazy_placement(bool on) { lazy_placement_enabled = on; }

bool lazy_placement() { return lazy_placement_enabled; }

namespace {
std::atomic<std::uint64_t> filter_asked{0}, filter_decided{0}, filter_posed_edges{0}, filter_memo_posed{0},
    filter_memo_decided{0};
}

bool PairOverlap::certainly_overlapping(const ChartAxis& x, const ChartAxis& y, const Interval& qx,
                                        const Interval& qy) const {
  filter_asked.fetch_add(1, std::memory_order_relaxed);
  // the relative map over the whole box, as at_chart_point poses a rational point
  const ChartAxis& second_axis = axes_.first_moves ? y : x;
  const Interval& second_value = axes_.first_moves ? qy : qx;
  const IntervalMap relative = interval_relative(
      axes_.first_moves ? interval_world_map(model_.parts.at(axes_.first), x, qx) : IntervalMap{},
      axes_.second_moves ? interval_world_map(model_.parts.at(axes_.second), second_axis, second_value) : IntervalMap{});
  const Placement& b = data_->second.placement;
  if (!b.filtered) return false;
  const PartEnclosure& first = *data_->first;
  // an edge of each crossing transversally at a point interior to both, at every pose of the
  // box: the interiors overlap there (the analysis's first certified shortcut)
  auto crossing = [&](const IntervalEdge& e, const Box& box) {
    if (!box.meets(b.total)) return false;
    for (std::size_t j = 0; j < b.boxes.size(); ++j) {
      // a block of b's edges whose boxes' union misses the edge's box: none of them meets it
      if (j % PartEnclosure::kBlock == 0 && !box.meets(b.block_boxes[j / PartEnclosure::kBlock])) {
        j += PartEnclosure::kBlock - 1;
        continue;
      }
      if (box.meets(b.boxes[j]) && filter_pair(e, b.intervals[j]) == Filter::overlapping) return true;
    }
    return false;
  };
  // Session 63: the first part posed a block at a time (its blocks' posed disks, session 47's
  // lazy placement), its edges' geometry made only in blocks whose disk meets the second part:
  // a crossing inside both parts lies in the disk of its edge's block and in the second part's
  // box, so the blocks skipped hold none. (Before, every edge of the first part was posed:
  // 465 K instructions a call on the 18 x 27 gears, 10 % of their operating region.)
  thread_local std::vector<Box> blocks;
  thread_local std::vector<std::size_t> near, listed, asked;
  // (set_lazy_placement(false): every edge posed, as before; tests compare the two)
  bool lazy = lazy_placement_enabled && !first.blocks.empty() && relative.tame();
  const bool windowed = first.bounded && bounded_map(relative);
  // Session 75 (growth75): the edge pairs that certified this pair's last crossings on this
  // thread are tried first (`memo`), before any block is posed. Under the window (a bounded part
  // under a bounded map: no block, edge disk or edge poses untamed, so the route below never
  // returns false before its end) the route below answers true exactly when some pair it
  // reaches is certified crossing, and it reaches every certified pair: a certified crossing
  // point lies in both edges' certified enclosures (the posed disk of the first edge's block,
  // the edge's own posed disk and box, the second edge's box and block box, all meeting the
  // second part's box: the arguments below). So a pair certified here is one the route below
  // would find: the same boolean, found after a few edges posed where consecutive calls (the
  // vertices of one region of blocked space) share the teeth that overlap, instead of the
  // meshing zone's blocks and edges (which grow with the tooth count). Any pair of valid
  // indices is only a guess (a memo left by another pair's oracle at the same address is
  // harmless); set_lazy_placement(false) bypasses it.
  thread_local PairMemo memo;
  std::size_t certified_first = 0, certified_second = 0;
  if (lazy && windowed && memo.owner == this) {
    IntervalEdge e;
    Box box;
    for (std::size_t m = 0; m < memo.count; ++m) {
      const auto [i, j] = memo.pairs[m];
      if (i >= first.refs.size() || j >= b.boxes.size()) continue;
      filter_memo_posed.fetch_add(1, std::memory_order_relaxed);
      if (!PlacedPart::posed_edge(first, i, relative, e, box)) break;   // (not under the window)
      if (box.meets(b.total) && box.meets(b.boxes[j]) && filter_pair(e, b.intervals[j]) == Filter::overlapping) {
        if (m > 0) memo.remember(this, i, j);
        filter_memo_decided.fetch_add(1, std::memory_order_relaxed);
        filter_decided.fetch_add(1, std::memory_order_relaxed);
        return true;
      }
    }
  }
  // Session 74 (growth74): with the window (below), only the first part's blocks whose body-frame
  // disks meet the second part's box brought back into the first's body frame are posed (asked
  // of the grid of the disks): every map of the relative enclosure is a rigid motion p -> R p + o
  // with (R, o) in it, so a point p posed into the second part's box q lies in R^T (q - o),
  // enclosed in intervals; a block whose disk misses that enclosure has no point posed into the
  // box, so it holds no edge that crossing() accepts (the same test as the posed disk missing
  // the box, certified the other way round). Under the window every block poses tame (bounded
  // part, bounded map), so the blocks not posed would not have refused the lazy route either.
  // (Before, every block of the first part was posed a call: O(n) on an n-tooth gear.)
  bool selected = false;
  if (lazy && windowed) {
    const Interval qx(b.total.xlo, b.total.xhi), qy(b.total.ylo, b.total.yhi);
    const Interval dx = qx - relative.ox, dy = qy - relative.oy;
    const Interval px = relative.c * dx + relative.s * dy, py = relative.c * dy - relative.s * dx;
    if (tame(px) && tame(py)) {
      data_->first_blocks.query(BoxGrid::Bounds{px.lo, px.hi, py.lo, py.hi}, asked);
      blocks.resize(first.blocks.size());
      for (std::size_t k : asked) lazy = lazy && PlacedPart::posed_block(first.blocks[k], relative, blocks[k]);
      selected = true;
    }
  }
  if (lazy && !selected) {
    asked.resize(first.blocks.size());
    std::iota(asked.begin(), asked.end(), std::size_t{0});
    blocks.resize(first.blocks.size());
    for (std::size_t k = 0; k < first.blocks.size() && lazy; ++k)
      lazy = PlacedPart::posed_block(first.blocks[k], relative, blocks[k]);
  }
  // Session 70 (growth70): a block of the first part is skipped when its posed box meets no
  // block box of the second part, not only when it misses the second part's whole box. The
  // answer is the same: filter_pair's `overlapping` certifies a crossing point p on both edges
  // at every pose of the box; p lies in the posed box of its edge's block (certified for every
  // pose) and in the box of the second edge's block (the union of its edges' certified boxes),
  // so those two boxes meet, and a block meeting none holds no edge that crossing() accepts.
  // Skipping also skips posed_edge's "untamed" refusal of the block's edges: only where no
  // edge can be refused (a bounded part under a bounded map, PartEnclosure::bounded). A gear's
  // whole box holds a quarter of its mate's teeth, the block boxes only the meshing ones: the
  // edges posed per call no longer grow with the tooth count (O(n) per call before: n^1.8 of
  // the operating region's classification, docs/performance.md "Session 70 (growth70)").
  // For the same reason an edge of a block is tested only against the second part's blocks
  // whose boxes meet the block's (`near`), not against all of them.
  bool found = false;
  // crossing() over the blocks in `near`, naming the second part's edge it found
  auto crossing_near_at = [&](const IntervalEdge& e, const Box& box, std::size_t& at) {
    if (!box.meets(b.total)) return false;
    for (std::size_t block : near) {
      if (!box.meets(b.block_boxes[block])) continue;
      for (std::size_t j = block * PartEnclosure::kBlock;
           j < std::min(b.boxes.size(), (block + 1) * PartEnclosure::kBlock); ++j)
        if (box.meets(b.boxes[j]) && filter_pair(e, b.intervals[j]) == Filter::overlapping) {
          at = j;
          return true;
        }
    }
    return false;
  };
  if (lazy) {
    const std::size_t n = first.refs.size();
    IntervalEdge e;
    Box box;
    for (std::size_t at = 0; at < asked.size() && !found; ++at) {
      const std::size_t k = asked[at];
      if (!blocks[k].meets(b.total)) continue;
      if (windowed) {
        // (session 74: the second part's blocks that may meet, from its grid, ascending)
        data_->second_blocks.query(bounds(blocks[k]), listed);
        near.clear();
        for (std::size_t block : listed)
          if (blocks[k].meets(b.block_boxes[block])) near.push_back(block);
        if (near.empty()) continue;
      }
      for (std::size_t i = k * PartEnclosure::kBlock; i < std::min(n, (k + 1) * PartEnclosure::kBlock) && !found; ++i) {
        // (session 74: under the window, an edge whose posed disk meets none of the near blocks'
        // boxes is not posed — its edge lies in that disk, so crossing_near finds nothing on it;
        // the disk poses tame there, as its block's does)
        if (windowed && !first.edge_disks.empty()) {
          Box disk;
          if (!PlacedPart::posed_block(first.edge_disks[i], relative, disk)) return false;
          bool meets = false;
          for (std::size_t block : near)
            if (disk.meets(b.block_boxes[block])) {
              meets = true;
              break;
            }
          if (!meets) continue;
        }
        filter_posed_edges.fetch_add(1, std::memory_order_relaxed);
        if (!PlacedPart::posed_edge(first, i, relative, e, box)) return false;   // (as an untamed placement)
        if (windowed) {
          found = crossing_near_at(e, box, certified_second);
          if (found) certified_first = i;
        } else {
          found = crossing(e, box);
        }
      }
    }
    if (found && windowed) memo.remember(this, certified_first, certified_second);
  } else {
    thread_local Placement a;
    PlacedPart::place(first, relative, a);
    if (!a.filtered || !a.total.meets(b.total)) return false;
    for (std::size_t i = 0; i < a.boxes.size() && !found; ++i) found = crossing(a.intervals[i], a.boxes[i]);
  }
  if (found) filter_decided.fetch_add(1, std::memory_order_relaxed);
  return found;
}

std::uint64_t overlap_filter_posed_edges() { return filter_posed_edges.load(std::memory_order_relaxed); }

std::array<std::uint64_t, 2> overlap_filter_memo_counts() {
  return {filter_memo_posed.load(std::memory_order_relaxed), filter_memo_decided.load(std::memory_order_relaxed)};
}

std::array<std::uint64_t, 2> overlap_filter_counts() {
  return {filter_asked.load(std::memory_order_relaxed), filter_decided.load(std::memory_order_relaxed)};
}

std::optional<Point> interior_witness(const Model& model, const PairAxes& axes,
                                      const ChartAxis& x, const ChartAxis& y,
                                      const ChartPoint& q) {
  OverlapOptions options;
  options.want_witness = true;
  return analyse_overlap(model, axes, x, y, q, options).witness;
}

PointLocation locate_point(const Part& part, const RigidMap& map, const Point& p) {
  // Locate in the part's body frame: certified intervals first, exact when uncertain.
  RigidMap back = inverse(map);
  PlacedPart placed(part, IntervalMap{}, {}, true);
  Point body = back.apply(p);
  // (inside_by_intervals refuses enclosures that are not tame: a point beyond double range.)
  std::optional<bool> quick =
      inside_by_intervals(placed, algebra::enclose_kernel(body.x), algebra::enclose_kernel(body.y));
  // A certain interval answer implies the point is on no edge: an edge through it would give
  // an orientation or circle test whose interval contains 0.
  if (quick) return *quick ? PointLocation::inside : PointLocation::outside;
  return OverlapAnalysis::locate(placed, body);
}

struct PartLocator::Data {
  IdentityPart part;
  explicit Data(const Part& p) : part(p) {}
};

PartLocator::PartLocator(const Part& part) : data_(std::make_unique<const Data>(part)) {}

PartLocator::~PartLocator() = default;

PointLocation PartLocator::locate(const Point& p) const {
  // locate_point at the identity (the body frame is the world frame), on the prepared part
  PlacedPart placed(data_->part.enclosure, data_->part.placement, data_->part.exact);
  std::optional<bool> quick = inside_by_intervals(placed, Interval::enclose(p.x), Interval::enclose(p.y));
  if (quick) return *quick ? PointLocation::inside : PointLocation::outside;
  return OverlapAnalysis::locate(placed, p);
}

}  // namespace hipair::cspace
