// PEER comparison of dynamical simulation (issue 11): the same Geneva drive simulated by HIPAIR
// (hipair::Simulation: certified first crossings on the exact C-space, Dormand-Prince with error
// control), Box2D 2.4.1 (arcs polygonised, convex decomposition, revolute joints, a motor on the
// driver) and MuJoCo 2.2.2 (hinge joints, convex prism meshes of the same decomposition, a
// cylinder for the pin), for several accuracies / step sizes, in one process.
//
// The drive: examples/models/geneva-drive.json (4 slots, crank c = 56.5 mm, centre distance
// d = 80 mm, pin radius 4.5 mm, slot width 10 mm, wheel 1000 kg mm^2, restitution 0, no
// friction), the driver at a prescribed 2 pi rad/s, both parts starting at angle 0, 2 s (two
// turns: two drives, two dwells).
//
// Error (rad), evaluated at every state a simulator produces (HIPAIR: every step end; peers:
// every step), against the closed form (docs/simulation.md, "Scenarios"):
//   drive  |psi| < pi/4 - 0.02 (psi: pin direction against the line of centres): the wheel angle
//          must lie within asin(w / rho) of the closed form tan(theta) = lambda sin(psi) /
//          (1 - lambda cos(psi)), lambda = c / d = 0.70625, w = 0.5 mm the slot's play (pin
//          radius 4.5 in a 10 mm slot), rho the pin centre's distance from the wheel centre; the
//          error is the excess over that band (0 inside it);
//   dwell  |psi| >= 2.3 (the wheel has coasted into the locking arcs): the wheel must not move;
//          the error is the range of the wheel angle over each dwell.
// Contacts: at every state, the touching feature pairs (labels of the model's edges, e.g.
// "pin / slot 1 wall R"); for the peers, each contact point is labelled with the nearest edge of
// each part's exact outline. Runs of consecutive states with a label are contact episodes.
// HIPAIR's are exact (its events and sustained contacts); a HIPAIR episode no peer episode of
// the same label overlaps is "missed", a peer episode overlapping no HIPAIR episode of its label
// is "invented" (intervals widened by a matching window of 2 peer steps + 1 ms, a convention).
//
// Deviation: the largest |wheel - reference| on a 4 ms grid, the reference being HIPAIR at
// accuracy 1e-12 stopped on the grid (HIPAIR's own rows: a second, untimed run on the grid).
// HIPAIR runs with max_step 0.1 s: without it, the second drive is skipped (see run_hipair).
// A second case, a falling pin bouncing in a slot, is compared with its closed form (BM_Pin*).
//
// Output: Google Benchmark rows (CPU time = the simulation loop only, C-space build and model
// compilation excluded) with counters, then the tables; with --out=DIR (before the benchmark
// flags) also DIR/simulation-peers.csv, DIR/simulation-peers.svg (closed-form error against CPU
// time, log-log), DIR/simulation-peers-deviation.svg and DIR/geneva-peer-pieces.svg (the peers'
// convex pieces). Results: docs/performance.md, "Simulation against Box2D and MuJoCo".
#include "bench_paths.hpp"

#include "peer_timing.hpp"

#include "io/atomic_file.hpp"
#include "io/svg.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <benchmark/benchmark.h>

#ifdef HIPAIR_HAVE_BOX2D
#include <box2d/box2d.h>
#endif
#ifdef HIPAIR_HAVE_MUJOCO
#include <mujoco/mujoco.h>
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace hipair;
constexpr double pi = 3.14159265358979323846;

// ------------------------------------------------------------------ the drive and its geometry
constexpr double centre = 80, crank = 56.5, pin_radius = 4.5, half_width = 5, half_clearance = 0.5;
constexpr double lambda = crank / centre;
constexpr double omega = 2 * pi;     // driver speed, rad/s
constexpr double wheel_inertia = 1000;  // kg mm^2
constexpr double t_end = 2;

Model geneva_model() {
  return read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "geneva-drive.json");
}

struct Vec2 {
  double x = 0, y = 0;
};
Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
Vec2 polar(double r, double a) { return {r * std::cos(a), r * std::sin(a)}; }
Vec2 rotate(Vec2 p, double a) { return {std::cos(a) * p.x - std::sin(a) * p.y, std::sin(a) * p.x + std::cos(a) * p.y}; }
using Polygon = std::vector<Vec2>;

// Keeps the part of a convex polygon left of the directed line a -> b (Sutherland-Hodgman).
Polygon clip(const Polygon& polygon, Vec2 a, Vec2 b) {
  Polygon out;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    Vec2 p = polygon[i], q = polygon[(i + 1) % polygon.size()];
    double sp = cross(b - a, p - a), sq = cross(b - a, q - a);
    if (sp >= 0) out.push_back(p);
    if ((sp >= 0) != (sq >= 0)) out.push_back(p + (sp / (sp - sq)) * (q - p));
  }
  return out;
}

// Drops vertices closer than `weld` to the previous one (Box2D welds them anyway).
Polygon tidy(const Polygon& polygon, double weld) {
  Polygon out;
  for (Vec2 p : polygon)
    if (out.empty() || std::hypot(p.x - out.back().x, p.y - out.back().y) > weld) out.push_back(p);
  while (out.size() > 1 && std::hypot(out.front().x - out.back().x, out.front().y - out.back().y) <= weld) out.pop_back();
  return out;
}

double area(const Polygon& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) a += cross(p[i], p[(i + 1) % p.size()]);
  return a / 2;
}

// Convex pieces (mm, each part's frame about its pivot) whose union is the part's outline with
// its arcs polygonised by `segments` chords per quarter turn (vertices on the arcs).
struct Decomposition {
  std::vector<Polygon> wheel;     // wheel frame, pivot at the origin
  std::vector<Polygon> driver;    // driver frame, pivot at the origin (the pin is a circle)
  Vec2 pin{crank, 0};
};

Decomposition decompose(int segments) {
  Decomposition d;
  // Wheel (model: slots along pi/4 + k pi/2, walls at +-5 from the axis from radius 20 to 60,
  // bottom half-discs at radius 20, locking arcs of radius 46.683 about the points at 80 in the
  // directions k pi/2, spanning pi/2). The slot bottoms are drawn square at radius 15 (the pin
  // centre never comes nearer than 80 - 56.5 = 23.5, so the pin never reaches below radius 19:
  // only material it cannot touch differs).
  const double lock_radius = 46.683, slot_in = 20, slot_out = 60, notch = 15;
  for (int k = 0; k < 4; ++k) {
    double beta = k * pi / 2;
    // the arm between the slots at beta - pi/4 and beta + pi/4
    Vec2 u_minus = polar(1, beta - pi / 4), u_plus = polar(1, beta + pi / 4);
    Vec2 n_minus = polar(1, beta + pi / 4), n_plus = polar(1, beta - pi / 4);   // towards the arm
    Vec2 wm_in = slot_in * u_minus + half_width * n_minus, wm_out = slot_out * u_minus + half_width * n_minus;
    Vec2 wp_in = slot_in * u_plus + half_width * n_plus, wp_out = slot_out * u_plus + half_width * n_plus;
    Vec2 c = polar(centre, beta);
    double a0 = beta + pi - pi / 4, a1 = beta + pi + pi / 4;   // the locking arc, ccw about c
    Vec2 arc0 = c + polar(lock_radius, a0), arc1 = c + polar(lock_radius, a1);
    // arc0 (angle a0 about c) lies on the + side of the arm, arc1 on the - side
    Polygon hull{wm_in, wm_out, arc1, arc0, wp_out, wp_in};
    if (area(hull) < 0) std::reverse(hull.begin(), hull.end());
    std::vector<Vec2> arc;
    for (int j = 0; j <= segments; ++j) arc.push_back(c + polar(lock_radius, a0 + (a1 - a0) * j / segments));
    for (int j = 0; j < segments; ++j) {
      Polygon piece = clip(hull, c, arc[j]);               // ccw of the ray through arc[j]... (left of c->arc[j])
      piece = clip(piece, arc[j + 1], c);                  // and cw of the ray through arc[j+1]
      piece = clip(piece, arc[j + 1], arc[j]);             // beyond the chord (away from c)
      d.wheel.push_back(piece);
    }
    d.wheel.push_back(clip(hull, arc[0], c));              // beyond the first ray
    d.wheel.push_back(clip(hull, c, arc[segments]));       // beyond the last ray
    // the material between the arm and the hub: wall feet at radius 20 down to the notch at 15
    Vec2 nm = notch * u_minus + half_width * n_minus, np = notch * u_plus + half_width * n_plus;
    d.wheel.push_back(Polygon{nm, wm_in, wp_in, np});
  }
  Polygon hub;
  for (int k = 0; k < 4; ++k) {
    double beta = k * pi / 2;
    hub.push_back(notch * polar(1, beta - pi / 4) + half_width * polar(1, beta + pi / 4));
    hub.push_back(notch * polar(1, beta + pi / 4) + half_width * polar(1, beta - pi / 4));
  }
  d.wheel.push_back(hub);
  // Driver: the locking segment, an annulus 36..46 mm over [pi - 2.4708, pi + 2.4708] about the
  // driver's pivot (model: outer/inner-arc-offset and span), in quadrilaterals.
  const double r_out = 46, r_in = 36, start = pi - 2.4708, span = 4.9416;
  int pieces = static_cast<int>(std::ceil(span / (pi / 2) * segments));
  for (int j = 0; j < pieces; ++j) {
    double a = start + span * j / pieces, b = start + span * (j + 1) / pieces;
    d.driver.push_back(Polygon{polar(r_in, a), polar(r_out, a), polar(r_out, b), polar(r_in, b)});
  }
  for (Polygon& p : d.wheel) {
    p = tidy(p, 0.05);   // Box2D welds vertices closer than 0.025 mm
    if (area(p) < 0) std::reverse(p.begin(), p.end());
  }
  d.wheel.erase(std::remove_if(d.wheel.begin(), d.wheel.end(), [](const Polygon& p) { return p.size() < 3 || area(p) < 0.01; }),
                d.wheel.end());
  for (Polygon& p : d.driver)
    if (area(p) < 0) std::reverse(p.begin(), p.end());
  return d;
}

