// A certified path through the free space of a 3-DOF pair (SlicedSpace::path), on the public
// queries only: the cell graph (free cells of the intervals, connections across critical
// angles with their witnesses) gives the sequence of cells; inside one interval the path
// alternates moves in a slice (a lazy roadmap on a grid over the slice cell's extent) and
// rotations at a fixed offset (a staircase, halving the angle step where a rotation is
// blocked); across a critical angle it rotates at the connection's witness offset. Every
// straight motion is certified free by the exact first-contact query before it is taken; the
// planner's own choices (grid points, distances) use doubles and decide nothing.
#include <hipair/error.hpp>
#include <hipair/sliced.hpp>

#include "algebra/exact_real.hpp"
#include "sliced/critical_angles.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <optional>
#include <queue>

namespace hipair {
namespace {

namespace algebra = cspace::algebra;
using sliced::real_of;

// The exponent e of a power of two 2^e (SlicedSpace::length_unit).
long exponent_of(const Rational& power) {
  return static_cast<long>(mpz_sizeinbase(power.get_num_mpz_t(), 2)) - static_cast<long>(mpz_sizeinbase(power.get_den_mpz_t(), 2));
}

// A rational near v, a multiple of 2^(unit_exponent - bits) (the pair's length unit 2^e over
// 2^bits: 2^-bits mm for ordinary pairs): a waypoint proposal, decided on exactly later. The
// double is scaled by ldexp (exact), so a pair at 10^-300 or 10^300 mm gets its own grid.
Rational dyadic(double v, long unit_exponent, int bits = 10) {
  const long shift = bits - unit_exponent;   // v 2^shift rounded, times 2^-shift
  mpz_class n(std::nearbyint(std::ldexp(v, static_cast<int>(shift))));
  mpz_class one = 1;
  Rational r = shift >= 0 ? Rational(n, one << static_cast<unsigned long>(shift)) : Rational(n * (one << static_cast<unsigned long>(-shift)));
  r.canonicalize();
  return r;
}

bool same_angle(const SlicedAngle& a, const SlicedAngle& b) {
  return a.half_turn == b.half_turn && (a.half_turn || a.t == b.t);
}

// Chart coordinate of an angle (flip: centred at the half turn); nullopt outside the chart.
std::optional<Rational> w_of(const SlicedAngle& a, bool flip) {
  if (!flip) {
    if (a.half_turn) return std::nullopt;
    return a.t;
  }
  if (a.half_turn) return Rational(0);
  if (sgn(a.t) == 0) return std::nullopt;
  return Rational(-1 / a.t);
}
SlicedAngle angle_of(const Rational& w, bool flip) {
  if (!flip) return SlicedAngle{w, false};
  if (sgn(w) == 0) return SlicedAngle{Rational(0), true};
  return SlicedAngle{Rational(-1 / w), false};
}

class Planner {
 public:
  Planner(const SlicedSpace& space, SlicedPath& out)
      : space_(space), out_(out), unit_(space.length_unit()), unit_exponent_(exponent_of(unit_)) {}

  bool motion(const SlicedConfiguration& a, const SlicedConfiguration& b, bool flip) {
    ++out_.motions_checked;
    try {
      return space_.motion_free(SlicedMotion{a, b, flip, {}});
    } catch (const GeometryError&) {
      return false;
    }
  }
  void append(const SlicedConfiguration& q, bool flip) {
    const auto& last = out_.waypoints.back();
    if (last.x == q.x && last.y == q.y && same_angle(last.angle, q.angle)) return;
    out_.waypoints.push_back(q);
    out_.through_half_turn.push_back(flip);
  }

