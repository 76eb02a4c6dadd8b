// Tolerance analysis of a spur-gear train as an assembly chain (docs/tolerance.md "Assembly
// chains", "Gear trains"): examples/models/gear-train-3.json, gears A (10 teeth) -> B (12, the
// idler) -> C (10), 34 toleranced parameters, each flank one circular arc (the spur_gear's
// generic form with flank_radius).
//
// Oracles:
//   - closed forms that hold whatever the tooth profile (at nominal, the runouts being 0, a
//     gear's "phase" turns its teeth about its pivot like its own rotation): turning the idler's
//     teeth on its shaft by delta turns its body by -delta and leaves the output where it was,
//     d out / d B-phase = 0; turning the output gear's teeth turns it back by delta,
//     d out / d C-phase = -1; turning the driver's teeth is turning the driver,
//     d out / d A-phase = d out / d theta (here from exact recomputations at theta +- h);
//   - every other checked sensitivity equals central finite differences of exact recomputations
//     (the model rebuilt exactly at p +- h, the whole train's motion recomputed by the exact
//     kinematic engine sliced from the contact kernels);
//   - the certified band contains every exact recomputation at random vectors of the box.
#include "tolerance_chain_oracle.hpp"

#include "model/parametric/parametric.hpp"
#include "test_paths.hpp"

#include <hipair/tolerance.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>

namespace hipair {
namespace {

std::string gear_train_text() {
  std::ifstream in(std::filesystem::path(HIPAIR_EXAMPLES) / "gear-train-3.json");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ToleranceChainGear, GearTrainSensitivitiesMatchClosedFormsAndExactRecomputations) {
  std::string text = gear_train_text();
  ToleranceOptions options;
  options.driver = "gear-A";
  options.chain = true;
  options.range = std::make_pair(Rational(0), Rational(3, 10));
  options.positions = 120;
  options.threads = 2;
  ToleranceResult result = analyze_tolerances_text(text, options);
  ASSERT_EQ(result.chain.size(), 2u);
  EXPECT_EQ(result.follower, "gear-C");
  auto index = [&](const std::string& name) {
    for (std::size_t i = 0; i < result.parameters.size(); ++i)
      if (result.parameters[i].name == name) return i;
    ADD_FAILURE() << name;
    return std::size_t{0};
  };
  auto model = std::make_shared<const model_detail::ParametricModel>(model_detail::ParametricModel::read(text));
  // Central differences at h: the rebuilds' roundings (<= 1e-11) and the positions' doubles are
  // below 1e-10, so within h^2 |f'''| / 6 + 2e-10 / h of the derivative; |f'''| <= 1e3 on this
  // train's scale (radii 10-14 mm, tolerances 1e-2 mm: third derivatives of the contact angles).
  Rational h(1, 20000);
  double bound = 1e3 * h.get_d() * h.get_d() / 6 + 2e-10 / h.get_d();
  std::size_t checked = 0;
  for (std::size_t k = 1; k < result.samples.size() && checked < 2; k += 3) {
    const VariationSample& s = result.samples[k];
    if (!s.contact) continue;
    ++checked;
    SCOPED_TRACE("driver " + std::to_string(s.driver));
    EXPECT_NEAR(s.sensitivities[index("B-phase")], 0.0, 1e-9);
    EXPECT_NEAR(s.sensitivities[index("C-phase")], -1.0, 1e-9);
    auto rebuilt = [&](std::size_t i, const Rational& delta, double theta) {
      std::vector<Rational> d(result.parameters.size(), Rational(0));
      d[i] = delta;
      return test_chain::chain_output(model->exact_model(d), "gear-A", theta, "gear-C", Rational(0), 120);
    };
    double ratio = (test_chain::chain_output(model->nominal(), "gear-A", s.driver + h.get_d(), "gear-C", Rational(0), 120) -
                    test_chain::chain_output(model->nominal(), "gear-A", s.driver - h.get_d(), "gear-C", Rational(0), 120)) /
                   (2 * h.get_d());
    EXPECT_NEAR(s.sensitivities[index("A-phase")], ratio, bound);
    for (const char* name : {"module", "A-thinning", "B-pivot-y", "B-runout-y", "B-flank-radius", "C-pitch-radius"}) {
      SCOPED_TRACE(name);
      std::size_t i = index(name);
      double difference = (rebuilt(i, h, s.driver) - rebuilt(i, -h, s.driver)) / (2 * h.get_d());
      EXPECT_NEAR(s.sensitivities[i], difference, bound);
    }
  }
  EXPECT_EQ(checked, 2u);
  // The certified band holds the exact train at a random vector of the box (where it is bounded).
  std::mt19937 rng(23);
  std::uniform_int_distribution<int> u(0, 1000);
  std::size_t bounded = 0;
  for (int trial = 0; trial < 1; ++trial) {
    std::vector<Rational> d(result.parameters.size(), Rational(0));
    for (std::size_t i = 0; i < d.size(); ++i) {
      const Parameter& p = result.parameters[i];
      if (p.range.lo != p.range.hi) d[i] = p.range.lo - p.nominal + Rational(u(rng), 1000) * (p.range.hi - p.range.lo);
    }
    Model exact = model->exact_model(d);
    for (std::size_t k = 1; k < result.samples.size(); k += 3) {
      const VariationSample& s = result.samples[k];
      if (!s.contact || !std::isfinite(s.certified.upper - s.certified.lower)) continue;
      ++bounded;
      double out = test_chain::chain_output(exact, "gear-A", s.driver, "gear-C", Rational(0), 120);
      EXPECT_GE(out, s.certified.lower - 1e-10) << s.driver;
      EXPECT_LE(out, s.certified.upper + 1e-10) << s.driver;
    }
  }
  RecordProperty("bounded_checks", static_cast<int>(bounded));
}

}  // namespace
}  // namespace hipair
