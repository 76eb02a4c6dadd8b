// Sliced (3-DOF) pairs at extreme uniform scales (session 43; docs/cspace.md, "Scale and
// degenerate curves"): the same pair drawn at s = 10^-300, 10^-30, 1, 10^30 mm (every length
// multiplied by s exactly) has the same critical angles (the same algebraic numbers, the arm's
// closed form among them), the same intervals, free cells, contact keys, crossings and
// components, and at 1,200 generated configurations (s x, s y, t) the location of (x, y, t) at
// scale 1, which equals the exact overlap oracle's relation of the posed scaled parts. At
// 10^400 mm the slices' coordinates leave the doubles: the build is refused with one clear
// message (GeometryError naming the part) unless asked to normalise the lengths, and then sliced
// in units of 2^L mm, the same as at 1 (session 50). The scale-free frame of the critical angles
// (sliced::scale_free_factor) is checked on generated parts: the scaled coordinates are
// coprime integers, and ordinary or mixed-scale parts keep model units.
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/cspace.hpp>
#include <hipair/sliced.hpp>

#include "algebra/exact_real.hpp"
#include "algebra/polynomial.hpp"
#include "cli/cspace_sliced.hpp"
#include "core/model_scale.hpp"
#include "sliced/critical_angles.hpp"
#include "sliced_model_support.hpp"
#include "test_paths.hpp"
#include "random_rationals.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace hipair {
namespace {

using namespace sliced_models;
namespace algebra = cspace::algebra;


// The L-shaped corridor of tests/unit/sliced_test.cpp (width W = 4: the arm's critical angle is
// the root in (0, 1) of (W - 2) - 2 L t + (W + 2) t^2); a 6 x 2 peg turns the corner. Its pivot
// is off the origin, (1/3, -1/7), so that the pivot is scaled too.
Model corridor(const Rational& length) {
  std::string hole = polygon({{-20, 0}, {4, 0}, {4, 20}, {0, 20}, {0, 4}, {-20, 4}});
  std::string outer = polygon({{-30, -30}, {30, -30}, {30, 30}, {-30, 30}});
  Rational px(1, 3), py(-1, 7);
  std::string peg = polygon({{px - length / 2, py - 1}, {px + length / 2, py - 1}, {px + length / 2, py + 1}, {px - length / 2, py + 1}});
  return read_model(R"({ "hipair": 1, "name": "corridor", "parts": [
    { "name": "fixed", "motion": "fixed", "loops": [ )" + outer + ", " + hole + R"( ] },
    { "name": "free", "motion": { "planar": { "pivot": )" + point(px, py) + R"( } }, "loops": [ )" + peg + R"( ] } ] })");
}

Model scaled(const Model& model, const Rational& s) {
  Model out = model;
  for (auto& part : out.parts) part = sliced::scaled_part(part, s);
  return out;
}

using test_numbers::power_of_ten;

algebra::Real real(const AlgebraicNumber& a) {
  algebra::Real t;
  t.polynomial = a.polynomial;
  t.lower = a.lower;
  t.upper = a.upper;
  t.exact = a.exact;
  return t;
}

struct Structure {
  std::vector<std::string> interval_keys;   // per interval: its free cells' contact keys
  std::vector<std::size_t> connections;     // per crossing
  std::size_t components = 0;
};

Structure structure_of(const SlicedSpace& space) {
  Structure out;
  for (const auto& in : space.intervals()) {
    std::string keys;
    for (const auto& c : in.free_cells) keys += c.contacts + " | ";
    out.interval_keys.push_back(keys);
  }
  for (const auto& c : space.crossings()) out.connections.push_back(c.connections.size());
  out.components = space.components();
  return out;
}

// Every connection's witnesses are the model's configurations (not a frame's): free by the
// exact overlap oracle on the model's parts, located in the connected cells of the two
// intervals, and the pure rotation between them is free (the motion's exact first contact).
void expect_witnesses_certified(const Model& model, const SlicedSpace& space) {
  for (const auto& crossing : space.crossings())
    for (const auto& link : crossing.connections) {
      EXPECT_EQ(static_cast<int>(kind_at(model, link.left_witness)), static_cast<int>(SlicedLocation::Kind::free));
      EXPECT_EQ(static_cast<int>(kind_at(model, link.right_witness)), static_cast<int>(SlicedLocation::Kind::free));
      SlicedLocation l = space.locate(link.left_witness), r = space.locate(link.right_witness);
      EXPECT_EQ(l.interval, crossing.left_interval);
      EXPECT_EQ(l.cell, link.left_cell);
      EXPECT_EQ(r.interval, crossing.right_interval);
      EXPECT_EQ(r.cell, link.right_cell);
      SlicedMotion turn;
      turn.from = link.left_witness;
      turn.to = link.right_witness;
      turn.through_half_turn = link.through_half_turn;
      EXPECT_TRUE(space.motion_free(turn)) << "crossing " << crossing.critical;
    }
}

