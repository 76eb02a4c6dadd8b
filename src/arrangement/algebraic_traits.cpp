// The only translation unit of the C-space builder that includes CGAL's algebraic arrangement
// code (about 30 s to compile). See arrangement.hpp.
#include "arrangement/arrangement.hpp"
#include "arrangement/clip_common.hpp"

#include <hipair/cgal/arrangement.hpp>
#include <hipair/error.hpp>

#include "cspace/builder_impl.hpp"

#include <CGAL/Arr_algebraic_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Random.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>

namespace hipair::cspace::raw {
namespace {

using Traits = hipair::cgal::Traits;
using Arrangement_2 = hipair::cgal::Arrangement;
using Polynomial_2 = Traits::Polynomial_2;
using Polynomial_1 = Polynomial_2::NT;
using Curve = Traits::Curve_2;
using XCurve = Traits::X_monotone_curve_2;
using Point = Traits::Point_2;
using Algebraic_real_1 = Traits::Algebraic_real_1;
using Bound = Traits::Bound;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

CGAL::Gmpz to_cgal(const mpz_class& z) { return CGAL::Gmpz(z.get_mpz_t()); }
Bound to_bound(const Rational& q) { return Bound(q.get_mpq_t()); }
mpz_class from_cgal(const CGAL::Gmpz& z) { return mpz_class(z.mpz()); }
Rational from_bound(const Bound& q) { return Rational(q.mpq()); }

Polynomial_2 to_cgal(const IntegerPolynomial2& f) {
  const auto& c = f.coefficients;
  std::size_t degree_y = 0;
  for (const auto& row : c) degree_y = std::max(degree_y, row.size());
  std::vector<Polynomial_1> by_y;
  for (std::size_t j = 0; j < degree_y; ++j) {
    std::vector<CGAL::Gmpz> by_x;
    for (const auto& row : c) by_x.push_back(j < row.size() ? to_cgal(row[j]) : CGAL::Gmpz(0));
    by_y.emplace_back(by_x.begin(), by_x.end());
  }
  if (by_y.empty()) by_y.emplace_back(CGAL::Gmpz(0));
  return Polynomial_2(by_y.begin(), by_y.end());
}

IntegerPolynomial2 from_cgal(const Polynomial_2& g) {
  IntegerPolynomial2 f;
  int degree_x = 0;
  for (int j = 0; j <= g.degree(); ++j) degree_x = std::max(degree_x, g[j].degree());
  f.coefficients.assign(static_cast<std::size_t>(degree_x + 1),
                        std::vector<mpz_class>(static_cast<std::size_t>(g.degree() + 1)));
  for (int j = 0; j <= g.degree(); ++j)
    for (int i = 0; i <= g[j].degree(); ++i)
      f.coefficients[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = from_cgal(g[j][i]);
  return f;
}

algebra::Real to_real(const Algebraic_real_1& a) {
  if (a.is_rational()) return algebra::Real::from_rational(from_bound(a.rational()));
  algebra::Polynomial p;
  const auto& poly = a.polynomial();
  for (int i = 0; i <= poly.degree(); ++i) p.push_back(from_cgal(poly[i]));
  p = algebra::square_free_part(p);
  Rational lo = from_bound(a.low()), hi = from_bound(a.high());
  int s_lo = algebra::sign_at(p, lo), s_hi = algebra::sign_at(p, hi);
  if (s_lo != 0 && s_hi != 0 && s_lo != s_hi) {
    algebra::Real r;
    r.polynomial = std::move(p);
    r.lower = std::move(lo);
    r.upper = std::move(hi);
    return r;
  }
  auto roots = algebra::real_roots(p, lo, hi);
  if (roots.size() != 1) throw NumericError("internal: algebraic number from CGAL is not isolated");
  return roots.front();
}

// The same number with an isolating interval that depends on the number alone: the cell
// [c, c + 2^-k] of the dyadic grid that contains it, for the first k = 64, 96, ... at which that
// cell isolates it (p changes sign across it and has no other root in it). CGAL refines its
// cached algebraic numbers in place, so the interval of p.x() at export depended on what an
// earlier build in the same thread had asked (two builds in one process gave different extents).
// Left as it is (still isolating, not canonical) if no k up to 256 gives such a cell.
algebra::Real canonical_interval(algebra::Real r) {
  if (r.exact) return r;
  for (int k = 64; k <= 256; k += 32) {
    const mpz_class scale = mpz_class(1) << k;
    const Rational h(1, scale);
    algebra::refine_dyadically(r, h / 2);
    if (r.exact) return r;
    // r within [g h, (g + 2) h]: the cell is [g h, (g + 1) h] or [(g + 1) h, (g + 2) h]
    mpz_class g, scaled = r.lower.get_num() * scale;
    mpz_fdiv_q(g.get_mpz_t(), scaled.get_mpz_t(), r.lower.get_den_mpz_t());
    Rational middle(g + 1, scale);
    middle.canonicalize();
    mpz_class cell = g;
    if (r.upper < middle) {
      cell = g;
    } else if (r.lower > middle) {
      cell = g + 1;
    } else {
      const int at_middle = algebra::sign_at(r.polynomial, middle);
      if (at_middle == 0) return algebra::Real::from_rational(middle);   // the number is the grid point
      const int at_lower = algebra::sign_at(r.polynomial, r.lower);
      if (at_lower == 0) continue;
      cell = at_lower == at_middle ? g + 1 : g;
    }
    Rational lo(cell, scale), hi(cell + 1, scale);
    lo.canonicalize();
    hi.canonicalize();
    const int s_lo = algebra::sign_at(r.polynomial, lo), s_hi = algebra::sign_at(r.polynomial, hi);
    if (s_lo == 0 || s_hi == 0 || s_lo == s_hi) continue;
    if (algebra::real_roots(r.polynomial, lo, hi).size() != 1) continue;
    r.lower = std::move(lo);
    r.upper = std::move(hi);
    return r;
  }
  return r;
}

Algebraic_real_1 to_algebraic(const Rational& q) { return Algebraic_real_1(to_bound(q)); }

}  // namespace

/// Thrown by Builder::run when CGAL's arrangement has one point as two vertices (see
/// duplicate_vertex below); build_arrangement then rebuilds with the other insertion.
struct DuplicateVertex {
  std::string where;
};

struct Kept {
  std::unique_ptr<hipair::cgal::Traits> traits;
  std::unique_ptr<hipair::cgal::Arrangement> arrangement;
};

namespace {

class Builder {
 public:
  Builder(const Box& box, const Options& options) : box_(box), options_(options) {
    traits_ = std::make_unique<Traits>();
    arrangement_ = std::make_unique<Arrangement_2>(traits_.get());
    make_box();
  }