  // A configuration next to q off any critical angle (rotating at q's offset), appended.
  std::optional<SlicedConfiguration> off_critical(const SlicedConfiguration& q, bool append_it) {
    if (space_.locate(q).interval != no_index) return q;
    for (int k = 12; k <= 60; k += 6) {
      Rational step = Rational(1) / Rational(mpz_class(1) << k);
      for (int sign : {1, -1}) {
        bool flip = q.angle.half_turn;
        Rational w = flip ? Rational(sign * step) : Rational(q.angle.t + sign * step);
        SlicedConfiguration r{q.x, q.y, angle_of(w, flip)};
        if (space_.locate(r).interval == no_index) continue;
        if (!motion(q, r, flip)) continue;
        if (append_it) append(r, flip);
        return r;
      }
    }
    return std::nullopt;
  }

  // Is the angle range [w0, w1] of the chart free of critical angles?
  bool range_clear(const Rational& w0, const Rational& w1, bool flip) const {
    Rational lo = std::min(w0, w1), hi = std::max(w0, w1);
    for (const auto& c : space_.critical_angles()) {
      if (c.half_turn) {
        if (flip && sgn(lo) <= 0 && sgn(hi) >= 0) return false;
        continue;
      }
      algebra::Real t = real_of(c.t);
      if (!flip) {
        if (t.compare(lo) >= 0 && t.compare(hi) <= 0) return false;
        continue;
      }
      int st = t.compare(0);
      if (st == 0) continue;   // theta = 0 lies outside the chart
      bool inside;
      if (st > 0)   // v = -1/t < 0
        inside = sgn(lo) < 0 && t.compare(-1 / lo) >= 0 && (sgn(hi) >= 0 || t.compare(-1 / hi) <= 0);
      else          // v > 0
        inside = sgn(hi) > 0 && t.compare(-1 / hi) <= 0 && (sgn(lo) <= 0 || t.compare(-1 / lo) >= 0);
      if (inside) return false;
    }
    return true;
  }

  // Samples of the free cell `cell` of `interval` in the slice at `angle`: the slice cells'
  // samples, and for a pair drawn at an extreme scale (length unit != 1 mm) also, over each such
  // cell's extent (its boundary edges' certified ranges), the simplest rationals in the pair's
  // unit and the inner points of a 4 x 4 grid (dyadics at the pair's unit), those located in
  // the cell (exactly): the slice's samples are the simplest rationals of their cells in mm,
  // which at 10^30 mm lie within 1 mm of a side and at 10^-30 mm within 10^-60 mm of one (a
  // rotation there meets the side). Ordinary pairs keep the slice's samples only.
  std::vector<Point> cell_samples(const SlicedAngle& angle, std::size_t interval, std::size_t cell) {
    std::vector<Point> out;
    auto slice = space_.slice(angle);
    for (const auto& c : slice->cells()) {
      if (c.kind != CellKind::free) continue;
      SlicedLocation l = space_.locate(SlicedConfiguration{c.sample_x, c.sample_y, angle});
      if (l.interval != interval || l.cell != cell) continue;
      out.push_back(Point{c.sample_x, c.sample_y});
      if (unit_ == 1) continue;
      double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
      for (std::size_t e : c.boundary) {
        const auto& edge = slice->edges()[e];
        x0 = std::min(x0, edge.x_chart.lower);
        x1 = std::max(x1, edge.x_chart.upper);
        y0 = std::min(y0, edge.y_chart.lower);
        y1 = std::max(y1, edge.y_chart.upper);
      }
      if (!(x0 < x1 && y0 < y1)) continue;
      // the simplest rationals of the extent (and of its middle half) in the pair's unit: what
      // the slice's samples are at scale 1, a point well inside a cell of ordinary size
      auto simplest = [&](double lo, double hi) {
        Rational l = dyadic(lo, unit_exponent_, 20) / unit_, h = dyadic(hi, unit_exponent_, 20) / unit_;
        if (!(l < h)) return Rational(dyadic((lo + hi) / 2, unit_exponent_));
        return Rational(algebra::simplest_between(l, h) * unit_);
      };
      for (int shrink : {0, 1}) {
        const double dx = (x1 - x0) * shrink / 4, dy = (y1 - y0) * shrink / 4;
        Point p{simplest(x0 + dx, x1 - dx), simplest(y0 + dy, y1 - dy)};
        SlicedLocation m = space_.locate(SlicedConfiguration{p.x, p.y, angle});
        if (m.kind == SlicedLocation::Kind::free && m.interval == interval && m.cell == cell) out.push_back(p);
      }
      for (int i = 1; i < 4; ++i)
        for (int j = 1; j < 4; ++j) {
          Point p{dyadic(x0 + (x1 - x0) * i / 4, unit_exponent_), dyadic(y0 + (y1 - y0) * j / 4, unit_exponent_)};
          SlicedLocation m = space_.locate(SlicedConfiguration{p.x, p.y, angle});
          if (m.kind == SlicedLocation::Kind::free && m.interval == interval && m.cell == cell) out.push_back(p);
        }
    }
    return out;
  }

