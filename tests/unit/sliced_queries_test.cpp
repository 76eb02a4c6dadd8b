// Queries of 3-DOF pairs (hipair/sliced.hpp): the exact first contact along a straight motion in
// (x, y, w) against dense exact sampling with the overlap oracle (polygon pairs, parts with arcs,
// motions through the half turn); feature pairs near a configuration against the first contacts
// of translations from it; certified paths through free space, each motion re-checked by
// sampling with the exact oracle.
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/sliced.hpp>

#include "algebra/exact_real.hpp"
#include "sliced/critical_angles.hpp"
#include "sliced_model_support.hpp"
#include "test_paths.hpp"
#include "test_seed.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace hipair {
namespace {

using namespace sliced_models;
using sliced::real_of;
namespace algebra = cspace::algebra;

// The motion's configuration at a rational u (straight in x, y and the chart's w).
SlicedConfiguration at(const SlicedMotion& m, const Rational& u) {
  auto w_of = [&](const SlicedAngle& a) {
    if (!m.through_half_turn) return a.t;
    return a.half_turn ? Rational(0) : Rational(-1 / a.t);
  };
  Rational w = w_of(m.from.angle) + u * (w_of(m.to.angle) - w_of(m.from.angle));
  SlicedAngle angle{w, false};
  if (m.through_half_turn) angle = sgn(w) == 0 ? SlicedAngle{0, true} : SlicedAngle{Rational(-1 / w), false};
  return SlicedConfiguration{Rational(m.from.x + u * (m.to.x - m.from.x)), Rational(m.from.y + u * (m.to.y - m.from.y)), angle};
}

// First contact vs dense sampling: every sample before u* is apart; the first sample that is not
// apart lies at or after u*; at a rational u* the parts touch; `before` is apart.
struct Tally {
  int crossings = 0, free_motions = 0, started_in_contact = 0, rational_roots = 0;
};
void expect_first_crossing_agrees(const Model& model, const SlicedSpace& space, const SlicedMotion& m, Tally& tally,
                                  int samples = 160) {
  SlicedMotionCrossing crossing = space.first_crossing(m);
  if (relation_at(model, m.from) != PartRelation::apart) {
    EXPECT_EQ(crossing.status, CrossingStatus::starts_in_contact);
    ++tally.started_in_contact;
    return;
  }
  ASSERT_NE(crossing.status, CrossingStatus::starts_in_contact);
  algebra::Real u;
  if (crossing.status == CrossingStatus::crossing) {
    u = real_of(crossing.u);
    EXPECT_LE(crossing.u_lower, crossing.u_upper);
    EXPECT_GE(u.compare(crossing.u_lower), 0);
    EXPECT_LE(u.compare(crossing.u_upper), 0);
    EXPECT_FALSE(crossing.features.empty());
    EXPECT_EQ(relation_at(model, crossing.before), PartRelation::apart);
    if (u.exact) {
      ++tally.rational_roots;
      EXPECT_EQ(relation_at(model, at(m, u.lower)), PartRelation::touching) << "at the exact first contact u = " << u.lower.get_str();
    }
    ++tally.crossings;
  } else {
    ++tally.free_motions;
  }
  for (int k = 0; k <= samples; ++k) {
    Rational s(k, samples);
    s.canonicalize();
    bool before = crossing.status != CrossingStatus::crossing || u.compare(s) > 0;
    PartRelation relation = relation_at(model, at(m, s));
    if (before)
      ASSERT_EQ(relation, PartRelation::apart) << "sample u = " << s.get_str() << " before the reported first contact";
    else if (relation != PartRelation::apart)
      break;   // the first sample in contact lies after u*
  }
}

SlicedConfiguration random_configuration(Random& random, const Rational& range) {
  SlicedConfiguration q;
  q.x = random_rational(random, -range, range);
  q.y = random_rational(random, -range, range);
  q.angle = random() % 17 == 0 ? SlicedAngle{0, true} : SlicedAngle{random_rational(random, -3, 3, 23), false};
  return q;
}

// Motions from random starts within `start_range` of the origin (where the free part sits in the
// fixed part's hole) to ends within `range`.
void check_random_motions(const Model& model, const SlicedSpace& space, Random& random, int motions, const Rational& range,
                          Tally& tally, const Rational& start_range) {
  for (int i = 0; i < motions; ++i) {
    SlicedMotion m;
    m.from = random_configuration(random, start_range);
    // short and long motions, some pure rotations, some pure translations
    switch (i % 4) {
      case 0: m.to = random_configuration(random, range); break;
      case 1: m.to = SlicedConfiguration{m.from.x, m.from.y, random_configuration(random, range).angle}; break;
      case 2: m.to = SlicedConfiguration{random_rational(random, -range, range), random_rational(random, -range, range), m.from.angle}; break;
      default: {
        SlicedConfiguration near = random_configuration(random, Rational(2));
        m.to = SlicedConfiguration{Rational(m.from.x + near.x), Rational(m.from.y + near.y), near.angle};
      }
    }
    m.through_half_turn = m.from.angle.half_turn || m.to.angle.half_turn ||
                          (random() % 3 == 0 && sgn(m.from.angle.t) != 0 && sgn(m.to.angle.t) != 0);
    if (m.through_half_turn && ((!m.from.angle.half_turn && sgn(m.from.angle.t) == 0) || (!m.to.angle.half_turn && sgn(m.to.angle.t) == 0)))
      continue;
    SCOPED_TRACE("motion " + std::to_string(i));
    expect_first_crossing_agrees(model, space, m, tally);
  }
}

TEST(SlicedQueries, FirstCrossingAgreesWithDenseSamplingOnRandomPolygonPairs) {
  Random random(2024);
  Tally tally;
  for (int instance = 0; instance < 3; ++instance) {
    auto a = star(random, 5 + static_cast<int>(random() % 4), 0, 0, 6);
    auto b = star(random, 3 + static_cast<int>(random() % 4), 1, 0, 4);
    Model model;
    try {
      model = pair_model(polygon(a), polygon(b), Point{1, 0});
    } catch (const ModelError&) {
      continue;
    }
    SlicedBuildOptions options;
    options.cell_structure = false;
    SlicedSpace space = SlicedSpace::build(model, "fixed", "free", options);
    SCOPED_TRACE("instance " + std::to_string(instance));
    check_random_motions(model, space, random, 60, Rational(8), tally, Rational(8));
  }
  EXPECT_GT(tally.crossings, 40);
  EXPECT_GT(tally.free_motions, 5);
}

TEST(SlicedQueries, FirstCrossingAgreesWithDenseSamplingForPartsWithArcs) {
  Random random(99);
  Tally tally;
  // a stadium peg against a plate with a round hole and a stadium slot; a round peg in a square hole
  std::vector<Model> models{
      pair_model(rectangle(-20, -20, 20, 20) + ", " + circle(-10, 8, 5) + ", " + stadium(Rational(3), Rational(2)),
                 stadium(Rational(2), Rational(3, 2)), Point{0, 0}),
      pair_model(rectangle(-20, -20, 20, 20) + ", " + rectangle(-6, -6, 6, 6), circle(1, 0, 4), Point{0, 0})};
  for (std::size_t k = 0; k < models.size(); ++k) {
    SCOPED_TRACE("model " + std::to_string(k));
    SlicedBuildOptions options;
    options.cell_structure = false;
    SlicedSpace space = SlicedSpace::build(models[k], "fixed", "free", options);
    check_random_motions(models[k], space, random, 80, Rational(12), tally, Rational(1, 2));
  }
  EXPECT_GT(tally.crossings, 30);
  EXPECT_GT(tally.free_motions, 3);
}

// Hand-checked first contacts: a 10 mm square peg centred in a 12 mm hole, sliding right, touches
// the hole's side at x = 1 (u = 1/4 of a motion to x = 4); turning in place, its corner
// (5, 5) reaches the side x = 6 where 5 (cos + sin) = 6 at the half-angle tangent
// t = (5 - sqrt(11))/11... (root of 11 t^2 - 10 t + 1 = 0 in (0, 1)); a round peg of radius 4
// centred at the pivot + (1, 0) in the same hole touches the side x = 6 after a shift of 1.
TEST(SlicedQueries, HandCheckedFirstContacts) {
  Model model = peg_in_hole(10, 12);
  SlicedBuildOptions options;
  options.cell_structure = false;
  SlicedSpace space = SlicedSpace::build(model, "fixed", "free", options);
  SlicedMotion slide{SlicedConfiguration{0, 0, SlicedAngle{0, false}}, SlicedConfiguration{4, 0, SlicedAngle{0, false}}};
  auto c = space.first_crossing(slide);
  ASSERT_EQ(c.status, CrossingStatus::crossing);
  EXPECT_TRUE(c.u.exact);
  EXPECT_EQ(c.u.lower, Rational(1, 4));
  EXPECT_EQ(c.features.size(), 2u);   // the peg's two right corners on the hole's right side
  SlicedMotion turn{SlicedConfiguration{0, 0, SlicedAngle{0, false}}, SlicedConfiguration{0, 0, SlicedAngle{1, false}}};
  c = space.first_crossing(turn);
  ASSERT_EQ(c.status, CrossingStatus::crossing);
  // 5 (c + s) = 6 with c = (1 - t^2)/(1 + t^2), s = 2t/(1 + t^2): 11 t^2 - 10 t + 1 = 0
  EXPECT_TRUE(algebra::vanishes_at(algebra::from_rationals({1, -10, 11}), real_of(c.u)));
  EXPECT_EQ(c.features.size(), 4u);   // four corners on four sides
  Model round = pair_model(rectangle(-20, -20, 20, 20) + ", " + rectangle(-6, -6, 6, 6), circle(1, 0, 4), Point{0, 0});
  SlicedSpace round_space = SlicedSpace::build(round, "fixed", "free", options);
  c = round_space.first_crossing(slide);
  ASSERT_EQ(c.status, CrossingStatus::crossing);
  EXPECT_EQ(c.u.lower, Rational(1, 4));
  ASSERT_EQ(c.features.size(), 1u);
  EXPECT_EQ(c.features[0].fixed.kind, FeatureKind::segment);
  EXPECT_EQ(c.features[0].free.kind, FeatureKind::arc);
  // turning the round peg about the pivot: its centre (1, 0) swings to (0, 1): never touches
  EXPECT_TRUE(round_space.motion_free(turn));
  // a motion starting in contact
  SlicedMotion touching{SlicedConfiguration{1, 0, SlicedAngle{0, false}}, SlicedConfiguration{0, 0, SlicedAngle{0, false}}};
  EXPECT_EQ(space.first_crossing(touching).status, CrossingStatus::starts_in_contact);
  // the half turn needs the chart through it
  SlicedMotion bad{SlicedConfiguration{0, 0, SlicedAngle{0, true}}, SlicedConfiguration{0, 0, SlicedAngle{1, false}}};
  EXPECT_THROW(space.first_crossing(bad), GeometryError);
}

// Near features against first contacts: translating from q in a direction v, the parts first
// touch after moving |v| u*; every feature pair touching there was at most that far apart, so
// features_near(q, d) with d >= |v| u* lists it, and the nearest pair's lower bound is <= it.
TEST(SlicedQueries, FeaturesNearAgreeWithTranslationContacts) {
  Random random(7);
  std::vector<Model> models{
      peg_in_hole(10, Rational(21, 2)),
      pair_model(rectangle(-20, -20, 20, 20) + ", " + circle(-10, 8, 5) + ", " + stadium(Rational(3), Rational(2)),
                 stadium(Rational(2), Rational(3, 2)))};
  int checked = 0;
  for (const Model& model : models) {
    SlicedBuildOptions options;
    options.cell_structure = false;
    SlicedSpace space = SlicedSpace::build(model, "fixed", "free", options);
    for (int i = 0; i < 60; ++i) {
      // near the fitting orientation (the peg of the first model fits only within about 5.7 degrees)
      SlicedConfiguration q = random_configuration(random, Rational(1, 2));
      q.angle = SlicedAngle{random_rational(random, Rational(-1, 20), Rational(1, 20)), false};
      if (relation_at(model, q) != PartRelation::apart) continue;
      for (int direction = 0; direction < 8; ++direction) {
        // directions (3, 4)-rotated by quarter turns and mirrored: |v| = 5 exactly
        const int vx[8] = {3, 4, -3, -4, 3, 4, -3, -4}, vy[8] = {4, 3, 4, 3, -4, -3, -4, -3};
        SlicedMotion m{q, SlicedConfiguration{Rational(q.x + 4 * vx[direction]), Rational(q.y + 4 * vy[direction]), q.angle},
                       q.angle.half_turn};
        auto c = space.first_crossing(m);
        if (c.status != CrossingStatus::crossing) continue;
        Rational travel = 20 * c.u_upper;   // |v| = 20
        auto near = space.features_near(q, travel);
        ASSERT_FALSE(near.empty());
        EXPECT_LE(near.front().distance_lower, travel);
        for (const auto& touching : c.features) {
          bool listed = false;
          for (const auto& n : near)
            listed = listed || (n.pair.fixed == touching.fixed && n.pair.free == touching.free);
          EXPECT_TRUE(listed) << touching.label << " touches after a translation of at most " << to_double(travel);
        }
        // and nothing is nearer than the least bound
        for (const auto& n : near) EXPECT_LE(n.distance_lower, n.distance_upper);
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 100);
}

TEST(SlicedQueries, FeaturesNearAtAContactConfiguration) {
  Model model = peg_in_hole(10, 12);
  SlicedBuildOptions options;
  options.cell_structure = false;
  SlicedSpace space = SlicedSpace::build(model, "fixed", "free", options);
  // the peg against the hole's right side: x = 1
  auto near = space.features_near(SlicedConfiguration{1, 0, SlicedAngle{0, false}}, 0);
  ASSERT_EQ(near.size(), 2u);   // the peg's two right corners on the hole's right side
  for (const auto& n : near) {
    EXPECT_TRUE(n.exact);
    EXPECT_EQ(n.distance_lower, 0);
  }
  auto wider = space.features_near(SlicedConfiguration{1, 0, SlicedAngle{0, false}}, 2);
  EXPECT_GT(wider.size(), near.size());   // the top and bottom sides at 1 mm
  EXPECT_THROW(space.features_near(SlicedConfiguration{1, 0, SlicedAngle{0, false}}, -1), GeometryError);
}

// A disc above and far beyond the end of a floor (session 63, hunt63): the nearest pair's lower
// bound is the disc's true distance from the floor, |c - nearest point of the floor| - r (to the
// bounds' 2^-40), never above it. Until then a segment-arc pair was bounded by the distance of
// the circle from the segment's LINE: a disc 10^6 mm beyond the floor's end and 100 mm above
// its line got 90 mm, and the planar simulator's conservative advancement crept along the line
// by the floor's height per query (disc-incline.json with gravity 1.8e308 along the floor: no
// end in 10 minutes).
TEST(SlicedQueries, FeaturesNearBoundADiscBeyondAFloorsEndByItsTrueDistance) {
  Random random(test::test_seed(63));
  const Rational r(10);
  const Model model = pair_model(rectangle(0, -20, 400, 0), circle(0, 0, r));
  SlicedBuildOptions options;
  options.cell_structure = false;
  SlicedSpace space = SlicedSpace::build(model, "fixed", "free", options);
  int beyond = 0;
  for (int i = 0; i < 200; ++i) {
    // the disc's centre above the floor (x in [0, 400]) or beyond its end (x up to 10^6)
    const bool past_end = i % 4 != 0;
    const Rational x = past_end ? random_rational(random, Rational(401), Rational(1000000), 1009)
                                : random_rational(random, Rational(0), Rational(400));
    const Rational y = random_rational(random, Rational(21, 2), Rational(300));
    const Rational dx = past_end ? Rational(x - 400) : Rational(0);
    const double truth = std::sqrt(to_double(Rational(dx * dx + y * y))) - to_double(r);
    const SlicedConfiguration q{x, y, SlicedAngle{0, false}};
    auto near = space.features_near(q, Rational(2 * static_cast<long>(truth) + 2));
    ASSERT_FALSE(near.empty()) << "x " << to_double(x) << ", y " << to_double(y);
    const Rational& lower = near.front().distance_lower;
    // certified: (lower + r)^2 <= |c - p|^2 exactly
    EXPECT_LE(Rational((lower + r) * (lower + r)), Rational(dx * dx + y * y))
        << "x " << to_double(x) << ", y " << to_double(y) << ": lower bound " << to_double(lower) << " above the distance";
    EXPECT_GE(to_double(lower), truth * (1 - 1e-9) - 1e-9)
        << "x " << to_double(x) << ", y " << to_double(y) << ": lower bound " << to_double(lower) << ", distance " << truth
        << " (" << near.front().pair.label << ")";
    beyond += past_end;
  }
  EXPECT_GT(beyond, 100);
}

// A path's motions are each free: dense exact sampling of every motion.
void expect_path_free(const Model& model, const SlicedSpace& space, const SlicedPath& path, const SlicedConfiguration& a,
                      const SlicedConfiguration& b) {
  ASSERT_EQ(path.status, SlicedPath::Status::found);
  ASSERT_GE(path.waypoints.size(), 2u);
  ASSERT_EQ(path.through_half_turn.size(), path.waypoints.size() - 1);
  EXPECT_TRUE(path.waypoints.front().x == a.x && path.waypoints.front().y == a.y);
  EXPECT_TRUE(path.waypoints.back().x == b.x && path.waypoints.back().y == b.y);
  for (std::size_t i = 0; i + 1 < path.waypoints.size(); ++i) {
    SlicedMotion m{path.waypoints[i], path.waypoints[i + 1], path.through_half_turn[i]};
    EXPECT_TRUE(space.motion_free(m)) << "motion " << i;
    for (int k = 0; k <= 24; ++k) {
      Rational s(k, 24);
      s.canonicalize();
      ASSERT_EQ(relation_at(model, at(m, s)), PartRelation::apart) << "motion " << i << " at u = " << s.get_str();
    }
  }
}

TEST(SlicedQueries, PathsThroughFreeSpaceOfAPegInAHole) {
  Model model = peg_in_hole(10, Rational(21, 2));
  SlicedSpace space = SlicedSpace::build(model, "fixed", "free");
  SlicedConfiguration centred{0, 0, SlicedAngle{0, false}};
  SlicedConfiguration nudged{Rational(1, 10), Rational(-1, 10), SlicedAngle{Rational(1, 200), false}};
  SlicedConfiguration turned{0, 0, SlicedAngle{1, false}};
  SlicedConfiguration outside{30, 0, SlicedAngle{Rational(1, 3), false}};
  SlicedConfiguration outside_half{-30, 5, SlicedAngle{0, true}};
  SlicedPath p = space.path(centred, nudged);
  expect_path_free(model, space, p, centred, nudged);
  p = space.path(outside, outside_half);
  expect_path_free(model, space, p, outside, outside_half);
  EXPECT_EQ(space.path(centred, turned).status, SlicedPath::Status::not_connected);
  EXPECT_EQ(space.path(centred, outside).status, SlicedPath::Status::not_connected);
  EXPECT_EQ(space.path(SlicedConfiguration{10, 0, SlicedAngle{0, false}}, outside).status, SlicedPath::Status::not_free);
}

// The short rectangle turns the corner of an L-shaped corridor: a certified path from one arm
// to the other (see sliced_test.cpp for the critical angles).
TEST(SlicedQueries, PathAroundTheCornerOfAnLShapedCorridor) {
  std::string hole = polygon({{-20, 0}, {4, 0}, {4, 20}, {0, 20}, {0, 4}, {-20, 4}});
  Model model = pair_model(rectangle(-30, -30, 30, 30) + ", " + hole, rectangle(-3, -1, 3, 1));
  SlicedSpace space = SlicedSpace::build(model, "fixed", "free");
  SlicedConfiguration horizontal{-10, 2, SlicedAngle{0, false}}, vertical{2, 12, SlicedAngle{1, false}};
  SlicedPath p = space.path(horizontal, vertical);
  expect_path_free(model, space, p, horizontal, vertical);
}

TEST(SlicedQueries, PathWithARotationInAWideHole) {
  Model model = peg_in_hole(10, Rational(1415, 100));
  SlicedSpace space = SlicedSpace::build(model, "fixed", "free");
  SlicedConfiguration flat{0, 0, SlicedAngle{0, false}}, upright{0, 0, SlicedAngle{1, false}};
  SlicedPath p = space.path(flat, upright);
  expect_path_free(model, space, p, flat, upright);
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// The 12 x 2 peg of examples/models/peg-in-slot.json from its chamber below the 3 mm slot to its
// insertion configuration above: a certified path (turned upright through the slot). The pair
// takes about 10 s idle to build: with HIPAIR_SLOW_TESTS=1.
TEST(SlicedQueries, PathOfThePegThroughTheSlot) {
  if (!std::getenv("HIPAIR_SLOW_TESTS")) GTEST_SKIP() << "set HIPAIR_SLOW_TESTS=1 (about 10 s idle)";
  ReadOptions options;
  Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/peg-in-slot.json", options);
  SlicedSpace space = SlicedSpace::build(model, "plate", "peg");
  SlicedConfiguration below{0, 0, SlicedAngle{0, false}}, above{0, 22, SlicedAngle{0, false}};
  SlicedPath p = space.path(below, above);
  expect_path_free(model, space, p, below, above);
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// A round peg (a disc of radius 4 whose centre is 1 mm off the pivot) in a round hole of radius
// 6 and in a square hole of side 12: turning only moves the disc's centre, so every slice is a
// translate of the slice at theta = 0 and there is no critical angle; the free space in the hole
// is one solid torus (hand-checked: the centre within 2 mm of the hole's centre, resp. within
// the square of half-side 1), outside the plate another. A disc of radius 6.01 does not fit.
TEST(SlicedQueries, RoundPegInRoundAndSquareHoles) {
  Random random(11);
  const std::string plate = rectangle(-20, -20, 20, 20);
  struct Case {
    std::string hole;
    Rational radius;
    std::size_t components;
  };
  const std::vector<Case> cases{{circle(0, 0, 6), 4, 2}, {rectangle(-6, -6, 6, 6), 4, 2}, {circle(0, 0, 6), Rational(601, 100), 1}};
  for (const auto& c : cases) {
    SCOPED_TRACE("hole " + c.hole + ", peg radius " + c.radius.get_str());
    Model model = pair_model(plate + ", " + c.hole, circle(1, 0, c.radius), Point{0, 0});
    SlicedSpace space = SlicedSpace::build(model, "fixed", "free");
    EXPECT_TRUE(space.critical_angles().empty());
    ASSERT_EQ(space.intervals().size(), 1u);
    EXPECT_EQ(space.components(), c.components);
    // point location against the oracle; the free cell is the hole's exactly when the disc's
    // centre pivot + R(1, 0) + (x, y) lies in the hole's free region
    int inside = 0;
    for (int i = 0; i < 300; ++i) {
      SlicedConfiguration q{random_rational(random, -3, 3), random_rational(random, -3, 3),
                            SlicedAngle{random_rational(random, -4, 4, 13), random() % 7 == 0}};
      SlicedLocation l = space.locate(q);
      PartRelation expected = relation_at(model, q);
      ASSERT_EQ(l.kind == SlicedLocation::Kind::free, expected == PartRelation::apart);
      ASSERT_EQ(l.kind == SlicedLocation::Kind::blocked, expected == PartRelation::overlapping);
      if (l.kind == SlicedLocation::Kind::free) {
        ++inside;
        EXPECT_EQ(l.interval, 0u);
        EXPECT_NE(l.cell, no_index);
      }
    }
    if (c.components == 2) EXPECT_GT(inside, 20);
  }
  // paths in the round hole: the centre from (0, 0) (theta = 0, shift (-1, 0)) to (1/2, 3/2)
  // (theta = pi/2, shift (1/2, 1/2)), and from the hole to outside: not connected
  Model model = pair_model(plate + ", " + circle(0, 0, 6), circle(1, 0, 4), Point{0, 0});
  SlicedSpace space = SlicedSpace::build(model, "fixed", "free");
  SlicedConfiguration a{-1, 0, SlicedAngle{0, false}}, b{Rational(1, 2), Rational(1, 2), SlicedAngle{1, false}};
  EXPECT_TRUE(space.connected(a, b));
  expect_path_free(model, space, space.path(a, b), a, b);
  SlicedConfiguration turned_round{-1, 0, SlicedAngle{0, true}};   // centre at (-2, 0): touching, not free
  EXPECT_EQ(space.locate(turned_round).kind, SlicedLocation::Kind::contact);
  EXPECT_EQ(space.path(a, SlicedConfiguration{30, 0, SlicedAngle{0, false}}).status, SlicedPath::Status::not_connected);
}

}  // namespace
}  // namespace hipair
