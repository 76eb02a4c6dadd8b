// The certainly-blocked tester of the C-space builder (see blocked_tester.hpp): disks of the
// parts' material guessed in doubles, certified once (exact location, certified clearance), and
// a certified (outward-rounded interval) test that two posed disks overlap over a chart box.
#include "oracle/blocked_tester.hpp"

#include "core/model_scale.hpp"
#include "oracle/overlap.hpp"

#include <hipair/error.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <deque>
#include <mutex>
#include <numbers>
#include <limits>
#include <new>
#include <tuple>

namespace hipair::cspace {
namespace {

// ---------------------------------------------------------------- certainly blocked cells
//
// The double guess of disks inside a part's material (candidates on a grid and just inside
// every edge, kept when the doubles say they are inside, shrunk and greedily chosen). The guess
// decides nothing: BlockedTester certifies every disk it keeps.

struct Disk {
  double x, y, r;
  double rho = 0;   // distance from the part's pivot (rotating parts)
};

struct EdgeGeometry {
  bool arc = false;
  double ax, ay, bx, by;           // ends
  double cx = 0, cy = 0, r = 0;    // arcs
  double start = 0, sweep = 0;     // arcs: start angle, signed sweep (ccw positive)
  bool ccw = true;
  bool minor = false;              // arcs: less than a half turn (decided exactly)
};

double angle_in_span(double angle, double start, double sweep) {
  // fraction along the arc of the direction `angle` (in [0, 1] when on the arc)
  double d = sweep >= 0 ? angle - start : start - angle;
  d = std::fmod(d, 2 * std::numbers::pi);
  if (d < 0) d += 2 * std::numbers::pi;
  return d / std::fabs(sweep);
}

// A length in the tester's unit of 2^exponent mm, as a double (exact scaling, then one rounding).
double scaled(const Rational& value, long exponent) {
  Rational q = value;
  if (exponent >= 0)
    mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(exponent));
  else
    mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(-exponent));
  return q.get_d();
}

// The exponent of the largest coordinate of the parts (points, centres, pivots): lengths
// divided by 2^exponent are about 1 in size, so that the doubles of this heuristic neither
// overflow (plates of 1e400 mm) nor lose small features to rounding at any scale.
long scale_exponent(const std::vector<const Part*>& parts) {
  Rational largest = 0;
  auto see = [&](const Rational& value) {
    if (abs(value) > largest) largest = abs(value);
  };
  for (const Part* part : parts) {
    see(part->motion.pivot.x);
    see(part->motion.pivot.y);
    for (const auto& loop : part->loops)
      for (const auto& edge : loop.edges)
        for (const Point* p : {&edge.source, &edge.target, &edge.center}) {
          see(p->x);
          see(p->y);
        }
  }
  if (sgn(largest) == 0) return 0;
  return static_cast<long>(mpz_sizeinbase(largest.get_num_mpz_t(), 2)) -
         static_cast<long>(mpz_sizeinbase(largest.get_den_mpz_t(), 2));
}

std::vector<EdgeGeometry> edges_of(const Part& part, long exponent) {
  std::vector<EdgeGeometry> edges;
  for (const auto& loop : part.loops)
    for (const auto& edge : loop.edges) {
      EdgeGeometry g;
      g.ax = scaled(edge.source.x, exponent);
      g.ay = scaled(edge.source.y, exponent);
      g.bx = scaled(edge.target.x, exponent);
      g.by = scaled(edge.target.y, exponent);
      if (edge.is_arc()) {
        g.arc = true;
        g.cx = scaled(edge.center.x, exponent);
        g.cy = scaled(edge.center.y, exponent);
        g.r = std::hypot(g.ax - g.cx, g.ay - g.cy);
        g.ccw = edge.ccw;
        if (!edge.is_full_circle()) {
          const Rational cross = (edge.source.x - edge.center.x) * (edge.target.y - edge.center.y) -
                                 (edge.source.y - edge.center.y) * (edge.target.x - edge.center.x);
          g.minor = edge.ccw ? sgn(cross) > 0 : sgn(cross) < 0;
        }
        g.start = std::atan2(g.ay - g.cy, g.ax - g.cx);
        double end = std::atan2(g.by - g.cy, g.bx - g.cx);
        double sweep = end - g.start;
        if (edge.ccw) {
          while (sweep <= 0) sweep += 2 * std::numbers::pi;
        } else {
          while (sweep >= 0) sweep -= 2 * std::numbers::pi;
        }
        if (edge.is_full_circle()) sweep = edge.ccw ? 2 * std::numbers::pi : -2 * std::numbers::pi;
        g.sweep = sweep;
      }
      edges.push_back(g);
    }
  return edges;
}

double distance_to(const EdgeGeometry& e, double px, double py) {
  if (!e.arc) {
    double dx = e.bx - e.ax, dy = e.by - e.ay;
    double t = ((px - e.ax) * dx + (py - e.ay) * dy) / (dx * dx + dy * dy);
    t = std::clamp(t, 0.0, 1.0);
    return std::hypot(px - e.ax - t * dx, py - e.ay - t * dy);
  }
  double angle = std::atan2(py - e.cy, px - e.cx);
  if (angle_in_span(angle, e.start, e.sweep) <= 1) return std::fabs(std::hypot(px - e.cx, py - e.cy) - e.r);
  return std::min(std::hypot(px - e.ax, py - e.ay), std::hypot(px - e.bx, py - e.by));
}

// Crossings of the ray from (px, py) towards +x with the edge (parity test).
int crossings(const EdgeGeometry& e, double px, double py) {
  if (!e.arc) {
    if ((e.ay > py) == (e.by > py)) return 0;
    double x = e.ax + (py - e.ay) * (e.bx - e.ax) / (e.by - e.ay);
    return x > px ? 1 : 0;
  }
  double h = e.r * e.r - (py - e.cy) * (py - e.cy);
  if (h <= 0) return 0;
  int count = 0;
  for (double sign : {-1.0, 1.0}) {
    double x = e.cx + sign * std::sqrt(h);
    if (x <= px) continue;
    double angle = std::atan2(py - e.cy, x - e.cx);
    if (angle_in_span(angle, e.start, e.sweep) <= 1) ++count;
  }
  return count;
}

