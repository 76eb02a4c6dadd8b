// C-space builder pipeline (CGAL-free part): per chart, the CGAL stage's topology is labelled
// with feature pairs, every face gets an exact rational sample point classified by the
// overlap oracle, and charts are glued along seams into cells.
#include "cspace/builder_impl.hpp"
#include "algebra/interval_shift.hpp"
#include "algebra/ordinate.hpp"
#include "algebra/proportional.hpp"
#include "algebra/simplest_small.hpp"
#include "algebra/small_integers.hpp"
#include "cspace/angle_filter.hpp"
#include "cspace/curve_cost.hpp"
#include "cspace/label_filter.hpp"
#include "cspace/quadratic_root.hpp"
#include "cspace/valid_point.hpp"
#include "arrangement/circle_segment_traits.hpp"
#include "arrangement/quadratic_traits.hpp"
#include "curves/pose.hpp"
#include "oracle/blocked_tester.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <numbers>
#include <numeric>
#include <optional>
#include <set>
#include <span>
#include <string_view>
#include <string>
#include <tuple>
#include <unordered_map>
#include <functional>

namespace hipair::cspace {
namespace {

using algebra::Real;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

FaceKind kind_of(Overlap overlap) {
  switch (overlap) {
    case Overlap::apart: return FaceKind::free;
    case Overlap::overlapping: return FaceKind::blocked;
    case Overlap::touching: return FaceKind::touching;
  }
  return FaceKind::touching;
}

CellKind cell_kind(FaceKind kind) {
  return kind == FaceKind::free ? CellKind::free : kind == FaceKind::blocked ? CellKind::blocked : CellKind::touching;
}

// ---------------------------------------------------------------- per-chart stages

// Quadtree over a chart: where can a curve bound free space? A cell is dropped when the curve
// cannot vanish in it (interval evaluation), when a validity clause certainly fails in it, when
// the whole cell is certainly blocked (the chart box's grid, BlockedCells: the merged cull's
// cells, memoised and shared with the curve generator), or when a vertex contact's corner
// certainly enters the other part there: some corner-entry atom (ContactCurve::corner_entry)
// is < 0 and every validity clause holds strictly (some atom > 0) over the whole closed cell,
// so every configuration of the curve in the cell has the parts' interiors overlapping (the
// argument at corner_entry_atoms, contact_curves.cpp) and lies inside blocked space. That test
// follows the curve itself, finer than the disks' grid, which cannot certify configurations
// next to the boundary of free space. The x-ranges of the surviving finest cells are the
// curve's windows.
class CurveCuller {
 public:
  // `entry_depth`: levels below the grid's finest cells to which a curve with corner-entry
  // atoms is followed (its own test only).
  CurveCuller(BlockedCells& grid, int entry_depth) : entry_depth_(entry_depth), grid_(grid) {}

  // Windows of the curve (merged, ascending); empty when the curve bounds nothing. `cells`
  // receives the surviving finest cells (merged along columns), sorted by x.
  // `entry`: the curve's corner-entry atoms (empty: no such test).
  std::vector<std::pair<double, double>> windows(const algebra::IntervalPolynomial2& f,
                                                 const std::vector<std::vector<algebra::IntervalPolynomial2>>& clauses,
                                                 const std::vector<algebra::IntervalPolynomial2>& entry,
                                                 std::vector<std::array<double, 4>>& cells) {
    std::vector<std::array<double, 4>> boxes;
    entry_ = &entry;
    // the atoms' slots in the per-depth row caches: the clauses' atoms in order, then the
    // corner-entry atoms
    clause_slot_.clear();
    std::size_t atoms = 0;
    for (const auto& clause : clauses) {
      clause_slot_.push_back(atoms);
      atoms += clause.size();
    }
    entry_slot_ = atoms;
    f_slot_ = atoms + entry.size();
    const std::size_t slots = f_slot_ + 1;
    const int deepest = grid_.depth() + (entry.empty() ? 0 : entry_depth_);
    if (row_caches_.size() < static_cast<std::size_t>(deepest) + 1) row_caches_.resize(static_cast<std::size_t>(deepest) + 1);
    for (auto& cache : row_caches_)
      if (cache.size() < slots * row_ways) cache.resize(slots * row_ways);
    sides_to(deepest);
    ++curve_;   // every entry of an earlier curve is stale
    row_cache_ = culling_row_cache().load(std::memory_order_relaxed);
    known_blocked_ = culling_known_blocked().load(std::memory_order_relaxed);
    visit(f, clauses, 0, 0, 0, boxes, f.evaluate(cell_x(0, 0), cell_y(0, 0)), 0);
    std::sort(boxes.begin(), boxes.end());
    cells.clear();
    for (const auto& b : boxes) {
      // a cell just above the last one in the same column extends it
      if (!cells.empty() && cells.back()[0] == b[0] && cells.back()[1] == b[1] && cells.back()[3] == b[2])
        cells.back()[3] = b[3];
      else
        cells.push_back(b);
    }
    std::vector<std::pair<double, double>> found;
    for (const auto& b : cells) found.emplace_back(b[0], b[1]);
    std::sort(found.begin(), found.end());
    std::vector<std::pair<double, double>> merged;
    for (const auto& w : found) {
      if (!merged.empty() && w.first <= merged.back().second)
        merged.back().second = std::max(merged.back().second, w.second);
      else
        merged.push_back(w);
    }
    return merged;
  }

 private:
  // The rows of the current curve's polynomials (IntervalPolynomial2::rows_at: each validity
  // and corner-entry atom, and f) at the y-intervals of the grid's rows of cells, per depth:
  // the cells of one row (j) have the same y, so a polynomial evaluated in several of them
  // (the two children of a row of one parent, and the neighbouring parents' children) has its
  // rows in y enclosed once. evaluate_rows(x, rows_at(y)) is evaluate(x, y) bound for bound:
  // the same enclosures, the same decisions. Direct-mapped: `row_ways` rows per polynomial
  // and depth, entry j % row_ways, holding the rows of row j of the curve numbered `curve`
  // (0: none; a new curve makes every entry stale without a pass over them).
  struct RowEntry {
    std::uint64_t curve = 0;
    long j = -1;
    std::vector<algebra::Interval> rows;
  };
  static constexpr std::size_t row_ways = 32;

  // The rows of polynomial `p` (its slot) at row j of depth `depth`.
  const std::vector<algebra::Interval>& rows_of(const algebra::IntervalPolynomial2& p, std::size_t slot, int depth,
                                                long j) {
    RowEntry& e = row_caches_[static_cast<std::size_t>(depth)][slot * row_ways + static_cast<std::size_t>(j) % row_ways];
    if (e.j != j || e.curve != curve_) {
      p.rows_at(cell_y(depth, j), e.rows);
      e.j = j;
      e.curve = curve_;
    }
    return e.rows;
  }

  // Atom `slot` (polynomial `atom`) over cell (depth, i, j), x and y its intervals.
  algebra::Interval atom_value(const algebra::IntervalPolynomial2& atom, std::size_t slot, int depth, long j,
                               algebra::Interval x, algebra::Interval y) {
    if (!row_cache_) return atom.evaluate(x, y);
    return atom.evaluate_rows(x, rows_of(atom, slot, depth, j));
  }

  // `value`: f over the cell (its parent evaluates the four children's, the two of a row of
  // cells from the same rows of f at the row's y: the enclosures of evaluate, bound for bound).
  // `settled`: bit k set when clause k (k < 64) holds strictly over an enclosing cell (an atom's
  // enclosure there is > 0), hence over this one: it is not evaluated again.
  void visit(const algebra::IntervalPolynomial2& f, const std::vector<std::vector<algebra::IntervalPolynomial2>>& clauses,
             int depth, long i, long j, std::vector<std::array<double, 4>>& found, algebra::Interval value,
             std::uint64_t settled) {
    if (!value.contains_zero()) return;
    // A cell the grid has answered blocked already (the curve generator's walk, which tests
    // every depth from 2 and ran before this one, or an earlier curve's walk) is left at once:
    // every finest cell below it would be answered blocked — a cell with an untested entry
    // inside a blocked cell is blocked (BlockedCells::blocked), and none below it has a tested
    // entry: both walks test a cell only after every tested ancestor answered free (the
    // generator from depth 2, this walk at the odd depths and the finest) and descend no
    // further from a blocked one, and the generator's walk was over before this one began. So
    // no window or cell changes; the cell's clauses and children are not evaluated.
    if (known_blocked_ && depth >= 2 && depth <= grid_.depth() && grid_.known_blocked(depth, i, j)) return;
    algebra::Interval x = cell_x(depth, i), y = cell_y(depth, j);
    bool strict = !entry_->empty();   // every clause holds strictly over the cell (so far)
    for (std::size_t k = 0; k < clauses.size(); ++k) {
      if (k < 64 && (settled >> k & 1u)) continue;
      const auto& clause = clauses[k];
      bool can_hold = false, holds = false;
      for (std::size_t a = 0; a < clause.size(); ++a) {
        const algebra::Interval value = atom_value(clause[a], clause_slot_[k] + a, depth, j, x, y);
        can_hold = can_hold || value.hi >= 0;
        holds = holds || value.lo > 0;
        if (holds || (can_hold && !strict)) break;
      }
      if (!can_hold) return;
      strict = strict && holds;
      if (holds && k < 64) settled |= std::uint64_t{1} << k;
    }
    if (strict) {
      for (std::size_t a = 0; a < entry_->size(); ++a)
        if (atom_value((*entry_)[a], entry_slot_ + a, depth, j, x, y).hi < 0) return;
    }
    if (depth >= 3 && (depth % 2 == 1 || depth == grid_.depth()) && depth <= grid_.depth() && blocked(depth, i, j))
      return;
    // a curve with corner-entry atoms is followed entry_depth_ levels below the grid's finest
    // cells (its own test only: the disks certify nothing more there, next to the channel)
    if (depth == grid_.depth() + (entry_->empty() ? 0 : entry_depth_)) {
      found.push_back({x.lo, x.hi, y.lo, y.hi});
      return;
    }
    algebra::Interval values[2][2];
    for (long dj = 0; dj < 2; ++dj) {
      if (!row_cache_) f.rows_at(cell_y(depth + 1, 2 * j + dj), rows_);
      const std::vector<algebra::Interval>& rows = row_cache_ ? rows_of(f, f_slot_, depth + 1, 2 * j + dj) : rows_;
      for (long di = 0; di < 2; ++di) values[di][dj] = f.evaluate_rows(cell_x(depth + 1, 2 * i + di), rows);
    }
    // (a child where f cannot vanish is left here, as its visit would leave it at once)
    for (long di = 0; di < 2; ++di)
      for (long dj = 0; dj < 2; ++dj)
        if (values[di][dj].contains_zero())
          visit(f, clauses, depth + 1, 2 * i + di, 2 * j + dj, found, values[di][dj], settled);
  }

  // The grid's cell sides (BlockedCells::cell_x / cell_y, pure functions of depth and index),
  // tabulated per depth once per chart (sides_to, before a curve's walk): every curve of the
  // chart walks the same cells, and the walk asked the grid for the same sides again at each node
  // (Geneva: 416 K calls for ~ 4 K distinct sides). The table holds the grid's own values, so the
  // enclosures and every decision are the same.
  void sides_to(int deepest) {
    for (int depth = static_cast<int>(x_sides_.size()); depth <= deepest; ++depth) {
      const long count = 1L << depth;
      x_sides_.emplace_back();
      y_sides_.emplace_back();
      x_sides_.back().reserve(static_cast<std::size_t>(count));
      y_sides_.back().reserve(static_cast<std::size_t>(count));
      for (long m = 0; m < count; ++m) {
        x_sides_.back().push_back(grid_.cell_x(depth, m));
        y_sides_.back().push_back(grid_.cell_y(depth, m));
      }
    }
  }
  algebra::Interval cell_x(int depth, long i) const {
    return x_sides_[static_cast<std::size_t>(depth)][static_cast<std::size_t>(i)];
  }
  algebra::Interval cell_y(int depth, long j) const {
    return y_sides_[static_cast<std::size_t>(depth)][static_cast<std::size_t>(j)];
  }

  // The grid's answer for cell (depth, i, j), remembered in a dense table per depth (0: not
  // asked yet, 1: free, 2: blocked). BlockedCells keeps every answer it gives (an answer is
  // never changed once made), so a second call would return the same; the table only spares
  // the next curves of the chart the grid's hashed look-up at each node they share. The table
  // has 4^depth entries, so the culler's depths stay small (the grid's finest depth, at most 9
  // today, plus entry_depth_).
  bool blocked(int depth, long i, long j) {
    // (a grid with whole tables reads a cell's own entry first by index, a flat look-up or a
    // directory's block, at every depth it tables: no table here; a deeper cell would be read
    // from the grid's map of deeper cells, which this table spares)
    if (grid_.whole_tables() && grid_.tabled(depth)) return grid_.blocked(depth, i, j);
    const auto d = static_cast<std::size_t>(depth);
    if (answers_.size() <= d) answers_.resize(d + 1);
    std::vector<std::uint8_t>& table = answers_[d];
    if (table.empty()) table.assign(std::size_t{1} << (2 * depth), 0);
    std::uint8_t& answer = table[(static_cast<std::size_t>(i) << depth) | static_cast<std::size_t>(j)];
    if (answer == 0) answer = grid_.blocked(depth, i, j) ? 2 : 1;
    return answer == 2;
  }

