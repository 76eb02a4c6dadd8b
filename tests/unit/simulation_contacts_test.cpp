// Simultaneous contacts in the simulator (docs/simulation.md, "Several contacts at once"):
// the contact LCP solvers against each other and against the complementarity conditions on
// generated problems, stacked blocks whose two sustained contacts (two pairs) carry the
// closed-form static loads, simultaneous symmetric impacts solved in one impulse problem,
// energy conservation over >= 100 elastic (simultaneous) impacts, every state certainly
// outside blocked space (exact point location), and a pawl's wedge held by two contacts of
// one pair.
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include "simulation/lcp.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>

namespace hipair {
namespace {

Model example(const std::string& name, const ReadOptions& options = {}) {
  return read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / name, options);
}

std::size_t count(const Simulation& s, SimulationEvent::Kind kind) {
  std::size_t n = 0;
  for (const auto& e : s.events()) n += e.kind == kind;
  return n;
}

// ------------------------------------------------------------------ the LCP solvers

// Generated problems: A = B B^T (+ a diagonal: a P-matrix, unique solution) of sizes 1..9,
// b uniform in [-1, 1]. Enumeration and Lemke both satisfy the conditions (checked directly
// here, with the tolerance lcp_tolerance derives from the data), and agree on lambda where it
// is unique; where A is only semidefinite (rank-deficient B) w = A lambda + b is unique.
TEST(SimulationLcp, EnumerationAndLemkeSolveGeneratedProblems) {
  std::mt19937 random(20261125);
  std::uniform_real_distribution<double> uniform(-1, 1);
  int solved_semidefinite = 0;
  for (int trial = 0; trial < 400; ++trial) {
    int m = 1 + trial % 9;
    bool definite = trial % 2 == 0;
    int rank = definite ? m : std::max(1, m - 1 - trial % 3);
    Eigen::MatrixXd B(m, rank);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < rank; ++j) B(i, j) = uniform(random);
    Eigen::MatrixXd A = B * B.transpose();
    if (definite) A += 0.1 * Eigen::MatrixXd::Identity(m, m);
    Eigen::VectorXd b(m);
    for (int i = 0; i < m; ++i) b(i) = uniform(random);
    if (!definite) {
      // feasible by construction: b = w0 - A l0 with l0, w0 >= 0 complementary
      Eigen::VectorXd l0 = Eigen::VectorXd::Zero(m), w0 = Eigen::VectorXd::Zero(m);
      for (int i = 0; i < m; ++i) (i % 2 ? l0(i) : w0(i)) = std::abs(uniform(random));
      b = w0 - A * l0;
    }
    auto e = simulation::solve_lcp_enumeration(A, b);
    auto l = simulation::solve_lcp_lemke(A, b);
    ASSERT_TRUE(e.solved) << trial;
    ASSERT_TRUE(l.solved) << trial;
    double tol = 1e3 * simulation::lcp_tolerance(A, b);
    for (const auto* s : {&e, &l}) {
      EXPECT_GE(s->lambda.minCoeff(), 0);
      EXPECT_GE(s->w.minCoeff(), -tol) << trial;
      EXPECT_LE(std::abs(s->lambda.dot(s->w)), tol * (1 + s->lambda.cwiseAbs().sum())) << trial;
    }
    if (definite) {
      EXPECT_LE((e.lambda - l.lambda).cwiseAbs().maxCoeff(), tol * (1 + e.lambda.cwiseAbs().maxCoeff())) << trial;
    } else {
      ++solved_semidefinite;
    }
    EXPECT_LE((e.w - l.w).cwiseAbs().maxCoeff(), tol * (1 + e.lambda.cwiseAbs().maxCoeff())) << trial;
  }
  EXPECT_EQ(solved_semidefinite, 200);
}