  // Moves in the slice at `angle` from `from` to (to.x, to.y): a straight motion, else a lazy
  // roadmap over grid points of the slice cell.
  bool in_slice(const SlicedConfiguration& from, const Point& to) {
    const SlicedAngle& angle = from.angle;
    SlicedConfiguration target{to.x, to.y, angle};
    if (from.x == to.x && from.y == to.y) return true;
    bool flip = angle.half_turn;
    if (motion(from, target, flip)) {
      append(target, flip);
      return true;
    }
    auto slice = space_.slice(angle);
    auto cell_at = [&](const Point& p) -> std::size_t {
      const auto& chart = slice->charts()[0];
      if (p.x <= chart.x_lo || p.x >= chart.x_hi || p.y <= chart.y_lo || p.y >= chart.y_hi) return no_index - 1;
      Location l = slice->locate(ChartPoint{0, p.x, p.y});
      return l.kind == Location::Kind::free ? l.cell : no_index;
    };
    std::size_t cell = cell_at(Point{from.x, from.y});
    // the cell's extent (its boundary edges' certified ranges), or the chart box for the outer cell
    const auto& chart = slice->charts()[0];
    double x0 = to_double(chart.x_lo), x1 = to_double(chart.x_hi), y0 = to_double(chart.y_lo), y1 = to_double(chart.y_hi);
    // the outer cell (holding the chart box's corner) spreads to the box
    const std::size_t outer = cell_at(Point{Rational(chart.x_lo + unit_ / 2), Rational(chart.y_lo + unit_ / 2)});
    if (cell != no_index && cell != no_index - 1 && cell != outer) {
      double bx0 = 1e300, bx1 = -1e300, by0 = 1e300, by1 = -1e300;
      bool limit = false;
      for (std::size_t e : slice->cells()[cell].boundary) {
        const auto& edge = slice->edges()[e];
        if (edge.role == EdgeRole::limit) limit = true;
        bx0 = std::min(bx0, edge.x_chart.lower);
        bx1 = std::max(bx1, edge.x_chart.upper);
        by0 = std::min(by0, edge.y_chart.lower);
        by1 = std::max(by1, edge.y_chart.upper);
      }
      if (!limit && bx0 < bx1 && by0 < by1) {
        x0 = bx0, x1 = bx1, y0 = by0, y1 = by1;
      }
    }
    // proposals along thin channels: midpoints of each boundary vertex of the cell with its
    // nearest ones (a channel's mouth), fine enough for channels far narrower than the grid
    std::vector<Point> mouths;
    if (cell != no_index && cell != no_index - 1) {
      std::vector<std::array<double, 2>> corners;
      for (std::size_t e : slice->cells()[cell].boundary)
        for (std::size_t v : {slice->edges()[e].source, slice->edges()[e].target}) {
          const auto& vertex = slice->vertices()[v];
          if (!vertex.y_exact) continue;
          corners.push_back({vertex.x.approximate(), vertex.y.approximate()});
        }
      for (std::size_t i = 0; i < corners.size(); ++i) {
        std::vector<std::pair<double, std::size_t>> near;
        for (std::size_t j = 0; j < corners.size(); ++j)
          if (j != i)
            near.emplace_back(std::hypot(corners[i][0] - corners[j][0], corners[i][1] - corners[j][1]), j);
        std::sort(near.begin(), near.end());
        for (std::size_t k = 0; k < near.size() && k < 4; ++k) {
          if (near[k].first <= 0) continue;
          const auto& c = corners[near[k].second];
          Point p{dyadic((corners[i][0] + c[0]) / 2, unit_exponent_, 30), dyadic((corners[i][1] + c[1]) / 2, unit_exponent_, 30)};
          if (cell_at(p) == cell) mouths.push_back(p);
        }
      }
    }
    for (int grid : {10, 24}) {
      std::vector<Point> nodes{Point{from.x, from.y}, to};
      for (const auto& p : mouths) nodes.push_back(p);
      for (int i = 1; i < grid; ++i)
        for (int j = 1; j < grid; ++j) {
          Point p{dyadic(x0 + (x1 - x0) * i / grid, unit_exponent_), dyadic(y0 + (y1 - y0) * j / grid, unit_exponent_)};
          if (cell_at(p) == cell) nodes.push_back(p);
        }
      if (route(nodes, angle, flip)) return true;
    }
    return false;
  }