  int entry_depth_ = 0;
  BlockedCells& grid_;
  std::vector<std::vector<std::uint8_t>> answers_;   // per depth: blocked(), i * 2^depth + j
  std::vector<std::vector<algebra::Interval>> x_sides_, y_sides_;   // per depth: the cells' sides
  const std::vector<algebra::IntervalPolynomial2>* entry_ = nullptr;   // the current curve's (windows)
  std::vector<std::size_t> clause_slot_;  // the current curve's: slot of each clause's first atom
  std::size_t entry_slot_ = 0;            // slot of the first corner-entry atom
  std::size_t f_slot_ = 0;                // slot of f (after the atoms)
  std::uint64_t curve_ = 0;               // the current curve's number (from 1)
  bool row_cache_ = true;                 // culling_row_cache() when the curve's walk began
  bool known_blocked_ = true;             // culling_known_blocked() when the curve's walk began
  std::vector<algebra::Interval> rows_;   // f's rows without the cache (scratch)
  std::vector<std::vector<RowEntry>> row_caches_;   // per depth: slot * row_ways + j % row_ways
};

}  // namespace

std::atomic<bool>& culling_row_cache() {
  static std::atomic<bool> on{true};
  return on;
}

std::atomic<bool>& culling_known_blocked() {
  static std::atomic<bool> on{true};
  return on;
}

std::atomic<bool>& mapped_twin_charts() {
  static std::atomic<bool> on{true};
  return on;
}

namespace {

const mpz_class& coefficient_of(const IntegerPolynomial2& f, std::size_t i, std::size_t j) {
  static const mpz_class zero = 0;
  if (i >= f.coefficients.size() || j >= f.coefficients[i].size()) return zero;
  return f.coefficients[i][j];
}

bool linear_atom(const IntegerPolynomial2& p) {
  return p.degree_x() <= 1 && p.degree_y() <= 1 && sgn(coefficient_of(p, 1, 1)) == 0;
}

// valid_point_in_box's search in machine integers (algebra/small_integers.hpp): the same signs
// of the same integer expressions, each computed exactly in __int128 with every operation
// checked for overflow. Nothing (the caller takes its GMP path) when an integer read is not
// below 2^62, an expression overflows, or a non-linear atom would have to be evaluated.
std::optional<bool> valid_point_in_box_small(const ContactCurve& curve, const raw::Box& box, const mpz_class& a_z,
                                             const mpz_class& b_z, const mpz_class& c_z) {
  namespace si = algebra::small_integers;
  si::Wide a, b, c;
  si::Wide bounds[8];   // x_lo, x_hi, y_lo, y_hi: numerator, denominator
  const Rational* sides[4] = {&box.x_lo, &box.x_hi, &box.y_lo, &box.y_hi};
  if (!si::read(a_z.get_mpz_t(), a) || !si::read(b_z.get_mpz_t(), b) || !si::read(c_z.get_mpz_t(), c)) return std::nullopt;
  for (int i = 0; i < 4; ++i)
    if (!si::read(sides[i]->get_num_mpz_t(), bounds[2 * i]) || !si::read(sides[i]->get_den_mpz_t(), bounds[2 * i + 1]))
      return std::nullopt;
  // sgn(num bound_den - bound_num det) (num / det against the bound, times sgn(det))
  auto against = [&](si::Wide num, si::Wide det, int side, int& out) {
    si::Wide t;
    if (!si::cross(num, bounds[2 * side + 1], bounds[2 * side], det, t)) return false;
    out = si::sign(t);
    return true;
  };
  for (const auto& clause : curve.validity)
    for (const auto& atom : clause.atoms) {
      if (!linear_atom(atom)) continue;
      si::Wide d, e, g, det, x_num, y_num;
      if (!si::read(coefficient_of(atom, 1, 0).get_mpz_t(), d) || !si::read(coefficient_of(atom, 0, 1).get_mpz_t(), e) ||
          !si::read(coefficient_of(atom, 0, 0).get_mpz_t(), g) || !si::cross(a, e, b, d, det))
        return std::nullopt;
      const int s = si::sign(det);
      if (s == 0) continue;
      if (!si::cross(b, g, c, e, x_num) || !si::cross(c, d, a, g, y_num)) return std::nullopt;
      // x_lo <= x <= x_hi and y_lo <= y <= y_hi
      int x_lo, y_lo, x_hi, y_hi;
      if (!against(x_num, det, 0, x_lo) || !against(y_num, det, 2, y_lo)) return std::nullopt;
      if (x_lo * s < 0 || y_lo * s < 0) continue;
      if (!against(x_num, det, 1, x_hi) || !against(y_num, det, 3, y_hi)) return std::nullopt;
      if (x_hi * s > 0 || y_hi * s > 0) continue;
      // every clause: some atom >= 0 at the point (nothing: a non-linear atom, or an overflow)
      auto valid = [&]() -> std::optional<bool> {
        for (const auto& other : curve.validity) {
          bool any = false;
          for (const auto& p : other.atoms) {
            if (!linear_atom(p)) return std::nullopt;
            si::Wide pa, pb, pc, t, u;
            if (!si::read(coefficient_of(p, 1, 0).get_mpz_t(), pa) || !si::read(coefficient_of(p, 0, 1).get_mpz_t(), pb) ||
                !si::read(coefficient_of(p, 0, 0).get_mpz_t(), pc) || !si::mul(pa, x_num, t) || !si::mul(pb, y_num, u) ||
                !si::add(t, u, t) || !si::mul(pc, det, u) || !si::add(t, u, t))
              return std::nullopt;
            if (si::sign(t) * s >= 0) {
              any = true;
              break;
            }
          }
          if (!any) return false;
        }
        return true;
      }();
      if (!valid) return std::nullopt;
      if (*valid) return true;
    }
  return false;
}

}  // namespace

// An exact witness that the culling quadtree keeps a line: a point of the line inside the
// closed chart box where every validity clause holds (some atom >= 0), found where the line
// meets the line of one of its linear atoms. The quadtree's interval enclosures contain the
// exact values at that point, so the finest cell holding it survives every test (there is no
// blocked test without a usable grid): the curve is kept with the same (empty) windows.
// Machine integers first (valid_point_in_box_small), GMP's when they do not suffice.
bool valid_point_in_box(const ContactCurve& curve, const raw::Box& box) {
  const IntegerPolynomial2& f = curve.polynomial;
  if (f.degree_x() > 1 || f.degree_y() > 1 || sgn(coefficient_of(f, 1, 1)) != 0 || curve.validity.empty()) return false;
  const mpz_class &a = coefficient_of(f, 1, 0), &b = coefficient_of(f, 0, 1), &c = coefficient_of(f, 0, 0);
  if (const std::optional<bool> small = valid_point_in_box_small(curve, box, a, b, c)) return *small;
  return valid_point_in_box_gmp(curve, box);
}

bool valid_point_in_box_gmp(const ContactCurve& curve, const raw::Box& box) {
  const IntegerPolynomial2& f = curve.polynomial;
  if (f.degree_x() > 1 || f.degree_y() > 1 || sgn(coefficient_of(f, 1, 1)) != 0 || curve.validity.empty()) return false;
  const mpz_class &a = coefficient_of(f, 1, 0), &b = coefficient_of(f, 0, 1), &c = coefficient_of(f, 0, 0);
  // The meeting point is (X / det, Y / det); every test below is the sign of an integer
  // expression times sgn(det), so that no rational is formed (nor canonicalised) for linear
  // atoms: x >= x_lo iff sgn(X m - n det) sgn(det) >= 0 for x_lo = n / m (m > 0), and a linear
  // atom d' x + e' y + g' >= 0 iff sgn(d' X + e' Y + g' det) sgn(det) >= 0.
  // (products accumulated in place with mpz_addmul / mpz_submul: no temporary integer is
  // allocated per atom; per-thread scratch, assigned before every read)
  thread_local mpz_class det, x_num, y_num, t;
  auto at_least = [&](const mpz_class& num, const Rational& bound, int s) {   // num / det >= bound
    mpz_mul(t.get_mpz_t(), num.get_mpz_t(), bound.get_den_mpz_t());
    mpz_submul(t.get_mpz_t(), bound.get_num_mpz_t(), det.get_mpz_t());
    return sgn(t) * s >= 0;
  };
  auto at_most = [&](const mpz_class& num, const Rational& bound, int s) {   // num / det <= bound
    mpz_mul(t.get_mpz_t(), num.get_mpz_t(), bound.get_den_mpz_t());
    mpz_submul(t.get_mpz_t(), bound.get_num_mpz_t(), det.get_mpz_t());
    return sgn(t) * s <= 0;
  };
  for (const auto& clause : curve.validity)
    for (const auto& atom : clause.atoms) {
      if (!linear_atom(atom)) continue;
      const mpz_class &d = coefficient_of(atom, 1, 0), &e = coefficient_of(atom, 0, 1), &g = coefficient_of(atom, 0, 0);
      mpz_mul(det.get_mpz_t(), a.get_mpz_t(), e.get_mpz_t());
      mpz_submul(det.get_mpz_t(), b.get_mpz_t(), d.get_mpz_t());
      const int s = sgn(det);
      if (s == 0) continue;
      mpz_mul(x_num.get_mpz_t(), b.get_mpz_t(), g.get_mpz_t());
      mpz_submul(x_num.get_mpz_t(), c.get_mpz_t(), e.get_mpz_t());
      mpz_mul(y_num.get_mpz_t(), c.get_mpz_t(), d.get_mpz_t());
      mpz_submul(y_num.get_mpz_t(), a.get_mpz_t(), g.get_mpz_t());
      // x_lo <= x <= x_hi and y_lo <= y <= y_hi
      if (!at_least(x_num, box.x_lo, s) || !at_least(y_num, box.y_lo, s)) continue;
      if (!at_most(x_num, box.x_hi, s) || !at_most(y_num, box.y_hi, s)) continue;
      std::optional<Rational> x, y;   // the point as rationals, for a non-linear atom only
      bool valid = std::all_of(curve.validity.begin(), curve.validity.end(), [&](const ValidityClause& other) {
        return std::any_of(other.atoms.begin(), other.atoms.end(), [&](const IntegerPolynomial2& p) {
          if (linear_atom(p)) {
            mpz_mul(t.get_mpz_t(), coefficient_of(p, 1, 0).get_mpz_t(), x_num.get_mpz_t());
            mpz_addmul(t.get_mpz_t(), coefficient_of(p, 0, 1).get_mpz_t(), y_num.get_mpz_t());
            mpz_addmul(t.get_mpz_t(), coefficient_of(p, 0, 0).get_mpz_t(), det.get_mpz_t());
            return sgn(t) * s >= 0;
          }
          if (!x) {
            x.emplace(x_num, det);
            y.emplace(y_num, det);
            x->canonicalize();
            y->canonicalize();
          }
          return sgn(evaluate(p, *x, *y)) >= 0;
        });
      });
      if (valid) return true;
    }
  return false;
}

namespace {

// Keeps the curves that may bound free space somewhere in the chart box, with their windows;
// returns the input indices of the kept curves.
// The kept curves' polynomials and validity are moved into the chart (the input keeps each
// curve's features, type, label and blocked side, which are all the builder reads of it after).
// `entry_depth`: CurveCuller's. Three levels for the tiles of an operating region (the gears:
// there the vertex contacts' curves next to the channel are most of what is inserted; 18 x 27
// spurious edges 20 268 -> 5 912), none for a whole space, where following them deeper cost more
// than it saved (Geneva: 1.35 x the build's instructions with three levels, 0.97 x with none;
// docs/performance.md "Session 25 (integrator)").
// The interval forms of a curve (its polynomial, validity atoms and corner-entry atoms: what the
// culling quadtree of prepare_chart reads), kept for the next tiles of one operating region
// (session 66, gear66; a whole space's charts share no curve). The tiles share their curves: a feature pair's exact curve depends
// on the chart only through its axes' half-turn kinds (the generator forms it once,
// curves/formed_store.hpp) and reaches every tile its contacts may cross; on a 7 x 8 gear pair
// 17 038 curves of 492 tiles are 3 580 distinct ones, and each tile made the ~6.5 interval
// polynomials of each of its curves again (113 678 conversions, 2.1 % of the process). The
// forms are a pure function of the exact polynomials (and of algebra::interval_scaling(), part
// of the key): an entry is used only when the curve's polynomials are equal to the entry's,
// coefficient for coefficient, so the quadtree reads the same intervals bit for bit, with or
// without the memo. The features, type and chart kinds only choose the bucket. Bounded: two
// generations of `capacity` entries (an entry used again moves to the current one), so the
// memory is that of the last few thousand curves, not of the region (79 467 curves on 19 x 40).
class CurveIntervalMemo {
 public:
  struct Forms {
    IntegerPolynomial2 polynomial;
    std::vector<ValidityClause> validity;
    std::vector<IntegerPolynomial2> corner_entry;
    bool scaled = false;   // algebra::interval_scaling() when made
    algebra::IntervalPolynomial2 f;
    std::vector<std::vector<algebra::IntervalPolynomial2>> clauses;
    std::vector<algebra::IntervalPolynomial2> entry;
  };

  const Forms& of(const ContactCurve& curve, bool x_half, bool y_half) {
    const std::uint64_t key = bucket(curve, x_half, y_half);
    const bool scaled = algebra::interval_scaling();
    ++asked_;
    if (Forms* found = find(current_, key, curve, scaled)) return *found;
    std::unique_ptr<Forms> forms = take(previous_, key, curve, scaled);
    if (!forms) {
      forms = make(curve, scaled);
      ++made_;
    }
    if (count_ >= capacity) {
      previous_ = std::move(current_);
      current_.clear();
      count_ = 0;
    }
    ++count_;
    std::vector<std::unique_ptr<Forms>>& list = current_[key];
    list.push_back(std::move(forms));
    return *list.back();
  }

 private:
  static constexpr std::size_t capacity = 1024;
  using Generation = std::unordered_map<std::uint64_t, std::vector<std::unique_ptr<Forms>>>;

  static std::uint64_t bucket(const ContactCurve& curve, bool x_half, bool y_half) {
    std::uint64_t h = 1469598103934665603ull;
    auto mix = [&](std::uint64_t v) { h = (h ^ v) * 1099511628211ull; };
    for (const FeatureRef* ref : {&curve.first, &curve.second}) {
      mix(ref->part);
      mix(ref->loop);
      mix(ref->edge);
      mix(static_cast<std::uint64_t>(ref->kind));
    }
    mix(static_cast<std::uint64_t>(curve.type));
    mix((x_half ? 2u : 0u) | (y_half ? 1u : 0u));
    return h;
  }

  static bool same(const Forms& forms, const ContactCurve& curve, bool scaled) {
    if (forms.scaled != scaled || forms.polynomial.coefficients != curve.polynomial.coefficients ||
        forms.validity.size() != curve.validity.size() || forms.corner_entry.size() != curve.corner_entry.size())
      return false;
    for (std::size_t c = 0; c < curve.validity.size(); ++c) {
      const auto &a = forms.validity[c].atoms, &b = curve.validity[c].atoms;
      if (a.size() != b.size()) return false;
      for (std::size_t k = 0; k < a.size(); ++k)
        if (a[k].coefficients != b[k].coefficients) return false;
    }
    for (std::size_t k = 0; k < curve.corner_entry.size(); ++k)
      if (forms.corner_entry[k].coefficients != curve.corner_entry[k].coefficients) return false;
    return true;
  }

  static Forms* find(Generation& generation, std::uint64_t key, const ContactCurve& curve, bool scaled) {
    auto it = generation.find(key);
    if (it == generation.end()) return nullptr;
    for (const std::unique_ptr<Forms>& forms : it->second)
      if (same(*forms, curve, scaled)) return forms.get();
    return nullptr;
  }

  static std::unique_ptr<Forms> take(Generation& generation, std::uint64_t key, const ContactCurve& curve, bool scaled) {
    auto it = generation.find(key);
    if (it == generation.end()) return nullptr;
    for (std::unique_ptr<Forms>& forms : it->second)
      if (same(*forms, curve, scaled)) {
        std::unique_ptr<Forms> taken = std::move(forms);
        forms = std::move(it->second.back());
        it->second.pop_back();
        return taken;
      }
    return nullptr;
  }

  static std::unique_ptr<Forms> make(const ContactCurve& curve, bool scaled) {
    auto forms = std::make_unique<Forms>();
    forms->polynomial = curve.polynomial;
    forms->validity = curve.validity;
    forms->corner_entry = curve.corner_entry;
    forms->scaled = scaled;
    forms->f = algebra::IntervalPolynomial2(curve.polynomial);
    for (const auto& clause : curve.validity) {
      forms->clauses.emplace_back();
      for (const auto& atom : clause.atoms) forms->clauses.back().emplace_back(atom);
    }
    for (const IntegerPolynomial2& atom : curve.corner_entry) forms->entry.emplace_back(atom);
    return forms;
  }

  Generation current_, previous_;
  std::size_t count_ = 0;

 public:
  std::size_t asked_ = 0, made_ = 0;   // (HIPAIR_CSPACE_DEBUG)
};

std::vector<std::size_t> prepare_chart(ChartData& chart, ChartInput& input, int dimension, bool shortcuts,
                                       int entry_depth, CurveIntervalMemo* memo) {
  chart.x_axis = input.x;
  chart.y_axis = input.y;
  chart.box = raw::Box{input.x.lo, input.x.hi, input.y.lo, input.y.hi};
  // without a grid (no blocked test): one of the culling depth, that blocks nothing
  const bool blocked_test = input.blocked_cells && input.blocked_cells->usable();
  // (made when a curve first needs the quadtree: a polygon pair's lines all have an exact valid
  // point in the box, and their chart then makes neither)
  std::optional<BlockedCells> own;
  std::optional<CurveCuller> quadtree;
  auto culler = [&]() -> CurveCuller& {
    if (!quadtree) {
      if (!input.blocked_cells) own.emplace(nullptr, input.x, input.y, dimension, input.cull_depth > 0 ? input.cull_depth : 6);
      quadtree.emplace(input.blocked_cells ? *input.blocked_cells : *own, entry_depth);
    }
    return *quadtree;
  };
  std::vector<std::size_t> kept;
  for (std::size_t k = 0; k < input.curves.size(); ++k) {
    ContactCurve& curve = input.curves[k];
    // (the curve's interval forms: remembered from an earlier tile of the region, or made)
    const CurveIntervalMemo::Forms* forms = nullptr;
    std::optional<algebra::IntervalPolynomial2> f;
    if (!memo) f.emplace(curve.polynomial);
    std::vector<std::pair<Rational, Rational>> windows;
    std::vector<std::array<double, 4>> cells;
    if (dimension == 2) {
      // (a line with an exact valid point in the box is kept without the quadtree)
      std::vector<std::pair<double, double>> found;
      if (blocked_test || !shortcuts || !valid_point_in_box(curve, chart.box)) {
        if (memo) {
          forms = &memo->of(curve, input.x.half_turn, input.y.half_turn);
          found = culler().windows(forms->f, forms->clauses, forms->entry, cells);
        } else {
          std::vector<std::vector<algebra::IntervalPolynomial2>> clauses;
          for (const auto& clause : curve.validity) {
            clauses.emplace_back();
            for (const auto& atom : clause.atoms) clauses.back().emplace_back(atom);
          }
          std::vector<algebra::IntervalPolynomial2> entry(curve.corner_entry.begin(), curve.corner_entry.end());
          found = culler().windows(*f, clauses, entry, cells);
        }
        if (found.empty()) continue;
      }
      if (blocked_test)
        for (const auto& [lo, hi] : found)
          // (a chart end beyond the doubles' range encloses to an infinite cell side: no
          // double may become a rational there, the chart end is the window's end)
          windows.emplace_back(std::isfinite(lo) ? std::max(Rational(lo), input.x.lo) : input.x.lo,
                               std::isfinite(hi) ? std::min(Rational(hi), input.x.hi) : input.x.hi);
    }
    kept.push_back(k);
    chart.polynomials.push_back(std::move(curve.polynomial));
    chart.validity.push_back(std::move(curve.validity));
    // the cells restrict like the windows: only where the blocked test ran (else none)
    if (!blocked_test || windows.empty()) cells.clear();
    chart.windows.push_back(std::move(windows));
    chart.cells.push_back(std::move(cells));
    if (f) chart.interval_polynomials.push_back(std::move(*f));
    else if (forms) chart.interval_polynomials.push_back(forms->f);
    else chart.interval_polynomials.emplace_back(chart.polynomials.back());
  }
  static const bool debug = std::getenv("HIPAIR_CSPACE_DEBUG") != nullptr;
  if (debug && input.blocked_cells)
    std::fprintf(stderr, "  culling: %zu of %zu curves kept, %zu blocked tests, %zu candidate pairs tested\n", kept.size(),
                 input.curves.size(), input.blocked_cells->tests(), input.blocked_cells->pairs_tested());
  return kept;
}

// The refusal of a contact curve of two rotating parts whose coefficients have `bits` bits,
// more than max_rotation_curve_bits: its two features (part, JSON pointer of the edge) and what
// to do.
template <class PartName>
std::string too_fine_message(const ContactCurve& curve, std::size_t bits, const Model* model, const PartName& part_name) {
  auto feature = [&](const FeatureRef& f) {
    std::string text = "'" + part_name(f.part) + "'";
    if (model && f.part < model->parts.size()) {
      const Part& part = model->parts[f.part];
      if (f.loop < part.loops.size()) {
        const Loop& loop = part.loops[f.loop];
        const std::string& pointer = f.edge < loop.edges.size() && !loop.edges[f.edge].pointer.empty()
                                         ? loop.edges[f.edge].pointer
                                         : loop.pointer;
        if (!pointer.empty()) text += " (" + pointer + ")";
      }
    }
    return text;
  };
  return "the contact of " + feature(curve.first) + " with " + feature(curve.second) + " is a curve with " +
         std::to_string(bits) + "-bit coefficients, beyond the " + std::to_string(max_rotation_curve_bits) +
         " bits an exact C-space of two rotating parts is built with in reasonable time: their coordinates are "
         "written too finely relative to one another (an offset of 1e-300 mm on a 100 mm part); round them (to "
         "1e-100 mm, say), or give an offset that small as zero";
}

// Every validity clause holds at (x, y): one exact coordinate rational, the other algebraic.
template <class X, class Y>
bool valid_at(const std::vector<ValidityClause>& clauses, const X& x, const Y& y) {
  return std::all_of(clauses.begin(), clauses.end(), [&](const ValidityClause& clause) {
    return std::any_of(clause.atoms.begin(), clause.atoms.end(),
                       [&](const IntegerPolynomial2& atom) { return algebra::sign_at(atom, x, y) >= 0; });
  });
}

// A line or circle up to a non-zero factor: its non-zero integer coefficients, divided by their
// gcd, with the sign that makes the first one (in x^i y^j order) positive, written as bytes
// (per coefficient: i, j, the sign, the limb count and the limbs: an injective encoding, so
// that equal keys are equal supports), without text conversion and without a division when
// the gcd is 1.
// (Appended to `key`: label_edges writes every curve's key into one buffer.)
void append_support_key(std::string& key, const IntegerPolynomial2& f) {
  thread_local mpz_class g, q;
  g = 0;
  int sign = 0;
  for (const auto& row : f.coefficients)
    for (const auto& c : row) {
      if (sgn(c) == 0) continue;
      if (sign == 0) sign = sgn(c);
      mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), c.get_mpz_t());
    }
  if (sign == 0) return;
  const bool unit = mpz_cmp_ui(g.get_mpz_t(), 1) == 0;
  auto append = [&](const void* data, std::size_t bytes) { key.append(static_cast<const char*>(data), bytes); };
  for (std::size_t i = 0; i < f.coefficients.size(); ++i)
    for (std::size_t j = 0; j < f.coefficients[i].size(); ++j) {
      const mpz_class& c = f.coefficients[i][j];
      if (sgn(c) == 0) continue;
      const mpz_class* value = &c;
      if (!unit) {
        mpz_divexact(q.get_mpz_t(), c.get_mpz_t(), g.get_mpz_t());
        value = &q;
      }
      const std::uint32_t header[3] = {static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j),
                                       static_cast<std::uint32_t>(sgn(*value) * sign > 0 ? 1 : 2)};
      const std::size_t limbs = mpz_size(value->get_mpz_t());
      append(header, sizeof header);
      append(&limbs, sizeof limbs);
      append(mpz_limbs_read(value->get_mpz_t()), limbs * sizeof(mp_limb_t));
    }
}