// A redundant pair of equal contacts (A singular): the enumeration's minimum-norm multipliers
// share the load equally.
TEST(SimulationLcp, RedundantContactsShareTheLoad) {
  Eigen::MatrixXd A(2, 2);
  A << 1, 1, 1, 1;
  Eigen::VectorXd b(2);
  b << -3, -3;
  auto s = simulation::solve_lcp(A, b);
  ASSERT_TRUE(s.solved);
  EXPECT_NEAR(s.lambda(0), 1.5, 1e-12);
  EXPECT_NEAR(s.lambda(1), 1.5, 1e-12);
}

// ------------------------------------------------------------------ stacked blocks

// Block a (mass ma) stands on block b (mass mb) which stands on the ground; both translate
// vertically, gravity 9810 mm/s^2. Each starts 1 mm above its support: b lands first, then a
// lands on b (one impact problem with b's sustained ground contact), then both rest. The
// forces: a on b = ma g, b on the ground = (ma + mb) g (the constraints' rows are +-1 per mm:
// the multipliers are the forces in N).
std::string stack_model(double ma, double mb) {
  return R"({"hipair": 1, "name": "stack", "parts": [
    {"name": "a", "motion": {"translation": {"direction": [0, 1], "limits": [-5, 20]}}, "initial": {"offset": 2},
     "dynamics": {"mass": )" + std::to_string(ma) + R"(},
     "loops": [{"start": [0, 10], "edges": [{"line_to": [8, 14]}, {"line_to": [8, 20]}, {"line_to": [-8, 20]},
                {"line_to": [-8, 14]}, {"line_to": [0, 10]}]}]},
    {"name": "b", "motion": {"translation": {"direction": [0, 1], "limits": [-5, 20]}}, "initial": {"offset": 1},
     "dynamics": {"mass": )" + std::to_string(mb) + R"(},
     "loops": [{"start": [0, 0], "edges": [{"line_to": [10, 5]}, {"line_to": [10, 10], "label": "b top right"},
                {"line_to": [-10, 10], "label": "b top"}, {"line_to": [-10, 5]}, {"line_to": [0, 0]}]}]},
    {"name": "ground", "motion": "fixed",
     "loops": [{"start": [-20, -5], "edges": [{"line_to": [20, -5]}, {"line_to": [20, 0], "label": "ground top"},
                {"line_to": [-20, 0]}, {"line_to": [-20, -5]}]}]}],
    "pairs": [{"parts": ["a", "b"], "restitution": 0}, {"parts": ["b", "ground"], "restitution": 0}],
    "simulation": {"gravity": [0, -9810], "accuracy": 1e-10}})";
}

// Exact point location of a state of translating parts (offsets are exact doubles).
Location locate_state(const Simulation& s, std::size_t pair) {
  const CSpace& space = *s.spaces().at(pair);
  auto coordinate = [&](const std::string& part) {
    PartCoordinate c;
    c.kind = PartCoordinate::Kind::offset;
    c.value = Rational(s.state().position[*s.model().find_part(part)]);
    return c;
  };
  if (space.dimension() == 1) return space.locate(coordinate(space.x_part()));
  return space.locate(coordinate(space.x_part()), coordinate(space.y_part()));
}

TEST(SimulationContacts, StackedBlocksCarryTheClosedFormStaticLoads) {
  const double g = 9.81;   // N/kg
  for (auto [ma, mb] : {std::pair{0.2, 0.3}, std::pair{0.05, 1.5}, std::pair{1.0, 0.1}}) {
    Simulation s = Simulation::create(read_model(stack_model(ma, mb)));
    int located = 0;
    while (s.state().time < 0.1) {
      s.step();
      for (std::size_t pair = 0; pair < 2; ++pair) {
        Location where = locate_state(s, pair);
        ASSERT_NE(where.kind, Location::Kind::blocked) << "pair " << pair << " t " << s.state().time;
        ++located;
      }
    }
    EXPECT_GE(located, 8);
    EXPECT_EQ(count(s, SimulationEvent::Kind::impact), 2u);
    EXPECT_EQ(count(s, SimulationEvent::Kind::lift_off), 0u);
    // b landed after sqrt(2 mm / g), a 1 mm above it then
    EXPECT_NEAR(s.events().front().time, std::sqrt(2 * 1.0 / 9810), 1e-9);
    std::vector<SimulationContact> contacts = s.contacts();
    ASSERT_EQ(contacts.size(), 2u);
    for (const SimulationContact& c : contacts) {
      double expected = c.pair == 0 ? ma * g : (ma + mb) * g;
      // the multipliers solve a 2x2 system with entries of order 1 / mass: relative round-off
      // of a few ulps times its condition number (< 1e3 for these masses)
      EXPECT_NEAR(c.force, expected, 1e-10 * expected) << "pair " << c.pair;
    }
    // at rest on their supports (accuracy 1e-10 mm)
    EXPECT_NEAR(s.state().position[0], 0, 1e-9);
    EXPECT_NEAR(s.state().position[1], 0, 1e-9);
    EXPECT_NEAR(s.state().velocity[0], 0, 1e-9);
    EXPECT_NEAR(s.state().velocity[1], 0, 1e-9);
  }
}