  // Lazy shortest path over the k-nearest graph of `nodes` (0: start, 1: goal).
  bool route(const std::vector<Point>& nodes, const SlicedAngle& angle, bool flip) {
    const std::size_t n = nodes.size();
    std::vector<std::array<double, 2>> at(n);
    for (std::size_t i = 0; i < n; ++i) at[i] = {to_double(nodes[i].x), to_double(nodes[i].y)};
    auto distance = [&](std::size_t i, std::size_t j) { return std::hypot(at[i][0] - at[j][0], at[i][1] - at[j][1]); };
    std::map<std::pair<std::size_t, std::size_t>, int> state;   // 1 free, -1 blocked
    std::vector<std::vector<std::size_t>> adjacent(n);
    const std::size_t k = std::min<std::size_t>(10, n - 1);
    for (std::size_t i = 0; i < n; ++i) {
      std::vector<std::size_t> order;
      for (std::size_t j = 0; j < n; ++j)
        if (j != i) order.push_back(j);
      std::partial_sort(order.begin(), order.begin() + static_cast<long>(k), order.end(),
                        [&](std::size_t a, std::size_t b) { return distance(i, a) < distance(i, b); });
      for (std::size_t m = 0; m < k; ++m) {
        adjacent[i].push_back(order[m]);
        adjacent[order[m]].push_back(i);
      }
    }
    for (int iteration = 0; iteration < 300; ++iteration) {
      std::vector<double> best(n, std::numeric_limits<double>::infinity());
      std::vector<std::size_t> previous(n, no_index);
      using Item = std::pair<double, std::size_t>;
      std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
      best[0] = 0;
      queue.push({0, 0});
      while (!queue.empty()) {
        auto [d, i] = queue.top();
        queue.pop();
        if (d > best[i]) continue;
        if (i == 1) break;
        for (std::size_t j : adjacent[i]) {
          auto key = std::minmax(i, j);
          if (state[{key.first, key.second}] < 0) continue;
          double e = d + distance(i, j);
          if (e < best[j]) {
            best[j] = e;
            previous[j] = i;
            queue.push({e, j});
          }
        }
      }
      if (previous[1] == no_index) return false;
      std::vector<std::size_t> chain{1};
      while (chain.back() != 0) chain.push_back(previous[chain.back()]);
      std::reverse(chain.begin(), chain.end());
      bool ok = true;
      for (std::size_t m = 0; m + 1 < chain.size() && ok; ++m) {
        auto key = std::minmax(chain[m], chain[m + 1]);
        int& s = state[{key.first, key.second}];
        if (s == 0) {
          s = motion(SlicedConfiguration{nodes[chain[m]].x, nodes[chain[m]].y, angle},
                     SlicedConfiguration{nodes[chain[m + 1]].x, nodes[chain[m + 1]].y, angle}, flip)
                  ? 1
                  : -1;
        }
        ok = s > 0;
      }
      if (ok) {
        for (std::size_t m = 1; m < chain.size(); ++m)
          append(SlicedConfiguration{nodes[chain[m]].x, nodes[chain[m]].y, angle}, flip);
        return true;
      }
    }
    return false;
  }

