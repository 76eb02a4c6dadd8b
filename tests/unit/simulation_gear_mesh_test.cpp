// Session 57 (simgear57): spur-gear pairs simulated, a torque driving the pinion into a gear
// held back by its inertia and damping. `hipair simulate` of the 18 x 27 example built the whole
// torus (z1 z2 tooth encounters, minutes with nothing shown); a pair of more than
// SimulationOptions::operating_region_above_edges boundary edges is now built as its operating
// region (the whole flooded channel of its start), the smaller ones whole.
//
// Generated pairs (the example's profile; seeded, the seed printed on failure): 9 x 11 with
// backlash 0.1 mm, then one pair of 6 ... 12 teeth with backlash 0.08 ... 0.12 mm and the centre
// distance within +-0.02 mm of m (z1 + z2) / 2, and one without backlash, the centre distance
// opened by 0.1 ... 0.3 mm (less leaves these small teeth overlapping at the start); built as
// operating regions (above 100 edges). Each pair is driven until the rigid mesh's closed form
// has turned its pinion by 2.5 pitches (two tooth changes or more; session 58: 0.2 s before,
// 1.16 pitches of a 6 x 7 pair, which made one change where two were asked).
// - the space is an operating region exactly when the pair has more than 100 boundary edges;
// - no accepted state overlaps, by the exact overlap predicate at the state's angles (every
//   tenth state and every state of an event; a state holding a contact: at its angles or with
//   the gear turned by +-1e-12 rad, the rounding margin of a contact state computed in doubles);
// - a pair whose free channel closes locks: at rest on a drive and a back flank at once
//   (LockedPairCannotTurnOn checks such a lock exactly);
// - otherwise the drive flanks' tooth pairs follow one another one tooth of each gear at a time
//   (contacts on the back flanks are rattles: every pair of 6 ... 12 teeth interferes, the gear's
//   tip meets the pinion's radial flank below its base circle, and the gear may lift off there),
//   the gears turn opposite ways at z1 / z2 within one gear tooth over the run, with one tooth
//   change per pinion pitch;
// - the gear ratio: from one tooth change to the next where both take up the same contact of the
//   periodic space at the vertex where the old one ends (no lift-off between), the pinion turns
//   2 pi / z1 and the gear 2 pi / z2 the other way, within 1.2e-8 rad (each state lies within
//   three edge slacks, 3e-9 chart units, of the vertex: 6e-9 rad); 9 x 11 makes such checks
//   every seed;
// - against the whole space (7 x 9, 128 edges, an operating region by default, to 0.15 s,
//   one tooth change): the same events (kinds, features), at the same times within the
//   accuracy per step (1e-9 s times the steps; Coulomb events too), the same end state within
//   1e-6 rad, no accepted state of the region's run overlapping (as above), and at a handover
//   of both flanks' arcs (tangent-continuous: the sliding speed is) the new contact sliding the
//   way the old one did (session 58, slip58).
#include "test_paths.hpp"
#include "test_seed.hpp"
#include "tolerance/exact_order.hpp"

#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <regex>
#include <string>
#include <utility>
#include <vector>

