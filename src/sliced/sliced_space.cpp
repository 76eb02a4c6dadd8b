// The sliced 3-D C-space of a free (planar) part against a fixed part (include/hipair/sliced.hpp):
// slices through the translating-pair C-space (hipair::CSpace on the circle–segment stage),
// critical angles (critical_angles.hpp), representative slices, connections of free cells
// across critical angles, point location and connectivity.
#include <hipair/sliced.hpp>

#include <hipair/error.hpp>
#include <hipair/overlap.hpp>

#include "sliced/critical_angles.hpp"
#include "sliced/motion.hpp"
#include "sliced/nearby.hpp"
#include "core/exact_sqrt.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <numeric>
#include <set>
#include <sstream>

namespace hipair {

namespace algebra = cspace::algebra;
using algebra::Real;

double SlicedAngle::radians() const {
  if (half_turn) return 3.141592653589793;
  return 2 * std::atan(to_double(t));
}

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::string quoted(const Rational& r) {
  std::string out = "\"";
  out += to_exact_string(r);
  out += '"';
  return out;
}
std::string point_json(const Rational& x, const Rational& y) {
  std::string out = "[";
  out += quoted(x);
  out += ", ";
  out += quoted(y);
  out += ']';
  return out;
}

// The loops of `part` moved by p -> pivot + R (p - pivot), as model JSON.
std::string loops_json(const Part& part, const Point& pivot, const Rational& c, const Rational& s) {
  auto map = [&](const Point& p) {
    Rational dx = p.x - pivot.x, dy = p.y - pivot.y;
    return Point{Rational(pivot.x + c * dx - s * dy), Rational(pivot.y + s * dx + c * dy)};
  };
  std::string out;
  for (std::size_t l = 0; l < part.loops.size(); ++l) {
    const Loop& loop = part.loops[l];
    if (l > 0) out += ", ";
    if (loop.edges.size() == 1 && loop.edges[0].is_full_circle()) {
      auto r = rational_sqrt(loop.edges[0].radius_squared);
      if (!r)
        throw GeometryError("part '" + part.name + "': a full circle of irrational radius (" + loop.edges[0].pointer +
                            ") cannot be sliced exactly");
      Point centre = map(loop.edges[0].center);
      out += R"({ "circle": { "center": )" + point_json(centre.x, centre.y) + R"(, "radius": )" + quoted(*r) + " } }";
      continue;
    }
    Point start = map(loop.edges[0].source);
    out += R"({ "start": )" + point_json(start.x, start.y) + R"(, "edges": [)";
    for (std::size_t k = 0; k < loop.edges.size(); ++k) {
      const Edge& e = loop.edges[k];
      Point to = map(e.target);
      out += k ? ", " : " ";
      if (e.is_arc()) {
        Point centre = map(e.center);
        out += R"({ "arc_to": )" + point_json(to.x, to.y) + R"(, "center": )" + point_json(centre.x, centre.y) +
               R"(, "dir": ")" + (e.ccw ? "ccw" : "cw") + "\" }";
      } else {
        out += R"({ "line_to": )" + point_json(to.x, to.y) + " }";
      }
    }
    out += " ] }";
  }
  return out;
}

// An upper bound of max |p - pivot|_inf over the part's points... (L1 norms of vertices,
// centres plus radii; rational).
Rational reach(const Part& part, const Point& pivot) {
  Rational best = 0;
  for (const auto& loop : part.loops)
    for (const auto& e : loop.edges) {
      Rational v = abs(e.source.x - pivot.x) + abs(e.source.y - pivot.y);
      if (v > best) best = v;
      if (e.is_arc()) {
        Rational r_bound = e.radius_squared > 1 ? e.radius_squared : Rational(1);   // r <= max(1, r^2)
        Rational w = abs(e.center.x - pivot.x) + abs(e.center.y - pivot.y) + r_bound;
        if (w > best) best = w;
      }
    }
  return best;
}

struct UnionFind {
  std::vector<std::size_t> parent;
  std::size_t add() {
    parent.push_back(parent.size());
    return parent.size() - 1;
  }
  std::size_t find(std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::size_t a, std::size_t b) { parent[find(a)] = find(b); }
};