// ------------------------------------------------------------------ labelling contact points
// The model's labelled edges, per part, in the part's frame about its pivot (double precision).
struct LabelledEdge {
  std::string label;
  Vec2 a, b, c;
  bool arc = false, ccw = true, full = false;
};

struct Outline {
  Vec2 pivot;
  std::vector<LabelledEdge> edges;
};

Outline outline(const Part& part) {
  Outline o;
  o.pivot = {to_double(part.motion.pivot.x), to_double(part.motion.pivot.y)};
  for (const Loop& loop : part.loops)
    for (const Edge& e : loop.edges) {
      LabelledEdge l;
      l.label = e.label;
      l.a = Vec2{to_double(e.source.x), to_double(e.source.y)} - o.pivot;
      l.b = Vec2{to_double(e.target.x), to_double(e.target.y)} - o.pivot;
      l.arc = e.is_arc();
      if (l.arc) {
        l.c = Vec2{to_double(e.center.x), to_double(e.center.y)} - o.pivot;
        l.ccw = e.ccw;
        l.full = e.is_full_circle();
      }
      o.edges.push_back(l);
    }
  return o;
}

double distance_to(const LabelledEdge& e, Vec2 p) {
  if (!e.arc) {
    Vec2 ab = e.b - e.a;
    double t = std::clamp(dot(p - e.a, ab) / dot(ab, ab), 0.0, 1.0);
    Vec2 q = e.a + t * ab;
    return std::hypot(p.x - q.x, p.y - q.y);
  }
  double r = std::hypot(e.a.x - e.c.x, e.a.y - e.c.y);
  double angle = std::atan2(p.y - e.c.y, p.x - e.c.x);
  auto inside = [&](double a) {
    if (e.full) return true;
    double s = std::atan2(e.a.y - e.c.y, e.a.x - e.c.x), t = std::atan2(e.b.y - e.c.y, e.b.x - e.c.x);
    double span = std::remainder(e.ccw ? t - s : s - t, 2 * pi);
    if (span <= 0) span += 2 * pi;
    double along = std::remainder(e.ccw ? a - s : s - a, 2 * pi);
    if (along < 0) along += 2 * pi;
    return along <= span;
  };
  if (inside(angle)) return std::abs(std::hypot(p.x - e.c.x, p.y - e.c.y) - r);
  return std::min(std::hypot(p.x - e.a.x, p.y - e.a.y), std::hypot(p.x - e.b.x, p.y - e.b.y));
}

// The label of the edge of `o` nearest the world point p with the part at `angle`.
std::string nearest_label(const Outline& o, double angle, Vec2 p) {
  Vec2 local = rotate(p - o.pivot, -angle);
  double best = 1e300;
  std::string label;
  for (const LabelledEdge& e : o.edges) {
    double d = distance_to(e, local);
    if (d < best) best = d, label = e.label;
  }
  return label;
}

// The contact classes compared between simulators: the driver's pin against one side (L, R) of
// one slot of the wheel ("pin / slot 1 L": its wall, mouth or their corner), or the driver's
// locking segment against one arm of the wheel ("lock segment / arm 2": locking arc k with its
// corners, the mouths beside it: slot k mouth R and slot k-1 mouth L). HIPAIR's labels
// ("driver pin / wheel corner of slot 1 wall L and slot 1 mouth L (arc on vertex)") and the
// peers' nearest-edge labels ("pin / slot 1 wall L") map to the same classes; the classes keep
// apart what a contact sequence must get right (which slot, which wall, which arm) and ignore
// where along a wall or arc the touching point lies (polygonised corners move it).
std::string contact_class(const std::string& label) {
  auto slash = label.find(" / ");
  std::string first = label.substr(0, slash), second = slash == std::string::npos ? "" : label.substr(slash + 3);
  bool pin = first.find("pin") != std::string::npos;
  std::smatch m;
  static const std::regex slot("slot ([0-9]+) (wall|mouth|bottom) ?([LR]?)"), lock("lock arc ([0-9]+)");
  if (pin) {
    if (std::regex_search(second, m, slot)) return "pin / slot " + m[1].str() + (m[3].length() ? " " + m[3].str() : "");
    return "pin / " + second;
  }
  if (std::regex_search(second, m, lock)) return "lock segment / arm " + m[1].str();
  if (std::regex_search(second, m, slot)) {
    int k = std::stoi(m[1].str());
    if (m[3].str() == "L") k = k % 4 + 1;
    return "lock segment / arm " + std::to_string(k);
  }
  return "lock segment / " + second;
}

// ------------------------------------------------------------------ one run's record
struct Sample {
  double t = 0, driver = 0, wheel = 0;
  std::set<std::string> touching;
};

struct Episode {
  std::string label;
  double begin = 0, end = 0;
};

std::vector<Episode> episodes(const std::vector<Sample>& samples) {
  std::vector<Episode> out;
  std::map<std::string, std::size_t> open;   // label -> index in out
  for (const Sample& s : samples) {
    for (auto it = open.begin(); it != open.end();) {
      if (!s.touching.count(it->first)) it = open.erase(it);
      else ++it;
    }
    for (const std::string& label : s.touching) {
      auto it = open.find(label);
      if (it == open.end()) {
        open[label] = out.size();
        out.push_back({label, s.t, s.t});
      } else {
        out[it->second].end = s.t;
      }
    }
  }
  return out;
}

struct Errors {
  double drive = 0, dwell = 0;
  std::size_t drive_states = 0, dwell_states = 0;
};

Errors errors(const std::vector<Sample>& samples) {
  Errors e;
  bool in_dwell = false;
  double low = 0, high = 0;
  for (const Sample& s : samples) {
    double psi = std::remainder(s.driver - pi, 2 * pi);
    if (std::abs(psi) < pi / 4 - 0.02) {
      double expected = -std::atan(lambda * std::sin(psi) / (1 - lambda * std::cos(psi)));
      double rho = std::hypot(centre - crank * std::cos(psi), crank * std::sin(psi));
      double rel = std::remainder(s.wheel - expected - pi / 4, pi / 2);
      e.drive = std::max(e.drive, std::abs(rel) - std::asin(half_clearance / rho));
      ++e.drive_states;
    }
    if (std::abs(psi) >= 2.3) {
      if (!in_dwell) low = high = s.wheel;
      in_dwell = true;
      low = std::min(low, s.wheel);
      high = std::max(high, s.wheel);
      e.dwell = std::max(e.dwell, high - low);
      ++e.dwell_states;
    } else {
      in_dwell = false;
    }
  }
  e.drive = std::max(e.drive, 0.0);
  return e;
}