TEST(SlicedScale, UniformScalesHaveTheSameCriticalAnglesCellsAndLocations) {
  const Model unit = corridor(6);
  const SlicedSpace reference = SlicedSpace::build(unit, "fixed", "free");
  const Structure expected = structure_of(reference);
  ASSERT_GT(reference.critical_angles().size(), 4u);
  // the arm's closed form is among the critical angles
  const algebra::Polynomial arm = algebra::from_rationals({Rational(4 - 2), Rational(-2 * 6), Rational(4 + 2)});
  // configurations at scale 1: random offsets in the box and vertex-vertex contacts, at random
  // rational angles and at the representatives
  Random random(4343);
  std::vector<SlicedConfiguration> configurations;
  std::vector<Point> av, bv;
  for (const auto& loop : unit.parts[0].loops)
    for (const auto& e : loop.edges) av.push_back(e.source);
  for (const auto& loop : unit.parts[1].loops)
    for (const auto& e : loop.edges) bv.push_back(e.source);
  const Point pivot = unit.parts[1].motion.pivot;
  std::vector<SlicedAngle> angles{SlicedAngle{0, true}};
  for (const auto& in : reference.intervals()) angles.push_back(in.representative);
  while (angles.size() < 24) angles.push_back(SlicedAngle{random_rational(random, -3, 3, 29), false});
  for (std::size_t n = 0; n < angles.size(); ++n) {
    const SlicedAngle& angle = angles[n];
    // the free cells' samples of the representative slices (a narrow corridor: random offsets
    // are mostly blocked)
    std::vector<Point> free_samples;
    if (n >= 1 && n <= reference.intervals().size())
      for (const auto& cell : reference.slice(angle)->cells())
        if (cell.kind == CellKind::free) free_samples.push_back(Point{cell.sample_x, cell.sample_y});
    const auto [c, s] = sliced_models::rotation(angle);
    for (int k = 0; k < 50; ++k) {
      SlicedConfiguration q;
      q.angle = angle;
      if (k % 5 == 0) {
        const Point& a = av[random() % av.size()];
        const Point& b = bv[random() % bv.size()];
        std::tie(q.x, q.y) = sliced_models::vertex_vertex_offset(a, b, pivot, c, s);
      } else if (k % 5 == 1 && !free_samples.empty()) {
        const Point& p = free_samples[random() % free_samples.size()];
        q.x = p.x;
        q.y = p.y;
      } else {
        q.x = random_rational(random, Rational(-25), Rational(25));
        q.y = random_rational(random, Rational(-25), Rational(25));
      }
      configurations.push_back(q);
    }
  }
  std::vector<SlicedLocation> unit_locations;
  int counts[3] = {0, 0, 0};
  for (const auto& q : configurations) {
    unit_locations.push_back(reference.locate(q));
    ASSERT_EQ(static_cast<int>(unit_locations.back().kind), static_cast<int>(kind_at(unit, q)));
    ++counts[static_cast<int>(unit_locations.back().kind)];
  }
  EXPECT_GT(counts[0], 40);
  EXPECT_GT(counts[1], 50);
  EXPECT_GT(counts[2], 20);
  SlicedConfiguration in_horizontal_arm{-10, 2, SlicedAngle{0, false}}, in_vertical_arm{2, 12, SlicedAngle{1, false}};
  ASSERT_TRUE(reference.connected(in_horizontal_arm, in_vertical_arm));

  for (int e : {-300, -30, 30}) {
    SCOPED_TRACE("scale 1e" + std::to_string(e));
    const Rational s = power_of_ten(e);
    const Model model = scaled(unit, s);
    // the critical angles are computed in the scale-free frame: k s is a small rational
    auto k = sliced::scale_free_factor(model.parts[0], model.parts[1]);
    ASSERT_TRUE(k.has_value());
    Rational ks = *k * s;
    EXPECT_LT(mpz_sizeinbase(ks.get_num_mpz_t(), 2) + mpz_sizeinbase(ks.get_den_mpz_t(), 2), 16u) << ks.get_str();
    const SlicedSpace space = SlicedSpace::build(model, "fixed", "free");
    ASSERT_EQ(space.critical_angles().size(), reference.critical_angles().size());
    int arm_roots = 0;
    for (std::size_t i = 0; i < space.critical_angles().size(); ++i) {
      const auto& c = space.critical_angles()[i];
      const auto& r = reference.critical_angles()[i];
      ASSERT_EQ(c.half_turn, r.half_turn);
      EXPECT_EQ(c.events, r.events);
      if (c.half_turn) continue;
      algebra::Real a = real(c.t), b = real(r.t);
      EXPECT_EQ(algebra::compare(a, b), 0) << c.t.to_string("t") << " vs " << r.t.to_string("t");
      if (!a.exact && algebra::vanishes_at(arm, a) && a.compare(0) > 0 && a.compare(1) < 0) ++arm_roots;
    }
    EXPECT_EQ(arm_roots, 1);
    const Structure got = structure_of(space);
    EXPECT_EQ(got.interval_keys, expected.interval_keys);
    // Connectivity across the critical angles: the same connections per crossing and the same
    // components at every scale (session 44: main 7373213 missed a connection of crossing 7 at
    // 10^-30 and 10^-300, 4 components for 3)
    EXPECT_EQ(got.connections, expected.connections);
    EXPECT_EQ(got.components, expected.components);
    // every connection's witnesses certified on the scaled parts
    expect_witnesses_certified(model, space);
    for (std::size_t n = 0; n < configurations.size(); ++n) {
      SlicedConfiguration q = configurations[n];
      q.x *= s;
      q.y *= s;
      SlicedLocation l = space.locate(q);
      ASSERT_EQ(static_cast<int>(l.kind), static_cast<int>(unit_locations[n].kind)) << "configuration " << n;
      EXPECT_EQ(l.interval, unit_locations[n].interval);
      EXPECT_EQ(l.cell, unit_locations[n].cell);
      if (n % 10 == 0) EXPECT_EQ(static_cast<int>(kind_at(model, q)), static_cast<int>(l.kind)) << "configuration " << n;
    }
    SlicedConfiguration h = in_horizontal_arm, v = in_vertical_arm;
    h.x *= s;
    h.y *= s;
    v.x *= s;
    v.y *= s;
    EXPECT_TRUE(space.connected(h, v));
  }
}