std::string kind_name(FeatureKind k) { return k == FeatureKind::vertex ? "vertex" : k == FeatureKind::arc ? "arc" : "segment"; }

bool has_arc(const Part& part) {
  for (const auto& loop : part.loops)
    for (const auto& e : loop.edges)
      if (e.is_arc()) return true;
  return false;
}

}  // namespace

// Is the part invariant under every rotation about some point: every loop a full circle, all
// with one centre (exact)?
bool round_free_part(const Part& part) {
  const Point* centre = nullptr;
  for (const auto& loop : part.loops)
    for (const auto& e : loop.edges) {
      if (!e.is_full_circle()) return false;
      if (centre && !(e.center.x == centre->x && e.center.y == centre->y)) return false;
      centre = &e.center;
    }
  return centre != nullptr;
}

struct SlicedSpace::Impl {
  Model model;
  std::size_t fixed = 0, free = 0;
  std::string fixed_name, free_name;
  Rational bound;
  SlicedBuildOptions options;
  std::optional<sliced::PolygonalPair> pair;
  std::optional<sliced::MotionChecker> motion;
  std::vector<sliced::Critical> critical;
  std::vector<CriticalAngle> critical_public;
  std::vector<SlicedInterval> intervals;
  std::vector<SlicedCrossing> crossings;
  std::vector<std::map<std::string, std::size_t>> keys;   // per interval: cell key -> free cell
  std::size_t component_count = 0;
  mutable SlicedStatistics stats;
  mutable std::mutex mutex;
  mutable std::map<std::string, std::shared_ptr<const CSpace>> cache;