std::vector<Disk> inscribed_disks(const Part& part, std::size_t limit, long exponent) {
  std::vector<EdgeGeometry> edges = edges_of(part, exponent);
  if (edges.empty()) return {};
  // An arc of less than a half turn on a circle far larger than its chord (a centre 10^20 mm
  // from a tip of 8 mm; the sweep's doubles cannot tell it from a whole turn) is its chord here: the doubles of centre + r cos(angle) lose the whole part to rounding (every
  // parity test and distance to it was noise, and such a part got no disk: session 46); the
  // chord is within chord^2 / (8 r) < 2^-23 chord of it, and the disks are only guesses that
  // certify_part proves exactly.
  for (auto& e : edges)
    if (e.arc && e.minor && std::isfinite(e.r) && std::hypot(e.bx - e.ax, e.by - e.ay) < 0x1p-20 * e.r)
      e.arc = false;
  // every coordinate finite: lengths were divided by the largest coordinate's power of two
  for (const auto& e : edges)
    if (!std::isfinite(e.ax) || !std::isfinite(e.ay) || !std::isfinite(e.bx) || !std::isfinite(e.by) ||
        !std::isfinite(e.cx) || !std::isfinite(e.cy) || !std::isfinite(e.r))
      return {};
  double min_x = 1e300, min_y = 1e300, max_x = -1e300, max_y = -1e300;
  for (const auto& e : edges)
    for (auto [x, y] : {std::pair{e.ax, e.ay}, std::pair{e.bx, e.by}}) {
      min_x = std::min(min_x, x);
      max_x = std::max(max_x, x);
      min_y = std::min(min_y, y);
      max_y = std::max(max_y, y);
    }
  for (const auto& e : edges)
    if (e.arc) {
      min_x = std::min(min_x, e.cx - e.r);
      max_x = std::max(max_x, e.cx + e.r);
      min_y = std::min(min_y, e.cy - e.r);
      max_y = std::max(max_y, e.cy + e.r);
    }
  std::vector<std::pair<double, double>> candidates;
  const int grid = 40;
  for (int i = 0; i < grid; ++i)
    for (int j = 0; j < grid; ++j)
      candidates.emplace_back(min_x + (max_x - min_x) * (i + 0.5) / grid, min_y + (max_y - min_y) * (j + 0.5) / grid);
  // points just inside every edge (material lies on the left), at a few depths
  for (const auto& e : edges) {
    double mx, my, nx, ny, length;
    if (!e.arc) {
      mx = 0.5 * (e.ax + e.bx);
      my = 0.5 * (e.ay + e.by);
      length = std::hypot(e.bx - e.ax, e.by - e.ay);
      if (!(length > 0)) continue;   // a feature below the doubles' resolution at this scale
      nx = -(e.by - e.ay) / length;
      ny = (e.bx - e.ax) / length;
    } else {
      double middle = e.start + 0.5 * e.sweep;
      mx = e.cx + e.r * std::cos(middle);
      my = e.cy + e.r * std::sin(middle);
      length = e.r * std::fabs(e.sweep);
      if (!(e.r > 0) || !(length > 0)) continue;
      double toward_centre = e.ccw ? 1 : -1;
      nx = toward_centre * (e.cx - mx) / e.r;
      ny = toward_centre * (e.cy - my) / e.r;
    }
    for (double depth : {0.15, 0.35, 0.7}) candidates.emplace_back(mx + nx * depth * length, my + ny * depth * length);
  }
  // The part's own size in this unit: lengths are divided by the largest coordinate's power of
  // two, points, pivots and arc centres alike, so a part with an arc whose centre lies 10^20 mm
  // away has its corners at about 10^-19 here. The tests below are relative to 1 + |p| (the
  // unit); at such a scale every candidate was within 1e-9 of the boundary and the part got no
  // disk ("a part has no interior disks", session 46): the unit is the part's size times 2^10
  // where that is below 1 (1 for every part whose corners reach 2^-10 of the largest
  // coordinate: the same disks as before).
  double size = 0;
  for (const auto& e : edges)
    size = std::max({size, std::fabs(e.ax), std::fabs(e.ay), std::fabs(e.bx), std::fabs(e.by)});
  const double unit = size > 0 ? std::min(1.0, 1024 * size) : 1.0;
  // Session 70 (growth70): each edge's box (a segment's ends; an arc's whole circle and ends)
  // and a margin m far above every rounding of the tests below (1e-9 of the largest magnitude;
  // their roundings are a few ulps of it). An edge whose box, widened by m, misses the ray's
  // line or lies left of the candidate adds no crossing (a segment crosses only between its
  // ends' ordinates, at an abscissa between its ends'; an arc only where |py - cy| < r, at
  // cx +- sqrt(h) <= cx + r); an edge whose box is farther than the best distance so far plus
  // m is no nearer than it (every point distance_to measures to, the nearest point of the
  // circle on the arc's span or an end, lies in the box). So the parity and the distance are
  // those of the loops over every edge, bit for bit (the minimum of the same doubles), and the
  // trigonometry runs for the few edges near each candidate: it ran for every edge at every
  // candidate, (1600 + 3 E) E evaluations, n^2 in the tooth count (≈ 1 G instructions of the
  // 56 x 56 gears' operating region).
  struct EdgeBox {
    double xlo, xhi, ylo, yhi;
  };
  std::vector<EdgeBox> boxes;
  boxes.reserve(edges.size());
  double magnitude = 0;
  for (const auto& e : edges) {
    EdgeBox b{std::min(e.ax, e.bx), std::max(e.ax, e.bx), std::min(e.ay, e.by), std::max(e.ay, e.by)};
    if (e.arc) {
      b = EdgeBox{std::min(b.xlo, e.cx - e.r), std::max(b.xhi, e.cx + e.r), std::min(b.ylo, e.cy - e.r),
                  std::max(b.yhi, e.cy + e.r)};
      magnitude = std::max(magnitude, e.r);
    }
    magnitude = std::max({magnitude, std::fabs(b.xlo), std::fabs(b.xhi), std::fabs(b.ylo), std::fabs(b.yhi)});
    boxes.push_back(b);
  }
  const double margin = 1e-9 * (1 + magnitude);
  // a lower bound of the distance from (px, py) to the box (its larger axis gap)
  auto box_gap = [](const EdgeBox& b, double px, double py) {
    return std::max({b.xlo - px, px - b.xhi, b.ylo - py, py - b.yhi, 0.0});
  };
  std::vector<Disk> disks;
  for (auto [px, py] : candidates) {
    // the parity first: a candidate outside the part (most of the bounding box's grid around a
    // toothed wheel) is dropped whatever its distance, which is not measured then
    int count = 0;
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const EdgeBox& b = boxes[i];
      if (py < b.ylo - margin || py > b.yhi + margin || b.xhi + margin < px) continue;   // no crossing
      count += crossings(edges[i], px, py);
    }
    if (count % 2 == 0) continue;
    // the nearest box's edge first, then every edge whose box is within the best distance
    std::size_t nearest = 0;
    double nearest_gap = 1e300;
    for (std::size_t i = 0; i < edges.size(); ++i)
      if (const double gap = box_gap(boxes[i], px, py); gap < nearest_gap) {
        nearest_gap = gap;
        nearest = i;
      }
    double distance = std::min(1e300, distance_to(edges[nearest], px, py));
    for (std::size_t i = 0; i < edges.size(); ++i)
      if (i != nearest && !(box_gap(boxes[i], px, py) > distance + margin))
        distance = std::min(distance, distance_to(edges[i], px, py));
    if (!std::isfinite(px) || !std::isfinite(py) || !std::isfinite(distance)) continue;
    if (distance <= 1e-9 * (unit + std::fabs(px) + std::fabs(py))) continue;
    // double rounding in the distance is far below 1e-9 relative: shrink by that much (a guess:
    // certify_part certifies the radius and the centre exactly)
    disks.push_back({px, py, distance * (1 - 1e-9) - 1e-9 * (unit + std::fabs(px) + std::fabs(py))});
  }
  std::sort(disks.begin(), disks.end(), [](const Disk& a, const Disk& b) { return a.r > b.r; });
  std::vector<Disk> chosen;
  for (const auto& d : disks) {
    if (d.r <= 0) continue;   // (dropped whether covered or not)
    bool covered = false;
    for (const auto& c : chosen) {
      // |dx| or |dy| beyond c.r: the distance (hypot, at least either) plus 0.5 d.r > 0 is too
      if (std::fabs(d.x - c.x) > c.r || std::fabs(d.y - c.y) > c.r) continue;
      if (std::hypot(d.x - c.x, d.y - c.y) + 0.5 * d.r <= c.r) {
        covered = true;
        break;
      }
    }
    if (covered) continue;
    chosen.push_back(d);
    if (chosen.size() >= limit) break;
  }
  return chosen;
}

// A rational divided by 2^exponent (exact), as scaled_model() scales a length.
Rational scaled_exactly(const Rational& value, long exponent) {
  Rational q = value;
  if (exponent >= 0)
    mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(exponent));
  else
    mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), static_cast<mp_bitcnt_t>(-exponent));
  return q;
}

// One part's certified disks in the unit of 2^exponent mm: its interior disks first, then its
// boundary points (radius 0). A function of the part's loops, its pivot and the exponent only.
struct PartDisks {
  std::vector<BlockedTester::CertifiedCore> disks;
  std::size_t interior = 0;
};