// The line a x + b y + c = 0 of a polynomial of total degree <= 1 (false: a curve of higher
// degree, or a constant).
bool line_of(const IntegerPolynomial2& f, const mpz_class*& a, const mpz_class*& b, const mpz_class*& c) {
  for (std::size_t i = 0; i < f.coefficients.size(); ++i)
    for (std::size_t j = 0; j < f.coefficients[i].size(); ++j)
      if (i + j > 1 && sgn(f.coefficients[i][j]) != 0) return false;
  a = &coefficient_of(f, 1, 0);
  b = &coefficient_of(f, 0, 1);
  c = &coefficient_of(f, 0, 0);
  return sgn(*a) != 0 || sgn(*b) != 0;
}

// Sign of the line a x + b y + c at the rational point (x, y), exactly (integer arithmetic:
// c dx dy + a nx dy + b ny dx, with x = nx / dx, y = ny / dy and dx, dy > 0).
// (Accumulated in place in this thread's two scratch integers: no integer allocated per call
// once they have grown.)
// Machine integers first (algebra/small_integers.hpp: exact, every operation checked for
// overflow), these GMP integers when an integer is not below 2^62 or the value overflows.
int sign_of_line_at(const mpz_class& a, const mpz_class& b, const mpz_class& c, const Rational& x, const Rational& y) {
  {
    namespace si = algebra::small_integers;
    si::Wide sa, sb, sc, xn, xd, yn, yd, value, term;
    if (si::read(a.get_mpz_t(), sa) && si::read(b.get_mpz_t(), sb) && si::read(c.get_mpz_t(), sc) &&
        si::read(x.get_num_mpz_t(), xn) && si::read(x.get_den_mpz_t(), xd) && si::read(y.get_num_mpz_t(), yn) &&
        si::read(y.get_den_mpz_t(), yd) && si::mul(sc, xd, value) && si::mul(sa, xn, term) && si::add(value, term, value) &&
        si::mul(value, yd, value) && si::mul(sb, yn, term) && si::mul(term, xd, term) && si::add(value, term, value))
      return si::sign(value);
  }
  thread_local mpz_class value, term;
  mpz_mul(value.get_mpz_t(), c.get_mpz_t(), x.get_den_mpz_t());
  mpz_addmul(value.get_mpz_t(), a.get_mpz_t(), x.get_num_mpz_t());
  mpz_mul(value.get_mpz_t(), value.get_mpz_t(), y.get_den_mpz_t());
  mpz_mul(term.get_mpz_t(), b.get_mpz_t(), y.get_num_mpz_t());
  mpz_addmul(value.get_mpz_t(), term.get_mpz_t(), x.get_den_mpz_t());
  return sgn(value);
}

// Every validity clause holds at the rational point (x, y): some atom >= 0 (valid_at, with the
// linear atoms evaluated without a substitution polynomial).
bool valid_at_rational(const std::vector<ValidityClause>& clauses, const Rational& x, const Rational& y) {
  return std::all_of(clauses.begin(), clauses.end(), [&](const ValidityClause& clause) {
    return std::any_of(clause.atoms.begin(), clause.atoms.end(), [&](const IntegerPolynomial2& atom) {
      const mpz_class *a, *b, *c;
      if (line_of(atom, a, b, c)) return sign_of_line_at(*a, *b, *c, x, y) >= 0;
      return algebra::sign_at(atom, x, y) >= 0;
    });
  });
}

// Feature pairs along every edge: exact test at one interior point of the edge.
// `by_support` (circle–segment charts: every curve and every edge's support is a line or a
// circle, irreducible): a curve vanishes along an edge only if it is its support up to a
// factor, so only the curves with the edge's support are tested (a curve crossing the edge
// at its sample point alone would be a vertex there, unless its piece there was culled as
// certainly blocked: such a crossing is no contact along the edge and is not listed).
//
// The sample's algebraic coordinate is refined only for the interval filter in front of the
// exact test (vanishes_at and valid_at decide every label, at any width of the enclosure):
// to 2^-48, which the bisection reaches with its double filter on the charts' coordinates
// (the exact signs it needs below 2^-52 cost more than the exact tests that a slightly wider
// enclosure lets through; the labels are the same).
const Rational& label_filter_width() {
  static const Rational width(1, mpz_class(1) << 48);
  return width;
}

// A line edge's sample between the rational abscissae lo < hi of its ends, on the line
// a x + b y + c = 0 (b != 0): sample_x the simplest rational between them
// (algebra::rational_between of the two exact ends; written into data.sample_x in place when the
// ends fit machine integers, else assigned) and sample_y the exact rational -(a x + c) / b
// (edge_y_at's value, as an exact Real written into data.sample_y in place).
void line_sample(const mpz_class& a, const mpz_class& b, const mpz_class& c, const Rational& lo, const Rational& hi,
                 EdgeData& data) {
  if (!(lo < hi) || !algebra::simplest_between_small(lo, hi, data.sample_x)) data.sample_x = algebra::simplest_between(lo, hi);
  Rational y;   // -(a x + c) / b, its integers written in place
  const mpz_ptr y_num = mpq_numref(y.get_mpq_t()), y_den = mpq_denref(y.get_mpq_t());
  mpz_mul(y_num, a.get_mpz_t(), data.sample_x.get_num_mpz_t());
  mpz_addmul(y_num, c.get_mpz_t(), data.sample_x.get_den_mpz_t());
  mpz_neg(y_num, y_num);
  mpz_mul(y_den, b.get_mpz_t(), data.sample_x.get_den_mpz_t());
  y.canonicalize();
  raw::exact_real_into(data.sample_y, std::move(y));   // in place, y's integers taken
}

void label_edges(ChartData& chart, bool by_support) {
  const auto& arrangement = chart.arrangement;
  chart.edges.resize(arrangement.edges.size());
  // by_support: the curves grouped by support. Every curve's key is written into one buffer
  // (`ends`: where each ends); `by_key` lists the curves sorted by key, stably, so that a
  // group (a run of equal keys: the curves with one support) lists its curves in ascending
  // order, as they are tested; group_of[k] is curve k's run.
  const std::size_t curve_count = chart.polynomials.size();
  std::string key_buffer;
  std::vector<std::size_t> ends, by_key;
  std::vector<std::span<const std::size_t>> group_of;   // per curve: the curves with its support
  auto key_of = [&](std::size_t k) {
    const std::size_t begin = k == 0 ? 0 : ends[k - 1];
    return std::string_view(key_buffer).substr(begin, ends[k] - begin);
  };
  if (by_support) {
    ends.reserve(curve_count);
    for (std::size_t k = 0; k < curve_count; ++k) {
      append_support_key(key_buffer, chart.polynomials[k]);
      ends.push_back(key_buffer.size());
    }
    by_key.resize(curve_count);
    std::iota(by_key.begin(), by_key.end(), std::size_t{0});
    std::stable_sort(by_key.begin(), by_key.end(), [&](std::size_t a, std::size_t b) { return key_of(a) < key_of(b); });
    group_of.resize(curve_count);
    for (std::size_t i = 0; i < curve_count;) {
      std::size_t j = i + 1;
      while (j < curve_count && key_of(by_key[j]) == key_of(by_key[i])) ++j;
      const std::span<const std::size_t> group(by_key.data() + i, j - i);
      for (std::size_t r = i; r < j; ++r) group_of[by_key[r]] = group;
      i = j;
    }
  }
  // Per edge: its sample (written into chart.edges), the sample's box for the interval filter,
  // and the refined copy of an algebraic coordinate that the box was read from (the exact tests
  // read it, as they did before the boxes were made first).
  struct Sample {
    SampleBox box;
    std::optional<Real> refined;
    bool front_end = false;   // the polygon front end's edge: labelled in rationals, no box
  };
  auto sample = [&](std::size_t e, Sample& s) {
    const raw::Edge& edge = arrangement.edges[e];
    EdgeData& data = chart.edges[e];
    const raw::Vertex& low = arrangement.vertices[edge.min_vertex];
    const raw::Vertex& high = arrangement.vertices[edge.max_vertex];
    const std::size_t carried = by_support ? edge.support_curve : raw::none;
    if (edge.vertical) {
      data.vertical_x = low.x;
      // written into the default sample_y in place (exact: lower = upper = y)
      raw::exact_real_into(data.sample_y, low.y_exact && high.y_exact
                                              ? algebra::rational_between(low.y, high.y)
                                              : algebra::simplest_between(low.y_upper, high.y_lower));
      // refined in a copy (an exact x is not refined: read in place)
      if (!low.x.exact) s.refined.emplace(low.x).refine_to(label_filter_width());
      const Real& x = s.refined ? *s.refined : low.x;
      s.box = {algebra::Interval{x.lower_bound(), x.upper_bound()}, algebra::enclose(data.sample_y.lower)};
    } else if (const mpz_class *a, *b, *c; carried < group_of.size() && low.x.exact && high.x.exact &&
                                             line_of(edge.support, a, b, c) && sgn(*b) != 0) {
      // The polygon front end (a line edge whose support was carried from its input curve,
      // between rational abscissae): the same sample as below without root isolation
      // (rational_between of two exact numbers is the simplest rational between them; edge_y_at
      // of the line a x + b y + c is the rational -(a x + c) / b), and the same labels: every
      // candidate has the edge's support up to a factor, so it vanishes along the whole edge
      // (the filter and vanishes_at below hold), and only its validity at the sample decides,
      // exactly in rationals. (The general path, without carried supports, takes the branch
      // below: the tests compare the two.)
      s.front_end = true;
      line_sample(*a, *b, *c, low.x.lower, high.x.lower, data);
    } else if (const mpz_class *a, *b, *c; low.x.exact && high.x.exact && line_of(edge.support, a, b, c) && sgn(*b) != 0) {
      // A line edge between rational abscissae without a carried support (a chart side, or a
      // line edge of the general path): the sample of the branch below in rationals —
      // rational_between of two exact numbers is the simplest rational between them, and
      // edge_y_at of the line a x + b y + c is the exact rational -(a x + c) / b — written in
      // place (session 73: no Rational and Real temporaries per edge); the labels below as before.
      line_sample(*a, *b, *c, low.x.lower, high.x.lower, data);
      s.box = {algebra::enclose(data.sample_x), algebra::Interval{data.sample_y.lower_bound(), data.sample_y.upper_bound()}};
    } else {
      data.sample_x = algebra::rational_between(low.x, high.x);
      data.sample_y = edge_y_at(chart, e, data.sample_x);
      // as above: an exact y is read in place
      if (!data.sample_y.exact) s.refined.emplace(data.sample_y).refine_to(label_filter_width());
      const Real& y = s.refined ? *s.refined : data.sample_y;
      s.box = {algebra::enclose(data.sample_x), algebra::Interval{y.lower_bound(), y.upper_bound()}};
    }
  };
  // The exact tests of edge e's candidates (`filtered`: they passed the interval filter already).
  auto label = [&](std::size_t e, const Sample& s, std::span<const std::size_t> candidates, bool filtered) {
    const raw::Edge& edge = arrangement.edges[e];
    EdgeData& data = chart.edges[e];
    auto near = [&](std::size_t k) { return filtered || chart.interval_polynomials[k].evaluate(s.box[0], s.box[1]).contains_zero(); };
    if (s.front_end) {
      for (std::size_t k : candidates)
        if (valid_at_rational(chart.validity[k], data.sample_x, data.sample_y.lower)) data.curves.push_back(k);
    } else if (edge.vertical) {
      const Real& x = s.refined ? *s.refined : arrangement.vertices[edge.min_vertex].x;
      const Rational& y = data.sample_y.lower;
      for (std::size_t k : candidates) {
        if (!near(k)) continue;
        if (x.exact) {
          // a rational x (a chart side, a vertical contact line of a polygon pair): the same
          // signs at the rational point (x.lower, y) that vanishes_at and valid_at take for an
          // exact x, without their substitution polynomials (lines: sign_of_line_at)
          const IntegerPolynomial2& f = chart.polynomials[k];
          const mpz_class *a, *b, *c;
          const int value = line_of(f, a, b, c) ? sign_of_line_at(*a, *b, *c, x.lower, y) : algebra::sign_at(f, x.lower, y);
          if (value == 0 && valid_at_rational(chart.validity[k], x.lower, y)) data.curves.push_back(k);
          continue;
        }
        if (algebra::vanishes_at(chart.polynomials[k], x, y) && valid_at(chart.validity[k], x, y))
          data.curves.push_back(k);
      }
    } else {
      const Real& y = s.refined ? *s.refined : data.sample_y;
      for (std::size_t k : candidates) {
        if (!near(k)) continue;
        // the sample's y is a root of the edge's support at sample_x (edge_y_at): a curve
        // proportional to the support vanishes there without the exact test
        if ((algebra::proportional(chart.polynomials[k], edge.support) || algebra::vanishes_at(chart.polynomials[k], data.sample_x, y)) &&
            valid_at(chart.validity[k], data.sample_x, data.sample_y))
          data.curves.push_back(k);
      }
    }
  };
  if (!by_support) {
    // every curve is a candidate at every edge: the samples first, then the interval filter for
    // all pairs through the samples' k-d tree (curves_at_samples: the pairs the plain filter
    // passes, but those of curves certainly without a zero near a group of samples), then the
    // exact tests
    std::vector<Sample> samples(arrangement.edges.size());
    std::vector<SampleBox> boxes(arrangement.edges.size());
    for (std::size_t e = 0; e < arrangement.edges.size(); ++e) {
      sample(e, samples[e]);
      boxes[e] = samples[e].box;
    }
    const std::vector<std::vector<std::size_t>> passed = curves_at_samples(chart.interval_polynomials, boxes);
    for (std::size_t e = 0; e < arrangement.edges.size(); ++e) label(e, samples[e], passed[e], true);
    return;
  }
  for (std::size_t e = 0; e < arrangement.edges.size(); ++e) {
    std::span<const std::size_t> candidates;
    // an edge along an input line has that line's support: its group, without a key
    const std::size_t carried = arrangement.edges[e].support_curve;
    if (carried < group_of.size()) {
      candidates = group_of[carried];
    } else {
      // the group whose key is the edge's support's (none: no curve)
      thread_local std::string edge_key;
      edge_key.clear();
      append_support_key(edge_key, arrangement.edges[e].support);
      auto it = std::lower_bound(by_key.begin(), by_key.end(), std::string_view(edge_key),
                                 [&](std::size_t k, std::string_view key) { return key_of(k) < key; });
      candidates = it == by_key.end() || key_of(*it) != std::string_view(edge_key) ? std::span<const std::size_t>()
                                                                                   : group_of[*it];
    }
    Sample s;
    sample(e, s);
    label(e, s, candidates, false);
  }
}

struct Hit {
  bool found = false;
  Real y;
};

// The nearest non-vertical edge above (or below) the point (x, from) on the vertical line x,
// where x is no vertex abscissa of the chart.
Hit nearest_on_vertical(const ChartData& chart, const Rational& x, const Real& from, bool upward) {
  const auto& arrangement = chart.arrangement;
  const algebra::Interval xi = algebra::enclose(x);
  const double from_lo = from.lower_bound(), from_hi = from.upper_bound();
  std::vector<std::pair<double, std::size_t>> candidates;
  for (std::size_t e = 0; e < arrangement.edges.size(); ++e) {
    const raw::Edge& edge = arrangement.edges[e];
    if (edge.vertical || edge.box[0] > xi.hi || edge.box[2] < xi.lo) continue;
    if (upward ? edge.box[3] < from_lo : edge.box[1] > from_hi) continue;
    candidates.emplace_back(upward ? edge.box[1] : -edge.box[3], e);
  }
  std::sort(candidates.begin(), candidates.end());
  Hit best;
  for (const auto& [key, e] : candidates) {
    if (best.found && (upward ? key > best.y.upper_bound() : -key < best.y.lower_bound())) break;
    const raw::Edge& edge = arrangement.edges[e];
    if (arrangement.vertices[edge.min_vertex].x.compare(x) >= 0 ||
        arrangement.vertices[edge.max_vertex].x.compare(x) <= 0)
      continue;
    Real y = edge_y_at(chart, e, x);
    int c = algebra::compare(y, from);
    if (upward ? c <= 0 : c >= 0) continue;
    if (!best.found || (upward ? algebra::compare(y, best.y) < 0 : algebra::compare(y, best.y) > 0)) {
      best.found = true;
      best.y = std::move(y);
    }
  }
  return best;
}

// The derivative of f in y.
IntegerPolynomial2 derivative_y(const IntegerPolynomial2& f) {
  IntegerPolynomial2 d;
  d.coefficients.resize(f.coefficients.size());
  for (std::size_t i = 0; i < f.coefficients.size(); ++i)
    for (std::size_t j = 1; j < f.coefficients[i].size(); ++j)
      d.coefficients[i].push_back(f.coefficients[i][j] * static_cast<unsigned long>(j));
  return d;
}

// Every validity clause holds strictly at (x, y): some atom > 0.
bool strictly_valid_at(const std::vector<ValidityClause>& clauses, const Rational& x, const Real& y) {
  return std::all_of(clauses.begin(), clauses.end(), [&](const ValidityClause& clause) {
    return std::any_of(clause.atoms.begin(), clause.atoms.end(),
                       [&](const IntegerPolynomial2& atom) { return algebra::sign_at(atom, x, y) > 0; });
  });
}

// strictly_valid_at at a rational point (x, y): the linear atoms' signs in integers
// (sign_of_line_at), the others by algebra::sign_at at the rationals.
bool strictly_valid_at_rational(const std::vector<ValidityClause>& clauses, const Rational& x, const Rational& y) {
  return std::all_of(clauses.begin(), clauses.end(), [&](const ValidityClause& clause) {
    return std::any_of(clause.atoms.begin(), clause.atoms.end(), [&](const IntegerPolynomial2& atom) {
      const mpz_class *a, *b, *c;
      if (line_of(atom, a, b, c)) return sign_of_line_at(*a, *b, *c, x, y) > 0;
      return algebra::sign_at(atom, x, y) > 0;
    });
  });
}