struct Row {
  std::string engine, setting;
  double parameter = 0;       // accuracy or step (s)
  double cpu = 0;             // CPU seconds of the simulation loop
  double setup = 0;           // CPU seconds of the set-up (C-space build / model compilation)
  std::size_t steps = 0;
  Errors error;
  std::size_t episodes = 0, raw_episodes = 0, missed = 0, invented = 0;
  double final_wheel = 0;
  double window = 0;          // matching window of the episodes (s)
  std::vector<Episode> found; // contact episodes
  std::string failure;        // the simulator's error, when it stopped early
  double reached = t_end;     // time reached
  double deviation = -1;      // largest |wheel - reference| on the 4 ms grid (-1: not measured)
};

// The reference trajectory: HIPAIR at accuracy 1e-12 (steps at most 0.1 s), stopped exactly at
// every multiple of 4 ms (a grid every peer's steps land on), wheel angles. Computed once.
constexpr double grid = 4e-3;
constexpr double reference_accuracy = 1e-12;
const std::vector<double>& reference_wheel();

// Largest |wheel - reference| over the samples that lie on the grid.
double deviation(const std::vector<Sample>& samples) {
  const std::vector<double>& ref = reference_wheel();
  double worst = 0;
  for (const Sample& s : samples) {
    double k = std::round(s.t / grid);
    if (std::abs(s.t - k * grid) > 1e-9 || k >= static_cast<double>(ref.size())) continue;
    worst = std::max(worst, std::abs(s.wheel - ref[static_cast<std::size_t>(k)]));
  }
  return worst;
}

std::vector<Row> rows;
std::vector<Episode> exact_episodes;   // HIPAIR's at its tightest accuracy
double exact_accuracy = 0;

// Peer episodes of one label separated by less than `window` are one episode (chatter).
std::vector<Episode> merged(std::vector<Episode> list, double window) {
  std::sort(list.begin(), list.end(), [](const Episode& a, const Episode& b) {
    return a.label != b.label ? a.label < b.label : a.begin < b.begin;
  });
  std::vector<Episode> out;
  for (const Episode& e : list) {
    if (!out.empty() && out.back().label == e.label && e.begin - out.back().end <= window)
      out.back().end = std::max(out.back().end, e.end);
    else
      out.push_back(e);
  }
  return out;
}

void compare(Row& row) {
  double window = row.window;
  row.raw_episodes = row.found.size();
  std::vector<Episode> peer = merged(row.found, window);
  row.episodes = peer.size();
  auto overlaps = [&](const Episode& a, const Episode& b) {
    return a.label == b.label && a.begin - window <= b.end && b.begin - window <= a.end;
  };
  row.missed = row.invented = 0;
  for (const Episode& e : exact_episodes)
    row.missed += std::none_of(peer.begin(), peer.end(), [&](const Episode& p) { return overlaps(e, p); });
  for (const Episode& p : peer)
    row.invented += std::none_of(exact_episodes.begin(), exact_episodes.end(), [&](const Episode& e) { return overlaps(e, p); });
}

void report(benchmark::State& state, const Row& row) {
  state.counters["sim_s_per_cpu_s"] = t_end / row.cpu;
  state.counters["err_drive_rad"] = row.error.drive;
  state.counters["err_dwell_rad"] = row.error.dwell;
  state.counters["steps"] = static_cast<double>(row.steps);
  state.counters["contacts"] = static_cast<double>(row.found.size());
  state.counters["deviation_rad"] = row.deviation;
  state.counters["setup_s"] = row.setup;
}

// ------------------------------------------------------------------ HIPAIR
// One run: CPU time of run_until alone; the contact labels at each step end are read in the
// progress callback, whose own CPU time is subtracted.
// HIPAIR's wheel angles at every multiple of the grid (run_until stops there exactly), or up
// to its failure.
std::vector<Sample> hipair_on_grid(double accuracy, std::string* failure) {
  SimulationOptions options;
  options.accuracy = accuracy;
  options.max_step = 0.1;
  Simulation s = Simulation::create(geneva_model(), options);
  std::vector<Sample> samples{{0, s.state().position[0], s.state().position[1], {}}};
  auto n = static_cast<long>(std::llround(t_end / grid));
  try {
    for (long k = 1; k <= n; ++k) {
      s.run_until(static_cast<double>(k) * grid);
      samples.push_back({s.state().time, s.state().position[0], s.state().position[1], {}});
    }
  } catch (const Error& error) {
    if (failure) *failure = error.what();
  }
  return samples;
}

const std::vector<double>& reference_wheel() {
  static const std::vector<double> reference = [] {
    std::string failure;
    std::vector<double> wheel;
    for (const Sample& s : hipair_on_grid(reference_accuracy, &failure)) wheel.push_back(s.wheel);
    if (!failure.empty()) std::cerr << "reference run failed: " << failure << "\n";
    return wheel;
  }();
  return reference;
}

Row run_hipair(double accuracy) {
  Model model = geneva_model();
  Row row;
  row.engine = "HIPAIR";
  row.parameter = accuracy;
  char text[32];
  std::snprintf(text, sizeof text, "accuracy %.0e", accuracy);
  row.setting = text;
  SimulationOptions options;
  options.accuracy = accuracy;
  // Without a step limit the run is wrong after the first dwell: a step in sustained contact
  // (the wheel's corner on the driver's locking arc) spans more than a driver turn, the edge's
  // end is tested only at the step's end, which lies on the edge again one turn later, and the
  // second drive is skipped (docs/performance.md, "Simulation against Box2D and MuJoCo").
  options.max_step = 0.1;
  double start = bench::thread_cpu_seconds();
  Simulation s = Simulation::create(model, options);
  row.setup = bench::thread_cpu_seconds() - start;
  std::vector<Sample> samples;
  double excluded = 0;
  std::size_t seen_events = 0;
  auto record = [&] {
    double begin = bench::thread_cpu_seconds();
    Sample sample{s.state().time, s.state().position[0], s.state().position[1], {}};
    for (const SimulationContact& c : s.contacts())
      for (const std::string& f : c.features) sample.touching.insert(contact_class(f));
    // impacts of this step (an impact that leaves no sustained contact is a one-state episode)
    for (; seen_events < s.events().size(); ++seen_events) {
      const SimulationEvent& e = s.events()[seen_events];
      if (e.kind == SimulationEvent::Kind::impact || e.kind == SimulationEvent::Kind::contact)
        for (const std::string& f : e.features) sample.touching.insert(contact_class(f));
    }
    samples.push_back(std::move(sample));
    excluded += bench::thread_cpu_seconds() - begin;
  };
  record();
  start = bench::thread_cpu_seconds();
  try {
    s.run_until(t_end, [&](double) { record(); });
  } catch (const Error& error) {
    row.failure = error.what();
  }
  row.reached = s.state().time;
  row.cpu = bench::thread_cpu_seconds() - start - excluded;
  row.steps = s.steps();
  row.error = errors(samples);
  // an edge change within one class (HIPAIR's edge end and the impact taken up 1e-8 s later at
  // the next edge, for instance) is one episode: merged within 1 microsecond
  row.found = merged(episodes(samples), 1e-6);
  // the deviation from the reference comes from a second run at the same accuracy whose steps
  // also end on the grid (not timed)
  row.deviation = deviation(hipair_on_grid(accuracy, nullptr));
  row.window = 1e-3;
  row.final_wheel = s.state().position[1];
  if (row.failure.empty() && (exact_episodes.empty() || accuracy < exact_accuracy)) {
    exact_episodes = row.found;
    exact_accuracy = accuracy;
  }
  return row;
}

void BM_GenevaHipair(benchmark::State& state, double accuracy) {
  Row row;
  for (auto _ : state) row = run_hipair(accuracy);
  state.SetIterationTime(row.cpu);
  report(state, row);
  rows.push_back(row);
}