  // ------------------------------------------------------------ slices
  std::shared_ptr<const CSpace> slice(const SlicedAngle& angle) const {
    std::string key = angle.half_turn ? "pi" : to_exact_string(angle.t);
    {
      std::lock_guard<std::mutex> lock(mutex);
      auto it = cache.find(key);
      if (it != cache.end()) return it->second;
    }
    auto start = Clock::now();
    auto [c, s] = sliced::rotation_of(angle);
    const Part& a = model.parts[fixed];
    const Part& b = model.parts[free];
    std::string limits = "[" + quoted(-bound) + ", " + quoted(bound) + "]";
    // the slice's parts carry the pair's names (legends and labels read "plate ... / peg ...")
    auto json_string = [](const std::string& name) {
      std::string out = "\"";
      for (char ch : name) {
        if (ch == '"' || ch == '\\') out += '\\';
        if (static_cast<unsigned char>(ch) >= 0x20) out += ch;
      }
      return out + "\"";
    };
    const std::string first = json_string(a.name), second = json_string(b.name);
    std::string text = R"({ "hipair": 1, "name": "slice", "parts": [
      { "name": )" + first + R"(, "motion": { "translation": { "direction": [-1, 0], "limits": )" +
                       limits + R"( } }, "loops": [ )" + loops_json(a, b.motion.pivot, Rational(1), Rational(0)) + R"( ] },
      { "name": )" + second + R"(, "motion": { "translation": { "direction": [0, 1], "limits": )" +
                       limits + R"( } }, "loops": [ )" + loops_json(b, b.motion.pivot, c, s) + R"( ] } ],
      "pairs": [ { "parts": [)" + first + ", " + second + R"(] } ] })";
    Model slice_model;
    try {
      slice_model = read_model(text, "<slice>");
    } catch (const ModelError& e) {
      // the slice's posed coordinates exceed what the model format holds (4096-bit rationals:
      // a part of 10^-300 mm beside one of millimetres, turned by an angle of hundreds of
      // bits): one message naming the pair and the reason, not a pointer into a model the
      // user never wrote
      throw GeometryError("pair '" + a.name + "' / '" + b.name + "': the translational slice at the angle " +
                          std::to_string(angle.radians()) + " rad cannot be built exactly (" + e.what() +
                          " in the slice's posed coordinates: lengths of very different scales in one pair)");
    }
    auto space = std::make_shared<const CSpace>(CSpace::build(slice_model, a.name, b.name));
    std::lock_guard<std::mutex> lock(mutex);
    ++stats.slices_built;
    stats.seconds_slices += seconds_since(start);
    cache.emplace(key, space);
    return space;
  }

  // Does the free part at offset q stay apart from the fixed part while it turns through the
  // half-angle range [u_lo, u_hi] (chart about pi when `flip`)? Polygonal pairs: no contact
  // line passes q (steady_along); pairs with arcs: the pure rotation is certified free (exact).
  bool steady(const Point& q, const Rational& u_lo, const Rational& u_hi, bool flip) const {
    if (pair) return sliced::steady_along(*pair, q, u_lo, u_hi, flip);
    sliced::StraightMotion m{q.x, q.y, u_lo, q.x, q.y, u_hi, flip, {}};
    for (Rational* r : {&m.x0, &m.y0, &m.w0, &m.x1, &m.y1, &m.w1}) r->canonicalize();
    sliced::MotionResult r = motion->first_contact(m);
    return r.starts_apart && !r.found;
  }

  // ------------------------------------------------------------ cells of a slice
  static std::string cell_key(const CSpace& space, std::size_t cell) {
    std::set<std::string> labels;
    for (std::size_t e : space.cells()[cell].boundary)
      for (std::size_t f : space.edges()[e].curves) {
        const FeaturePair& fp = space.feature_pairs()[f];
        auto name = [](const std::string& part, const FeatureIdentity& id) {
          return part + " " + kind_name(id.kind) + " loop " + std::to_string(id.loop) + " edge " + std::to_string(id.edge);
        };
        labels.insert(name(fp.first_part, fp.first) + " / " + name(fp.second_part, fp.second));
      }
    std::string key;
    for (const auto& l : labels) {
      if (!key.empty()) key += "; ";
      key += l;
    }
    return key.empty() ? "(no contact)" : key;
  }

  // free cells of a slice: cell index -> key
  static std::vector<std::pair<std::size_t, std::string>> free_cells(const CSpace& space) {
    std::vector<std::pair<std::size_t, std::string>> out;
    for (std::size_t c = 0; c < space.cells().size(); ++c)
      if (space.cells()[c].kind == CellKind::free) out.emplace_back(c, cell_key(space, c));
    return out;
  }

  // The free cell of interval `interval` that the slice cell corresponds to.
  std::size_t match(std::size_t interval, const CSpace& space, std::size_t cell) const {
    std::string key = cell_key(space, cell);
    auto it = keys[interval].find(key);
    if (it == keys[interval].end())
      throw GeometryError("3-DOF pair '" + fixed_name + "'/'" + free_name + "': a free cell (" + key +
                          ") has no counterpart in the representative slice of interval " + std::to_string(interval) +
                          " (an unlisted critical angle)");
    return it->second;
  }

  // ------------------------------------------------------------ location
  SlicedLocation::Kind classify(const CSpace& space, const Rational& x, const Rational& y, std::size_t* cell) const {
    *cell = no_index;
    if (abs(x) >= bound || abs(y) >= bound) return SlicedLocation::Kind::free;   // outside the box: apart
    Location l = space.locate(ChartPoint{0, x, y});
    switch (l.kind) {
      case Location::Kind::free:
        *cell = l.cell;
        return SlicedLocation::Kind::free;
      case Location::Kind::blocked: return SlicedLocation::Kind::blocked;
      case Location::Kind::touching: return SlicedLocation::Kind::contact;
      case Location::Kind::edge:
      case Location::Kind::vertex:
        if (l.cell == no_index) return SlicedLocation::Kind::contact;
        if (space.cells()[l.cell].kind == CellKind::free) {
          *cell = l.cell;
          return SlicedLocation::Kind::free;
        }
        return space.cells()[l.cell].kind == CellKind::blocked ? SlicedLocation::Kind::blocked : SlicedLocation::Kind::contact;
      case Location::Kind::outside: break;
    }
    throw GeometryError("internal: a configuration inside the slice box located outside the slice");
  }

  // The free cell of the slice holding (x, y) outside the box: the cell touching the box.
  static std::size_t outer_cell(const CSpace& space) {
    const Rational& lo = space.charts()[0].x_lo;
    // a point just inside the box corner is free (the box exceeds the blocked region)
    Location l = space.locate(ChartPoint{0, lo + Rational(1, 2), space.charts()[0].y_lo + Rational(1, 2)});
    if (l.kind != Location::Kind::free) throw GeometryError("internal: the slice box corner is not free");
    return l.cell;
  }

  // Position of a rational angle: (interval, false) or (critical index, true).
  std::pair<std::size_t, bool> position(const SlicedAngle& angle) const {
    const std::size_t n = critical.size();
    if (n == 0) return {0, false};
    if (angle.half_turn) {
      if (critical.back().half_turn) return {n - 1, true};
      return {n - 1, false};
    }
    std::size_t below = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (critical[i].half_turn) continue;
      int c = critical[i].t.compare(angle.t);   // sign of critical - t
      if (c == 0) return {i, true};
      if (c < 0) ++below;
    }
    if (below == 0) return {n - 1, false};
    return {below - 1, false};
  }

  // A rational angle just after critical angle i with the half-angle range to it (u range and
  // chart flip), narrowed by `halvings`.
  struct Near {
    SlicedAngle left, right;
    Rational u_lo, u_hi;
    bool flip = false;
  };
  Near near(std::size_t i, int halvings) const {
    const sliced::Critical& c = critical[i];
    Near out;
    Rational width = Rational(1) / Rational(mpz_class(1) << (10 + 2 * halvings));
    auto separated = [&](const Rational& lo, const Rational& hi) {
      for (std::size_t k = 0; k < critical.size(); ++k) {
        if (k == i || critical[k].half_turn) continue;
        if (critical[k].t.compare(lo) >= 0 && critical[k].t.compare(hi) <= 0) return false;
      }
      return true;
    };
    if (c.half_turn) {
      // every other critical angle must lie in (-1/d, 1/d)
      Rational d = width;
      for (std::size_t k = 0; k < critical.size(); ++k)
        while (!critical[k].half_turn && (critical[k].t.compare(-1 / d) <= 0 || critical[k].t.compare(1 / d) >= 0)) d /= 2;
      out.flip = true;
      out.u_lo = -d;
      out.u_hi = d;
      out.left.t = 1 / d;      // theta just below pi: u = -1/t = -d
      out.right.t = -1 / d;    // just above -pi: u = d
      return out;
    }
    Real t = c.t;
    Rational lo, hi;
    if (t.exact) {
      Rational d = width;
      while (!separated(t.lower - d, t.lower + d)) d /= 2;
      lo = t.lower - d;
      hi = t.lower + d;
    } else {
      algebra::refine_dyadically(t, width);
      while (!t.exact && !separated(t.lower, t.upper)) algebra::refine_dyadically(t, (t.upper - t.lower) / 4);
      if (t.exact) {
        Rational d = width;
        while (!separated(t.lower - d, t.lower + d)) d /= 2;
        lo = t.lower - d;
        hi = t.lower + d;
      } else {
        lo = t.lower;
        hi = t.upper;
      }
    }
    out.u_lo = lo;
    out.u_hi = hi;
    out.left.t = lo;
    out.right.t = hi;
    return out;
  }

  // ------------------------------------------------------------ the structure
  void build_structure() {
    auto start = Clock::now();
    sliced::CriticalStatistics cs;
    if (round_free_part(model.parts[free])) {
      // A disc (or concentric rings) turning about its pivot only moves its centre: the slice at
      // theta is the slice at 0 translated by (c - pivot) - R(theta)(c - pivot). Its contact
      // structure never changes: no critical angle, whatever the fixed part (arcs included).
    } else if (has_arc(model.parts[fixed]) || has_arc(model.parts[free])) {
      if (options.progress) options.progress("critical angles");
      critical = sliced::critical_angles_with_arcs(model.parts[fixed], model.parts[free], cs);
    } else {
      pair = sliced::polygonal_pair(model.parts[fixed], model.parts[free]);
      if (options.progress) options.progress("critical angles");
      critical = sliced::critical_angles(*pair, cs);
    }
    stats.candidate_polynomials = cs.polynomials;
    stats.candidate_roots = cs.roots;
    stats.irrelevant_roots = cs.irrelevant;
    stats.seconds_critical = seconds_since(start);
    for (const auto& c : critical) {
      CriticalAngle out;
      out.half_turn = c.half_turn;
      out.events = c.events;
      if (c.half_turn) {
        out.degrees = 180;
      } else {
        out.t.polynomial = c.t.polynomial;
        out.t.lower = c.t.lower;
        out.t.upper = c.t.upper;
        out.t.exact = c.t.exact;
        out.degrees = 2 * std::atan(c.t.approximate()) * 180 / 3.141592653589793;
      }
      critical_public.push_back(std::move(out));
    }
    // intervals and representatives
    const std::size_t n = critical.size();
    std::size_t count = std::max<std::size_t>(n, 1);
    intervals.resize(count);
    keys.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      SlicedInterval& in = intervals[i];
      if (n == 0) {
        in.representative.t = 0;
      } else {
        in.lower_critical = i;
        in.upper_critical = (i + 1) % n;
        const auto& L = critical[i];
        const auto& U = critical[(i + 1) % n];
        if (L.half_turn && U.half_turn) {
          in.representative.t = 0;
        } else if (L.half_turn) {
          mpz_class f;
          mpz_fdiv_q(f.get_mpz_t(), U.t.lower.get_num_mpz_t(), U.t.lower.get_den_mpz_t());
          in.representative.t = Rational(f - 1);
        } else if (U.half_turn || i + 1 == n) {
          mpz_class f;
          mpz_cdiv_q(f.get_mpz_t(), L.t.upper.get_num_mpz_t(), L.t.upper.get_den_mpz_t());
          in.representative.t = Rational(f + 1);
        } else {
          in.representative.t = algebra::rational_between(L.t, U.t);
        }
      }
      if (options.progress) options.progress("slice " + std::to_string(i + 1) + " of " + std::to_string(count));
      auto space = slice(in.representative);
      for (const auto& [cell, key] : free_cells(*space)) {
        if (!keys[i].emplace(key, in.free_cells.size()).second)
          throw GeometryError("3-DOF pair '" + fixed_name + "'/'" + free_name +
                              "': two free cells of one slice have the same contacts (" + key + "); cannot match slices");
        in.free_cells.push_back(SlicedInterval::Cell{cell, key, no_index});
      }
    }
    // crossings
    UnionFind uf;
    std::vector<std::size_t> first_node(count);
    for (std::size_t i = 0; i < count; ++i) {
      first_node[i] = uf.parent.size();
      for (std::size_t k = 0; k < intervals[i].free_cells.size(); ++k) uf.add();
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (options.progress) options.progress("crossing " + std::to_string(i + 1) + " of " + std::to_string(n));
      SlicedCrossing crossing;
      crossing.critical = i;
      crossing.left_interval = (i + n - 1) % n;
      crossing.right_interval = i;
      std::set<std::size_t> left_done, right_done;
      std::map<std::pair<std::size_t, std::size_t>, SlicedConnection> links;
      const std::size_t left_count = intervals[crossing.left_interval].free_cells.size();
      const std::size_t right_count = intervals[crossing.right_interval].free_cells.size();
      for (int round = 0; round < 4 && (left_done.size() < left_count || right_done.size() < right_count); ++round) {
        Near nr = near(i, round);
        auto ls = slice(nr.left), rs = slice(nr.right);
        // each free cell's sample, and the same nudged off the contact lines through it
        std::vector<Point> samples;
        for (const auto* space : {ls.get(), rs.get()})
          for (const auto& cell : space->cells())
            if (cell.kind == CellKind::free)
              for (const Rational& e : {Rational(0), Rational(1, 1009), Rational(-1, 10007)}) {
                samples.push_back(Point{Rational(cell.sample_x + e), Rational(cell.sample_y + e * Rational(13, 10))});
              }
        std::size_t before = links.size();
        for (const auto& q : samples) {
          std::size_t lc = no_index, rc = no_index;
          if (classify(*ls, q.x, q.y, &lc) != SlicedLocation::Kind::free) continue;
          if (!steady(q, nr.u_lo, nr.u_hi, nr.flip)) continue;
          if (classify(*rs, q.x, q.y, &rc) != SlicedLocation::Kind::free)
            throw GeometryError("internal: a configuration steady across a critical angle is not free on both sides");
          if (lc == no_index) lc = outer_cell(*ls);
          if (rc == no_index) rc = outer_cell(*rs);
          std::size_t a = match(crossing.left_interval, *ls, lc), b = match(crossing.right_interval, *rs, rc);
          left_done.insert(a);
          right_done.insert(b);
          SlicedConnection link{a, b, SlicedConfiguration{q.x, q.y, nr.left}, SlicedConfiguration{q.x, q.y, nr.right}, nr.flip};
          link.left_witness.angle.t.canonicalize();   // (dyadic refinement leaves fractions unreduced)
          link.right_witness.angle.t.canonicalize();
          links.emplace(std::make_pair(a, b), link);
        }
        if (round >= 1 && links.size() == before) break;   // the rest end or start here
      }
      for (const auto& [ab, link] : links) {
        const auto [a, b] = ab;
        crossing.connections.push_back(link);
        uf.unite(first_node[crossing.left_interval] + a, first_node[crossing.right_interval] + b);
      }
      for (std::size_t a = 0; a < left_count; ++a)
        if (!left_done.count(a)) crossing.ending.push_back(a);
      for (std::size_t b = 0; b < right_count; ++b)
        if (!right_done.count(b)) crossing.starting.push_back(b);
      crossings.push_back(std::move(crossing));
    }
    std::map<std::size_t, std::size_t> numbering;
    for (std::size_t i = 0; i < count; ++i)
      for (std::size_t k = 0; k < intervals[i].free_cells.size(); ++k) {
        std::size_t root = uf.find(first_node[i] + k);
        auto it = numbering.emplace(root, numbering.size()).first;
        intervals[i].free_cells[k].component = it->second;
      }
    component_count = numbering.size();
  }