// Path planning (SlicedSpace::path) at extreme scales: between configurations of the corridor
// in one component (the two arms, and free cells' interior points of representative slices),
// generated at scale 1 and multiplied by s, a path is found at 10^-300, 10^-30, 10^30 and 10^300
// as at scale 1, and every straight motion of it is certified free again (first_crossing), its
// ends the queries.
TEST(SlicedScale, PathsAreFoundAndCertifiedAtEveryScale) {
  const Model unit = corridor(6);
  const SlicedSpace reference = SlicedSpace::build(unit, "fixed", "free");
  std::vector<std::pair<SlicedConfiguration, SlicedConfiguration>> queries{
      {SlicedConfiguration{-10, 2, SlicedAngle{0, false}}, SlicedConfiguration{2, 12, SlicedAngle{1, false}}}};
  // interior points of free cells of two representative slices (a cell's sample), joined to
  // the first query's start when in its component
  Random random(4444);
  std::vector<SlicedConfiguration> inner;
  for (const auto& in : reference.intervals())
    for (const auto& cell : reference.slice(in.representative)->cells())
      if (cell.kind == CellKind::free) {
        SlicedConfiguration q{cell.sample_x, cell.sample_y, in.representative};
        if (reference.connected(q, queries[0].first)) inner.push_back(q);
      }
  ASSERT_GE(inner.size(), 4u);
  for (int k = 0; k < 2; ++k) queries.push_back({inner[random() % inner.size()], inner[random() % inner.size()]});
  for (int e : {0, -300, -30, 30, 300}) {
    SCOPED_TRACE("scale 1e" + std::to_string(e));
    const Rational s = power_of_ten(e);
    const Model model = scaled(unit, s);
    const SlicedSpace space = SlicedSpace::build(model, "fixed", "free");
    for (std::size_t n = 0; n < queries.size(); ++n) {
      SlicedConfiguration a = queries[n].first, b = queries[n].second;
      a.x *= s;
      a.y *= s;
      b.x *= s;
      b.y *= s;
      SlicedPath path = space.path(a, b);
      ASSERT_EQ(static_cast<int>(path.status), static_cast<int>(SlicedPath::Status::found)) << "query " << n;
      ASSERT_GE(path.waypoints.size(), 1u);
      ASSERT_EQ(path.through_half_turn.size() + 1, path.waypoints.size());
      EXPECT_TRUE(path.waypoints.front().x == a.x && path.waypoints.front().y == a.y);
      EXPECT_TRUE(path.waypoints.back().x == b.x && path.waypoints.back().y == b.y);
      for (std::size_t i = 0; i + 1 < path.waypoints.size(); ++i) {
        SlicedMotion m;
        m.from = path.waypoints[i];
        m.to = path.waypoints[i + 1];
        m.through_half_turn = path.through_half_turn[i];
        EXPECT_TRUE(space.motion_free(m)) << "query " << n << " motion " << i;
      }
    }
  }
}

// A pair with arcs (examples/models/peg-in-slot.json: a stadium peg in a plate with a slot)
// crosses its critical angles in the scale-free frame too, its steady test on the model's
// configuration q / k (the motion checker, model units): at 10^-300 and 10^30 the same contact
// keys, connections per crossing and components as at 1, and every connection's witnesses free
// by the exact overlap oracle, in the connected cells, the rotation between them free.
TEST(SlicedScale, PairWithArcsCrossesInTheFrameAsAtScaleOne) {
  const Model unit = read_model_file(std::string(hipair::test::examples_dir()) + "/peg-in-slot.json");
  ASSERT_EQ(unit.parts.size(), 2u);
  const SlicedSpace reference = SlicedSpace::build(unit, unit.parts[0].name, unit.parts[1].name);
  const Structure expected = structure_of(reference);
  ASSERT_GT(expected.connections.size(), 4u);
  for (int e : {-300, 30}) {
    SCOPED_TRACE("scale 1e" + std::to_string(e));
    const Model model = scaled(unit, power_of_ten(e));
    ASSERT_TRUE(sliced::scale_free_factor(model.parts[0], model.parts[1]).has_value());
    const SlicedSpace space = SlicedSpace::build(model, model.parts[0].name, model.parts[1].name);
    const Structure got = structure_of(space);
    EXPECT_EQ(got.interval_keys, expected.interval_keys);
    EXPECT_EQ(got.connections, expected.connections);
    EXPECT_EQ(got.components, expected.components);
    expect_witnesses_certified(model, space);
  }
}