// ------------------------------------------------------------------ Box2D
#ifdef HIPAIR_HAVE_BOX2D
// Box2D works in float and is tuned for bodies of 0.1 to 10 units: 1 unit = 10 mm here (its
// polygon skin b2_polygonRadius = 0.01 unit = 0.1 mm, linear slop 0.05 mm).
constexpr double box2d_unit = 10;   // mm per unit

struct Box2dTag {
  int part = 0;   // 0 driver, 1 wheel
};

Row run_box2d(double step, int velocity_iterations, int position_iterations, const Decomposition& shape,
              const Outline& driver_outline, const Outline& wheel_outline) {
  Row row;
  row.engine = "Box2D";
  row.parameter = step;
  char text[64];
  std::snprintf(text, sizeof text, "h %.2g ms, %d/%d iterations", step * 1e3, velocity_iterations, position_iterations);
  row.setting = text;
  double start = bench::thread_cpu_seconds();
  b2World world(b2Vec2(0, 0));
  b2BodyDef ground_def;
  b2Body* ground = world.CreateBody(&ground_def);
  static Box2dTag driver_tag{0}, wheel_tag{1};
  auto body = [&](double x, const std::vector<Polygon>& polygons, bool pin, Box2dTag* tag, double inertia) {
    b2BodyDef def;
    def.type = b2_dynamicBody;
    def.position.Set(static_cast<float>(x / box2d_unit), 0);
    def.allowSleep = false;
    def.bullet = true;
    b2Body* b = world.CreateBody(&def);
    for (const Polygon& p : polygons) {
      b2Vec2 points[b2_maxPolygonVertices];
      if (p.size() > b2_maxPolygonVertices) throw std::runtime_error("Box2D piece with more than 8 vertices");
      for (std::size_t i = 0; i < p.size(); ++i)
        points[i].Set(static_cast<float>(p[i].x / box2d_unit), static_cast<float>(p[i].y / box2d_unit));
      b2PolygonShape polygon;
      polygon.Set(points, static_cast<int32>(p.size()));   // pieces are convex, vertices > 0.05 mm apart
      b2FixtureDef fixture;
      fixture.shape = &polygon;
      fixture.density = 1;
      fixture.friction = 0;
      fixture.restitution = 0;
      fixture.userData.pointer = reinterpret_cast<uintptr_t>(tag);
      b->CreateFixture(&fixture);
    }
    if (pin) {
      b2CircleShape circle;
      circle.m_p.Set(static_cast<float>(shape.pin.x / box2d_unit), static_cast<float>(shape.pin.y / box2d_unit));
      circle.m_radius = static_cast<float>(pin_radius / box2d_unit);
      b2FixtureDef fixture;
      fixture.shape = &circle;
      fixture.density = 1;
      fixture.friction = 0;
      fixture.restitution = 0;
      fixture.userData.pointer = reinterpret_cast<uintptr_t>(tag);
      b->CreateFixture(&fixture);
    }
    b2MassData mass;
    mass.mass = 1;
    mass.center.SetZero();
    mass.I = static_cast<float>(inertia / (box2d_unit * box2d_unit));   // kg unit^2
    b->SetMassData(&mass);
    return b;
  };
  b2Body* wheel = body(0, shape.wheel, false, &wheel_tag, wheel_inertia);
  {
    b2RevoluteJointDef joint;
    joint.Initialize(ground, wheel, wheel->GetPosition());
    world.CreateJoint(&joint);
  }
  // the driver: a heavy body on a revolute joint whose motor holds 2 pi rad/s
  b2Body* driver = body(centre, shape.driver, true, &driver_tag, 1000 * wheel_inertia);
  {
    b2RevoluteJointDef joint;
    joint.Initialize(ground, driver, driver->GetPosition());
    joint.enableMotor = true;
    joint.motorSpeed = static_cast<float>(omega);
    joint.maxMotorTorque = 1e12f;
    world.CreateJoint(&joint);
  }
  driver->SetAngularVelocity(static_cast<float>(omega));
  row.setup = bench::thread_cpu_seconds() - start;

  auto steps = static_cast<long>(std::llround(t_end / step));
  std::vector<Sample> samples;
  samples.reserve(static_cast<std::size_t>(steps) + 1);
  double excluded = 0;
  auto record = [&](double t) {
    double begin = bench::thread_cpu_seconds();
    Sample sample{t, driver->GetAngle(), wheel->GetAngle(), {}};
    for (b2Contact* c = world.GetContactList(); c; c = c->GetNext()) {
      if (!c->IsTouching()) continue;
      b2WorldManifold manifold;
      c->GetWorldManifold(&manifold);
      for (int32 i = 0; i < c->GetManifold()->pointCount; ++i) {
        Vec2 p{manifold.points[i].x * box2d_unit, manifold.points[i].y * box2d_unit};
        sample.touching.insert(contact_class(nearest_label(driver_outline, sample.driver, p) + " / " +
                                             nearest_label(wheel_outline, sample.wheel, p)));
      }
    }
    samples.push_back(std::move(sample));
    excluded += bench::thread_cpu_seconds() - begin;
  };
  record(0);
  start = bench::thread_cpu_seconds();
  for (long k = 1; k <= steps; ++k) {
    world.Step(static_cast<float>(step), velocity_iterations, position_iterations);
    record(static_cast<double>(k) * step);
  }
  row.cpu = bench::thread_cpu_seconds() - start - excluded;
  row.steps = static_cast<std::size_t>(steps);
  row.error = errors(samples);
  row.final_wheel = wheel->GetAngle();
  row.deviation = deviation(samples);
  row.found = episodes(samples);
  row.window = 2 * step + 1e-3;
  return row;
}

void BM_GenevaBox2d(benchmark::State& state, double step, int velocity_iterations, int position_iterations) {
  Model model = geneva_model();
  Outline driver_outline = outline(model.parts[0]), wheel_outline = outline(model.parts[1]);
  Decomposition shape = decompose(12);
  Row row;
  for (auto _ : state) row = run_box2d(step, velocity_iterations, position_iterations, shape, driver_outline, wheel_outline);
  state.SetIterationTime(row.cpu);
  report(state, row);
  rows.push_back(row);
}
#endif

// ------------------------------------------------------------------ MuJoCo
#ifdef HIPAIR_HAVE_MUJOCO
// MuJoCo in SI units (m, kg, s). Each convex piece is a prism mesh 10 mm thick; the pin a
// cylinder. Both bodies turn on hinge joints about z; the driver's joint position and velocity
// are set to the prescribed law before every step (a kinematic driver).
std::string mjcf(double step, const Decomposition& shape, const std::string& integrator, double time_constant) {
  std::ostringstream xml;
  xml.precision(12);
  auto mesh = [&](const std::string& name, const Polygon& p) {
    xml << "<mesh name=\"" << name << "\" vertex=\"";
    for (Vec2 v : p) xml << v.x * 1e-3 << " " << v.y * 1e-3 << " -0.005 " << v.x * 1e-3 << " " << v.y * 1e-3 << " 0.005 ";
    xml << "\"/>\n";
  };
  xml << "<mujoco model=\"geneva\">\n<compiler angle=\"radian\"/>\n";
  xml << "<option timestep=\"" << step << "\" gravity=\"0 0 0\" integrator=\"" << integrator << "\"/>\n";
  xml << "<default><geom friction=\"0 0 0\" condim=\"1\"";
  if (time_constant > 0) xml << " solref=\"" << time_constant << " 1\"";
  xml << "/></default>\n<asset>\n";
  for (std::size_t i = 0; i < shape.wheel.size(); ++i) mesh("w" + std::to_string(i), shape.wheel[i]);
  for (std::size_t i = 0; i < shape.driver.size(); ++i) mesh("d" + std::to_string(i), shape.driver[i]);
  xml << "</asset>\n<worldbody>\n";
  xml << "<body name=\"wheel\" pos=\"0 0 0\">\n<joint name=\"wheel\" type=\"hinge\" axis=\"0 0 1\"/>\n"
      << "<inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"" << wheel_inertia * 1e-6 << " " << wheel_inertia * 1e-6 << " "
      << wheel_inertia * 1e-6 << "\"/>\n";
  for (std::size_t i = 0; i < shape.wheel.size(); ++i)
    xml << "<geom name=\"w" << i << "\" type=\"mesh\" mesh=\"w" << i << "\"/>\n";
  xml << "</body>\n<body name=\"driver\" pos=\"" << centre * 1e-3 << " 0 0\">\n"
      << "<joint name=\"driver\" type=\"hinge\" axis=\"0 0 1\"/>\n"
      << "<inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"1 1 1\"/>\n";
  xml << "<geom name=\"pin\" type=\"cylinder\" size=\"" << pin_radius * 1e-3 << " 0.005\" pos=\"" << shape.pin.x * 1e-3
      << " " << shape.pin.y * 1e-3 << " 0\"/>\n";
  for (std::size_t i = 0; i < shape.driver.size(); ++i)
    xml << "<geom name=\"d" << i << "\" type=\"mesh\" mesh=\"d" << i << "\"/>\n";
  xml << "</body>\n</worldbody>\n</mujoco>\n";
  return xml.str();
}