  Arrangement run(const std::vector<IntegerPolynomial2>& curves,
                  const std::vector<std::vector<ValidityClause>>& validity,
                  const std::vector<std::vector<std::pair<Rational, Rational>>>& windows) {
    auto start = Clock::now();
    std::vector<XCurve> pieces;
    std::vector<Point> isolated;
    for (const auto& side : sides_) pieces.push_back(side);
    static const std::vector<ValidityClause> no_clauses;
    static const bool debug = std::getenv("HIPAIR_CSPACE_DEBUG") != nullptr;
    // Curves with the same polynomial (up to a constant factor) are clipped once, together
    // (monomial factors split off first: see clip_common.hpp).
    const CurveGroups grouped = group_curves(curves);
    const auto& group_polynomials = grouped.polynomials;
    const auto& groups = grouped.members;
    for (std::size_t group_index = 0; group_index < groups.size(); ++group_index) {
      const auto& group = groups[group_index];
      std::size_t k = group.front();
      std::vector<const std::vector<ValidityClause>*> alternatives;
      for (std::size_t member : group) alternatives.push_back(member < validity.size() ? &validity[member] : &no_clauses);
      // windows: the union over the group (no restriction if a member has none)
      std::vector<std::pair<Rational, Rational>> group_windows;
      bool restricted = true;
      for (std::size_t member : group) {
        if (member >= windows.size() || windows[member].empty()) {
          restricted = false;
          break;
        }
        group_windows.insert(group_windows.end(), windows[member].begin(), windows[member].end());
      }
      auto curve_start = Clock::now();
      std::size_t before = pieces.size();
      clip(group_polynomials[group_index], alternatives, restricted ? &group_windows : nullptr, pieces, isolated);
      if (debug)
        std::fprintf(stderr, "  clip curve %zu: %zu pieces, %.4f s\n", k, pieces.size() - before, seconds_since(curve_start));
    }
    result_.times.curves_seconds = seconds_since(start);

    start = Clock::now();
    if (options_.aggregated_insertion) {
      CGAL::insert(*arrangement_, pieces.begin(), pieces.end());
    } else {
      static const bool debug = std::getenv("HIPAIR_CSPACE_DEBUG") != nullptr;
      for (std::size_t i = 0; i < pieces.size(); ++i) {
        auto piece_start = Clock::now();
        if (debug) {
          const XCurve& c = pieces[i];
          std::fprintf(stderr, "  inserting piece %zu: %s x [%.17g, %.17g] vertical %d\n", i,
                       algebra::to_string(from_cgal(c.curve().polynomial_2()), "x", "y").substr(0, 300).c_str(),
                       CGAL::to_double(c.curve_end(CGAL::ARR_MIN_END).x()), CGAL::to_double(c.curve_end(CGAL::ARR_MAX_END).x()),
                       int(c.is_vertical()));
        }
        CGAL::insert(*arrangement_, pieces[i]);
        if (debug)
          std::fprintf(stderr, "  insert piece %zu: %.4f s, %zu vertices\n", i, seconds_since(piece_start),
                       static_cast<std::size_t>(arrangement_->number_of_vertices()));
      }
    }
    static const bool debug_points = std::getenv("HIPAIR_CSPACE_DEBUG") != nullptr;
    if (debug_points) std::fprintf(stderr, "  isolated points: %zu\n", isolated.size());
    for (const auto& point : isolated) CGAL::insert_point(*arrangement_, point);
    result_.pieces_inserted = pieces.size();
    result_.times.insertion_seconds = seconds_since(start);

    start = Clock::now();
    export_topology();
    result_.times.export_seconds = seconds_since(start);
    for (const auto& [what, seconds] : debug_totals_) std::fprintf(stderr, "  export %s: %.4f s\n", what.c_str(), seconds);
    if (options_.keep_cgal) {
      auto kept = std::make_shared<Kept>();
      kept->traits = std::move(traits_);
      kept->arrangement = std::move(arrangement_);
      result_.cgal = kept;
    }
    return std::move(result_);
  }

 private:
  const Traits& traits() const { return *traits_; }