PartDisks certify_part(const Part& part, long exponent) {
  using kernels::Interval;
  using kernels::interval_detail::up;
  Model one;
  one.parts = {part};
  const Model scaled = scaled_model(one, exponent);
  const Part& exact = scaled.parts.front();
  const Interval pivot[2] = {Interval::enclose(exact.motion.pivot.x), Interval::enclose(exact.motion.pivot.y)};
  PartDisks out;
  // enough disks that every tooth of a many-toothed part gets some (the operating
  // region's flood must see blocked space between neighbouring channels)
  std::size_t edges = 0;
  for (const Loop& loop : part.loops) edges += loop.edges.size();
  std::vector<Disk> guess = inscribed_disks(part, std::max<std::size_t>(150, 2 * edges), exponent);
  const ClearanceBound clearance(exact);
  // certify_disk's two tests (a certified clearance, then exact location of the centre), with
  // the part's enclosure and exact edges made once for all its disks instead of once per disk
  const PartLocator locator(exact);
  for (const Disk& d : guess) {
    const Point centre{Rational(d.x), Rational(d.y)};
    const double radius = clearance.lower(centre.x, centre.y);
    if (!(radius > 0) || locator.locate(centre) != PointLocation::inside) continue;
    BlockedTester::CertifiedCore core;
    core.x = Interval::enclose(centre.x);
    core.y = Interval::enclose(centre.y);
    // never larger than the guess: the tester claims no more than the guess would
    core.r = std::min(radius, d.r);
    if (!(core.r > 0)) continue;
    core.rx = core.x - pivot[0];
    core.ry = core.y - pivot[1];
    core.rho = kernels::sqrt(core.rx * core.rx + core.ry * core.ry).hi;
    if (!std::isfinite(core.rho)) continue;
    // the double evaluation of blocked(): the centre (an exact double), its offset from the
    // pivot as a double and a bound of that double's error, and a bound of the magnitudes
    core.cx = d.x;
    core.cy = d.y;
    core.rx_m = core.rx.lo;
    core.ry_m = core.ry.lo;
    core.r_error = up(std::max(core.rx.hi - core.rx.lo, core.ry.hi - core.ry.lo));
    core.magnitude = up(up(std::fabs(core.rx_m) + std::fabs(core.ry_m)) + core.r_error);
    if (!std::isfinite(core.magnitude) || !std::isfinite(core.cx) || !std::isfinite(core.cy)) continue;
    out.disks.push_back(core);
  }
  out.interior = out.disks.size();
  // Points of the part's boundary as disks of radius 0: a point of the part's closure
  // strictly inside a disk of the other part's material makes the interiors overlap (the
  // part is the closure of its interior, so every neighbourhood of the point holds interior
  // points of the part). A pair of posed disks is tested on the sum of its reaches, so such
  // a point certifies a box only where it lies in the other part's disk by more than every
  // error. The points are the loops' vertices (exact; the double centre's error is carried in
  // centre_error and in the offset's r_error): where a part's corners reach deepest into the
  // other part. Points along the edges certified no further box of the examples' charts.
  for (const Loop& loop : exact.loops)
    for (const Edge& edge : loop.edges) {
      const Point& point = edge.source;
      BlockedTester::CertifiedCore core;
      core.x = Interval::enclose(point.x);
      core.y = Interval::enclose(point.y);
      core.r = 0;
      core.rx = core.x - pivot[0];
      core.ry = core.y - pivot[1];
      core.rho = kernels::sqrt(core.rx * core.rx + core.ry * core.ry).hi;
      core.cx = core.x.lo;
      core.cy = core.y.lo;
      core.centre_error = up(std::max(core.x.hi - core.x.lo, core.y.hi - core.y.lo));
      core.rx_m = core.rx.lo;
      core.ry_m = core.ry.lo;
      core.r_error = up(std::max(core.rx.hi - core.rx.lo, core.ry.hi - core.ry.lo));
      core.magnitude = up(up(std::fabs(core.rx_m) + std::fabs(core.ry_m)) + core.r_error);
      if (!std::isfinite(core.rho) || !std::isfinite(core.magnitude) || !std::isfinite(core.cx) ||
          !std::isfinite(core.cy) || !std::isfinite(core.centre_error))
        continue;
      out.disks.push_back(core);
    }
  return out;
}

// The memo of certified part disks (part_disk_memo()): an entry is keyed by everything
// certify_part() reads — the loops' exact geometry (each edge's kind, ends, centre, direction
// and squared radius, each loop's hole flag), the pivot and the exponent — and filled once
// (the first caller computes, a concurrent caller of the same key waits). The last
// `memo_capacity` keys are kept.
struct MemoEntry {
  long exponent = 0;
  Point pivot;
  std::vector<Loop> loops;
  std::once_flag once;
  std::shared_ptr<const PartDisks> value;
};

bool same_edge(const Edge& a, const Edge& b) {
  return a.kind == b.kind && a.source == b.source && a.target == b.target && a.center == b.center && a.ccw == b.ccw &&
         a.radius_squared == b.radius_squared;
}

bool same_key(const MemoEntry& entry, const Part& part, long exponent) {
  if (entry.exponent != exponent || !(entry.pivot == part.motion.pivot) || entry.loops.size() != part.loops.size())
    return false;
  for (std::size_t i = 0; i < part.loops.size(); ++i) {
    const Loop& a = entry.loops[i];
    const Loop& b = part.loops[i];
    if (a.is_hole != b.is_hole || a.edges.size() != b.edges.size()) return false;
    for (std::size_t j = 0; j < a.edges.size(); ++j)
      if (!same_edge(a.edges[j], b.edges[j])) return false;
  }
  return true;
}

constexpr std::size_t memo_capacity = 64;

std::shared_ptr<const PartDisks> part_disks(const Part& part, long exponent) {
  if (!part_disk_memo().load(std::memory_order_relaxed))
    return std::make_shared<const PartDisks>(certify_part(part, exponent));
  static std::mutex mutex;
  static std::deque<std::shared_ptr<MemoEntry>> entries;
  std::shared_ptr<MemoEntry> entry;
  {
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& e : entries)
      if (same_key(*e, part, exponent)) {
        entry = e;
        break;
      }
    if (entry) {
      part_disk_memo_hits().fetch_add(1, std::memory_order_relaxed);
    } else {
      entry = std::make_shared<MemoEntry>();
      entry->exponent = exponent;
      entry->pivot = part.motion.pivot;
      entry->loops = part.loops;
      entries.push_back(entry);
      if (entries.size() > memo_capacity) entries.pop_front();
    }
  }
  std::call_once(entry->once, [&] { entry->value = std::make_shared<const PartDisks>(certify_part(part, exponent)); });
  return entry->value;
}

}  // namespace

std::atomic<bool>& part_disk_memo() {
  static std::atomic<bool> on{true};
  return on;
}

std::atomic<std::size_t>& part_disk_memo_hits() {
  static std::atomic<std::size_t> hits{0};
  return hits;
}

// blocked() decides with certified bounds only: the disks are certified once (exact centre
// strictly inside the part, radius a certified lower bound of its clearance), the parts' poses
// at a middle chart value m come from outward-rounded enclosures of the rational cos/sin of m,
// the movement from there over the box is bounded by a certified angle or travel bound, and
// every rounding of the double evaluation of a posed centre is covered by an a-priori bound
// (each term below is at least the error it stands for). The doubles of inscribed_disks()
// only guess where to put the disks. A part's disks are certified once per process for its
// geometry, pivot and the pair's exponent (part_disks(): the anchor of the escapement, in
// three pairs, once).
BlockedTester::BlockedTester(const Model& model, const PairAxes& axes)
    : axes_(axes), exponent_(scale_exponent({&model.parts[axes.first], &model.parts[axes.second]})) {
  using kernels::Interval;
  using kernels::interval_detail::up;
  for (int k = 0; k < 2; ++k) {
    const Part& part = model.parts[k == 0 ? axes.first : axes.second];
    motion_[k] = part.motion.kind;
    moves_[k] = k == 0 ? axes.first_moves : axes.second_moves;
    pivot_[k][0] = Interval::enclose(scaled_exactly(part.motion.pivot.x, exponent_));
    pivot_[k][1] = Interval::enclose(scaled_exactly(part.motion.pivot.y, exponent_));
    direction_[k][0] = Interval::enclose(part.motion.direction.x);
    direction_[k][1] = Interval::enclose(part.motion.direction.y);
    direction_length_[k] = kernels::sqrt(direction_[k][0] * direction_[k][0] + direction_[k][1] * direction_[k][1]).hi;
    const std::shared_ptr<const PartDisks> cores = part_disks(part, exponent_);
    disks_[k] = cores->disks;
    interior_disks_[k] = cores->interior;
    pivot_m_[k][0] = pivot_[k][0].lo;
    pivot_m_[k][1] = pivot_[k][1].lo;
    pivot_error_[k] = up(std::max(pivot_[k][0].hi - pivot_[k][0].lo, pivot_[k][1].hi - pivot_[k][1].lo));
    pivot_magnitude_[k] = std::max(std::fabs(pivot_m_[k][0]), std::fabs(pivot_m_[k][1]));
  }
}

bool BlockedTester::blocked(const ChartAxis& x_axis, const ChartAxis& y_axis, const algebra::Interval& x,
                            const algebra::Interval& y) const {
  thread_local Posed posed[2];
  // the first moving part carries the chart's x axis, the second moving part its y axis
  bool x_used = false;
  for (int k = 0; k < 2; ++k) {
    const bool use_x = !x_used;
    if (moves_[k]) x_used = true;
    if (!pose_part(k, use_x ? x_axis : y_axis, use_x ? x : y, posed[k])) return false;
  }
  return overlapping(posed[0], posed[1]);
}