Row run_mujoco(double step, const std::string& integrator, double time_constant, const Decomposition& shape,
               const Outline& driver_outline, const Outline& wheel_outline) {
  Row row;
  row.engine = "MuJoCo";
  row.parameter = step;
  char text[96];
  if (time_constant > 0)
    std::snprintf(text, sizeof text, "h %.2g ms, %s, solref %.2g s", step * 1e3, integrator.c_str(), time_constant);
  else
    std::snprintf(text, sizeof text, "h %.2g ms, %s, default solref", step * 1e3, integrator.c_str());
  row.setting = text;
  double start = bench::thread_cpu_seconds();
  std::string xml = mjcf(step, shape, integrator, time_constant);
  mjVFS vfs;
  mj_defaultVFS(&vfs);
  if (mj_makeEmptyFileVFS(&vfs, "geneva.xml", static_cast<int>(xml.size())) != 0) throw std::runtime_error("MuJoCo VFS");
  int file = mj_findFileVFS(&vfs, "geneva.xml");
  std::memcpy(vfs.filedata[file], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* m = mj_loadXML("geneva.xml", &vfs, error, sizeof error);
  mj_deleteVFS(&vfs);
  if (!m) throw std::runtime_error(std::string("MuJoCo: ") + error);
  mjData* d = mj_makeData(m);
  int wheel_q = m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, "wheel")];
  int driver_q = m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, "driver")];
  int wheel_v = m->jnt_dofadr[mj_name2id(m, mjOBJ_JOINT, "wheel")];
  int driver_v = m->jnt_dofadr[mj_name2id(m, mjOBJ_JOINT, "driver")];
  int wheel_body = mj_name2id(m, mjOBJ_BODY, "wheel");
  row.setup = bench::thread_cpu_seconds() - start;

  auto steps = static_cast<long>(std::llround(t_end / step));
  std::vector<Sample> samples;
  samples.reserve(static_cast<std::size_t>(steps) + 1);
  double excluded = 0;
  auto record = [&](double t) {
    double begin = bench::thread_cpu_seconds();
    Sample sample{t, d->qpos[driver_q], d->qpos[wheel_q], {}};
    for (int i = 0; i < d->ncon; ++i) {
      const mjContact& c = d->contact[i];
      if (c.dist > 0) continue;
      Vec2 p{c.pos[0] * 1e3, c.pos[1] * 1e3};
      sample.touching.insert(contact_class(nearest_label(driver_outline, sample.driver, p) + " / " +
                                           nearest_label(wheel_outline, sample.wheel, p)));
    }
    (void)wheel_body;
    samples.push_back(std::move(sample));
    excluded += bench::thread_cpu_seconds() - begin;
  };
  d->qpos[driver_q] = 0;
  d->qvel[driver_v] = omega;
  mj_forward(m, d);
  record(0);
  start = bench::thread_cpu_seconds();
  for (long k = 1; k <= steps; ++k) {
    double t = static_cast<double>(k - 1) * step;
    d->qpos[driver_q] = omega * t;   // the prescribed law, exactly, at the start of every step
    d->qvel[driver_v] = omega;
    mj_step(m, d);
    record(static_cast<double>(k) * step);
  }
  row.cpu = bench::thread_cpu_seconds() - start - excluded;
  (void)wheel_v;
  row.steps = static_cast<std::size_t>(steps);
  row.error = errors(samples);
  row.final_wheel = d->qpos[wheel_q];
  row.deviation = deviation(samples);
  row.found = episodes(samples);
  row.window = 2 * step + 1e-3;
  mj_deleteData(d);
  mj_deleteModel(m);
  return row;
}

void BM_GenevaMujoco(benchmark::State& state, double step, std::string integrator, double time_constant) {
  Model model = geneva_model();
  Outline driver_outline = outline(model.parts[0]), wheel_outline = outline(model.parts[1]);
  Decomposition shape = decompose(12);
  Row row;
  for (auto _ : state) row = run_mujoco(step, integrator, time_constant, shape, driver_outline, wheel_outline);
  state.SetIterationTime(row.cpu);
  report(state, row);
  rows.push_back(row);
}
#endif

// ------------------------------------------------------------------ falling pin in a slot
// A pin (radius 4.5 mm, 10 g) on a vertical slide falls from rest 20 mm into a 10 mm slot and
// bounces on its bottom, restitution 0.8, gravity 9810 mm/s^2, 0.4 s: closed form, the height
// above rest y(t) piecewise parabolic, impacts at T1 = sqrt(2 h / g), T(k+1) = Tk + 2 e^k v1 / g
// (v1 = g T1). The walls (0.5 mm play each side) are never touched. Error: the largest |y - y
// exact| over the states; impacts: the closed form's list against each simulator's contact
// begins (matched within 2 steps + 1 ms).
constexpr double pin_drop = 20, gravity = 9810, pin_restitution = 0.8, pin_t_end = 0.4, pin_mass = 0.01;

struct PinExact {
  std::vector<double> impacts;   // times
  double v1 = 0;
  double height(double t) const {
    if (t <= impacts.front()) return pin_drop - 0.5 * gravity * t * t;
    double v = v1;
    for (std::size_t k = 0; k + 1 < impacts.size(); ++k) {
      v *= pin_restitution;
      double s = t - impacts[k];
      if (t <= impacts[k + 1]) return std::max(0.0, v * s - 0.5 * gravity * s * s);
    }
    return 0;
  }
};

PinExact pin_exact() {
  PinExact e;
  double t = std::sqrt(2 * pin_drop / gravity);
  e.v1 = gravity * t;
  double v = e.v1;
  while (t <= pin_t_end + 1) {
    e.impacts.push_back(t);
    v *= pin_restitution;
    t += 2 * v / gravity;
    if (v < 1e-9) break;
  }
  return e;
}

struct PinRow {
  std::string engine, setting;
  double cpu = 0, error = 0;
  std::size_t steps = 0, impacts = 0, missed = 0, invented = 0;
  std::string failure;
};
std::vector<PinRow> pin_rows;

void pin_compare(PinRow& row, const std::vector<double>& found, double window) {
  PinExact exact = pin_exact();
  std::vector<double> expected;
  for (double t : exact.impacts)
    if (t <= pin_t_end) expected.push_back(t);
  row.impacts = found.size();
  for (double t : expected)
    row.missed += std::none_of(found.begin(), found.end(), [&](double f) { return std::abs(f - t) <= window; });
  for (double f : found)
    row.invented += std::none_of(expected.begin(), expected.end(), [&](double t) { return std::abs(f - t) <= window; });
}

std::string pin_model() {
  std::ostringstream m;
  m.precision(17);
  m << R"({"hipair": 1, "name": "falling-pin", "parts": [
    {"name": "pin", "motion": {"translation": {"direction": [0, 1], "limits": [-25, 5]}}, "initial": {"offset": 0},
     "dynamics": {"mass": )" << pin_mass << R"(},
     "loops": [{"start": [4.5, 24.5], "edges": [{"arc_to": [4.5, 24.5], "center": [0, 24.5], "dir": "ccw", "label": "pin"}]}]},
    {"name": "slot", "motion": "fixed",
     "loops": [{"start": [-20, -10], "edges": [{"line_to": [20, -10]}, {"line_to": [20, 20]}, {"line_to": [5, 20]},
       {"line_to": [5, 0], "label": "wall R"}, {"line_to": [-5, 0], "label": "bottom"}, {"line_to": [-5, 20], "label": "wall L"},
       {"line_to": [-20, 20]}, {"line_to": [-20, -10]}]}]}],
    "pairs": [{"parts": ["pin", "slot"], "restitution": )" << pin_restitution << R"(}],
    "simulation": {"gravity": [0, )" << -gravity << R"(]}})";
  return m.str();
}