// A pair drawn at an extreme scale crosses its critical angles in a frame of ordinary size (the
// integers of scale_free_factor divided by sliced::size_unit) as a pair at 1 mm does, with its
// cells' samples alone (session 52; session 51's frame of integers up to 36 540 put the samples
// against the cells' sides and needed steps of k x unit, whose rationals carried the model's
// 10^300: 2x the build's time at 10^-300). Generated corridors (peg 27/5 and three random
// lengths in [5, 6]) times S = 10^e r (e = -300, -30, 30, 300 in turn; r random in [1/2, 2)):
// the same critical angles (exactly), free cells' contact keys, connections per crossing and
// components as at 1; every witness free by the exact overlap oracle at S and located in its
// connected cell, and the turn between a link's witnesses free.
TEST(SlicedScale, ExtremeScalesCrossInAFrameOfOrdinarySizeAsAtScaleOne) {
  Random random(5252);
  const int exponents[] = {-300, -30, 30, 300};
  for (int n = 0; n < 4; ++n) {
    const Rational length = n == 0 ? Rational(27, 5) : random_rational(random, Rational(5), Rational(6));
    const Model unit = corridor(length);
    const SlicedSpace reference = SlicedSpace::build(unit, "fixed", "free");
    const Structure expected = structure_of(reference);
    const int e = exponents[n];
    const Rational r = random_rational(random, Rational(1, 2), Rational(2), 1000);
    SCOPED_TRACE("peg " + to_exact_string(length) + ", scale 1e" + std::to_string(e) + " * " + to_exact_string(r));
    const Model model = scaled(unit, power_of_ten(e) * r);
    ASSERT_TRUE(sliced::scale_free_factor(model.parts[0], model.parts[1]).has_value());
    const SlicedSpace space = SlicedSpace::build(model, "fixed", "free");
    ASSERT_EQ(space.critical_angles().size(), reference.critical_angles().size());
    for (std::size_t i = 0; i < space.critical_angles().size(); ++i) {
      const auto& c = space.critical_angles()[i];
      const auto& u = reference.critical_angles()[i];
      EXPECT_EQ(c.half_turn, u.half_turn);
      if (!c.half_turn && !u.half_turn) EXPECT_EQ(algebra::compare(real(c.t), real(u.t)), 0) << "critical angle " << i;
    }
    const Structure got = structure_of(space);
    EXPECT_EQ(got.interval_keys, expected.interval_keys);
    EXPECT_EQ(got.connections, expected.connections);
    EXPECT_EQ(got.components, expected.components);
    expect_witnesses_certified(model, space);
  }
}

// Without SlicedBuildOptions::normalise_lengths (every consumer that reads lengths in mm:
// simulation, analysis) such a pair is still refused.
TEST(SlicedScale, BeyondTheDoublesTheBuildIsRefusedClearly) {
  const Model model = scaled(corridor(6), power_of_ten(400));
  try {
    SlicedSpace::build(model, "fixed", "free");
    FAIL() << "built";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("beyond 2^1016"), std::string::npos) << e.what();
  }
}

