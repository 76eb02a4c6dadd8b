// Lost motion of a serial gear train when the driver turns back: a gear whose driving gear has
// not moved (its position compares equal, exactly, to where it was at the reversal point) has
// not moved either. The oracle needs no rounding: each gear's free range is a function of its
// driving gear's exact position (the slices are taken at rational_near of it, a function of
// the number), so an unmoved driving gear leaves the same slice, and a gear that is not pushed
// stays where it was. Before rational_near was canonical (main 2271bbd), a driving gear that
// was re-placed on the same contact point got a new isolating interval, hence another rational
// and another slice: every gear from the third on "moved" at the first step back and
// `hipair analyze examples/models/gear-train.json` reported a lost motion of 0 for them.
#include "algebra/exact_real.hpp"
#include "kinematics/engine.hpp"
#include "test_paths.hpp"

#include <hipair/model.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace hipair;
using namespace hipair::kinematics_detail;

// t = tan(theta / 2) on the driver's first chart, rounded to 2^-20
Rational chart_value(double theta) {
  Rational t(mpz_class(static_cast<long>(std::llround(std::tan(theta / 2) * 1048576.0))), mpz_class(1048576));
  t.canonicalize();
  return t;
}

struct Tally {
  std::size_t held = 0;         // gears checked whose driving gear had not moved
  std::size_t deep = 0;         // of them, gears driven by a follower (the third gear on)
  std::size_t moved = 0;        // gears whose driving gear (a follower) had moved: no claim
  std::size_t reversals = 0;
};

// Drives gear-A forward in half-degree steps (the analysis's grid), and from every `every`-th
// state walks back in half-degree steps (as the reversal checks of analyze_kinematics do, strict
// steps) for `back_steps` steps, checking each gear against its driving gear.
void check_reversals(const Model& model, const std::string& name, int forward_steps, int every, int back_steps,
                     Tally& tally) {
  Chain chain = build_chain(model, *model.find_part("gear-A"), {}, SliceMethod::kernels, {});
  ASSERT_EQ(chain.parts.size(), 9u) << name;
  // the serial order: each gear is driven by exactly one earlier chain part
  std::vector<std::size_t> driving(chain.parts.size(), none);
  for (std::size_t k = 1; k < chain.parts.size(); ++k) {
    for (std::size_t s : chain.parts[k].constraints)
      if (chain.slicers[s]->other_moves()) {
        ASSERT_EQ(driving[k], none) << name << ": part " << k << " has two driving parts";
        driving[k] = chain.chain_index[chain.slicers[s]->other()];
      }
    ASSERT_LT(driving[k], k) << name;
  }
  const double h = std::numbers::pi / 360;
  std::vector<Interference> interference;
  ChainState state = initial_state(chain, 0, Rational(0), 0.0, interference);
  ASSERT_FALSE(state.jammed) << name;
  for (int i = 1; i <= forward_steps; ++i) {
    double theta = i * h;
    state = step(chain, state, 0, chart_value(theta), theta, false);
    ASSERT_FALSE(state.jammed) << name << " forward at " << theta;
    if (i % every != 0) continue;
    ++tally.reversals;
    ChainState current = state;
    for (int j = 1; j <= back_steps; ++j) {
      double back = theta - j * h;
      ChainState next = step(chain, current, 0, chart_value(back), back);
      if (next.jammed && next.coarse) next = step(chain, current, 0, chart_value(back), back, false);
      ASSERT_FALSE(next.jammed) << name << " reversing at " << theta << " to " << back;
      for (std::size_t k = 1; k < chain.parts.size(); ++k) {
        std::size_t d = driving[k];
        if (d == 0) continue;   // the driver moved
        if (compare(next.parts[d].position, state.parts[d].position) != 0) {
          ++tally.moved;
          continue;
        }
        EXPECT_EQ(compare(next.parts[k].position, state.parts[k].position), 0)
            << name << ": part " << k << " moved while its driving part " << d << " had not, reversing at " << theta
            << " rad, back at " << back;
        ++tally.held;
        tally.deep += d >= 2;
      }
      current = std::move(next);
      if (::testing::Test::HasFailure()) return;
    }
  }
}

TEST(KinematicsReversal, GearTrainGearDoesNotMoveBeforeItsDrivingGear) {
  Model model = read_model_file(std::string(HIPAIR_EXAMPLES) + "/gear-train.json");
  Tally tally;
  check_reversals(model, "gear-train.json", 36, 6, 8, tally);
  EXPECT_EQ(tally.reversals, 6u);
  // (267 held, 255 of them driven by a follower; 69 driven by a follower that had moved)
  EXPECT_GT(tally.deep, 200u);   // gears driven by a follower, which held
  EXPECT_GT(tally.moved, 50u);   // the walks back are long enough for followers to move
}

// The same on gear trains generated within the model's tolerances: each gear's tooth thinning
// (the backlash), the teeth's angular phase and the runout of the gear on its shaft at random.
TEST(KinematicsReversal, GeneratedGearTrainsGearDoesNotMoveBeforeItsDrivingGear) {
  const std::string path = std::string(HIPAIR_EXAMPLES) + "/gear-train.json";
  const Model nominal = read_model_file(path);
  std::mt19937_64 random(2027);
  // a value in the parameter's tolerance range, on a grid of 1000 steps
  auto within = [&](const std::string& name) {
    const Parameter* parameter = nominal.find_parameter(name);
    EXPECT_NE(parameter, nullptr) << name;
    if (parameter == nullptr) return Rational(0);
    Rational step = (parameter->range.hi - parameter->range.lo) / 1000;
    return Rational(parameter->range.lo + step * static_cast<long>(random() % 1001));
  };
  Tally tally;
  for (int trial = 0; trial < 3; ++trial) {
    ReadOptions options;
    for (char gear = 'A'; gear <= 'I'; ++gear)
      for (const char* quantity : {"-thinning", "-phase", "-runout-x", "-runout-y"}) {
        std::string name = std::string(1, gear) + quantity;
        options.parameter_values[name] = within(name);
      }
    Model model = read_model_file(path, options);
    check_reversals(model, "generated gear train " + std::to_string(trial), 24, 8, 8, tally);
    if (HasFailure()) return;
  }
  EXPECT_EQ(tally.reversals, 9u);
  EXPECT_GT(tally.deep, 300u);   // 383
  EXPECT_GT(tally.moved, 80u);   // 103
}

}  // namespace