  Point rational_point(const Rational& x, const Rational& y) {
    Curve horizontal = traits().construct_curve_2_object()(
        to_cgal(IntegerPolynomial2{{{-y.get_num(), y.get_den()}}}));
    return traits().construct_point_2_object()(to_algebraic(x), horizontal, 0);
  }

  void make_box() {
    Point corners[4] = {rational_point(box_.x_lo, box_.y_lo), rational_point(box_.x_hi, box_.y_lo),
                        rational_point(box_.x_hi, box_.y_hi), rational_point(box_.x_lo, box_.y_hi)};
    auto segment = traits().construct_x_monotone_segment_2_object();
    auto add = [&](const Point& p, const Point& q) {
      std::vector<XCurve> out;
      segment(p, q, std::back_inserter(out));
      if (out.size() != 1) throw GeometryError("internal: chart box side is not one segment");
      sides_.push_back(out.front());
    };
    add(corners[0], corners[1]);  // bottom
    add(corners[1], corners[2]);  // right
    add(corners[3], corners[2]);  // top
    add(corners[0], corners[3]);  // left
  }

  // Strictly inside the open box? The point is known not to lie on the box boundary unless it
  // is on it exactly (then false).
  bool strictly_inside(const Point& p) {
    const Algebraic_real_1& x = p.x();
    if (!(to_algebraic(box_.x_lo) < x && x < to_algebraic(box_.x_hi))) return false;
    auto compare_y_at_x = traits().compare_y_at_x_2_object();
    return compare_y_at_x(p, sides_[0]) == CGAL::LARGER && compare_y_at_x(p, sides_[2]) == CGAL::SMALLER;
  }

  // Does every validity clause hold at the point of the arc above the rational x?
  bool valid_at_point(const Rational& x, const algebra::Real& y,
                      const std::vector<const std::vector<ValidityClause>*>& alternatives) {
    return clauses_hold(alternatives, x, y);
  }

  // (Curves with the same polynomial are clipped together: valid where any of them is.)
  bool valid_at(const IntegerPolynomial2& f, const XCurve& arc, const Algebraic_real_1& x_cgal, const Rational& x,
                const std::vector<const std::vector<ValidityClause>*>& alternatives) {
    for (const auto* clauses : alternatives)
      if (clauses->empty()) return true;
    algebra::Real y = algebra::nth_real_root(algebra::substitute_x(f, x), arc.arcno(x_cgal));
    return clauses_hold(alternatives, x, y);
  }

  // Abscissae where an atom of a clause may change sign along the curve: roots of the
  // resultant in y of the curve and the atom, within the box's x-range.
  std::vector<Algebraic_real_1> validity_breaks(const Polynomial_2& f, const std::vector<ValidityClause>& clauses) {
    std::vector<Algebraic_real_1> breaks;
    auto& kernel = Traits::CKvA_2::instance().kernel();
    Algebraic_real_1 x_lo = to_algebraic(box_.x_lo), x_hi = to_algebraic(box_.x_hi);
    for (const auto& clause : clauses)
      for (const auto& atom : clause.atoms) {
        Polynomial_1 r = CGAL::resultant(f, to_cgal(atom));
        if (CGAL::is_zero(r) || r.degree() < 1) continue;
        std::vector<std::pair<Algebraic_real_1, unsigned>> roots;
        kernel.solve_1_object()(r, std::back_inserter(roots));
        for (const auto& root : roots)
          if (x_lo < root.first && root.first < x_hi) breaks.push_back(root.first);
      }
    return breaks;
  }

