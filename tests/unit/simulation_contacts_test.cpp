// Simultaneous contacts in the simulator (docs/simulation.md, "Several contacts at once"):
// the contact LCP solvers against each other and against the complementarity conditions on
// generated problems, stacked blocks whose two sustained contacts (two pairs) carry the
// closed-form static loads, simultaneous symmetric impacts solved in one impulse problem,
// energy conservation over >= 100 elastic (simultaneous) impacts, every state certainly
// outside blocked space (exact point location), and a pawl's wedge held by two contacts of
// one pair.
#include <hipair/cspace.hpp>
#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include "simulation/lcp.hpp"
#include "test_paths.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
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
// The bundled ratchet with the wheel driven by `torque` (N mm), at `accuracy`, within 5000 steps.
Simulation ratchet_driven(double torque, double accuracy) {
  Model model = example("ratchet.json");
  model.parts[0].dynamics->torque = Rational(torque);
  SimulationOptions options;
  options.accuracy = accuracy;
  options.max_steps = 5000;
  return Simulation::create(model, options);
}

TEST(SimulationContacts, RatchetDrivenClockwiseHoldsInTheWedgeWithBothContacts) {
  // -50 N mm rests on the nose face alone, rightly (session 37: RatchetDrivenClockwiseRestsInStaticBalance)
  for (double torque : {-5.0, -12.5, -20.0})
    for (double accuracy : {1e-3, 1e-6, 1e-9}) {
      Simulation s = ratchet_driven(torque, accuracy);
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

namespace hipair {
namespace {

// Session 37: the ratchet driven clockwise at rest, checked against an independent static
// balance. From the kernels' contact frames at the final state (CSpace::contact_frame: world
// point p and unit normal n of each held feature pair, n oriented as the simulator's frame:
// the force on the second part, the pawl, is N n + f t, t = (-n_y, n_x)) the moments about
// the two pivots must balance the wheel's torque and the pawl's spring:
//   T_wheel - sum (p - c_wheel) x (N n + f t) = 0,  -k (phi - rest) + sum (p - c_pawl) x (N n + f t) = 0.
// Two held contacts: the 2x2 system gives both normal forces N (the friction forces f
// reported by the simulator entered as known terms); one contact: it gives N and f. The
// solution must equal the simulator's forces, be compressive, and lie in the Coulomb cone.
struct Balance {
  std::vector<double> normal, friction;   // solved (one contact: both unknown)
  Eigen::Matrix2d normals;                // two contacts: the normal forces' moments (wheel, pawl)
  double spring = 0;                      // the pawl spring's moment
  int corner = -1;                        // two contacts: the index of the nose's corner
};

double mid(const CertifiedRange& r) { return 0.5 * (r.lower + r.upper); }

Balance static_balance(const Simulation& s) {
  const Model& model = s.model();
  const std::vector<SimulationContact> held = s.contacts();
  const CSpace& space = *s.spaces().at(0);
  const double theta = s.state().position[0], phi = s.state().position[1];
  auto coordinate = [&](const std::string& part) {
    PartCoordinate c;
    c.value = Rational(std::tan((part == "wheel" ? theta : phi) / 2));
    return c;
  };
  const Point& cw = model.parts[0].motion.pivot;
  const Point& cp = model.parts[1].motion.pivot;
  // per contact: the moments of a unit normal and a unit tangent force on the pawl about the
  // wheel's pivot (with minus: the reaction on the wheel) and about the pawl's
  std::vector<std::array<double, 4>> m;
  Balance out;
  for (const SimulationContact& c : held) {
    for (const std::string& f : c.features)
      if (f.find("pawl corner of nose face and nose underside") != std::string::npos) out.corner = static_cast<int>(&c - held.data());
    const std::size_t curve = space.edge(c.edge).curves.at(0);
    std::optional<Contact> frame = space.contact_frame(FeatureId(curve), coordinate(space.x_part()), coordinate(space.y_part()));
    EXPECT_TRUE(frame.has_value());
    if (!frame) return {};
    const double px = mid(frame->point_range[0]), py = mid(frame->point_range[1]);
    const double nx = mid(frame->normal[0]), ny = mid(frame->normal[1]), tx = -ny, ty = nx;
    auto moment = [](double ox, double oy, double x, double y, double fx, double fy) { return (x - ox) * fy - (y - oy) * fx; };
    const double wx = cw.x.get_d(), wy = cw.y.get_d(), qx = cp.x.get_d(), qy = cp.y.get_d();
    m.push_back({-moment(wx, wy, px, py, nx, ny), -moment(wx, wy, px, py, tx, ty), moment(qx, qy, px, py, nx, ny),
                 moment(qx, qy, px, py, tx, ty)});
  }
  const double torque = model.parts[0].dynamics->torque->get_d();
  const Spring& spring = *model.parts[1].dynamics->torsional_spring;
  const double load = -spring.stiffness.get_d() * (phi - spring.rest.get_d());
  Eigen::Matrix2d A;
  Eigen::Vector2d b(-torque, -load);
  out.spring = load;
  if (held.size() == 2) {
    for (int k = 0; k < 2; ++k) {
      A(0, k) = m[k][0];
      A(1, k) = m[k][2];
      b(0) -= m[k][1] * held[k].friction_force;
      b(1) -= m[k][3] * held[k].friction_force;
    }
    out.normals = A;
    Eigen::Vector2d x = A.fullPivLu().solve(b);
    out.normal = {x(0), x(1)};
    out.friction = {held[0].friction_force, held[1].friction_force};
  } else if (held.size() == 1) {
    A << m[0][0], m[0][1], m[0][2], m[0][3];
    Eigen::Vector2d x = A.fullPivLu().solve(b);
    out.normal = {x(0)};
    out.friction = {x(1)};
  }
  return out;
}

// Generated clockwise torques -5...-80 N mm at accuracies 1e-3, 1e-6, 1e-9: the run reaches
// t_end at rest, held by the wedge's two contacts (the nose face and the nose's corner) or,
// where the tooth comes to rest sticking on the nose face short of the wedge (-50 N mm, ...),
// by that contact alone; either way the forces are the independent static balance's.
TEST(SimulationContacts, RatchetDrivenClockwiseRestsInStaticBalance) {
  // the wedge's balance at its vertex (from the first run, -5 N mm, held there by both
  // contacts): the normal forces are linear in the torque, N(T) = A^-1 (-T, -spring); the
  // corner's falls to zero at T* (about -45.9 N mm), beyond which the wedge could hold only by
  // pulling on the corner: the tooth then rests on the nose face alone, held by friction
  std::optional<Balance> vertex;
  std::mt19937 rng(37);
  std::vector<double> torques{-5, -12.5, -20, -50, -80};
  for (int i = 0; i < 3; ++i) torques.push_back(-std::round(std::uniform_real_distribution<double>(5, 80)(rng) * 8) / 8);
  for (double torque : torques)
    for (double accuracy : {1e-3, 1e-6, 1e-9}) {
      Simulation s = ratchet_driven(torque, accuracy);
      ASSERT_NO_THROW(s.run_until(0.1)) << torque << " " << accuracy;
      // at rest (within 1e-4 of the accuracy: a sticking state at 1e-3 keeps 2.5e-8 rad/s)
      EXPECT_NEAR(s.state().velocity[0], 0, 1e-9 + 1e-4 * accuracy) << torque << " " << accuracy;
      EXPECT_NEAR(s.state().velocity[1], 0, 1e-9 + 1e-4 * accuracy) << torque << " " << accuracy;
      const std::vector<SimulationContact> held = s.contacts();
      ASSERT_GE(held.size(), 1u) << torque << " " << accuracy;
      ASSERT_LE(held.size(), 2u) << torque << " " << accuracy;
      const Balance balance = static_balance(s);
      ASSERT_EQ(balance.normal.size(), held.size());
      if (!vertex) {
        ASSERT_EQ(held.size(), 2u);
        ASSERT_GE(balance.corner, 0);
        vertex = balance;
      }
      // which contacts hold: both where the vertex balance's corner force is positive, the
      // nose face alone where it is negative (a margin of 1e-3 of the force scale)
      const Eigen::Vector2d n = vertex->normals.fullPivLu().solve(Eigen::Vector2d(-torque, -vertex->spring));
      const double corner = n(vertex->corner);
      if (corner > 1e-4) EXPECT_EQ(held.size(), 2u) << torque << " " << accuracy << " corner force " << corner;
      if (corner < -1e-4) EXPECT_EQ(held.size(), 1u) << torque << " " << accuracy << " corner force " << corner;
      // the simulator's forces balance the loads at its own rows, which are held to the
      // accuracy's projection; the frames here are the kernels': agreement to 1e-6 of the
      // load scale plus the accuracy (relative)
      const double scale = std::abs(torque) / 10;   // N: the torque over the ~10 mm lever
      const double tolerance = (1e-6 + accuracy) * scale;
      const double mu = s.model().pairs[0].friction->get_d();
      for (std::size_t k = 0; k < held.size(); ++k) {
        EXPECT_TRUE(held[k].sticking) << torque << " " << accuracy;
        EXPECT_GT(balance.normal[k], 0) << torque << " " << accuracy;
        EXPECT_NEAR(held[k].normal_force, balance.normal[k], tolerance) << torque << " " << accuracy << " " << k;
        EXPECT_NEAR(held[k].friction_force, balance.friction[k], tolerance) << torque << " " << accuracy << " " << k;
        EXPECT_LE(std::abs(balance.friction[k]), mu * balance.normal[k] + tolerance) << torque << " " << accuracy;
      }
      // the two-contact rest is the wedge's vertex; a single contact is the nose face
      if (held.size() == 2) EXPECT_NEAR(s.state().position[0], -0.0088977622, 1e-8) << torque << " " << accuracy;
      std::cout << "torque " << torque << " accuracy " << accuracy << ": " << held.size() << " contacts, wheel "
                << s.state().position[0] << ", N";
      for (std::size_t k = 0; k < held.size(); ++k)
        std::cout << " " << held[k].normal_force << " (balance " << balance.normal[k] << "), f " << held[k].friction_force
                  << " (" << balance.friction[k] << ")";
      double worst = 0;   // the largest difference relative to the load scale
      for (std::size_t k = 0; k < held.size(); ++k)
        worst = std::max({worst, std::abs(held[k].normal_force - balance.normal[k]) / scale,
                          std::abs(held[k].friction_force - balance.friction[k]) / scale});
      std::cout << "; worst difference " << worst << " of the load scale\n";
    }
}

}  // namespace
}  // namespace hipair
