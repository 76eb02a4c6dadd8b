// The simulator's right-hand-side storage kept between calls (src/simulation/kept_scratch.hpp,
// switch simulation::kept_scratch(); src/simulation/friction.hpp, BilateralWork). Two oracles:
// - the bilateral solve's `work` form, one BilateralWork and one FrictionalSolution used for a
//   sequence of generated problems of changing sizes (contacts 1-5, coordinates 1-6, driven
//   coordinates, each contact frictionless / sticking / slipping either way, with or without the
//   frictionless fallback), against the value form with fresh storage on each problem: every
//   double bit for bit;
// - whole simulations run side by side with the switch on and off (tests/unit/
//   simulation_side_by_side.hpp): every state and event bit for bit, on the example models with
//   frictional and frictionless pairs held together (the escapement, whose banking pins have no
//   friction; the ratchet, driven either way; a cam with a follower; the scotch yoke), and on
//   the escapement with its pairs' friction switched on and off in every mixed way.
#include "simulation/friction.hpp"
#include "simulation/kept_scratch.hpp"
#include "eigen_bits.hpp"
#include "simulation_side_by_side.hpp"

#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "test_paths.hpp"

namespace hipair {
namespace {

using test::same_bits;

TEST(SimulationKeptScratch, BilateralWorkEqualsFreshSolves) {
  std::mt19937_64 random(20261203);
  std::uniform_real_distribution<double> unit(-1, 1);
  simulation::BilateralWork work;
  simulation::FrictionalSolution kept;
  int sticking = 0, slipping = 0, shrunk = 0;
  Eigen::Index last_m = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const auto m = static_cast<Eigen::Index>(1 + random() % 5), n = static_cast<Eigen::Index>(1 + random() % 6);
    if (m < last_m) ++shrunk;
    last_m = m;
    Eigen::MatrixXd G(m, n);
    Eigen::VectorXd minv(n), a0(n), h(m);
    for (Eigen::Index i = 0; i < n; ++i) {
      minv(i) = random() % 5 == 0 ? 0.0 : 0.1 + unit(random) * unit(random) + 1;   // driven: 0
      a0(i) = 10 * unit(random);
    }
    for (Eigen::Index k = 0; k < m; ++k) {
      h(k) = unit(random);
      for (Eigen::Index i = 0; i < n; ++i) G(k, i) = random() % 4 == 0 ? 0.0 : unit(random);
    }
    std::vector<simulation::Friction> friction(static_cast<std::size_t>(m));
    std::vector<int> state(static_cast<std::size_t>(m), simulation::frictionless);
    for (std::size_t k = 0; k < friction.size(); ++k) {
      simulation::Friction& c = friction[k];
      c.on = random() % 4 != 0;
      c.T = Eigen::VectorXd(n);
      for (Eigen::Index i = 0; i < n; ++i) c.T(i) = unit(random);
      c.s = 0.5 + std::abs(unit(random));
      c.mu_static = 0.3 + 0.2 * std::abs(unit(random));
      c.mu_kinetic = 0.2 * std::abs(unit(random));
      c.bias = random() % 3 == 0 ? unit(random) : 0.0;
      static constexpr int states[4] = {simulation::stick, simulation::slip_positive, simulation::slip_negative,
                                        simulation::frictionless};
      state[k] = states[random() % 4];
      if (c.on && state[k] == simulation::stick) ++sticking;
      if (c.on && (state[k] == simulation::slip_positive || state[k] == simulation::slip_negative)) ++slipping;
    }
    const bool plain = random() % 2 == 0;
    const simulation::FrictionalSolution fresh = simulation::solve_bilateral(G, minv, a0, h, friction, state, plain);
    simulation::solve_bilateral(G, minv, a0, h, friction, state, plain, work, kept);
    const std::string at = "trial " + std::to_string(trial) + " (" + std::to_string(m) + " x " + std::to_string(n) + ")";
    ASSERT_EQ(kept.solved, fresh.solved) << at;
    ASSERT_EQ(kept.state, fresh.state) << at;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(kept.tolerance), std::bit_cast<std::uint64_t>(fresh.tolerance)) << at;
    ASSERT_TRUE(same_bits(kept.lambda, fresh.lambda)) << at;
    ASSERT_TRUE(same_bits(kept.w, fresh.w)) << at;
    ASSERT_TRUE(same_bits(kept.x, fresh.x)) << at;
    ASSERT_TRUE(same_bits(kept.f, fresh.f)) << at;
  }
  std::printf("bilateral work: 3000 solves equal (%d sticking, %d slipping contacts; %d smaller than the one before)\n",
              sticking, slipping, shrunk);
  EXPECT_GT(shrunk, 500);
}

TEST(SimulationKeptScratch, RunsEqualTheRunsWithFreshStorage) {
  const test::SideBySide escapement = test::examples_side_by_side<simulation::kept_scratch>(
      {{"escapement.json", 0.5, 1e-3}, {"escapement.json", 0.1, 1e-6}});
  const test::SideBySide others = test::examples_side_by_side<simulation::kept_scratch>(
      {{"ratchet.json", 0.05, 0, -20}, {"ratchet.json", 0.2, 1e-6}, {"cam-follower.json", 0.3, 1e-6},
       {"scotch-yoke.json", 0.3, 1e-6}},
      3000);
  std::printf("kept scratch: %zu steps, %zu events equal\n", escapement.steps + others.steps,
              escapement.events + others.events);
  EXPECT_GT(escapement.events + others.events, 100u);
}

// The escapement with its three pairs' friction switched on and off in every mixed way (0.1 or
// none): contacts with and without friction take each other's places in the held set, so a
// contact's kept Coulomb data left from another's would show.
TEST(SimulationKeptScratch, MixedFrictionRunsEqualTheRunsWithFreshStorage) {
  test::SideBySide total;
  for (unsigned mask = 1; mask < 7; ++mask) {
    Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / "escapement.json");
    ASSERT_EQ(model.pairs.size(), 3u);
    for (std::size_t p = 0; p < 3; ++p) {
      if (mask >> p & 1u) model.pairs[p].friction = Rational(1, 10);
      else model.pairs[p].friction.reset();
      model.pairs[p].kinetic_friction.reset();
    }
    SimulationOptions options;
    options.accuracy = 1e-3;
    const std::string where = "escapement, friction mask " + std::to_string(mask);
    if (!test::add_side_by_side<simulation::kept_scratch>(model, options, 0.3, where, 100000, total)) break;
  }
  std::printf("kept scratch, mixed friction: %zu steps, %zu events equal\n", total.steps, total.events);
  EXPECT_GT(total.events, 100u);
}

}  // namespace
}  // namespace hipair