  void clip(const IntegerPolynomial2& f, const std::vector<const std::vector<ValidityClause>*>& alternatives,
            const std::vector<std::pair<Rational, Rational>>* windows, std::vector<XCurve>& pieces,
            std::vector<Point>& isolated) {
    Polynomial_2 polynomial = to_cgal(f);
    Curve curve = traits().construct_curve_2_object()(polynomial);
    std::vector<Algebraic_real_1> breaks;
    for (const auto* clauses : alternatives) {
      auto more = validity_breaks(polynomial, *clauses);
      breaks.insert(breaks.end(), more.begin(), more.end());
    }
    std::vector<Algebraic_real_1> tangent_breaks;   // horizontal tangents: pieces stay y-monotone
    {
      Polynomial_2 f_x = CGAL::differentiate(polynomial, 0);
      if (!CGAL::is_zero(f_x)) {
        Polynomial_1 r = CGAL::resultant(polynomial, f_x);
        if (!CGAL::is_zero(r) && r.degree() >= 1) {
          std::vector<std::pair<Algebraic_real_1, unsigned>> roots;
          Traits::CKvA_2::instance().kernel().solve_1_object()(r, std::back_inserter(roots));
          Algebraic_real_1 x_lo = to_algebraic(box_.x_lo), x_hi = to_algebraic(box_.x_hi);
          for (const auto& root : roots)
            if (x_lo < root.first && root.first < x_hi) tangent_breaks.push_back(root.first);
        }
      }
    }
    std::vector<Algebraic_real_1> side_breaks;
    for (const Rational& y : {box_.y_lo, box_.y_hi}) {
      algebra::Polynomial p = algebra::substitute_y(f, y);
      if (algebra::degree(p) < 1) continue;
      std::vector<CGAL::Gmpz> coefficients;
      for (const auto& c : p) coefficients.push_back(to_cgal(c));
      Polynomial_1 restricted(coefficients.begin(), coefficients.end());
      std::vector<std::pair<Algebraic_real_1, unsigned>> roots;
      Traits::CKvA_2::instance().kernel().solve_1_object()(restricted, std::back_inserter(roots));
      Algebraic_real_1 x_lo = to_algebraic(box_.x_lo), x_hi = to_algebraic(box_.x_hi);
      for (const auto& root : roots)
        if (x_lo < root.first && root.first < x_hi) side_breaks.push_back(root.first);
    }
    std::vector<boost::variant<Point, XCurve>> parts;
    traits().make_x_monotone_2_object()(curve, std::back_inserter(parts));
    auto intersect = traits().intersect_2_object();
    auto compare_xy = traits().compare_xy_2_object();
    auto equal = traits().equal_2_object();
    auto& kernel = Traits::CKvA_2::instance().kernel();
    for (const auto& part : parts) {
      if (const Point* point = boost::get<Point>(&part)) {
        if (!strictly_inside(*point)) continue;
        // an isolated real point of the curve: keep it when it may be a valid contact
        algebra::Real x = to_real(point->x());
        if (x.exact) {
          algebra::Polynomial fiber = algebra::substitute_x(f, x.lower);
          if (algebra::degree(fiber) >= 1) {
            algebra::Real y = algebra::nth_real_root(fiber, point->arcno());
            if (!valid_at_point(x.lower, y, alternatives)) continue;
          }
        }
        isolated.push_back(*point);
        continue;
      }
      const XCurve& arc = boost::get<XCurve>(part);
      std::vector<Point> cuts;
      std::vector<Algebraic_real_1> hard;   // abscissae where runs of kept pieces must break
      auto cut_at = [&](const Algebraic_real_1& x) {
        if (!arc.is_in_x_range(x)) return;
        for (auto end : {CGAL::ARR_MIN_END, CGAL::ARR_MAX_END})
          if (arc.is_finite(end) && arc.curve_end(end).x() == x) return;
        cuts.push_back(Point(x, arc.curve(), arc.arcno(x)));
      };
      if (arc.is_vertical()) {
        for (std::size_t side : {0u, 2u}) {
          using Result = boost::variant<std::pair<Point, Traits::Multiplicity>, XCurve>;
          std::vector<Result> hits;
          intersect(arc, sides_[side], std::back_inserter(hits));
          for (const auto& hit : hits) {
            if (const auto* p = boost::get<std::pair<Point, Traits::Multiplicity>>(&hit)) {
              cuts.push_back(p->first);
            } else {
              const XCurve& overlap = boost::get<XCurve>(hit);
              cuts.push_back(overlap.curve_end(CGAL::ARR_MIN_END));
              cuts.push_back(overlap.curve_end(CGAL::ARR_MAX_END));
            }
          }
        }
      } else {
        // crossings of the box sides: the arc's points at x_lo and x_hi, and at every root of
        // f(x, y_lo) and f(x, y_hi) (cutting at a root where another branch crosses is harmless)
        cut_at(to_algebraic(box_.x_lo));
        cut_at(to_algebraic(box_.x_hi));
        for (const auto& x : side_breaks) cut_at(x);
        for (const auto& x : breaks) cut_at(x);
        if (windows)
          for (const auto& [lo, hi] : *windows)
            for (const Rational* bound : {&lo, &hi})
              if (box_.x_lo < *bound && *bound < box_.x_hi) cut_at(to_algebraic(*bound));
        for (const auto& x : tangent_breaks) {
          std::size_t before = cuts.size();
          cut_at(x);
          if (cuts.size() > before) hard.push_back(x);
        }
      }
      for (auto end : {CGAL::ARR_MIN_END, CGAL::ARR_MAX_END})
        if (arc.is_finite(end) && arc.location(end) == CGAL::ARR_INTERIOR) cuts.push_back(arc.curve_end(end));
      std::sort(cuts.begin(), cuts.end(),
                [&](const Point& a, const Point& b) { return compare_xy(a, b) == CGAL::SMALLER; });
      cuts.erase(std::unique(cuts.begin(), cuts.end(), [&](const Point& a, const Point& b) { return equal(a, b); }),
                 cuts.end());
      // Pieces between consecutive cuts are inside or outside the box and valid or not as a
      // whole. Runs of inside, valid pieces are inserted (broken at horizontal tangents). A run
      // that ends at a validity boundary inside the box is extended a little into the invalid
      // part (a spurious stretch, harmless): the exact boundary is a tangency with another
      // contact curve, and CGAL loops forever comparing such independently computed equal
      // coordinates, while it handles the tangential intersection of the two curves fine.
      const std::size_t count = cuts.size() < 2 ? 0 : cuts.size() - 1;
      std::vector<char> in_box(count, 0), valid(count, 0);
      for (std::size_t i = 0; i < count; ++i) {
        const Point& a = cuts[i];
        const Point& b = cuts[i + 1];
        if (arc.is_vertical()) {
          // the point (x, y_mid) with y_mid rational between the ends
          algebra::Real ya = to_real(a.xy().y()), yb = to_real(b.xy().y());
          Rational y_mid = algebra::rational_between(ya, yb);
          in_box[i] = to_algebraic(box_.x_lo) < a.x() && a.x() < to_algebraic(box_.x_hi) && box_.y_lo < y_mid &&
                      y_mid < box_.y_hi;
          valid[i] = 1;
        } else {
          Bound x_mid = kernel.bound_between_1_object()(a.x(), b.x());
          Algebraic_real_1 x(x_mid);
          Point middle(x, arc.curve(), arc.arcno(x));
          in_box[i] = strictly_inside(middle);
          valid[i] = in_box[i] && in_windows(from_bound(x_mid), windows) &&
                     valid_at(f, arc, x, from_bound(x_mid), alternatives);
        }
      }
      auto is_hard = [&](std::size_t c) { return std::find(hard.begin(), hard.end(), cuts[c].x()) != hard.end(); };
      auto near = [&](std::size_t from, std::size_t to) {
        // a point of the arc strictly between cuts[from] and cuts[to], near cuts[to]
        Bound x = kernel.bound_between_1_object()(cuts[from].x(), cuts[to].x());
        Algebraic_real_1 ax(x);
        x = kernel.bound_between_1_object()(ax, cuts[to].x());
        ax = Algebraic_real_1(x);
        x = kernel.bound_between_1_object()(ax, cuts[to].x());
        ax = Algebraic_real_1(x);
        return Point(ax, arc.curve(), arc.arcno(ax));
      };
      for (std::size_t i = 0; i < count;) {
        if (!valid[i]) {
          ++i;
          continue;
        }
        std::size_t start = i, end = i + 1;
        while (end < count && valid[end] && !is_hard(end)) ++end;
        Point first = cuts[start], last = cuts[end];
        if (!arc.is_vertical()) {
          // never across a horizontal tangent: the edge box is the box of the ends (at 1e300
          // mm a circle's piece stretched past its bottom point and evaluating it there failed)
          if (start > 0 && in_box[start - 1] && !valid[start - 1] && !is_hard(start)) first = near(start - 1, start);
          if (end < count && in_box[end] && !valid[end] && !is_hard(end)) last = near(end + 1, end);
        }
        pieces.push_back(arc.trim(first, last));
        i = end;
      }
    }
  }