  // The free cell (interval, cell) of a free configuration (structure built).
  std::pair<std::size_t, std::size_t> node_of(const SlicedConfiguration& q) const {
    auto [index, critical_angle] = position(q.angle);
    Point p{q.x, q.y};
    if (!critical_angle) {
      auto space = slice(q.angle);
      std::size_t cell = no_index;
      if (classify(*space, q.x, q.y, &cell) != SlicedLocation::Kind::free) return {no_index, no_index};
      if (cell == no_index) cell = outer_cell(*space);
      return {index, match(index, *space, cell)};
    }
    // on a critical angle: follow the configuration's offset into the next interval, along
    // angles where it certainly stays free
    {
      auto space = slice(q.angle);
      std::size_t cell = no_index;
      if (classify(*space, q.x, q.y, &cell) != SlicedLocation::Kind::free) return {no_index, no_index};
    }
    for (int round = 0; round < 40; ++round) {
      Near nr = near(index, round);
      Rational u_lo = nr.flip ? Rational(0) : q.angle.t;
      if (steady(p, u_lo, nr.u_hi, nr.flip)) {
        auto space = slice(nr.right);
        std::size_t cell = no_index;
        if (classify(*space, q.x, q.y, &cell) != SlicedLocation::Kind::free)
          throw GeometryError("internal: a configuration steady off a critical angle is not free");
        if (cell == no_index) cell = outer_cell(*space);
        return {index, match(index, *space, cell)};
      }
    }
    throw GeometryError("3-DOF pair: no certified free motion off the critical angle at this configuration");
  }
};