void BM_PinHipair(benchmark::State& state, double accuracy) {
  PinRow row;
  row.engine = "HIPAIR";
  char text[32];
  std::snprintf(text, sizeof text, "accuracy %.0e", accuracy);
  row.setting = text;
  for (auto _ : state) {
    Model model = read_model(pin_model());
    SimulationOptions options;
    options.accuracy = accuracy;
    Simulation s = Simulation::create(model, options);
    PinExact exact = pin_exact();
    std::vector<std::pair<double, double>> states{{0, s.state().position[0]}};
    double start = bench::thread_cpu_seconds();
    try {
      s.run_until(pin_t_end, [&](double) { states.emplace_back(s.state().time, s.state().position[0]); });
    } catch (const Error& error) {
      row.failure = error.what();
    }
    row.cpu = bench::thread_cpu_seconds() - start;
    row.steps = s.steps();
    for (auto [t, offset] : states) row.error = std::max(row.error, std::abs(pin_drop + offset - exact.height(t)));
    std::vector<double> found;
    for (const SimulationEvent& e : s.events())
      if (e.kind == SimulationEvent::Kind::impact) found.push_back(e.time);
    pin_compare(row, found, 1e-3);
  }
  state.SetIterationTime(row.cpu);
  state.counters["error_mm"] = row.error;
  state.counters["impacts"] = static_cast<double>(row.impacts);
  pin_rows.push_back(row);
}

#ifdef HIPAIR_HAVE_BOX2D
void BM_PinBox2d(benchmark::State& state, double step) {
  PinRow row;
  row.engine = "Box2D";
  char text[48];
  std::snprintf(text, sizeof text, "h %.2g ms", step * 1e3);
  row.setting = text;
  for (auto _ : state) {
    b2World world(b2Vec2(0, static_cast<float>(-gravity / box2d_unit)));
    b2BodyDef ground_def;
    b2Body* ground = world.CreateBody(&ground_def);
    auto block = [&](double x0, double y0, double x1, double y1) {
      b2PolygonShape box;
      box.SetAsBox(static_cast<float>((x1 - x0) / 2 / box2d_unit), static_cast<float>((y1 - y0) / 2 / box2d_unit),
                   b2Vec2(static_cast<float>((x0 + x1) / 2 / box2d_unit), static_cast<float>((y0 + y1) / 2 / box2d_unit)), 0);
      b2FixtureDef f;
      f.shape = &box;
      f.restitution = static_cast<float>(pin_restitution);
      f.restitutionThreshold = 0;
      f.friction = 0;
      ground->CreateFixture(&f);
    };
    block(-20, -10, -5, 20);
    block(5, -10, 20, 20);
    block(-5, -10, 5, 0);
    b2BodyDef def;
    def.type = b2_dynamicBody;
    def.position.Set(0, static_cast<float>(24.5 / box2d_unit));
    def.fixedRotation = true;
    def.bullet = true;
    def.allowSleep = false;
    b2Body* pin = world.CreateBody(&def);
    b2CircleShape circle;
    circle.m_radius = static_cast<float>(pin_radius / box2d_unit);
    b2FixtureDef f;
    f.shape = &circle;
    f.density = 1;
    f.restitution = static_cast<float>(pin_restitution);
    f.restitutionThreshold = 0;
    f.friction = 0;
    pin->CreateFixture(&f);
    b2MassData mass;
    mass.mass = static_cast<float>(pin_mass);
    mass.center.SetZero();
    mass.I = 1;
    pin->SetMassData(&mass);
    b2PrismaticJointDef slide;
    slide.Initialize(ground, pin, pin->GetPosition(), b2Vec2(0, 1));
    slide.collideConnected = true;   // the slide's ground is the slot
    world.CreateJoint(&slide);
    PinExact exact = pin_exact();
    auto steps = static_cast<long>(std::llround(pin_t_end / step));
    std::vector<double> found;
    bool touching = false;
    double start = bench::thread_cpu_seconds();
    std::vector<std::pair<double, double>> states{{0, 24.5}};
    for (long k = 1; k <= steps; ++k) {
      world.Step(static_cast<float>(step), 8, 3);
      double t = static_cast<double>(k) * step;
      states.emplace_back(t, pin->GetPosition().y * box2d_unit);
      bool now = false;
      for (b2Contact* c = world.GetContactList(); c; c = c->GetNext()) now |= c->IsTouching();
      if (now && !touching) found.push_back(t);
      touching = now;
    }
    row.cpu = bench::thread_cpu_seconds() - start;
    row.steps = static_cast<std::size_t>(steps);
    for (auto [t, y] : states) row.error = std::max(row.error, std::abs(y - 4.5 - exact.height(t)));
    pin_compare(row, found, 2 * step + 1e-3);
  }
  state.SetIterationTime(row.cpu);
  state.counters["error_mm"] = row.error;
  state.counters["impacts"] = static_cast<double>(row.impacts);
  pin_rows.push_back(row);
}
#endif

