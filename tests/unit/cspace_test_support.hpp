// Shared helpers of the C-space tests: the oracle's chart axis of a public chart, a random
// rational configuration inside a random built chart or tile, the example spaces the query
// tests run on, exact descriptions of crossing answers, and the queries' switches.
#pragma once

#include "curves/contact_curves.hpp"
#include "test_paths.hpp"

#include <hipair/cspace.hpp>
#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <optional>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace hipair::test {

// The overlap oracle's description of one axis of a public chart.
inline cspace::ChartAxis axis_of(AxisKind kind, bool half_turn, const Rational& lo, const Rational& hi) {
  cspace::ChartAxis axis;
  axis.kind = kind == AxisKind::rotation ? cspace::ChartAxis::Kind::rotation : cspace::ChartAxis::Kind::translation;
  axis.half_turn = half_turn;
  axis.lo = lo;
  axis.hi = hi;
  return axis;
}

// The example pairs whose sliding contacts the derivative tests walk edge by edge (the Geneva
// drive, the cam and its follower, the Scotch yoke): model file and the pair's two parts.
struct SlidingPair {
  const char* file;
  const char* first;
  const char* second;
};
inline constexpr SlidingPair sliding_pairs[] = {
    {"geneva-drive.json", "driver", "wheel"}, {"cam-follower.json", "cam", "follower"}, {"scotch-yoke.json", "crank", "yoke"}};

// The example spaces the C-space query tests run on: the Geneva drive, the escapement's built
// pairs, the cam and its flat-faced follower.
inline std::vector<std::unique_ptr<CSpace>> example_spaces() {
  auto example = [](const char* name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; };
  std::vector<std::unique_ptr<CSpace>> owned;
  owned.push_back(std::make_unique<CSpace>(CSpace::build(read_model_file(example("geneva-drive.json")), "driver", "wheel")));
  for (const PairBuild& pair : CSpace::build_pairs(read_model_file(example("escapement.json"))))
    if (pair.status == PairBuild::Status::built) owned.push_back(std::make_unique<CSpace>(*pair.space));
  owned.push_back(std::make_unique<CSpace>(CSpace::build(read_model_file(example("cam-follower.json")), "cam", "follower")));
  return owned;
}

// The example spaces of example_spaces() with a sample count and a seed per model: fn(space,
// run) on Geneva driver:wheel with runs[0], on each built pair of the escapement with runs[1] and
// on cam:follower with runs[2]; stops at a fatal failure (the caller asserts on it).
struct ExampleSamples {
  int samples;
  std::uint64_t seed;
};
template <class Fn>
void on_example_spaces(const ExampleSamples (&runs)[3], Fn&& fn) {
  auto example = [](const char* name) { return std::filesystem::path(HIPAIR_EXAMPLES) / name; };
  fn(CSpace::build(read_model_file(example("geneva-drive.json")), "driver", "wheel"), runs[0]);
  if (::testing::Test::HasFatalFailure()) return;
  for (const PairBuild& pair : CSpace::build_pairs(read_model_file(example("escapement.json")))) {
    if (pair.status != PairBuild::Status::built) continue;
    fn(*pair.space, runs[1]);
    if (::testing::Test::HasFatalFailure()) return;
  }
  fn(CSpace::build(read_model_file(example("cam-follower.json")), "cam", "follower"), runs[2]);
}

// The degenerate corpus the motion tests also run on (tests/data/degenerate): every built pair
// of its models, each with its model's file name, in the corpus's order.
struct NamedSpace {
  std::string file;
  std::unique_ptr<CSpace> space;
};
inline std::vector<NamedSpace> degenerate_spaces() {
  std::vector<NamedSpace> spaces;
  for (const char* name : {"zero-clearance.json", "tangent-circles.json", "concentric-arcs.json", "coincident-edges.json",
                           "collinear-edges.json", "interval-contact.json", "vertex-on-vertex.json"}) {
    const Model model = read_model_file(std::filesystem::path(HIPAIR_TEST_DATA) / "degenerate" / name);
    for (const PairBuild& pair : CSpace::build_pairs(model))
      if (pair.status == PairBuild::Status::built) spaces.push_back({name, std::make_unique<CSpace>(*pair.space)});
  }
  return spaces;
}