SlicedSpace SlicedSpace::build(const Model& model, std::string_view fixed_part, std::string_view free_part,
                               const SlicedBuildOptions& options) {
  auto start = Clock::now();
  auto impl = std::make_shared<Impl>();
  impl->model = model;
  auto fixed = model.find_part(fixed_part);
  auto free = model.find_part(free_part);
  if (!fixed) throw ModelError("", "no part named '" + std::string(fixed_part) + "'");
  if (!free) throw ModelError("", "no part named '" + std::string(free_part) + "'");
  const Part& a = model.parts[*fixed];
  const Part& b = model.parts[*free];
  if (a.motion.kind != Motion::Kind::fixed)
    throw GeometryError("3-DOF pair: part '" + a.name + "' (" + a.pointer + ") must be fixed");
  if (b.motion.kind != Motion::Kind::planar)
    throw GeometryError("3-DOF pair: part '" + b.name + "' (" + b.pointer + ") must have a planar motion");
  if (b.motion.angle_limits || b.motion.translation_limits)
    throw GeometryError("3-DOF pair: part '" + b.name + "' has limits; the sliced C-space is built without limits");
  impl->fixed = *fixed;
  impl->free = *free;
  impl->fixed_name = a.name;
  impl->free_name = b.name;
  impl->options = options;
  // every contact translation d = a - pivot - R (b - pivot) has |d|_inf <= reach(a) + reach(b)
  impl->bound = reach(a, b.motion.pivot) + reach(b, b.motion.pivot) + 2;
  impl->motion.emplace(impl->model, *fixed, *free);
  if (options.cell_structure) impl->build_structure();
  impl->stats.seconds_total = seconds_since(start);
  SlicedSpace out;
  out.impl_ = impl;
  return out;
}