bool BlockedTester::blocked(const ChartAxis& x_axis, const ChartAxis& y_axis, const algebra::Interval& x,
                            const algebra::Interval& y, Cache& cache) const {
  const Posed* posed[2] = {nullptr, nullptr};
  if (!posed_parts(x_axis, y_axis, x, y, cache, posed)) return false;
  return overlapping(*posed[0], *posed[1]);
}

// Calls f(k, axis, range, key) for each part k: the chart axis and interval its pose depends
// on (the first moving part carries the chart's x axis, the second its y axis) and its cache
// key (a fixed part's pose does not depend on the box: one entry). False when f is.
template <class F>
bool BlockedTester::each_part(const ChartAxis& x_axis, const ChartAxis& y_axis, const algebra::Interval& x,
                              const algebra::Interval& y, F&& f) const {
  bool x_used = false;
  for (int k = 0; k < 2; ++k) {
    const bool use_x = !x_used;
    if (moves_[k]) x_used = true;
    const algebra::Interval& range = use_x ? x : y;
    const std::pair<double, double> key = moves_[k] ? std::pair<double, double>{range.lo, range.hi}
                                                    : std::pair<double, double>{0.0, 0.0};
    if (!f(k, use_x ? x_axis : y_axis, range, key)) return false;
  }
  return true;
}

std::size_t BlockedTester::Cache::KeyHash::operator()(const std::pair<double, double>& key) const noexcept {
  // (-0.0 and 0.0 are equal keys: normalised by adding 0.0, which maps -0.0 to 0.0)
  const auto lo = std::bit_cast<std::uint64_t>(key.first + 0.0), hi = std::bit_cast<std::uint64_t>(key.second + 0.0);
  std::uint64_t h = lo * 0x9E3779B97F4A7C15ULL ^ (hi + 0x632BE59BD9B4E019ULL + (lo << 6) + (lo >> 2));
  h ^= h >> 29;
  h *= 0xBF58476D1CE4E5B9ULL;
  return static_cast<std::size_t>(h ^ (h >> 32));
}

bool BlockedTester::posed_parts(const ChartAxis& x_axis, const ChartAxis& y_axis, const algebra::Interval& x,
                                const algebra::Interval& y, Cache& cache, const Posed* out[2]) const {
  return each_part(x_axis, y_axis, x, y, [&](int k, const ChartAxis& axis, const algebra::Interval& range, const auto& key) {
    auto [it, inserted] = cache.parts_[k]->posed.try_emplace(key);
    if (inserted) it->second.usable = pose_part(k, axis, range, it->second);
    out[k] = &it->second;
    return it->second.usable;
  });
}

bool BlockedTester::pose_bounds(const ChartAxis& x_axis, const ChartAxis& y_axis, const algebra::Interval& x,
                                const algebra::Interval& y, Cache& cache, Cache::Pose* out[2],
                                const GridCell* cell) const {
  // both parts' poses of a grid cell already indexed: two array reads (the indices each_part
  // gives below: part 0 on the chart's x axis, part 1 on x when part 0 is fixed, else on y;
  // a fixed part at index 0 of depth 0)
  if (cell && cell->depth >= 0 && cell->depth < Cache::cell_index_depths) {
    Cache::Pose* found[2] = {nullptr, nullptr};
    for (int k = 0; k < 2; ++k) {
      const int depth = moves_[k] ? cell->depth : 0;
      const long index = !moves_[k] ? 0 : (k == 0 || !moves_[0]) ? cell->i : cell->j;
      const std::vector<Cache::Pose*>& table = cache.parts_[k]->by_cell[depth];
      if (index >= 0 && static_cast<std::size_t>(index) < table.size()) found[k] = table[static_cast<std::size_t>(index)];
    }
    if (found[0] && found[1]) {
      out[0] = found[0];
      out[1] = found[1];
      return found[0]->bound.usable && found[1]->bound.usable;
    }
  }
  return each_part(x_axis, y_axis, x, y, [&](int k, const ChartAxis& axis, const algebra::Interval& range, const auto& key) {
    // a grid cell's pose by its column (x) or row (y) index; a fixed part's at index 0 of depth 0
    Cache::Pose** indexed = nullptr;
    if (cell && cell->depth >= 0 && cell->depth < Cache::cell_index_depths) {
      const int depth = moves_[k] ? cell->depth : 0;
      const long index = moves_[k] ? (&range == &x ? cell->i : cell->j) : 0;
      std::vector<Cache::Pose*>& table = cache.parts_[k]->by_cell[depth];
      if (table.empty()) table.assign(std::size_t{1} << depth, nullptr);
      if (index >= 0 && static_cast<std::size_t>(index) < table.size()) {
        indexed = &table[static_cast<std::size_t>(index)];
        if (*indexed) {
          out[k] = *indexed;
          return (*indexed)->bound.usable;
        }
      }
    }
    auto [it, inserted] = cache.parts_[k]->bounds.try_emplace(key);
    if (inserted) it->second.bound = pose_bound(k, axis, range);
    out[k] = &it->second;
    if (indexed) *indexed = &it->second;
    return it->second.bound.usable;
  });
}

// (the first call for an index; out of line: the lookup below is in the candidates' loop)
[[gnu::noinline]] const BlockedTester::PosedDisk* BlockedTester::pose_new_disk(int k, Cache::Pose& pose,
                                                                              std::uint32_t index) const {
  if (pose.slot.empty()) {
    pose.slot.assign(disks_[k].size(), -1);
    pose.disks.reserve(std::min<std::size_t>(disks_[k].size(), 64));
  }
  std::int32_t& slot = pose.slot[index];
  if (slot == -1) {
    PosedDisk q;
    if (pose_disk(k, pose.bound, index, q)) {
      slot = static_cast<std::int32_t>(pose.disks.size());
      pose.disks.push_back(q);
    } else {
      slot = -2;
    }
  }
  return slot >= 0 ? &pose.disks[static_cast<std::size_t>(slot)] : nullptr;
}

inline const BlockedTester::PosedDisk* BlockedTester::posed_disk(int k, Cache::Pose& pose, std::uint32_t index) const {
  if (index < pose.slot.size()) {
    const std::int32_t slot = pose.slot[index];
    if (slot >= 0) return &pose.disks[static_cast<std::size_t>(slot)];
    if (slot == -2) return nullptr;
  }
  return pose_new_disk(k, pose, index);
}

namespace {
using kernels::interval_detail::down;
using kernels::interval_detail::up;

// Can the pair certify some box inside the one its disks were posed over? Every pair that
// certifies a sub-box has centres closer than the sum of the radii at each configuration of the
// sub-box, and each posed centre lies within its movement and error bound (outer - radius) of
// the true centre at every configuration of the box: so |centre_a - centre_b| < outer_a +
// outer_b exactly. The double test below keeps every such pair (its margin, relative 2^-20 and
// absolute 2^-1000, is far above the roundings of a few operations on doubles of size 1); it
// keeps some more, which costs only work. The certified test (certifies()) implies it: rounding
// is monotone and reach <= outer.
template <class Disk>
[[gnu::always_inline]] inline bool may_certify_inside(const Disk& a, const Disk& b) {
  const double dx = a.x - b.x, dy = a.y - b.y, s = a.outer + b.outer;
  if (!(s > 0)) return false;
  return dx * dx + dy * dy <= s * s * (1 + 0x1p-20) + 0x1p-1000;
}

// Do the disks overlap with their nominal radii (the middle of reach and outer)? Orders the
// candidates only (decides nothing).
template <class Disk>
[[gnu::always_inline]] inline bool overlap_nominally(const Disk& a, const Disk& b) {
  const double dx = a.x - b.x, dy = a.y - b.y, s = 0.5 * (a.outer + b.outer + a.reach + b.reach);
  return s > 0 && dx * dx + dy * dy < s * s;
}

// The certified test of one pair of posed disks: they overlap at every configuration of the box.
// (Inlined: it runs in the innermost loops of blocked() and gather(); a call costs ≈ 1 % of a build.)
template <class Disk>
[[gnu::always_inline]] inline bool certifies(const Disk& a, const Disk& b) {
  // a plain double test first (the certified one below implies it: skipping when it fails
  // decides nothing), then certified: |centre_a - centre_b|^2 (rounded up) <
  // (reach_a + reach_b)^2 (rounded down)
  const double plain_dx = a.x - b.x, plain_dy = a.y - b.y, plain_reach = a.reach + b.reach;
  if (!(plain_reach > 0) || !(plain_dx * plain_dx + plain_dy * plain_dy < plain_reach * plain_reach)) return false;
  const double dx = up(std::fabs(plain_dx)), dy = up(std::fabs(plain_dy));
  const double far2 = up(up(dx * dx) + up(dy * dy));
  const double reach = down(a.reach + b.reach);
  if (!(reach > 0)) return false;
  return far2 < down(reach * reach);
}
}  // namespace