// Beyond the doubles, when asked (SlicedBuildOptions::normalise_lengths, as `hipair cspace`
// does): the corridor (peg lengths 6 and 11/2) times S = 10^e r (e = 400 and 450 respectively;
// r a random rational in [1/2, 2)) is sliced on its copy scaled by 2^-L, its lengths in units of 2^L mm.
// Against scale 1: the same critical angles (exactly) and events, free cells' contact keys,
// connections and components; 1,200 generated configurations (x, y, t) at 1, taken to
// (S x / 2^L, S y / 2^L, t), locate in the same interval and cell, and every tenth the exact
// overlap oracle on the parts at S (10^400-mm coordinates) at (S x, S y, t) says the same; every
// witness times 2^L is free by that oracle. The JSON (cli::sliced_json) is in mm: every free
// cell's sample and every witness read back is free by the oracle at S, and divided by 2^L
// lies in its cell (the witnesses: in the connected cells).
TEST(SlicedScale, BeyondTheDoublesWhenAskedTheBuildIsInUnitsOfAPowerOfTwo) {
  Random random(5050);
  for (const auto& [length, e] : {std::pair{Rational(6), 400}, std::pair{Rational(11, 2), 450}}) {
    const Model unit = corridor(length);
    const SlicedSpace reference = SlicedSpace::build(unit, "fixed", "free");
    const Structure expected = structure_of(reference);
    // configurations at 1: random offsets, the representative slices' free samples, at the
    // representatives and random rational angles
    std::vector<SlicedConfiguration> configurations;
    std::vector<SlicedAngle> angles;
    for (const auto& in : reference.intervals()) angles.push_back(in.representative);
    while (angles.size() < 24) angles.push_back(SlicedAngle{random_rational(random, -3, 3, 29), false});
    for (std::size_t n = 0; n < angles.size(); ++n) {
      std::vector<Point> free_samples;
      if (n < reference.intervals().size())
        for (const auto& cell : reference.slice(angles[n])->cells())
          if (cell.kind == CellKind::free) free_samples.push_back(Point{cell.sample_x, cell.sample_y});
      for (int k = 0; k < 50; ++k) {
        SlicedConfiguration q;
        q.angle = angles[n];
        if (k % 3 == 0 && !free_samples.empty()) {
          const Point& p = free_samples[random() % free_samples.size()];
          q.x = p.x;
          q.y = p.y;
        } else {
          q.x = random_rational(random, Rational(-25), Rational(25));
          q.y = random_rational(random, Rational(-25), Rational(25));
        }
        configurations.push_back(q);
      }
    }
    std::vector<SlicedLocation> unit_locations;
    for (const auto& q : configurations) unit_locations.push_back(reference.locate(q));
    {
      const Rational s = power_of_ten(e) * random_rational(random, Rational(1, 2), Rational(2), 1000);
      SCOPED_TRACE("length " + to_exact_string(length) + ", scale 1e" + std::to_string(e) + " * " +
                   to_exact_string(Rational(s / power_of_ten(e))));
      const Model model = scaled(unit, s);
      SlicedBuildOptions options;
      options.normalise_lengths = true;
      const SlicedSpace space = SlicedSpace::build(model, "fixed", "free", options);
      const long l = space.length_unit_exponent();
      ASSERT_GT(l, 1000);
      // S / 2^L: a configuration at 1 times it is the space's (units of 2^L mm)
      const Rational to_units = times_power_of_two(s, -l);
      ASSERT_TRUE(to_units > Rational(1, 64) && to_units < 64) << to_units.get_d();
      ASSERT_EQ(space.critical_angles().size(), reference.critical_angles().size());
      for (std::size_t i = 0; i < space.critical_angles().size(); ++i) {
        const auto& c = space.critical_angles()[i];
        const auto& r = reference.critical_angles()[i];
        ASSERT_EQ(c.half_turn, r.half_turn);
        EXPECT_EQ(c.events, r.events);
        if (!c.half_turn) EXPECT_EQ(algebra::compare(real(c.t), real(r.t)), 0) << "critical angle " << i;
      }
      const Structure got = structure_of(space);
      EXPECT_EQ(got.interval_keys, expected.interval_keys);
      EXPECT_EQ(got.connections, expected.connections);
      EXPECT_EQ(got.components, expected.components);
      for (std::size_t n = 0; n < configurations.size(); ++n) {
        SlicedConfiguration q = configurations[n];
        q.x *= to_units;
        q.y *= to_units;
        SlicedLocation got_location = space.locate(q);
        ASSERT_EQ(static_cast<int>(got_location.kind), static_cast<int>(unit_locations[n].kind)) << "configuration " << n;
        EXPECT_EQ(got_location.interval, unit_locations[n].interval);
        EXPECT_EQ(got_location.cell, unit_locations[n].cell);
        if (n % 10 == 0) {
          SlicedConfiguration in_mm = configurations[n];
          in_mm.x *= s;
          in_mm.y *= s;
          EXPECT_EQ(static_cast<int>(kind_at(model, in_mm)), static_cast<int>(got_location.kind)) << "configuration " << n;
        }
      }
      // the witnesses, in mm, on the parts at S
      auto mm = [&](SlicedConfiguration q) {
        q.x = times_power_of_two(q.x, l);
        q.y = times_power_of_two(q.y, l);
        return q;
      };
      for (const auto& crossing : space.crossings())
        for (const auto& link : crossing.connections) {
          EXPECT_EQ(static_cast<int>(kind_at(model, mm(link.left_witness))), static_cast<int>(SlicedLocation::Kind::free));
          EXPECT_EQ(static_cast<int>(kind_at(model, mm(link.right_witness))), static_cast<int>(SlicedLocation::Kind::free));
        }
      // the JSON, read back in mm
      const nlohmann::json doc = nlohmann::json::parse(cli::sliced_json(space, false));
      EXPECT_EQ(parse_rational(doc.at("bound").get<std::string>()), times_power_of_two(space.bound(), l));
      std::size_t samples = 0, witnesses = 0;
      for (std::size_t i = 0; i < space.intervals().size(); ++i) {
        const SlicedAngle angle = space.intervals()[i].representative;
        for (const auto& cell : doc.at("slices").at(i).at("free_cells")) {
          SlicedConfiguration q{parse_rational(cell.at("sample").at("x").get<std::string>()),
                                parse_rational(cell.at("sample").at("y").get<std::string>()), angle};
          EXPECT_EQ(static_cast<int>(kind_at(model, q)), static_cast<int>(SlicedLocation::Kind::free)) << "slice " << i;
          q.x = times_power_of_two(q.x, -l);
          q.y = times_power_of_two(q.y, -l);
          SlicedLocation at = space.locate(q);
          EXPECT_EQ(at.interval, i);
          EXPECT_EQ(at.cell, cell.at("index").get<std::size_t>());
          ++samples;
        }
      }
      for (const auto& crossing : doc.at("crossings"))
        for (std::size_t k = 0; k < crossing.at("witnesses").size(); ++k)
          for (const char* side : {"left", "right"}) {
            const auto& w = crossing.at("witnesses")[k].at(side);
            SlicedConfiguration q{parse_rational(w.at("x").get<std::string>()), parse_rational(w.at("y").get<std::string>()),
                                  SlicedAngle{w.at("half_turn").get<bool>() ? Rational(0) : parse_rational(w.at("t").get<std::string>()),
                                              w.at("half_turn").get<bool>()}};
            EXPECT_EQ(static_cast<int>(kind_at(model, q)), static_cast<int>(SlicedLocation::Kind::free));
            q.x = times_power_of_two(q.x, -l);
            q.y = times_power_of_two(q.y, -l);
            SlicedLocation at = space.locate(q);
            EXPECT_EQ(at.interval, crossing.at(std::string(side) + "_slice").get<std::size_t>());
            EXPECT_EQ(at.cell, crossing.at("connections")[k][std::string(side) == "left" ? 0 : 1].get<std::size_t>());
            ++witnesses;
          }
      EXPECT_GT(samples, 10u);
      EXPECT_GT(witnesses, 10u);
    }
  }
}