// Face classification by the blocked side of a contact edge (docs/contact-kernels.md: a
// contact function has the sign `blocked_sign` where its two features locally penetrate, near
// configurations where the contact is valid). At the sample point of the non-vertical edge e,
// a curve k along it is valid with every clause strictly satisfied and f_k,y != 0 (a simple
// point): then f_k has the sign of f_k,y just above the edge and the opposite sign just below.
// When the face on the `above` side gets the blocked sign, the two features penetrate at
// configurations of that face arbitrarily near the sample, so the parts' interiors overlap
// there, and a face has one overlap relation throughout (no touching configuration lies inside
// a face): the face is blocked. Exact (signs at the edge's exact sample); false when undecided.
class ContactSides {
 public:
  ContactSides(const ChartData& chart, std::vector<int> blocked_signs)
      : chart_(chart), blocked_signs_(std::move(blocked_signs)), derivatives_(chart.polynomials.size()) {}

  bool blocked_side(std::size_t e, bool above) {
    const EdgeData& data = chart_.edges[e];
    for (std::size_t k : data.curves) {
      int sign = k < blocked_signs_.size() ? blocked_signs_[k] : 0;
      if (sign == 0) continue;
      // a line a x + b y + c: f_y is the constant b (no derivative polynomial formed); at an
      // exact sample its linear atoms' signs in integers (sign_of_line_at), as valid_at_rational
      const mpz_class *a, *b, *c;
      const bool line = line_of(chart_.polynomials[k], a, b, c);
      int slope;
      if (line) {
        slope = sgn(*b);
      } else {
        if (!derivatives_[k]) derivatives_[k] = derivative_y(chart_.polynomials[k]);
        slope = algebra::sign_at(*derivatives_[k], data.sample_x, data.sample_y);
      }
      if (slope == 0 || (above ? slope : -slope) != sign) continue;
      if (line && data.sample_y.exact ? strictly_valid_at_rational(chart_.validity[k], data.sample_x, data.sample_y.lower)
                                      : strictly_valid_at(chart_.validity[k], data.sample_x, data.sample_y))
        return true;
    }
    return false;
  }

 private:
  const ChartData& chart_;
  std::vector<int> blocked_signs_;
  std::vector<std::optional<IntegerPolynomial2>> derivatives_;
};

// A rational in (lo, hi) that is the abscissa of no vertex of the chart, decided exactly: the
// rational abscissae flagged exact are looked up, and every other vertex whose isolating
// interval holds the candidate is compared with it exactly (an abscissa can be rational
// without being flagged exact, e.g. a clipping end that CGAL reports as an algebraic real; a
// face sample taken on such a vertical line would miss the edges ending there).
Rational abscissa_avoiding_vertices(const ChartData& chart, const Real& lo, const Real& hi) {
  const std::vector<Rational>& exact = chart.rational_vertex_x;
  Rational candidate = algebra::rational_between(lo, hi);
  for (;;) {
    bool on_vertex = std::binary_search(exact.begin(), exact.end(), candidate);
    if (!on_vertex) {
      const algebra::Interval c = algebra::enclose(candidate);
      for (const raw::Vertex& v : chart.arrangement.vertices) {
        if (v.x.exact || v.x.upper_bound() < c.lo || v.x.lower_bound() > c.hi) continue;
        if (v.x.compare(candidate) == 0) {
          on_vertex = true;
          break;
        }
      }
    }
    if (!on_vertex) return candidate;
    candidate = algebra::rational_between(Real::from_rational(candidate), hi);
  }
}

// An exact rational sample strictly inside the bounded face f (once; deterministic: the same
// point whichever face asks first): on the vertical line through a rational abscissa of the
// face's widest non-vertical boundary edge, between that edge and the next edge on the face's
// side. Costs a scan of the chart's edges (nearest_on_vertical).
void sample_face(ChartData& chart, std::size_t f) {
  FaceData& data = chart.faces[f];
  if (data.sampled) return;
  const auto& arrangement = chart.arrangement;
  const raw::Face& face = arrangement.faces[f];
  // the non-vertical boundary edge with the widest x-range gives the simplest sample
  std::size_t chosen = raw::none;
  bool above = false;
  double widest = -1;
  for (const auto& [e, on_left] : face.boundary) {
    const raw::Edge& edge = arrangement.edges[e];
    if (edge.vertical) continue;
    double width = edge.box[2] - edge.box[0];
    if (width > widest) {
      widest = width;
      chosen = e;
      above = on_left;
    }
  }
  if (chosen == raw::none) throw GeometryError("internal: a C-space face has no non-vertical boundary edge");
  const raw::Edge& edge = arrangement.edges[chosen];
  Rational x = abscissa_avoiding_vertices(chart, arrangement.vertices[edge.min_vertex].x,
                                         arrangement.vertices[edge.max_vertex].x);
  Real from = edge_y_at(chart, chosen, x);
  Hit hit = nearest_on_vertical(chart, x, from, above);
  if (!hit.found) throw GeometryError("internal: no edge bounds a C-space face on a vertical line");
  data.sample_x = x;
  data.sample_y = above ? algebra::rational_between(from, hit.y) : algebra::rational_between(hit.y, from);
  data.sampled = true;
}

// Test-only check (CSpaceBuildOptions::check_face_classification) that a face's sample lies
// inside the face, independent of how sample_face found it (the nearest edge above or below
// on a vertical line, over all edges of the chart): the parity of the crossings of the upward
// ray from the sample with each boundary cycle of the face itself (the export's CCBs, an edge
// counted as often as the cycle runs along it). Inside iff the outer cycle is crossed an odd
// number of times and every inner cycle (hole) an even number. The sample's abscissa avoids
// every vertex (abscissa_avoiding_vertices), so every crossing is at an edge's interior and
// decided exactly (edge_y_at at a rational x); the sample on an edge, or a vertex at its
// abscissa, is an error too.
void check_sample_in_face(const ChartData& chart, std::size_t f) {
  const auto& arrangement = chart.arrangement;
  const raw::Face& face = arrangement.faces[f];
  const FaceData& data = chart.faces[f];
  const std::string where = data.sample_x.get_str() + ", " + data.sample_y.get_str();
  const Real sample_y = Real::from_rational(data.sample_y);
  for (std::size_t c = 0; c < face.component_starts.size(); ++c) {
    const std::size_t begin = face.component_starts[c];
    const std::size_t end = c + 1 < face.component_starts.size() ? face.component_starts[c + 1] : face.boundary.size();
    std::size_t crossings = 0;
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t e = face.boundary[i].first;
      const raw::Edge& edge = arrangement.edges[e];
      const int at_min = arrangement.vertices[edge.min_vertex].x.compare(data.sample_x);
      const int at_max = arrangement.vertices[edge.max_vertex].x.compare(data.sample_x);
      if (at_min == 0 || at_max == 0)
        throw GeometryError("internal: a face sample's abscissa meets a boundary vertex at " + where);
      if (edge.vertical || at_min > 0 || at_max < 0) continue;
      const int side = algebra::compare(edge_y_at(chart, e, data.sample_x), sample_y);
      if (side == 0) throw GeometryError("internal: a face sample lies on the face's boundary at " + where);
      crossings += side > 0;
    }
    // the first cycle of a bounded face is its outer boundary
    const bool outer = c == 0 && !face.unbounded;
    if ((crossings % 2 == 1) != outer)
      throw GeometryError(std::string("internal: a face sample is not inside its face (") +
                          (outer ? "outside the outer boundary" : "inside a hole") + ") at " + where);
  }
}

// Every bounded face gets its kind (samples are taken lazily by sample_face: the builder needs
// one per cell). Blocked when it lies on the blocked side of a contact edge of its boundary
// (`sides`); else, with `propagate`, the kind of a neighbour across an edge that carries no
// valid contact curve; else the exact oracle at its sample. `check`: the oracle at every
// face's sample, and disagreement is an error.
//
// Propagation: every configuration where the parts touch lies on a valid contact curve of the
// chart (the curve generator and the culls remove only feature pairs that never touch there
// or whose contacts lie in certified blocked space, and label_edges lists every curve valid
// along an edge). A point inside an edge that carries no valid curve is therefore no touching
// configuration: the parts are apart there or overlap, both open conditions, so the faces on
// its two sides have the same kind. Only free and blocked are propagated (not touching), and
// never across the chart box. The caller switches it off when some contact function is
// identically zero (then touching configurations fill whole faces).
void classify_faces(ChartData& chart, const Classifier& classify, ContactSides* sides, bool check, bool propagate) {
  const auto& arrangement = chart.arrangement;
  chart.rational_vertex_x.reserve(chart.rational_vertex_x.size() + arrangement.vertices.size());   // (no regrowth: its rationals are not copied)
  for (const auto& v : arrangement.vertices)
    if (v.x.exact) chart.rational_vertex_x.push_back(v.x.lower);
  // (CGAL's sweep makes the vertices left to right, so the list is usually sorted already: a
  // sort moves rationals, and every gmpxx move re-initialises its source, two allocations)
  if (!std::is_sorted(chart.rational_vertex_x.begin(), chart.rational_vertex_x.end()))
    std::sort(chart.rational_vertex_x.begin(), chart.rational_vertex_x.end());
  chart.faces.assign(arrangement.faces.size(), FaceData{});
  std::vector<char> known(arrangement.faces.size(), 0);
  std::vector<std::size_t> queue;
  // faces on the blocked side of a contact edge
  for (std::size_t f = 0; f < arrangement.faces.size(); ++f) {
    const raw::Face& face = arrangement.faces[f];
    if (face.unbounded) continue;
    bool by_side = false;
    if (sides)
      for (std::size_t i = 0; i < face.boundary.size() && !by_side; ++i) {
        const auto& [e, on_left] = face.boundary[i];
        if (arrangement.edges[e].vertical || chart.edges[e].curves.empty()) continue;
        by_side = sides->blocked_side(e, on_left);
      }
    if (!by_side) continue;
    chart.faces[f].kind = FaceKind::blocked;
    known[f] = 1;
    queue.push_back(f);
  }
  // propagation across edges without a valid contact curve
  std::vector<std::vector<std::size_t>> free_edges;   // per face: its curve-free inner edges
  if (propagate) {
    free_edges.resize(arrangement.faces.size());
    for (std::size_t e = 0; e < arrangement.edges.size(); ++e) {
      const raw::Edge& edge = arrangement.edges[e];
      if (edge.box_side >= 0 || !chart.edges[e].curves.empty() || edge.left_face == edge.right_face) continue;
      free_edges[edge.left_face].push_back(e);
      free_edges[edge.right_face].push_back(e);
    }
  }
  auto spread = [&] {
    while (propagate && !queue.empty()) {
      std::size_t f = queue.back();
      queue.pop_back();
      const FaceKind kind = chart.faces[f].kind;
      if (kind != FaceKind::free && kind != FaceKind::blocked) continue;
      for (std::size_t e : free_edges[f]) {
        const raw::Edge& edge = arrangement.edges[e];
        std::size_t g = edge.left_face == f ? edge.right_face : edge.left_face;
        if (g == raw::none || known[g] || arrangement.faces[g].unbounded) continue;
        chart.faces[g].kind = kind;
        known[g] = 1;
        queue.push_back(g);
      }
    }
    queue.clear();
  };
  spread();
  // the rest: the exact oracle at the sample, then propagation from it
  for (std::size_t f = 0; f < arrangement.faces.size(); ++f) {
    if (arrangement.faces[f].unbounded) continue;
    FaceData& data = chart.faces[f];
    if (check) {
      sample_face(chart, f);
      check_sample_in_face(chart, f);
    }
    if (known[f]) {
      if (!check) continue;
      if (kind_of(classify(ChartPoint{data.sample_x, data.sample_y})) != data.kind)
        throw GeometryError("internal: a face classified by a contact edge's blocked side or by propagation "
                            "disagrees with the oracle at " + data.sample_x.get_str() + ", " + data.sample_y.get_str());
      continue;
    }
    sample_face(chart, f);
    data.kind = kind_of(classify(ChartPoint{data.sample_x, data.sample_y}));
    known[f] = 1;
    queue.push_back(f);
    spread();
  }
}

// ---------------------------------------------------------------- zero-clearance contacts

// The exact value of r when it is rational: r exact, r the root of a linear polynomial, or a
// rational of moderate denominator (Real::detect_rational).
std::optional<Rational> rational_value(Real r, bool thorough = true) {
  if (!r.exact && algebra::degree(r.polynomial) == 1) {
    Rational value(r.polynomial[0], r.polynomial[1]);
    value.canonicalize();
    return Rational(-value);
  }
  if (!thorough) return r.exact ? std::optional<Rational>(r.lower) : std::nullopt;
  r.detect_rational();
  if (r.exact) return r.lower;
  return std::nullopt;
}

// A rational point on the relative interior of edge e (not a chart side), or nullopt. The
// oracle's answer there is the answer along the whole open edge: the overlap relation only
// changes where some contact curve meets the edge, which is a vertex of the arrangement.
// Not `thorough`: only the edge's sample, when its ordinate is rational without searching.
std::optional<ChartPoint> rational_point_on_edge(const ChartData& chart, std::size_t e, bool thorough) {
  const raw::Edge& edge = chart.arrangement.edges[e];
  const EdgeData& data = chart.edges[e];
  const raw::Vertex& low = chart.arrangement.vertices[edge.min_vertex];
  const raw::Vertex& high = chart.arrangement.vertices[edge.max_vertex];
  if (edge.vertical) {
    // sample_y is rational; the edge's x is one number
    auto x = rational_value(*data.vertical_x, thorough);
    if (x && data.sample_y.exact) return ChartPoint{*x, data.sample_y.lower};
    return std::nullopt;
  }
  if (!thorough) {
    auto y = rational_value(data.sample_y, false);
    if (y) return ChartPoint{data.sample_x, *y};
    return std::nullopt;
  }
  // rational abscissae across the edge (the sample first), each with the edge's exact ordinate
  std::vector<Rational> xs{data.sample_x};
  std::vector<std::pair<Real, Real>> spans{{low.x, Real::from_rational(data.sample_x)},
                                           {Real::from_rational(data.sample_x), high.x}};
  for (std::size_t i = 0; i < spans.size() && xs.size() < 7; ++i) {
    auto [lo, hi] = spans[i];   // a copy: the vector grows below
    Rational x = algebra::rational_between(lo, hi);
    xs.push_back(x);
    spans.emplace_back(lo, Real::from_rational(x));
    spans.emplace_back(Real::from_rational(x), hi);
  }
  for (std::size_t i = 0; i < xs.size(); ++i) {
    Real y = i == 0 ? data.sample_y : edge_y_at(chart, e, xs[i]);
    if (auto value = rational_value(std::move(y))) return ChartPoint{xs[i], *value};
  }
  // rational ordinates: the edge is y-monotone, so a rational root x of support(x, y0) strictly
  // inside the edge's x-range whose edge ordinate is y0 is a point of the edge
  auto below = [](const raw::Vertex& v) { return v.y_exact ? v.y : Real::from_rational(v.y_lower); };
  auto above = [](const raw::Vertex& v) { return v.y_exact ? v.y : Real::from_rational(v.y_upper); };
  Real a, b;
  if (algebra::compare(above(low), below(high)) < 0) {
    a = above(low);
    b = below(high);
  } else if (algebra::compare(above(high), below(low)) < 0) {
    a = above(high);
    b = below(low);
  } else {
    return std::nullopt;
  }
  if (algebra::compare(a, b) >= 0) return std::nullopt;   // horizontal: handled by the abscissae
  std::vector<Rational> ys;
  std::vector<std::pair<Real, Real>> y_spans{{a, b}};
  for (std::size_t i = 0; i < y_spans.size() && ys.size() < 7; ++i) {
    auto [lo, hi] = y_spans[i];   // a copy: the vector grows below
    Rational y = algebra::rational_between(lo, hi);
    ys.push_back(y);
    y_spans.emplace_back(lo, Real::from_rational(y));
    y_spans.emplace_back(Real::from_rational(y), hi);
  }
  Rational x_lo = low.x.lower, x_hi = high.x.upper;
  for (const Rational& y : ys) {
    algebra::Polynomial p = algebra::substitute_y(edge.support, y);
    if (algebra::degree(p) < 1) continue;
    for (Real& root : algebra::real_roots(p, x_lo, x_hi)) {
      auto x = rational_value(root);
      if (!x || low.x.compare(*x) >= 0 || high.x.compare(*x) <= 0) continue;
      if (edge_y_at(chart, e, *x).compare(y) == 0) return ChartPoint{*x, y};
    }
  }
  return std::nullopt;
}

// The algebraic oracle's relation at a zero-clearance candidate between blocked faces: touching
// or overlapping (apart there would contradict the blocked faces around it).
bool algebraic_touching(Overlap relation, const char* where) {
  if (relation == Overlap::apart)
    throw GeometryError(std::string("internal: the parts are apart at an irrational point ") + where);
  return relation == Overlap::touching;
}