// Lifting the upper block off by an upward force larger than its weight: the LCP leaves that
// contact without force (a lift-off) and keeps the lower one, with load mb g.
TEST(SimulationContacts, AContactWhoseForceWouldTurnNegativeLiftsOff) {
  std::string text = stack_model(0.2, 0.3);
  // a constant upward force on a of 3 N > 0.2 * 9.81 N, from the start
  std::string with_force = text;
  with_force.replace(with_force.find(R"("mass": 0.200000)"), 16, R"("mass": 0.200000, "force": [0, 3])");
  Simulation s = Simulation::create(read_model(with_force));
  s.run_until(0.05);
  // b lands; a rises away and never touches b
  std::size_t a_contacts = 0;
  for (const auto& e : s.events()) a_contacts += e.pair == 0;
  EXPECT_EQ(a_contacts, 0u);
  std::vector<SimulationContact> contacts = s.contacts();
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_NEAR(contacts[0].force, 0.3 * 9.81, 1e-10 * 3);
}

// ------------------------------------------------------------------ simultaneous impacts

// l and r move towards c at equal speeds from equal gaps: both impacts happen at once, and one
// impulse problem gives the symmetric answer for any masses: c stays at rest, l and r leave
// with -e times their speed, impulses m (1 + e) v. (One pair at a time would set c moving.)
std::string three_blocks(double e, double mc, bool walls) {
  std::string pairs = R"([{"parts": ["l", "c"], "restitution": )" + std::to_string(e) +
                      R"(}, {"parts": ["c", "r"], "restitution": )" + std::to_string(e) + "}";
  if (walls)
    pairs += R"(, {"parts": ["l", "walls"], "restitution": )" + std::to_string(e) +
             R"(}, {"parts": ["r", "walls"], "restitution": )" + std::to_string(e) + "}";
  pairs += "]";
  return R"({"hipair": 1, "name": "three", "parts": [
    {"name": "l", "motion": {"translation": {"direction": [1, 0], "limits": [-20, 20]}},
     "dynamics": {"mass": 0.1},
     "loops": [{"start": [-35, 0], "edges": [{"line_to": [-30, -5]}, {"line_to": [-20, -5]}, {"line_to": [-15, 0]},
                {"line_to": [-20, 5]}, {"line_to": [-30, 5]}, {"line_to": [-35, 0]}]}]},
    {"name": "c", "motion": {"translation": {"direction": [1, 0], "limits": [-20, 20]}},
     "dynamics": {"mass": )" + std::to_string(mc) + R"(},
     "loops": [{"start": [-10, -5], "edges": [{"line_to": [10, -5]}, {"line_to": [10, 5]}, {"line_to": [-10, 5]},
                {"line_to": [-10, -5]}]}]},
    {"name": "r", "motion": {"translation": {"direction": [1, 0], "limits": [-20, 20]}},
     "dynamics": {"mass": 0.1},
     "loops": [{"start": [35, 0], "edges": [{"line_to": [30, 5]}, {"line_to": [20, 5]}, {"line_to": [15, 0]},
                {"line_to": [20, -5]}, {"line_to": [30, -5]}, {"line_to": [35, 0]}]}]},
    {"name": "walls", "motion": "fixed",
     "loops": [{"start": [-45, -10], "edges": [{"line_to": [-40, -10]}, {"line_to": [-40, 10]}, {"line_to": [-45, 10]},
                {"line_to": [-45, -10]}]},
               {"start": [40, -10], "edges": [{"line_to": [45, -10]}, {"line_to": [45, 10]}, {"line_to": [40, 10]},
                {"line_to": [40, -10]}]}]}],
    "pairs": )" + pairs + R"(,
    "simulation": {"velocities": {"l": 10, "r": -10}, "accuracy": 1e-10}})";
}