// The 3-D queries of a pair at extreme scales (issue 13, session 51): a caller holding the
// configurations of the model in mm gets the answers of the pair at scale 1. The corridor with a
// random peg length in [5, 6], times S = 10^e r (r a random rational in
// [1/2, 2)): at e = 400 the space is built in units of 2^L mm (SlicedBuildOptions::
// normalise_lengths), and a configuration given in mm is the space's with x and y times 2^-L
// (length_unit_exponent(); at e = -300, L = 0: mm). Generated at scale 1 — free configurations at
// the representatives and random rational angles, and random straight motions from them — each
// taken to mm (x S, y S) and then to the space's units, against the pair at 1 (the same number of
// components first): locate (kind,
// interval, cell) and connected; first_crossing's status, its first contact u
// (the same algebraic number: u does not depend on the unit), the feature pairs touching there,
// and its `before` mapped back to 1 a configuration of the motion before u, free by the exact
// overlap oracle at S in mm; features_near with the distance mapped (d S 2^-L): the same feature
// pairs, decided exactly at both, their certified distance bounds mapped back overlapping 1's;
// path between connected configurations: found, its ends the queries, every motion free and every
// waypoint taken to mm free by the oracle at S. Besides two drawn pairs, the 10^-300 pair this test
// first drew (peg 155/29, r = 733/656): it crossed its frame with 10 components for 3 before
// session 51 (its frame's samples hugged the cells' sides at the critical angles 0, +-90 and 180
// degrees: sliced_space.cpp's steps).
TEST(SlicedScale, QueriesInMillimetresAnswerAsAtScaleOne) {
  Random random(5151);
  std::size_t crossings = 0, near_pairs = 0, paths = 0, waypoints = 0;
  // (e, peg length, r): drawn where 0; the second is the pair this test first drew at 10^-300 in
  // session 51 (10 components for 3 before the frame's steps), kept whatever the draws give
  for (const auto& [e, fixed_length, fixed_r] : {std::tuple{400, Rational(0), Rational(0)},
                                                 std::tuple{-300, Rational(155, 29), Rational(733, 656)},
                                                 std::tuple{-300, Rational(0), Rational(0)}}) {
    const Rational length = sgn(fixed_length) > 0 ? fixed_length : random_rational(random, Rational(5), Rational(6), 31);
    const Model unit = corridor(length);
    const SlicedSpace reference = SlicedSpace::build(unit, "fixed", "free");
    const Rational r = sgn(fixed_r) > 0 ? fixed_r : random_rational(random, Rational(1, 2), Rational(2), 1000), s = power_of_ten(e) * r;
    SCOPED_TRACE("peg length " + to_exact_string(length) + ", scale 1e" + std::to_string(e) + " * " + to_exact_string(r));
    const Model model = scaled(unit, s);
    SlicedBuildOptions options;
    options.normalise_lengths = true;
    const SlicedSpace space = SlicedSpace::build(model, "fixed", "free", options);
    const long l = space.length_unit_exponent();
    EXPECT_EQ(l != 0, e > 0);
    EXPECT_EQ(space.components(), reference.components());
    // the caller's mapping: mm of the model at S to the space's units, and back
    auto in_units = [&](SlicedConfiguration q) {
      q.x = times_power_of_two(q.x, -l);
      q.y = times_power_of_two(q.y, -l);
      return q;
    };
    auto in_mm = [&](SlicedConfiguration q) {
      q.x = times_power_of_two(q.x, l);
      q.y = times_power_of_two(q.y, l);
      return q;
    };
    auto at_s = [&](SlicedConfiguration q) {   // a configuration of the pair at 1 in mm at S
      q.x *= s;
      q.y *= s;
      return q;
    };
    const Rational to_units = times_power_of_two(s, -l);   // a length at 1 in the space's units
    // free configurations at 1: the representatives' free samples and random offsets located
    // free, at the representatives and at random rational angles
    std::vector<SlicedAngle> angles;
    for (const auto& in : reference.intervals()) angles.push_back(in.representative);
    while (angles.size() < reference.intervals().size() + 8)
      angles.push_back(SlicedAngle{random_rational(random, angles.size() % 2 ? Rational(-3) : Rational(-1, 4),
                                                   angles.size() % 2 ? Rational(3) : Rational(1, 4), 29),
                                   false});
    std::vector<SlicedConfiguration> free;
    for (std::size_t n = 0; n < angles.size(); ++n) {
      if (n < reference.intervals().size())
        for (const auto& cell : reference.slice(angles[n])->cells())
          if (cell.kind == CellKind::free) free.push_back(SlicedConfiguration{cell.sample_x, cell.sample_y, angles[n]});
      for (int k = 0; k < 60; ++k) {   // offsets over the corridor's two arms
        SlicedConfiguration q{random_rational(random, Rational(-20), Rational(4)), random_rational(random, Rational(0), Rational(20)),
                              angles[n]};
        if (reference.locate(q).kind == SlicedLocation::Kind::free) free.push_back(q);
      }
    }
    ASSERT_GT(free.size(), 30u);
    for (std::size_t n = 0; n < free.size(); ++n) {
      const SlicedConfiguration& q = free[n];
      const SlicedConfiguration scaled_q = in_units(at_s(q));
      // location and connectivity
      const SlicedLocation want = reference.locate(q), got = space.locate(scaled_q);
      EXPECT_EQ(static_cast<int>(got.kind), static_cast<int>(want.kind)) << "configuration " << n;
      if (got.kind != want.kind) continue;
      EXPECT_EQ(got.interval, want.interval) << "configuration " << n;
      EXPECT_EQ(got.cell, want.cell) << "configuration " << n;
      const SlicedConfiguration& other = free[random() % free.size()];
      EXPECT_EQ(space.connected(scaled_q, in_units(at_s(other))), reference.connected(q, other)) << "configuration " << n;
      // a random straight motion from it (to a random offset and angle; mostly into contact)
      // (from the half turn: through it, in the chart centred there, to a t beyond 4 in size)
      const Rational turn = random_rational(random, Rational(-1), Rational(1), 13);
      SlicedMotion motion{q, SlicedConfiguration{Rational(q.x + random_rational(random, Rational(-12), Rational(12))),
                                                 Rational(q.y + random_rational(random, Rational(-12), Rational(12))),
                                                 SlicedAngle{q.angle.half_turn ? (sgn(turn) < 0 ? Rational(turn - 4) : Rational(turn + 4))
                                                                               : Rational(q.angle.t + turn),
                                                             false}},
                          q.angle.half_turn};
      SlicedMotion scaled_motion{in_units(at_s(motion.from)), in_units(at_s(motion.to)), motion.through_half_turn};
      const SlicedMotionCrossing c1 = reference.first_crossing(motion), cs = space.first_crossing(scaled_motion);
      EXPECT_EQ(static_cast<int>(cs.status), static_cast<int>(c1.status)) << "motion " << n;
      if (cs.status == CrossingStatus::crossing && c1.status == CrossingStatus::crossing) {
        ++crossings;
        EXPECT_EQ(algebra::compare(real(cs.u), real(c1.u)), 0) << "motion " << n;
        std::vector<std::string> labels1, labelss;
        for (const auto& f : c1.features) labels1.push_back(f.label);
        for (const auto& f : cs.features) labelss.push_back(f.label);
        std::sort(labels1.begin(), labels1.end());
        std::sort(labelss.begin(), labelss.end());
        EXPECT_EQ(labelss, labels1) << "motion " << n;
        // `before`, back at 1: on the motion, before u (x is linear in u), free at S in mm
        const SlicedConfiguration before_mm = in_mm(cs.before);
        EXPECT_EQ(static_cast<int>(kind_at(model, before_mm)), static_cast<int>(SlicedLocation::Kind::free)) << "motion " << n;
        const SlicedConfiguration before_1{Rational(before_mm.x / s), Rational(before_mm.y / s), cs.before.angle};
        EXPECT_EQ(static_cast<int>(reference.locate(before_1).kind), static_cast<int>(SlicedLocation::Kind::free)) << "motion " << n;
        const Rational dx = motion.to.x - motion.from.x;
        if (sgn(dx) != 0) {
          const Rational u_before = (before_1.x - motion.from.x) / dx;
          EXPECT_GE(sgn(u_before), 0) << "motion " << n;
          EXPECT_GE(real(c1.u).compare(u_before), 0) << "motion " << n;   // u_before <= u
          EXPECT_TRUE(before_1.y == motion.from.y + u_before * (motion.to.y - motion.from.y)) << "motion " << n;
        }
      }
      // features near it within a random distance
      const Rational d = random_rational(random, Rational(0), Rational(8), 17);
      const auto near1 = reference.features_near(q, d), nears = space.features_near(scaled_q, Rational(d * to_units));
      EXPECT_EQ(nears.size(), near1.size()) << "configuration " << n << " distance " << to_exact_string(d);
      std::map<std::string, std::pair<Rational, Rational>> bounds1;
      for (const auto& f : near1) {
        EXPECT_TRUE(f.exact);
        bounds1[f.pair.label] = {f.distance_lower, f.distance_upper};
      }
      for (const auto& f : nears) {
        EXPECT_TRUE(f.exact);
        auto found = bounds1.find(f.pair.label);
        if (found == bounds1.end()) {
          ADD_FAILURE() << f.pair.label << " near at S, not at 1";
          continue;
        }
        EXPECT_LE(f.distance_lower, found->second.second * to_units) << f.pair.label;
        EXPECT_LE(found->second.first * to_units, f.distance_upper) << f.pair.label;
        ++near_pairs;
      }
      // a path to another free configuration (every second: paths are the slow query)
      if (n % 2 != 0) continue;
      const SlicedPath p1 = reference.path(q, other);
      if (p1.status != SlicedPath::Status::found) {
        EXPECT_NE(static_cast<int>(space.path(scaled_q, in_units(at_s(other))).status), static_cast<int>(SlicedPath::Status::found));
        continue;
      }
      const SlicedPath ps = space.path(scaled_q, in_units(at_s(other)));
      EXPECT_EQ(static_cast<int>(ps.status), static_cast<int>(SlicedPath::Status::found)) << "configuration " << n;
      if (ps.status != SlicedPath::Status::found) continue;
      ++paths;
      ASSERT_EQ(ps.through_half_turn.size() + 1, ps.waypoints.size());
      EXPECT_TRUE(in_mm(ps.waypoints.front()).x == at_s(q).x && in_mm(ps.waypoints.front()).y == at_s(q).y);
      EXPECT_TRUE(in_mm(ps.waypoints.back()).x == at_s(other).x && in_mm(ps.waypoints.back()).y == at_s(other).y);
      for (std::size_t i = 0; i < ps.waypoints.size(); ++i) {
        EXPECT_EQ(static_cast<int>(kind_at(model, in_mm(ps.waypoints[i]))), static_cast<int>(SlicedLocation::Kind::free)) << "waypoint " << i;
        ++waypoints;
        if (i + 1 < ps.waypoints.size())
          EXPECT_TRUE(space.motion_free(SlicedMotion{ps.waypoints[i], ps.waypoints[i + 1], ps.through_half_turn[i]})) << "motion " << i;
      }
    }
  }
  EXPECT_GT(crossings, 40u);
  EXPECT_GT(near_pairs, 40u);
  EXPECT_GT(paths, 5u);
  EXPECT_GT(waypoints, 20u);
}