// The ordinate of an arrangement vertex as an expression in its abscissa x0, for the algebraic
// oracle at a vertex whose coordinates are not both rational (RadicalOrdinate), or nullopt. The
// curves through the vertex: its edges' supports, and, at an isolated point of a curve (a
// singular point: the curve's partial derivatives vanish there too), that curve's derivative in
// y. Tried in turn:
//  - one of degree 1 in y, b(x) y + c(x) with b(x0) != 0, has the vertex's ordinate as its only
//    root: -c / b;
//  - two of degree 2, f = a y^2 + b y + c and g = d y^2 + e y + h, vanish at the vertex, so
//    a g - d f = (a e - b d) y + (a h - c d) does: where a e - b d is not 0 at x0, its root is
//    the ordinate (the first subresultant);
//  - one of degree 2 (the vertex's own curve first), f(x0, y) = a y^2 + b y + c: with a(x0) = 0
//    and b(x0) != 0 its root -c / b; else with D = b^2 - 4ac, D(x0) = 0, its double root
//    -b / 2a; D(x0) > 0, its root in the vertex's y-enclosure (lo, hi) when f(x0, lo) and
//    f(x0, hi) have opposite signs (then exactly one is there): f_y = 2a y + b = s √D at the
//    root (-b + s √D) / 2a, and f_y there has f(x0, hi)'s sign, so s = sign f(x0, hi). (On the
//    vertex's own curve, whose roots at x0 the enclosure isolates, this leaves out only an
//    ordinate at an end of its enclosure.) A curve crossing a vertical contact line, or two
//    contact lines crossing, one vertical and one horizontal of degree 2 (the escapement's wheel
//    tip on an arc about the anchor's pivot while a pallet corner is on an arc about the wheel's
//    centre), has such a vertex.
// Curves of higher degree in y are not tried. The ordinate found is checked exactly on the
// vertex's own curve (its sign there 0) and within its y-enclosure (algebraic_overlap checks the
// enclosure), which isolates the vertex's ordinate among the roots of that curve: any ordinate
// passing both is the vertex's.
std::optional<RadicalOrdinate> vertex_ordinate(const raw::Arrangement& arrangement, const raw::Vertex& vertex) {
  std::vector<const IntegerPolynomial2*> curves;
  for (const auto& incidence : vertex.around) curves.push_back(&arrangement.edges[incidence.edge].support);
  IntegerPolynomial2 derivative;
  if (vertex.isolated && vertex.y_curve.degree_y() >= 1) {
    derivative.coefficients.resize(vertex.y_curve.coefficients.size());
    for (std::size_t i = 0; i < vertex.y_curve.coefficients.size(); ++i) {
      const auto& row = vertex.y_curve.coefficients[i];
      for (std::size_t j = 1; j < row.size(); ++j) derivative.coefficients[i].push_back(row[j] * static_cast<unsigned long>(j));
    }
    curves.push_back(&vertex.y_curve);
    curves.push_back(&derivative);
  }
  auto sign_at_x = [&](const algebra::Polynomial& p) { return algebra::sign_at(p, vertex.x); };
  auto nonzero_at_x = [&](const algebra::Polynomial& p) { return sign_at_x(p) != 0; };
  auto minus = [](algebra::Polynomial a, const algebra::Polynomial& b) {
    if (a.size() < b.size()) a.resize(b.size());
    for (std::size_t i = 0; i < b.size(); ++i) a[i] -= b[i];
    algebra::trim(a);
    return a;
  };
  std::optional<RadicalOrdinate> found;
  for (std::size_t i = 0; i < curves.size() && !found; ++i) {
    const IntegerPolynomial2& f = *curves[i];
    if (f.degree_y() == 1) {
      algebra::Polynomial b = algebra::y_coefficient(f, 1);
      if (nonzero_at_x(b)) found = RadicalOrdinate{minus({}, algebra::y_coefficient(f, 0)), {}, std::move(b), {}, {}};
      continue;
    }
    if (f.degree_y() != 2) continue;
    for (std::size_t k = i + 1; k < curves.size() && !found; ++k) {
      const IntegerPolynomial2& g = *curves[k];
      if (g.degree_y() != 2) continue;
      const algebra::Polynomial a = algebra::y_coefficient(f, 2), b = algebra::y_coefficient(f, 1), c = algebra::y_coefficient(f, 0);
      const algebra::Polynomial d = algebra::y_coefficient(g, 2), e = algebra::y_coefficient(g, 1), h = algebra::y_coefficient(g, 0);
      algebra::Polynomial m = minus(algebra::product(a, e), algebra::product(b, d));
      if (!nonzero_at_x(m)) continue;
      // y = -(a h - c d) / (a e - b d)
      found = RadicalOrdinate{minus(algebra::product(c, d), algebra::product(a, h)), {}, std::move(m), {}, {}};
    }
  }
  const Rational& lower = vertex.y_exact ? vertex.y.lower : vertex.y_lower;
  const Rational& upper = vertex.y_exact ? vertex.y.upper : vertex.y_upper;
  if (!found) {
    // a root of one curve of degree 2 in y: the vertex's own curve first
    std::vector<const IntegerPolynomial2*> quadratics{&vertex.y_curve};
    quadratics.insert(quadratics.end(), curves.begin(), curves.end());
    for (const IntegerPolynomial2* f : quadratics) {
      if (f->degree_y() != 2) continue;
      algebra::Polynomial a = algebra::y_coefficient(*f, 2), b = algebra::y_coefficient(*f, 1), c = algebra::y_coefficient(*f, 0);
      if (!nonzero_at_x(a)) {
        if (nonzero_at_x(b)) found = RadicalOrdinate{minus({}, c), {}, std::move(b), {}, {}};
      } else {
        algebra::Polynomial D = minus(algebra::product(b, b), algebra::product(algebra::product(a, c), {mpz_class(4)}));
        const int d = sign_at_x(D);
        algebra::Polynomial two_a = algebra::product(a, {mpz_class(2)});
        if (d == 0) {
          found = RadicalOrdinate{minus({}, b), {}, std::move(two_a), {}, {}};
        } else if (d > 0) {
          const int at_lower = sign_at_x(algebra::substitute_y(*f, lower)), at_upper = sign_at_x(algebra::substitute_y(*f, upper));
          if (at_lower * at_upper < 0)
            found = at_upper > 0 ? RadicalOrdinate{minus({}, b), std::move(D), std::move(two_a), {}, {}}
                                 : RadicalOrdinate{std::move(b), std::move(D), minus({}, two_a), {}, {}};
        }
      }
      if (found) break;
    }
  }
  if (!found) return std::nullopt;
  found->lower = lower;
  found->upper = upper;
  if (!vertex.y_curve.is_zero()) {
    const int q = sign_at_x(found->denominator);
    if (q == 0 || (!found->radicand.empty() && sign_at_x(found->radicand) < 0) ||
        algebra::sign_at(vertex.y_curve, vertex.x, *found, q) != 0)
      return std::nullopt;
  }
  return found;
}

// Zero-clearance contacts: edges and isolated vertices of contact space with blocked space on
// every side. A face sample never lies on them; the exact oracle decides at a rational point
// of each whether the parts only touch there (a channel of zero width: EdgeRole::touching) or
// overlap (a curve through blocked space: spurious).
void find_touching(ChartData& chart, const Classifier& classify, const AlgebraicClassifier& classify_algebraic,
                   const OrdinateClassifier& classify_ordinate, const OverlapFilter& certainly_overlapping,
                   ContactSides* sides, bool check, CSpaceStatistics& stats,
                   const std::function<void(std::size_t, std::size_t)>& tick = {}) {
  const auto& arrangement = chart.arrangement;
  // (progress: tick(done, total) over the edges, then the vertices)
  const std::size_t work = arrangement.edges.size() + arrangement.vertices.size();
  chart.touching_vertex.assign(arrangement.vertices.size(), 0);
  auto blocked = [&](std::size_t face) {
    return face != raw::none && !arrangement.faces[face].unbounded && chart.faces[face].kind == FaceKind::blocked;
  };
  auto decide = [&](const ChartPoint& q) {
    Overlap relation = classify(q);
    if (relation == Overlap::apart)
      throw GeometryError("internal: the parts are apart at " + q.x.get_str() + ", " + q.y.get_str() +
                          " in contact space between blocked faces");
    return relation == Overlap::touching;
  };
  for (std::size_t e = 0; e < arrangement.edges.size(); ++e) {
    const raw::Edge& edge = arrangement.edges[e];
    if (tick) tick(e, work);
    if (edge.box_side >= 0 || !blocked(edge.left_face) || !blocked(edge.right_face)) continue;
    EdgeData& data = chart.edges[e];
    if (data.curves.empty()) continue;
    // One contact along the edge, with a decided blocked side (ContactSides: the curve is
    // valid with every clause strict and f_y != 0 at the sample): if the parts only touched at
    // the sample, that contact would be their only one (every feature pair touching there has
    // a valid curve through it, and culled curves lie only in certainly blocked space), so
    // moving off the edge to the curve's other side would separate them: that face would be
    // free. Both faces are blocked, so the edge lies in blocked space; no oracle call.
    if (sides && data.curves.size() == 1 && !edge.vertical &&
        (sides->blocked_side(e, true) || sides->blocked_side(e, false))) {
      if (check) {
        auto point = rational_point_on_edge(chart, e, false);
        if (point && decide(*point))
          throw GeometryError("internal: a one-contact edge between blocked faces is touching at " +
                              point->x.get_str() + ", " + point->y.get_str());
      }
      continue;
    }
    // one curve: the sample only (without a rational point the edge certainly overlaps, below)
    auto point = rational_point_on_edge(chart, e, data.curves.size() >= 2);
    if (!point) {
      // A touching edge between blocked faces carries two or more contacts (one contact alone
      // separates on one side); with one curve the edge certainly lies in blocked space. With
      // two or more, the exact oracle at the edge's sample, one coordinate irrational (the
      // edge's ordinate at its rational sample abscissa; a vertical edge's abscissa).
      if (data.curves.size() < 2) continue;
      std::optional<Overlap> relation;
      if (classify_algebraic)
        relation = edge.vertical ? classify_algebraic(*data.vertical_x, data.sample_y)
                                 : classify_algebraic(Real::from_rational(data.sample_x), data.sample_y);
      if (!relation) {
        ++stats.touching_undecided;
        continue;
      }
      data.touching = algebraic_touching(*relation, "on a contact edge between blocked faces");
      if (data.touching) ++stats.touching_edges;
      continue;
    }
    data.touching = decide(*point);
    if (data.touching) ++stats.touching_edges;
  }
  // isolated points: rational vertices of curves only, blocked all around
  for (std::size_t v = 0; v < arrangement.vertices.size(); ++v) {
    const raw::Vertex& vertex = arrangement.vertices[v];
    if (tick) tick(arrangement.edges.size() + v, work);
    if (!vertex.isolated && vertex.around.size() < 2) continue;
    // on curves (not a corner of the box), no end of a touching edge, blocked in every wedge
    // inside the box (a vertex on a seam is checked in each chart it appears in); an isolated
    // point of a curve (a peg in a round hole of exactly its radius: the curve of two equal
    // concentric arcs is one point) inside a blocked face
    bool on_curve = vertex.isolated, candidate = !vertex.isolated || blocked(vertex.face_below);
    for (const auto& incidence : vertex.around) {
      if (arrangement.edges[incidence.edge].box_side < 0) on_curve = true;
      if (chart.edges[incidence.edge].touching) candidate = false;
      if (incidence.wedge_face == raw::none) candidate = false;
      else if (!arrangement.faces[incidence.wedge_face].unbounded && !blocked(incidence.wedge_face)) candidate = false;
      if (!candidate) break;
    }
    if (!candidate || !on_curve) continue;
    auto x = rational_value(vertex.x, false);   // rational vertices come out exact (or linear)
    // (an irrational abscissa: only an exact or linear ordinate is looked for, cheaply)
    std::optional<Rational> y;
    if (vertex.y_exact) y = rational_value(vertex.y, false);
    // Session 63: the classifiers' certified filter over the vertex's box, first — where the
    // parts certainly overlap throughout it, every route below answers "overlapping" (not
    // touching), and neither the complete rational test of the ordinate (Hensel lifting) nor
    // the ordinate's expression (vertex_ordinate) is needed. Not where the point is rational
    // (the exact oracle at it costs less) or one contact decides it (below, no oracle call).
    auto filtered = [&] {
      if (!certainly_overlapping) return false;
      const Rational& y_lower = vertex.y_exact ? vertex.y.lower : vertex.y_lower;
      const Rational& y_upper = vertex.y_exact ? vertex.y.upper : vertex.y_upper;
      return certainly_overlapping(x ? Real::from_rational(*x) : vertex.x, y_lower, y_upper);
    };
    if (vertex.y_exact && x && !y) {
      if (filtered()) continue;
      y = rational_value(vertex.y, true);
    }
    if (!x || !y) {
      // One contact curve at the vertex (every edge there carries the same single curve): the
      // parts' relation at it is its edges' — along a curve it changes only where another
      // contact begins or ends, which another curve through the point would mark (culled curves
      // lie only in certainly blocked space) — and those edges, blocked on both sides with one
      // curve, are decided and not touching (above): the vertex overlaps; no oracle call.
      const std::vector<std::size_t>& first = chart.edges[vertex.around.empty() ? 0 : vertex.around.front().edge].curves;
      bool one_curve = !vertex.isolated && !vertex.around.empty() && first.size() == 1;
      for (const auto& incidence : vertex.around)
        if (arrangement.edges[incidence.edge].box_side >= 0 || chart.edges[incidence.edge].curves != first) one_curve = false;
      if (one_curve) continue;
      if (!(vertex.y_exact && x) && filtered()) continue;   // (asked above when x is rational)
      // one coordinate irrational: the exact oracle at the algebraic point; both irrational (or
      // an ordinate known by its curve only): at the ordinate as a rational function of the
      // abscissa (vertex_ordinate); undecided (counted) where neither applies
      std::optional<Overlap> relation;
      if (vertex.y_exact && (x || y)) {
        if (classify_algebraic)
          relation = classify_algebraic(x ? Real::from_rational(*x) : vertex.x, y ? Real::from_rational(*y) : vertex.y);
      } else if (classify_ordinate) {
        if (std::optional<RadicalOrdinate> ordinate = vertex_ordinate(arrangement, vertex))
          relation = classify_ordinate(vertex.x, *ordinate);
      }
      if (!relation) {
        ++stats.touching_undecided;
      } else if (algebraic_touching(*relation, "at a contact vertex between blocked faces")) {
        chart.touching_vertex[v] = 1;
        ++stats.touching_vertices;
      }
      continue;
    }
    if (decide(ChartPoint{*x, *y})) {
      chart.touching_vertex[v] = 1;
      ++stats.touching_vertices;
    }
  }
}

// ---------------------------------------------------------------- 1-D charts

// Zero-clearance points of a 1-D chart (session 29): a contact point with blocked intervals on
// both sides is a configuration where the parts only touch (a peg of exactly its hole's length:
// touching, a separate blocked cell on each side, like a 2-D touching edge) or a curve through
// blocked space, decided as the 2-D find_touching decides: a rational point by the exact
// oracle; a point of one contact whose polynomial changes sign there is blocked (were the parts
// only touching, that contact would be their only one and the side where it opens would be
// free); any other irrational point stays blocked and is counted undecided.
// States that cannot arise (faces not one more than the points, a point without its curves,
// the parts overlapping at one point between free intervals: overlap is open in the
// configuration) throw GeometryError naming the chart point, never reach undefined behaviour.
void find_touching_points(ChartData& chart, const Classifier& classify, const AlgebraicClassifier& classify_algebraic,
                          CSpaceStatistics& stats) {
  if (chart.faces.size() != chart.points.size() + 1 || chart.point_curves.size() != chart.points.size())
    throw GeometryError("internal: a 1-D chart has " + std::to_string(chart.points.size()) + " contact points, " +
                        std::to_string(chart.point_curves.size()) + " curve lists and " + std::to_string(chart.faces.size()) +
                        " intervals (intervals must be points + 1)");
  chart.touching_vertex.assign(chart.points.size(), 0);
  chart.seam_relation.assign(chart.points.size(), -1);
  chart.grazing_point.assign(chart.points.size(), 0);
  for (std::size_t i = 0; i < chart.points.size(); ++i) {
    // a point on the chart's end (its outer face empty) with blocked or free space inside: the
    // relation of the parts there, for the seam decision in `build` (the other side is another
    // chart's) and for point location there (a contact point is no contact where the parts
    // overlap or are apart). The point is the chart's end itself, a rational.
    const bool low_empty = chart.faces[i].kind == FaceKind::outside, high_empty = chart.faces[i + 1].kind == FaceKind::outside;
    if (low_empty != high_empty) {
      const FaceKind inner = (low_empty ? chart.faces[i + 1] : chart.faces[i]).kind;
      if (inner != FaceKind::blocked && inner != FaceKind::free) continue;
      const Overlap relation = classify(ChartPoint{low_empty ? chart.box.x_lo : chart.box.x_hi, Rational(0)});
      chart.seam_relation[i] = relation == Overlap::touching ? 1 : relation == Overlap::overlapping ? 0 : 2;
      continue;
    }
    // a contact point with free space on both sides: a grazing contact where the parts touch,
    // or no contact at all; a rational point is decided by the exact oracle (an irrational one
    // stays inside its free cell: not decided, docs/performance.md, session 30)
    if (chart.faces[i].kind == FaceKind::free && chart.faces[i + 1].kind == FaceKind::free) {
      if (auto x = rational_value(chart.points[i])) {
        Overlap relation = classify(ChartPoint{*x, Rational(0)});
        if (relation == Overlap::overlapping)
          throw GeometryError("internal: the parts overlap at " + x->get_str() + " between free intervals");
        chart.grazing_point[i] = relation == Overlap::touching;
      }
      continue;
    }
    if (chart.faces[i].kind != FaceKind::blocked || chart.faces[i + 1].kind != FaceKind::blocked) continue;
    const Real& point = chart.points[i];
    if (!point.exact && chart.point_curves[i].size() == 1) {
      algebra::Polynomial p = algebra::univariate_x(chart.polynomials[chart.point_curves[i][0]]);
      if (algebra::square_free_test(p) == algebra::primitive_part(point.polynomial) &&
          algebra::sign_at(p, point.lower) * algebra::sign_at(p, point.upper) < 0)
        continue;
    }
    auto x = rational_value(point);
    if (!x) {
      // irrational: the exact oracle at the algebraic point (undecided only where it cannot)
      std::optional<Overlap> relation;
      if (classify_algebraic) relation = classify_algebraic(point, Real::from_rational(Rational(0)));
      if (!relation) {
        ++stats.touching_undecided;
      } else if (algebraic_touching(*relation, ("between blocked intervals at " + point.description()).c_str())) {
        chart.touching_vertex[i] = 1;
        ++stats.touching_vertices;
      }
      continue;
    }
    Overlap relation = classify(ChartPoint{*x, Rational(0)});
    if (relation == Overlap::apart)
      throw GeometryError("internal: the parts are apart at " + x->get_str() + " between blocked intervals");
    if (relation == Overlap::touching) {
      chart.touching_vertex[i] = 1;
      ++stats.touching_vertices;
    }
  }
}