bool BlockedTester::blocked(const ChartAxis& x_axis, const ChartAxis& y_axis, const algebra::Interval& x,
                            const algebra::Interval& y, Cache& cache, const std::vector<DiskPair>* candidates,
                            std::vector<DiskPair>* narrowed, const GridCell* cell) const {
  if (narrowed) narrowed->clear();
  if (!candidates) {
    const Posed* posed[2] = {nullptr, nullptr};
    if (!posed_parts(x_axis, y_axis, x, y, cache, posed)) return false;
    if (!narrowed) return overlapping(*posed[0], *posed[1]);
    return gather(*posed[0], *posed[1], *narrowed);
  }
  Cache::Pose* poses[2] = {nullptr, nullptr};
  if (!pose_bounds(x_axis, y_axis, x, y, cache, poses, cell)) return false;
  // the narrowed list puts first the pairs whose nominal disks overlap (the likeliest to
  // certify a sub-cell: a blocked cell's test stops at its first certifying pair)
  thread_local std::vector<DiskPair> later_list;
  std::vector<DiskPair>& later = later_list;
  later.clear();
  // (pose_disk depends only on the part, the pose and the index: a disk is posed once per
  // pose, for every cell of the column or row that shares the pose, and kept in the pose's
  // slots. The loop reads the second part's slots directly: the slot table is made whole
  // before the loop, so a pair's second disk is one slot read; the first part's disk is looked
  // up once per run of pairs that share it: the lists come from the sweep, grouped by disk.)
  Cache::Pose& pose_a = *poses[0];
  Cache::Pose& pose_b = *poses[1];
  if (pose_b.slot.empty()) {
    pose_b.slot.assign(disks_[1].size(), -1);
    pose_b.disks.reserve(std::min<std::size_t>(disks_[1].size(), 64));
  }
  const std::int32_t* const slot_b = pose_b.slot.data();
  const PosedDisk* posed_b = pose_b.disks.data();   // moves when a new disk is posed: re-read then
  const PosedDisk* a = nullptr;
  std::uint32_t a_index = UINT32_MAX;
  for (const DiskPair& pair : *candidates) {
    if (pair.first != a_index) {
      a_index = pair.first;
      a = posed_disk(0, pose_a, pair.first);
    }
    if (!a) continue;
    const std::int32_t slot = slot_b[pair.second];
    const PosedDisk* b;
    if (slot >= 0) {
      b = posed_b + slot;
    } else {
      if (slot == -2) continue;   // not finite
      b = pose_new_disk(1, pose_b, pair.second);
      posed_b = pose_b.disks.data();
      if (!b) continue;
    }
    // (a stays valid: only a disk of the first part posed later moves it, and then it is
    // replaced)
    // A pair that fails may_certify_inside neither certifies (certifies() implies it) nor is
    // kept: one test of the outer radii first decides most pairs; the answer and the list are
    // those of testing certifies() then may_certify_inside() on every pair.
    if (!may_certify_inside(*a, *b)) continue;
    if (certifies(*a, *b)) {
      if (narrowed) narrowed->clear();
      return true;
    }
    if (narrowed) (overlap_nominally(*a, *b) ? *narrowed : later).push_back(pair);
  }
  if (narrowed) narrowed->insert(narrowed->end(), later.begin(), later.end());
  return false;
}

// Part k's disks posed over its axis interval `range`: the centre at the middle pose in
// doubles and a lower bound of the radius that holds over the whole interval (radius minus
// movement and every error of the double centre), sorted by the centre's x. False when the
// interval admits no claim (then nothing is blocked).
bool BlockedTester::pose_part(int k, const ChartAxis& axis, const algebra::Interval& range, Posed& out) const {
  out.interior.disks.clear();
  out.boundary.disks.clear();
  const PoseBound pose = pose_bound(k, axis, range);
  if (!pose.usable) return false;
  for (std::size_t i = 0; i < disks_[k].size(); ++i) {
    PosedDisk q;
    if (!pose_disk(k, pose, static_cast<std::uint32_t>(i), q)) continue;
    (disks_[k][i].r > 0 ? out.interior : out.boundary).disks.push_back(q);
  }
  for (PosedSet* set : {&out.interior, &out.boundary}) {
    std::sort(set->disks.begin(), set->disks.end(), [](const PosedDisk& a, const PosedDisk& b) { return a.x < b.x; });
    set->xs.resize(set->disks.size());
    set->widest = -std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < set->disks.size(); ++j) {
      set->xs[j] = set->disks[j].x;
      set->widest = std::max(set->widest, set->disks[j].reach);
    }
  }
  return true;
}

// Part k's pose over its axis interval `range` (see PoseBound); not usable when the interval
// admits no claim. (Flattened: the interval operations of the angle bound inlined, the same
// operations in the same order.)
[[gnu::flatten]] BlockedTester::PoseBound BlockedTester::pose_bound(int k, const ChartAxis& axis, const algebra::Interval& range) const {
  using kernels::Interval;
  // The moving part's pose over its chart interval: the pose at a middle chart value m
  // (certified cos/sin of its angle, or its offset) and a bound on how far a point at
  // distance rho from the pivot moves from there: rho * |theta - theta_m| for rotations
  // (the chord is shorter than the arc), the angle bound from the series of atan (side() below);
  // |s - m| * |direction| for translations.
  PoseBound pose;
  pose.direction_error =
      up(std::max(direction_[k][0].hi - direction_[k][0].lo, direction_[k][1].hi - direction_[k][1].lo));
  if (!moves_[k]) return pose;
  if (!std::isfinite(range.lo) || !std::isfinite(range.hi) || !(range.lo <= range.hi)) {
    pose.usable = false;
    return pose;
  }
  double lo = range.lo, hi = range.hi;
  if (axis.kind == ChartAxis::Kind::translation) {
    // chart offsets are in mm: into the tester's unit, outward (out of double range: no claim)
    int shift = static_cast<int>(std::clamp<long>(-exponent_, -4000, 4000));
    lo = down(std::ldexp(lo, shift));
    hi = up(std::ldexp(hi, shift));
    if (!std::isfinite(lo) || !std::isfinite(hi)) {
      pose.usable = false;
      return pose;
    }
    double m = std::clamp(0.5 * lo + 0.5 * hi, lo, hi);
    double half = std::max((Interval(m, m) - Interval(lo, lo)).hi, (Interval(hi, hi) - Interval(m, m)).hi);
    pose.shift = m;
    pose.travel = (Interval(half, half) * Interval(direction_length_[k], direction_length_[k])).hi;
  } else {
    // the middle of the angle range (any m in [lo, hi] is sound; this one balances the sides)
    double m = std::clamp(std::tan(0.5 * (std::atan(lo) + std::atan(hi))), lo, hi);
    if (!std::isfinite(m)) m = std::clamp(0.5 * lo + 0.5 * hi, lo, hi);
    auto [c, s] = rotation_enclosure(axis.half_turn, Interval(m, m));
    pose.c = c.lo;
    pose.s = s.lo;
    pose.cs_error = up(up(c.hi - c.lo) + up(s.hi - s.lo));
    pose.cs_size = up(std::max(std::fabs(c.lo), std::fabs(c.hi)) + std::max(std::fabs(s.lo), std::fabs(s.hi)));
    auto side = [](double a, double b) {   // bound of |2 atan b - 2 atan a|, a <= b
      // atan b - atan a = atan z, z = (b - a)/(1 + ab), when 1 + ab > 0; atan z <= z - z^3/3 + z^5/5
      // for 0 <= z <= 1 (alternating series), atan z < pi/2 < 1.5708
      Interval width = Interval(b, b) - Interval(a, a);
      Interval denominator = Interval(1) + Interval(a, a) * Interval(b, b);
      if (!(denominator.lo > 0)) return (Interval(2) * width).hi;   // mean value theorem: slope <= 2
      double z = (width / denominator).hi;
      if (!(z <= 1)) return (Interval(2) * Interval(std::min(z, 1.5708), std::min(z, 1.5708))).hi;
      Interval zi(z, z), z2 = zi * zi;
      Interval series = zi * (Interval(1) - z2 / Interval(3) + z2 * z2 / Interval(5));
      return (Interval(2) * series).hi;
    };
    pose.angle = std::max(side(lo, m), side(m, hi));
  }
  return pose;
}