  // From `from` (current, last waypoint) to `to`, both in free cell `cell` of `interval`.
  bool within(const SlicedConfiguration& from, const SlicedConfiguration& to, std::size_t interval, std::size_t cell) {
    const std::size_t mark = out_.waypoints.size();
    if (direct(from, to, interval, cell)) return true;
    // a detour: turn to another angle of the interval (its representative, the middle of the
    // chart range between the two, quarter points), move there, and come back
    std::vector<SlicedAngle> detours{space_.intervals()[interval].representative};
    for (bool flip : {false, true}) {
      auto a = w_of(from.angle, flip), b = w_of(to.angle, flip);
      if (!a || !b) continue;
      for (const Rational& f : {Rational(1, 2), Rational(1, 4), Rational(3, 4)})
        detours.push_back(angle_of(Rational(*a + f * (*b - *a)), flip));
    }
    for (const auto& angle : detours) {
      if (space_.locate(SlicedConfiguration{from.x, from.y, angle}).interval != interval &&
          space_.locate(SlicedConfiguration{to.x, to.y, angle}).interval != interval)
        continue;
      rollback(mark);
      // the goal's offset at the detour angle, else the cell's samples there
      std::vector<Point> via{Point{to.x, to.y}};
      for (const auto& p : cell_samples(angle, interval, cell)) via.push_back(p);
      for (const auto& p : via) {
        SlicedConfiguration middle{p.x, p.y, angle};
        if (space_.locate(middle).kind != SlicedLocation::Kind::free) continue;
        rollback(mark);
        if (direct(from, middle, interval, cell) && direct(out_.waypoints.back(), to, interval, cell)) return true;
      }
    }
    rollback(mark);
    return false;
  }

  void rollback(std::size_t mark) {
    out_.waypoints.resize(mark);
    out_.through_half_turn.resize(mark - 1);
  }

  bool direct(const SlicedConfiguration& from, const SlicedConfiguration& to, std::size_t interval, std::size_t cell) {
    if (same_angle(from.angle, to.angle)) return in_slice(from, Point{to.x, to.y});
    bool flip = false;
    std::optional<Rational> a0 = w_of(from.angle, false), a1 = w_of(to.angle, false);
    if (!a0 || !a1 || !range_clear(*a0, *a1, false)) {
      std::optional<Rational> b0 = w_of(from.angle, true), b1 = w_of(to.angle, true);
      if (b0 && b1 && (range_clear(*b0, *b1, true) || !a0 || !a1)) {
        flip = true;
        a0 = b0;
        a1 = b1;
      }
    }
    if (!a0 || !a1) return false;
    SlicedConfiguration current = from;
    if (!stair(current, *a0, *a1, flip, interval, cell, Point{to.x, to.y}, 0)) return false;
    return in_slice(current, Point{to.x, to.y});
  }

  // Rotates from chart coordinate w0 (current's angle) to w1, moving in slices where needed.
  bool stair(SlicedConfiguration& current, const Rational& w0, const Rational& w1, bool flip, std::size_t interval,
             std::size_t cell, const Point& goal, int depth) {
    SlicedAngle end = angle_of(w1, flip);
    // the goal first (move at this angle, then turn in place), then the cell's samples at both
    // angles, then turning where the path is
    std::vector<Point> candidates{goal};
    for (const auto& p : cell_samples(end, interval, cell)) candidates.push_back(p);
    for (const auto& p : cell_samples(current.angle, interval, cell)) candidates.push_back(p);
    candidates.push_back(Point{current.x, current.y});
    for (const auto& p : candidates) {
      SlicedConfiguration here{p.x, p.y, current.angle}, there{p.x, p.y, end};
      if (space_.locate(here).kind != SlicedLocation::Kind::free) continue;
      if (!motion(here, there, flip)) continue;
      std::size_t mark = out_.waypoints.size();
      if (!in_slice(current, p)) {
        out_.waypoints.resize(mark);
        out_.through_half_turn.resize(mark - 1);
        continue;
      }
      append(there, flip);
      current = there;
      return true;
    }
    if (depth >= 6) return false;
    Rational middle = (w0 + w1) / 2;
    return stair(current, w0, middle, flip, interval, cell, goal, depth + 1) &&
           stair(current, middle, w1, flip, interval, cell, goal, depth + 1);
  }

