// A square thrown past a needle-sized bump (docs/simulation.md, "A held set the velocities cannot
// keep"; docs/performance.md, session 52 esc52): the square's bottom-right corner is aimed at a fixed
// bump of width d (1e-4 ... 1.5e-8 mm) just below its parabola, so the bottom face lands on the bump's
// two top vertices, bounces on them (restitution 1/2) until the bounces are plastic, and then turns
// on them. Where the two vertices are within a few chord deviations of each other, base52 held both
// after the impact that moved the face from one to the other: the projection onto two nearly
// dependent rows left one approaching, the next step lifted it off and the chord struck it again,
// without end (each round 2 steps and 4 events, its exact numbers growing: no progress in minutes).
// Oracles from the physics of the case: the impacts of the bounce series (approach speed g t_c,
// times e per bounce, plastic below the rest speed sqrt(2 g delta)), at most a few contact changes
// afterwards, never a contact made and lifted off at one instant, and t_end reached within a step
// budget from the chord length at the energy's bounds (docs/simulation.md, "Parts free in the plane").
#include <hipair/model.hpp>
#include <hipair/overlap.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include "simulation/companion_watch.hpp"
#include "simulation_planar_support.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <utility>

namespace hipair {
namespace {

using planar_test::num;

struct NeedleCase {
  double d = 1e-8, vx = 600;
  double y0 = 56, tc = 0.028, g = 9810, mass = 0.008, inertia = 0.1333, e = 0.5;

