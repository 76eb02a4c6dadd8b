// Planar runs to very long end times (docs/simulation.md, "Session 34"): the first integration
// step of a planar part in sustained contact (or with springs) was the whole time left, and a
// --t-end of 1e40 ... 1e300 overflowed the integrator ("the integration in sustained contact
// fails", "the simulated configuration of a planar part is not finite", a floating-point trap
// of the several-parts simulator on pusher-blocks.json) instead of running on until the step
// budget. Every planar example model that simulates, to generated end times 10^e, e uniform in
// [3, 300], with a budget of 40 steps: the run reaches the end time (a part at rest stays) or
// uses up the budget (NumericError with steps() at the budget: the CLI's "used up its step
// budget", exit 3, nothing written) — never another error.
//   - SimulationPlanarLongRun.GeneratedEndTimesRunUntilTheBudget
#include "simulation_planar_support.hpp"
#include "test_paths.hpp"

#include <hipair/error.hpp>
#include <hipair/model.hpp>
#include <hipair/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace hipair {
namespace {

template <class Sim>
void run_to(const Model& model, double t_end, const std::string& name) {
  SimulationOptions options;
  options.max_steps = 40;
  Sim s = Sim::create(model, options);
  try {
    s.run_until(t_end);
    EXPECT_EQ(s.state().time, t_end) << name << " to " << t_end;
  } catch (const NumericError& error) {
    EXPECT_GE(s.steps(), options.max_steps) << name << " to " << t_end << ": " << error.what();
  }
}

TEST(SimulationPlanarLongRun, GeneratedEndTimesRunUntilTheBudget) {
  planar_test::Lcg random{34};
  int runs = 0;
  for (const char* file : {"disc-incline.json", "friction-slide.json", "incline-limit.json", "ladder.json", "peg-drop.json",
                           "peg-throw.json", "pushed-block.json", "pusher-blocks.json", "spring-block.json",
                           "stacked-blocks.json", "wheel-socket.json"}) {
    const Model model = read_model_file(std::filesystem::path(HIPAIR_EXAMPLES) / file);
    std::size_t planar = 0;
    for (const Part& part : model.parts) planar += part.motion.kind == Motion::Kind::planar;
    for (int n = 0; n < 2; ++n) {
      const double t_end = std::pow(10.0, std::floor(random.uniform(3, 301)));
      if (planar == 1) run_to<PlanarSimulation>(model, t_end, file);
      else run_to<PlanarSystemSimulation>(model, t_end, file);
      ++runs;
    }
  }
  EXPECT_EQ(runs, 22);
}

}  // namespace
}  // namespace hipair