const std::string& SlicedSpace::fixed_part() const { return impl_->fixed_name; }
const std::string& SlicedSpace::free_part() const { return impl_->free_name; }
std::shared_ptr<const CSpace> SlicedSpace::slice(const SlicedAngle& angle) const { return impl_->slice(angle); }
const Rational& SlicedSpace::bound() const { return impl_->bound; }
const std::vector<CriticalAngle>& SlicedSpace::critical_angles() const { return impl_->critical_public; }
const std::vector<SlicedInterval>& SlicedSpace::intervals() const { return impl_->intervals; }
const std::vector<SlicedCrossing>& SlicedSpace::crossings() const { return impl_->crossings; }
std::size_t SlicedSpace::components() const { return impl_->component_count; }
const SlicedStatistics& SlicedSpace::statistics() const { return impl_->stats; }

SlicedLocation SlicedSpace::locate(const SlicedConfiguration& q) const {
  SlicedLocation out;
  auto space = impl_->slice(q.angle);
  std::size_t cell = no_index;
  out.kind = impl_->classify(*space, q.x, q.y, &cell);
  if (out.kind != SlicedLocation::Kind::free || !impl_->options.cell_structure) return out;
  auto [index, critical_angle] = impl_->position(q.angle);
  if (critical_angle) return out;
  if (cell == no_index) cell = Impl::outer_cell(*space);
  out.interval = index;
  out.cell = impl_->match(index, *space, cell);
  return out;
}

