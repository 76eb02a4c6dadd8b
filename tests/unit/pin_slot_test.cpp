// Pin-in-slot pairs (src/pinslot, hipair/pin_slot.hpp): exact point location in (q, s, psi)
// against the exact overlap oracle at thousands of random rational configurations per pair of
// the film advance (cam/follower: a rotating driver; film/follower: a translating part;
// pin/follower: a fixed part), the structure of the cam/follower stack (two free cells near
// psi = 0, none beyond the tangency of the slot line to the cam centre's circle, changes
// isolated around it), witnesses of connections re-checked by the oracle, and bad pairs.
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/pin_slot.hpp>

#include "algebra/exact_real.hpp"
#include "sliced/critical_angles.hpp"
#include "pin_slot_test_support.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <string>

namespace hipair {
namespace {

using Random = std::mt19937_64;

using pin_slot_test::film_advance;
using pin_slot_test::random_rational;

PinSlotLocation::Kind oracle(const Model& model, const PinSlotSpace& space, const PinSlotConfiguration& q) {
  const Part& other = model.parts[*model.find_part(space.other_part())];
  const Part& pin = model.parts[*model.find_part(space.pin_slot_part())];
  PartOverlap o = part_overlap(other, part_placement(other, q.other), pin, pin_slot_placement(pin, q.slide, q.tau));
  switch (o.relation) {
    case PartRelation::apart: return PinSlotLocation::Kind::free;
    case PartRelation::touching: return PinSlotLocation::Kind::contact;
    case PartRelation::overlapping: return PinSlotLocation::Kind::blocked;
  }
  return PinSlotLocation::Kind::outside;
}

const char* name(PinSlotLocation::Kind k) {
  switch (k) {
    case PinSlotLocation::Kind::free: return "free";
    case PinSlotLocation::Kind::blocked: return "blocked";
    case PinSlotLocation::Kind::contact: return "contact";
    case PinSlotLocation::Kind::outside: return "outside";
  }
  return "?";
}

// Random configurations near the mechanism's working set (so that free, blocked and contact
// all occur): psi from `taus` random tangents inside the stack's range, the other part's
// coordinate uniform, s uniform within the slot limits.
struct Tally {
  std::size_t free = 0, blocked = 0, contact = 0, mismatches = 0;
};
Tally check_locate(const PinSlotSpace& space, std::size_t taus, std::size_t per_tau, unsigned seed,
                   double other_lo, double other_hi) {
  const Model& model = film_advance();
  Random random(seed);
  Tally tally;
  for (std::size_t i = 0; i < taus; ++i) {
    Rational tau = random_rational(random, to_double(space.tau_lower()), to_double(space.tau_upper()), 4096);
    for (std::size_t j = 0; j < per_tau; ++j) {
      PinSlotConfiguration q;
      if (space.other_kind() == Motion::Kind::translation) q.other.kind = PartCoordinate::Kind::offset;
      q.other.value = random_rational(random, other_lo, other_hi);
      q.slide = random_rational(random, -5.75, 5.75, 64);
      q.tau = tau;
      PinSlotLocation at = space.locate(q);
      PinSlotLocation::Kind expected = oracle(model, space, q);
      EXPECT_EQ(name(at.kind), std::string(name(expected)))
          << "tau " << tau << " other " << q.other.value << " s " << q.slide;
      if (at.kind != expected) ++tally.mismatches;
      if (tally.mismatches > 5) return tally;   // enough to see
      (expected == PinSlotLocation::Kind::free      ? tally.free
       : expected == PinSlotLocation::Kind::blocked ? tally.blocked
                                                    : tally.contact)++;
    }
  }
  return tally;
}

PinSlotBuildOptions quick(std::size_t slices, bool connections) {
  PinSlotBuildOptions options;
  options.slices = slices;
  options.refine_steps = 0;
  options.connections = connections;
  return options;
}

TEST(PinSlot, CamFollowerLocateMatchesOracle) {
  PinSlotSpace space = PinSlotSpace::build(film_advance(), "cam", "follower", quick(4, false));
  EXPECT_EQ(space.dimension(), 3);
  // the cam's half-angle tangent over [-4, 4] (|phi| < 152 deg) and s over the slot: free space
  // is a thin tube (0.2 mm clearance), so most points are blocked; contact comes from below
  Tally t = check_locate(space, 8, 400, 11, -4, 4);
  EXPECT_GT(t.free, 0u);
  EXPECT_GT(t.blocked, 1000u);
}

TEST(PinSlot, CamFollowerContactConfigurations) {
  // psi = 0, cam at phi = 90 deg (t = 1): the cam's centre is (0, 4), its top at y = 14 and its
  // bottom at -6; the window spans [s - 10.2, s + 10.2]: free for s in (3.8, 4.2), contact at
  // both ends exactly, blocked outside.
  PinSlotSpace space = PinSlotSpace::build(film_advance(), "cam", "follower", quick(2, false));
  auto at = [&](const Rational& s) {
    return space.locate(PinSlotConfiguration{PartCoordinate{PartCoordinate::Kind::half_angle_tangent, 1}, s, 0}).kind;
  };
  EXPECT_EQ(at(Rational(19, 5)), PinSlotLocation::Kind::contact);
  EXPECT_EQ(at(Rational(19, 5) - Rational(1, 1000)), PinSlotLocation::Kind::blocked);
  EXPECT_EQ(at(Rational(19, 5) + Rational(1, 1000)), PinSlotLocation::Kind::free);
  EXPECT_EQ(at(Rational(4)), PinSlotLocation::Kind::free);
  EXPECT_EQ(at(Rational(21, 5)), PinSlotLocation::Kind::contact);
  EXPECT_EQ(at(Rational(21, 5) + Rational(1, 1000)), PinSlotLocation::Kind::blocked);
}

TEST(PinSlot, FilmFollowerLocateMatchesOracle) {
  PinSlotSpace space = PinSlotSpace::build(film_advance(), "film", "follower", quick(3, false));
  EXPECT_EQ(space.dimension(), 3);
  Tally t = check_locate(space, 6, 400, 12, -20, 5);
  EXPECT_GT(t.free, 100u);
  EXPECT_GT(t.blocked, 10u);
}

TEST(PinSlot, PinFollowerLocateMatchesOracle) {
  PinSlotSpace space = PinSlotSpace::build(film_advance(), "pin", "follower", quick(3, true));
  EXPECT_EQ(space.dimension(), 2);
  Tally t = check_locate(space, 6, 300, 13, 0, 0);
  EXPECT_GT(t.free, 100u);
  EXPECT_GT(t.blocked, 10u);
  // the pin (radius 3 at the pivot) meets the slot's ends at s = +-4.5 exactly, for every psi
  for (const Rational& tau : {Rational(0), Rational(1, 20), Rational(-3, 50)}) {
    EXPECT_EQ(space.locate(PinSlotConfiguration{{}, Rational(9, 2), tau}).kind, PinSlotLocation::Kind::contact);
    EXPECT_EQ(space.locate(PinSlotConfiguration{{}, Rational(-9, 2), tau}).kind, PinSlotLocation::Kind::contact);
  }
  // one free cell per slice, all in one certainly-connected group
  for (const auto& slice : space.slices()) EXPECT_EQ(slice.free_cells.size(), 1u);
  EXPECT_EQ(space.groups(), 1u);
}

TEST(PinSlot, CamFollowerStackStructure) {
  PinSlotBuildOptions options;
  options.slices = 12;
  options.refine_steps = 3;
  PinSlotSpace space = PinSlotSpace::build(film_advance(), "cam", "follower", options);
  // the window's centre runs on the line through the pin turned by psi; the cam's centre on a
  // circle of radius 4 about the shaft 40 below the pin: two crossings (two free cells) while
  // |psi| < asin(4/40) = 5.74 deg less the clearance's share, none beyond it plus that share
  const double tangent = std::asin(0.1) * 180 / std::numbers::pi;
  for (const auto& slice : space.slices()) {
    if (std::abs(slice.degrees) < tangent - 0.5) EXPECT_EQ(slice.free_cells.size(), 2u) << slice.degrees;
    if (std::abs(slice.degrees) > tangent + 0.5) EXPECT_EQ(slice.free_cells.size(), 0u) << slice.degrees;
  }
  ASSERT_FALSE(space.changes().empty());
  // the widest gap between the stack's own (not refining) slices, in tau
  Rational widest = 0, previous;
  bool first = true;
  for (const auto& slice : space.slices()) {
    if (slice.refinement) continue;
    if (!first && slice.tau - previous > widest) widest = slice.tau - previous;
    previous = slice.tau;
    first = false;
  }
  for (const auto& change : space.changes()) {
    double a = space.slices()[change.lower].degrees, b = space.slices()[change.lower + 1].degrees;
    // each isolated interval lies near the tangency (within the clearance's share)
    EXPECT_GT(std::max(std::abs(a), std::abs(b)), tangent - 0.6) << change.description;
    EXPECT_LT(std::min(std::abs(a), std::abs(b)), tangent + 0.6) << change.description;
    // three bisections of a gap: at most an eighth of the widest gap, exactly
    EXPECT_LE(Rational(space.slices()[change.lower + 1].tau - space.slices()[change.lower].tau), Rational(widest / 8));
  }
}

TEST(PinSlot, WitnessesAreFreeSegments) {
  PinSlotBuildOptions options;
  options.slices = 6;
  options.refine_steps = 0;
  PinSlotSpace space = PinSlotSpace::build(film_advance(), "film", "follower", options);
  ASSERT_FALSE(space.connections().empty());
  Random random(17);
  const Model& model = film_advance();
  for (const auto& c : space.connections()) {
    Rational lo = space.slices()[c.lower].tau, hi = space.slices()[c.lower + 1].tau;
    for (int k = 0; k <= 40; ++k) {
      Rational tau = lo + (hi - lo) * Rational(k, 40);
      tau.canonicalize();
      PinSlotConfiguration q{c.witness_other, c.witness_slide, tau};
      EXPECT_EQ(oracle(model, space, q), PinSlotLocation::Kind::free) << "witness at tau " << tau;
    }
    // and the witness joins the cells it names
    auto below = space.locate(PinSlotConfiguration{c.witness_other, c.witness_slide, lo});
    auto above = space.locate(PinSlotConfiguration{c.witness_other, c.witness_slide, hi});
    EXPECT_EQ(below.cell, c.lower_cell);
    EXPECT_EQ(above.cell, c.upper_cell);
  }
  // with the claw out of the film plane (psi <= 0) the film slides freely: one free cell in
  // each such slice, all in one group (witnessed)
  std::size_t group = no_index;
  for (const auto& slice : space.slices()) {
    if (slice.degrees > 0) continue;
    ASSERT_EQ(slice.free_cells.size(), 1u) << slice.degrees;
    EXPECT_EQ(slice.free_cells[0].contacts, "(no contact)");
    if (group == no_index) group = slice.free_cells[0].group;
    EXPECT_EQ(slice.free_cells[0].group, group) << slice.degrees;
  }
}

Model with_motion(const std::string& other_motion) {
  return read_model(R"({ "hipair": 1, "name": "bad", "parts": [
    { "name": "a", "motion": )" + other_motion + R"(, "loops": [ { "start": [30, 0], "edges": [
      { "line_to": [34, 0] }, { "line_to": [34, 4] }, { "line_to": [30, 4] }, { "line_to": [30, 0] } ] } ] },
    { "name": "b", "motion": { "pin_slot": { "pivot": [0, 0], "direction": [1, 0], "angle_limits": [-0.5, 0.5], "limits": [-2, 2] } },
      "loops": [ { "start": [0, 0], "edges": [ { "line_to": [10, 0] }, { "line_to": [10, 2] }, { "line_to": [0, 2] },
      { "line_to": [0, 0] } ] } ] } ] })");
}