  void export_topology() {
    debug_time(nullptr);
    const Arrangement_2& arr = *arrangement_;
    std::unordered_map<const void*, std::size_t> vertex_id, face_id, edge_id;
    std::unordered_map<const void*, bool> forward;   // halfedge -> goes min -> max
    for (auto v = arr.vertices_begin(); v != arr.vertices_end(); ++v) {
      vertex_id[&*v] = result_.vertices.size();
      vertex_handles_.push_back(v);
      Vertex out;
      fill_vertex(v, out);
      out.isolated = v->is_isolated();
      result_.vertices.push_back(std::move(out));
    }
    // before anything walks the edges and faces: a DCEL with a duplicated vertex may also have
    // broken boundary cycles (seen: a crash walking a face's outer boundary)
    if (auto where = duplicate_vertex()) throw DuplicateVertex{*where};
    for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
      face_id[&*f] = result_.faces.size();
      Face out;
      out.unbounded = f->is_unbounded();
      if (out.unbounded && result_.unbounded_face == none) result_.unbounded_face = result_.faces.size();
      result_.faces.push_back(std::move(out));
    }
    debug_time("vertices");
    std::map<int, std::vector<Algebraic_real_1>> events_of_curve;
    for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
      auto h = e->direction() == CGAL::ARR_LEFT_TO_RIGHT ? e : e->twin();
      edge_id[&*h] = edge_id[&*h->twin()] = result_.edges.size();
      forward[&*h] = true;
      forward[&*h->twin()] = false;
      Edge out;
      const XCurve& arc = h->curve();
      out.min_vertex = vertex_id.at(&*h->source());
      out.max_vertex = vertex_id.at(&*h->target());
      out.vertical = arc.is_vertical();
      if (out.vertical) separate_in_y(h->source()->point(), h->target()->point(), out.min_vertex, out.max_vertex);
      out.support = from_cgal(arc.curve().polynomial_2());
      out.left_face = face_id.at(&*h->face());
      out.right_face = face_id.at(&*h->twin()->face());
      debug_time(nullptr);
      fill_box(arc, out);
      debug_time("box");
      out.box_side = side_of(arc, h->source()->point(), h->target()->point());
      debug_time("side");
      if (!out.vertical) fill_arc_numbers(arc, h->source()->point().x(), h->target()->point().x(), events_of_curve,
                                          out.arc_numbers);
      debug_time("arcno");
      result_.edges.push_back(std::move(out));
    }
    debug_time(nullptr);
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
        incidence.direction = leaving_direction(h->curve().is_vertical(), h->direction() == CGAL::ARR_LEFT_TO_RIGHT);
        incidence.wedge_face = face_id.at(&*h->face());
        out.around.push_back(incidence);
      }
      out.face_below = wedge_containing(around, out.around, v->point(), true);
      out.face_above = wedge_containing(around, out.around, v->point(), false);
    }
    debug_time("incidences");
    for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f)
      export_face_boundary(*f, result_.faces[face_id.at(&*f)], [&](const auto& c) { return edge_id.at(&*c); },
                           [&](const auto& c) { return forward.at(&*c); });
  }

  // CGAL 5.5.1's incremental insertion can record one point as two vertices (docs/cspace.md,
  // "A CGAL failure and its guard"): an arc ending exactly at a vertex where another curve has
  // a vertical tangent. The arrangement is then wrong (edges end at the wrong copy, crossings
  // nearby are missed). Exact check: vertices whose x are equal (exact comparison) and whose
  // certified y bounds overlap (equal points always do) are compared by CGAL's Equal_2.
  // Returns where the first duplicate is, or nothing.
  std::optional<std::string> duplicate_vertex() const {
    const auto& vertices = result_.vertices;
    std::vector<std::size_t> order(vertices.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return vertices[a].x.lower_bound() < vertices[b].x.lower_bound();
    });
    auto equal = traits().equal_2_object();
    for (std::size_t i = 0; i < order.size(); ++i) {
      const Vertex& p = vertices[order[i]];
      for (std::size_t j = i + 1; j < order.size(); ++j) {
        const Vertex& q = vertices[order[j]];
        if (q.x.lower_bound() > p.x.upper_bound()) break;   // sorted: no later x overlaps
        if (p.y_upper < q.y_lower || q.y_upper < p.y_lower) continue;
        if (algebra::compare(p.x, q.x) != 0) continue;
        if (equal(vertex_handles_[order[i]]->point(), vertex_handles_[order[j]]->point()))
          return "x ~ " + std::to_string(p.x.approximate()) + ", y ~ " + std::to_string(p.y_lower_bound());
      }
    }
    return std::nullopt;
  }

  // The vertex's coordinates: x exact; y exact when x is rational (a root of the curve's
  // polynomial at that x), else isolated by CGAL's fiber interval, refined.
  void fill_vertex(Arrangement_2::Vertex_const_handle v, Vertex& out) {
    const Point& p = v->point();
    out.x = canonical_interval(to_real(p.x()));
    out.y_curve = from_cgal(p.curve().polynomial_2());
    out.y_branch = p.arcno();
    if (out.x.exact) {
      algebra::Polynomial fiber = algebra::substitute_x(out.y_curve, out.x.lower);
      if (algebra::degree(fiber) >= 1) {
        out.y = algebra::nth_real_root(fiber, out.y_branch);
        algebra::refine_dyadically(out.y, Rational(1, mpz_class(1) << 64));   // same number, no rational gcds
        out.y_exact = true;
        out.y_lower = out.y.lower;
        out.y_upper = out.y.upper;
        return;
      }
      out.y = to_real(p.xy().y());   // the curve contains the vertical line: CGAL's exact y
      out.y_exact = true;
      out.y_lower = out.y.lower;
      out.y_upper = out.y.upper;
      return;
    }
    {
      static const bool debug = std::getenv("HIPAIR_CSPACE_DEBUG") != nullptr;
      auto start = Clock::now();
      bool done = !v->is_isolated() && certified_y_bounds(v, out);
      if (debug) std::fprintf(stderr, "  own y bounds: %d %.6f s\n", int(done), seconds_since(start));
      if (done) return;
    }
    // CGAL's interval isolates y among the fiber's points but may be wide: refine it so that
    // edge boxes stay tight
    for (int i = 0; i < 64; ++i) {
      Rational lo = from_bound(p.xy().lower_bound_y()), hi = from_bound(p.xy().upper_bound_y());
      if (hi - lo <= Rational(1, 1 << 12) * (1 + abs(lo))) break;
      p.xy().refine_y();
    }
    out.y_lower = from_bound(p.xy().lower_bound_y());
    out.y_upper = from_bound(p.xy().upper_bound_y());
  }

  // Certified y bounds of a vertex with irrational x, without CGAL's fibre of the curve at an
  // algebraic x (the costliest step of the export in a fresh process). With f = y_curve, X an
  // isolating interval of x and B = X * [c, d]:
  //  - f_y excludes 0 on B: f(x, .) has at most one root in [c, d] for each x in X;
  //  - f(X, c) and f(X, d) exclude 0 with opposite signs: exactly one, never on the sides;
  //  - an incident arc of f (same polynomial) reaches (x', y') with x' in X rational and
  //    c < y' < d: between x' and the vertex the arc cannot leave the box without crossing
  //    y = c or y = d, so the vertex's y lies in (c, d), the unique root of f(x, .) there.
  // Returns false (the caller asks CGAL) when no attempt certifies.
  bool certified_y_bounds(Arrangement_2::Vertex_const_handle v, Vertex& out) {
    const IntegerPolynomial2& f = out.y_curve;
    if (f.degree_y() < 1 || out.x.exact) return false;
    const Polynomial_2& curve_polynomial = v->point().curve().polynomial_2();
    auto h = v->incident_halfedges();
    auto first = h;
    const XCurve* arc = nullptr;
    Arrangement_2::Halfedge_const_handle along;
    int on_left = 0, on_right = 0;   // arcs of f ending here from each side
    do {
      if (!h->curve().is_vertical() && h->curve().curve().polynomial_2() == curve_polynomial) {
        arc = &h->curve();
        along = h;
        ++(h->direction() == CGAL::ARR_LEFT_TO_RIGHT ? on_left : on_right);
      }
    } while (++h != first);
    // Two arcs of f on one side: a turning point or a crossing of f, where f_y vanishes and the
    // certificate below cannot succeed (and its exact work is the most expensive there).
    if (!arc || on_left > 1 || on_right > 1) return false;
    // h targets v: left to right means v is the arc's right (max) end
    const bool v_is_right = along->direction() == CGAL::ARR_LEFT_TO_RIGHT;
    const Algebraic_real_1& other_x = along->source()->point().x();
    IntegerPolynomial2 f_y;
    f_y.coefficients.assign(f.coefficients.size(), {});
    for (std::size_t i = 0; i < f.coefficients.size(); ++i)
      for (std::size_t j = 1; j < f.coefficients[i].size(); ++j) {
        f_y.coefficients[i].resize(f.coefficients[i].size() - 1);
        f_y.coefficients[i][j - 1] = f.coefficients[i][j] * static_cast<unsigned long>(j);
      }
    const algebra::IntervalPolynomial2 f_interval(f), f_y_interval(f_y);
    algebra::Real x = out.x;   // a copy: the exported x keeps its interval
    // One attempt: the failures are vertices where f_y vanishes (vertical tangents, crossings
    // of f with itself), which finer boxes do not cure; retrying cost more than it saved.
    constexpr int attempts = 1;
    for (int attempt = 0; attempt < attempts; ++attempt) {
      algebra::refine_dyadically(x, Rational(1, mpz_class(1) << (24 + 12 * attempt)));
      if (x.exact) return false;
      const Rational& x_probe = v_is_right ? x.lower : x.upper;
      Algebraic_real_1 probe = to_algebraic(x_probe);
      if (v_is_right ? !(other_x < probe) : !(probe < other_x)) continue;   // beyond the arc
      algebra::Polynomial fiber = algebra::substitute_x(f, x_probe);
      if (algebra::degree(fiber) < 1) return false;
      algebra::Real y = algebra::nth_real_root(fiber, arc->arcno(probe));
      algebra::refine_dyadically(y, Rational(1, mpz_class(1) << (24 + 6 * attempt)));
      Rational scale = 1 + abs(y.lower);
      // width about 2^-13 (1 + |y|), like the bounds CGAL's refinement gave (2^-12)
      Rational margin = scale / Rational(mpz_class(1) << (14 + 6 * attempt));
      // outward to dyadic bounds (small numbers for later exact work)
      const mpz_class unit = mpz_class(1) << (18 + 6 * attempt);
      Rational low = y.lower - margin, high = y.upper + margin;
      mpz_class low_scaled, high_scaled;
      mpz_class low_num = low.get_num() * unit, high_num = high.get_num() * unit;
      mpz_fdiv_q(low_scaled.get_mpz_t(), low_num.get_mpz_t(), low.get_den_mpz_t());
      mpz_cdiv_q(high_scaled.get_mpz_t(), high_num.get_mpz_t(), high.get_den_mpz_t());
      Rational c(low_scaled, unit), d(high_scaled, unit);
      c.canonicalize();
      d.canonicalize();
      algebra::Interval box_x{algebra::lower_double(x.lower), algebra::upper_double(x.upper)};
      algebra::Interval box_y{algebra::lower_double(c), algebra::upper_double(d)};
      if (f_y_interval.evaluate(box_x, box_y).contains_zero()) continue;
      algebra::Interval at_c = f_interval.evaluate(box_x, algebra::enclose(c));
      algebra::Interval at_d = f_interval.evaluate(box_x, algebra::enclose(d));
      if (at_c.contains_zero() || at_d.contains_zero() || (at_c.lo > 0) == (at_d.lo > 0)) continue;
      if (!(c < y.lower && y.upper < d)) continue;
      out.y_lower = c;
      out.y_upper = d;
      return true;
    }
    return false;
  }

  // The ends of a vertical edge get disjoint y bounds. A vertex's bounds only ever shrink: they
  // are intersected with CGAL's refined interval, never replaced by it (CGAL's interval may be
  // wider than the vertex's own certified bounds, and a vertex shared by two vertical edges of
  // one line must keep the separation the first edge gave it; replacing the bounds undid it
  // and label_edges then asked for a rational strictly between overlapping intervals).
  void separate_in_y(const Point& low, const Point& high, std::size_t low_id, std::size_t high_id) {
    Vertex& a = result_.vertices[low_id];
    Vertex& b = result_.vertices[high_id];
    if (a.y_exact && b.y_exact) return;
    auto tighten = [](const Point& p, Vertex& v) {
      p.xy().refine_y();
      Rational lower = from_bound(p.xy().lower_bound_y()), upper = from_bound(p.xy().upper_bound_y());
      if (lower > v.y_lower) v.y_lower = std::move(lower);
      if (upper < v.y_upper) v.y_upper = std::move(upper);
    };
    while (!(a.y_upper < b.y_lower)) {
      if (!a.y_exact) tighten(low, a);
      if (!b.y_exact) tighten(high, b);
    }
  }

  // Certified bounding box: the box of the ends (every edge is monotone in x and in y since
  // curves are split at their vertical and horizontal tangents before insertion).
  void fill_box(const XCurve&, Edge& out) { fill_edge_box(result_.vertices, out); }

  // Which chart box side the edge lies on (-1: none).
  int side_of(const XCurve& arc, const Point& source, const Point& target) {
    if (arc.is_vertical()) {
      if (source.x() == to_algebraic(box_.x_lo)) return 3;
      if (source.x() == to_algebraic(box_.x_hi)) return 1;
      return -1;
    }
    auto& kernel = Traits::CKvA_2::instance().kernel();
    Algebraic_real_1 x(kernel.bound_between_1_object()(source.x(), target.x()));
    Point middle(x, arc.curve(), arc.arcno(x));
    auto compare_y_at_x = traits().compare_y_at_x_2_object();
    if (compare_y_at_x(middle, sides_[0]) == CGAL::EQUAL) return 0;
    if (compare_y_at_x(middle, sides_[2]) == CGAL::EQUAL) return 2;
    return -1;
  }

  // Which wedge around the vertex contains the straight-down (below) or straight-up direction?
  // Angles are measured clockwise from the reference direction; classes order them and, within
  // a class, CGAL's comparisons to the right/left of the vertex.
  std::size_t wedge_containing(const std::vector<Arrangement_2::Halfedge_const_handle>& around,
                               const std::vector<Incidence>& incidences, const Point& p, bool below) {
    auto compare_right = traits().compare_y_at_x_right_2_object();
    auto compare_left = traits().compare_y_at_x_left_2_object();
    return wedge_around(incidences, below, [&](std::size_t a, std::size_t b, Direction side) {
      if (side == Direction::right)  // clockwise runs top to bottom
        return compare_right(around[a]->curve(), around[b]->curve(), p) == CGAL::LARGER;
      // left: clockwise runs bottom to top
      return compare_left(around[a]->curve(), around[b]->curve(), p) == CGAL::SMALLER;
    });
  }

  void fill_arc_numbers(const XCurve& arc, const Algebraic_real_1& x_min, const Algebraic_real_1& x_max,
                        std::map<int, std::vector<Algebraic_real_1>>& cache, ArcNumbers& out) {
    const Curve& curve = arc.curve();
    auto it = cache.find(curve.id());
    if (it == cache.end()) {
      std::vector<Algebraic_real_1> events;
      for (int i = 0; i < curve.number_of_status_lines_with_event(); ++i)
        events.push_back(curve.status_line_at_event(i).x());
      it = cache.emplace(curve.id(), std::move(events)).first;
    }
    auto& kernel = Traits::CKvA_2::instance().kernel();
    std::vector<Algebraic_real_1> inside;
    for (const auto& x : it->second)
      if (x_min < x && x < x_max) inside.push_back(x);
    Algebraic_real_1 left = x_min;
    for (std::size_t i = 0; i <= inside.size(); ++i) {
      const Algebraic_real_1& right = i < inside.size() ? inside[i] : x_max;
      Algebraic_real_1 sample(kernel.bound_between_1_object()(left, right));
      out.between.push_back(arc.arcno(sample));
      if (i < inside.size()) {
        out.events.push_back(to_real(inside[i]));
        out.at_event.push_back(arc.arcno(inside[i]));
        left = inside[i];
      }
    }
  }

  // HIPAIR_CSPACE_DEBUG=1: time the export's parts on stderr
  void debug_time(const char* what) {
    static const bool enabled = std::getenv("HIPAIR_CSPACE_DEBUG") != nullptr;
    if (!enabled) return;
    auto now = Clock::now();
    if (what) debug_totals_[what] += std::chrono::duration<double>(now - debug_last_).count();
    debug_last_ = now;
  }
  Clock::time_point debug_last_ = Clock::now();
  std::map<std::string, double> debug_totals_;

  Box box_;
  Options options_;
  std::unique_ptr<Traits> traits_;
  std::unique_ptr<Arrangement_2> arrangement_;
  std::vector<XCurve> sides_;   // bottom, right, top, left
  std::vector<Arrangement_2::Vertex_const_handle> vertex_handles_;   // by exported vertex index
  Arrangement result_;
};

}  // namespace