std::size_t SlicedSpace::component_of(const SlicedConfiguration& q) const {
  if (!impl_->options.cell_structure) throw GeometryError("3-DOF pair: connectivity needs the cell structure");
  auto [interval, cell] = impl_->node_of(q);
  if (interval == no_index) return no_index;
  return impl_->intervals[interval].free_cells[cell].component;
}

namespace {

std::string feature_text(const Model& model, const FeatureIdentity& id) {
  std::string out = model.parts[id.part].name + " ";
  if (id.kind == FeatureKind::vertex) return out + "vertex of loop " + std::to_string(id.loop) + " edge " + std::to_string(id.edge);
  const std::string& label = model.parts[id.part].loops[id.loop].edges[id.edge].label;
  out += (id.kind == FeatureKind::arc ? "arc" : "segment");
  out += " loop " + std::to_string(id.loop) + " edge " + std::to_string(id.edge);
  if (!label.empty()) out += " (" + label + ")";
  return out;
}

// The motion's chart coordinate of an end.
Rational chart_w(SlicedAngle angle, bool flip, const char* which) {
  angle.t.canonicalize();
  if (!flip) {
    if (angle.half_turn)
      throw GeometryError(std::string("3-DOF motion: its ") + which +
                          " is the half turn; give the motion through_half_turn (the chart centred at pi)");
    return angle.t;
  }
  if (angle.half_turn) return Rational(0);
  if (sgn(angle.t) == 0)
    throw GeometryError(std::string("3-DOF motion: its ") + which +
                        " is at theta = 0, outside the chart centred at the half turn (through_half_turn)");
  return Rational(-1 / angle.t);
}

SlicedAngle angle_of_w(const Rational& w, bool flip) {
  if (!flip) return SlicedAngle{w, false};
  if (sgn(w) == 0) return SlicedAngle{Rational(0), true};
  return SlicedAngle{Rational(-1 / w), false};
}

SlicedFeaturePair sliced_feature_pair(const Model& model, const FeatureIdentity& fixed, const FeatureIdentity& free) {
  return SlicedFeaturePair{fixed, free, feature_text(model, fixed) + " / " + feature_text(model, free)};
}

}  // namespace