TEST(PinSlot, BadPairsAreRefusedWithAMessage) {
  Model planar = with_motion(R"({ "planar": { "pivot": [0, 0] } })");
  try {
    PinSlotSpace::build(planar, "a", "b");
    FAIL() << "a pin_slot part against a planar part was accepted";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("'a':'b'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("planar"), std::string::npos) << e.what();
  }
  Model both = with_motion(R"({ "pin_slot": { "pivot": [0, 0], "direction": [0, 1] } })");
  EXPECT_THROW(PinSlotSpace::build(both, "a", "b"), GeometryError);
  Model fine = with_motion(R"("fixed")");
  EXPECT_THROW(PinSlotSpace::build(fine, "b", "a"), GeometryError);   // 'a' has no pin_slot motion
  EXPECT_THROW(PinSlotSpace::build(fine, "a", "nope"), ModelError);
  PinSlotSpace ok = PinSlotSpace::build(fine, "a", "b", quick(4, true));
  EXPECT_EQ(ok.dimension(), 2);
  // narrow angle limits (+-0.001 rad) are sliced with finer tangents, inside the limits
  Model narrow = fine;
  narrow.parts[1].motion.angle_limits = RationalInterval{Rational(-1, 1000), Rational(1, 1000)};
  PinSlotSpace thin = PinSlotSpace::build(narrow, "a", "b", quick(16, false));
  ASSERT_EQ(thin.slices().size(), 16u);
  for (const auto& slice : thin.slices()) EXPECT_LT(std::abs(slice.degrees), 0.001 * 180 / std::numbers::pi);
  EXPECT_EQ(thin.locate(PinSlotConfiguration{{}, Rational(0), Rational(1, 100)}).kind, PinSlotLocation::Kind::outside);
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// The film advance's work cycle (pin_slot_cycle): the claw enters a perforation, pulls the film
// down one frame and retracts, in that order; every sample re-checked by the exact oracle.
// The film advance's cycle, the cam turning clockwise (the sense of its torque) in `steps` steps.
PinSlotCycle film_cycle(std::size_t steps) {
  PinSlotCycleOptions options;
  options.clockwise = true;
  options.steps = steps;
  return pin_slot_cycle(film_advance(), options);
}

TEST(PinSlot, FilmAdvanceCycle) {
  const Model& model = film_advance();
  PinSlotCycle cycle = film_cycle(72);
  EXPECT_EQ(cycle.driver, "cam");
  EXPECT_EQ(cycle.follower, "follower");
  EXPECT_EQ(cycle.target, "film");
  ASSERT_EQ(cycle.samples.size(), 73u);
  // phases: clear, engaged (the claw inside the perforation), pushing, clear
  std::vector<CyclePhase> phases;
  for (const auto& run : cycle.runs) phases.push_back(run.phase);
  ASSERT_EQ(phases, (std::vector<CyclePhase>{CyclePhase::clear, CyclePhase::engaged, CyclePhase::pushing,
                                             CyclePhase::clear}));
  // one frame: the pitch is 7.8 mm; the film stops where the claw's last pushing sample leaves
  // it, and the claw's slide changes by at most 4 mm * (5 deg in rad) = 0.35 mm per sample
  // (s ~ 4 sin(phi)), so the sampled pull is within that of the pitch
  EXPECT_NEAR(to_double(cycle.advance), -7.8, 0.35);
  const Part& cam = model.parts[*model.find_part("cam")];
  const Part& follower = model.parts[*model.find_part("follower")];
  const Part& film = model.parts[*model.find_part("film")];
  for (const CycleSample& s : cycle.samples) {
    EXPECT_TRUE(s.follower_free);
    Placement pose = pin_slot_placement(follower, s.slide, s.tau);
    EXPECT_EQ(part_overlap(cam, part_placement(cam, s.driver), follower, pose).relation, PartRelation::apart)
        << s.driver_degrees;
    PartRelation film_relation =
        part_overlap(film, part_placement(film, PartCoordinate{PartCoordinate::Kind::offset, s.target_offset}), follower, pose)
            .relation;
    EXPECT_NE(film_relation, PartRelation::overlapping) << s.driver_degrees;
    // pushing: the film is exactly in contact with the claw
    if (s.phase == CyclePhase::pushing) {
      EXPECT_TRUE(s.target_offset_exact);
      EXPECT_EQ(film_relation, PartRelation::touching) << s.driver_degrees;
      ASSERT_FALSE(s.contacts.empty());
      EXPECT_NE(s.contacts.front().find("claw bottom"), std::string::npos) << s.contacts.front();
    }
    if (s.phase == CyclePhase::clear) EXPECT_TRUE(s.contacts.empty() && s.bounds.empty());
    // engaged: the claw inside perforation 0, held between its edges
    if (s.phase == CyclePhase::engaged) {
      bool perforation = false;
      for (const auto& b : s.bounds) perforation = perforation || b.find("perforation 0") != std::string::npos;
      EXPECT_TRUE(perforation) << s.driver_degrees;
    }
  }
}

// The cam-follower contacts reported per sample: the follower's free slide interval against the
// eccentric cam (radius 10 in a square window of half side 10.2 whose top and bottom are normal
// to the slot at every follower angle) is bounded below by the cam touching the window's top and
// above by its bottom, and is exactly 2 (10.2 - 10) = 0.4 mm long at every cam and follower angle (closed form;
// `clearance` is the difference of the doubles of the two exact ends, each within a few units
// in the last place of numbers below 60, hence the 1e-12).
TEST(PinSlot, FilmAdvanceCycleReportsTheCamContactsBoundingTheSlide) {
  PinSlotCycle cycle = film_cycle(24);
  ASSERT_EQ(cycle.samples.size(), 25u);
  for (const CycleSample& s : cycle.samples) {
    SCOPED_TRACE(s.driver_degrees);
    ASSERT_EQ(s.driver_bounds.size(), 2u);
    // sliding down (the lower end) brings the window's top onto the cam; sliding up, its bottom
    EXPECT_EQ(s.driver_bounds[0], "cam circle / follower window top (arc tangent to segment)");
    EXPECT_EQ(s.driver_bounds[1], "cam circle / follower window bottom (arc tangent to segment)");
    EXPECT_NEAR(s.clearance, 0.4, 1e-12);
  }
}

TEST(PinSlot, CycleNeedsAChain) {
  // the pin and the follower alone: nothing to drive it
  Model model = film_advance();
  model.pairs.erase(std::remove_if(model.pairs.begin(), model.pairs.end(),
                                   [&](const PairSpec& p) { return model.parts[p.first].name == "cam" || model.parts[p.second].name == "cam"; }),
                    model.pairs.end());
  try {
    pin_slot_cycle(model);
    FAIL() << "a cycle without a driver was accepted";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("no rotating part"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// A slotted bar on a pin without angle limits: the stack covers the whole turn, and the wrap
// across the half turn is witnessed too (the slotted part pre-turned by pi): one group. A bar
// also carrying a stop that hits a fixed block splits nothing but adds contacts.
TEST(PinSlot, WholeTurnWrapsAcrossTheHalfTurn) {
  Model model = read_model(R"({ "hipair": 1, "name": "whole-turn", "parts": [
    { "name": "pin", "motion": "fixed", "features": [ { "circle": { "center": [0, 0], "radius": 1 } } ] },
    { "name": "bar", "motion": { "pin_slot": { "pivot": [0, 0], "direction": [1, 0], "limits": [-3, 3] } },
      "loops": [
        { "start": [-8, -2], "edges": [ { "line_to": [8, -2] }, { "line_to": [8, 2] }, { "line_to": [-8, 2] },
          { "line_to": [-8, -2] } ] },
        { "start": [-3, -1.25], "edges": [ { "line_to": [3, -1.25] }, { "line_to": [3, 1.25] },
          { "line_to": [-3, 1.25] }, { "line_to": [-3, -1.25] } ] } ] } ],
    "pairs": [ { "parts": ["pin", "bar"] } ] })");
  PinSlotBuildOptions options;
  options.slices = 6;
  PinSlotSpace space = PinSlotSpace::build(model, "pin", "bar", options);
  ASSERT_EQ(space.slices().size(), 6u);
  EXPECT_LT(space.slices().front().degrees, -149);   // -150 deg, rounded tangent
  EXPECT_GT(space.slices().back().degrees, 149);
  for (const auto& slice : space.slices()) EXPECT_EQ(slice.free_cells.size(), 1u);
  bool wrap = false;
  for (const auto& c : space.connections()) wrap = wrap || c.lower + 1 == space.slices().size();
  EXPECT_TRUE(wrap);
  EXPECT_EQ(space.groups(), 1u);
  // the pin meets the slot's ends at s = +-2 (slot half-length 3 less the pin's radius 1)
  for (const Rational& tau : {Rational(5), Rational(-7, 3), Rational(0)}) {
    EXPECT_EQ(space.locate(PinSlotConfiguration{{}, Rational(2), tau}).kind, PinSlotLocation::Kind::contact);
    EXPECT_EQ(space.locate(PinSlotConfiguration{{}, Rational(199, 100), tau}).kind, PinSlotLocation::Kind::free);
    EXPECT_EQ(space.locate(PinSlotConfiguration{{}, Rational(201, 100), tau}).kind, PinSlotLocation::Kind::blocked);
  }
  // connected across the half turn: psi near +pi and near -pi
  EXPECT_TRUE(space.certainly_connected(PinSlotConfiguration{{}, Rational(1), Rational(40)},
                                        PinSlotConfiguration{{}, Rational(-1), Rational(-40)}));
  EXPECT_FALSE(space.certainly_connected(PinSlotConfiguration{{}, Rational(1), Rational(40)},
                                         PinSlotConfiguration{{}, Rational(5, 2), Rational(-40)}));   // blocked
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

// The cam pair's free space is one thin tube (0.2 mm clearance) winding through (phi, s, psi):
// vertical witnesses leave it in pieces, plane witnesses (constant slide) join it into one
// group at 32 slices. Every plane witness re-checked by the oracle along its straight path.
TEST(PinSlot, CamFollowerTubeIsOneGroupWithPlaneWitnesses) {
  PinSlotBuildOptions options;
  options.slices = 32;
  options.plane_witnesses = true;
  PinSlotSpace space = PinSlotSpace::build(film_advance(), "cam", "follower", options);
  EXPECT_EQ(space.groups(), 1u);
  const Model& model = film_advance();
  std::size_t planes = 0;
  for (const auto& c : space.connections()) {
    if (c.kind != PinSlotConnection::Kind::plane) continue;
    ++planes;
    Rational lo = space.slices()[c.lower].tau, hi = space.slices()[c.lower + 1].tau;
    ASSERT_EQ(c.witness_other.kind, PartCoordinate::Kind::half_angle_tangent);
    ASSERT_EQ(c.witness_other_upper.kind, PartCoordinate::Kind::half_angle_tangent);
    for (int k = 0; k <= 40; ++k) {
      Rational u(k, 40);
      PartCoordinate at{PartCoordinate::Kind::half_angle_tangent,
                        Rational(c.witness_other.value + u * (c.witness_other_upper.value - c.witness_other.value))};
      at.value.canonicalize();
      Rational tau = lo + u * (hi - lo);
      tau.canonicalize();
      EXPECT_EQ(oracle(model, space, PinSlotConfiguration{at, c.witness_slide, tau}), PinSlotLocation::Kind::free)
          << "plane witness between slices " << c.lower << " and " << c.lower + 1 << " at u = " << u;
    }
    EXPECT_EQ(space.locate(PinSlotConfiguration{c.witness_other, c.witness_slide, lo}).cell, c.lower_cell);
    EXPECT_EQ(space.locate(PinSlotConfiguration{c.witness_other_upper, c.witness_slide, hi}).cell, c.upper_cell);
  }
  EXPECT_GT(planes, 0u);
  // two configurations on opposite sides of the tube (claw at the top and at the bottom of its
  // stroke, near psi = 0) are certainly connected
  const PinSlotSlice* middle = nullptr;
  for (const auto& slice : space.slices())
    if (!middle || std::abs(slice.degrees) < std::abs(middle->degrees)) middle = &slice;
  ASSERT_EQ(middle->free_cells.size(), 2u);
  const PinSlotCell& top = middle->free_cells[0];
  const PinSlotCell& bottom = middle->free_cells[1];
  EXPECT_TRUE(space.certainly_connected(PinSlotConfiguration{top.sample_other, top.sample_slide, middle->tau},
                                        PinSlotConfiguration{bottom.sample_other, bottom.sample_slide, middle->tau}));
}

}  // namespace
}  // namespace hipair

namespace hipair {
namespace {

namespace algebra = cspace::algebra;

using sliced::real_of;


// Slices at two random rational tau inside each interval between consecutive critical values
// have the same structure; with `all_change` (hand-checked cases where every critical value is
// a change; in general the list is a superset) a rational critical value's slice differs from
// both neighbours'.
void expect_steady_between_critical_values(const PinSlotSpace& space, Random& random, bool all_change = false) {
  const auto& critical = space.critical_values();
  std::vector<algebra::Real> ends;
  ends.push_back(algebra::Real::from_rational(space.tau_lower()));
  for (const auto& c : critical) ends.push_back(real_of(c.tau));
  ends.push_back(algebra::Real::from_rational(space.tau_upper()));
  int checked = 0;
  for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
    algebra::Real a = ends[k], b = ends[k + 1];
    while (!a.exact && a.upper >= b.lower) a.refine();
    while (!b.exact && b.lower <= a.upper) b.refine();
    const Rational lo = a.exact ? a.lower : a.upper, hi = b.exact ? b.lower : b.lower;
    std::vector<Rational> taus;
    for (int i = 0; i < 2; ++i) {
      Rational u(static_cast<long>(1 + random() % 97), 98);
      Rational t = lo + u * (hi - lo);
      t.canonicalize();
      if (ends[k].compare(t) < 0 && ends[k + 1].compare(t) > 0) taus.push_back(t);
    }
    if (taus.size() < 2) continue;
    EXPECT_EQ(pin_slot_test::free_structure(*space.slice(taus[0])), pin_slot_test::free_structure(*space.slice(taus[1])))
        << "between critical values " << k << " and " << k + 1 << ": tau " << taus[0].get_str() << ", " << taus[1].get_str();
    ++checked;
  }
  EXPECT_GE(checked, static_cast<int>(critical.size()));
  for (std::size_t k = 0; k < critical.size() && all_change; ++k) {
    if (!critical[k].tau.exact) continue;
    Rational t = critical[k].tau.lower, d(1, 1 << 20);
    std::string at = pin_slot_test::free_structure(*space.slice(t));
    EXPECT_NE(at, pin_slot_test::free_structure(*space.slice(Rational(t - d)))) << t.get_str();
    EXPECT_NE(at, pin_slot_test::free_structure(*space.slice(Rational(t + d)))) << t.get_str();
  }
}

// A bar [0, 10] x [-1, 1] turning about (0, 0) by psi in [-60, 60] degrees and sliding along
// itself by s in [-5, 5], against a wall x >= 12. Its far corners reach x = (10 + s) cos psi +
// |sin psi|: the slide's end s = 5 touches the wall where 15 cos psi + |sin psi| = 12, the
// positive root of 27 t^2 - 2 t - 3 and the negative root of 27 t^2 + 2 t - 3 (psi = +-40.9
// degrees); at psi = 0 the touching corner changes (the end edge is parallel to the wall).
// Nothing else: three critical values.
TEST(PinSlotCritical, BarAgainstAWallHasThreeCriticalValues) {
  Model model = read_model(R"({ "hipair": 1, "name": "bar-wall", "parts": [
    { "name": "wall", "motion": "fixed", "loops": [ { "start": [12, -20], "edges": [ { "line_to": [20, -20] },
      { "line_to": [20, 20] }, { "line_to": [12, 20] }, { "line_to": [12, -20] } ] } ] },
    { "name": "bar", "motion": { "pin_slot": { "pivot": [0, 0], "direction": [1, 0], "angle_limits": [-60, 60],
      "limits": [-5, 5] } }, "loops": [ { "start": [0, -1], "edges": [ { "line_to": [10, -1] }, { "line_to": [10, 1] },
      { "line_to": [0, 1] }, { "line_to": [0, -1] } ] } ] } ],
    "pairs": [ { "parts": ["wall", "bar"] } ] })");
  PinSlotSpace space = PinSlotSpace::build(model, "wall", "bar");
  ASSERT_TRUE(space.critical_values_exact());
  const auto& critical = space.critical_values();
  std::string listing;
  for (const auto& c : critical) listing += c.tau.to_string("t") + "\n";
  ASSERT_EQ(critical.size(), 3u) << listing;
  EXPECT_TRUE(algebra::vanishes_at(algebra::from_rationals({-3, 2, 27}), real_of(critical[0].tau))) << listing;
  EXPECT_LT(critical[0].degrees, -40);
  EXPECT_TRUE(critical[1].tau.exact && critical[1].tau.lower == 0) << listing;
  EXPECT_TRUE(algebra::vanishes_at(algebra::from_rationals({-3, -2, 27}), real_of(critical[2].tau))) << listing;
  EXPECT_GT(critical[2].degrees, 40);
  // the free interval at tau: s < (12 - |sin|) / cos - 10, within [-5, 5]
  Random random(13);
  expect_steady_between_critical_values(space, random, true);
  for (int i = 0; i < 200; ++i) {
    PinSlotConfiguration q{{}, random_rational(random, -5, 5, 64), random_rational(random, -0.57, 0.57, 64)};
    EXPECT_EQ(space.locate(q).kind, oracle(model, space, q));
  }
}

// The film advance's film/follower pair (a translating part; both within limits) and the
// pin/follower pair (fixed): exact critical values, and slices between consecutive ones alike.
// (tau = 0 is listed for the film pair without a change: the slot is parallel to the film's
// motion there, the window degenerates, and such a value is kept unfiltered.)
// The pin is a disc centred on the follower's pivot: turning the follower turns the slot about
// the pin's centre, so nothing changes with psi (no critical value); the claw meets the film's
// perforations at many.
TEST(PinSlotCritical, FilmAdvancePairsAreSteadyBetweenCriticalValues) {
  const Model& model = film_advance();
  Random random(17);
  for (const char* other : {"pin", "film"}) {
    SCOPED_TRACE(other);
    PinSlotSpace space = PinSlotSpace::build(model, other, "follower");
    ASSERT_TRUE(space.critical_values_exact());
    if (std::string(other) == "pin") EXPECT_TRUE(space.critical_values().empty());
    else EXPECT_GE(space.critical_values().size(), 1u);
    expect_steady_between_critical_values(space, random);
  }
}

// Generated pairs: a random star-shaped part on a pin-slot motion against a fixed plate with a
// random star-shaped hole (polygonal), and against a stadium-shaped fixed part (arcs).
TEST(PinSlotCritical, GeneratedPairsAreSteadyBetweenCriticalValues) {
  Random random(29);
  for (int round = 0; round < 3; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    auto coord = [&](double lo, double hi) { return "\"" + to_exact_string(random_rational(random, lo, hi, 4)) + "\""; };
    // (against the stadium an axis-parallel bar: a slanted edge of irrational length facing an
    // arc is outside the exact class, checked below)
    const std::string length = coord(6, 9);
    std::string bar = round == 2 ? R"({ "start": [0, -1], "edges": [ { "line_to": [)" + length + R"(, -1] }, { "line_to": [)" +
                                       length + R"(, 1] }, { "line_to": [0, 1] }, { "line_to": [0, -1] } ] })"
                                 : R"({ "start": [0, -1], "edges": [ { "line_to": [)" + coord(6, 9) + R"(, -1] }, { "line_to": [)" +
                                       coord(6, 9) + ", " + coord(0, 1.5) + R"(] }, { "line_to": [0, 1] }, { "line_to": [0, -1] } ] })";
    const std::string x0 = coord(9, 11), y0 = coord(-8, -4);
    std::string fixed = round == 2
        ? R"({ "start": [10, -3], "edges": [ { "line_to": [14, -3] }, { "arc_to": [14, 3], "center": [14, 0], "dir": "ccw" },
             { "line_to": [10, 3] }, { "arc_to": [10, -3], "center": [10, 0], "dir": "ccw" } ] })"
        : R"({ "start": [)" + x0 + ", " + y0 + R"(], "edges": [ { "line_to": [16, -6] }, { "line_to": [15, 7] },
             { "line_to": [)" + coord(9, 11) + ", " + coord(3, 8) + R"(] }, { "line_to": [)" + coord(11, 12) +
              R"(, 0] }, { "line_to": [)" + x0 + ", " + y0 + R"(] } ] })";
    std::string text = R"({ "hipair": 1, "name": "generated", "parts": [
      { "name": "block", "motion": "fixed", "loops": [ )" + fixed + R"( ] },
      { "name": "bar", "motion": { "pin_slot": { "pivot": [0, 0], "direction": [1, 0], "angle_limits": [-70, 70],
        "limits": [-3, 4] } }, "loops": [ )" + bar + R"( ] } ],
      "pairs": [ { "parts": ["block", "bar"] } ] })";
    Model model = read_model(text);
    PinSlotSpace space = PinSlotSpace::build(model, "block", "bar");
    ASSERT_TRUE(space.critical_values_exact());
    expect_steady_between_critical_values(space, random);
    for (int i = 0; i < 200; ++i) {
      PinSlotConfiguration q{{}, random_rational(random, -3, 4, 64), random_rational(random, -0.7, 0.7, 64)};
      EXPECT_EQ(space.locate(q).kind, oracle(model, space, q));
    }
  }
  // outside the class (a slanted bar end of length sqrt 5 facing the stadium's arcs): the
  // sampled stack, no exact critical values, no error
  Model slanted = read_model(R"({ "hipair": 1, "name": "slanted", "parts": [
    { "name": "block", "motion": "fixed", "loops": [ { "start": [10, -3], "edges": [ { "line_to": [14, -3] },
      { "arc_to": [14, 3], "center": [14, 0], "dir": "ccw" }, { "line_to": [10, 3] },
      { "arc_to": [10, -3], "center": [10, 0], "dir": "ccw" } ] } ] },
    { "name": "bar", "motion": { "pin_slot": { "pivot": [0, 0], "direction": [1, 0], "angle_limits": [-70, 70],
      "limits": [-3, 4] } }, "loops": [ { "start": [0, -1], "edges": [ { "line_to": [7, -1] }, { "line_to": [8, 1] },
      { "line_to": [0, 1] }, { "line_to": [0, -1] } ] } ] } ],
    "pairs": [ { "parts": ["block", "bar"] } ] })");
  PinSlotSpace sampled = PinSlotSpace::build(slanted, "block", "bar");
  EXPECT_FALSE(sampled.critical_values_exact());
  EXPECT_TRUE(sampled.critical_values().empty());
}

}  // namespace
}  // namespace hipair