namespace hipair {
namespace {

constexpr double kAccuracy = 1e-9;   // SimulationOptions::accuracy of every run here

std::uint64_t test_seed() { return hipair::test::test_seed(61); }

// The example's gears with z1 and z2 teeth, the given backlash (mm) and centre distance
// m (z1 + z2) / 2 + offset (mm), exact.
Model gear_pair(long z1, long z2, const Rational& backlash, const Rational& offset) {
  ReadOptions read;
  read.parameter_values["teeth-1"] = Rational(z1);
  read.parameter_values["teeth-2"] = Rational(z2);
  read.parameter_values["backlash"] = backlash;
  read.parameter_values["center-distance"] = Rational(Rational(z1 + z2) + offset);
  read.allow_out_of_tolerance = true;
  return read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "spur-gears.json", read);
}

std::size_t boundary_edges(const Model& model) {
  std::size_t edges = 0;
  for (const Part& part : model.parts)
    for (const Loop& loop : part.loops) edges += loop.edges.size();
  return edges;
}

// A part turned by `angle` about its pivot, exactly: the rotation through the rational half-angle
// tangent nearest in double (within a few 1e-16 rad of `angle`).
Placement turned(const Part& part, double angle) {
  Rational t(std::tan(angle / 2));
  Rational d = 1 + t * t;
  return placement_about(part.motion.pivot, (1 - t * t) / d, 2 * t / d, Point{Rational(0), Rational(0)});
}

PartRelation relation(const Model& model, double pinion, double gear) {
  return part_overlap(model.parts[0], turned(model.parts[0], pinion), model.parts[1], turned(model.parts[1], gear))
      .relation;
}

struct Recorded {
  double time;
  double pinion, gear;
};

// The tooth pair and flanks an event names: "pinion tooth 1 flank L upper / gear tooth 27 flank L
// lower (...)", or a corner, "gear corner of tooth 9 flank L lower and tooth 9 flank L radial"
// (each side: its first tooth and its first flank letter, "" for a tip alone); nullopt when a
// side names no tooth.
struct Mesh {
  long pinion_tooth = 0, gear_tooth = 0;
  std::string pinion_flank, gear_flank;
};
std::optional<Mesh> mesh_of(const SimulationEvent& e) {
  static const std::regex tooth(R"(tooth (\d+))"), flank(R"(flank (\w+))");
  if (e.features.empty()) return std::nullopt;
  const std::string& label = e.features.front();
  const std::size_t bar = label.find(" / ");
  if (label.rfind("pinion ", 0) != 0 || bar == std::string::npos) return std::nullopt;
  const std::string sides[2] = {label.substr(0, bar), label.substr(bar + 3)};
  if (sides[1].rfind("gear ", 0) != 0) return std::nullopt;
  Mesh mesh;
  long* teeth[2] = {&mesh.pinion_tooth, &mesh.gear_tooth};
  std::string* flanks[2] = {&mesh.pinion_flank, &mesh.gear_flank};
  for (int k = 0; k < 2; ++k) {
    std::smatch m;
    if (!std::regex_search(sides[k], m, tooth)) return std::nullopt;
    *teeth[k] = std::stol(m[1]);
    if (std::regex_search(sides[k], m, flank)) *flanks[k] = m[1];
  }
  return mesh;
}

// (a - b) mod n in 0 .. n-1
long step_mod(long a, long b, long n) { return ((a - b) % n + n) % n; }

struct GearRun {
  std::vector<Recorded> states;
  std::vector<SimulationEvent> events;
  bool complete = true;
  double end_speed = 0;                           // the larger of the two end speeds (rad/s)
  std::vector<SimulationContact> end_contacts;    // the contacts held at the end
  std::shared_ptr<const CSpace> space;            // the pair's built C-space (the lock's exact check)
};

// `check_overlap`: every accepted state checked by the exact overlap predicate, or (`sparse`)
// every tenth and every one at which an event happened (the contact changes, where the faults
// were; the predicate on two gears costs milliseconds a state).
GearRun simulate(const Model& model, double t_end, std::size_t above_edges, const std::string& where,
             bool check_overlap, bool sparse = false) {
  SimulationOptions options;
  options.accuracy = kAccuracy;
  options.operating_region_above_edges = above_edges;
  Simulation s = Simulation::create(model, options);
  GearRun run;
  run.complete = s.spaces()[0]->complete();
  run.space = s.spaces()[0];
  run.states.push_back({s.state().time, s.state().position[0], s.state().position[1]});
  std::size_t overlaps = 0;
  auto check = [&] {
    const double p = s.state().position[0], g = s.state().position[1];
    if (!check_overlap || relation(model, p, g) != PartRelation::overlapping) return;
    const bool held = !s.contacts().empty();
    // a contact state: on its curve in doubles, within rounding of the exact curve
    if (held && (relation(model, p, g + 1e-12) != PartRelation::overlapping ||
                 relation(model, p, g - 1e-12) != PartRelation::overlapping))
      return;
    if (++overlaps <= 3)
      ADD_FAILURE() << where << ": the parts overlap at t = " << s.state().time << " (pinion " << p << ", gear " << g
                    << ", " << (held ? "holding a contact" : "free") << ")";
  };
  check();
  std::size_t events_seen = 0;
  try {
    s.run_until(t_end, [&](double) {
      run.states.push_back({s.state().time, s.state().position[0], s.state().position[1]});
      const bool event = s.events().size() != events_seen;
      events_seen = s.events().size();
      if (!sparse || event || run.states.size() % 10 == 0) check();
    });
  } catch (const Error& error) {
    ADD_FAILURE() << where << ": " << error.what();
  }
  EXPECT_EQ(overlaps, 0u) << where;
  run.events = s.events();
  run.end_speed = std::max(std::abs(s.state().velocity[0]), std::abs(s.state().velocity[1]));
  run.end_contacts = s.contacts();
  return run;
}

// The example's dynamics: the pinion (inertia I1 = 300 kg mm^2) driven by T = 100 N mm, the gear
// (I2 = 1500 kg mm^2) held back by its damping c = 5 N mm s. Meshed rigidly at the ratio
// r = z1 / z2, without friction, the pinion's angle from rest is the closed form
// (T / c_r) (t - tau (1 - exp(-t / tau))), c_r = c r^2, tau = (I1 + I2 r^2) / c_r. The time it
// takes to turn the pinion by `angle` (bisection on that increasing function).
double closed_form_time(long z1, long z2, double angle) {
  const double r = static_cast<double>(z1) / static_cast<double>(z2);
  const double T = 100e3, I1 = 300, I2 = 1500, c = 5e3;   // mN mm, kg mm^2, mN mm s
  const double cr = c * r * r, tau = (I1 + I2 * r * r) / cr;
  auto turned = [&](double t) { return T / cr * (t - tau * (1 - std::exp(-t / tau))); };
  double lo = 0, hi = 10;
  for (int k = 0; k < 100; ++k) (turned(0.5 * (lo + hi)) < angle ? lo : hi) = 0.5 * (lo + hi);
  return hi;
}

// A feature-pair label with its tooth numbers left out: the same contact of the periodic space.
std::string untoothed(const std::string& label) {
  static const std::regex number(R"(\d+)");
  return std::regex_replace(label, number, "#");
}

// The chart of a gear pair's C-space is t = tan(theta / 2); a state at a contact change lies
// within the held contact's slack of the vertex, at most three edge slacks (3e-9 chart units,
// simulation.cpp) past it: within 2 x 3e-9 rad of it (d theta = 2 dt / (1 + t^2)). Two such
// states of the same vertex of the periodic space are a pitch apart within twice that.
constexpr double kVertexTolerance = 2 * 2 * 3e-9;

// A lock checked exactly through the adaptor (session 62, exact62; until then 241 samples of the
// exact overlap predicate at gear angles g + k delta / 100, |k| <= 120): the pair's C-space sliced
// exactly at the pinion turned on by delta past the locked state (pinion p, gear g; the pinion is
// the space's x axis, t = tan(theta / 2)), and no free interval of that 1-D slice may meet the gear
// angles [g - 1.2 delta, g + 1.2 delta] — every gear angle there, not samples, is blocked (or on
// contact space): the channel is closed ahead, for delta = 1e-4 and 1e-6 rad. The intervals' ends
// are the slice's exact algebraic points, compared with the window's rational ends exactly (the
// sign of their polynomial). LockedPairCannotTurnOn also finds the sliver behind (a free interval
// meeting the window at p - delta).
constexpr double kLockDelta = 1e-4;
// -1, 0, +1: the sign of a - y, exactly (the tolerance analysis' exact order of slice points).
using tolerance_detail::compare;
struct SliceWindow {
  std::size_t free = 0;        // free intervals meeting the window (exactly)
  bool found = false;          // the slice through the window's chart was found
};
SliceWindow free_in_window(const CSpace& space, double pinion, double gear, double half_width) {
  using Kind = PartCoordinate::Kind;
  SliceWindow out;
  const PartCoordinate x{Kind::half_angle_tangent, Rational(std::tan(pinion / 2))};
  const auto lo = space.to_chart(x, PartCoordinate{Kind::half_angle_tangent, Rational(std::tan((gear - half_width) / 2))});
  const auto hi = space.to_chart(x, PartCoordinate{Kind::half_angle_tangent, Rational(std::tan((gear + half_width) / 2))});
  if (!lo || !hi || lo->chart != hi->chart) return out;
  const Rational y_lo = std::min(lo->y, hi->y), y_hi = std::max(lo->y, hi->y);
  for (const Slice& slice : space.slice(SliceAxis::x, lo->x)) {
    if (slice.chart != lo->chart) continue;
    out.found = true;
    for (std::size_t i = 0; i < slice.intervals.size(); ++i) {
      if (slice.intervals[i].kind != CellKind::free) continue;
      // the interval (A, B) meets [y_lo, y_hi] when A < y_hi and B > y_lo
      const bool below_top = i == 0 ? slice.lower < y_hi : compare(slice.points[i - 1].at, y_hi) < 0;
      const bool above_bottom = i + 1 == slice.intervals.size() ? slice.upper > y_lo : compare(slice.points[i].at, y_lo) > 0;
      if (below_top && above_bottom) ++out.free;
    }
  }
  return out;
}
void expect_cannot_turn_on(const CSpace& space, double p, double g, const std::string& where) {
  ASSERT_EQ(space.x_part(), "pinion") << where;
  for (const double delta : {kLockDelta, 1e-6}) {
    const SliceWindow ahead = free_in_window(space, p + delta, g, 1.2 * delta);
    ASSERT_TRUE(ahead.found) << where << ": no slice of the built space at pinion " << p + delta;
    EXPECT_EQ(ahead.free, 0u) << where << ": locked at pinion " << p << ", but turned on by " << delta
                                  << " rad a free interval of gear angles meets " << g << " +- " << 1.2 * delta;
  }
}

struct MeshSummary {
  bool locked = false;
  std::size_t ratio_checks = 0;   // tooth pitches checked at the same vertex of the periodic space
};

// The checks on one generated pair (see the file's comment).
MeshSummary expect_meshing(long z1, long z2, const Rational& backlash, const Rational& offset) {
  MeshSummary summary;
  const std::string where = "gears " + std::to_string(z1) + "x" + std::to_string(z2) + ", backlash " +
                            backlash.get_str() + " mm, centre offset " + offset.get_str() + " mm";
  const double pinion_pitch = 2 * std::numbers::pi / static_cast<double>(z1);
  const double gear_pitch = 2 * std::numbers::pi / static_cast<double>(z2);
  // long enough for the rigid mesh to turn the pinion by 2.5 pitches: at least two tooth changes
  const double t_end = closed_form_time(z1, z2, 2.5 * pinion_pitch);
  Model model = gear_pair(z1, z2, backlash, offset);
  GearRun run = simulate(model, t_end, 100, where, true, true);
  EXPECT_EQ(run.complete, boundary_edges(model) <= 100) << where << ": " << boundary_edges(model) << " edges";
  if (run.events.empty() || run.states.back().time < t_end) {
    ADD_FAILURE() << where << ": the teeth never met, or the run stopped at t = " << run.states.back().time;
    return summary;
  }
  EXPECT_EQ(run.events.front().kind, SimulationEvent::Kind::impact) << where;
  // A pair whose free channel closes (the gear's tip on the pinion's radial flank below its base
  // circle, the back flanks touching at the same configuration) locks: it ends at rest on two
  // contacts, one on each side of the teeth (checked exactly by LockedPairCannotTurnOn's oracle)
  if (run.end_contacts.size() == 2 && run.end_speed < 1e-9) {
    summary.locked = true;
    bool drive = false, back = false;
    for (const SimulationContact& c : run.end_contacts) {
      SimulationEvent e;
      e.features = c.features;
      std::optional<Mesh> m = mesh_of(e);
      if (!m) {
        ADD_FAILURE() << where << ": a held contact names no flank pair";
        return summary;
      }
      drive = drive || m->gear_flank == "L";
      back = back || m->gear_flank == "R";
    }
    EXPECT_TRUE(drive && back) << where << ": locked, but not between a drive and a back flank";
    expect_cannot_turn_on(*run.space, run.states.back().pinion, run.states.back().gear, where);
    return summary;
  }
  // The drive flanks ("L" of both gears under this torque) meet tooth pair after tooth pair, one
  // tooth of each gear at a time. A contact on the back flanks ("R") is a rattle: these small
  // pinions' radial flanks meet the gear's tip below the base circle (every pair of 6 ... 12 teeth
  // interferes: the gear's tip radius z2 + 2 exceeds sqrt((z2 cos 20)^2 + ((z1 + z2) sin 20)^2)),
  // the ratio there jumps, and the gear, faster than the next contact lets it be, lifts off and
  // crosses the backlash (docs/simulation.md, session 58)
  std::optional<Mesh> current;
  std::optional<std::pair<long, long>> direction;   // the tooth steps of a change
  struct Change {
    std::size_t state;
    bool at_vertex;       // the old contact ended at the same time (an edge end): a vertex of the space
    std::string label;    // the new contact, teeth left out
    std::size_t lift_offs;   // lift-offs before it
  };
  std::vector<Change> changes;
  std::size_t lift_offs = 0;
  for (std::size_t k = 0; k < run.events.size(); ++k) {
    const SimulationEvent& e = run.events[k];
    if (e.kind == SimulationEvent::Kind::lift_off) ++lift_offs;
    std::optional<Mesh> mesh = mesh_of(e);
    if (!mesh) {
      ADD_FAILURE() << where << ": an event names no flank pair: " << (e.features.empty() ? "" : e.features.front());
      return summary;
    }
    if (mesh->gear_flank == "R" || mesh->pinion_flank == "R") continue;   // a rattle
    if (!current) {
      current = mesh;
      continue;
    }
    if (mesh->pinion_tooth == current->pinion_tooth && mesh->gear_tooth == current->gear_tooth) continue;
    // the old pair's edge-end names the old teeth after the new contact: only moves forward count
    std::pair<long, long> step{step_mod(mesh->pinion_tooth, current->pinion_tooth, z1),
                               step_mod(mesh->gear_tooth, current->gear_tooth, z2)};
    std::pair<long, long> back{step_mod(current->pinion_tooth, mesh->pinion_tooth, z1),
                               step_mod(current->gear_tooth, mesh->gear_tooth, z2)};
    if (direction && back == *direction) continue;
    if (!direction) {
      direction = step;
      EXPECT_TRUE((step.first == 1 || step.first == z1 - 1) && (step.second == 1 || step.second == z2 - 1))
          << where << ": the first tooth change skips teeth at t = " << e.time;
    }
    EXPECT_EQ(step, *direction) << where << ": a tooth change out of order at t = " << e.time;
    current = mesh;
    std::size_t at = 0;
    for (std::size_t j = 0; j < run.states.size(); ++j)
      if (std::abs(run.states[j].time - e.time) < std::abs(run.states[at].time - e.time)) at = j;
    EXPECT_EQ(run.states[at].time, e.time) << where << ": no step ends at the tooth change";
    bool edge_end = false;
    for (const SimulationEvent& f : run.events)
      edge_end = edge_end || (f.time == e.time && f.kind == SimulationEvent::Kind::edge_end);
    changes.push_back({at, edge_end, untoothed(e.features.front()), lift_offs});
  }
  if (changes.size() < 2) {
    ADD_FAILURE() << where << ": " << changes.size() << " tooth changes by t = " << t_end << " (two or more asked)";
    return summary;
  }
  // the whole run: the gears turned opposite ways at z1 / z2 within one gear tooth (the mesh never
  // skips a tooth), and one tooth change per pinion pitch turned (within the first and last)
  const Recorded& first = run.states.front();
  const Recorded& last = run.states.back();
  EXPECT_LT(std::abs((last.gear - first.gear) + (last.pinion - first.pinion) * static_cast<double>(z1) / static_cast<double>(z2)),
            gear_pitch)
      << where;
  EXPECT_LE(std::abs(static_cast<double>(changes.size()) - (last.pinion - first.pinion) / pinion_pitch), 2.0) << where;
  // from one tooth change to the next at the same vertex of the periodic space (the same contact
  // taken up where the old one ends, no lift-off between): the pinion turns 2 pi / z1 and the
  // gear 2 pi / z2 the other way, to the vertex's tolerance
  for (std::size_t k = 1; k < changes.size(); ++k) {
    const Change& a = changes[k - 1];
    const Change& b = changes[k];
    if (!a.at_vertex || !b.at_vertex || a.label != b.label || a.lift_offs != b.lift_offs) continue;
    ++summary.ratio_checks;
    const Recorded& sa = run.states[a.state];
    const Recorded& sb = run.states[b.state];
    EXPECT_NEAR(std::abs(sb.pinion - sa.pinion), pinion_pitch, kVertexTolerance) << where << ": change " << k;
    EXPECT_NEAR(std::abs(sb.gear - sa.gear), gear_pitch, kVertexTolerance) << where << ": change " << k;
    EXPECT_LT((sb.pinion - sa.pinion) * (sb.gear - sa.gear), 0) << where << ": change " << k;
  }
  return summary;
}

// Session 58 (gearsim58): enabled. Before, seeds 1 ... 4 failed: 6 x 8 (backlash 0.087 mm, offset
// -0.013 mm) jammed at 0.0700516 s where its free channel closes (now it locks, as it must: see
// LockedPairCannotTurnOn); 6 x 7 made one tooth change by 0.2 s where two were asked (the closed
// form turns its pinion 1.21 rad = 1.16 pitches by then: the test's expectation was wrong, the
// run now lasts until the rigid mesh turns 2.5 pitches); 6 x 9 and 6 x 8 without backlash lift
// off after the gear's tip strikes the pinion's radial flank and rattle onto the back flanks
// (physically possible, see expect_meshing), and the ratio was checked across such a rattle,
// from one impact to another at no common vertex.
TEST(SimulationGearMesh, GeneratedPairsMeshToothByToothAtTheRatioOfTheirTeeth) {
  const std::uint64_t seed = test_seed();
  SCOPED_TRACE("seed " + std::to_string(seed) + " (HIPAIR_TEST_SEED repeats it)");
  std::mt19937_64 random(seed);
  auto millis = [](long n) {
    Rational r(n, 1000);
    r.canonicalize();
    return r;
  };
  std::size_t ratio_checks = 0;
  // 9 x 11 with backlash (its tooth changes at vertices: the ratio is checked every seed), then
  // a generated pair of 6 ... 12 teeth with backlash and one without (the centre distance opened)
  ratio_checks += expect_meshing(9, 11, Rational(1, 10), Rational(0)).ratio_checks;
  for (int round = 0; round < 2; ++round) {
    long z1 = 6 + static_cast<long>(random() % 7), z2 = 6 + static_cast<long>(random() % 7);
    if (z1 > z2) std::swap(z1, z2);
    Rational backlash = round == 0 ? millis(80 + static_cast<long>(random() % 41)) : Rational(0);
    Rational offset = round == 0 ? millis(static_cast<long>(random() % 41) - 20) : millis(100 + static_cast<long>(random() % 201));
    ratio_checks += expect_meshing(z1, z2, backlash, offset).ratio_checks;
  }
  EXPECT_GE(ratio_checks, 1u) << "no two tooth changes at the same vertex: the ratio was never checked";
}

// The generated test's pairs one by one (session 61, gearflake61): HIPAIR_GEAR_PAIRS lists pairs as
// z1xz2:backlash:offset in thousandths of a mm ("6x8:87:-13 7x12:0:150"), each checked as the
// generated test checks its pairs. Skipped without it: this is how the parameter space is swept
// by hand, one process per pair (docs/simulation.md, session 61).
TEST(SimulationGearMesh, PairsListedInTheEnvironment) {
  const char* text = std::getenv("HIPAIR_GEAR_PAIRS");
  if (text == nullptr || *text == '\0') GTEST_SKIP() << "set HIPAIR_GEAR_PAIRS=z1xz2:backlash:offset ... (thousandths of a mm)";
  static const std::regex pair(R"((\d+)x(\d+):(-?\d+):(-?\d+))");
  const std::string list(text);
  std::size_t pairs = 0;
  for (std::sregex_iterator it(list.begin(), list.end(), pair), end; it != end; ++it, ++pairs) {
    const std::smatch& m = *it;
    Rational backlash(std::stol(m[3]), 1000), offset(std::stol(m[4]), 1000);
    backlash.canonicalize();
    offset.canonicalize();
    const MeshSummary summary = expect_meshing(std::stol(m[1]), std::stol(m[2]), backlash, offset);
    std::cout << m[0] << ": " << (summary.locked ? "locked" : "meshed") << ", " << summary.ratio_checks
              << " ratio checks\n";
  }
  EXPECT_GT(pairs, 0u) << "HIPAIR_GEAR_PAIRS names no pair z1xz2:backlash:offset: " << list;
}

// Session 61 (gearflake61): pairs the generated test can draw that failed (found by sweeping
// PairsListedInTheEnvironment over the test's parameter space; session 60's CI went red at one it
// drew). Each closes its channel where the gear's tip, sliding on the pinion's radial flank,
// meets the back flanks' contact (a cusp), and must lock there (checked exactly, as every locked
// pair of the generated test):
// - 6 x 11, backlash 0.08 mm, offset -0.02 mm: "a jammed contact change" at t = 0.0464797 s. The
//   tip's contact, taken up at a vertex, was continued across the chart seam at 1/16 with the old
//   edge's vertex end: its slack of three edge slacks held about the new edge's far end, the cut
//   came 3e-9 chart units past the cusp, beyond the back flanks' contact's reach;
// - 6 x 10 without backlash, offset 0.1 mm: the impact into the cusp "has no consistent stick/slip
//   solution" at t = 0.0620619 s (both contacts sticking stop the pair and leave the impulses
//   open; the frictionless impulses are the consistent solution).
// And one that meshes: 7 x 8, backlash 0.105 mm, offset -0.016 mm (seed 61's first pair):
// "a jammed contact change ... beyond blocked space" at t = 0.267906 s, the same stale vertex end
// at a tooth change.
TEST(SimulationGearMesh, PairsThatFailedAtDrawnParametersLockAtTheirCuspOrMesh) {
  EXPECT_TRUE(expect_meshing(6, 11, Rational(2, 25), Rational(-1, 50)).locked);
  EXPECT_TRUE(expect_meshing(6, 10, Rational(0), Rational(1, 10)).locked);
  const MeshSummary meshed = expect_meshing(7, 8, Rational(21, 200), Rational(-2, 125));
  EXPECT_FALSE(meshed.locked);
  EXPECT_GE(meshed.ratio_checks, 1u);
}

// The 6 x 8 pair of backlash 0.087 mm and centre offset -0.013 mm (seed 3 before session 58):
// at pinion 0.18935 rad the gear's tooth 1 tip, on the pinion's tooth 6 radial flank, meets the
// back flanks' contact, and the free channel closes in a cusp (the two contact curves meet there
// with slopes -0.835 and -0.754). The simulator holds both contacts and the pair stays at rest,
// driven into the cusp. The exact slice of its C-space says the same (expect_cannot_turn_on): at
// the pinion turned on by delta no gear angle near the lock is free, and turned back by delta the
// sliver between the two curves (about 0.08 delta wide in gear angle) is a free interval.
TEST(SimulationGearMesh, LockedPairCannotTurnOn) {
  Model model = gear_pair(6, 8, Rational(87, 1000), Rational(-13, 1000));
  GearRun run = simulate(model, 0.1, 100, "6x8 lock", true);
  ASSERT_EQ(run.end_contacts.size(), 2u);
  EXPECT_LT(run.end_speed, 1e-9);
  const double p = run.states.back().pinion, g = run.states.back().gear;
  EXPECT_NEAR(p, 0.18935, 1e-5);
  expect_cannot_turn_on(*run.space, p, g, "6x8 lock");
  const SliceWindow behind = free_in_window(*run.space, p - kLockDelta, g, 1.2 * kLockDelta);
  EXPECT_GE(behind.free, 1u) << "the sliver behind the lock was not found: the slice cannot see the channel";
  // the overlap oracle agrees at the sliver's middle and ahead
  EXPECT_EQ(relation(model, p + kLockDelta, g), PartRelation::overlapping);
}

TEST(SimulationGearMesh, TheOperatingRegionRunsAsTheWholeSpace) {
  // 7 x 9 teeth: 128 boundary edges, an operating region in the default run
  Model model = gear_pair(7, 9, Rational(1, 10), Rational(0));
  ASSERT_GT(boundary_edges(model), 120u);
  GearRun region = simulate(model, 0.15, 120, "7x9 region", true);
  GearRun whole = simulate(model, 0.15, 0, "7x9 whole", false);
  EXPECT_FALSE(region.complete);
  EXPECT_TRUE(whole.complete);
  ASSERT_EQ(region.events.size(), whole.events.size());
  // the two runs' steps differ in their last bits (the crossing queries' subdivisions meet the
  // tiles' seams): event times agree to the accuracy per step taken
  const double time_tolerance = kAccuracy * static_cast<double>(whole.states.size());
  // A Coulomb event (slip, stick) included: the relative sliding speed of the drive flanks
  // crosses zero at the pitch point with a slope of about 1e3 mm/s^2 (not a near-tangent
  // crossing), at the 0.1368 s handover of the flanks' arcs. Before session 58 (slip58) the
  // contact taken up there was decided at rest without the tangent's curvature term and slid the
  // wrong way for one step (its event 1e-7 s apart in the two runs at backlash 0.1 mm, 9.6e-8 at
  // 0.101 mm, the step lengths); now within the at-rest band (sliding speed 2.1e-5 over that
  // slope: 2e-8 s) of each other.
  for (std::size_t k = 0; k < whole.events.size(); ++k) {
    EXPECT_EQ(region.events[k].kind, whole.events[k].kind) << "event " << k;
    EXPECT_EQ(region.events[k].features, whole.events[k].features) << "event " << k;
    EXPECT_NEAR(region.events[k].time, whole.events[k].time, time_tolerance) << "event " << k;
  }
  // Where a sliding contact hands over to the next arcs of both flanks (arc tangent to arc on
  // both sides of an edge end: the profiles are tangent-continuous there, so is the sliding
  // speed) the new contact slides the way the old one did: before slip58 the contact taken up at
  // the pitch point was decided at rest without the tangent's curvature term and slid the other
  // way for a step (a slip +1 at 0.1367683 s after the old contact's slip -1).
  for (const GearRun* run : {&region, &whole}) {
    const std::vector<SimulationEvent>& ev = run->events;
    int sliding = 0;   // the last slip direction of the contact held before
    for (std::size_t k = 0; k < ev.size(); ++k) {
      if (ev[k].kind == SimulationEvent::Kind::stick) sliding = 0;
      if (ev[k].kind != SimulationEvent::Kind::slip || ev[k].features.empty()) continue;
      bool tangent_handover = false;
      for (std::size_t j = 0; j < k; ++j)
        if (ev[j].kind == SimulationEvent::Kind::edge_end && ev[j].time == ev[k].time && !ev[j].features.empty() &&
            ev[j].features.front().find("(arc tangent to arc)") != std::string::npos &&
            ev[k].features.front().find("(arc tangent to arc)") != std::string::npos)
          tangent_handover = true;
      if (tangent_handover)
        EXPECT_EQ(ev[k].slip_direction, sliding) << (run == &region ? "region" : "whole") << " event " << k << " at t = " << ev[k].time;
      sliding = ev[k].slip_direction;
    }
  }
  // (tighter than the event-time tolerance times the gears' speeds, about 3e-6 rad)
  EXPECT_NEAR(region.states.back().pinion, whole.states.back().pinion, 1e-6);
  EXPECT_NEAR(region.states.back().gear, whole.states.back().gear, 1e-6);
}

}  // namespace
}  // namespace hipair