// Disk `index` of part k posed with `p`: the centre at the middle pose in doubles, a lower
// bound of its radius over the whole interval (radius minus movement and every error of the
// double centre) and an upper bound of radius plus the same. False when not finite.
bool BlockedTester::pose_disk(int k, const PoseBound& p, std::uint32_t index, PosedDisk& q) const {
  // u = 2^-53 (unit roundoff); a bound of the rounding of a few operations on terms of size M
  // is a small multiple of u M, plus an absolute term for underflow (each rounding below the
  // normal range errs by at most 2^-1075).
  constexpr double unit = 0x1p-53;
  constexpr double underflow = 0x1p-1000;
  constexpr double inflate = 1 + 0x1p-40;   // covers the rounding of the error terms' own sums
  const CertifiedCore& d = disks_[k][index];
  const bool rotates = moves_[k] && motion_[k] == Motion::Kind::rotation;
  const bool translates = moves_[k] && motion_[k] == Motion::Kind::translation;
  double error = 0;
  if (rotates) {
    // world = pivot + R (centre - pivot); |R - R_m| <= cs_error entrywise, |R_m| <= cs_size
    q.x = pivot_m_[k][0] + (p.c * d.rx_m - p.s * d.ry_m);
    q.y = pivot_m_[k][1] + (p.s * d.rx_m + p.c * d.ry_m);
    error = pivot_error_[k] + p.cs_error * d.magnitude + p.cs_size * d.r_error +
            4 * unit * (pivot_magnitude_[k] + p.cs_size * d.magnitude) + d.rho * p.angle;
  } else if (translates) {
    const double dx_m = direction_[k][0].lo, dy_m = direction_[k][1].lo;
    q.x = d.cx + p.shift * dx_m;
    q.y = d.cy + p.shift * dy_m;
    double shift = std::fabs(p.shift);
    error = shift * p.direction_error + 4 * unit * (std::max(std::fabs(d.cx), std::fabs(d.cy)) + 2 * shift) + p.travel +
            d.centre_error;
  } else {
    q.x = d.cx;
    q.y = d.cy;
    error = d.centre_error;
  }
  error = error * inflate + underflow;
  // may be negative: a pair is tested on the sum of its reaches
  q.reach = down(d.r - error);
  q.outer = up(d.r + error);
  q.index = index;
  return std::isfinite(q.reach) && std::isfinite(q.x) && std::isfinite(q.y);
}

// Does some pair of posed disks certainly overlap (the box is blocked)? Pairs of two boundary
// points (reach <= 0 both) never do.
bool BlockedTester::overlapping(const Posed& first, const Posed& second) {
  return overlapping(first.interior, second.interior) || overlapping(first.boundary, second.interior) ||
         overlapping(first.interior, second.boundary);
}

// Does some pair of posed disks certainly overlap (the box is blocked)?
bool BlockedTester::overlapping(const PosedSet& first, const PosedSet& second) {
  // A pair passes the certified test below only if |x_a - x_b| < reach_a + reach_b <=
  // 2 max(reach_a, reach_b) (exactly). So every pair that can pass is met by one of two
  // sweeps: each disk of A against the disks of B with |x_a - x_b| <= 2 reach_a, and each
  // disk of B against the disks of A with |x_b - x_a| <= 2 reach_b (the windows, slightly
  // widened, decide nothing: leaving a pair out can only keep the answer "not blocked"). A
  // pair's test is symmetric in a and b (the same roundings), so the answer is that of testing
  // every pair. (A window of reach_a + the widest reach of B, as before, let one large disk
  // widen every window.)
  if (!(first.widest + second.widest > 0)) return false;
  auto sweep = [](const PosedSet& from, const PosedSet& to) {
    const std::vector<double>& xs = to.xs;
    if (xs.empty()) return false;
    // (widened relatively to cover the roundings of the window ends)
    const double magnitude = std::max(std::fabs(xs.front()), std::fabs(xs.back()));
    const double reach_bound = 2 * (from.widest > 0 ? from.widest : 0) * (1 + 0x1p-40) + magnitude * 0x1p-40 + 0x1p-1000;
    // only disks with x in [x_to min - reach_bound, x_to max + reach_bound] can meet one
    const auto from_begin = std::lower_bound(from.xs.begin(), from.xs.end(), xs.front() - reach_bound);
    const auto from_end = std::upper_bound(from_begin, from.xs.end(), xs.back() + reach_bound);
    for (auto x = from_begin; x != from_end; ++x) {
      const PosedDisk& a = from.disks[static_cast<std::size_t>(x - from.xs.begin())];
      if (!(a.reach > 0)) continue;   // a pair with a larger partner is met from the partner
      const double span = 2 * a.reach * (1 + 0x1p-40) + std::fabs(a.x) * 0x1p-40 + 0x1p-1000;
      const double left = a.x - span, right = a.x + span;
      for (auto y = std::lower_bound(xs.begin(), xs.end(), left); y != xs.end() && *y <= right; ++y) {
        if (certifies(a, to.disks[static_cast<std::size_t>(y - xs.begin())])) return true;
      }
    }
    return false;
  };
  return sweep(first, second) || sweep(second, first);
}

// The sweep of overlapping(), collecting the pairs that can certify a box inside this one
// (may_certify_inside) until one certifies this box (then true, `out` incomplete).
bool BlockedTester::gather(const Posed& first, const Posed& second, std::vector<DiskPair>& out) {
  return gather(first.interior, second.interior, out) || gather(first.boundary, second.interior, out) ||
         gather(first.interior, second.boundary, out);
}

bool BlockedTester::gather(const PosedSet& first, const PosedSet& second, std::vector<DiskPair>& out) {
  // (`first` holds disks of part 0, `second` of part 1.) Every pair kept (may_certify_inside)
  // or certifying has |x_a - x_b| <= (outer_a + outer_b) (1 + 2^-21) + 2^-500 (the margins of
  // the double tests; outer >= 0) <= 2 max(outer_a, outer_b) (1 + 2^-21) + 2^-500. So two
  // sweeps meet every such pair exactly once: each disk a of A against the disks b of B with
  // outer_b <= outer_a in the window 2 outer_a, and each disk b of B against the disks a of A
  // with outer_a < outer_b in the window 2 outer_b (windows widened by more than the margins
  // and the window ends' rounding). (A window of outer_a + the widest outer of B, as before,
  // let one large disk — a gear's hub — widen every window to the whole part.) The pairs kept
  // are the same set; a list runs over the disks of A in groups (BlockedTester::blocked poses a
  // disk once per run of pairs that share it): the two sweeps' pairs are sorted by (first,
  // second) for that.
  // Where no disk is much wider than the rest (Geneva, escapement: the two sweeps would scan
  // about every pair twice), one sweep of A's disks in the window outer_a + the widest outer of
  // B meets the same pairs with less work, already in groups (each disk of A sweeps once), so
  // they are not sorted (Geneva: the sort was 6.7 M instructions of 623 M). Which sweep runs is
  // chosen by the windows' summed widths times the disks they scan; it decides only the work
  // and the list's order, never the set nor an answer (blocked() is "some pair certifies").
  if (first.disks.empty() || second.disks.empty()) return false;
  const std::size_t start = out.size();
  double widest_b = 0, sum_a = 0, sum_b = 0;
  for (const PosedDisk& a : first.disks) sum_a += a.outer;
  for (const PosedDisk& b : second.disks) sum_b += b.outer, widest_b = std::max(widest_b, b.outer);
  const auto count_a = static_cast<double>(first.disks.size()), count_b = static_cast<double>(second.disks.size());
  const double one_sweep = (sum_a + count_a * widest_b) * count_b;
  const double two_sweeps = 2 * (sum_a * count_b + sum_b * count_a);
  auto by_pair = [](const DiskPair& p, const DiskPair& q) {
    return p.first != q.first ? p.first < q.first : p.second < q.second;
  };
  if (one_sweep <= two_sweeps) {
    const std::vector<double>& xs = second.xs;
    const std::size_t n = xs.size();
    for (const PosedDisk& a : first.disks) {
      const double span = (a.outer + widest_b) * (1 + 0x1p-18) + std::fabs(a.x) * 0x1p-40 + 0x1p-400;
      if (!(span > 0)) continue;
      const double left = a.x - span, right = a.x + span;
      for (std::size_t j = static_cast<std::size_t>(std::lower_bound(xs.begin(), xs.end(), left) - xs.begin());
           j < n && xs[j] <= right; ++j) {
        const PosedDisk& b = second.disks[j];
        if (certifies(a, b)) return true;
        if (may_certify_inside(a, b)) out.push_back(DiskPair{a.index, b.index});
      }
    }
    // (grouped by A's disk already: each disk of A sweeps once, its pairs appended together;
    // no sort — the order of a list decides only the work, never an answer)
    return false;
  }
  auto sweep = [&](const PosedSet& from, const PosedSet& to, bool from_first) {
    const std::vector<double>& xs = to.xs;
    const std::size_t n = xs.size();
    for (const PosedDisk& p : from.disks) {
      const double span = 2 * p.outer * (1 + 0x1p-18) + std::fabs(p.x) * 0x1p-40 + 0x1p-400;
      if (!(span > 0)) continue;
      const double left = p.x - span, right = p.x + span;
      for (std::size_t j = static_cast<std::size_t>(std::lower_bound(xs.begin(), xs.end(), left) - xs.begin());
           j < n && xs[j] <= right; ++j) {
        const PosedDisk& q = to.disks[j];
        // each pair in one sweep only: the disk with the larger outer (ties: A's) sweeps
        if (from_first ? q.outer > p.outer : q.outer >= p.outer) continue;
        const PosedDisk& a = from_first ? p : q;
        const PosedDisk& b = from_first ? q : p;
        if (certifies(a, b)) return true;
        if (may_certify_inside(a, b)) out.push_back(DiskPair{a.index, b.index});
      }
    }
    return false;
  };
  if (sweep(first, second, true) || sweep(second, first, false)) return true;
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(start), out.end(), by_pair);
  return false;
}