void build_interval_chart(ChartData& chart, const ChartInput& input, CSpaceStatistics& stats) {
  struct Point {
    Real x;
    std::vector<std::size_t> curves;
  };
  std::vector<Point> points;
  for (std::size_t k = 0; k < chart.polynomials.size(); ++k) {
    algebra::Polynomial p = algebra::univariate_x(chart.polynomials[k]);
    if (algebra::degree(p) < 1) continue;
    for (auto& root : algebra::real_roots(p, chart.box.x_lo, chart.box.x_hi)) {
      root.detect_rational();
      bool valid = true;
      for (const auto& clause : chart.validity[k]) {
        bool holds = false;
        for (const auto& atom : clause.atoms)
          if (algebra::sign_at(algebra::univariate_x(atom), root) >= 0) holds = true;
        if (!holds) valid = false;
      }
      if (!valid) continue;
      auto it = std::find_if(points.begin(), points.end(),
                             [&](const Point& q) { return algebra::compare(q.x, root) == 0; });
      if (it != points.end())
        it->curves.push_back(k);
      else
        points.push_back(Point{std::move(root), {k}});
    }
  }
  std::sort(points.begin(), points.end(), [](const Point& a, const Point& b) { return algebra::compare(a.x, b.x) < 0; });
  for (auto& p : points) {
    chart.points.push_back(p.x);
    chart.point_curves.push_back(p.curves);
  }
  // faces[i]: the open interval before point i (faces.back(): after the last point)
  chart.faces.assign(points.size() + 1, FaceData{});
  for (std::size_t i = 0; i <= points.size(); ++i) {
    Real lo = i == 0 ? Real::from_rational(chart.box.x_lo) : points[i - 1].x;
    Real hi = i == points.size() ? Real::from_rational(chart.box.x_hi) : points[i].x;
    if (algebra::compare(lo, hi) >= 0) continue;   // empty (a point on the chart boundary)
    FaceData& face = chart.faces[i];
    face.sample_x = algebra::rational_between(lo, hi);
    face.sample_y = 0;
    face.sampled = true;
    face.kind = kind_of(input.classify(ChartPoint{face.sample_x, Rational(0)}));
  }
  find_touching_points(chart, input.classify, input.classify_algebraic, stats);
}

// ---------------------------------------------------------------- cells

// Union-find over faces of all charts with integer winding potentials per rotation axis.
class Components {
 public:
  explicit Components(std::size_t n) : parent_(n), offset_(n, {0, 0}), wraps_(n, {false, false}) {
    std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  }
  std::pair<std::size_t, std::array<long, 2>> find(std::size_t a) {
    std::array<long, 2> total{0, 0};
    std::size_t root = a;
    while (parent_[root] != root) {
      total[0] += offset_[root][0];
      total[1] += offset_[root][1];
      root = parent_[root];
    }
    // path compression
    std::array<long, 2> running = total;
    while (parent_[a] != a) {
      std::size_t next = parent_[a];
      std::array<long, 2> own = offset_[a];
      parent_[a] = root;
      offset_[a] = running;
      running[0] -= own[0];
      running[1] -= own[1];
      a = next;
    }
    return {root, total};
  }
  // lift(b) = lift(a) + d
  void join(std::size_t a, std::size_t b, std::array<long, 2> d) {
    auto [ra, oa] = find(a);
    auto [rb, ob] = find(b);
    if (ra == rb) {
      for (int k = 0; k < 2; ++k)
        if (ob[k] - oa[k] != d[k]) wraps_[ra][k] = true;
      return;
    }
    parent_[rb] = ra;
    for (int k = 0; k < 2; ++k) {
      offset_[rb][k] = oa[k] + d[k] - ob[k];
      wraps_[ra][k] = wraps_[ra][k] || wraps_[rb][k];
    }
  }
  std::array<bool, 2> wraps(std::size_t root) const { return wraps_[root]; }

 private:
  std::vector<std::size_t> parent_;
  std::vector<std::array<long, 2>> offset_;
  std::vector<std::array<bool, 2>> wraps_;
};

double chart_angle(const ChartAxis& axis, const Rational& t) {
  return (axis.half_turn ? std::numbers::pi : 0.0) + 2 * std::atan(t.get_d());
}

// Is chart axis a's value `ta` the same part coordinate as chart axis b's value `tb`?
// Translation axes meet only where tiles of one chart meet (a chart never wraps).
bool same_coordinate(const ChartAxis& a, const Rational& ta, const ChartAxis& b, const Rational& tb) {
  if (a.kind != b.kind) return false;
  if (a.kind == ChartAxis::Kind::translation) return ta == tb && a.lo != b.lo;
  if (a.half_turn == b.half_turn) return ta == tb;
  return ta * tb == -1;
}

long winding_between(const ChartAxis& a, const Rational& ta, const ChartAxis& b, const Rational& tb) {
  if (a.kind == ChartAxis::Kind::translation) return 0;
  return std::lround((chart_angle(a, ta) - chart_angle(b, tb)) / (2 * std::numbers::pi));
}

struct SeamPiece {
  Real start, end;
  std::size_t edge;   // local
  std::size_t face;   // inner face, local
};

std::vector<SeamPiece> seam_pieces(const ChartData& chart, int side) {
  std::vector<SeamPiece> pieces;
  const auto& arrangement = chart.arrangement;
  for (std::size_t e = 0; e < arrangement.edges.size(); ++e) {
    const raw::Edge& edge = arrangement.edges[e];
    if (edge.box_side != side) continue;
    const raw::Vertex& a = arrangement.vertices[edge.min_vertex];
    const raw::Vertex& b = arrangement.vertices[edge.max_vertex];
    bool along_y = side == 1 || side == 3;
    std::size_t inner = arrangement.faces[edge.left_face].unbounded ? edge.right_face : edge.left_face;
    pieces.push_back(SeamPiece{along_y ? a.y : a.x, along_y ? b.y : b.x, e, inner});
  }
  std::sort(pieces.begin(), pieces.end(),
            [](const SeamPiece& p, const SeamPiece& q) { return algebra::compare(p.start, q.start) < 0; });
  return pieces;
}

}  // namespace

// ---------------------------------------------------------------- shared helpers

algebra::Real edge_y_at(const ChartData& chart, std::size_t local_edge, const Rational& x) {
  const raw::Edge& edge = chart.arrangement.edges[local_edge];
  // a line a x + b y + c (b != 0): its one root -(a x + c) / b, the rational that the root
  // isolation below returns (as an exact Real), without the substitution and square-free part
  if (const mpz_class *a, *b, *c; line_of(edge.support, a, b, c) && sgn(*b) != 0) {
    // (per-thread scratch, assigned before every read: no integer allocated per call)
    thread_local Rational root, box_lo, box_hi;
    const mpz_ptr num = mpq_numref(root.get_mpq_t()), den = mpq_denref(root.get_mpq_t());
    mpz_mul(num, a->get_mpz_t(), x.get_num_mpz_t());
    mpz_addmul(num, c->get_mpz_t(), x.get_den_mpz_t());
    mpz_neg(num, num);
    mpz_mul(den, b->get_mpz_t(), x.get_den_mpz_t());
    root.canonicalize();
    // strictly inside the certified box: decided by the root's certified double enclosure when
    // it lies strictly between the box's doubles (session 73: no conversion of the box to
    // rationals), else exactly as before
    if (const algebra::Interval r = algebra::enclose(root); !(edge.box[1] < r.lo && r.hi < edge.box[3])) {
      mpq_set_d(box_lo.get_mpq_t(), edge.box[1]);
      mpq_set_d(box_hi.get_mpq_t(), edge.box[3]);
      if (!(box_lo < root && root < box_hi))
        throw NumericError("internal: contact curve root 0 is not in its certified box");
    }
    return raw::exact_real(root);
  }
  algebra::Polynomial p = algebra::substitute_x(edge.support, x);
  Rational lo(edge.box[1]), hi(edge.box[3]);
  const int index = edge_arc_at(chart, local_edge, x);
  // a quadratic with two roots: the same root without the exact square-free part and Sturm
  // sequence (quadratic_root_in)
  if (std::optional<Real> root = quadratic_root_in(p, index, lo, hi)) return std::move(*root);
  return algebra::nth_real_root_in(p, index, lo, hi);
}

int edge_arc_at(const ChartData& chart, std::size_t local_edge, const Rational& x) {
  const raw::ArcNumbers& numbers = chart.arrangement.edges[local_edge].arc_numbers;
  int arcno = numbers.between.empty() ? 0 : numbers.between.back();
  for (std::size_t i = 0; i < numbers.events.size(); ++i) {
    int c = numbers.events[i].compare(x);
    if (c > 0) return numbers.between[i];
    if (c == 0) return numbers.at_event[i];
  }
  return arcno;
}

namespace {

algebra::Interval negated(algebra::Interval a) { return {-a.hi, -a.lo}; }

// a / b for b not containing 0: the hull of the four end quotients, each rounded to nearest
// (within half a unit in the last place) and widened outward by down/up.
algebra::Interval quotient(algebra::Interval a, algebra::Interval b) {
  double q[4] = {a.lo / b.lo, a.lo / b.hi, a.hi / b.lo, a.hi / b.hi};
  double lo = q[0], hi = q[0];
  for (double v : q) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  return {algebra::interval_detail::down(lo), algebra::interval_detail::up(hi)};
}

bool finite(algebra::Interval a) { return std::isfinite(a.lo) && std::isfinite(a.hi) && a.lo <= a.hi; }

}  // namespace

std::optional<QuadraticOrdinate> quadratic_ordinate(const ChartData& chart, std::size_t local_edge, const Rational& x) {
  const raw::Edge& edge = chart.arrangement.edges[local_edge];
  if (edge.vertical) return std::nullopt;
  if (const mpz_class *a, *b, *c; line_of(edge.support, a, b, c)) return std::nullopt;   // exact and cheap already
  algebra::Polynomial p = algebra::substitute_x(edge.support, x);
  if (p.size() != 3 || sgn(p[2]) == 0) return std::nullopt;
  QuadraticOrdinate q;
  q.a = p[2];
  q.b = p[1];
  q.c = p[0];
  mpz_class discriminant = q.b * q.b - 4 * q.a * q.c;
  if (sgn(discriminant) <= 0) return std::nullopt;   // a double root or none: the exact path
  q.index = edge_arc_at(chart, local_edge, x);
  if (q.index < 0 || q.index > 1) return std::nullopt;   // no such root: the exact path reports it
  if (std::optional<algebra::Interval> y = quadratic_root_enclosure(q.a, q.b, q.c, q.index)) {
    q.enclosed = true;
    q.y = *y;
  }
  ++locate_filter_edges();
  return q;
}

std::optional<algebra::Interval> quadratic_root_enclosure(const mpz_class& a, const mpz_class& b, const mpz_class& c,
                                                          int index) {
  // the two roots q_b / a and c / q_b with q_b = -(b + sign(b) sqrt(D)) / 2 where b's sign is
  // certain (no cancellation), else (-b -+ sqrt(D)) / (2 a); all with outward rounding
  using algebra::Interval;
  if (index < 0 || index > 1) return std::nullopt;
  Interval A = algebra::enclose(a), B = algebra::enclose(b), C = algebra::enclose(c);
  Interval D = algebra::enclose(mpz_class(b * b - 4 * a * c));
  if (!finite(A) || !finite(B) || !finite(C) || !finite(D) || D.lo <= 0 || A.contains_zero()) return std::nullopt;
  Interval root_d{algebra::interval_detail::down(std::sqrt(D.lo)), algebra::interval_detail::up(std::sqrt(D.hi))};
  Interval r0, r1;
  if (!B.contains_zero()) {
    Interval sum = B.lo > 0 ? B + root_d : B + negated(root_d);
    Interval qb = quotient(negated(sum), Interval{2, 2});
    if (qb.contains_zero()) return std::nullopt;
    r0 = quotient(qb, A);
    r1 = quotient(C, qb);
  } else {
    Interval two_a = A * Interval{2, 2};
    r0 = quotient(negated(B) + negated(root_d), two_a);
    r1 = quotient(negated(B) + root_d, two_a);
  }
  if (!finite(r0) || !finite(r1)) return std::nullopt;
  if (r1.hi < r0.lo) std::swap(r0, r1);
  if (!(r0.hi < r1.lo)) return std::nullopt;   // the enclosures do not separate the two roots
  return index == 0 ? r0 : r1;
}

int QuadraticOrdinate::compare(const Rational& v) const {
  // the sign of root - v, exactly: p(v) d^2 = a n^2 + b n d + c d^2 (v = n / d, d > 0) is zero
  // at a root, of a's sign outside [r0, r1] and of the other sign between; v against the
  // roots' midpoint -b / (2 a) tells r0 from r1 and below from above: sign(2 a n + b d) sign(a)
  const mpz_class& n = v.get_num();
  const mpz_class& d = v.get_den();
  mpz_class value = (a * n + b * d) * n + c * d * d;
  int side = sgn(2 * a * n + b * d) * sgn(a);   // sign of v - midpoint
  int s = sgn(value) * sgn(a);
  if (s < 0) return index == 0 ? -1 : 1;   // r0 < v < r1
  if (s > 0) return side < 0 ? 1 : -1;     // v < r0 (left of the midpoint) or v > r1
  // v is a root: r0 left of the midpoint, r1 right of it
  int which = side < 0 ? 0 : 1;
  return which == index ? 0 : (index > which ? 1 : -1);
}

namespace {
// to_public into an existing number (the vertices' public coordinates are written in place:
// no temporary number whose rationals are made and then destroyed with the ones it replaces)
void assign_public(AlgebraicNumber& n, const algebra::Real& r) {
  n.polynomial = r.polynomial;
  n.lower = r.lower;
  n.upper = r.upper;
  n.exact = r.exact;
}
}  // namespace

}  // namespace hipair::cspace

namespace hipair {

std::size_t& cspace::vertex_numbers_copied() {
  thread_local std::size_t copied = 0;
  return copied;
}

namespace {

// The numbers of public vertex `vertex` from raw vertex `source`.
void copy_vertex_numbers(CSpaceVertex& vertex, const cspace::raw::Vertex& source) {
  ++cspace::vertex_numbers_copied();
  cspace::assign_public(vertex.x, source.x);
  vertex.y_exact = source.y_exact;
  if (source.y_exact) cspace::assign_public(vertex.y, source.y);
  vertex.y_lower = source.y_lower;
  vertex.y_upper = source.y_upper;
  vertex.y_curve = source.y_curve.coefficients;
  vertex.y_branch = source.y_branch;
}

}  // namespace

// (the public vertices are the Impl's own, never const objects: a vertex is written once, under
// numbers.mutex, before any reader is told it is (numbers.written / numbers.all, release), and
// never rewritten, so a reader holding a written vertex never sees it change)
void CSpace::Impl::write_vertex_numbers() const {
  std::lock_guard<std::mutex> lock(numbers.mutex);
  if (numbers.all.load(std::memory_order_relaxed)) return;
  if (dimension == 2) {   // a 1-D space's vertices are written whole by the build
    auto& out = const_cast<std::vector<CSpaceVertex>&>(vertices);
    const std::atomic<unsigned char>* written = numbers.written.load(std::memory_order_relaxed);
    for (const cspace::ChartData& chart : charts) {
      const auto& raw = chart.arrangement.vertices;
      for (std::size_t v = 0; v < raw.size() && v < chart.vertex_global.size(); ++v) {
        const std::size_t g = chart.vertex_global[v];
        if (written && written[g].load(std::memory_order_relaxed)) continue;
        copy_vertex_numbers(out[g], raw[v]);
      }
    }
  }
  numbers.all.store(true, std::memory_order_release);
}

// (the public cells are the Impl's own, never const objects: every cell's sample is written
// once, under samples.mutex, before readers are told it is (samples.all, release), and never
// rewritten; sample_face writes only the faces' sample fields, which nothing reads but this and
// the build)
void CSpace::Impl::write_cell_samples() const {
  std::lock_guard<std::mutex> lock(samples.mutex);
  if (samples.all.load(std::memory_order_relaxed)) return;
  auto& out = const_cast<std::vector<CSpaceCell>&>(cells);
  std::vector<char> done(out.size(), 0);
  // a cell's first face in chart, then face order: the build's cells loop made the cell there
  for (std::size_t c = 0; c < charts.size(); ++c) {
    auto& chart = const_cast<cspace::ChartData&>(charts[c]);
    for (std::size_t f = 0; f < chart.faces.size(); ++f) {
      const std::size_t cell = chart.faces[f].cell;
      if (chart.faces[f].kind == cspace::FaceKind::outside || cell >= out.size() || done[cell]) continue;
      done[cell] = 1;
      cspace::sample_face(chart, f);
      out[cell].sample_x = chart.faces[f].sample_x;
      out[cell].sample_y = chart.faces[f].sample_y;
    }
  }
  samples.all.store(true, std::memory_order_release);
}

void CSpace::Impl::write_vertex_number(std::size_t index) const {
  std::lock_guard<std::mutex> lock(numbers.mutex);
  if (numbers.all.load(std::memory_order_relaxed)) return;
  if (dimension != 2) {   // written whole by the build
    numbers.all.store(true, std::memory_order_release);
    return;
  }
  std::atomic<unsigned char>* written = numbers.written.load(std::memory_order_relaxed);
  if (!written) {
    written = new std::atomic<unsigned char>[vertices.size()]();
    numbers.written.store(written, std::memory_order_release);
  }
  if (written[index].load(std::memory_order_relaxed)) return;
  // the raw vertex write_vertex_numbers copies to public vertex `index`, if any
  if (index < vertex_local.size()) {
    auto [c, v] = vertex_local[index];
    if (c < charts.size()) {
      const cspace::ChartData& chart = charts[c];
      if (v < chart.arrangement.vertices.size() && v < chart.vertex_global.size() && chart.vertex_global[v] == index)
        copy_vertex_numbers(const_cast<std::vector<CSpaceVertex>&>(vertices)[index], chart.arrangement.vertices[v]);
    }
  }
  written[index].store(1, std::memory_order_release);
}

}  // namespace hipair