#ifdef HIPAIR_HAVE_MUJOCO
// MuJoCo has no coefficient of restitution: a contact is a damped spring. solref = (-k, -b)
// sets its stiffness and damping per unit mass directly: a contact lasting about 5 ms (omega =
// pi / 5 ms = 628 rad/s, k = omega^2 = 394784 s^-2) with damping ratio zeta = 0.0708, b = 2 zeta
// omega = 88.9 s^-1, rebounds with e = exp(-zeta pi / sqrt(1 - zeta^2)) = 0.8. (The (time
// constant, damping ratio) form with ratio 0.0708 is unstable: its stiffness grows as 1/ratio^2.)
void BM_PinMujoco(benchmark::State& state, double step) {
  PinRow row;
  row.engine = "MuJoCo";
  char text[64];
  std::snprintf(text, sizeof text, "h %.2g ms, Euler, solref -394784 -88.9", step * 1e3);
  row.setting = text;
  for (auto _ : state) {
    std::ostringstream xml;
    xml.precision(12);
    xml << "<mujoco><option timestep=\"" << step << "\" gravity=\"0 " << -gravity * 1e-3 << " 0\"/>"
        << "<default><geom friction=\"0 0 0\" condim=\"1\" solref=\"-394784 -88.9\"/></default><worldbody>"
        << "<geom type=\"box\" size=\"0.0075 0.015 0.005\" pos=\"-0.0125 0.005 0\"/>"
        << "<geom type=\"box\" size=\"0.0075 0.015 0.005\" pos=\"0.0125 0.005 0\"/>"
        << "<geom type=\"box\" size=\"0.005 0.005 0.005\" pos=\"0 -0.005 0\"/>"
        << "<body name=\"pin\" pos=\"0 0.0245 0\"><joint name=\"slide\" type=\"slide\" axis=\"0 1 0\"/>"
        << "<inertial pos=\"0 0 0\" mass=\"" << pin_mass << "\" diaginertia=\"1e-6 1e-6 1e-6\"/>"
        << "<geom type=\"cylinder\" size=\"0.0045 0.005\"/></body></worldbody></mujoco>";
    std::string text_xml = xml.str();
    mjVFS vfs;
    mj_defaultVFS(&vfs);
    mj_makeEmptyFileVFS(&vfs, "pin.xml", static_cast<int>(text_xml.size()));
    std::memcpy(vfs.filedata[mj_findFileVFS(&vfs, "pin.xml")], text_xml.data(), text_xml.size());
    char error[1000] = "";
    mjModel* m = mj_loadXML("pin.xml", &vfs, error, sizeof error);
    mj_deleteVFS(&vfs);
    if (!m) throw std::runtime_error(std::string("MuJoCo: ") + error);
    mjData* d = mj_makeData(m);
    PinExact exact = pin_exact();
    auto steps = static_cast<long>(std::llround(pin_t_end / step));
    std::vector<double> found;
    bool touching = false;
    std::vector<std::pair<double, double>> states{{0, 0}};
    double start = bench::thread_cpu_seconds();
    for (long k = 1; k <= steps; ++k) {
      mj_step(m, d);
      double t = static_cast<double>(k) * step;
      states.emplace_back(t, d->qpos[0] * 1e3);
      bool now = false;
      for (int i = 0; i < d->ncon; ++i) now |= d->contact[i].dist <= 0;
      if (now && !touching) found.push_back(t);
      touching = now;
    }
    row.cpu = bench::thread_cpu_seconds() - start;
    row.steps = static_cast<std::size_t>(steps);
    for (auto [t, y] : states) row.error = std::max(row.error, std::abs(pin_drop + y - exact.height(t)));
    pin_compare(row, found, 2 * step + 1e-3);
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  state.SetIterationTime(row.cpu);
  state.counters["error_mm"] = row.error;
  state.counters["impacts"] = static_cast<double>(row.impacts);
  pin_rows.push_back(row);
}
#endif

// ------------------------------------------------------------------ outputs
std::string number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

// Error used for the plot and the ratios: the larger of the drive and dwell errors, floored at
// 1e-15 rad (a zero cannot be drawn on a log scale).
// The deviation from the reference (0: not drawn: a failed run, or the reference run itself).
double plotted_deviation(const Row& r) {
  if (!r.failure.empty() || (r.engine == "HIPAIR" && r.parameter == reference_accuracy)) return 0;
  return std::max(r.deviation, 1e-15);
}

double plotted_error(const Row& r) {
  if (!r.failure.empty()) return 0;
  return std::max({r.error.drive, r.error.dwell, 1e-15});
}

std::string csv() {
  std::ostringstream out;
  out << "engine,setting,parameter,cpu_s,sim_s_per_cpu_s,setup_s,steps,err_drive_rad,err_dwell_rad,"
         "deviation_rad,episodes,raw_episodes,missed,invented,final_wheel_rad,failure\n";
  for (const Row& r : rows)
    out << r.engine << ",\"" << r.setting << "\"," << number(r.parameter) << "," << number(r.cpu) << ","
        << number(t_end / r.cpu) << "," << number(r.setup) << "," << r.steps << "," << number(r.error.drive) << ","
        << number(r.error.dwell) << "," << number(r.deviation) << "," << r.episodes << "," << r.raw_episodes << "," << r.missed << "," << r.invented
        << "," << number(r.final_wheel) << ",\"" << r.failure << "\"\n";
  return out.str();
}

std::string plot(double (*metric)(const Row&), const std::string& title) {
  bool any = false;
  for (const Row& r : rows) any |= r.failure.empty() && metric(r) > 0;
  if (!any) return io::SvgWriter(io::SvgBox{0, 0, 1, 1}).str();
  // log-log: x = log10(CPU seconds per simulated second), y = log10(error)
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const Row& r : rows) {
    if (!r.failure.empty() || !(metric(r) > 0)) continue;
    double x = std::log10(r.cpu / t_end), y = std::log10(metric(r));
    x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  }
  x0 = std::floor(x0), x1 = std::ceil(x1), y0 = std::floor(y0), y1 = std::ceil(y1);
  if (x1 <= x0) x1 = x0 + 1;
  if (y1 <= y0) y1 = y0 + 1;
  const double w = 100, h = 70;
  auto X = [&](double v) { return (v - x0) / (x1 - x0) * w; };
  auto Y = [&](double v) { return (v - y0) / (y1 - y0) * h; };
  io::SvgWriter svg(io::SvgBox{-14, -14, w + 42, h + 8}, 900);
  svg.set_default_stroke_width(0.2);
  io::SvgStyle grid;
  grid.stroke = "#dddddd";
  grid.stroke_width = 0.1;
  for (double v = x0; v <= x1 + 1e-9; v += 1) {
    svg.line(X(v), 0, X(v), h, grid);
    svg.text(X(v), -4, "1e" + number(v), 2.2);
  }
  for (double v = y0; v <= y1 + 1e-9; v += 1) {
    svg.line(0, Y(v), w, Y(v), grid);
    svg.text(-1, Y(v) - 0.8, "1e" + number(v), 2.2, "end");
  }
  io::SvgStyle frame;
  svg.rectangle(0, 0, w, h, frame);
  svg.text(w / 2, -9, "CPU seconds per simulated second (log)", 2.6);
  svg.text(0, h + 3, title, 2.6,
           "start", "black", "bold");
  const std::map<std::string, std::string> colours{{"HIPAIR", "#4e79a7"}, {"Box2D", "#e15759"}, {"MuJoCo", "#59a14f"}};
  std::vector<io::SvgWriter::LegendEntry> legend;
  std::map<std::string, std::vector<const Row*>> series;
  for (const Row& r : rows) {
    if (!r.failure.empty() || !(metric(r) > 0)) continue;
    std::string key = r.engine;
    if (r.engine == "MuJoCo") key += r.setting.find("RK4") != std::string::npos ? " RK4" : " Euler";
    if (r.engine == "MuJoCo" && r.setting.find("default") == std::string::npos) key += ", stiff";
    series[key].push_back(&r);
  }
  const char* extra[] = {"#f28e2b", "#b07aa1", "#76b7b2", "#9c755f"};
  int next = 0;
  for (auto& [key, list] : series) {
    std::string engine = key.substr(0, key.find(' '));
    std::string colour = key == engine ? colours.at(engine) : extra[next++ % 4];
    std::sort(list.begin(), list.end(), [](const Row* a, const Row* b) { return a->cpu < b->cpu; });
    io::SvgPath path;
    for (std::size_t i = 0; i < list.size(); ++i) {
      double x = X(std::log10(list[i]->cpu / t_end)), y = Y(std::log10(metric(*list[i])));
      if (i == 0) path.move_to(x, y);
      else path.line_to(x, y);
    }
    io::SvgStyle line;
    line.stroke = colour;
    line.stroke_width = 0.35;
    svg.path(path, line);
    io::SvgStyle dot;
    dot.fill = colour;
    dot.stroke = colour;
    for (const Row* r : list) svg.circle(X(std::log10(r->cpu / t_end)), Y(std::log10(metric(*r))), 0.8, dot);
    legend.push_back({dot, key});
  }
  svg.legend(w + 2, h, legend, 2.4);
  return svg.str();
}

}  // namespace

int main(int argc, char** argv) {
  std::string out;
  std::vector<char*> arguments{argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], "--out=", 6) == 0) out = argv[i] + 6;
    else arguments.push_back(argv[i]);
  }
  int count = static_cast<int>(arguments.size());
  // HIPAIR first: its tightest run gives the exact contact sequence the peers are compared with
  for (double accuracy : {1e-4, 1e-6, 1e-8, 1e-10, 1e-12}) {
    char name[64];
    std::snprintf(name, sizeof name, "BM_GenevaHipair/accuracy:%.0e", accuracy);
    benchmark::RegisterBenchmark(name, BM_GenevaHipair, accuracy)->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
  }
#ifdef HIPAIR_HAVE_BOX2D
  for (double step : {4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4, 1e-4}) {
    char name[64];
    std::snprintf(name, sizeof name, "BM_GenevaBox2d/h_ms:%g", step * 1e3);
    benchmark::RegisterBenchmark(name, BM_GenevaBox2d, step, 8, 3)->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
  }
  for (double step : {1e-3, 2.5e-4}) {
    char name[64];
    std::snprintf(name, sizeof name, "BM_GenevaBox2d/h_ms:%g/iterations:40", step * 1e3);
    benchmark::RegisterBenchmark(name, BM_GenevaBox2d, step, 40, 20)->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
  }
#endif
#ifdef HIPAIR_HAVE_MUJOCO
  for (double step : {4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4, 1e-4}) {
    char name[80];
    std::snprintf(name, sizeof name, "BM_GenevaMujoco/h_ms:%g/Euler", step * 1e3);
    benchmark::RegisterBenchmark(name, BM_GenevaMujoco, step, std::string("Euler"), 0.0)
        ->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
    std::snprintf(name, sizeof name, "BM_GenevaMujoco/h_ms:%g/RK4", step * 1e3);
    benchmark::RegisterBenchmark(name, BM_GenevaMujoco, step, std::string("RK4"), 0.0)
        ->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
    // the stiffest contact MuJoCo recommends: time constant 2 steps
    std::snprintf(name, sizeof name, "BM_GenevaMujoco/h_ms:%g/Euler/stiff", step * 1e3);
    benchmark::RegisterBenchmark(name, BM_GenevaMujoco, step, std::string("Euler"), 2 * step)
        ->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
  }