 private:
  const SlicedSpace& space_;
  SlicedPath& out_;
  Rational unit_;          // the pair's length unit (1 mm for ordinary pairs)
  long unit_exponent_;     // unit_ = 2^unit_exponent_
};

}  // namespace

SlicedPath SlicedSpace::path(const SlicedConfiguration& a, const SlicedConfiguration& b) const {
  SlicedPath out;
  if (locate(a).kind != SlicedLocation::Kind::free || locate(b).kind != SlicedLocation::Kind::free) return out;
  if (!connected(a, b)) {
    out.status = SlicedPath::Status::not_connected;
    return out;
  }
  out.status = SlicedPath::Status::not_found;
  out.waypoints.push_back(a);
  Planner planner(*this, out);
  auto start = planner.off_critical(a, true);
  // the goal's side: reached from b' and then rotated to b
  SlicedPath tail;
  tail.waypoints.push_back(b);
  Planner tail_planner(*this, tail);
  auto goal = tail_planner.off_critical(b, true);
  out.motions_checked += tail.motions_checked;
  if (!start || !goal) return out;
  // the cell graph: nodes (interval, cell), edges the connections
  SlicedLocation from = locate(*start), to = locate(*goal);
  using Node = std::pair<std::size_t, std::size_t>;
  struct Step {
    Node previous;
    const SlicedConnection* connection = nullptr;
    bool rightwards = true;
  };
  std::map<Node, Step> seen;
  std::deque<Node> queue{Node{from.interval, from.cell}};
  seen[queue.front()] = Step{queue.front(), nullptr, true};
  while (!queue.empty()) {
    Node node = queue.front();
    queue.pop_front();
    if (node == Node{to.interval, to.cell}) break;
    for (const auto& crossing : crossings())
      for (const auto& link : crossing.connections) {
        Node left{crossing.left_interval, link.left_cell}, right{crossing.right_interval, link.right_cell};
        for (bool rightwards : {true, false}) {
          const Node& here = rightwards ? left : right;
          const Node& there = rightwards ? right : left;
          if (here != node || seen.count(there)) continue;
          seen[there] = Step{node, &link, rightwards};
          queue.push_back(there);
        }
      }
  }
  Node target{to.interval, to.cell};
  if (!seen.count(target)) return out;   // (connected() agreed: should not happen)
  std::vector<std::pair<Node, Step>> chain;
  for (Node n = target; seen[n].connection; n = seen[n].previous) chain.emplace_back(n, seen[n]);
  std::reverse(chain.begin(), chain.end());
  SlicedConfiguration current = *start;
  Node node{from.interval, from.cell};
  for (const auto& [next, step] : chain) {
    const SlicedConfiguration& enter = step.rightwards ? step.connection->left_witness : step.connection->right_witness;
    const SlicedConfiguration& leave = step.rightwards ? step.connection->right_witness : step.connection->left_witness;
    if (!planner.within(current, enter, node.first, node.second)) return out;
    current = out.waypoints.back();
    if (!planner.motion(current, leave, step.connection->through_half_turn)) return out;
    planner.append(leave, step.connection->through_half_turn);
    current = leave;
    node = next;
  }
  if (!planner.within(current, *goal, node.first, node.second)) return out;
  // then the tail, reversed (b' -> b)
  for (std::size_t i = tail.waypoints.size() - 1; i-- > 0;) planner.append(tail.waypoints[i], tail.through_half_turn[i]);
  out.status = SlicedPath::Status::found;
  return out;
}

}  // namespace hipair