namespace hipair::cspace {

AlgebraicNumber to_public(const algebra::Real& r) {
  AlgebraicNumber n;
  assign_public(n, r);
  return n;
}

CertifiedRange to_coordinate_range(const ChartAxis& axis, double lo, double hi) {
  if (axis.kind == ChartAxis::Kind::translation) return {lo, hi};
  // theta = c + 2 atan(t) is increasing; atan and the addition of c (pi rounded) are within a
  // few units in the last place: widen by 8 ulp-sized margins plus 4e-16 absolute.
  auto angle = [&](double t) { return (axis.half_turn ? std::numbers::pi : 0.0) + 2 * std::atan(t); };
  double a = angle(lo), b = angle(hi);
  double margin_a = 8 * std::numeric_limits<double>::epsilon() * std::fabs(a) + 4e-16;
  double margin_b = 8 * std::numeric_limits<double>::epsilon() * std::fabs(b) + 4e-16;
  return {a - margin_a, b + margin_b};
}

// ---------------------------------------------------------------- the build

CSpace build_cspace(PairInput input, const CSpaceBuildOptions& options) {
  auto total_start = Clock::now();
  auto impl = std::make_shared<CSpace::Impl>();
  impl->first_part = input.first_part;
  impl->second_part = input.second_part;
  impl->x_part = input.x_part;
  impl->y_part = input.y_part;
  impl->dimension = input.dimension;
  CSpaceStatistics& stats = impl->statistics;
  impl->complete = input.complete;
  impl->length_unit_exponent = input.length_unit_exponent;
  impl->model = input.model;
  impl->axes = input.axes;
  stats.region_cells = input.region_cells;
  stats.seconds_region = input.seconds_region;
  // the charts come whole (`charts`) or one at a time from `make_chart`, whose curves are then
  // generated, built into the chart's arrangement and released before the next chart's
  const bool streamed = static_cast<bool>(input.make_chart);
  const std::size_t chart_count = streamed ? input.chart_count : input.charts.size();
  double seconds_streamed = 0;   // time in make_chart (curve generation), counted as curves
  if (!input.complete) stats.region_tiles = chart_count;

  // feature pairs: one per contact curve of any chart, deduplicated by (first, second, type)
  // "vertex of loop L edge E" or "loop L edge E", written into one string (no temporaries)
  auto feature_name = [&](const FeatureRef& f) -> std::string {
    std::string name = f.kind == FeatureRef::Kind::vertex ? "vertex of loop " : "loop ";
    char digits[24];
    name.append(digits, std::to_chars(digits, digits + sizeof digits, f.loop).ptr);
    name += " edge ";
    name.append(digits, std::to_chars(digits, digits + sizeof digits, f.edge).ptr);
    return name;
  };
  auto part_name = [&](std::size_t part) {
    return part < input.part_names.size() ? input.part_names[part] : "part " + std::to_string(part);
  };
  // (first, second, type) -> index of the feature pair: an ordered index, so that matching a
  // kept curve to its pair is logarithmic rather than a scan over every pair met so far
  using Key = std::tuple<std::size_t, std::size_t, std::size_t, int, std::size_t, std::size_t, std::size_t, int, int>;
  auto key_of = [](const ContactCurve& curve) {
    return Key{curve.first.part,  curve.first.loop,  curve.first.edge,  static_cast<int>(curve.first.kind),
               curve.second.part, curve.second.loop, curve.second.edge, static_cast<int>(curve.second.kind),
               static_cast<int>(curve.type)};
  };
  std::map<Key, std::size_t> keys;
  std::vector<Key> pair_keys;   // per feature pair: its key (a twin chart's pairs are its source's mapped)
  // the counts a chart adds to the statistics (a twin chart adds its source's; its direct build's
  // may differ in the spurious pieces: other culling windows)
  struct ChartCounts {
    std::size_t curves = 0, circle_segment_charts = 0, quadratic_charts = 0, pieces_inserted = 0;
    std::size_t touching_edges = 0, touching_vertices = 0, touching_undecided = 0;
    CurveStatistics generated;
  };
  std::vector<ChartCounts> chart_counts(chart_count);
  auto twin_of = [&](std::size_t c) -> const TwinChart* {
    return input.dimension == 2 && input.model && input.complete && c < input.twins.size() &&
                   input.twins[c].source < c
               ? &input.twins[c]
               : nullptr;
  };
  // a feature read through a twin's half turn (features of other parts unchanged)
  auto twin_feature = [](const TwinChart& twin, FeatureRef f) {
    if (f.part == twin.part) {
      const HalfTurnImage to = twin.image.at(f.loop).at(f.edge);
      f.loop = to.loop;
      f.edge = to.edge;
    }
    return f;
  };
  // the curves' interval forms, for the next tiles of an operating region (prepare_chart; a
  // whole space's few charts share no curve)
  CurveIntervalMemo interval_memo;

  impl->charts.resize(chart_count);
  // Face classification runs once every chart's curves are known: whether it may propagate
  // across contact edges depends on the curve statistics of all charts. What it needs of a
  // chart's input (the kept curves' blocked sides, the oracle) is kept until then.
  struct Deferred {
    std::vector<int> signs;
    Classifier classify;
    AlgebraicClassifier classify_algebraic;
    OrdinateClassifier classify_ordinate;
    OverlapFilter certainly_overlapping;
  };
  std::vector<Deferred> deferred(chart_count);
  // progress (options.progress): the charts built, then (2-D) the charts classified, then the
  // cells, as work units; a chart's classification by its share of edges and vertices decided
  const std::size_t progress_units = (input.dimension == 2 ? 2 : 1) * chart_count + 1;
  std::size_t progress_done = 0;
  CSpaceBuildProgress report;
  report.first_part = input.first_part;
  report.second_part = input.second_part;
  report.charts = chart_count;
  report.tiles = !input.complete;
  auto progress_report = [&](CSpaceBuildProgress::Stage stage, double share) {
    report.stage = stage;
    report.fraction = stage == CSpaceBuildProgress::Stage::done
                          ? 1.0
                          : std::min(1.0, (static_cast<double>(progress_done) + share) / static_cast<double>(progress_units));
    options.progress(report);
  };
  for (std::size_t c = 0; c < chart_count; ++c) {
    if (options.progress) {
      report.chart = c + 1;
      progress_report(CSpaceBuildProgress::Stage::chart, 0);
    }
    if (const TwinChart* twin = twin_of(c)) {
      // the source chart's curves read through the half turn (TwinChart): its feature pairs
      // mapped, new ones registered as the direct build registers them; the arrangement, faces
      // and contacts are the source's, copied once the source is classified (below)
      ChartData& chart = impl->charts[c];
      const ChartData& source = impl->charts[twin->source];
      chart.x_index = twin->x_index;
      chart.y_index = twin->y_index;
      chart.x_axis = twin->x;
      chart.y_axis = twin->y;
      chart.box = source.box;
      chart.curve_global.reserve(source.curve_global.size());
      for (std::size_t g : source.curve_global) {
        const Key key = pair_keys[g];   // (a copy: pair_keys grows below)
        const FeatureRef first = twin_feature(*twin, FeatureRef{std::get<0>(key), std::get<1>(key), std::get<2>(key),
                                                                static_cast<FeatureRef::Kind>(std::get<3>(key))});
        const FeatureRef second = twin_feature(*twin, FeatureRef{std::get<4>(key), std::get<5>(key), std::get<6>(key),
                                                                 static_cast<FeatureRef::Kind>(std::get<7>(key))});
        const Key mapped{first.part,  first.loop,  first.edge,  static_cast<int>(first.kind),
                         second.part, second.loop, second.edge, static_cast<int>(second.kind), std::get<8>(key)};
        auto [found, inserted] = keys.try_emplace(mapped, impl->feature_pairs.size());
        if (inserted) {
          pair_keys.push_back(mapped);
          const FeaturePair& from = impl->feature_pairs[g];
          const auto type = static_cast<ContactType>(std::get<8>(key));
          FeaturePair pair;
          pair.first_part = from.first_part;
          pair.second_part = from.second_part;
          pair.first_feature = feature_name(first);
          pair.second_feature = feature_name(second);
          pair.kind = from.kind;
          pair.label = curve_label(*input.model, first, second, type);
          pair.first = FeatureIdentity{first.part, first.loop, first.edge, first.kind};
          pair.second = FeatureIdentity{second.part, second.loop, second.edge, second.kind};
          pair.blocked_sign = from.blocked_sign;
          impl->feature_pairs.push_back(std::move(pair));
        }
        chart.curve_global.push_back(found->second);
      }
      const ChartCounts& counts = chart_counts[twin->source];
      chart_counts[c] = counts;
      stats.curves += counts.curves;
      stats.circle_segment_charts += counts.circle_segment_charts;
      stats.quadratic_charts += counts.quadratic_charts;
      stats.pieces_inserted += counts.pieces_inserted;
      input.curve_statistics.feature_pairs_considered += counts.generated.feature_pairs_considered;
      input.curve_statistics.feature_pairs_culled += counts.generated.feature_pairs_culled;
      input.curve_statistics.curves += counts.generated.curves;
      input.curve_statistics.identically_zero += counts.generated.identically_zero;
      input.curve_statistics.reflex_vertices_skipped += counts.generated.reflex_vertices_skipped;
      input.curve_statistics.feature_pairs_in_blocked_space += counts.generated.feature_pairs_in_blocked_space;
      CSpaceChart public_chart = impl->public_charts[twin->source];
      public_chart.x_kind = chart.x_axis.kind;
      public_chart.y_kind = chart.y_axis.kind;
      public_chart.x_half_turn = chart.x_axis.half_turn;
      public_chart.y_half_turn = chart.y_axis.half_turn;
      impl->public_charts.push_back(std::move(public_chart));
      ++progress_done;
      continue;
    }
    const CurveStatistics generated_before = input.curve_statistics;
    const std::size_t curves_before = stats.curves, circle_segment_before = stats.circle_segment_charts,
                      quadratic_before = stats.quadratic_charts, pieces_before = stats.pieces_inserted;
    ChartInput streamed_input;
    if (streamed) {
      auto start = Clock::now();
      streamed_input = input.make_chart(c, input);
      seconds_streamed += seconds_since(start);
    }
    ChartInput& chart_input = streamed ? streamed_input : input.charts[c];
    ChartData& chart = impl->charts[c];
    chart.x_index = chart_input.x_index;
    chart.y_index = chart_input.y_index;
    // Two rotating parts: a curve with coefficients beyond max_rotation_curve_bits is refused
    // before the chart's culling and arrangement, naming its features (src/cspace/curve_cost.hpp:
    // their cost grows with the coefficients' bits squared; hostile74 H1 ran for minutes).
    if (input.dimension == 2 && chart_input.x.kind == AxisKind::rotation && chart_input.y.kind == AxisKind::rotation)
      for (const ContactCurve& curve : chart_input.curves)
        if (const std::size_t bits = primitive_coefficient_bits(curve.polynomial); bits > max_rotation_curve_bits)
          throw GeometryError(too_fine_message(curve, bits, input.model.get(), part_name));
    auto culling_start = Clock::now();
    std::vector<std::size_t> kept =
        prepare_chart(chart, chart_input, input.dimension, options.polygon_front_end, input.complete ? 0 : 3,
                      input.complete ? nullptr : &interval_memo);
    // the culling's blocked test is done with: release what it keeps (posed disks per interval)
    chart_input.blocked_cells.reset();
    stats.seconds_culling += seconds_since(culling_start);
    stats.curves += kept.size();
    // (the chart's list reserved to its size; the space's lists grown at most once here to hold
    // what the kept curves can add, geometrically, so that an operating region's many tiles
    // still move them a logarithmic number of times)
    chart.curve_global.reserve(chart.curve_global.size() + kept.size());
    auto room_for = [](auto& list, std::size_t extra) {
      if (list.size() + extra > list.capacity()) list.reserve(std::max(list.size() + extra, 2 * list.capacity()));
    };
    room_for(pair_keys, kept.size());
    room_for(impl->feature_pairs, kept.size());
    for (std::size_t k : kept) {
      ContactCurve& curve = chart_input.curves[k];
      auto [found, inserted] = keys.try_emplace(key_of(curve), impl->feature_pairs.size());
      const std::size_t index = found->second;
      if (inserted) {
        pair_keys.push_back(found->first);
        FeaturePair pair;
        pair.first_part = part_name(curve.first.part);
        pair.second_part = part_name(curve.second.part);
        pair.first_feature = feature_name(curve.first);
        pair.second_feature = feature_name(curve.second);
        pair.kind = public_kind(curve.type);
        pair.label = std::move(curve.label);   // (read here only: the input curves are freed below)
        auto identity = [](const FeatureRef& f) {
          return FeatureIdentity{f.part, f.loop, f.edge, f.kind};
        };
        pair.first = identity(curve.first);
        pair.second = identity(curve.second);
        pair.blocked_sign = curve.blocked_sign;
        impl->feature_pairs.push_back(std::move(pair));
      }
      chart.curve_global.push_back(index);
    }
    CSpaceChart public_chart;
    public_chart.x_kind = chart.x_axis.kind;
    public_chart.y_kind = chart.y_axis.kind;
    public_chart.x_half_turn = chart.x_axis.half_turn;
    public_chart.y_half_turn = chart.y_axis.half_turn;
    public_chart.x_lo = chart.box.x_lo;
    public_chart.x_hi = chart.box.x_hi;
    public_chart.y_lo = input.dimension == 2 ? chart.box.y_lo : Rational(0);
    public_chart.y_hi = input.dimension == 2 ? chart.box.y_hi : Rational(0);
    impl->public_charts.push_back(std::move(public_chart));

    if (input.dimension == 1) {
      auto start = Clock::now();
      build_interval_chart(chart, chart_input, stats);
      stats.seconds_classification += seconds_since(start);
      ++progress_done;
      continue;
    }
    raw::Options raw_options;
    raw_options.aggregated_insertion = options.aggregated_insertion;
    raw_options.keep_cgal = options.keep_arrangements;
    raw_options.carry_line_supports = options.polygon_front_end;
    raw_options.quadratic_max_coefficient_bits = options.quadratic_max_coefficient_bits;
    raw_options.cells = &chart.cells;
    // lines and circles (translating pairs): the circle–segment traits; else the algebraic ones
    const bool circle_segment = raw::circle_segment_applies(chart.polynomials, chart.validity);
    // curves of degree <= 2 in y: the filtered quadratic traits (nullopt: outside its class)
    std::optional<raw::Arrangement> quadratic;
    if (!circle_segment && options.quadratic_traits)
      quadratic = raw::build_quadratic_arrangement(chart.box, chart.polynomials, chart.validity, chart.windows,
                                                   raw_options);
    chart.arrangement =
        circle_segment ? raw::build_circle_segment_arrangement(chart.box, chart.polynomials, chart.validity,
                                                               chart.windows, raw_options)
        : quadratic    ? std::move(*quadratic)
                       : raw::build_arrangement(chart.box, chart.polynomials, chart.validity, chart.windows, raw_options);
    stats.circle_segment_charts += circle_segment ? 1 : 0;
    stats.quadratic_charts += quadratic ? 1 : 0;
    stats.seconds_clipping += chart.arrangement.times.curves_seconds;
    stats.seconds_arrangement += chart.arrangement.times.insertion_seconds;
    stats.seconds_export += chart.arrangement.times.export_seconds;
    stats.pieces_inserted += chart.arrangement.pieces_inserted;
    auto start = Clock::now();
    label_edges(chart, circle_segment);
    stats.seconds_labelling += seconds_since(start);
    // kernel curves carry their blocked side; synthetic input (no model) is classified by the oracle only
    if (input.model)
      for (std::size_t k : kept) deferred[c].signs.push_back(chart_input.curves[k].blocked_sign);
    deferred[c].classify = std::move(chart_input.classify);
    deferred[c].classify_algebraic = std::move(chart_input.classify_algebraic);
    deferred[c].classify_ordinate = std::move(chart_input.classify_ordinate);
    deferred[c].certainly_overlapping = std::move(chart_input.certainly_overlapping);
    // the chart's input curves are done with (its arrangement, polynomials and labels are
    // kept): free them now rather than at the end, so a region's peak holds one copy
    std::vector<ContactCurve>().swap(chart_input.curves);
    ChartCounts& counts = chart_counts[c];
    counts.curves = stats.curves - curves_before;
    counts.circle_segment_charts = stats.circle_segment_charts - circle_segment_before;
    counts.quadratic_charts = stats.quadratic_charts - quadratic_before;
    counts.pieces_inserted = stats.pieces_inserted - pieces_before;
    const CurveStatistics& now = input.curve_statistics;
    counts.generated.feature_pairs_considered = now.feature_pairs_considered - generated_before.feature_pairs_considered;
    counts.generated.feature_pairs_culled = now.feature_pairs_culled - generated_before.feature_pairs_culled;
    counts.generated.curves = now.curves - generated_before.curves;
    counts.generated.identically_zero = now.identically_zero - generated_before.identically_zero;
    counts.generated.reflex_vertices_skipped = now.reflex_vertices_skipped - generated_before.reflex_vertices_skipped;
    counts.generated.feature_pairs_in_blocked_space =
        now.feature_pairs_in_blocked_space - generated_before.feature_pairs_in_blocked_space;
    ++progress_done;
  }
  stats.charts = impl->charts.size();
  stats.feature_pairs_considered = input.curve_statistics.feature_pairs_considered;
  stats.feature_pairs_culled = input.curve_statistics.feature_pairs_culled;
  stats.seconds_curves = input.seconds_curves;
  if (input.dimension == 2) {
    auto start = Clock::now();
    // Progress while classifying (hunt38): the exact classification can take minutes where the
    // pair mixes very different scales (a 1e-30 mm square against a 1e400 mm one: signs of
    // polynomials with coefficients of thousands of bits at algebraic points), and nothing was
    // shown after the last chart's curves. The widest coefficient goes with the reports (the
    // terminal's line names it as the reason over 300 bits; the examples stay under 200).
    for (std::size_t c = 0; c < chart_count; ++c) {
      ChartData& chart = impl->charts[c];
      if (const TwinChart* twin = twin_of(c)) {
        // the source chart as classified, with this chart's axes and feature pairs (TwinChart)
        ChartData mapped = impl->charts[twin->source];
        mapped.x_index = chart.x_index;
        mapped.y_index = chart.y_index;
        mapped.x_axis = std::move(chart.x_axis);
        mapped.y_axis = std::move(chart.y_axis);
        mapped.curve_global = std::move(chart.curve_global);
        chart = std::move(mapped);
        ChartCounts& counts = chart_counts[c];   // (the build stage copied the source's, before its classification)
        const ChartCounts& source_counts = chart_counts[twin->source];
        counts.touching_edges = source_counts.touching_edges;
        counts.touching_vertices = source_counts.touching_vertices;
        counts.touching_undecided = source_counts.touching_undecided;
        stats.touching_edges += counts.touching_edges;
        stats.touching_vertices += counts.touching_vertices;
        stats.touching_undecided += counts.touching_undecided;
        ++progress_done;
        continue;
      }
      const std::size_t touching_edges_before = stats.touching_edges, touching_vertices_before = stats.touching_vertices,
                        touching_undecided_before = stats.touching_undecided;
      std::function<void(std::size_t, std::size_t)> tick;
      if (options.progress) {
        std::size_t bits = 0;
        for (const IntegerPolynomial2& f : chart.polynomials)
          for (const auto& row : f.coefficients)
            for (const mpz_class& a : row) bits = std::max(bits, mpz_sizeinbase(a.get_mpz_t(), 2));
        report.chart = c + 1;
        report.coefficient_bits = bits;
        tick = [&](std::size_t done, std::size_t total) {
          report.done = done;
          report.total = total;
          progress_report(CSpaceBuildProgress::Stage::classification,
                          static_cast<double>(done) / static_cast<double>(std::max<std::size_t>(total, 1)));
        };
      }
      std::optional<ContactSides> sides;
      if (input.model) sides.emplace(chart, std::move(deferred[c].signs));
      // propagation needs the kernels' curves (every touching configuration on a valid curve)
      const bool propagate = sides && input.curve_statistics.identically_zero == 0;
      classify_faces(chart, deferred[c].classify, sides ? &*sides : nullptr, options.check_face_classification,
                     propagate);
      find_touching(chart, deferred[c].classify, deferred[c].classify_algebraic, deferred[c].classify_ordinate,
                    deferred[c].certainly_overlapping, sides ? &*sides : nullptr, options.check_face_classification, stats, tick);
      deferred[c] = Deferred{};
      chart_counts[c].touching_edges = stats.touching_edges - touching_edges_before;
      chart_counts[c].touching_vertices = stats.touching_vertices - touching_vertices_before;
      chart_counts[c].touching_undecided = stats.touching_undecided - touching_undecided_before;
      ++progress_done;
    }
    stats.seconds_classification += seconds_since(start);
  }

  auto cells_start = Clock::now();
  // global face numbering
  std::vector<std::size_t> face_offset(impl->charts.size() + 1, 0);
  for (std::size_t c = 0; c < impl->charts.size(); ++c)
    face_offset[c + 1] = face_offset[c] + impl->charts[c].faces.size();
  Components components(face_offset.back());
  auto kind_at = [&](std::size_t c, std::size_t f) { return impl->charts[c].faces[f].kind; };

  // seams: (chart a, local edge a) real across the seam?
  std::vector<std::vector<int>> seam_state(impl->charts.size());   // per local edge: 0 none, 1 seam, 2 real seam
  std::vector<std::pair<std::size_t, std::size_t>> real_face_pairs;
  for (std::size_t c = 0; c < impl->charts.size(); ++c)
    seam_state[c].assign(input.dimension == 2 ? impl->charts[c].arrangement.edges.size() : 0, 0);

  if (input.dimension == 2) {
    for (std::size_t c = 0; c < impl->charts.size(); ++c) {
      ChartData& chart = impl->charts[c];
      for (std::size_t e = 0; e < chart.arrangement.edges.size(); ++e) {
        const raw::Edge& edge = chart.arrangement.edges[e];
        if (edge.box_side >= 0) continue;
        const raw::Face& left = chart.arrangement.faces[edge.left_face];
        const raw::Face& right = chart.arrangement.faces[edge.right_face];
        if (left.unbounded || right.unbounded) continue;
        FaceKind a = kind_at(c, edge.left_face), b = kind_at(c, edge.right_face);
        if (a == b && !chart.edges[e].touching)
          components.join(face_offset[c] + edge.left_face, face_offset[c] + edge.right_face, {0, 0});
        else
          real_face_pairs.emplace_back(face_offset[c] + edge.left_face, face_offset[c] + edge.right_face);
      }
    }
    // glue along seams: a's high side meets b's low side
    for (std::size_t a = 0; a < impl->charts.size(); ++a)
      for (std::size_t b = 0; b < impl->charts.size(); ++b) {
        const ChartData& A = impl->charts[a];
        const ChartData& B = impl->charts[b];
        for (int axis = 0; axis < 2; ++axis) {
          bool x_axis = axis == 0;
          // the other axis must be the same chart axis
          if (x_axis ? (A.y_index != B.y_index) : (A.x_index != B.x_index)) continue;
          const ChartAxis& axis_a = x_axis ? A.x_axis : A.y_axis;
          const ChartAxis& axis_b = x_axis ? B.x_axis : B.y_axis;
          const Rational& high = x_axis ? A.box.x_hi : A.box.y_hi;
          const Rational& low = x_axis ? B.box.x_lo : B.box.y_lo;
          if (!same_coordinate(axis_a, high, axis_b, low)) continue;
          std::array<long, 2> winding{0, 0};
          winding[static_cast<std::size_t>(axis)] = winding_between(axis_a, high, axis_b, low);
          auto pieces_a = seam_pieces(A, x_axis ? 1 : 2);
          auto pieces_b = seam_pieces(B, x_axis ? 3 : 0);
          std::size_t i = 0, j = 0;
          while (i < pieces_a.size() && j < pieces_b.size()) {
            const SeamPiece& p = pieces_a[i];
            const SeamPiece& q = pieces_b[j];
            if (algebra::compare(p.start, q.end) < 0 && algebra::compare(q.start, p.end) < 0) {
              FaceKind ka = kind_at(a, p.face), kb = kind_at(b, q.face);
              int state = ka == kb ? 1 : 2;
              seam_state[a][p.edge] = std::max(seam_state[a][p.edge], state);
              seam_state[b][q.edge] = std::max(seam_state[b][q.edge], state);
              if (ka == kb)
                components.join(face_offset[a] + p.face, face_offset[b] + q.face, winding);
              else
                real_face_pairs.emplace_back(face_offset[a] + p.face, face_offset[b] + q.face);
            }
            if (algebra::compare(p.end, q.end) < 0)
              ++i;
            else
              ++j;
          }
        }
      }
  } else {
    for (std::size_t c = 0; c < impl->charts.size(); ++c) {
      ChartData& chart = impl->charts[c];
      for (std::size_t i = 0; i < chart.points.size(); ++i) {
        FaceKind a = chart.faces[i].kind, b = chart.faces[i + 1].kind;
        if (a == FaceKind::outside || b == FaceKind::outside) continue;
        if (a == b && !(i < chart.touching_vertex.size() && chart.touching_vertex[i]))
          components.join(face_offset[c] + i, face_offset[c] + i + 1, {0, 0});
        else
          real_face_pairs.emplace_back(face_offset[c] + i, face_offset[c] + i + 1);
      }
    }
    // seams of a circle: a chart's high end meets another's low end
    for (std::size_t a = 0; a < impl->charts.size(); ++a)
      for (std::size_t b = 0; b < impl->charts.size(); ++b) {
        ChartData& A = impl->charts[a];
        ChartData& B = impl->charts[b];
        if (!same_coordinate(A.x_axis, A.box.x_hi, B.x_axis, B.box.x_lo)) continue;
        std::size_t fa = A.faces.size() - 1, fb = 0;
        long winding = winding_between(A.x_axis, A.box.x_hi, B.x_axis, B.box.x_lo);
        // A contact point exactly on the seam (A's last point at its x_hi, or B's first at its
        // x_lo: the face beyond it empty) separates the two ends, except between two blocked
        // faces (session 29): there it is decided as inside a chart — the parts overlapping at
        // the (rational) seam point: one blocked cell across it; only touching: a touching
        // vertex, a separate blocked cell on each side; not decided: counted undecided.
        const bool a_point = A.faces[fa].kind == FaceKind::outside && fa >= 1;
        const bool b_point = B.faces[fb].kind == FaceKind::outside && B.faces.size() >= 2;
        if (a_point || b_point) {
          const std::size_t ia = A.points.size() - 1;   // (valid when a_point)
          if (a_point) --fa;
          if (b_point) ++fb;
          auto relation = [](const ChartData& chart, std::size_t i) {
            return i < chart.seam_relation.size() ? chart.seam_relation[i] : static_cast<signed char>(-1);
          };
          const signed char ra = a_point ? relation(A, ia) : -1, rb = b_point ? relation(B, 0) : -1;
          if (A.faces[fa].kind == FaceKind::free && B.faces[fb].kind == FaceKind::free) {
            // a contact point on the seam between free intervals (session 30): one free cell
            // across it, as inside a chart; where the parts touch there, a grazing contact
            components.join(face_offset[a] + fa, face_offset[b] + fb, {winding, 0});
            if (a_point && ra == 1) A.grazing_point[ia] = 1;
            if (b_point && rb == 1) B.grazing_point[0] = 1;
            continue;
          }
          if (A.faces[fa].kind != FaceKind::blocked || B.faces[fb].kind != FaceKind::blocked) continue;
          if (ra == 1 || rb == 1) {
            if (a_point && ia < A.touching_vertex.size() && !A.touching_vertex[ia]) {
              A.touching_vertex[ia] = 1;
              ++stats.touching_vertices;
            }
            if (b_point && !B.touching_vertex.empty() && !B.touching_vertex[0]) {
              B.touching_vertex[0] = 1;
              ++stats.touching_vertices;
            }
            real_face_pairs.emplace_back(face_offset[a] + fa, face_offset[b] + fb);
          } else if (ra == 0 || rb == 0) {
            components.join(face_offset[a] + fa, face_offset[b] + fb, {winding, 0});
          } else {
            ++stats.touching_undecided;
          }
          continue;
        }
        if (A.faces[fa].kind == B.faces[fb].kind)
          components.join(face_offset[a] + fa, face_offset[b] + fb, {winding, 0});
        else
          real_face_pairs.emplace_back(face_offset[a] + fa, face_offset[b] + fb);
      }
  }

  // cells
  std::vector<std::size_t> cell_of_root(face_offset.back(), no_index);
  for (std::size_t c = 0; c < impl->charts.size(); ++c) {
    ChartData& chart = impl->charts[c];
    for (std::size_t f = 0; f < chart.faces.size(); ++f) {
      FaceData& face = chart.faces[f];
      if (face.kind == FaceKind::outside) continue;
      auto [root, offset] = components.find(face_offset[c] + f);
      if (cell_of_root[root] == no_index) {
        cell_of_root[root] = impl->cells.size();
        CSpaceCell cell;
        cell.kind = cell_kind(face.kind);
        auto wraps = components.wraps(root);
        cell.wraps_x = wraps[0];
        cell.wraps_y = wraps[1];
        // (its sample: face f's, taken when the cells are first read: CSpace::Impl::write_cell_samples)
        cell.sample_chart = c;
        impl->cells.push_back(std::move(cell));
      }
      face.cell = cell_of_root[root];
      impl->cells[face.cell].faces += 1;
    }
  }
  auto cell_of_global_face = [&](std::size_t g) {
    std::size_t c = static_cast<std::size_t>(std::upper_bound(face_offset.begin(), face_offset.end(), g) - face_offset.begin()) - 1;
    return impl->charts[c].faces[g - face_offset[c]].cell;
  };
  std::set<std::pair<std::size_t, std::size_t>> neighbour_pairs;
  for (auto [fa, fb] : real_face_pairs) {
    std::size_t ca = cell_of_global_face(fa), cb = cell_of_global_face(fb);
    if (ca != cb) neighbour_pairs.insert({std::min(ca, cb), std::max(ca, cb)});
  }
  for (auto [ca, cb] : neighbour_pairs) {
    impl->cells[ca].neighbours.push_back(cb);
    impl->cells[cb].neighbours.push_back(ca);
  }

  // public vertices and edges, the vertices built where they stay (a CSpaceVertex moved to a
  // grown vector leaves fresh rationals behind: reserved for all charts at once)
  {
    std::size_t vertex_count = impl->vertices.size();
    std::size_t edge_count = impl->edges.size();
    for (const ChartData& chart : impl->charts) {
      vertex_count += input.dimension == 1 ? chart.points.size() : chart.arrangement.vertices.size();
      if (input.dimension == 2) edge_count += chart.arrangement.edges.size();
    }
    impl->vertices.reserve(vertex_count);
    // (the global lists too, once: reserved per chart, each chart's growth moved every earlier
    // chart's edges again — quadratic in the tiles of an operating region)
    impl->vertex_local.reserve(impl->vertex_local.size() + (vertex_count - impl->vertices.size()));
    impl->edge_local.reserve(edge_count);
    impl->edges.reserve(edge_count);
  }
  for (std::size_t c = 0; c < impl->charts.size(); ++c) {
    ChartData& chart = impl->charts[c];
    if (input.dimension == 1) {
      for (std::size_t i = 0; i < chart.points.size(); ++i) {
        chart.vertex_global.push_back(impl->vertices.size());
        impl->vertex_local.emplace_back(c, i);
        CSpaceVertex& vertex = impl->vertices.emplace_back();
        vertex.chart = c;
        assign_public(vertex.x, chart.points[i]);
        assign_public(vertex.y, Real::from_rational(0));
        vertex.y_exact = true;
        for (std::size_t k : chart.point_curves[i]) vertex.curves.push_back(chart.curve_global[k]);
        std::sort(vertex.curves.begin(), vertex.curves.end());
        vertex.curves.erase(std::unique(vertex.curves.begin(), vertex.curves.end()), vertex.curves.end());
        vertex.contact_change = vertex.curves.size() >= 2;
        vertex.touching = i < chart.touching_vertex.size() && chart.touching_vertex[i] != 0;
        vertex.on_chart_boundary = chart.points[i].compare(chart.box.x_lo) == 0 || chart.points[i].compare(chart.box.x_hi) == 0;
      }
      continue;
    }
    const auto& arrangement = chart.arrangement;
    // (the per-chart lists and each vertex's edges reserved to the size they get: no regrowth)
    chart.vertex_global.reserve(chart.vertex_global.size() + arrangement.vertices.size());
    for (std::size_t v = 0; v < arrangement.vertices.size(); ++v) {
      chart.vertex_global.push_back(impl->vertices.size() + v);
      impl->vertex_local.emplace_back(c, v);
    }
    std::size_t vertex_base = impl->vertices.size();
    // each vertex's feature pairs reserved to the most its edges give it (no regrowth)
    thread_local std::vector<std::size_t> curve_room;
    curve_room.assign(arrangement.vertices.size(), 0);
    for (std::size_t e = 0; e < arrangement.edges.size(); ++e) {
      curve_room[arrangement.edges[e].min_vertex] += chart.edges[e].curves.size();
      curve_room[arrangement.edges[e].max_vertex] += chart.edges[e].curves.size();
    }
    impl->vertices.resize(vertex_base + arrangement.vertices.size());
    for (std::size_t v = 0; v < arrangement.vertices.size(); ++v) {
      CSpaceVertex& vertex = impl->vertices[vertex_base + v];
      vertex.chart = c;
      const raw::Vertex& source = arrangement.vertices[v];
      vertex.edges.reserve(source.around.size());
      vertex.curves.reserve(curve_room[v]);
      // (its numbers: CSpace::Impl::write_vertex_numbers / write_vertex_number, when the public vertices are first read)
      vertex.touching = chart.touching_vertex[v] != 0;
    }
    for (std::size_t e = 0; e < arrangement.edges.size(); ++e) {
      const raw::Edge& edge = arrangement.edges[e];
      EdgeData& data = chart.edges[e];
      data.global = impl->edges.size();
      impl->edge_local.emplace_back(c, e);
      CSpaceEdge out;
      out.chart = c;
      out.source = chart.vertex_global[edge.min_vertex];
      out.target = chart.vertex_global[edge.max_vertex];
      out.vertical = edge.vertical;
      out.curves.reserve(data.curves.size());
      for (std::size_t k : data.curves) out.curves.push_back(chart.curve_global[k]);
      std::sort(out.curves.begin(), out.curves.end());
      out.curves.erase(std::unique(out.curves.begin(), out.curves.end()), out.curves.end());
      const raw::Face& left = arrangement.faces[edge.left_face];
      const raw::Face& right = arrangement.faces[edge.right_face];
      out.left_cell = left.unbounded ? no_index : chart.faces[edge.left_face].cell;
      out.right_cell = right.unbounded ? no_index : chart.faces[edge.right_face].cell;
      if (edge.box_side >= 0) {
        int state = seam_state[c][e];
        out.role = state == 0 ? EdgeRole::limit : EdgeRole::seam;
        out.real = state == 2;
      } else {
        bool real = chart.faces[edge.left_face].kind != chart.faces[edge.right_face].kind;
        out.role = real ? EdgeRole::contact : data.touching ? EdgeRole::touching : EdgeRole::spurious;
        out.real = real || data.touching;
      }
      out.x_chart = {edge.box[0], edge.box[2]};
      out.y_chart = {edge.box[1], edge.box[3]};
      out.x_coordinate = to_coordinate_range(chart.x_axis, edge.box[0], edge.box[2]);
      out.y_coordinate = to_coordinate_range(chart.y_axis, edge.box[1], edge.box[3]);
      for (std::size_t v : {out.source, out.target}) {
        impl->vertices[v].edges.push_back(data.global);
        for (std::size_t k : out.curves) impl->vertices[v].curves.push_back(k);
        if (edge.box_side >= 0) impl->vertices[v].on_chart_boundary = true;
      }
      if (out.real) {
        for (std::size_t cell : {out.left_cell, out.right_cell})
          if (cell != no_index) impl->cells[cell].boundary.push_back(data.global);
      }
      if (out.role == EdgeRole::contact) ++stats.contact_edges;
      impl->edges.push_back(std::move(out));
    }
    for (std::size_t v = 0; v < arrangement.vertices.size(); ++v) {
      CSpaceVertex& vertex = impl->vertices[vertex_base + v];
      std::sort(vertex.curves.begin(), vertex.curves.end());
      vertex.curves.erase(std::unique(vertex.curves.begin(), vertex.curves.end()), vertex.curves.end());
      vertex.contact_change = vertex.curves.size() >= 2;
    }
    stats.faces += arrangement.faces.size() - 1;
  }
  stats.vertices = impl->vertices.size();
  stats.edges = impl->edges.size();
  stats.cells = impl->cells.size();
  stats.seconds_cells = seconds_since(cells_start);
  // point location's vertex bounds (locate_prefilter.hpp): certified doubles of each vertex's
  // algebraic coordinates, from its rational bounds as they are now (any later isolating
  // interval holds the same number)
  if (input.dimension == 2)
    for (ChartData& chart : impl->charts) {
      chart.vertex_bounds.clear();
      chart.vertex_bounds.reserve(chart.arrangement.vertices.size());
      for (const raw::Vertex& v : chart.arrangement.vertices)   // (double_bounds: lower_double, upper_double)
        chart.vertex_bounds.push_back(
            {raw::double_bounds(v.x.lower).first, raw::double_bounds(v.x.upper).second, raw::double_bounds(v.y_upper).second});
    }
  stats.seconds_total = seconds_since(total_start) - seconds_streamed + stats.seconds_curves + stats.seconds_region;
  if (std::getenv("HIPAIR_CSPACE_DEBUG"))
    std::fprintf(stderr, "  curve interval forms: %zu asked, %zu made\n", interval_memo.asked_, interval_memo.made_);
  if (options.progress) progress_report(CSpaceBuildProgress::Stage::done, 0);
  return make_cspace(impl);
}

}  // namespace hipair::cspace