SlicedMotionCrossing SlicedSpace::first_crossing(const SlicedMotion& motion, const CrossingOptions& options) const {
  sliced::StraightMotion m;
  m.flip = motion.through_half_turn;
  m.x0 = motion.from.x;
  m.y0 = motion.from.y;
  m.w0 = chart_w(motion.from.angle, m.flip, "start");
  m.x1 = motion.to.x;
  m.y1 = motion.to.y;
  m.w1 = chart_w(motion.to.angle, m.flip, "end");
  for (Rational* r : {&m.x0, &m.y0, &m.x1, &m.y1}) r->canonicalize();
  for (const auto& [fixed, free] : motion.ignored) m.ignored.push_back(sliced::MotionContact{fixed, free});
  sliced::MotionResult r = impl_->motion->first_contact(m);
  SlicedMotionCrossing out;
  if (!r.starts_apart) {
    out.status = CrossingStatus::starts_in_contact;
    out.before = motion.from;
    return out;
  }
  if (!r.found) {
    out.u_lower = out.u_upper = 1;
    out.before = motion.to;
    return out;
  }
  out.status = CrossingStatus::crossing;
  Rational width = Rational(1) / Rational(mpz_class(1) << options.resolution_bits);
  Real u = r.u;
  if (!u.exact) algebra::refine_dyadically(u, width);
  out.u.polynomial = u.polynomial;
  out.u.lower = u.lower;
  out.u.upper = u.upper;
  out.u.exact = u.exact;
  out.u.lower.canonicalize();
  out.u.upper.canonicalize();
  out.u_lower = out.u.lower;
  out.u_upper = u.exact ? out.u.lower : out.u.upper;
  Rational before = u.exact ? Rational(out.u_lower - width) : out.u_lower;   // < u: free
  if (sgn(before) < 0) before = 0;
  auto lerp = [&](const Rational& a, const Rational& b) { return Rational(a + before * (b - a)); };
  out.before = SlicedConfiguration{lerp(m.x0, m.x1), lerp(m.y0, m.y1), angle_of_w(lerp(m.w0, m.w1), m.flip)};
  for (const auto& c : r.contacts) out.features.push_back(sliced_feature_pair(impl_->model, c.fixed, c.free));
  return out;
}

bool SlicedSpace::motion_free(const SlicedMotion& motion) const {
  return first_crossing(motion, CrossingOptions{4}).status == CrossingStatus::none;
}

std::vector<SlicedNearFeature> SlicedSpace::features_near(const SlicedConfiguration& q, const Rational& distance) const {
  if (sgn(distance) < 0) throw GeometryError("3-DOF pair: features_near needs a distance >= 0");
  auto found = sliced::near_features(impl_->model, impl_->fixed, impl_->free, q, distance);
  std::vector<SlicedNearFeature> out;
  for (const auto& f : found) {
    SlicedNearFeature n;
    n.pair = sliced_feature_pair(impl_->model, f.fixed, f.free);
    n.distance_lower = f.lower;
    n.distance_upper = f.upper;
    n.exact = f.exact;
    out.push_back(std::move(n));
  }
  return out;
}

bool SlicedSpace::connected(const SlicedConfiguration& a, const SlicedConfiguration& b) const {
  std::size_t ca = component_of(a), cb = component_of(b);
  return ca != no_index && ca == cb;
}

}  // namespace hipair