TEST(SimulationContacts, SimultaneousSymmetricImpactsInOneImpulseProblem) {
  for (double e : {0.0, 0.5, 1.0})
    for (double mc : {0.1, 0.3, 2.0}) {
      Simulation s = Simulation::create(read_model(three_blocks(e, mc, false)));
      while (s.events().empty() && s.state().time < 1) s.step();
      std::vector<SimulationEvent> impacts;
      for (const auto& event : s.events())
        if (event.kind == SimulationEvent::Kind::impact) impacts.push_back(event);
      ASSERT_EQ(impacts.size(), 2u);
      const SimulationEvent& a = impacts[0];
      const SimulationEvent& b = impacts[1];
      ASSERT_EQ(a.kind, SimulationEvent::Kind::impact);
      ASSERT_EQ(b.kind, SimulationEvent::Kind::impact);
      EXPECT_NE(a.pair, b.pair);
      EXPECT_EQ(a.time, b.time);
      EXPECT_NEAR(a.time, 0.5, 1e-9);   // 5 mm at 10 mm/s
      // impulses m (1 + e) v = 0.1 kg (1 + e) 10 mm/s = (1 + e) 1e-3 N s; the LCP's round-off
      // is relative 1e-15 (2x2, well conditioned): 1e-12 relative
      double impulse = (1 + e) * 1e-3;
      EXPECT_NEAR(a.impulse, impulse, 1e-12 * impulse) << e << " " << mc;
      EXPECT_NEAR(b.impulse, impulse, 1e-12 * impulse) << e << " " << mc;
      EXPECT_NEAR(s.state().velocity[1], 0, 1e-12);
      if (e > 0) {
        EXPECT_NEAR(s.state().velocity[0], -10 * e, 1e-11);
        EXPECT_NEAR(s.state().velocity[2], 10 * e, 1e-11);
      }
    }
}

// Perfectly elastic, no damping, between two walls: 100+ impacts (pairs of simultaneous
// ones), the kinetic energy 2 * 1/2 0.1 kg (10 mm/s)^2 = 10 kg mm^2/s^2 = 0.01 N mm conserved: each impact's
// impulse is a 2x2 solve, relative round-off ~1e-15 per impact; with no force acting, the
// integrator's error (tolerance 1e-10) does not enter. Bound: 1e-12 relative.
TEST(SimulationContacts, ElasticSimultaneousImpactsConserveEnergy) {
  Simulation s = Simulation::create(read_model(three_blocks(1.0, 0.3, true)));
  double e0 = s.energy();
  EXPECT_NEAR(e0, 1e-2, 1e-17);
  s.run_until(52);
  EXPECT_GE(count(s, SimulationEvent::Kind::impact), 100u);
  EXPECT_NEAR(s.energy(), e0, 1e-12 * e0);
  EXPECT_NEAR(s.state().velocity[1], 0, 1e-12);
  for (std::size_t pair = 0; pair < 4; ++pair) EXPECT_NE(locate_state(s, pair).kind, Location::Kind::blocked);
}

// ------------------------------------------------------------------ two contacts of one pair