// ---------------------------------------------------------------- the grid of one chart box

BlockedCells::BlockedCells(std::shared_ptr<const BlockedTester> tester, const ChartAxis& x, const ChartAxis& y,
                           int dimension, int depth, SharedPoses* shared, bool whole_tables)
    : tester_(tester && tester->usable() ? std::move(tester) : nullptr), x_axis_(x), y_axis_(y),
      dimension_(dimension), depth_(depth),
      x_{algebra::lower_double(x.lo), algebra::upper_double(x.hi)},
      y_{dimension == 2 ? algebra::Interval{algebra::lower_double(y.lo), algebra::upper_double(y.hi)}
                        : algebra::Interval{0, 0}} {
  if (depth_ < 0 || depth_ > 24) throw NumericError("blocked-space grid: depth out of range");
  whole_depth_ = dimension_ >= 1 ? whole_table_log2 / dimension_ : dense_cells_log2;
  for (int d = 0; d <= dense_cells_log2; ++d) {
    flat_[d] = zero_block();
    directory_[d] = zero_directory();
  }
  if (whole_tables && dimension_ >= 1 && tester_) {
    // every tabled depth one flat table, the depths one after the other in one zeroed
    // allocation (untested is 0): the cells' look-ups are the shallow depths' plain reads
    static_assert(untested == 0, "zeroed tables hold untested cells");
    whole_depth_ = whole_cells_log2 / dimension_;
    const std::size_t entries = whole_table_bytes(dimension_) / sizeof(std::int32_t);
    whole_.reset(static_cast<std::int32_t*>(std::calloc(entries, sizeof(std::int32_t))));   // zeros: untested
    if (!whole_) throw std::bad_alloc();
    block_bytes_ = entries * sizeof(std::int32_t);
    std::size_t at = 0;
    for (int d = 0; d <= whole_depth_; ++d) {
      flat_[d] = whole_.get() + at;
      at += std::size_t{1} << (d * dimension_);
    }
    // 2-D: the sides of the tabled depths (at most the grid's finest, whose cells the culls
    // test), 2 x 1 023 intervals at depth 9 (32 KB)
    const int sides_depth = dimension_ == 2 ? std::min(depth_, dense_cells_log2 / 2) : -1;
    for (int axis = 0; axis < 2 && sides_depth >= 0; ++axis) {
      sides_[axis].reserve((std::size_t{2} << sides_depth) - 1);
      for (int d = 0; d <= sides_depth; ++d)
        for (long k = 0; k < (1L << d); ++k) sides_[axis].push_back(axis == 0 ? side_x(d, k) : side_y(d, k));
    }
    sides_depth_ = sides_depth;
  }
  // (a pose is found by the cell's column or row index, a pure function of the box side the
  // axis's cells cut: the side is part of the pool's key with the axis)
  if (shared && tester_ && dimension_ == 2)
    for (int k = 0; k < 2; ++k) {
      const int use = tester_->axis_of(k);
      const algebra::Interval& side = use == 1 ? y_ : x_;
      cache_.share(k, shared->part(tester_, k, use, use == 1 ? y_axis_ : x_axis_, side.lo, side.hi));
    }
}

std::shared_ptr<BlockedTester::Cache::Part> SharedPoses::part(const std::shared_ptr<const BlockedTester>& tester, int k,
                                                              int use, const ChartAxis& axis, double lo, double hi) {
  // a fixed part's pose depends on no axis: one entry per part
  const bool fixed = use < 0;
  auto same = [&](const Entry& e) {
    return e.tester == tester && e.k == k && e.use == use &&
           (fixed || (e.kind == axis.kind && e.half_turn == axis.half_turn &&
                      std::bit_cast<std::uint64_t>(e.lo) == std::bit_cast<std::uint64_t>(lo) &&
                      std::bit_cast<std::uint64_t>(e.hi) == std::bit_cast<std::uint64_t>(hi)));
  };
  for (std::size_t m = 0; m < entries_.size(); ++m)
    if (same(entries_[m])) {
      // the most recently used last
      Entry found = std::move(entries_[m]);
      entries_.erase(entries_.begin() + static_cast<std::ptrdiff_t>(m));
      entries_.push_back(std::move(found));
      ++reused_;
      return entries_.back().part;
    }
  // at most kept_ entries of part k: the least recently used goes
  std::size_t of_k = 0;
  for (const Entry& e : entries_) of_k += e.k == k;
  if (of_k >= kept_)
    for (std::size_t m = 0; m < entries_.size(); ++m)
      if (entries_[m].k == k) {
        entries_.erase(entries_.begin() + static_cast<std::ptrdiff_t>(m));
        break;
      }
  if (kept_ == 0) return std::make_shared<BlockedTester::Cache::Part>();
  entries_.push_back(Entry{tester, k, use, axis.kind, axis.half_turn, lo, hi,
                           std::make_shared<BlockedTester::Cache::Part>()});
  return entries_.back().part;
}

namespace {
// Side k of 2^depth equal parts of [whole]: the ends are the doubles lo + width * k (the same
// expression for the cells on either side of a cut, so the cells of one depth tile the whole
// interval). The cells of depth d + 1 must also tile their parents exactly (a cell inside a
// blocked cell is blocked without a test; a child's candidates are its parent's list), so the
// cut k of depth d and the cut 2k of depth d + 1 must be the same double. They are when every
// width is exactly half the one above (a normal double: whole widths >= 2^-960, depths <= 62):
// the products width * k are then the same real number, rounded alike. A narrower box (cells
// below the smallest normal double, models at ~10^-305 and below: the halving rounds, a child
// then reached past its parent; a point box) or one whose width or ends are beyond the doubles
// (NaN or reversed cells) is cut on a copy scaled by an exact 2^e (ends clamped to the finite
// doubles), where the widths are normal: each cut is a monotone function (x 2^-e, rounded; held
// inside the box) of a scaled cut that is the same real number at every depth, so the children
// tile their parents exactly (cells may shrink to points there, never leave a gap). Session 56
// (scale56); the common case stays inline (the Geneva's C-space asks ~700 000 sides).
[[gnu::noinline]] algebra::Interval part_of_scaled(const algebra::Interval& whole, int depth, long k) {
  const long count = 1L << depth;
  if (!(whole.lo <= whole.hi) || depth > 62)
    throw NumericError("blocked-space grid: a cell of a box that is not an interval, or deeper than 62");
  const double largest = std::numeric_limits<double>::max();
  const double lo = std::max(whole.lo, -largest), hi = std::min(whole.hi, largest);
  // 2^e brings the larger end to [2^1020, 2^1021): the scaled width is finite and, at least the
  // ends' spacing 2^968, stays normal when divided by 2^62
  const double larger = std::max(std::fabs(lo), std::fabs(hi));
  const int exponent = larger > 0 ? 1020 - std::ilogb(larger) : 0;
  const double scaled_lo = std::ldexp(lo, exponent), scaled_hi = std::ldexp(hi, exponent);
  const double width = (scaled_hi - scaled_lo) / static_cast<double>(count);
  auto cut = [&](long m) {
    if (m == 0) return whole.lo;
    if (m == count) return whole.hi;
    return std::clamp(std::ldexp(scaled_lo + width * static_cast<double>(m), -exponent), whole.lo, whole.hi);
  };
  return {cut(k), cut(k + 1)};
}

inline algebra::Interval part_of(const algebra::Interval& whole, int depth, long k) {
  const double span = whole.hi - whole.lo;
  if (!(span >= 0x1p-960 && span <= std::numeric_limits<double>::max())) [[unlikely]]
    return part_of_scaled(whole, depth, k);
  const long count = 1L << depth;
  const double width = span / static_cast<double>(count);
  return {k == 0 ? whole.lo : whole.lo + width * static_cast<double>(k),
          k + 1 == count ? whole.hi : whole.lo + width * static_cast<double>(k + 1)};
}
}  // namespace