#endif
  for (double accuracy : {1e-6, 1e-9, 1e-12}) {
    char name[64];
    std::snprintf(name, sizeof name, "BM_PinHipair/accuracy:%.0e", accuracy);
    benchmark::RegisterBenchmark(name, BM_PinHipair, accuracy)->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
  }
#ifdef HIPAIR_HAVE_BOX2D
  for (double step : {1e-3, 2.5e-4, 1e-4}) {
    char name[64];
    std::snprintf(name, sizeof name, "BM_PinBox2d/h_ms:%g", step * 1e3);
    benchmark::RegisterBenchmark(name, BM_PinBox2d, step)->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
  }
#endif
#ifdef HIPAIR_HAVE_MUJOCO
  for (double step : {1e-3, 2.5e-4, 1e-4}) {
    char name[64];
    std::snprintf(name, sizeof name, "BM_PinMujoco/h_ms:%g", step * 1e3);
    benchmark::RegisterBenchmark(name, BM_PinMujoco, step)->Iterations(1)->UseManualTime()->Unit(benchmark::kMillisecond);
  }
#endif
  {
    Decomposition shape = decompose(12);
    std::size_t most = 0;
    for (const Polygon& p : shape.wheel) most = std::max(most, p.size());
    std::cout << "peers' Geneva: wheel in " << shape.wheel.size() << " convex pieces (at most " << most
              << " vertices), driver's locking segment in " << shape.driver.size() << " quadrilaterals, pin a circle\n";
  }
  benchmark::Initialize(&count, arguments.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();

  for (Row& r : rows) compare(r);
  // The table, and the ratios at equal CPU time: each peer's error interpolated (log-log, along
  // its own runs sorted by CPU time) at each HIPAIR run's CPU time.
  std::cout << "\nengine\tsetting\tCPU s\tsim/CPU\terr drive\terr dwell\tdeviation\tsteps\tepisodes(raw)\tmissed\tinvented\n";
  for (const Row& r : rows)
    std::cout << r.engine << "\t" << r.setting << "\t" << number(r.cpu) << "\t" << number(t_end / r.cpu) << "\t"
              << number(r.error.drive) << "\t" << number(r.error.dwell) << "\t" << number(r.deviation) << "\t" << r.steps << "\t" << r.episodes << "("
              << r.raw_episodes << ")\t" << r.missed << "\t" << r.invented
              << (r.failure.empty() ? "" : "\tFAILED at t = " + number(r.reached) + ": " + r.failure) << "\n";
  std::cout << "exact contact episodes (HIPAIR, accuracy " << number(exact_accuracy) << "):\n";
  for (const Episode& e : exact_episodes)
    std::cout << "  " << number(e.begin) << " .. " << number(e.end) << " s  " << e.label << "\n";
  // equal CPU time: for each successful HIPAIR run, each peer's smallest error among its runs
  // that took no more CPU time
  std::cout << "\nat equal CPU time (peer runs taking at most HIPAIR's CPU time):\n";
  for (const Row& h : rows) {
    if (h.engine != "HIPAIR" || !h.failure.empty()) continue;
    for (const char* peer : {"Box2D", "MuJoCo"}) {
      const Row* best = nullptr;
      for (const Row& r : rows)
        if (r.engine == peer && r.failure.empty() && r.cpu <= h.cpu && (!best || plotted_error(r) < plotted_error(*best)))
          best = &r;
      if (!best) continue;
      std::cout << "  HIPAIR " << h.setting << " (" << number(h.cpu) << " s, error " << number(plotted_error(h)) << ") vs "
                << peer << " " << best->setting << " (" << number(best->cpu) << " s, error " << number(plotted_error(*best))
                << "): HIPAIR " << number(plotted_error(*best) / plotted_error(h)) << "x more accurate\n";
      const Row* closest = nullptr;
      for (const Row& r : rows)
        if (r.engine == peer && r.failure.empty() && r.cpu <= h.cpu &&
            (!closest || plotted_deviation(r) < plotted_deviation(*closest)))
          closest = &r;
      if (plotted_deviation(h) > 0)
        std::cout << "    deviation from the reference: HIPAIR " << number(plotted_deviation(h)) << ", " << peer << " "
                << closest->setting << " " << number(plotted_deviation(*closest)) << ": ratio "
                << number(plotted_deviation(*closest) / plotted_deviation(h)) << "\n";
    }
  }
  for (const Row& r : rows) {
    if (r.engine == "HIPAIR") continue;
    std::cout << r.engine << ", " << r.setting << ": contact episodes (merged within " << number(r.window) << " s)\n";
    for (const Episode& e : merged(r.found, r.window))
      std::cout << "  " << number(e.begin) << " .. " << number(e.end) << " s  " << e.label << "\n";
  }
  if (!pin_rows.empty()) {
    PinExact exact = pin_exact();
    std::size_t n = 0;
    for (double t : exact.impacts) n += t <= pin_t_end;
    std::cout << "\nfalling pin in a slot: " << n << " impacts in " << number(pin_t_end) << " s (closed form, first at "
              << number(exact.impacts.front()) << " s)\nengine\tsetting\tCPU s\tsim/CPU\terror mm\tsteps\timpacts\tmissed\tinvented\n";
    for (const PinRow& r : pin_rows)
      std::cout << r.engine << "\t" << r.setting << "\t" << number(r.cpu) << "\t" << number(pin_t_end / r.cpu) << "\t"
                << number(r.error) << "\t" << r.steps << "\t" << r.impacts << "\t" << r.missed << "\t" << r.invented
                << (r.failure.empty() ? "" : "\tFAILED: " + r.failure) << "\n";
  }
  if (!out.empty()) {
    std::filesystem::create_directories(out);
    io::write_file_atomically(std::filesystem::path(out) / "simulation-peers.csv", csv());
    io::write_file_atomically(
        std::filesystem::path(out) / "simulation-peers.svg",
        plot(plotted_error, "Geneva drive, 2 s: wheel-angle error against the closed form (rad, log), floored at 1e-15"));
    io::write_file_atomically(
        std::filesystem::path(out) / "simulation-peers-deviation.svg",
        plot(plotted_deviation, "Geneva drive, 2 s: largest wheel-angle deviation from the reference run (rad, log)"));
    // the peers' geometry at the initial configuration: every convex piece outlined
    {
      Decomposition shape = decompose(12);
      io::SvgWriter svg(io::SvgBox{-70, -70, 146, 70}, 900);
      svg.set_default_stroke_width(0.15);
      auto draw = [&](const Polygon& p, Vec2 offset, const std::string& colour) {
        io::SvgPath path;
        path.move_to(p[0].x + offset.x, p[0].y + offset.y);
        for (std::size_t i = 1; i < p.size(); ++i) path.line_to(p[i].x + offset.x, p[i].y + offset.y);
        path.close();
        io::SvgStyle style;
        style.fill = colour;
        style.opacity = 0.5;
        svg.path(path, style);
      };
      for (const Polygon& p : shape.wheel) draw(p, {0, 0}, "#f28e2b");
      for (const Polygon& p : shape.driver) draw(p, {centre, 0}, "#4e79a7");
      io::SvgStyle pin;
      pin.fill = "#4e79a7";
      svg.circle(centre + shape.pin.x, shape.pin.y, pin_radius, pin);
      svg.text(-65, 63, "Box2D / MuJoCo geometry: convex pieces (wheel " + std::to_string(shape.wheel.size()) +
                            ", locking segment " + std::to_string(shape.driver.size()) + ")", 4, "start");
      io::write_file_atomically(std::filesystem::path(out) / "geneva-peer-pieces.svg", svg.str());
    }
    std::cout << "wrote " << out << "/simulation-peers.csv, simulation-peers.svg, simulation-peers-deviation.svg, "
                                    "geneva-peer-pieces.svg\n";
  }
  return 0;
}