// Generated parts (random integer polygons, a random pivot) times s = 2^a 5^b 3^c / 7^d: the
// factor k makes every coordinate an integer, the integers coprime (k is exactly 1 / their
// common measure), and is applied only at extreme scales; a pair of mixed scales (one part
// 10^-300, the other millimetres) keeps model units.
TEST(SlicedScale, ScaleFreeFactorGivesCoprimeIntegers) {
  Random random(4343);
  int applied = 0;
  for (int instance = 0; instance < 200; ++instance) {
    auto make = [&](int n) {
      Part p;
      Loop loop;
      std::vector<Point> v;
      for (int i = 0; i < n; ++i) v.push_back(Point{Rational(static_cast<long>(random() % 2001) - 1000, 1 + static_cast<long>(random() % 8)),
                                                    Rational(static_cast<long>(random() % 2001) - 1000, 1 + static_cast<long>(random() % 8))});
      for (auto& q : v) {
        q.x.canonicalize();
        q.y.canonicalize();
      }
      for (int i = 0; i < n; ++i) {
        Edge e;
        e.source = v[i];
        e.target = v[(i + 1) % n];
        loop.edges.push_back(e);
      }
      p.loops.push_back(loop);
      return p;
    };
    Part a = make(3 + static_cast<int>(random() % 6)), b = make(3 + static_cast<int>(random() % 4));
    b.motion.kind = Motion::Kind::planar;
    b.motion.pivot = Point{Rational(static_cast<long>(random() % 201) - 100, 3), Rational(static_cast<long>(random() % 201) - 100, 5)};
    b.motion.pivot.x.canonicalize();
    b.motion.pivot.y.canonicalize();
    const int e2 = static_cast<int>(random() % 2401) - 1200, e5 = static_cast<int>(random() % 801) - 400;
    mpz_class two = 1, five, three, seven;
    two <<= static_cast<unsigned long>(std::abs(e2));
    mpz_ui_pow_ui(five.get_mpz_t(), 5, static_cast<unsigned long>(std::abs(e5)));
    mpz_ui_pow_ui(three.get_mpz_t(), 3, random() % 5);
    mpz_ui_pow_ui(seven.get_mpz_t(), 7, random() % 3);
    Rational s = Rational(e2 >= 0 ? two : mpz_class(1), e2 >= 0 ? mpz_class(1) : two) *
                 Rational(e5 >= 0 ? five : mpz_class(1), e5 >= 0 ? mpz_class(1) : five) * Rational(three, seven);
    s.canonicalize();
    const Part sa = sliced::scaled_part(a, s), sb = sliced::scaled_part(b, s);
    Rational largest = 0;
    for (const Part* p : {&sa, &sb})
      for (const auto& l : p->loops)
        for (const auto& e : l.edges)
          for (const Rational* x : {&e.source.x, &e.source.y}) largest = std::max(largest, Rational(abs(*x)));
    const bool extreme = largest < Rational(1, 1 << 20) || largest > Rational(mpz_class(1) << 40);
    auto k = sliced::scale_free_factor(sa, sb);
    SCOPED_TRACE("instance " + std::to_string(instance) + ", s = 2^" + std::to_string(e2) + " 5^" + std::to_string(e5));
    if (!extreme) {
      EXPECT_FALSE(k.has_value());
      continue;
    }
    ASSERT_TRUE(k.has_value());
    ++applied;
    mpz_class g = 0;
    const Part ka = sliced::scaled_part(sa, *k), kb = sliced::scaled_part(sb, *k);
    auto check = [&](const Rational& x) {
      ASSERT_EQ(x.get_den(), 1) << x.get_str();
      mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), x.get_num_mpz_t());
    };
    for (const Part* p : {&ka, &kb})
      for (const auto& l : p->loops)
        for (const auto& e : l.edges) {
          check(e.source.x);
          check(e.source.y);
        }
    check(kb.motion.pivot.x);
    check(kb.motion.pivot.y);
    EXPECT_EQ(g, 1);
    // the scaled pair is the unscaled one times a small factor
    Rational ks = *k * s;
    EXPECT_LT(mpz_sizeinbase(ks.get_num_mpz_t(), 2) + mpz_sizeinbase(ks.get_den_mpz_t(), 2), 48u);
    // mixed scales: the free part at s, the fixed part at 1: no factor shortens them
    if (instance % 4 == 0) EXPECT_FALSE(sliced::scale_free_factor(a, sb).has_value());
  }
  EXPECT_GT(applied, 150);
}

}  // namespace
}  // namespace hipair