constexpr unsigned kCgalSeed = 20261128;

Arrangement build_arrangement(const Box& box, const std::vector<IntegerPolynomial2>& curves,
                              const std::vector<std::vector<ValidityClause>>& validity,
                              const std::vector<std::vector<std::pair<Rational, Rational>>>& windows,
                              const Options& options) {
  // The sweep (aggregated) insertion is the default of this stage, whatever
  // options.aggregated_insertion says: CGAL 5.5.1's incremental insertion can record one point as
  // two vertices (docs/cspace.md), and the duplicate check below only sees that symptom, not an
  // arrangement wrong without a duplicate. The duplicate check stays as a guard, with the
  // incremental insertion as the fallback.
  // CGAL's Bitstream Descartes isolation splits intervals at points drawn from the thread's
  // CGAL::get_default_random(), which CGAL seeds from the clock: the isolating intervals (vertex
  // y bounds, edge boxes) then changed from run to run (same C-space, different certified
  // bounds in the output). A fixed seed for every chart makes the output a function of the input.
  CGAL::get_default_random() = CGAL::Random(kCgalSeed);
  Options sweep = options;
  sweep.aggregated_insertion = true;
  auto with_other_insertion = [&]() {
    if (std::getenv("HIPAIR_CSPACE_DEBUG")) std::fprintf(stderr, "  rebuilding with the incremental insertion\n");
    Options other = options;
    other.aggregated_insertion = false;
    Builder builder(box, other);
    return builder.run(curves, validity, windows);
  };
  try {
    try {
      Builder builder(box, sweep);
      return builder.run(curves, validity, windows);
    } catch (const DuplicateVertex&) {
      return with_other_insertion();
    }
  } catch (const DuplicateVertex& failure) {
    throw GeometryError("CGAL's arrangement has one point as two vertices (" + failure.where +
                        ") with both insertions; see docs/cspace.md");
  } catch (const hipair::Error&) {
    throw;
  } catch (const CGAL::Failure_exception& e) {
    throw GeometryError(std::string("CGAL rejected a contact curve arrangement: ") + e.what());
  } catch (const CGAL::internal::Zero_resultant_exception<Polynomial_2>&) {
    throw GeometryError("CGAL could not analyse a contact curve (zero resultant: a curve is not square-free)");
  }
}

}  // namespace hipair::cspace::raw

namespace hipair::cgal {

const Arrangement* arrangement(const CSpace& space, std::size_t chart) {
  const auto& impl = cspace::impl_of(space);
  if (chart >= impl.charts.size()) return nullptr;
  const auto& kept = impl.charts[chart].arrangement.cgal;
  if (!kept) return nullptr;
  return static_cast<const cspace::raw::Kept*>(kept.get())->arrangement.get();
}

}  // namespace hipair::cgal