namespace {
// The tables' shared zeros: the block of every cell of a tabled depth not yet written, and the
// directory of a depth with no block yet (only read, never written through: a write makes the
// depth's own directory and the cell's block first).
constexpr std::size_t largest_block = std::size_t{1} << BlockedCells::whole_table_log2;
constexpr int directory_log2 = 10;   // 2-D depth 9 in 16 x 16 squares, 1-D depth 18 in runs of 256
static_assert(BlockedCells::whole_table_log2 >= 2 * BlockedCells::table_block_log2);
static_assert(2 * (9 - BlockedCells::block_side_log2(2, 9)) <= directory_log2 &&
              18 - BlockedCells::block_side_log2(1, 18) <= directory_log2);
}  // namespace

const std::int32_t BlockedCells::zero_entries_[largest_block] = {};

std::int32_t* const* BlockedCells::zero_directory() {
  static const auto directory = [] {
    std::array<std::int32_t*, std::size_t{1} << directory_log2> pointers;
    pointers.fill(zero_block());
    return pointers;
  }();
  return directory.data();
}

algebra::Interval BlockedCells::side_x(int depth, long i) const { return part_of(x_, depth, i); }

algebra::Interval BlockedCells::side_y(int depth, long j) const {
  return dimension_ == 2 ? part_of(y_, depth, j) : y_;
}

namespace {
long cell_key(int depth, long i, long j) { return (static_cast<long>(depth) << 56) | (i << 28) | j; }
}  // namespace

bool BlockedCells::enclose(const algebra::Interval& x, const algebra::Interval& y,
                           std::shared_ptr<const std::vector<BlockedTester::DiskPair>> pairs) {
  if (!tester_ || !pairs || dimension_ != 2) return false;
  // the grid's box (every cell lies inside it) inside the list's box, compared exactly
  if (!(x.lo <= x_.lo && x_.hi <= x.hi && y.lo <= y_.lo && y_.hi <= y.hi)) return false;
  enclosing_ = std::move(pairs);
  return true;
}

std::int32_t BlockedCells::known_deep(int depth, long i, long j) const {
  const auto it = known_.find(cell_key(depth, i, j));
  return it == known_.end() ? untested : it->second;
}

std::int32_t& BlockedCells::make_slot(int depth, long i, long j) {
  static_assert(untested == 0, "a block of zeros holds untested cells");
  auto make_block = [&](std::size_t cells) {
    blocks_.push_back(std::make_unique<std::int32_t[]>(cells));   // value-initialized: untested
    block_bytes_ += cells * sizeof(std::int32_t);
    return blocks_.back().get();
  };
  if (depth <= whole_depth_) {
    std::int32_t*& table = flat_[depth];
    if (table == zero_block()) table = make_block(std::size_t{1} << (depth * dimension_));
    return table[static_cast<std::size_t>(dimension_ == 2 ? (i << depth) | j : i)];
  }
  const int b = dimension_ == 2 ? table_block_log2 : 2 * table_block_log2;
  auto& own = own_directory_[depth];
  if (!own) {
    const std::size_t blocks = std::size_t{1} << ((depth - b) * dimension_);
    own = std::make_unique_for_overwrite<std::int32_t*[]>(blocks);
    std::fill_n(own.get(), blocks, zero_block());
    directory_[depth] = own.get();
  }
  std::int32_t*& block = own[static_cast<std::size_t>(dimension_ == 2 ? ((i >> b) << (depth - b)) | (j >> b) : i >> b)];
  if (block == zero_block()) block = make_block(std::size_t{1} << (b * dimension_));
  const long m = (1L << b) - 1;
  return block[static_cast<std::size_t>(dimension_ == 2 ? ((i & m) << b) | (j & m) : i & m)];
}

std::size_t BlockedCells::table_bytes() const {
  std::size_t bytes = block_bytes_;
  const int b = dimension_ == 2 ? table_block_log2 : 2 * table_block_log2;
  for (int depth = 0; depth <= dense_cells_log2; ++depth)
    if (own_directory_[depth]) bytes += (std::size_t{1} << ((depth - b) * dimension_)) * sizeof(std::int32_t*);
  return bytes;
}

void BlockedCells::remember(int depth, long i, long j, std::int32_t entry) {
  if (dense(depth, i, j)) {
    dense_slot(depth, i, j) = entry;
    return;
  }
  known_.emplace(cell_key(depth, i, j), entry);
}

bool BlockedCells::blocked(int depth, long i, long j) {
  if (!tester_) return false;
  // a cell inside a cell already known to be blocked is blocked (no test); the parent is only
  // looked up, never tested on the way. The nearest tested ancestor with a candidate list
  // gives the pairs to test (every pair that can certify this cell is in it).
  bool result = false;
  const std::vector<BlockedTester::DiskPair>* candidates = nullptr;
  auto see = [&](std::int32_t parent) {
    if (parent == untested) return;
    if (parent == is_blocked) result = true;
    else if (!candidates && parent >= first_list) candidates = &lists_[static_cast<std::size_t>(parent - first_list)];
  };
  std::int32_t* own = nullptr;   // the cell's entry in its depth's table (a dense cell)
  if (dense(depth, i, j)) {
    // the cell and its ancestors (their indices are in range too) read from the tables
    own = &dense_slot(depth, i, j);
    if (*own != untested) return *own == is_blocked;
    // (the tables by depth, the deep ones through their directories, then the flat ones; a depth
    // or block never written reads the shared zeros: untested)
    int up = 1;
    if (dimension_ == 2) {
      for (; up <= depth && depth - up > whole_depth_ && !result; ++up) see(deep_entry_2d(depth - up, i >> up, j >> up));
      for (; up <= depth && !result; ++up)
        see(flat_[depth - up][static_cast<std::size_t>(((i >> up) << (depth - up)) | (j >> up))]);
    } else {
      for (; up <= depth && depth - up > whole_depth_ && !result; ++up) see(deep_entry_1d(depth - up, i >> up));
      for (; up <= depth && !result; ++up) see(flat_[depth - up][static_cast<std::size_t>(i >> up)]);
    }
  } else {
    const std::int32_t entry = known(depth, i, j);
    if (entry != untested) return entry == is_blocked;
    for (int up = 1; up <= depth && !result; ++up) see(known(depth - up, i >> up, dimension_ == 2 ? j >> up : j));
  }
  // (no listed ancestor: the enclosing box's list, when the grid has one)
  if (!result && !candidates && enclosing_) candidates = enclosing_.get();
  std::int32_t answer = is_blocked;
  if (!result) {
    ++tests_;
    if (candidates) pairs_tested_ += candidates->size();
    // the cells below the finest depth any caller tests (the builder's windows, the curve
    // generator's pairs to depth 9 at least) need no list
    const bool keep_list = depth < std::max(depth_, 9);
    // (gathered in a scratch list kept by the thread, then stored at its exact size: one
    // allocation per kept list instead of the growth of a new vector and its shrink)
    thread_local std::vector<BlockedTester::DiskPair> narrowed;
    const BlockedTester::GridCell cell{depth, i, dimension_ == 2 ? j : 0};
    result = tester_->blocked(x_axis_, y_axis_, cell_x(depth, i), cell_y(depth, j), cache_, candidates,
                              keep_list ? &narrowed : nullptr, &cell);
    if (result) {
      answer = is_blocked;
    } else if (keep_list) {
      answer = first_list + static_cast<std::int32_t>(lists_.size());
      lists_.emplace_back(narrowed.begin(), narrowed.end());
    } else {
      answer = not_blocked;
    }
  }
  // (`own` stays valid: a block is made once and never moves)
  if (own) *own = answer;
  else remember(depth, i, j, answer);
  return result;
}

}  // namespace hipair::cspace