  std::string json() const {
    // the corner (5, -5) of the square reaches x = a at t_c, at height yc; the bump's top is 1.3 d below
    const double a = 5 + vx * tc, yc = y0 - 5 - 0.5 * g * tc * tc;
    const std::string x0 = num(a - 0.4 * d), x1 = num(a + 0.6 * d), yb = num(yc - 2.3 * d), yt = num(yc - 1.3 * d);
    return R"({ "hipair": 1, "name": "needle", "units": { "length": "mm", "angle": "rad" },
      "parts": [
        { "name": "bump", "motion": "fixed", "loops": [ { "label": "bump", "start": [)" + x0 + ", " + yb +
           R"(], "edges": [ { "line_to": [)" + x1 + ", " + yb + R"(] }, { "line_to": [)" + x1 + ", " + yt +
           R"(] }, { "line_to": [)" + x0 + ", " + yt + R"(] }, { "line_to": [)" + x0 + ", " + yb + R"(] } ] } ] },
        { "name": "peg", "motion": { "planar": { "pivot": [0, 0] } }, "initial": { "x": 0, "y": )" + num(y0) +
           R"(, "angle": 0 }, "dynamics": { "mass": )" + num(mass) + R"(, "moment_of_inertia": )" + num(inertia) + R"( },
          "loops": [ { "label": "peg", "start": [-5, -5], "edges": [ { "line_to": [5, -5], "label": "peg bottom" },
            { "line_to": [5, 5] }, { "line_to": [-5, 5] }, { "line_to": [-5, -5] } ] } ] } ],
      "pairs": [ { "parts": ["bump", "peg"], "restitution": )" + num(e) + R"( } ],
      "simulation": { "units": { "time": "s", "force": "N" }, "gravity": [0, )" + num(-g) + R"(],
        "velocities": { "peg": { "x": )" + num(vx) + R"(, "y": 0, "angle": 0 } } } })";
  }
};

TEST(SimulationPlanarNeedle, TurningOnANeedleSizedBumpKeepsOneContactAndProgresses) {
  const double t_end = 0.034;
  int cases = 0;
  // bump widths and speeds: base52 chattered at the last three (2e-8 mm at 600 and 650 mm/s,
  // 1.5e-8 mm at 650 mm/s) and turned on one vertex throughout at the first two
  const std::pair<double, double> runs[] = {{1e-4, 600}, {1e-6, 650}, {2e-8, 600}, {2e-8, 650}, {1.5e-8, 650}};
  for (const auto& [d, vx] : runs) {
      NeedleCase c;
      c.d = d;
      c.vx = vx;
      SCOPED_TRACE("bump " + num(d) + " mm, vx " + num(vx) + " mm/s");
      PlanarSimulation sim = PlanarSimulation::create(read_model(c.json()));
      // the bounce series: approach g t_c at the first impact, e times that per bounce, plastic
      // below the rest speed sqrt(2 g delta)
      const double delta = sim.chord_deviation(), v0 = c.g * c.tc, rest = std::sqrt(2 * c.g * delta);
      const int bounces = static_cast<int>(std::ceil(std::log(v0 / rest) / std::log(1 / c.e))) + 2;
      // the chord length at the energy's bounds: kinetic energy at most the start's plus the drop to
      // the bump's top less the reach (sqrt 50); a held vertex's force at most m (g + w^2 R); the
      // angle chart's w'' with |w| <= tan(3 pi / 8) (docs/simulation.md, "Parts free in the plane")
      const double reach = std::sqrt(50.0), drop = c.y0 - (c.y0 - 5 - 0.5 * c.g * c.tc * c.tc - reach);
      const double energy = 0.5 * c.mass * c.vx * c.vx + c.mass * c.g * drop;
      const double w_max = std::sqrt(2 * energy / c.inertia), a_max = c.g + w_max * w_max * reach;
      const double alpha_max = c.mass * a_max * reach / c.inertia, W = std::tan(3 * std::numbers::pi / 8);
      const double wpp = 0.5 * (1 + W * W) * (alpha_max + W * w_max * w_max);
      const double chord = std::sqrt(4 * delta / (a_max + 2 * reach * wpp));
      const auto budget = static_cast<std::size_t>(4 * bounces + t_end / chord);
      // after the series: at most a contact, a lift-off or an edge end per vertex and two more
      const std::size_t event_budget = static_cast<std::size_t>(bounces) + 6;
      while (sim.state().time < t_end && sim.steps() <= budget && sim.events().size() <= event_budget) sim.step(t_end);
      EXPECT_GE(sim.state().time, t_end - 1e-12) << sim.steps() << " steps (budget " << budget << "), " << sim.events().size()
                                         << " events (budget " << event_budget << ")";
      EXPECT_LE(sim.events().size(), event_budget);
      int impacts = 0;
      for (const SimulationEvent& e : sim.events()) impacts += e.kind == SimulationEvent::Kind::impact;
      EXPECT_LE(impacts, bounces);
      EXPECT_GE(impacts, 2);
      // never a contact made and lifted off at one instant
      for (std::size_t i = 0; i < sim.events().size(); ++i)
        for (std::size_t j = i + 1; j < sim.events().size(); ++j) {
          const SimulationEvent &a = sim.events()[i], &b = sim.events()[j];
          if (a.kind == SimulationEvent::Kind::contact && b.kind == SimulationEvent::Kind::lift_off && a.time == b.time)
            EXPECT_NE(a.features, b.features) << "made and lifted off at t = " << a.time;
        }
      ++cases;
    }
  EXPECT_EQ(cases, 5);
}

// Turning on a vertex (session 56; docs/simulation.md, "Turning on a vertex"). After the needle's
// bounce series the face turns on one of the bump's top vertices with the other one (and the
// bump's bottom vertices) on the face's line within about the chord deviation; those pairs are
// now certified apart relative to the held contact (their gap is the held one's plus a function
// of the angle, bounded exactly over each step: src/simulation/companion_watch.hpp), so the steps
// are the integrator's instead of chords of deviation delta / 2. The second case turns towards
// the other vertex: a bar dropped tilted on a table 6 mm wide lands on the table's left corner,
// turns on it and strikes the right one (then rocks between them and rests): that impact must be
// found as the chords find it. Oracles: the same run with that certification off (the chords, as
// before) — the same events (kinds, features; times to the integrator's accuracy 1e-9 relative
// per step, accumulated over the chords' run's steps at most) and end state; the exact overlap
// predicate at every state of the certified run (the part never overlaps the fixed one); fewer
// steps.
TEST(SimulationPlanarNeedle, TurningOnAVertexIsCertifiedRelativeToTheHeldContact) {
  NeedleCase needle;
  const std::string tip = R"({ "hipair": 1, "name": "tip", "units": { "length": "mm", "angle": "rad" },
    "parts": [
      { "name": "table", "motion": "fixed", "loops": [ { "label": "table", "start": [-3, -2], "edges": [ { "line_to": [3, -2] },
        { "line_to": [3, 0] }, { "line_to": [-3, 0] }, { "line_to": [-3, -2] } ] } ] },
      { "name": "bar", "motion": { "planar": { "pivot": [0, 0] } }, "initial": { "x": 0, "y": 1.6, "angle": 0.05 },
        "dynamics": { "mass": 0.008, "moment_of_inertia": 0.07 },
        "loops": [ { "label": "bar", "start": [-5, -1], "edges": [ { "line_to": [5, -1], "label": "bar bottom" },
          { "line_to": [5, 1] }, { "line_to": [-5, 1] }, { "line_to": [-5, -1] } ] } ] } ],
    "pairs": [ { "parts": ["table", "bar"], "restitution": 0.3 } ],
    "simulation": { "units": { "time": "s", "force": "N" }, "gravity": [0, -9810] } })";
  struct Run {
    std::string name, json;
    double t_end;
    std::size_t ratio;   // at least this many times fewer steps
  };
  // the needle to 0.035 s: 1.3 ms of turning (the chords' run takes about 3 800 steps for it)
  const Run runs[] = {{"needle 1e-8 mm", needle.json(), 0.035, 50}, {"tip", tip, 0.05, 2}};
  for (const Run& r : runs) {
    SCOPED_TRACE(r.name);
    const Model model = read_model(r.json);
    auto run = [&](bool companions, std::size_t& certified) {
      simulation::companion_watch() = companions;
      const std::size_t before = simulation::companion_steps();
      PlanarSimulation sim = PlanarSimulation::create(model);
      const Part& part = model.parts[1];
      while (sim.state().time < r.t_end) {
        sim.step(r.t_end);
        if (!companions) continue;   // the certified run's states
        const SlicedConfiguration& q = sim.state().configuration;
        const Rational den = 1 + q.angle.t * q.angle.t;
        const Rational cs = q.angle.half_turn ? Rational(-1) : Rational((1 - q.angle.t * q.angle.t) / den);
        const Rational sn = q.angle.half_turn ? Rational(0) : Rational(2 * q.angle.t / den);
        EXPECT_NE(part_overlap(model.parts[0], Placement{}, part, placement_about(part.motion.pivot, cs, sn, Point{q.x, q.y}))
                      .relation,
                  PartRelation::overlapping)
            << "t = " << sim.state().time;
      }
      certified = simulation::companion_steps() - before;
      simulation::companion_watch() = true;
      return sim;
    };
    std::size_t certified_on = 0, certified_off = 0;
    const PlanarSimulation on = run(true, certified_on), off = run(false, certified_off);
    EXPECT_EQ(certified_off, 0u);
    EXPECT_GT(certified_on, 0u);
    ASSERT_EQ(on.events().size(), off.events().size());
    const double accuracy = 1e-9 * static_cast<double>(off.steps());
    for (std::size_t i = 0; i < on.events().size(); ++i) {
      const SimulationEvent &a = on.events()[i], &b = off.events()[i];
      EXPECT_EQ(a.kind, b.kind) << i;
      EXPECT_EQ(a.features, b.features) << i;
      EXPECT_NEAR(a.time, b.time, accuracy * b.time) << i;
    }
    const PlanarState &a = on.state(), &b = off.state();
    EXPECT_NEAR(a.x, b.x, accuracy * 10);   // the parts' size: 10 mm
    EXPECT_NEAR(a.y, b.y, accuracy * 10);
    EXPECT_NEAR(a.angle, b.angle, accuracy);
    EXPECT_LE(on.steps() * r.ratio, off.steps()) << on.steps() << " steps against " << off.steps();
  }
}

}  // namespace
}  // namespace hipair