// A random rational configuration inside a random built chart or tile (y = 0 in a 1-D space).
inline ChartPoint random_tile_point(const CSpace& space, std::mt19937_64& random) {
  std::size_t t = random() % space.charts().size();
  const CSpaceChart& chart = space.charts()[t];
  auto pick = [&](const Rational& lo, const Rational& hi) {
    Rational u(mpz_class(static_cast<unsigned long>(random() % 1000003)), 1000003);
    u.canonicalize();
    Rational v = lo + u * (hi - lo);
    v.canonicalize();
    return v;
  };
  Rational x = pick(chart.x_lo, chart.x_hi);
  Rational y = space.dimension() == 2 ? pick(chart.y_lo, chart.y_hi) : Rational(0);
  return ChartPoint{t, x, y};
}

// Every field of a first-crossing answer, printed exactly (rationals, doubles to 17 digits): two
// answers are the same when their descriptions are equal.
inline std::string describe_crossing(const CSpace& space, const MotionCrossing& c) {
  std::ostringstream out;
  out.precision(17);
  out << "status " << static_cast<int>(c.status) << " u [" << c.u_lower << ", " << c.u_upper << "] grazing " << c.grazing
      << " edge " << (c.edge.valid() ? static_cast<long>(c.edge.index()) : -1L) << " left "
      << (c.cell_left.valid() ? static_cast<long>(c.cell_left.index()) : -1L) << " entered "
      << (c.cell_entered.valid() ? static_cast<long>(c.cell_entered.index()) : -1L) << " chart "
      << static_cast<long>(c.chart == no_index ? -1 : static_cast<long>(c.chart)) << " features";
  for (FeatureId f : c.features) out << " " << space.feature_pair(f).label;
  for (const auto* ranges : {&c.chart_point, &c.point, &c.normal})
    for (const CertifiedRange& r : *ranges) out << " [" << r.lower << ", " << r.upper << "]";
  return out.str();
}

// Sets one of the C-space queries' switches (cspace/angle_filter.hpp: carried_bounds,
// second_order, start_anchors) for its lifetime.
template <bool& (*Flag)()>
struct FlagSwitch {
  explicit FlagSwitch(bool on) : old(Flag()) { Flag() = on; }
  ~FlagSwitch() { Flag() = old; }
  FlagSwitch(const FlagSwitch&) = delete;
  FlagSwitch& operator=(const FlagSwitch&) = delete;
  bool old;
};

// f(true) with the switch Flag on and f(false) with it off, in a random order (what a memo or
// filter answers must not depend on what ran before): {on, off}.
template <bool& (*Flag)(), class F>
auto on_and_off(std::mt19937_64& random, const F& f) {
  using Answer = decltype(f(true));
  Answer on{}, off{};
  if (random() % 2 == 0) {
    { FlagSwitch<Flag> flag(true); on = f(true); }
    { FlagSwitch<Flag> flag(false); off = f(false); }
  } else {
    { FlagSwitch<Flag> flag(false); off = f(false); }
    { FlagSwitch<Flag> flag(true); on = f(true); }
  }
  return std::pair<Answer, Answer>(std::move(on), std::move(off));
}

// A motion's axis as a polynomial in u with the given double coefficients (exact rationals).
inline AxisPath axis_path(AxisKind kind, const std::vector<double>& c) {
  AxisPath a;
  a.kind = kind == AxisKind::rotation ? AxisPath::Kind::angle : AxisPath::Kind::offset;
  for (double x : c) a.coefficients.push_back(Rational(x));
  return a;
}

// A chart coordinate back to the part's coordinate (angle or offset), in double.
inline double part_value(AxisKind kind, bool half_turn, double chart_value) {
  if (kind == AxisKind::translation) return chart_value;
  return (half_turn ? std::numbers::pi : 0.0) + 2 * std::atan(chart_value);
}

// The indices of the space's real edges (contact edges, not chart sides or seams).
inline std::vector<std::size_t> real_edges(const CSpace& space) {
  std::vector<std::size_t> edges;
  for (std::size_t e = 0; e < space.edges().size(); ++e)
    if (space.edges()[e].real) edges.push_back(e);
  return edges;
}

// A real, non-vertical edge's x range in doubles (its end vertices' approximations, ordered), or
// nothing for another edge or one narrower than 1e-9 (too short to sample inside).
inline std::optional<std::pair<double, double>> edge_x_range(const CSpace& space, std::size_t e) {
  const CSpaceEdge& edge = space.edges()[e];
  if (!edge.real || edge.vertical) return std::nullopt;
  double lo = space.vertices()[edge.source].x.approximate(), hi = space.vertices()[edge.target].x.approximate();
  if (lo > hi) std::swap(lo, hi);
  if (!(hi - lo > 1e-9)) return std::nullopt;
  return std::pair<double, double>(lo, hi);
}

}  // namespace hipair::test