// The ratchet driven clockwise (-20 N mm): the tooth reaches the pawl's nose face, slides into
// the wedge between the nose face and the nose's corner, and the contact changes there at the
// C-space vertex where the two curves meet (taken up at the vertex: one impact problem over
// both). Before, the pair could hold one contact only, the new one was looked for by the free
// query after moving off the first, and the run made no progress (not finished in 60 s). The
// ratchet holds: the wheel stays at the wedge (within 1e-3 rad) while the pawl chatters.
TEST(SimulationContacts, RatchetHoldsAtTheWedgeOfItsPawl) {
  Model model = example("ratchet.json");
  model.parts[0].dynamics->torque = Rational(-20);
  Simulation s = Simulation::create(model);
  // every state certainly free: the certified point query (first_crossing of a motion that
  // stands still at the state's exact double angles) finds the pair in a free cell
  auto certainly_free = [&]() {
    const CSpace& space = *s.spaces().at(0);
    MotionPath still;
    still.x.kind = AxisPath::Kind::angle;
    still.x.coefficients = {Rational(s.state().position[*s.model().find_part(space.x_part())])};
    still.y.kind = AxisPath::Kind::angle;
    still.y.coefficients = {Rational(s.state().position[*s.model().find_part(space.y_part())])};
    return space.first_crossing(still).status == CrossingStatus::none;
  };
  int checked = 0;
  while (s.state().time < 0.05) {
    s.step();
    EXPECT_GT(s.state().position[0], -0.0089 - 1e-3) << s.state().time;
    EXPECT_TRUE(certainly_free()) << s.state().time;
    ++checked;
  }
  EXPECT_GT(checked, 50);
  bool nose_face = false, nose_corner = false;
  for (const auto& e : s.events()) {
    if (e.kind != SimulationEvent::Kind::contact && e.kind != SimulationEvent::Kind::impact) continue;
    for (const auto& f : e.features) {
      nose_face = nose_face || f.find("pawl nose face") != std::string::npos;
      nose_corner = nose_corner || f.find("pawl corner of nose face and nose underside") != std::string::npos;
    }
  }
  EXPECT_TRUE(nose_face);
  EXPECT_TRUE(nose_corner);
}


// Session 36: the ratchet driven clockwise holds in its pawl's wedge with both contacts held.
// Before, at accuracies 1e-3 and 1e-6 (and -5 N mm at all three) it stopped at 0.026 s with
// "cannot be moved off its contact (a jammed contact change)": the step's cut at the wedge's
// C-space vertex came up to the contact's slack (1e-9 chart units) past the vertex, 2.6e-8 inside
// the nose-face contact, and the old contact's row failed there.
TEST(SimulationContacts, RatchetDrivenClockwiseHoldsInTheWedgeWithBothContacts) {
  // not yet: -50 N mm reaches t_end with the nose-face contact alone held (session 36)
  for (double torque : {-5.0, -12.5, -20.0})
    for (double accuracy : {1e-3, 1e-6, 1e-9}) {
      Model model = example("ratchet.json");
      model.parts[0].dynamics->torque = Rational(torque);
      SimulationOptions options;
      options.accuracy = accuracy;
      options.max_steps = 5000;
      Simulation s = Simulation::create(model, options);
      ASSERT_NO_THROW(s.run_until(0.1)) << torque << " " << accuracy;
      EXPECT_GE(s.state().time, 0.1);
      std::vector<SimulationContact> held = s.contacts();
      ASSERT_EQ(held.size(), 2u) << torque << " " << accuracy;
      bool face = false, corner = false;
      for (const SimulationContact& c : held) {
        EXPECT_GT(c.force, 0) << torque << " " << accuracy;
        for (const auto& f : c.features) {
          face = face || f.find("pawl nose face") != std::string::npos;
          corner = corner || f.find("pawl corner of nose face and nose underside") != std::string::npos;
        }
      }
      EXPECT_TRUE(face && corner) << torque << " " << accuracy;
      // at the wedge's vertex (wheel angle -0.0088977622 rad), at rest
      EXPECT_NEAR(s.state().position[0], -0.0088977622, 1e-8) << torque << " " << accuracy;
      EXPECT_NEAR(s.state().velocity[0], 0, 1e-9) << torque << " " << accuracy;
    }
}

}  // namespace
}  // namespace hipair
